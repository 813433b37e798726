//! The Sobol stream of W neighbouring samples of one pixel at once, one sample per lane:
//! what paths traced in lanes would draw. Lane `i` is, to the bit, [`SobolStream`] of
//! sample `first + i`: the scramble runs the same code over lanes of words
//! (`laine_karras_permutation` over [`Word`]), and what the lanes share (the pixel's key,
//! the dimension's hash) is computed once for all of them.

use super::hash::{hash_words, mix64};
use super::sobol::{
    DIMENSION_1_BYTES_REVERSED, by_bytes, laine_karras_permutation, pair_hash, split_reversed_index,
};
use crate::lanes::{Lanes, Word};

#[cfg(doc)]
use super::SobolStream;

/// W consecutive samples of one pixel's Sobol stream, drawn together.
#[derive(Debug, Clone)]
pub struct SobolLanes<const W: usize> {
    key: u64,
    reversed_index: Lanes<u32, W>,
    dimension: u64,
}

impl<const W: usize> SobolLanes<W> {
    /// Samples `first`, `first + 1`, ..., `first + W - 1` of pixel `pixel` under `seed`
    /// (indices wrap at 2^32, as [`SobolStream::new`]'s do).
    pub fn new(seed: u64, pixel: u64, first: u64) -> Self {
        Self {
            key: hash_words(&[seed, pixel]),
            reversed_index: Lanes::from_fn(|i| {
                (first.wrapping_add(i as u64) as u32).reverse_bits()
            }),
            dimension: 0,
        }
    }

    /// Part `part` of `parts` of each lane's sample, as [`SobolStream::split`] gives it:
    /// lane `i` becomes sample `(first + i) * parts + part`, at the same dimension.
    pub fn split(&self, part: u32, parts: u32) -> Self {
        Self {
            key: self.key,
            reversed_index: self
                .reversed_index
                .map(|r| split_reversed_index(r, part, parts)),
            dimension: self.dimension,
        }
    }

    /// Jumps to `dimension`.
    pub fn set_dimension(&mut self, dimension: u64) {
        self.dimension = dimension;
    }

    /// The next dimension, per lane.
    pub fn next_1d(&mut self) -> Lanes<f32, W> {
        let h = pair_hash(self.key, self.dimension);
        self.dimension += 1;
        let index =
            laine_karras_permutation(self.reversed_index, Lanes::splat(h as u32)).reverse_bits();
        let x = laine_karras_permutation(index, Lanes::splat((h >> 32) as u32)).reverse_bits();
        unit(x)
    }

    /// The next two dimensions, per lane.
    pub fn next_2d(&mut self) -> [Lanes<f32, W>; 2] {
        let h = pair_hash(self.key, self.dimension);
        self.dimension += 2;
        let index =
            laine_karras_permutation(self.reversed_index, Lanes::splat(h as u32)).reverse_bits();
        let x = laine_karras_permutation(index, Lanes::splat((h >> 32) as u32));
        let y_reversed = index.map(|i| by_bytes(&DIMENSION_1_BYTES_REVERSED, i));
        let y = laine_karras_permutation(y_reversed, Lanes::splat(mix64(h) as u32));
        [unit(x.reverse_bits()), unit(y.reverse_bits())]
    }
}

/// Each lane's 32 bits as a float in [0, 1) (`bits_to_unit_f32`, lane by lane).
#[inline]
fn unit<const W: usize>(bits: Lanes<u32, W>) -> Lanes<f32, W> {
    bits.map(super::bits_to_unit_f32)
}
