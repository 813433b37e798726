//! When a path sees the scene: the clock of an instant or an exposure, the lights it finds
//! on, and the delay of a phosphor's re-emission.

use prism_sampling::stream::{SampleStream, SobolStream};
use prism_spectrum::SampledSpectrum;

use super::Tracer;

/// When a path sees the scene: an instant, or a time drawn uniformly from an exposure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Clock {
    At(f64),
    Shutter(f64, f64),
}

/// The sample-stream dimension an exposure's time is drawn from: far past any bounce's,
/// so that it changes no other dimension.
const TIME_DIMENSION: u64 = 1 << 24;

impl Clock {
    /// The clock of `settings` (None: the steady state).
    pub(crate) fn of(settings: &crate::RenderSettings) -> Option<Self> {
        match (settings.at, settings.shutter) {
            (Some(t), _) => Some(Clock::At(t)),
            (None, Some((open, close))) => Some(Clock::Shutter(open, close)),
            (None, None) => None,
        }
    }

    /// The time of the path whose stream is `stream` (an instant's is fixed; an
    /// exposure's uniform in it). Leaves the stream at another dimension.
    pub(crate) fn time(&self, stream: &mut SobolStream) -> f64 {
        match *self {
            Clock::At(t) => t,
            Clock::Shutter(open, close) => {
                stream.set_dimension(TIME_DIMENSION);
                let u = f64::from(stream.next_1d());
                (open + u * (close - open)).min(close)
            }
        }
    }
}

impl Tracer<'_> {
    /// Darkens the lanes of `le`, light `light`'s, whose time finds it off.
    pub(crate) fn gate<const N: usize>(
        &self,
        light: Option<u32>,
        times: &[f64; N],
        le: &mut SampledSpectrum<N>,
    ) {
        let Some(light) = light else { return };
        let timeline = self.scene.timeline();
        for (j, t) in times.iter().enumerate() {
            if !timeline.on(light, *t) {
                le[j] = 0.0;
            }
        }
    }

    /// At a phosphor, sends each re-emitting lane back to when its light was absorbed: a
    /// delay drawn with `u` from the decay law restricted to when some source shone,
    /// weighing the lane by the law's mass there (`prism_sampling::decay`); a lane with
    /// nothing to absorb is dark.
    pub(super) fn delay<const N: usize>(
        &self,
        decay: &prism_sampling::decay::Decay,
        u: f32,
        reemitted: &[bool; N],
        times: &mut [f64; N],
        weights: &mut SampledSpectrum<N>,
    ) {
        let on = self.scene.timeline().any_on();
        for j in 0..N {
            if !reemitted[j] {
                continue;
            }
            let windows = prism_sampling::decay::delay_windows(times[j], on);
            match decay.sample_within(f64::from(u), &windows) {
                Some((d, mass)) => {
                    times[j] -= d;
                    weights[j] *= mass as f32;
                }
                None => weights[j] = 0.0,
            }
        }
    }
}
