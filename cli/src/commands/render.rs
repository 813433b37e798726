//! `prism render`: a scene (or the embedded default) to EXR and PNG images.

use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use clap::Args;
use prism_integrator::{
    CameraResponse, DisplaySettings, ExrMetadata, Film, Filter, LambdaSampler, RenderSettings,
    ResponseCurve, Reuse, SpectralBands, Splits, decode_accumulation, encode_accumulation,
    encode_exr, encode_png, encode_polarization_png,
};
use prism_scene::geometry::BvhQuality;
use prism_scene::load::{LoadedGeometry, environment_map, load_geometry};
use prism_scene::world::{DEFAULT_ENVIRONMENT, Environment, Scene, SceneOptions, grey_environment};
use prism_spectrum::Readable;
use prism_spectrum::color::{RgbSpaceId, ToneMap};

use crate::output::{check_writable, write_atomically};
use crate::session::{self, Ending, Outcome, SessionOptions};

/// The scene `prism render` renders without a SCENE argument: the repository's spectral
/// effects stage (`scenes/effects.gltf`, one file with its buffer embedded): dispersion,
/// fluorescence under UV, and a blackbody and a standard illuminant side by side.
const DEFAULT_GLTF: &[u8] = include_bytes!("../../../scenes/effects.gltf");

#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  prism render -o effects.png\n  prism render scenes/cornell-bunny.gltf --spp 256 -o bunny.exr -o bunny.png --stats\n\nOutputs are chosen by extension: .exr (linear f32 RGB in --space, with chromaticities) or\n.png (tone mapped, 8-bit). The image depends only on the scene, the settings and --seed."
)]
pub struct RenderArgs {
    /// A .gltf or .glb file, or a .toml overlay (default: the embedded effects stage,
    /// scenes/effects.gltf).
    pub scene: Option<PathBuf>,
    /// Output file(s), .exr or .png; repeat for several.
    #[arg(short = 'o', long = "output", default_value = "prism.png")]
    pub outputs: Vec<PathBuf>,
    /// Samples per pixel.
    #[arg(long, default_value_t = 64, conflicts_with = "sample_range")]
    pub spp: u64,
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
    /// Longest path in bounces (default: unbounded, ended by Russian roulette).
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
    /// Pixel filter: box, gaussian or blackman-harris.
    #[arg(long, default_value = "box")]
    pub filter: String,
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
    /// Stop at the first whole sample per pixel after this many seconds.
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
    /// No progress output.
    #[arg(long, short)]
    pub quiet: bool,
    /// Print one JSON object of statistics on stdout after the render.
    #[arg(long)]
    pub stats: bool,
}

fn load(path: Option<&Path>, scene: Option<usize>) -> Result<LoadedGeometry, String> {
    match path {
        Some(p) => crate::scene_file::load(p, scene),
        None => load_geometry(
            DEFAULT_GLTF,
            &|uri| Err(std::io::Error::other(format!("no file '{uri}'"))),
            scene,
        )
        .map_err(|e| format!("embedded scene: {e}")),
    }
}

/// The output size: what the command line gives, the rest from the camera's aspect ratio
/// (square without one), 512 pixels high when neither is given.
fn image_size(width: Option<u32>, height: Option<u32>, aspect: Option<f32>) -> (u32, u32) {
    let aspect = f64::from(aspect.unwrap_or(1.0));
    let scaled = |v: u32, by: f64| ((f64::from(v) * by).round() as u32).max(1);
    match (width, height) {
        (Some(w), Some(h)) => (w, h),
        (Some(w), None) => (w, scaled(w, 1.0 / aspect)),
        (None, h) => {
            let h = h.unwrap_or(512);
            (scaled(h, aspect), h)
        }
    }
}

/// The camera response a scene describes (`camera_response` on the root's
/// `PRISM_spectral`), over where its curves exceed 0.1% of their peaks.
fn scene_camera(loaded: &LoadedGeometry) -> Result<Option<CameraResponse>, String> {
    let Some(curves) = &loaded.spectral.camera_response else {
        return Ok(None);
    };
    let range = curves
        .iter()
        .filter_map(|c| c.extent(1e-3))
        .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))
        .ok_or("the scene's camera_response is zero everywhere")?;
    let curves: [ResponseCurve; 3] = curves.clone().map(|c| Arc::new(c) as ResponseCurve);
    CameraResponse::new(curves, range)
        .map(Some)
        .map_err(|e| format!("the scene's {e}"))
}

/// The environment the command line asks for: a grey of an emissive-colour value, or an
/// image file, either times --environment-strength.
fn environment(args: &RenderArgs) -> Result<Option<Environment>, String> {
    let (rotation, strength) = (args.environment_rotation, args.environment_strength);
    if !rotation.is_finite() {
        return Err(format!(
            "--environment-rotation {} must be a finite number of degrees",
            Readable(rotation)
        ));
    }
    // Radiance is f32 in the renderer: beyond f32::MAX a value would saturate there.
    let in_range = |v: f64| v >= 0.0 && v <= f64::from(f32::MAX);
    if !in_range(strength) {
        return Err(format!(
            "--environment-strength {} must be >= 0 and at most f32's largest value, 3.4e38",
            Readable(strength)
        ));
    }
    let Some(text) = &args.environment else {
        return Ok(None);
    };
    if let Ok(value) = text.parse::<f64>() {
        let value = value * strength;
        if !in_range(value) {
            return Err(format!(
                "--environment {} must be >= 0 and at most f32's largest value, 3.4e38",
                Readable(value)
            ));
        }
        return Ok(Some(Environment::Uniform(grey_environment(value))));
    }
    let path = Path::new(text);
    let bytes =
        std::fs::read(path).map_err(|e| format!("--environment '{}': {e}", path.display()))?;
    let map = environment_map(&bytes, rotation, strength)
        .map_err(|e| format!("--environment '{}': {e}", path.display()))?;
    Ok(Some(Environment::Map(map)))
}

pub fn run(args: &RenderArgs) -> Result<(), String> {
    let space_id = RgbSpaceId::from_name(&args.space).map_err(|e| e.to_string())?;
    let lambda_sampler =
        LambdaSampler::from_name(&args.lambda_sampler).map_err(|e| e.to_string())?;
    let filter = Filter::from_name(&args.filter).map_err(|e| e.to_string())?;
    check_outputs(&args.outputs)?;
    let samples_only = args.sample_range.as_deref().map(parse_range).transpose()?;
    if samples_only.is_some()
        && let Some(out) = args.outputs.iter().find(|o| !has_extension(o, "exr"))
    {
        return Err(format!(
            "output '{}': --sample-range writes accumulation files, which must be .exr",
            out.display()
        ));
    }
    let started = Instant::now();
    let loaded = load(args.scene.as_deref(), args.scene_index)?;
    let quality = match args.bvh.as_str() {
        "medium" => BvhQuality::Medium,
        "slow" => BvhQuality::Slow,
        other => return Err(format!("--bvh '{other}': expected medium or slow")),
    };
    let options = SceneOptions::default()
        .camera(args.camera.clone())
        .environment(environment(args)?)
        .quality(quality);
    let camera = args
        .camera_response
        .as_deref()
        .map(|path| {
            let text = std::fs::read_to_string(path)
                .map_err(|e| format!("cannot read '{}': {e}", path.display()))?;
            CameraResponse::from_csv(&text).map_err(|e| format!("'{}': {e}", path.display()))
        })
        .transpose()?;
    // The command line's camera wins over the scene's own.
    let camera = match camera {
        Some(c) => Some(c),
        None => scene_camera(&loaded)?,
    };
    let summary = loaded.summary();
    let (polarizing, timed) = (summary.polarizing, summary.timed);
    let scene = Scene::from_loaded(loaded, &options).map_err(|e| e.to_string())?;
    if polarizing != (0, 0) && !args.polarized && args.camera_polarizer.is_none() {
        eprintln!(
            "prism: note: the scene has polarizers, retarders or polarized lights, which only a polarized render shows (--polarized); this one sees their intensity only"
        );
    }
    if timed != (0, 0) && args.at.is_none() && args.shutter.is_none() && !args.quiet {
        eprintln!(
            "prism: note: the scene has schedules or phosphors; without --at every source has always been on (the steady state)"
        );
    }
    if scene.lit_by_default() {
        eprintln!(
            "prism: the scene has no light source (only glowing surfaces, if any); lighting it with a \
             neutral environment (CIE D65, --environment {DEFAULT_ENVIRONMENT}); choose another with --environment VALUE|FILE"
        );
    }
    let (width, height) = image_size(args.width, args.height, scene.camera().aspect_ratio);
    if camera.is_some() && args.white_balance.is_some() {
        return Err(
            "--white-balance applies to XYZ; with a camera response the channels are the camera's own"
                .into(),
        );
    }
    let range = match (&args.wavelength_range, &camera) {
        (Some(text), _) => parse_nm_range("--wavelength-range", text)?,
        (None, Some(c)) => c.range(),
        (None, None) => (360.0, 830.0),
    };
    let settings = RenderSettings::default()
        .width(width)
        .height(height)
        .samples(samples_only.clone().unwrap_or(0..args.spp))
        .seed(args.seed)
        .max_depth(args.max_depth)
        .splits(args.splits.parse::<Splits>()?)
        .reuse(args.reuse.parse::<Reuse>()?)
        .wavelengths(args.wavelengths)
        .lambda_sampler(lambda_sampler)
        .threads(args.threads)
        .filter(filter)
        .clamp(args.clamp)
        .bands(spectral_bands(args)?)
        .energy(args.energy)
        .polarized(args.polarized)
        .camera_polarizer(args.camera_polarizer)
        .at(args.at)
        .shutter(args.shutter.as_deref().map(parse_shutter).transpose()?)
        .light_paths(!args.no_light_paths)
        .transparent(args.transparent)
        .range(range)
        .camera(camera.map(Arc::new));
    let white_balance = args
        .white_balance
        .as_deref()
        .map(|spec| white_balance(spec, space_id))
        .transpose()?;
    settings.validate().map_err(|e| e.to_string())?;
    if args.polarization_png.is_some() && !settings.is_polarized() {
        return Err("--polarization-png needs a polarized render (--polarized)".into());
    }
    // The film, one pass's film and the output's RGB: 24 + 24 + 12 bytes per pixel.
    let film_bytes = u64::from(width) * u64::from(height) * 60;
    if let Some(available) = crate::memory::available_bytes()
        && film_bytes > available
    {
        return Err(format!(
            "a {width}x{height} image needs {:.1} GiB for its film, more than the {:.1} GiB available",
            film_bytes as f64 / f64::from(1u32 << 30),
            available as f64 / f64::from(1u32 << 30)
        ));
    }
    // Duration::from_secs_f64 panics past u64 seconds (1e300 did); such a span is a
    // mistake, not a plan, so it is an error like any other out-of-range value.
    let seconds_arg = |name: &str, v: Option<f64>| {
        v.map(|s| {
            Duration::try_from_secs_f64(s).map_err(|_| {
                format!(
                    "--{name} {} must be a finite number of seconds >= 0",
                    Readable(s)
                )
            })
        })
        .transpose()
    };
    let time_budget = seconds_arg("time", args.time)?;
    let checkpoint_every = seconds_arg("checkpoint", args.checkpoint)?;
    let range = settings.samples.clone();
    let fingerprint = fingerprint(args, width, height);
    let film = match &args.resume {
        None => Film::for_settings(&settings),
        Some(path) => resume(path, &fingerprint, &range)?,
    };
    let checkpoint = checkpoint_every.map(|every| {
        let first = &args.outputs[0];
        let mut name = first.file_name().unwrap_or_default().to_os_string();
        name.push(".checkpoint.exr");
        (every, first.with_file_name(name))
    });
    let options = SessionOptions {
        time_budget,
        checkpoint,
        quiet: args.quiet,
        fingerprint: fingerprint.clone(),
    };
    let cancel = Arc::new(AtomicBool::new(false));
    session::stop_on_signals(&cancel)?;
    let Outcome {
        film,
        stats,
        ending,
        seconds,
    } = session::run(&scene, &settings, range.clone(), film, &options, &cancel)?;
    if samples_only.is_some() {
        let done = range.start..range.start + film.samples();
        let bytes = encode_accumulation(&film, done, &fingerprint).map_err(|e| e.to_string())?;
        for out in &args.outputs {
            write_atomically(out, &bytes)?;
        }
    } else {
        let mut facts = vec![
            ("seed".into(), args.seed.to_string()),
            ("wavelengths".into(), args.wavelengths.to_string()),
            ("lambda_sampler".into(), args.lambda_sampler.clone()),
            (
                "wavelength_range".into(),
                format!("{}:{}", settings.range.0, settings.range.1),
            ),
        ];
        if let Some(spec) = &args.white_balance {
            facts.push(("white_balance".into(), spec.clone()));
        }
        if settings.is_polarized() {
            facts.push(("polarized".into(), "1".into()));
        }
        if let Some(angle) = settings.camera_polarizer {
            facts.push(("camera_polarizer".into(), angle.to_string()));
        }
        if let Some(t) = settings.at {
            facts.push(("at".into(), t.to_string()));
        }
        if stats.splits > 1 {
            facts.push(("splits".into(), stats.splits.to_string()));
        }
        if stats.reuse > 1 {
            facts.push(("reuse".into(), stats.reuse.to_string()));
        }
        let shown = match &white_balance {
            Some(m) => film.adapted(m),
            None => film.clone(),
        };
        write_images(&shown, &args.outputs, space_id, display(args)?, facts)?;
        if let Some(path) = &args.polarization_png
            && let Some(bytes) = encode_polarization_png(&shown, space_id.space(), display(args)?)
        {
            write_atomically(path, &bytes)?;
        }
    }
    if stats.nonfinite > 0 {
        eprintln!(
            "prism: warning: {} non-finite samples were rejected",
            stats.nonfinite
        );
    }
    if args.stats {
        let json = serde_json::json!({
            "spp": film.samples(),
            "width": width,
            "height": height,
            "seconds": seconds,
            "total_seconds": started.elapsed().as_secs_f64(),
            "paths": stats.paths,
            "paths_per_second": stats.paths as f64 / seconds.max(1e-9),
            "rays": stats.rays,
            "rays_per_second": stats.rays as f64 / seconds.max(1e-9),
            "nonfinite_samples": stats.nonfinite,
            "ending": format!("{ending:?}"),
            "peak_memory_bytes": crate::memory::peak_bytes(),
            "wavelengths": args.wavelengths,
            "splits": stats.splits,
            "reuse": stats.reuse,
            "lambda_sampler": args.lambda_sampler,
            "energy": energy_stats(&film, settings.range),
            "polarized": settings.is_polarized(),
            "camera_polarizer": settings.camera_polarizer,
            "at": settings.at,
            "shutter": settings.shutter,
        });
        println!("{json}");
    }
    match ending {
        Ending::Complete => Ok(()),
        Ending::TimeBudget => {
            if !args.quiet {
                eprintln!(
                    "prism: time budget reached at {} spp of {}",
                    film.samples(),
                    range.end - range.start
                );
            }
            Ok(())
        }
        Ending::Interrupted => {
            eprintln!(
                "prism: interrupted at {} spp of {}; the image so far was written",
                film.samples(),
                range.end - range.start
            );
            std::process::exit(130);
        }
    }
}

/// `A:B` in seconds, A < B (the settings check the order).
fn parse_shutter(text: &str) -> Result<(f64, f64), String> {
    let bad = || format!("--shutter '{text}': expected A:B in seconds, A before B");
    let (a, b) = text.split_once(':').ok_or_else(bad)?;
    let (a, b): (f64, f64) = (
        a.trim().parse().map_err(|_| bad())?,
        b.trim().parse().map_err(|_| bad())?,
    );
    Ok((a, b))
}

/// `A:B` in nm, 0 < A < B.
fn parse_nm_range(flag: &str, text: &str) -> Result<(f32, f32), String> {
    // The renderer's wavelengths are f32: 1e-300 reads as 0 and 1e300 as infinity.
    let bad = || {
        format!("{flag} '{text}': expected A:B in nm with 0 < A < B, both from 1.2e-38 to 3.4e38")
    };
    let (a, b) = text.split_once(':').ok_or_else(bad)?;
    let (a, b): (f32, f32) = (
        a.trim().parse().map_err(|_| bad())?,
        b.trim().parse().map_err(|_| bad())?,
    );
    if a.is_finite() && b.is_finite() && 0.0 < a && a < b {
        Ok((a, b))
    } else {
        Err(bad())
    }
}

/// The chromatic adaptation (Bradford) from the white of the illuminant `spec` to the
/// white of the output space.
fn white_balance(spec: &str, space: RgbSpaceId) -> Result<prism_spectrum::color::Mat3, String> {
    use prism_spectrum::color::{AdaptationMethod, adaptation_matrix};
    use prism_spectrum::colorimetry::{Observer, WhitePoint, emission_xyz};
    let spectrum = crate::spectrum_spec::parse(spec).map_err(|e| format!("--white-balance {e}"))?;
    let white = WhitePoint::from_xyz(emission_xyz(&*spectrum, Observer::Cie1931))
        .map_err(|e| format!("--white-balance '{spec}': {e}"))?;
    Ok(adaptation_matrix(
        white,
        space.space().white(),
        AdaptationMethod::Bradford,
    ))
}

/// The image means of the energy channels, or null without --energy.
fn energy_stats(film: &Film, range: (f32, f32)) -> serde_json::Value {
    if !film.has_energy() {
        return serde_json::Value::Null;
    }
    let (w, h) = (film.width(), film.height());
    let mut sum = [0.0f64; 2];
    for y in 0..h {
        for x in 0..w {
            let e = film.energy(x, y).unwrap_or_default();
            sum[0] += e[0];
            sum[1] += e[1];
        }
    }
    let n = f64::from(w) * f64::from(h);
    let ev = prism_spectrum::constants::ELEMENTARY_CHARGE;
    serde_json::json!({
        "range_nm": [range.0, range.1],
        "mean_radiance_w_m2_sr": sum[0] / n,
        "mean_radiance_ev_s_m2_sr": sum[0] / n / ev,
        "mean_photon_radiance_s_m2_sr": sum[1] / n,
    })
}

/// The bands of `--spectral-bands N --spectral-range A:B`.
fn spectral_bands(args: &RenderArgs) -> Result<Option<SpectralBands>, String> {
    // Checked even without bands: a mistyped range is an error, not silently unused.
    let range = parse_nm_range("--spectral-range", &args.spectral_range)?;
    let Some(count) = args.spectral_bands else {
        return Ok(None);
    };
    SpectralBands::new(range.0, range.1, count)
        .map(Some)
        .map_err(|e| e.to_string())
}

/// What must match for a checkpoint to be resumed or parts merged: everything that changes
/// the estimate or what the film accumulates (bands, energy, a camera's channels). Not
/// `--splits`: every choice estimates the same image, only with more or less noise per
/// sample, so parts split differently merge into an unbiased whole.
fn fingerprint(args: &RenderArgs, width: u32, height: u32) -> String {
    let bands = args
        .spectral_bands
        .map_or("none".into(), |n| format!("{n}@{}", args.spectral_range));
    format!(
        "scene={};camera={:?};size={width}x{height};seed={};max_depth={:?};wavelengths={};lambda_sampler={};filter={};clamp={:?};environment={:?};wavelength_range={};scene_index={:?};light_paths={};bands={bands};energy={};camera_response={:?};transparent={}",
        args.scene
            .as_ref()
            .map_or("(default)".into(), |p| p.display().to_string()),
        args.camera,
        args.seed,
        args.max_depth,
        args.wavelengths,
        args.lambda_sampler,
        args.filter,
        args.clamp,
        args.environment.as_ref().map(|e| format!(
            "{e}@{}deg*{}",
            args.environment_rotation, args.environment_strength
        )),
        args.wavelength_range.as_deref().unwrap_or("360:830"),
        args.scene_index,
        !args.no_light_paths,
        args.energy,
        args.camera_response,
        args.transparent
    ) + &later_settings_fingerprint(args)
}

/// The polarization and time settings' part of the fingerprint: empty for a render without,
/// so that checkpoints written before polarization existed still resume.
fn later_settings_fingerprint(args: &RenderArgs) -> String {
    let polarization = match (args.polarized, args.camera_polarizer) {
        (false, None) => String::new(),
        (_, filter) => format!(";polarized=1;camera_polarizer={filter:?}"),
    };
    // The instant, likewise only when one is rendered.
    match (args.at, &args.shutter) {
        (Some(t), _) => format!("{polarization};at={t}"),
        (None, Some(s)) => format!("{polarization};shutter={s}"),
        (None, None) => polarization,
    }
}

/// The film of a checkpoint, checked against this render's settings and range.
fn resume(path: &Path, fingerprint: &str, range: &Range<u64>) -> Result<Film, String> {
    let bytes =
        std::fs::read(path).map_err(|e| format!("cannot read '{}': {e}", path.display()))?;
    let saved = decode_accumulation(&bytes).map_err(|e| format!("'{}': {e}", path.display()))?;
    if saved.settings != fingerprint {
        return Err(format!(
            "'{}' was rendered with other settings than this render: {} (the file's vs this \
             render's)",
            path.display(),
            prism_integrator::settings_difference(&saved.settings, fingerprint)
        ));
    }
    if saved.samples.start != range.start || saved.samples.end > range.end {
        return Err(format!(
            "'{}' holds samples {}..{}, not a start of {}..{}",
            path.display(),
            saved.samples.start,
            saved.samples.end,
            range.start,
            range.end
        ));
    }
    Ok(saved.film)
}

/// `A..B` with A < B.
fn parse_range(text: &str) -> Result<Range<u64>, String> {
    let parsed = text
        .split_once("..")
        .and_then(|(a, b)| Some(a.trim().parse::<u64>().ok()?..b.trim().parse::<u64>().ok()?));
    match parsed {
        Some(r) if r.start < r.end => Ok(r),
        _ => Err(format!(
            "--sample-range '{text}': expected A..B with whole numbers A < B"
        )),
    }
}

fn has_extension(path: &Path, extension: &str) -> bool {
    path.extension().and_then(|e| e.to_str()) == Some(extension)
}

/// Every output is a .exr or .png file that can be written.
pub fn check_outputs(outputs: &[PathBuf]) -> Result<(), String> {
    for out in outputs {
        if !(has_extension(out, "exr") || has_extension(out, "png")) {
            return Err(format!(
                "output '{}': the extension must be .exr or .png",
                out.display()
            ));
        }
        check_writable(out)?;
    }
    Ok(())
}

/// How --exposure, --tonemap and --transparent show a film in a PNG.
fn display(args: &RenderArgs) -> Result<DisplaySettings, String> {
    Ok(DisplaySettings::default()
        .exposure(args.exposure)
        .tone_map(ToneMap::from_name(&args.tonemap).map_err(|e| e.to_string())?)
        .alpha(args.transparent))
}

/// Writes `film` to every output: .exr as linear RGB and alpha in `space` with prism's
/// facts, .png as `display` says.
pub fn write_images(
    film: &Film,
    outputs: &[PathBuf],
    space: RgbSpaceId,
    display: DisplaySettings,
    facts: Vec<(String, String)>,
) -> Result<(), String> {
    let space = space.space();
    for out in outputs {
        let bytes = if has_extension(out, "exr") {
            let metadata = ExrMetadata::default()
                .spp(film.samples())
                .strings(facts.clone());
            encode_exr(film, space, &metadata).map_err(|e| e.to_string())?
        } else {
            encode_png(film, space, display)
        };
        write_atomically(out, &bytes)?;
    }
    Ok(())
}
