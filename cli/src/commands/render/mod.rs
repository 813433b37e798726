//! `prism render`: a scene (or the embedded default) to EXR and PNG images. `run` goes
//! through the phases in order, one module each: the scene with the command line's
//! overrides (`scene`), the render's settings (`settings`), the film to continue
//! (`checkpoint`), the session, and what it writes and reports (`outputs`).

mod args;
mod checkpoint;
mod outputs;
mod scene;
mod settings;

use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use prism_integrator::{Film, Filter, LambdaSampler, encode_accumulation};
use prism_spectrum::color::RgbSpaceId;

use crate::output::write_atomically;
use crate::session::{self, Outcome};

pub use args::RenderArgs;
pub use outputs::{
    check_outputs, denoise_film, denoised_image, has_extension, stats_json, write_images,
    write_render,
};

/// A render done: what it rendered, with the settings, colour space and white balance its
/// outputs are written with.
pub struct Rendered {
    pub outcome: Outcome,
    pub settings: prism_integrator::RenderSettings,
    pub space: RgbSpaceId,
    pub white_balance: Option<prism_spectrum::color::Mat3>,
    /// The samples asked for (a range of them for farms).
    pub range: std::ops::Range<u64>,
    /// Whether only a sample range was rendered (accumulation outputs).
    pub samples_only: bool,
    pub fingerprint: String,
    pub started: Instant,
}

/// Why a render failed: its settings (a bad flag, or flags that do not go together), or
/// its scene (it cannot be read, or the render of it failed). Python raises `ValueError`
/// for the first and `prism.SceneError` for the second; the command line prints either.
#[derive(Debug, Clone, PartialEq)]
pub enum Failure {
    /// A bad setting.
    Setting(String),
    /// A scene that cannot be loaded or rendered.
    Scene(String),
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Failure::Setting(m) | Failure::Scene(m) => f.write_str(m),
        }
    }
}

impl From<Failure> for String {
    fn from(failure: Failure) -> String {
        failure.to_string()
    }
}

pub fn run(args: &RenderArgs) -> Result<(), String> {
    let cancel = Arc::new(AtomicBool::new(false));
    session::stop_on_signals(&cancel)?;
    let rendered = render(args, None, &cancel, &Default::default())?;
    let Rendered {
        outcome,
        settings,
        space,
        white_balance,
        range,
        samples_only,
        fingerprint,
        started,
    } = &rendered;
    let Outcome { film, stats, .. } = outcome;
    if *samples_only {
        let done = range.start..range.start + film.samples();
        let bytes = encode_accumulation(film, done, fingerprint).map_err(|e| e.to_string())?;
        for out in &args.outputs {
            write_atomically(out, &bytes)?;
        }
    } else {
        outputs::write_render(
            args,
            film,
            settings,
            stats,
            *space,
            white_balance.as_ref(),
            None,
        )?;
    }
    if stats.nonfinite > 0 {
        eprintln!(
            "prism: warning: {} non-finite samples were rejected",
            stats.nonfinite
        );
    }
    if args.stats {
        outln!("{}", outputs::stats_json(args, settings, outcome, *started));
    }
    outputs::finish(args, outcome, range)
}

/// Renders as `prism render` does, the scene `loaded` (None: the one `args` names) with
/// `args`' settings, until done or `cancel` is set, counting the samples per pixel done in
/// `done`; writes nothing (checkpoints aside).
pub fn render(
    args: &RenderArgs,
    loaded: Option<(
        prism_scene::load::LoadedGeometry,
        crate::scene_file::FileDefaults,
    )>,
    cancel: &Arc<AtomicBool>,
    done: &Arc<std::sync::atomic::AtomicU64>,
) -> Result<Rendered, Failure> {
    let setting = |e: String| Failure::Setting(e);
    // The flags that need no scene are checked before it is loaded.
    let space = RgbSpaceId::from_name(&args.space).map_err(|e| setting(e.to_string()))?;
    let lambda_sampler =
        LambdaSampler::from_name(&args.lambda_sampler).map_err(|e| setting(e.to_string()))?;
    let chosen_filter = args
        .filter
        .as_deref()
        .map(Filter::from_name)
        .transpose()
        .map_err(|e| setting(e.to_string()))?;
    check_outputs(&args.outputs).map_err(setting)?;
    let samples_only = settings::samples_only(args).map_err(setting)?;
    let started = Instant::now();
    let (scene, camera, defaults) = scene::prepare(args, loaded).map_err(Failure::Scene)?;
    let (width, height) = match (args.width, args.height, defaults.size) {
        (None, None, Some(size)) => size,
        _ => scene::image_size(args.width, args.height, scene.camera().aspect_ratio),
    };
    let settings = settings::render_settings(
        args,
        settings::Image {
            width,
            height,
            samples: samples_only
                .clone()
                .unwrap_or(0..args.spp.or(defaults.spp).unwrap_or(64)),
            max_depth: args.max_depth.or(defaults.max_depth),
            lambda_sampler,
            filter: chosen_filter.or(defaults.filter).unwrap_or_default(),
        },
        camera,
    )
    .map_err(setting)?;
    if args.denoise {
        // Before the render, not after it: a missing library is said at once.
        crate::denoise::find_library().map_err(setting)?;
    }
    let white_balance = args
        .white_balance
        .as_deref()
        .map(|spec| settings::white_balance(spec, space))
        .transpose()
        .map_err(setting)?;
    settings::check_film_memory(width, height, settings.aovs).map_err(setting)?;
    let range = settings.samples.clone();
    // The filter as the command line named it, or the scene file's.
    let filter_name = match (&args.filter, defaults.filter) {
        (Some(name), _) => name.clone(),
        (None, Some(filter)) => format!("{filter:?}"),
        (None, None) => "box".to_string(),
    };
    let fingerprint = checkpoint::fingerprint(args, width, height, settings.aovs, &filter_name);
    let film = match &args.resume {
        None => Film::for_settings(&settings),
        Some(path) => checkpoint::resume(path, &fingerprint, &range).map_err(Failure::Scene)?,
    };
    let mut options = settings::session_options(args, fingerprint.clone()).map_err(setting)?;
    options.done = done.clone();
    let outcome = session::run(&scene, &settings, range.clone(), film, &options, cancel)
        .map_err(Failure::Scene)?;
    Ok(Rendered {
        outcome,
        settings,
        space,
        white_balance,
        range,
        samples_only: samples_only.is_some(),
        fingerprint,
        started,
    })
}
