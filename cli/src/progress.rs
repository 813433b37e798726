//! A render's progress on stderr: a bar on a terminal (indicatif: samples per pixel done,
//! rays per second, the time left, and where the film records its variance the relative
//! MSE that predicts), plain lines every ten seconds elsewhere (logs, CI), nothing with
//! `--quiet`.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use prism_integrator::Film;

/// How progress is shown.
pub enum Progress {
    Quiet,
    Bar(ProgressBar),
    Lines { last: Instant },
}

impl Progress {
    /// Progress over `total` samples per pixel of which `done` are already on the film.
    pub fn new(quiet: bool, done: u64, total: u64) -> Self {
        if quiet {
            return Progress::Quiet;
        }
        if !std::io::stderr().is_terminal() {
            return Progress::Lines {
                last: Instant::now(),
            };
        }
        let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
        let style = ProgressStyle::with_template(
            "{bar:30.cyan/blue} {pos}/{len} spp  {msg}  {elapsed} elapsed, ETA {eta}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("##-");
        bar.set_style(style);
        bar.set_position(done);
        bar.reset_eta();
        Progress::Bar(bar)
    }

    /// `done` of `total` samples per pixel, `rendered` of them in `elapsed` seconds by
    /// this session, which traced `rays` rays and `paths` paths; `film` for the error
    /// estimate.
    #[allow(clippy::too_many_arguments)]
    pub fn update(
        &mut self,
        done: u64,
        total: u64,
        rendered: u64,
        elapsed: f64,
        rays: u64,
        paths: u64,
        film: &Film,
    ) {
        let error = film
            .estimated_relmse()
            .map(|e| format!("  relMSE <= {e:.1e}"))
            .unwrap_or_default();
        let rays_rate = rays as f64 / elapsed.max(1e-9) / 1e6;
        let paths_rate = paths as f64 / elapsed.max(1e-9) / 1e6;
        match self {
            Progress::Quiet => {}
            Progress::Bar(bar) => {
                bar.set_message(format!("{rays_rate:.1} M rays/s{error}"));
                bar.set_position(done);
            }
            Progress::Lines { last } => {
                if last.elapsed() >= Duration::from_secs(10) || done == total {
                    let left = elapsed / rendered.max(1) as f64 * total.saturating_sub(done) as f64;
                    eprintln!(
                        "prism: {done}/{total} spp, {elapsed:.1} s, {paths_rate:.2} M paths/s, {rays_rate:.1} M rays/s{error}, ETA {left:.0} s"
                    );
                    *last = Instant::now();
                }
            }
        }
    }

    /// Clears the bar (its last state stays on screen).
    pub fn finish(&self) {
        if let Progress::Bar(bar) = self {
            bar.abandon();
        }
    }
}
