use glam::Vec2;

use super::hash::{hash_words, mix64};
use super::{SampleStream, bits_to_unit_f32};
use crate::lanes::Word;

/// Generator matrices (as 32 direction numbers each) of the first two Sobol dimensions,
/// which together form a (0, 2)-sequence in base 2. Derived at compile time from the
/// primitive polynomials and initial direction numbers of Joe and Kuo ("Constructing Sobol
/// sequences with better two-dimensional projections", SIAM J. Sci. Comput. 30(5), 2008):
/// dimension 0 is the van der Corput sequence, dimension 1 has polynomial x + 1 (degree 1,
/// a = 0) and m_1 = 1.
const DIRECTIONS: [[u32; 32]; 2] = [van_der_corput(), directions(1, 0, &[1])];

const fn van_der_corput() -> [u32; 32] {
    let mut v = [0u32; 32];
    let mut i = 0;
    while i < 32 {
        v[i] = 1u32 << (31 - i);
        i += 1;
    }
    v
}

/// Bratley and Fox's recurrence (ACM TOMS 14(1), 1988) for a dimension with primitive
/// polynomial of degree `s` and inner coefficients `a`, from initial values `m`.
const fn directions(s: usize, a: u32, m: &[u32]) -> [u32; 32] {
    let mut v = [0u32; 32];
    let mut i = 0;
    while i < 32 {
        v[i] = if i < s {
            m[i] << (31 - i)
        } else {
            let mut x = v[i - s] ^ (v[i - s] >> s);
            let mut k = 1;
            while k < s {
                if (a >> (s - 1 - k)) & 1 == 1 {
                    x ^= v[i - k];
                }
                k += 1;
            }
            x
        };
        i += 1;
    }
    v
}

/// Dimension 1's generator matrix applied to each byte of the index: entry [k][b] is the
/// XOR of the direction numbers of the set bits of byte value b at byte position k. Four
/// lookups replace a 32-step loop (the scrambled index uses all 32 bits). Built at compile
/// time, so a draw pays no lazy initialization check.
static DIMENSION_1_BYTES: [[u32; 256]; 4] = dimension_1_bytes(false);

/// The same with every entry bit-reversed: dimension 1 in the reversed-bit domain where
/// the Owen scramble works, which saves two bit reversals per draw.
pub(super) static DIMENSION_1_BYTES_REVERSED: [[u32; 256]; 4] = dimension_1_bytes(true);

const fn dimension_1_bytes(reversed: bool) -> [[u32; 256]; 4] {
    let v = &DIRECTIONS[1];
    let mut t = [[0u32; 256]; 4];
    let mut k = 0;
    while k < 4 {
        let mut b = 0;
        while b < 256 {
            let mut bit = 0;
            while bit < 8 {
                if (b >> bit) & 1 == 1 {
                    t[k][b] ^= v[8 * k + bit];
                }
                bit += 1;
            }
            if reversed {
                t[k][b] = t[k][b].reverse_bits();
            }
            b += 1;
        }
        k += 1;
    }
    t
}

/// The unscrambled Sobol point `index` in `dimension` (0 or 1), as 32 bits.
pub fn sobol_sample(index: u32, dimension: usize) -> u32 {
    if dimension == 0 {
        // Dimension 0's matrix is the bit reversal (van der Corput).
        return index.reverse_bits();
    }
    by_bytes(&DIMENSION_1_BYTES, index)
}

pub(super) fn by_bytes(t: &[[u32; 256]; 4], index: u32) -> u32 {
    t[0][(index & 0xff) as usize]
        ^ t[1][((index >> 8) & 0xff) as usize]
        ^ t[2][((index >> 16) & 0xff) as usize]
        ^ t[3][(index >> 24) as usize]
}

/// The straightforward definition, kept to test the fast path against.
#[cfg(test)]
fn sobol_sample_by_bits(index: u32, dimension: usize) -> u32 {
    let v = &DIRECTIONS[dimension.min(1)];
    (0..32)
        .filter(|i| (index >> i) & 1 == 1)
        .fold(0, |acc, i| acc ^ v[i])
}

/// Laine and Karras's hash-based Owen scramble of the bits above each bit, in Burley's
/// improved constants ("Practical hash-based Owen scrambling", JCGT 9(4), 2020, §4):
/// applied to a bit-reversed value it is a nested uniform scramble.
///
/// Written over [`Word`] so that one word and lanes of words (`SobolLanes`) run the same
/// code and agree to the bit.
#[inline]
pub(super) fn laine_karras_permutation<T: Word>(x: T, seed: T) -> T {
    let mut x = x.add(seed);
    for k in [0x6c50_b47c, 0xb82f_1e52, 0xc7af_e638, 0x8d22_f6e6] {
        x = x.xor(x.mul(T::splat(k)));
    }
    x
}

/// The pair hash of `dimension` under stream key `key` (see `SobolStream::scrambled_index`).
#[inline]
pub(super) fn pair_hash(key: u64, dimension: u64) -> u64 {
    mix64(key ^ dimension.wrapping_mul(0x9e37_79b9_7f4a_7c15))
}

/// The bit-reversed index of part `part` of `parts` of the sample whose bit-reversed
/// index is `reversed`: sample `index * parts + part` (see `SobolStream::split`).
#[inline]
pub(super) fn split_reversed_index(reversed: u32, part: u32, parts: u32) -> u32 {
    reversed
        .reverse_bits()
        .wrapping_mul(parts)
        .wrapping_add(part)
        .reverse_bits()
}

/// Owen-scrambled Sobol points, padded across dimensions (Burley 2020): each pair of
/// dimensions takes the first two Sobol dimensions at an index shuffled by its own hash,
/// each coordinate Owen-scrambled by its own hash. Every pair is therefore a (0, 2)-sequence
/// (any power-of-two prefix of a pixel's samples is a stratified net), pairs are
/// decorrelated from each other, and every value depends only on `(seed, pixel, sample,
/// dimension)`.
#[derive(Debug, Clone)]
pub struct SobolStream {
    pub(super) key: u64,
    /// The sample index with its bits reversed, as the scramble wants it.
    reversed_index: u32,
    dimension: u64,
}

impl SobolStream {
    /// The stream of sample `sample_index` (the first 2^32 samples of a pixel are distinct
    /// points; the index wraps beyond) of pixel `pixel` under `seed`.
    pub fn new(seed: u64, pixel: u64, sample_index: u64) -> Self {
        Self {
            key: hash_words(&[seed, pixel]),
            reversed_index: (sample_index as u32).reverse_bits(),
            dimension: 0,
        }
    }

    /// Jumps to `dimension`.
    pub fn set_dimension(&mut self, dimension: u64) {
        self.dimension = dimension;
    }

    /// Part `part` of `parts` of this sample (splitting one sample's later dimensions into
    /// several continuations): the stream of sample `index * parts + part` of the same
    /// pixel, at the same dimension. The parts of samples 0..n are samples 0..n * parts, so
    /// together they stay a stratified prefix in every pair of dimensions; one part of one
    /// is the stream itself.
    ///
    /// ```
    /// use prism_sampling::stream::{SampleStream, SobolStream};
    ///
    /// let stream = SobolStream::new(7, 42, 3);
    /// assert_eq!(stream.split(0, 1).next_2d(), stream.clone().next_2d());
    /// assert_eq!(stream.split(1, 4).next_2d(), SobolStream::new(7, 42, 13).next_2d());
    /// ```
    pub fn split(&self, part: u32, parts: u32) -> SobolStream {
        if parts == 1 && part == 0 {
            return self.clone();
        }
        Self {
            key: self.key,
            reversed_index: split_reversed_index(self.reversed_index, part, parts),
            dimension: self.dimension,
        }
    }

    /// The streams of a pixel's samples 0, 1, 2, ... in order: take as many as the
    /// pixel gets. Any power-of-two prefix is stratified in every pair of dimensions.
    ///
    /// ```
    /// use prism_sampling::stream::{SampleStream, SobolStream};
    ///
    /// let points: Vec<_> = SobolStream::pixel_samples(7, 42)
    ///     .take(16)
    ///     .map(|mut stream| stream.next_2d())
    ///     .collect();
    /// // 16 points of a (0, 2)-sequence: one in each cell of a 4 x 4 grid.
    /// let mut cells = [0u32; 16];
    /// for p in &points {
    ///     cells[(p.x * 4.0) as usize * 4 + (p.y * 4.0) as usize] += 1;
    /// }
    /// assert!(cells.iter().all(|&n| n == 1));
    /// // The same seed, pixel and sample give the same numbers, on any thread, any time.
    /// assert_eq!(SobolStream::new(7, 42, 3).next_2d(), points[3]);
    /// ```
    pub fn pixel_samples(seed: u64, pixel: u64) -> impl Iterator<Item = SobolStream> {
        (0..=u64::from(u32::MAX)).map(move |sample| Self::new(seed, pixel, sample))
    }

    /// The pair's hash for `dimension` and its Owen-scrambled sample index. The key is
    /// already a full-avalanche hash of (seed, pixel); one more mix with the dimension (an
    /// odd multiple, so distinct dimensions give distinct inputs) decorrelates the pairs.
    ///
    /// A nested uniform scramble of x is `reverse(LK(reverse(x)))` (Laine-Karras on the
    /// reversed bits); dimension 0 of the Sobol sequence is itself a bit reversal, so the
    /// draws below keep values reversed where they can and reverse only at the end.
    fn scrambled_index(&self, dimension: u64) -> (u64, u32) {
        let h = pair_hash(self.key, dimension);
        let index = laine_karras_permutation(self.reversed_index, h as u32).reverse_bits();
        (h, index)
    }

    /// The first coordinate of the pair at `dimension` (all that a 1D draw needs):
    /// scramble(sobol_0(index)) = reverse(LK(index)).
    fn first(&self, dimension: u64) -> u32 {
        let (h, index) = self.scrambled_index(dimension);
        laine_karras_permutation(index, (h >> 32) as u32).reverse_bits()
    }

    fn point(&self, dimension: u64) -> (u32, u32) {
        let (h, index) = self.scrambled_index(dimension);
        let x = laine_karras_permutation(index, (h >> 32) as u32);
        let y_reversed = by_bytes(&DIMENSION_1_BYTES_REVERSED, index);
        let y = laine_karras_permutation(y_reversed, mix64(h) as u32);
        // Both coordinates reversed by one 64-bit reversal (x86-64 has none for either
        // width: each is a byte swap and three mask-and-shift steps): the reversal of
        // x:y is reverse(y):reverse(x).
        let both = ((u64::from(x) << 32) | u64::from(y)).reverse_bits();
        (both as u32, (both >> 32) as u32)
    }
}

impl SampleStream for SobolStream {
    fn next_1d(&mut self) -> f32 {
        let x = self.first(self.dimension);
        self.dimension += 1;
        bits_to_unit_f32(x)
    }

    fn next_2d(&mut self) -> Vec2 {
        let (x, y) = self.point(self.dimension);
        self.dimension += 2;
        Vec2::new(bits_to_unit_f32(x), bits_to_unit_f32(y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first points of the 2D Sobol sequence in natural index order. (Joe and Kuo's
    /// generator prints them in Gray-code order, (0.5, 0.5), (0.75, 0.25), (0.25, 0.75), ...:
    /// the same sets for every power-of-two prefix.)
    #[test]
    fn fast_path_equals_the_definition() {
        let mut x = 0x1234_5678u32;
        for _ in 0..10_000 {
            x = x.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
            for d in 0..2 {
                assert_eq!(sobol_sample(x, d), sobol_sample_by_bits(x, d));
            }
        }
    }

    /// The scrambled draws, as their definition states them: Owen-scramble the index,
    /// take the Sobol point, Owen-scramble each coordinate (Burley 2020, listing 2).
    #[test]
    fn reversed_domain_draws_equal_the_definition() {
        let scramble =
            |x: u32, seed: u32| laine_karras_permutation(x.reverse_bits(), seed).reverse_bits();
        for (pixel, sample, dimension) in [
            (0, 0, 0u64),
            (7, 3, 2),
            (1 << 40, 12345, 9),
            (3, u64::from(u32::MAX), 30),
        ] {
            let stream = SobolStream::new(11, pixel, sample);
            let h = mix64(stream.key ^ dimension.wrapping_mul(0x9e37_79b9_7f4a_7c15));
            let index = scramble(sample as u32, h as u32);
            let x = scramble(sobol_sample(index, 0), (h >> 32) as u32);
            let y = scramble(sobol_sample(index, 1), mix64(h) as u32);
            assert_eq!(stream.point(dimension), (x, y));
            assert_eq!(stream.first(dimension), x);
        }
    }

    #[test]
    fn unscrambled_points_match_the_sequence() {
        let expected = [
            (0.0, 0.0),
            (0.5, 0.5),
            (0.25, 0.75),
            (0.75, 0.25),
            (0.125, 0.625),
            (0.625, 0.125),
        ];
        for (i, (x, y)) in expected.into_iter().enumerate() {
            let to_f = |b: u32| f64::from(b) / 4_294_967_296.0;
            assert_eq!(
                (
                    to_f(sobol_sample(i as u32, 0)),
                    to_f(sobol_sample(i as u32, 1))
                ),
                (x, y),
                "{i}"
            );
        }
    }
}
