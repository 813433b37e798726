//! A render as a session a person runs for minutes or days: passes of one sample per
//! pixel, so it can stop at any sample boundary (time budget, SIGINT or SIGTERM), report
//! progress, write checkpoints, and resume, while the image stays exactly the one an
//! uninterrupted render makes: the film adds each pass's sums in sample order, which is
//! the order a single render adds them in.

use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use prism_integrator::{Film, RenderSettings, RenderStats, Renderer, encode_accumulation};
use prism_scene::world::Scene;

use crate::output::write_atomically;
use crate::progress::Progress;
use crate::tev::TevPreview;

/// How a session runs besides the render settings.
pub struct SessionOptions {
    /// Stop at the first sample boundary after this long.
    pub time_budget: Option<Duration>,
    /// Write an accumulation file here every so often, and when the session ends.
    pub checkpoint: Option<(Duration, PathBuf)>,
    /// No progress output.
    pub quiet: bool,
    /// The settings fingerprint recorded in checkpoints.
    pub fingerprint: String,
    /// Samples per pixel done so far in this session, for whoever watches (Python's
    /// progress callback).
    pub done: std::sync::Arc<std::sync::atomic::AtomicU64>,
    /// Where to stream the image as it converges: tev's address (HOST:PORT), the image's
    /// name there, and the colour space it is shown in.
    pub tev: Option<(String, String, prism_spectrum::color::RgbSpaceId)>,
}

/// Why a session ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    /// Every sample was rendered.
    Complete,
    /// The time budget ran out.
    TimeBudget,
    /// SIGINT or SIGTERM.
    Interrupted,
}

/// The outcome: the film (holding `samples.start..film.samples() + start`), counters, why.
pub struct Outcome {
    pub film: Film,
    pub stats: RenderStats,
    pub ending: Ending,
    pub seconds: f64,
}

/// Renders `range` (continuing `film`, which already holds `range.start..done`) one sample
/// per pixel at a time until done, out of time, or `cancel` is set.
pub fn run(
    scene: &Scene,
    settings: &RenderSettings,
    range: Range<u64>,
    mut film: Film,
    options: &SessionOptions,
    cancel: &AtomicBool,
) -> Result<Outcome, String> {
    let started = Instant::now();
    let mut stats = RenderStats::default();
    let mut last_checkpoint = Instant::now();
    let first = range.start + film.samples();
    let total = range.end - range.start;
    let mut progress = Progress::new(options.quiet, first - range.start, total);
    let mut tev = options
        .tev
        .as_ref()
        .map(|(address, name, space)| TevPreview::connect(address, name, *space));
    let renderer = Renderer::new(scene, settings).map_err(|e| e.to_string())?;
    stats.splits = renderer.splits();
    stats.reuse = renderer.reuse();
    stats.adaptive = renderer.adaptive();
    stats.focus_distance = renderer.focus_distance();
    stats.estimators = renderer.estimators();
    if let prism_integrator::Reuse::Fixed(t) = settings.reuse
        && t > 1
        && renderer.reuse() == 1
    {
        eprintln!(
            "prism: warning: --reuse {t} does not apply to this render ({}); rendering without it",
            stats.estimators.reuse_why
        );
    }
    if let prism_integrator::Tracing::Lanes(_) = settings.tracing {
        eprintln!(
            "prism: warning: --tracer {}: {}",
            settings.tracing, stats.estimators.tracer_why
        );
    }
    let mut ending = Ending::Complete;
    for s in first..range.end {
        if cancel.load(Ordering::Relaxed) {
            ending = Ending::Interrupted;
            break;
        }
        // A time budget ends a render between groups of adaptive sampling's passes, where
        // every tile has its share of samples.
        if s.is_multiple_of(renderer.pass_group())
            && options
                .time_budget
                .is_some_and(|budget| started.elapsed() >= budget)
        {
            ending = Ending::TimeBudget;
            break;
        }
        match renderer
            .render_into(s..s + 1, &mut film, cancel)
            .map_err(|e| e.to_string())?
        {
            Some(p) => {
                stats.paths += p.paths;
                stats.rays += p.rays;
                stats.nonfinite += p.nonfinite;
            }
            None => {
                ending = Ending::Interrupted;
                break;
            }
        }
        let done = s + 1 - range.start;
        options.done.store(s + 1 - first, Ordering::Relaxed);
        if let Some((every, path)) = &options.checkpoint
            && last_checkpoint.elapsed() >= *every
            && s + 1 < range.end
        {
            write_checkpoint(&film, range.start, path, &options.fingerprint)?;
            last_checkpoint = Instant::now();
        }
        progress.update(
            done,
            total,
            s + 1 - first,
            started.elapsed().as_secs_f64(),
            stats.rays,
            stats.paths,
            &film,
        );
        if let Some(tev) = &mut tev {
            tev.show(&film, false);
        }
    }
    progress.finish();
    if let Some(tev) = &mut tev {
        tev.show(&film, true);
    }
    // Also when complete: a checkpoint can be resumed with a larger --spp.
    if let Some((_, path)) = &options.checkpoint {
        write_checkpoint(&film, range.start, path, &options.fingerprint)?;
    }
    Ok(Outcome {
        film,
        stats,
        ending,
        seconds: started.elapsed().as_secs_f64(),
    })
}

fn write_checkpoint(film: &Film, start: u64, path: &Path, fingerprint: &str) -> Result<(), String> {
    let bytes = encode_accumulation(film, start..start + film.samples(), fingerprint)
        .map_err(|e| e.to_string())?;
    write_atomically(path, &bytes)
}

/// Sets `cancel` on SIGINT and SIGTERM; a second one while it is set exits at once with
/// status 130.
pub fn stop_on_signals(cancel: &std::sync::Arc<AtomicBool>) -> Result<(), String> {
    #[cfg(unix)]
    {
        use signal_hook::consts::{SIGINT, SIGTERM};
        for signal in [SIGINT, SIGTERM] {
            // Registered first, so it sees the flag before this signal sets it.
            signal_hook::flag::register_conditional_shutdown(signal, 130, cancel.clone())
                .and_then(|_| signal_hook::flag::register(signal, cancel.clone()))
                .map_err(|e| format!("cannot handle signals: {e}"))?;
        }
    }
    #[cfg(not(unix))]
    let _ = cancel;
    Ok(())
}
