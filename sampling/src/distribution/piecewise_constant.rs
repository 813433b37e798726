use super::clamp_unit;
use crate::error::{SamplingError, validate};

/// A sample of a [`PiecewiseConstant1D`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample1D {
    /// The sampled point in the distribution's domain.
    pub value: f64,
    /// Its probability density (> 0: zero-valued bins are never sampled).
    pub pdf: f64,
    /// The bin it fell in.
    pub bin: usize,
}

/// A piecewise-constant density over `[min, max)` proportional to `n` non-negative bin
/// values, sampled by inverting its CDF (Pharr, Jakob and Humphreys, *PBR* 4th ed.,
/// §A.4.2).
///
/// The CDF is kept in `f64` so a million bins of very different weight keep their
/// resolution; bins with value 0 have probability exactly 0 and are never returned.
#[derive(Debug, Clone, PartialEq)]
pub struct PiecewiseConstant1D {
    values: Vec<f64>,
    cdf: Vec<f64>,
    integral: f64,
    min: f64,
    max: f64,
    first_nonzero: usize,
    last_nonzero: usize,
    /// A guide table (the cutpoint method: Chen and Asau, "On generating random variates
    /// from an empirical distribution", AIIE Transactions 6(2), 1974): entry j is the last
    /// i with cdf[i] <= j / n, so the bin of any u in [j / n, (j + 1) / n) lies between
    /// entries j and j + 1, usually one or two CDF values apart. A search of the whole CDF
    /// of a large distribution (an environment map's row of a thousand cells) touched a
    /// dozen cache lines; the guide's range touches one or two, and gives the same bin.
    guide: Vec<u32>,
}

impl PiecewiseConstant1D {
    /// A distribution proportional to `values` (finite, >= 0, not all 0) over
    /// `[min, max)` (finite, `min < max`).
    ///
    /// ```
    /// use prism_sampling::distribution::PiecewiseConstant1D;
    ///
    /// // Three bins over [0, 3) weighted 1 : 0 : 3.
    /// let d = PiecewiseConstant1D::new(&[1.0, 0.0, 3.0], 0.0, 3.0)?;
    /// let s = d.sample(0.5);
    /// assert_eq!(s.bin, 2); // the empty bin is never chosen
    /// assert!((s.pdf - 0.75).abs() < 1e-12 && (d.pdf(s.value) - s.pdf).abs() < 1e-12);
    /// assert!(PiecewiseConstant1D::new(&[0.0, 0.0], 0.0, 1.0).is_err());
    /// # Ok::<(), prism_sampling::SamplingError>(())
    /// ```
    pub fn new(values: &[f64], min: f64, max: f64) -> Result<Self, SamplingError> {
        validate(values)?;
        if !(min.is_finite() && max.is_finite() && min < max) {
            return Err(SamplingError::InvalidParameter(format!(
                "domain [{min}, {max}) must be finite and non-empty"
            )));
        }
        let n = values.len();
        let width = (max - min) / n as f64;
        let mut cdf = Vec::with_capacity(n + 1);
        cdf.push(0.0);
        let mut running = 0.0;
        for v in values {
            running += v * width;
            cdf.push(running);
        }
        let integral = running;
        if !(integral > 0.0 && integral.is_finite()) {
            return Err(if integral == 0.0 {
                SamplingError::AllZero
            } else {
                SamplingError::InvalidParameter(format!("the integral {integral} is not finite"))
            });
        }
        for c in &mut cdf {
            *c /= integral;
        }
        cdf[n] = 1.0;
        let guide = (0..=n)
            .map(|j| {
                let u = j as f64 / n as f64;
                (cdf.partition_point(|&c| c <= u) - 1) as u32
            })
            .collect();
        let first_nonzero = values.iter().position(|&v| v > 0.0).unwrap_or(0);
        let last_nonzero = values.iter().rposition(|&v| v > 0.0).unwrap_or(n - 1);
        Ok(Self {
            values: values.to_vec(),
            cdf,
            integral,
            min,
            max,
            first_nonzero,
            last_nonzero,
            guide,
        })
    }

    /// Number of bins.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Always false: a distribution has at least one bin.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The integral of the (unnormalized) function over the domain.
    pub fn integral(&self) -> f64 {
        self.integral
    }

    /// The domain `[min, max)`.
    pub fn domain(&self) -> (f64, f64) {
        (self.min, self.max)
    }

    /// The unnormalized bin values.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The probability of bin `i` (0 outside).
    pub fn bin_probability(&self, i: usize) -> f64 {
        if i < self.len() {
            self.cdf[i + 1] - self.cdf[i]
        } else {
            0.0
        }
    }

    /// The bin [`PiecewiseConstant1D::sample`] picks for `u`, by a search of the whole CDF
    /// (what the guide table must agree with).
    #[doc(hidden)]
    pub fn bin_by_search(&self, u: f64) -> usize {
        let u = clamp_unit(u);
        (self.cdf.partition_point(|&c| c <= u) - 1).clamp(self.first_nonzero, self.last_nonzero)
    }

    /// The CDF at the start of bin `i` (`i == len()` gives 1).
    pub(crate) fn cdf_at(&self, i: usize) -> f64 {
        self.cdf[i.min(self.len())]
    }

    /// A point with density proportional to the function. `u` is clamped into [0, 1).
    pub fn sample(&self, u: f64) -> Sample1D {
        let u = clamp_unit(u);
        // The bin with cdf[i] <= u < cdf[i + 1]; such a bin has positive probability. The
        // clamp covers u beyond the last positive bin's end through rounding.
        // The last i with cdf[i] <= u lies between the guide's entries around u.
        let j = ((u * self.len() as f64) as usize).min(self.len() - 1);
        let (lo, hi) = (self.guide[j] as usize, self.guide[j + 1] as usize);
        let after = self.cdf[lo + 1..=hi.max(lo)].partition_point(|&c| c <= u);
        // Rounding of u * n can put u a hair outside [j / n, (j + 1) / n): then search all.
        let inside = self.cdf[lo] <= u && self.cdf.get(hi + 1).is_none_or(|&c| c > u);
        let last = if inside {
            lo + after
        } else {
            self.cdf.partition_point(|&c| c <= u) - 1
        };
        let bin = last.clamp(self.first_nonzero, self.last_nonzero);
        let (c0, c1) = (self.cdf[bin], self.cdf[bin + 1]);
        let t = if c1 > c0 {
            ((u - c0) / (c1 - c0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let width = (self.max - self.min) / self.len() as f64;
        // Keep the point inside its bin's half-open interval, so that `pdf(value)` is the
        // density of the bin that was sampled even at t = 1 or after rounding.
        let (start, end) = (
            self.min + bin as f64 * width,
            self.min + (bin + 1) as f64 * width,
        );
        let value = (self.min + (bin as f64 + t) * width).clamp(start, end.next_down().max(start));
        Sample1D {
            value,
            pdf: self.values[bin] / self.integral,
            bin,
        }
    }

    /// The density at `x` (0 outside the domain and for NaN).
    pub fn pdf(&self, x: f64) -> f64 {
        if !(x >= self.min && x < self.max) {
            return 0.0;
        }
        let bin = (((x - self.min) / (self.max - self.min) * self.len() as f64) as u32 as usize)
            .min(self.len() - 1);
        self.values[bin] / self.integral
    }

    /// The CDF at `x`: the `u` that [`PiecewiseConstant1D::sample`] maps to `x` (for `x`
    /// inside a bin of positive probability). 0 below the domain, 1 above, 0 for NaN.
    pub fn invert(&self, x: f64) -> f64 {
        if x.is_nan() || x <= self.min {
            return 0.0;
        }
        if x >= self.max {
            return 1.0;
        }
        let position = (x - self.min) / (self.max - self.min) * self.len() as f64;
        let bin = (position as u32 as usize).min(self.len() - 1);
        let t = position - bin as f64;
        self.cdf[bin] + t * (self.cdf[bin + 1] - self.cdf[bin])
    }
}
