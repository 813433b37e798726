use super::{PiecewiseConstant1D, clamp_unit};
use crate::error::{SamplingError, validate};

/// A piecewise-linear density over `[min, max]` through `n >= 2` equally spaced
/// non-negative values: a segment is chosen in proportion to its trapezoid area, then the
/// linear density inside it is inverted in closed form (*PBR* 4th ed., §A.4.3).
#[derive(Debug, Clone, PartialEq)]
pub struct PiecewiseLinear1D {
    values: Vec<f64>,
    segments: PiecewiseConstant1D,
    integral: f64,
    min: f64,
    max: f64,
}

impl PiecewiseLinear1D {
    /// A density proportional to the linear interpolation of `values` (finite, >= 0, at
    /// least two, not all 0) at equally spaced points from `min` to `max`.
    pub fn new(values: &[f64], min: f64, max: f64) -> Result<Self, SamplingError> {
        validate(values)?;
        if values.len() < 2 {
            return Err(SamplingError::InvalidParameter(
                "a piecewise-linear function needs at least 2 values".into(),
            ));
        }
        let areas: Vec<f64> = values.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
        let segments = PiecewiseConstant1D::new(&areas, min, max)?;
        Ok(Self {
            values: values.to_vec(),
            integral: segments.integral(),
            segments,
            min,
            max,
        })
    }

    /// The integral of the (unnormalized) function.
    pub fn integral(&self) -> f64 {
        self.integral
    }

    /// A point with density proportional to the function, and that density.
    pub fn sample(&self, u: f64) -> (f64, f64) {
        let u = clamp_unit(u);
        let s = self.segments.sample(u);
        let (c0, c1) = (self.segments.cdf_at(s.bin), self.segments.cdf_at(s.bin + 1));
        let v = if c1 > c0 {
            ((u - c0) / (c1 - c0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (a, b) = (self.values[s.bin], self.values[s.bin + 1]);
        let t = sample_linear(v, a, b);
        let width = (self.max - self.min) / (self.values.len() - 1) as f64;
        let x = (self.min + (s.bin as f64 + t) * width).min(self.max);
        (x, self.pdf(x))
    }

    /// The density at `x` (0 outside `[min, max]`).
    pub fn pdf(&self, x: f64) -> f64 {
        if !(x >= self.min && x <= self.max) {
            return 0.0;
        }
        let segments = self.values.len() - 1;
        let position = (x - self.min) / (self.max - self.min) * segments as f64;
        let i = (position as usize).min(segments - 1);
        let t = position - i as f64;
        ((1.0 - t) * self.values[i] + t * self.values[i + 1]) / self.integral
    }
}

/// Inverts the CDF of the density proportional to `(1 - t) a + t b` on [0, 1]:
/// t = u (a + b) / (a + sqrt((1 - u) a^2 + u b^2)), which has no cancellation when
/// a ~ b and is exact at u = 0 and u = 1.
fn sample_linear(u: f64, a: f64, b: f64) -> f64 {
    if u == 0.0 && a == 0.0 {
        return 0.0;
    }
    let denominator = a + ((1.0 - u) * a * a + u * b * b).sqrt();
    if denominator == 0.0 {
        return u;
    }
    (u * (a + b) / denominator).clamp(0.0, 1.0)
}
