//! Pixel reconstruction filters, applied by filter importance sampling (Ernst et al.,
//! "Filter importance sampling", RT 2006; *PBR* 4th ed. §8.8.3): each sample's film
//! position is offset from its pixel's centre by a draw from the filter, and the sample
//! adds to its own pixel with weight 1. Every pixel therefore stays an independent sum of
//! its own samples, which keeps renders deterministic across threads and sample ranges
//! mergeable; the price is that neighbouring pixels do not share samples.
//!
//! The filters are separable and non-negative, so the draw is two independent 1D draws
//! from the filter's 1D profile tabulated in 256 bins: the filter a render uses is that
//! tabulation (within 1e-4 of the analytic profile's integral over any bin).

use glam::Vec2;
use prism_sampling::distribution::PiecewiseConstant1D;

use crate::RenderError;

/// A reconstruction filter.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub enum Filter {
    /// The pixel's square: each sample counts in the pixel it falls in.
    #[default]
    Box,
    /// exp(-x^2 / (2 sigma^2)) minus its value at `radius`, clamped at 0.
    Gaussian {
        /// Half-width of the support, pixels.
        radius: f32,
        /// Standard deviation, pixels.
        sigma: f32,
    },
    /// The 4-term Blackman-Harris window over [-radius, radius] (Harris 1978).
    BlackmanHarris {
        /// Half-width of the support, pixels.
        radius: f32,
    },
    /// A tent: 1 - |x| / radius (Mitsuba's `tent`, pbrt's triangle filter).
    Tent {
        /// Half-width of the support, pixels.
        radius: f32,
    },
}

impl Filter {
    /// Names accepted by [`Filter::from_name`].
    pub const NAMES: &'static str = "box, gaussian, blackman-harris";

    /// `box`, `gaussian` (radius 1.5, sigma 0.5, as pbrt-v4) or `blackman-harris`
    /// (radius 2).
    pub fn from_name(name: &str) -> Result<Self, RenderError> {
        Ok(match name {
            "box" => Filter::Box,
            "gaussian" => Filter::Gaussian {
                radius: 1.5,
                sigma: 0.5,
            },
            "blackman-harris" => Filter::BlackmanHarris { radius: 2.0 },
            other => {
                return Err(RenderError::Setting(format!(
                    "unknown filter '{other}' (expected one of {})",
                    Self::NAMES
                )));
            }
        })
    }

    /// The filter's 1D profile at offset `x` (pixels).
    pub fn profile(&self, x: f64) -> f64 {
        match *self {
            Filter::Box => f64::from(u8::from(x.abs() <= 0.5)),
            Filter::Gaussian { radius, sigma } => {
                let (r, s) = (f64::from(radius), f64::from(sigma));
                let g = |x: f64| (-x * x / (2.0 * s * s)).exp();
                if x.abs() >= r {
                    0.0
                } else {
                    (g(x) - g(r)).max(0.0)
                }
            }
            Filter::BlackmanHarris { radius } => {
                let r = f64::from(radius);
                if x.abs() >= r {
                    return 0.0;
                }
                let t = std::f64::consts::PI * (x / r + 1.0);
                0.35875 - 0.48829 * t.cos() + 0.14128 * (2.0 * t).cos() - 0.01168 * (3.0 * t).cos()
            }
            Filter::Tent { radius } => (1.0 - x.abs() / f64::from(radius)).max(0.0),
        }
    }

    fn radius(&self) -> f32 {
        match *self {
            Filter::Box => 0.5,
            Filter::Gaussian { radius, .. }
            | Filter::BlackmanHarris { radius }
            | Filter::Tent { radius } => radius,
        }
    }
}

/// Draws film offsets from a filter.
#[derive(Debug, Clone)]
pub(crate) struct FilterSampler {
    /// None for the box filter (a uniform offset needs no table).
    profile: Option<PiecewiseConstant1D>,
}

const BINS: usize = 256;

impl FilterSampler {
    /// The filter's 1D profile, whose density weighs splats (None: the box filter).
    pub(crate) fn profile(&self) -> Option<&PiecewiseConstant1D> {
        self.profile.as_ref()
    }

    pub(crate) fn new(filter: Filter) -> Result<Self, RenderError> {
        let radius = filter.radius();
        if !(radius.is_finite() && radius > 0.0 && radius <= 16.0) {
            return Err(RenderError::Setting(format!(
                "filter radius {radius} must be in (0, 16] pixels"
            )));
        }
        if let Filter::Gaussian { sigma, .. } = filter
            && !(sigma.is_finite() && sigma > 0.0)
        {
            return Err(RenderError::Setting(format!(
                "Gaussian sigma {sigma} must be finite and > 0"
            )));
        }
        if filter == Filter::Box {
            return Ok(Self { profile: None });
        }
        let r = f64::from(radius);
        // Each bin holds the profile's mean over it (Simpson's rule).
        let values: Vec<f64> = (0..BINS)
            .map(|i| {
                let a = -r + 2.0 * r * i as f64 / BINS as f64;
                let b = a + 2.0 * r / BINS as f64;
                (filter.profile(a) + 4.0 * filter.profile(0.5 * (a + b)) + filter.profile(b)) / 6.0
            })
            .collect();
        let profile = PiecewiseConstant1D::new(&values, -r, r)
            .map_err(|e| RenderError::Setting(format!("filter: {e}")))?;
        Ok(Self {
            profile: Some(profile),
        })
    }

    /// The offset from the pixel centre for uniform `u`, pixels.
    pub(crate) fn offset(&self, u: Vec2) -> Vec2 {
        match &self.profile {
            None => u - Vec2::splat(0.5),
            Some(p) => Vec2::new(
                p.sample(f64::from(u.x)).value as f32,
                p.sample(f64::from(u.y)).value as f32,
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Offsets are distributed as the filter: their histogram matches the profile's mass
    /// per bin (chi-square), and their mean is 0 and variance the profile's.
    #[test]
    fn offsets_follow_the_filter() {
        for filter in [
            Filter::Box,
            Filter::from_name("gaussian").unwrap(),
            Filter::from_name("blackman-harris").unwrap(),
            Filter::Tent { radius: 1.0 },
        ] {
            let sampler = FilterSampler::new(filter).unwrap();
            let r = f64::from(filter.radius());
            let bins = 16;
            let n = 64_000;
            let mut counts = vec![0u64; bins];
            let mut state = 0x2545_F491_4F6C_DD1Du64;
            let mut next = || {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state >> 40) as f32 / (1u64 << 24) as f32
            };
            for _ in 0..n {
                let o = sampler.offset(Vec2::new(next(), next()));
                assert!(o.x.abs() <= filter.radius() && o.y.abs() <= filter.radius());
                let bin = (((f64::from(o.x) + r) / (2.0 * r)) * bins as f64) as usize;
                counts[bin.min(bins - 1)] += 1;
            }
            // Expected mass per bin by fine quadrature of the profile.
            let mass: Vec<f64> = (0..bins)
                .map(|i| {
                    let a = -r + 2.0 * r * i as f64 / bins as f64;
                    let h = 2.0 * r / bins as f64 / 200.0;
                    (0..200)
                        .map(|k| filter.profile(a + (k as f64 + 0.5) * h) * h)
                        .sum()
                })
                .collect();
            let total: f64 = mass.iter().sum();
            let expected: Vec<f64> = mass.iter().map(|m| m / total * n as f64).collect();
            let chi2: f64 = counts
                .iter()
                .zip(&expected)
                .filter(|(_, e)| **e > 5.0)
                .map(|(&c, e)| (c as f64 - e).powi(2) / e)
                .sum();
            // 16 bins: the 1e-6 quantile of chi-square with 15 degrees of freedom is ~52.
            assert!(chi2 < 52.0, "{filter:?}: chi2 {chi2} counts {counts:?}");
        }
    }

    #[test]
    fn bad_filters_are_errors() {
        assert!(Filter::from_name("lanczos").is_err());
        assert!(
            FilterSampler::new(Filter::Gaussian {
                radius: 1.0,
                sigma: 0.0
            })
            .is_err()
        );
        assert!(FilterSampler::new(Filter::BlackmanHarris { radius: f32::NAN }).is_err());
    }
}
