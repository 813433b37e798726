//! Deterministic sample streams: the uniform numbers of sample `s` of pixel `p` are a pure
//! function of `(seed, p, s, dimension)`, so an image does not depend on thread count,
//! tile order or scheduling, and any subset of samples can be rendered anywhere (a farm
//! renders sample ranges and merges them).

mod hash;
mod independent;
mod replicas;
mod sobol;
mod sobol_lanes;

pub use hash::mix64;
pub use independent::IndependentStream;
pub use replicas::Replicas;
pub use sobol::{SobolStream, sobol_sample};
pub use sobol_lanes::SobolLanes;

use glam::Vec2;

/// A stream of uniform numbers in [0, 1) for one sample of one pixel.
pub trait SampleStream {
    /// The next dimension.
    fn next_1d(&mut self) -> f32;
    /// The next two dimensions, as a pair designed to be well distributed together.
    fn next_2d(&mut self) -> Vec2;
}

/// Converts 32 random bits to a float in [0, 1): the top 24 bits, so every value is
/// exactly representable and 1 is never produced.
pub(crate) fn bits_to_unit_f32(bits: u32) -> f32 {
    (bits >> 8) as f32 * (1.0 / 16_777_216.0)
}
