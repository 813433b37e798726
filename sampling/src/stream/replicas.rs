//! Independent replicates of a pixel's samples: the way to measure a randomized
//! quasi-Monte Carlo estimate's error from the estimate itself.
//!
//! The means of scrambled Sobol points err less than means of independent samples, by a
//! factor that depends on the integrand, so the spread of a pixel's samples overstates
//! its error. Splitting the samples into R interleaved groups, each an independently
//! scrambled Sobol sequence, makes the groups' means independent and unbiased: their
//! spread is then an unbiased estimate of the error of their average (Owen, "Monte Carlo
//! theory, methods and examples", 2013, §17.4 "Randomized quasi-Monte Carlo",
//! replicates; L'Ecuyer and Lemieux, "Recent advances in randomized quasi-Monte Carlo
//! methods", 2002, §2). Each group is a prefix of its own sequence, so it keeps the
//! stratification of n / R points.

use super::SobolStream;
use super::hash::hash_words;

/// How a pixel's samples are split into independently scrambled groups: sample `s` is
/// point `s / count` of group `s % count`. One group is the plain stream.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Replicas {
    count: u64,
}

impl Replicas {
    /// One group: sample `s` is `SobolStream::new(seed, pixel, s)`.
    pub const ONE: Replicas = Replicas { count: 1 };

    /// `count` groups (at least one).
    pub const fn new(count: u64) -> Self {
        Replicas {
            count: if count == 0 { 1 } else { count },
        }
    }

    /// How many groups.
    pub const fn count(self) -> u64 {
        self.count
    }

    /// The group of sample `sample`.
    #[inline]
    pub const fn group(self, sample: u64) -> u64 {
        sample % self.count
    }

    /// The stream of sample `sample` of `pixel` under `seed`.
    ///
    /// ```
    /// use prism_sampling::stream::{Replicas, SampleStream, SobolStream};
    ///
    /// // One group is the plain stream.
    /// assert_eq!(
    ///     Replicas::ONE.stream(7, 42, 5).next_2d(),
    ///     SobolStream::new(7, 42, 5).next_2d()
    /// );
    /// // With two, even samples and odd samples are two differently scrambled sequences.
    /// let two = Replicas::new(2);
    /// assert_ne!(two.stream(7, 42, 0).next_2d(), two.stream(7, 42, 1).next_2d());
    /// ```
    #[inline]
    pub fn stream(self, seed: u64, pixel: u64, sample: u64) -> SobolStream {
        if self.count == 1 {
            return SobolStream::new(seed, pixel, sample);
        }
        const GROUP: u64 = 0x7265_706c_6963_6100;
        let group_seed = hash_words(&[seed, GROUP ^ self.group(sample)]);
        SobolStream::new(group_seed, pixel, sample / self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stream::SampleStream;

    /// Each group's first 16 samples are a (0, 2)-net (one point per cell of a 4 x 4
    /// grid) in the first pair of dimensions and in a later one.
    #[test]
    fn each_group_is_a_stratified_prefix() {
        let replicas = Replicas::new(2);
        for group in 0..2 {
            for dimension in [0, 6] {
                let mut cells = [0u32; 16];
                for i in 0..16 {
                    let mut stream = replicas.stream(3, 11, 2 * i + group);
                    stream.set_dimension(dimension);
                    let p = stream.next_2d();
                    cells[(p.x * 4.0) as usize * 4 + (p.y * 4.0) as usize] += 1;
                }
                assert!(
                    cells.iter().all(|&n| n == 1),
                    "{group} {dimension}: {cells:?}"
                );
            }
        }
    }

    /// The groups' scrambles are unrelated: the means of a smooth integrand over each
    /// group's 16 points, over many pixels, have a correlation near 0 (a shared scramble
    /// would give 1; a paired, antithetic one -1).
    #[test]
    fn groups_are_uncorrelated() {
        let replicas = Replicas::new(2);
        let f = |p: glam::Vec2| (p.x * 5.0).sin() * (p.y * 3.0).cos() + p.x * p.y;
        let pixels = 4000u64;
        let mut pairs = Vec::new();
        for pixel in 0..pixels {
            let mean = |group: u64| {
                (0..16)
                    .map(|i| f64::from(f(replicas.stream(1, pixel, 2 * i + group).next_2d())))
                    .sum::<f64>()
                    / 16.0
            };
            pairs.push((mean(0), mean(1)));
        }
        let n = pairs.len() as f64;
        let (ma, mb) = pairs
            .iter()
            .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
        let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
        for (a, b) in &pairs {
            sab += (a - ma) * (b - mb);
            saa += (a - ma) * (a - ma);
            sbb += (b - mb) * (b - mb);
        }
        let correlation = sab / (saa * sbb).sqrt();
        // Standard error of a correlation of 0 over 4000 pairs: 1/sqrt(4000) = 0.016.
        assert!(correlation.abs() < 0.06, "correlation {correlation}");
    }

    #[test]
    fn zero_groups_is_one() {
        assert_eq!(Replicas::new(0), Replicas::ONE);
        assert_eq!(Replicas::new(3).group(7), 1);
    }
}
