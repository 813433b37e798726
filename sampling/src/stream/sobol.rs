use std::sync::LazyLock;

use glam::Vec2;

use super::hash::hash_words;
use super::{SampleStream, bits_to_unit_f32};

/// Generator matrices (as 32 direction numbers each) of the first two Sobol dimensions,
/// which together form a (0, 2)-sequence in base 2. Derived in code from the primitive
/// polynomials and initial direction numbers of Joe and Kuo ("Constructing Sobol sequences
/// with better two-dimensional projections", SIAM J. Sci. Comput. 30(5), 2008): dimension
/// 0 is the van der Corput sequence, dimension 1 has polynomial x + 1 (degree 1, a = 0)
/// and m_1 = 1.
static DIRECTIONS: LazyLock<[[u32; 32]; 2]> =
    LazyLock::new(|| [van_der_corput(), directions(1, 0, &[1])]);

fn van_der_corput() -> [u32; 32] {
    std::array::from_fn(|i| 1u32 << (31 - i))
}

/// Bratley and Fox's recurrence (ACM TOMS 14(1), 1988) for a dimension with primitive
/// polynomial of degree `s` and inner coefficients `a`, from initial values `m`.
fn directions(s: usize, a: u32, m: &[u32]) -> [u32; 32] {
    let mut v = [0u32; 32];
    for i in 0..32 {
        v[i] = if i < s {
            m[i] << (31 - i)
        } else {
            let mut x = v[i - s] ^ (v[i - s] >> s);
            for k in 1..s {
                if (a >> (s - 1 - k)) & 1 == 1 {
                    x ^= v[i - k];
                }
            }
            x
        };
    }
    v
}

/// Dimension 1's generator matrix applied to each byte of the index: entry [k][b] is the
/// XOR of the direction numbers of the set bits of byte value b at byte position k. Four
/// lookups replace a 32-step loop (the scrambled index uses all 32 bits).
static DIMENSION_1_BYTES: LazyLock<[[u32; 256]; 4]> = LazyLock::new(|| {
    let v = &DIRECTIONS[1];
    std::array::from_fn(|k| {
        std::array::from_fn(|b| {
            (0..8)
                .filter(|bit| (b >> bit) & 1 == 1)
                .fold(0, |acc, bit| acc ^ v[8 * k + bit])
        })
    })
});

/// The unscrambled Sobol point `index` in `dimension` (0 or 1), as 32 bits.
pub fn sobol_sample(index: u32, dimension: usize) -> u32 {
    if dimension == 0 {
        // Dimension 0's matrix is the bit reversal (van der Corput).
        return index.reverse_bits();
    }
    let t = &*DIMENSION_1_BYTES;
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
fn laine_karras_permutation(mut x: u32, seed: u32) -> u32 {
    x = x.wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x
}

fn nested_uniform_scramble(x: u32, seed: u32) -> u32 {
    laine_karras_permutation(x.reverse_bits(), seed).reverse_bits()
}

/// Owen-scrambled Sobol points, padded across dimensions (Burley 2020): each pair of
/// dimensions takes the first two Sobol dimensions at an index shuffled by its own hash,
/// each coordinate Owen-scrambled by its own hash. Every pair is therefore a (0, 2)-sequence
/// (any power-of-two prefix of a pixel's samples is a stratified net), pairs are
/// decorrelated from each other, and every value depends only on `(seed, pixel, sample,
/// dimension)`.
#[derive(Debug, Clone)]
pub struct SobolStream {
    key: u64,
    sample_index: u32,
    dimension: u64,
}

impl SobolStream {
    /// The stream of sample `sample_index` (the first 2^32 samples of a pixel are distinct
    /// points; the index wraps beyond) of pixel `pixel` under `seed`.
    pub fn new(seed: u64, pixel: u64, sample_index: u64) -> Self {
        Self {
            key: hash_words(&[seed, pixel]),
            sample_index: sample_index as u32,
            dimension: 0,
        }
    }

    /// Jumps to `dimension`.
    pub fn set_dimension(&mut self, dimension: u64) {
        self.dimension = dimension;
    }

    /// The scrambled sample index and the pair's hash for `dimension`.
    fn scrambled_index(&self, dimension: u64) -> (u32, u64) {
        let h = hash_words(&[self.key, dimension]);
        (nested_uniform_scramble(self.sample_index, h as u32), h)
    }

    /// The first coordinate of the pair at `dimension` (all that a 1D draw needs).
    fn first(&self, dimension: u64) -> u32 {
        let (index, h) = self.scrambled_index(dimension);
        nested_uniform_scramble(sobol_sample(index, 0), (h >> 32) as u32)
    }

    fn point(&self, dimension: u64) -> (u32, u32) {
        let (index, h) = self.scrambled_index(dimension);
        let x = nested_uniform_scramble(sobol_sample(index, 0), (h >> 32) as u32);
        let y = nested_uniform_scramble(sobol_sample(index, 1), hash_words(&[h]) as u32);
        (x, y)
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
