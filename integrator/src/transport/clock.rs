//! When a path sees the scene: the clock of an instant or an exposure, the lights it finds
//! on, and the delay of a phosphor's re-emission.

use prism_sampling::stream::{SampleStream, SobolStream};

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
