//! The one place a render's settings become its estimators: which tracer traces its camera
//! paths, how many continuations each sample splits into, the tile its paths share
//! second vertices in, whether light paths carry caustics, and whether a pilot spreads
//! the samples. [`resolve`] reads the settings and the scene and returns what is fixed
//! and what the pilots choose, each with its reason; a combination no estimator can
//! render right is refused in one line naming both settings.

use prism_scene::camera::Projection;
use prism_scene::world::Scene;

use crate::settings::{Reuse, Splits, Tracing};
use crate::{RenderError, RenderSettings};

/// Why `--tracer lanes` renders with the path tracer: the batch tracer traced the same
/// paths to the bit and was never faster at equal error, so it is not kept
/// (docs/trade-offs.md, "Tried and not kept").
const LANES_NOT_KEPT: &str =
    "the batch tracer (lanes) is not kept: the path tracer renders the same image, faster";

/// Which tracer traces a render's camera paths.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TracerKind {
    /// The path tracer, one path at a time.
    #[default]
    Paths,
    /// The volumetric path tracer (the scene has media or interfaces).
    Volume,
}

impl std::fmt::Display for TracerKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TracerKind::Paths => f.write_str("paths"),
            TracerKind::Volume => f.write_str("volume"),
        }
    }
}

/// The estimators a render uses, each with why: what `--stats` prints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Estimators {
    /// The tracer of camera paths.
    pub tracer: TracerKind,
    /// Why `tracer` is what it is.
    pub tracer_why: &'static str,
    /// Continuations per camera sample.
    pub splits: u32,
    /// Why `splits` is what it is.
    pub splits_why: &'static str,
    /// The side of the tiles whose paths share second vertices (1: none).
    pub reuse: u32,
    /// Why `reuse` is what it is.
    pub reuse_why: &'static str,
    /// Whether light paths carry the caustics seen directly.
    pub light_paths: bool,
    /// Why light paths are on or off.
    pub light_paths_why: &'static str,
    /// Whether adaptive sampling's pilot spreads the samples.
    pub adaptive: bool,
    /// Why adaptive sampling is on or off.
    pub adaptive_why: &'static str,
}

impl std::fmt::Display for Estimators {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let on = |b: bool| if b { "on" } else { "off" };
        write!(
            f,
            "tracer {} ({}); splits {} ({}); reuse {} ({}); light paths {} ({}); adaptive {} ({})",
            self.tracer,
            self.tracer_why,
            self.splits,
            self.splits_why,
            self.reuse,
            self.reuse_why,
            on(self.light_paths),
            self.light_paths_why,
            on(self.adaptive),
            self.adaptive_why,
        )
    }
}

/// How a render's splits and reuse tile are chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Modes {
    /// Fixed: (splits, reuse).
    Fixed(u32, u32),
    /// The splits pilot chooses the splits; no reuse.
    SplitsPilot,
    /// The mode pilot chooses splits or a reuse tile.
    ModePilot,
}

/// What [`resolve`] decides before any pilot runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Resolution {
    pub tracer: TracerKind,
    pub tracer_why: &'static str,
    pub modes: Modes,
    /// Why the modes are fixed or left to a pilot.
    pub splits_why: &'static str,
    pub reuse_why: &'static str,
    pub light_paths: bool,
    pub light_paths_why: &'static str,
    /// Whether a pilot may spread the samples (it may still find nothing to spread).
    pub adaptive: bool,
    pub adaptive_why: &'static str,
}

impl Resolution {
    /// The estimators, once the pilots chose `splits` and `reuse` and adaptive sampling's
    /// pilot made a map (`adaptive`) or not.
    pub(crate) fn estimators(&self, splits: u32, reuse: u32, adaptive: bool) -> Estimators {
        let (splits_why, reuse_why) = match self.modes {
            Modes::Fixed(..) => (self.splits_why, self.reuse_why),
            Modes::SplitsPilot => ("chosen by the splits pilot", self.reuse_why),
            Modes::ModePilot => ("chosen by the mode pilot", "chosen by the mode pilot"),
        };
        Estimators {
            tracer: self.tracer,
            tracer_why: self.tracer_why,
            splits,
            splits_why,
            reuse,
            reuse_why,
            light_paths: self.light_paths,
            light_paths_why: self.light_paths_why,
            adaptive,
            adaptive_why: if self.adaptive && !adaptive {
                "the pilot found no error to spread"
            } else {
                self.adaptive_why
            },
        }
    }
}

/// Resolves `settings` for `scene` (whose camera has a lens system where `lens_system`)
/// into estimators, or refuses a combination that cannot be rendered right.
pub(crate) fn resolve(
    scene: &Scene,
    settings: &RenderSettings,
    lens_system: bool,
) -> Result<Resolution, RenderError> {
    settings.validate()?;
    let features = scene.features();
    let refuse = |m: &str| Err(RenderError::Setting(m.to_string()));
    let (tracer, tracer_why) = match settings.tracing {
        _ if features.media => {
            if let Splits::Fixed(k) = settings.splits
                && k > 1
            {
                return refuse(
                    "splits above 1 with a scene of participating media: the volumetric tracer does no splitting (use --splits 1 or auto)",
                );
            }
            (
                TracerKind::Volume,
                "the scene has participating media or interfaces",
            )
        }
        Tracing::Paths => (TracerKind::Paths, "the path tracer serves every setting"),
        Tracing::Lanes(_) => (TracerKind::Paths, LANES_NOT_KEPT),
    };
    let no_reuse = why_not_reuse(scene, settings, lens_system);
    // A denoiser keeps reuse's blocks of shared noise as detail: on the Cornell box,
    // denoising cut the relative MSE several times over without reuse and hardly at all
    // with tiles of 2 (docs/trade-offs.md, "Denoising").
    let denoised_auto = settings.denoised && settings.reuse == Reuse::Auto;
    let reuse = if denoised_auto {
        Reuse::Fixed(1)
    } else {
        settings.reuse
    };
    let (modes, splits_why, mut reuse_why) = match (tracer, settings.splits, reuse) {
        (_, splits, Reuse::Fixed(t)) if t > 1 => match no_reuse {
            None => (Modes::Fixed(1, t), "reuse excludes splitting", "as asked"),
            Some(why) => (
                Modes::Fixed(1, 1),
                match splits {
                    Splits::Fixed(_) => "as asked",
                    Splits::Auto => "reuse was asked, which excludes splitting",
                },
                why,
            ),
        },
        (_, Splits::Auto, Reuse::Auto) if no_reuse.is_none() => (Modes::ModePilot, "", ""),
        (TracerKind::Volume, splits, reuse) => (
            Modes::Fixed(1, 1),
            match splits {
                Splits::Fixed(_) => "as asked",
                Splits::Auto => "the volumetric tracer does not split",
            },
            match (reuse, no_reuse) {
                (Reuse::Auto, Some(why)) => why,
                (Reuse::Auto, None) => "the mode pilot runs only where splits are auto",
                (Reuse::Fixed(_), _) => "as asked",
            },
        ),
        (_, Splits::Fixed(k), reuse) => (
            Modes::Fixed(k, 1),
            "as asked",
            match (reuse, no_reuse) {
                (Reuse::Fixed(_), _) => "as asked",
                (Reuse::Auto, _) if k > 1 => "splitting excludes reuse",
                (Reuse::Auto, Some(why)) => why,
                (Reuse::Auto, None) => "the mode pilot runs only where splits are auto",
            },
        ),
        (_, Splits::Auto, reuse) => (
            Modes::SplitsPilot,
            "",
            match (reuse, no_reuse) {
                (Reuse::Auto, Some(why)) => why,
                _ => "as asked",
            },
        ),
    };
    if denoised_auto && reuse_why == "as asked" {
        reuse_why = "a denoised render does not reuse (the denoiser keeps its blocks of noise)";
    }
    let (light_paths, light_paths_why) = light_paths(scene, settings, lens_system);
    let (adaptive, adaptive_why) = adaptive(settings);
    Ok(Resolution {
        tracer,
        tracer_why,
        modes,
        splits_why,
        reuse_why,
        light_paths,
        light_paths_why,
        adaptive,
        adaptive_why,
    })
}

/// Why paths cannot share second vertices in this render (None: they can). Sharing needs
/// spectra, not Stokes vectors; wavelengths no vertex changes (fluorescence, dispersion);
/// no instant (a lane's time can change at a phosphor); no surface a ray passes through
/// by chance; and a camera ray whose weight a restart at the second vertex keeps (a lens
/// system's would not survive it).
fn why_not_reuse(
    scene: &Scene,
    settings: &RenderSettings,
    lens_system: bool,
) -> Option<&'static str> {
    let features = scene.features();
    if settings.is_polarized() {
        Some("polarized paths do not share vertices")
    } else if settings.at.is_some() || settings.shutter.is_some() {
        Some("timed paths (at or shutter) do not share vertices")
    } else if features.fluorescence {
        Some("the scene's fluorescence changes wavelengths along paths")
    } else if features.dispersion {
        Some("the scene's dispersion changes wavelengths along paths")
    } else if scene.has_cutouts() {
        Some("the scene has cutout surfaces, which rays pass by chance")
    } else if lens_system {
        Some("a lens system's camera-ray weight does not survive sharing")
    } else {
        None
    }
}

/// Whether light paths carry caustics: the settings allow them, the scene has no media, a
/// light has power to start them, the camera is perspective without a lens system (an
/// orthographic camera cannot be connected to, nor a lens system's film found from a
/// point of the scene), and some surface focuses light (smooth or nearly smooth glass or
/// metal and every delta lobe: `Material::focuses`).
fn light_paths(
    scene: &Scene,
    settings: &RenderSettings,
    lens_system: bool,
) -> (bool, &'static str) {
    let why_not = if !settings.light_paths {
        Some("as asked")
    } else if scene.features().media {
        Some("the volumetric tracer does not splat light paths")
    } else if !scene.lights().start_light_paths() {
        Some("no light can start them")
    } else if lens_system {
        Some("a lens system's film cannot be found from the scene")
    } else if !matches!(scene.camera().projection, Projection::Perspective { .. }) {
        Some("only a perspective camera can be connected to")
    } else if !scene
        .materials()
        .iter()
        .any(|m| m.focuses(crate::transport::light_path::CAUSTIC_ALPHA))
    {
        Some("no surface focuses light")
    } else {
        None
    };
    match why_not {
        Some(why) => (false, why),
        None => (true, "surfaces focus light into caustics"),
    }
}

/// Whether a pilot may spread the samples (`RenderSettings::adaptive`): the path
/// tracers', over whole groups of passes from the first, enough of them that the pilot's
/// two samples per pixel are small beside them, and without the variance AOV (whose two
/// replicates split samples by their index).
fn adaptive(settings: &RenderSettings) -> (bool, &'static str) {
    let group = crate::adaptive::GROUP;
    let why_not = if !settings.adaptive {
        Some("as asked")
    } else if settings.piece {
        Some(
            "a piece of a larger render (a sample range) samples uniformly, so that the pieces merge",
        )
    } else if settings.aovs.has(crate::Aov::Variance) {
        Some("the variance AOV splits samples by their index")
    } else if settings.samples.start != 0 {
        Some("a sample range that does not start at 0 cannot follow the pilot's groups")
    } else if settings.samples.end < crate::adaptive::MIN_SAMPLES {
        Some("fewer than 16 samples per pixel")
    } else if !settings.samples.end.is_multiple_of(group) {
        Some("samples per pixel not a multiple of 4 (the pilot's group)")
    } else {
        None
    };
    match why_not {
        Some(why) => (false, why),
        None => (true, "the pilot spreads samples where the error is"),
    }
}
