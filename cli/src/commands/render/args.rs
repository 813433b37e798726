//! `prism render`'s command line.

use std::path::PathBuf;

use clap::Args;

#[derive(Debug, Clone, Args)]
#[command(
    after_help = "Examples:\n  prism render -o effects.png\n  prism render scenes/cornell-bunny.gltf --spp 256 -o bunny.exr -o bunny.png --stats\n\nOutputs are chosen by extension: .exr (linear f32 RGB in --space, with chromaticities) or\n.png (tone mapped, 8-bit). The image depends only on the scene, the settings and --seed."
)]
pub struct RenderArgs {
    /// A .gltf or .glb file, a .toml overlay, or a Mitsuba 3 scene (.xml) (default: the
    /// embedded effects stage, scenes/effects.gltf).
    pub scene: Option<PathBuf>,
    /// A Mitsuba scene's parameter, as `mitsuba -D`: replaces its `<default>` and every
    /// `$NAME` in the file. Repeat for several.
    #[arg(short = 'D', value_name = "NAME=VALUE")]
    pub defines: Vec<String>,
    /// Output file(s), .exr or .png; repeat for several.
    #[arg(short = 'o', long = "output", default_value = "prism.png")]
    pub outputs: Vec<PathBuf>,
    /// Samples per pixel (default: 64, or a Mitsuba scene's sampler's count).
    #[arg(long, conflicts_with = "sample_range")]
    pub spp: Option<u64>,
    /// Render only sample indices A to B-1 of every pixel and write accumulation files
    /// (.exr only) for `prism merge` (farms: one range per machine).
    #[arg(long, value_name = "A..B")]
    pub sample_range: Option<String>,
    /// Image width (default: the height times the camera's aspect ratio, or 512).
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height (default: 512, or the width over the camera's aspect ratio).
    #[arg(long)]
    pub height: Option<u32>,
    /// Seed of the random streams.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Worker threads (default: one per core; at most 1024); never changes the image.
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Longest path in bounces (default: unbounded, ended by Russian roulette, or a
    /// Mitsuba scene's integrator's max_depth, less the camera's vertex).
    #[arg(long)]
    pub max_depth: Option<u32>,
    /// Continuations per camera sample from its first vertex: auto (chosen per render by a
    /// short pilot: 1 or 2) or 1 to 64. The camera ray and the first light sample are
    /// traced once for all of them, so each costs less than a sample; where the noise is
    /// in indirect light, it falls nearly as if there were that many more samples.
    #[arg(long, default_value = "auto")]
    pub splits: String,
    /// Path reuse: auto (chosen per render by the same pilot as --splits: none, 2 or 4) or
    /// 1 to 8, the side of the square tiles of pixels whose paths share the light found
    /// beyond their first bounce. Each pixel's indirect light is then estimated from
    /// side^2 continuations for side^2 - 1 shadow rays; at a few samples per pixel the
    /// shared noise shows as faint blocks. Not with --splits above 1.
    #[arg(long, default_value = "auto")]
    pub reuse: String,
    /// Wavelengths per path: 1, 2, 4, 8 or 16.
    #[arg(long, default_value_t = 8)]
    pub wavelengths: usize,
    /// Hero wavelength sampler: uniform, visible, response or spd.
    #[arg(long, default_value = "visible")]
    pub lambda_sampler: String,
    /// Pixel filter: box, gaussian or blackman-harris [default: the Mitsuba scene's
    /// rfilter, else box].
    #[arg(long)]
    pub filter: Option<String>,
    /// Spectral output: EXR outputs also get this many bands of spectral radiance (the
    /// spectral OpenEXR layout), over --spectral-range.
    #[arg(long, value_name = "N")]
    pub spectral_bands: Option<usize>,
    /// The range of the spectral bands, nm.
    #[arg(long, value_name = "A:B", default_value = "380:780")]
    pub spectral_range: String,
    /// Energy output: EXR outputs also get energy.radiance (W m^-2 sr^-1 over the
    /// wavelength range), energy.eV and energy.photons channels; --stats gains their
    /// image means.
    #[arg(long)]
    pub energy: bool,
    /// Polarized rendering: paths carry a Stokes vector per wavelength (Mueller matrices
    /// at every surface: Fresnel for glass and metals, depolarizing diffuse surfaces).
    /// EXR outputs gain the Stokes components as S0.R, S0.G, S0.B, S1.R, ..., S3.B (the
    /// layout of Mitsuba 3's stokes integrator); PNG outputs show S0, the ordinary image.
    #[arg(long)]
    pub polarized: bool,
    /// A linear polarizing filter in front of the camera, its axis at this many degrees
    /// from the image's horizontal towards its vertical: outputs show what a photograph
    /// through it would. Implies --polarized.
    #[arg(long, value_name = "DEGREES", allow_negative_numbers = true)]
    pub camera_polarizer: Option<f32>,
    /// Also write the polarization as a PNG (needs --polarized): hue the angle of linear
    /// polarization (red along the image's rows, cyan along its columns), saturation its
    /// degree, brightness the intensity.
    #[arg(long, value_name = "FILE.png")]
    pub polarization_png: Option<PathBuf>,
    /// Render this instant of the scene's clock, in seconds: lights shine as their "on"
    /// schedules say then, and phosphorescent materials glow with the light they absorbed
    /// before it. Without it every light has always been on (the steady state).
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    pub at: Option<f64>,
    /// An exposure instead of an instant: the shutter is open from A to B seconds on the
    /// scene's clock, and the image is the mean over that time.
    #[arg(long, value_name = "A:B", allow_negative_numbers = true)]
    pub shutter: Option<String>,
    /// The wavelengths camera paths sample, nm (default 360:830, or the camera
    /// response's range; wider to include UV or infrared, of which only what the observer
    /// sees shows in RGB).
    #[arg(long, value_name = "A:B")]
    pub wavelength_range: Option<String>,
    /// A camera's response curves (CSV: nm, r, g, b) instead of the CIE observer, for any
    /// band (near-infrared, UV, a real sensor): outputs hold its raw channels as R, G, B,
    /// false colour outside the visible; the response sampler follows its curves.
    #[arg(long, value_name = "CSV")]
    pub camera_response: Option<PathBuf>,
    /// White balance: adapt the image from this illuminant's white to the output space's
    /// white (Bradford), e.g. illuminant:A, blackbody:3200, daylight:5000 or a CSV file.
    #[arg(long, value_name = "SPECTRUM")]
    pub white_balance: Option<String>,
    /// Output colour space of EXR and PNG files.
    #[arg(long, default_value = "srgb")]
    pub space: String,
    /// The camera, by name (default: the file's first).
    #[arg(long)]
    pub camera: Option<String>,
    /// The glTF scene to render, by index (default: the file's default scene).
    #[arg(long, visible_alias = "scene", value_name = "N")]
    pub scene_index: Option<usize>,
    /// The camera paths' tracer: paths. lanes (and lanes:4, lanes:8, lanes:16), the batch
    /// tracer, is not kept: it rendered the same image, never faster; asking for it
    /// renders with paths and warns.
    #[arg(long, default_value = "paths", value_name = "TRACER")]
    pub tracer: String,
    /// BVH build effort: medium (default) or slow (a better tree for long renders).
    #[arg(long, default_value = "medium")]
    pub bvh: String,
    /// Light from infinity, replacing the scene's own: a number (a grey of that
    /// emissive-colour value: 0.5 lights a white Lambertian plane to RGB 0.5) or an
    /// equirectangular HDR image (.exr or .hdr; +y up, the top row the zenith, the centre
    /// column towards +x), its texels read as emissive colours. A scene with no light at
    /// all gets a grey of 1 (CIE D65), and prism says so.
    #[arg(long, allow_negative_numbers = true, value_name = "VALUE|FILE")]
    pub environment: Option<String>,
    /// Turn the environment image by this many degrees about +y (counter-clockwise seen
    /// from above).
    #[arg(
        long,
        default_value_t = 0.0,
        allow_negative_numbers = true,
        value_name = "DEGREES"
    )]
    pub environment_rotation: f64,
    /// Multiply the environment (number or image) by this factor.
    #[arg(
        long,
        default_value_t = 1.0,
        allow_negative_numbers = true,
        value_name = "S"
    )]
    pub environment_strength: f64,
    /// Depth of field: a thin lens of this f-number (focal length over aperture diameter;
    /// the focal length follows from the camera's field of view and a 36 mm wide sensor,
    /// or the camera's `sensor_width`), replacing the camera's own aperture.
    #[arg(
        long,
        value_name = "N",
        conflicts_with = "aperture_radius",
        allow_negative_numbers = true
    )]
    pub f_number: Option<f32>,
    /// Depth of field: a thin lens of this aperture radius, in scene units (metres in
    /// glTF); 0 is a pinhole.
    #[arg(long, value_name = "R", allow_negative_numbers = true)]
    pub aperture_radius: Option<f32>,
    /// The distance in focus along the view, scene units (default: the camera's own, else
    /// what the image's centre sees; `--stats` reports it). Needs an aperture or a lens.
    #[arg(long, value_name = "D", allow_negative_numbers = true)]
    pub focus_distance: Option<f32>,
    /// A real lens before the film, from a prescription in pbrt-v4's lens file format
    /// (radius, thickness, index, aperture diameter per interface in mm, optionally a
    /// fifth column naming the glass: `bk7` or `1.5168:64.17`), traced per wavelength.
    /// Replaces the camera's own lens; the film is 36 mm wide (or the camera's
    /// `sensor_width`) and the lens's focal length sets the field of view. `--f-number`
    /// closes its stop, `--focus-distance` moves its film.
    #[arg(long, value_name = "FILE", conflicts_with = "aperture_radius")]
    pub lens: Option<std::path::PathBuf>,
    /// Adaptive sampling: on (a pilot of two samples per pixel spreads the samples where
    /// the error is, in tiles, keeping the total; unbiased) or off (every pixel takes
    /// --spp). It applies from 16 samples per pixel, in multiples of 4; a --sample-range
    /// render samples uniformly, so that farm pieces add up.
    #[arg(long, value_name = "on|off", default_value = "on", value_parser = ["on", "off"])]
    pub adaptive: String,
    /// Leave caustics to camera paths alone: no light paths, even in scenes with smooth
    /// glass or metal (unbiased either way; without light paths a small light's caustic
    /// is noise and a punctual light's is missing).
    #[arg(long)]
    pub no_light_paths: bool,
    /// Firefly clamp: scale samples whose luminance Y exceeds this down to it. Biased (it
    /// removes energy); off by default.
    #[arg(long)]
    pub clamp: Option<f64>,
    /// PNG exposure in stops.
    #[arg(long, default_value_t = 0.0)]
    pub exposure: f64,
    /// PNG tone mapping: neutral (Khronos PBR Neutral, as glTF viewers show models: base
    /// colours as authored, highlights compressed), aces, reinhard[:WHITE] or clamp.
    #[arg(long, default_value = "neutral")]
    pub tonemap: String,
    /// A transparent background: rays that miss the scene show nothing (the environment
    /// still lights it), and PNG outputs get the alpha channel too (EXR always has it).
    #[arg(long)]
    pub transparent: bool,
    /// Stop at the first whole sample per pixel after this many seconds (with adaptive
    /// sampling, the first whole group of four).
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    pub time: Option<f64>,
    /// Write a checkpoint (an accumulation file OUTPUT.checkpoint.exr next to the first
    /// output) this often, and when the render stops early.
    #[arg(long, value_name = "SECONDS")]
    pub checkpoint: Option<f64>,
    /// Continue the render a checkpoint holds (same scene and settings); the result equals
    /// the uninterrupted render.
    #[arg(long, value_name = "CHECKPOINT")]
    pub resume: Option<PathBuf>,
    /// Feature buffers (AOVs) EXR outputs also get, comma-separated: albedo (the first
    /// non-specular surface's reflectance, through mirrors and glass), normal (its shading
    /// normal, world space), depth (camera distance), position (world space), material_id
    /// (1 + the material's index, 0 for none), variance (of each pixel's mean, R G B: its
    /// expected squared error, from two independently scrambled halves of the samples,
    /// which leave the image somewhat noisier), or all. They share the
    /// radiance's film, filter, merges and checkpoints.
    #[arg(long, value_name = "LIST")]
    pub aov: Option<String>,
    /// Denoise with Intel Open Image Denoise (its HDR filter, guided by the albedo and
    /// normal buffers, which it adds to EXR outputs, themselves denoised first). Denoising
    /// works on the RGB image, after the spectral film, never on spectral bands. The
    /// outputs show the denoised image; EXR outputs keep the noisy one as noisy.R, noisy.G,
    /// noisy.B. Needs the OIDN library: `pip install pyoidn` (or PRISM_OIDN=its path).
    #[arg(long)]
    pub denoise: bool,
    /// Show the render as it converges in the tev image viewer listening at HOST[:PORT]
    /// (port 14158 by default): the image and its AOVs, updated every few seconds and at
    /// the end. A viewer that is not there is one warning, and the render goes on.
    #[arg(long, value_name = "HOST[:PORT]")]
    pub tev: Option<String>,
    /// No progress output.
    #[arg(long, short)]
    pub quiet: bool,
    /// Print one JSON object of statistics on stdout after the render.
    #[arg(long)]
    pub stats: bool,
}
