use glam::Vec2;

use super::hash::{hash_words, mix64};
use super::{SampleStream, bits_to_unit_f32};

/// Independent uniform numbers from a counter-based hash of `(seed, pixel, sample,
/// dimension)`: no state is shared between samples, so any sample is reproducible alone.
#[derive(Debug, Clone)]
pub struct IndependentStream {
    key: u64,
    dimension: u64,
}

impl IndependentStream {
    /// The stream of sample `sample_index` of pixel `pixel` under `seed`.
    pub fn new(seed: u64, pixel: u64, sample_index: u64) -> Self {
        Self {
            key: hash_words(&[seed, pixel, sample_index]),
            dimension: 0,
        }
    }

    /// Jumps to `dimension` (the next call returns that dimension).
    pub fn set_dimension(&mut self, dimension: u64) {
        self.dimension = dimension;
    }

    fn next_bits(&mut self) -> u64 {
        let bits = mix64(self.key ^ mix64(self.dimension));
        self.dimension += 1;
        bits
    }

    /// The next dimension as an f64 in [0, 1) with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_bits() >> 11) as f64 * (1.0 / 9_007_199_254_740_992.0)
    }
}

impl SampleStream for IndependentStream {
    fn next_1d(&mut self) -> f32 {
        bits_to_unit_f32((self.next_bits() >> 32) as u32)
    }

    fn next_2d(&mut self) -> Vec2 {
        let x = self.next_1d();
        Vec2::new(x, self.next_1d())
    }
}
