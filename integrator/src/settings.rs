//! What a render is asked to do.

use std::ops::Range;

use prism_sampling::wavelength::{PackageScheme, WavelengthDistribution, WavelengthRange};
use prism_spectrum::colorimetry::Observer;

use crate::{Filter, RenderError, SpectralBands};

/// How the hero wavelength of each path is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum LambdaSampler {
    /// Uniform over the range.
    Uniform,
    /// pbrt-v4's visible-importance density (smooth, peaked where the eye is sensitive).
    #[default]
    Visible,
    /// The sum of the observer's colour matching functions, each normalized (camera
    /// response sampling).
    Response,
    /// The scene's light spectra weighted by the response, with a defensive mixture.
    Spd,
}

impl LambdaSampler {
    /// Names accepted by [`LambdaSampler::from_name`].
    pub const NAMES: &'static str = "uniform, visible, response, spd";

    /// Parses one of [`LambdaSampler::NAMES`].
    pub fn from_name(name: &str) -> Result<Self, RenderError> {
        Ok(match name {
            "uniform" => LambdaSampler::Uniform,
            "visible" => LambdaSampler::Visible,
            "response" => LambdaSampler::Response,
            "spd" => LambdaSampler::Spd,
            other => {
                return Err(RenderError::Setting(format!(
                    "unknown wavelength sampler '{other}' (expected one of {})",
                    Self::NAMES
                )));
            }
        })
    }
}

/// Setters named after the fields of a `#[non_exhaustive]` settings struct, each taking
/// the settings by value, so that callers outside the crate write
/// `RenderSettings::default().width(64).samples(0..16)`.
macro_rules! setters {
    ($settings:ty { $($field:ident: $ty:ty),* $(,)? }) => {
        impl $settings {
            $(
                #[doc = concat!("With `", stringify!($field), "` set (see the field).")]
                #[must_use]
                pub fn $field(mut self, value: $ty) -> Self {
                    self.$field = value;
                    self
                }
            )*
        }
    };
}
pub(crate) use setters;

/// The settings of one render. The image depends only on the scene, these settings and
/// `seed`: never on `threads`.
///
/// The defaults: 512 x 512 pixels, samples 0..64 from seed 0, 8 wavelengths per path
/// over 360-830 nm drawn from the visible density by hero rotation, unbounded depth
/// (Russian roulette ends paths), the CIE 1931 observer, a box filter, no clamping, one
/// thread per core, light paths for caustics on, XYZ film (no bands, no energy), opaque
/// background. Start from them and set what you need:
///
/// ```
/// use prism_integrator::RenderSettings;
///
/// let settings = RenderSettings::default().width(64).height(48).samples(0..16).seed(7);
/// assert_eq!((settings.width, settings.wavelengths), (64, 8));
/// assert!(settings.validate().is_ok());
/// ```
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The sample indices rendered in every pixel (`0..spp` for a whole render; a farm
    /// renders disjoint ranges and merges them).
    pub samples: Range<u64>,
    /// Seed of every random stream.
    pub seed: u64,
    /// Longest path in bounces (None: unbounded, ended by Russian roulette).
    pub max_depth: Option<u32>,
    /// Continuations per camera sample from its first vertex (splitting): the camera ray
    /// and the first vertex's light sample are shared, each continuation carries 1 /
    /// splits of the throughput. Chosen per render by default ([`Splits::Auto`]).
    pub splits: Splits,
    /// Path reuse: square tiles of pixels whose paths share their second vertices
    /// (see [`Reuse`]). Chosen per render by default ([`Reuse::Auto`]).
    pub reuse: Reuse,
    /// Wavelengths per path: 1, 2, 4, 8 or 16 (default 8: the most efficient on the
    /// measured scenes, the repository's docs/trade-offs.md, "Wavelengths per path").
    pub wavelengths: usize,
    /// How the hero wavelength is chosen.
    pub lambda_sampler: LambdaSampler,
    /// How the other wavelengths of a package follow the hero.
    pub scheme: PackageScheme,
    /// The wavelength range transported, nm.
    pub range: (f32, f32),
    /// The observer turning spectra into XYZ.
    pub observer: Observer,
    /// A camera with its own response curves instead of the observer: the film then holds
    /// its raw channels (shown as R, G, B), and the response sampler follows its curves.
    pub camera: Option<std::sync::Arc<crate::CameraResponse>>,
    /// Worker threads (0: one per core). Does not change the image.
    pub threads: usize,
    /// The pixel reconstruction filter.
    pub filter: Filter,
    /// Firefly clamp: a sample whose luminance Y exceeds this is scaled down to it
    /// (keeping its chromaticity). Biased (it removes energy), so None by default.
    pub clamp: Option<f64>,
    /// Spectral output: the film also accumulates spectral radiance in these bands.
    pub bands: Option<SpectralBands>,
    /// Energy output: the film also accumulates radiance integrated over `range` and the
    /// photon radiance (the same with each wavelength's radiance divided by hc / lambda).
    pub energy: bool,
    /// Light paths for the caustics the camera sees directly, in scenes with delta
    /// surfaces (smooth glass or metal). Off, camera paths alone find them (unbiased, but
    /// a small light's caustic stays noise and a punctual light's is missing).
    pub light_paths: bool,
    /// Adaptive sampling: the samples spread over the image where a pilot finds the error
    /// (off by default here, on in the CLI; docs/trade-offs.md, "Adaptive sampling"). It
    /// applies to renders of the path tracer from sample 0 to a multiple of 4 samples, at
    /// least 16, without the variance AOV; others sample uniformly.
    pub adaptive: bool,
    /// Whether this render is one piece of a larger one (a farm's sample range, merged
    /// later with the others): its samples are then the uniform render's, so that the
    /// pieces' sample indices neither overlap nor leave gaps.
    pub piece: bool,
    /// Whether the image will be denoised: a denoiser keeps path reuse's blocks of shared
    /// noise as detail, so `Reuse::Auto` then means no reuse.
    pub denoised: bool,
    /// A transparent background: camera rays that leave the scene add nothing (the
    /// environment still lights it), so the image is premultiplied by its alpha.
    pub transparent: bool,
    /// Polarized transport: paths carry a Mueller matrix per wavelength lane and the film
    /// records the Stokes components S1..S3 besides S0 (the ordinary image). Slower; the
    /// default renders without (and its images do not depend on this code).
    pub polarized: bool,
    /// An ideal linear polarizing filter in front of the camera, its transmission axis
    /// at this many degrees from the image's x axis towards its y axis (up): the film
    /// holds what a photograph through it shows. Implies polarized transport.
    pub camera_polarizer: Option<f32>,
    /// The instant rendered on the scene's clock, seconds: light sources shine as their
    /// schedules say at that time, and phosphors glow with what they absorbed before it.
    /// None: the steady state, every source always on (a scene without schedules or
    /// lifetimes looks the same either way).
    pub at: Option<f64>,
    /// An exposure instead of an instant: the shutter opens and closes at these times
    /// (seconds), and each path sees the scene at a time drawn uniformly between them, so
    /// the image is the mean over the exposure.
    pub shutter: Option<(f64, f64)>,
    /// Which tracer runs the camera paths: the path tracer (`Tracing`).
    pub tracing: Tracing,
    /// The feature buffers the film records besides radiance (`crate::Aovs`; none by
    /// default, which costs nothing).
    pub aovs: crate::Aovs,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            width: 512,
            height: 512,
            samples: 0..64,
            seed: 0,
            max_depth: None,
            splits: Splits::Auto,
            reuse: Reuse::Auto,
            wavelengths: 8,
            lambda_sampler: LambdaSampler::default(),
            scheme: PackageScheme::HeroRotation,
            range: (360.0, 830.0),
            observer: Observer::Cie1931,
            camera: None,
            threads: 0,
            filter: Filter::Box,
            clamp: None,
            bands: None,
            energy: false,
            light_paths: true,
            adaptive: false,
            piece: false,
            denoised: false,
            transparent: false,
            polarized: false,
            camera_polarizer: None,
            at: None,
            shutter: None,
            tracing: Tracing::Paths,
            aovs: crate::Aovs::NONE,
        }
    }
}

setters!(RenderSettings {
    width: u32,
    height: u32,
    samples: Range<u64>,
    seed: u64,
    max_depth: Option<u32>,
    splits: Splits,
    reuse: Reuse,
    wavelengths: usize,
    lambda_sampler: LambdaSampler,
    scheme: PackageScheme,
    range: (f32, f32),
    observer: Observer,
    camera: Option<std::sync::Arc<crate::CameraResponse>>,
    threads: usize,
    filter: Filter,
    clamp: Option<f64>,
    bands: Option<SpectralBands>,
    energy: bool,
    light_paths: bool,
    adaptive: bool,
    piece: bool,
    denoised: bool,
    transparent: bool,
    polarized: bool,
    camera_polarizer: Option<f32>,
    at: Option<f64>,
    shutter: Option<(f64, f64)>,
    tracing: Tracing,
    aovs: crate::Aovs,
});

/// The most worker threads a render may ask for.
pub const MAX_THREADS: usize = 1024;

/// The most continuations a camera sample may split into.
pub const MAX_SPLITS: u32 = 64;

/// How many continuations each camera sample splits into at its first vertex.
///
/// Splitting pays where the error is in indirect light (a Cornell box's ceiling, lit only
/// by bounces) and costs where it is in what the camera ray and the first light sample
/// find (direct light, textures, edges); `Auto` tells them apart per render with a pilot
/// (see the integrator's `plan::modes` module and docs/trade-offs.md, "Splitting at the
/// first vertex").
///
/// ```
/// use prism_integrator::Splits;
///
/// assert_eq!("auto".parse::<Splits>(), Ok(Splits::Auto));
/// assert_eq!("4".parse::<Splits>(), Ok(Splits::Fixed(4)));
/// assert!("0".parse::<Splits>().is_err() && "many".parse::<Splits>().is_err());
/// assert_eq!(Splits::Fixed(2).to_string(), "2");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Splits {
    /// 1 or 2, whichever a pilot of the render predicts reaches a given error sooner; the
    /// choice depends only on the scene, the image size, the settings and the seed.
    #[default]
    Auto,
    /// This many, 1 to [`MAX_SPLITS`] (1: no splitting).
    Fixed(u32),
}

impl std::str::FromStr for Splits {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if s == "auto" {
            return Ok(Splits::Auto);
        }
        match s.parse::<u32>() {
            Ok(k) if (1..=MAX_SPLITS).contains(&k) => Ok(Splits::Fixed(k)),
            _ => Err(format!(
                "splits '{s}': expected auto or a whole number 1 to {MAX_SPLITS}"
            )),
        }
    }
}

impl std::fmt::Display for Splits {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Splits::Auto => f.write_str("auto"),
            Splits::Fixed(k) => write!(f, "{k}"),
        }
    }
}

/// Which tracer runs a render's camera paths.
///
/// ```
/// use prism_integrator::Tracing;
///
/// assert_eq!("paths".parse::<Tracing>(), Ok(Tracing::Paths));
/// assert_eq!("lanes".parse::<Tracing>(), Ok(Tracing::Lanes(None)));
/// assert_eq!("lanes:8".parse::<Tracing>(), Ok(Tracing::Lanes(Some(8))));
/// assert!("lanes:5".parse::<Tracing>().is_err() && "wide".parse::<Tracing>().is_err());
/// assert_eq!(Tracing::Lanes(Some(16)).to_string(), "lanes:16");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Tracing {
    /// The path tracer: each camera path traced alone, every feature served.
    #[default]
    Paths,
    /// The batch tracer, which traced neighbouring pixels' paths in SIMD lanes (4, 8 or
    /// 16 wide; None: the CPU's). It rendered the path tracer's images byte for byte and
    /// was never faster at equal error, so it is not kept: a render that asks for it
    /// runs the path tracer, the same image, and says why in its `Estimators`
    /// (docs/trade-offs.md, "Tried and not kept").
    Lanes(Option<usize>),
}

impl std::str::FromStr for Tracing {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "paths" => Ok(Tracing::Paths),
            "lanes" => Ok(Tracing::Lanes(None)),
            "lanes:4" => Ok(Tracing::Lanes(Some(4))),
            "lanes:8" => Ok(Tracing::Lanes(Some(8))),
            "lanes:16" => Ok(Tracing::Lanes(Some(16))),
            _ => Err(format!(
                "tracer '{s}': expected paths, lanes, or lanes:4, lanes:8 or lanes:16"
            )),
        }
    }
}

impl std::fmt::Display for Tracing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Tracing::Paths => f.write_str("paths"),
            Tracing::Lanes(None) => f.write_str("lanes"),
            Tracing::Lanes(Some(w)) => write!(f, "lanes:{w}"),
        }
    }
}

/// The widest tile of pixels whose paths may share their second vertices.
pub const MAX_REUSE: u32 = 8;

/// Path reuse (Bekaert, Sbert and Halton 2002): the pixels of each T x T tile share the
/// light their paths find beyond the first bounce, so each pixel's indirect light is
/// estimated from T^2 continuations for T^2 - 1 shadow rays. Unbiased; it pays where the
/// error is in indirect light on Lambertian surfaces (on a Cornell box, tiles of four were
/// the most efficient mode measured), costs shadow rays where it is not, and does not
/// apply to polarized, timed, fluorescent, dispersive or cut-out scenes, or with
/// splitting (see the integrator's `reuse` module and docs/trade-offs.md, "Path reuse
/// across tiles of pixels").
///
/// ```
/// use prism_integrator::Reuse;
///
/// assert_eq!("auto".parse::<Reuse>(), Ok(Reuse::Auto));
/// assert_eq!("4".parse::<Reuse>(), Ok(Reuse::Fixed(4)));
/// assert!("0".parse::<Reuse>().is_err() && "9".parse::<Reuse>().is_err());
/// assert_eq!(Reuse::Fixed(2).to_string(), "2");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Reuse {
    /// None, 2 or 4, whichever a pilot of the render predicts reaches a given error
    /// soonest (with the choice of splits); only where the scene allows reuse.
    #[default]
    Auto,
    /// Tiles this many pixels a side, 1 to [`MAX_REUSE`] (1: no reuse).
    Fixed(u32),
}

impl std::str::FromStr for Reuse {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if s == "auto" {
            return Ok(Reuse::Auto);
        }
        match s.parse::<u32>() {
            Ok(t) if (1..=MAX_REUSE).contains(&t) => Ok(Reuse::Fixed(t)),
            _ => Err(format!(
                "reuse '{s}': expected auto or a tile side 1 to {MAX_REUSE}"
            )),
        }
    }
}

impl std::fmt::Display for Reuse {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Reuse::Auto => f.write_str("auto"),
            Reuse::Fixed(t) => write!(f, "{t}"),
        }
    }
}

impl RenderSettings {
    /// Whether paths carry polarization (asked for, or implied by a camera polarizer).
    pub fn is_polarized(&self) -> bool {
        self.polarized || self.camera_polarizer.is_some()
    }

    /// Checks every setting, naming the first one out of range.
    ///
    /// ```
    /// use prism_integrator::RenderSettings;
    ///
    /// let defaults = RenderSettings::default();
    /// assert_eq!((defaults.width, defaults.height, defaults.samples.clone()), (512, 512, 0..64));
    /// assert_eq!((defaults.wavelengths, defaults.max_depth, defaults.light_paths), (8, None, true));
    /// assert!(defaults.validate().is_ok());
    /// let empty = RenderSettings::default().samples(5..5);
    /// assert!(empty.validate().unwrap_err().to_string().contains("sample"));
    /// ```
    pub fn validate(&self) -> Result<(), RenderError> {
        let bad = |m: String| Err(RenderError::Setting(m));
        if let Some(angle) = self.camera_polarizer
            && !angle.is_finite()
        {
            return bad(format!(
                "camera polarizer angle {angle} is not a number of degrees"
            ));
        }
        if let Some(t) = self.at
            && !t.is_finite()
        {
            return bad(format!("time {t} is not a number of seconds"));
        }
        match (self.at, self.shutter) {
            (Some(_), Some(_)) => {
                return bad("an instant (at) and an exposure (shutter) exclude each other".into());
            }
            (_, Some((open, close)))
                if !(open.is_finite() && close.is_finite() && open < close) =>
            {
                return bad(format!(
                    "shutter {open}:{close} must open before it closes, both finite seconds"
                ));
            }
            _ => {}
        }
        if let Tracing::Lanes(Some(w)) = self.tracing
            && ![4, 8, 16].contains(&w)
        {
            return bad(format!("tracer lanes:{w}: lanes were 4, 8 or 16 wide"));
        }
        if self.width == 0 || self.height == 0 {
            return bad(format!(
                "image size {}x{} is empty",
                self.width, self.height
            ));
        }
        // The film holds 32 bytes per pixel; refuse sizes whose film alone exceeds 64 GiB.
        if u64::from(self.width) * u64::from(self.height) > (1 << 31) {
            return bad(format!(
                "image size {}x{} is too large (at most 2^31 pixels)",
                self.width, self.height
            ));
        }
        // Threads are spawned one by one before any work: --threads 100000 spent minutes
        // creating threads, then failed with EAGAIN, and tearing them down outlasted a
        // two-minute timeout. More workers than this gains nothing on any machine.
        if self.threads > MAX_THREADS {
            return bad(format!(
                "{} threads: at most {MAX_THREADS} (0 is one per core)",
                self.threads
            ));
        }
        if self.samples.is_empty() {
            return bad(format!(
                "sample range {}..{} is empty",
                self.samples.start, self.samples.end
            ));
        }
        if let Splits::Fixed(k) = self.splits
            && !(1..=MAX_SPLITS).contains(&k)
        {
            return bad(format!(
                "{k} splits per camera sample: expected 1 to {MAX_SPLITS}"
            ));
        }
        if let Reuse::Fixed(t) = self.reuse
            && !(1..=MAX_REUSE).contains(&t)
        {
            return bad(format!(
                "reuse tiles {t} pixels wide: expected 1 to {MAX_REUSE}"
            ));
        }
        if let (Reuse::Fixed(t), Splits::Fixed(k)) = (self.reuse, self.splits)
            && t > 1
            && k > 1
        {
            return bad(format!(
                "reuse {t} and {k} splits: a render shares second vertices or splits, not both"
            ));
        }
        if ![1, 2, 4, 8, 16].contains(&self.wavelengths) {
            return bad(format!(
                "{} wavelengths per path: expected 1, 2, 4, 8 or 16",
                self.wavelengths
            ));
        }
        WavelengthRange::new(self.range.0, self.range.1)
            .map_err(|e| RenderError::Setting(format!("wavelength range: {e}")))?;
        crate::film::filter::FilterSampler::new(self.filter)?;
        if let Some(c) = self.clamp
            && !(c.is_finite() && c > 0.0)
        {
            return bad(format!("clamp {c} must be finite and > 0"));
        }
        Ok(())
    }

    /// The hero wavelength distribution. `light_spectra` are the scene's light spectra
    /// (used by [`LambdaSampler::Spd`]).
    pub fn distribution(
        &self,
        light_spectra: &[&dyn Fn(f64) -> f64],
    ) -> Result<WavelengthDistribution, RenderError> {
        let range = WavelengthRange::new(self.range.0, self.range.1)
            .map_err(|e| RenderError::Setting(format!("wavelength range: {e}")))?;
        let observer = self.observer;
        let camera = self.camera.clone();
        let cmf = |k: usize| {
            let camera = camera.clone();
            move |l: f64| match &camera {
                Some(c) => c.response(l)[k],
                None => observer.cmf(l)[k],
            }
        };
        let (x, y, z) = (cmf(0), cmf(1), cmf(2));
        let response_sum = |l: f64| x(l) + y(l) + z(l);
        let bins = ((self.range.1 - self.range.0).ceil() as usize).max(1);
        let setting = |e: prism_sampling::SamplingError| {
            RenderError::Setting(format!("wavelength sampler: {e}"))
        };
        Ok(match self.lambda_sampler {
            LambdaSampler::Uniform => WavelengthDistribution::uniform(range),
            LambdaSampler::Visible => WavelengthDistribution::visible(range),
            LambdaSampler::Response => {
                WavelengthDistribution::response(range, bins, &[&x, &y, &z]).map_err(setting)?
            }
            LambdaSampler::Spd => {
                WavelengthDistribution::light_spd(range, bins, light_spectra, &response_sum, 0.1)
                    .map_err(setting)?
            }
        })
    }
}
