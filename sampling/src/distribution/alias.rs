use super::clamp_unit;
use crate::error::{SamplingError, validate};

/// Walker's alias method for O(1) discrete sampling (A. J. Walker, ACM TOMS 3(3), 1977),
/// built with Vose's numerically stable construction (M. D. Vose, IEEE TSE 17(9), 1991).
/// Use it to choose among many lights in proportion to their power.
#[derive(Debug, Clone, PartialEq)]
pub struct AliasTable {
    /// Probability of keeping bin i rather than jumping to its alias.
    keep: Vec<f64>,
    alias: Vec<usize>,
    pmf: Vec<f64>,
}

impl AliasTable {
    /// A table choosing index `i` with probability `weights[i] / sum(weights)`; weights
    /// finite, >= 0, not all 0.
    ///
    /// ```
    /// use prism_sampling::distribution::AliasTable;
    ///
    /// let lights = AliasTable::new(&[10.0, 30.0, 60.0])?;
    /// assert!((lights.pmf(2) - 0.6).abs() < 1e-12);
    /// let (index, pmf) = lights.sample(0.99);
    /// assert_eq!(pmf, lights.pmf(index));
    /// # Ok::<(), prism_sampling::SamplingError>(())
    /// ```
    pub fn new(weights: &[f64]) -> Result<Self, SamplingError> {
        validate(weights)?;
        let sum: f64 = weights.iter().sum();
        if sum == 0.0 {
            return Err(SamplingError::AllZero);
        }
        if !sum.is_finite() {
            return Err(SamplingError::InvalidParameter(
                "weights sum to infinity".into(),
            ));
        }
        let n = weights.len();
        let pmf: Vec<f64> = weights.iter().map(|w| w / sum).collect();
        let mut scaled: Vec<f64> = pmf.iter().map(|p| p * n as f64).collect();
        let mut keep = vec![1.0; n];
        let mut alias: Vec<usize> = (0..n).collect();
        let (mut small, mut large): (Vec<usize>, Vec<usize>) =
            (0..n).partition(|&i| scaled[i] < 1.0);
        while let (Some(s), Some(&l)) = (small.pop(), large.last()) {
            keep[s] = scaled[s];
            alias[s] = l;
            scaled[l] = (scaled[l] + scaled[s]) - 1.0;
            if scaled[l] < 1.0 {
                large.pop();
                small.push(l);
            }
        }
        // Whatever remains is 1 up to rounding: keep it entirely. A zero-weight bin left
        // here (only through rounding) must still never be returned.
        for i in large.into_iter().chain(small) {
            keep[i] = if pmf[i] > 0.0 { 1.0 } else { 0.0 };
            if pmf[i] == 0.0 {
                alias[i] = pmf.iter().position(|&p| p > 0.0).unwrap_or(i);
            }
        }
        Ok(Self { keep, alias, pmf })
    }

    /// Number of entries.
    pub fn len(&self) -> usize {
        self.pmf.len()
    }

    /// Always false: a table has at least one entry.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// An index chosen with probability proportional to its weight, and that probability.
    /// `u` is clamped into [0, 1); one uniform number suffices (its fractional part after
    /// choosing the column decides between the column and its alias).
    pub fn sample(&self, u: f64) -> (usize, f64) {
        let (index, pmf, _) = self.sample_remapped(u);
        (index, pmf)
    }

    /// [`AliasTable::sample`], and what is left of `u`: its position within the part of
    /// [0, 1) that chose the index, again uniform in [0, 1). One number can then choose
    /// an entry and sample within it (a light and a point on it), which keeps the
    /// stratification of a 2D sample across the whole set where two numbers would break
    /// it between entries.
    pub fn sample_remapped(&self, u: f64) -> (usize, f64, f64) {
        let scaled = clamp_unit(u) * self.len() as f64;
        // Through u32: the saturating float-to-usize cast costs a dozen instructions on
        // baseline x86-64, to u32 a few; tables never hold 2^32 entries.
        let column = (scaled as u32 as usize).min(self.len() - 1);
        let fraction = scaled - column as f64;
        let keep = self.keep[column];
        let (index, rest) = if fraction < keep {
            (column, fraction / keep)
        } else {
            (self.alias[column], (fraction - keep) / (1.0 - keep))
        };
        (index, self.pmf[index], clamp_unit(rest))
    }

    /// The probability of `index` (0 outside).
    pub fn pmf(&self, index: usize) -> f64 {
        self.pmf.get(index).copied().unwrap_or(0.0)
    }
}
