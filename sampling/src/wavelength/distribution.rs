use super::WavelengthRange;
use crate::distribution::{PiecewiseConstant1D, clamp_unit, density_f32};
use crate::error::SamplingError;
use crate::lanes_exp::exp_lane;

/// Centre of the visible-importance density, nm (Radziszewski, Boryczko and Alda, "An
/// improved technique for full spectral rendering", WSCG 2009; used by pbrt-v4 and
/// Mitsuba 3).
pub const VISIBLE_CENTER_NM: f64 = 538.0;
/// Sharpness k of the visible-importance density 1 / cosh^2(k (lambda - 538)), per nm.
pub const VISIBLE_SHARPNESS: f64 = 0.0072;

/// A density over wavelength from which packages are drawn.
#[derive(Debug, Clone, PartialEq)]
pub enum WavelengthDistribution {
    /// Uniform over the range.
    Uniform(WavelengthRange),
    /// p(lambda) proportional to 1 / cosh^2(k (lambda - 538)) over the range. With
    /// t(lambda) = tanh(k (lambda - 538)) the CDF is (t(lambda) - t(min)) / (t(max) -
    /// t(min)), so the normalization k / (t(max) - t(min)) and the inverse
    /// lambda = 538 + atanh(lerp(u, t(min), t(max))) / k are exact for any range (for
    /// 360-830 nm the normalization is pbrt-v4's 0.0039398042; a test derives it).
    Visible {
        /// The range.
        range: WavelengthRange,
        /// tanh(k (min - 538)).
        t_min: f64,
        /// tanh(k (max - 538)).
        t_max: f64,
    },
    /// A histogram over the range: camera response, light SPD, or a defensive mixture.
    Tabulated {
        /// The range.
        range: WavelengthRange,
        /// The histogram.
        histogram: PiecewiseConstant1D,
    },
}

impl WavelengthDistribution {
    /// Uniform over `range`.
    pub fn uniform(range: WavelengthRange) -> Self {
        WavelengthDistribution::Uniform(range)
    }

    /// The visible-importance density over `range`.
    pub fn visible(range: WavelengthRange) -> Self {
        let t = |l: f32| ((f64::from(l) - VISIBLE_CENTER_NM) * VISIBLE_SHARPNESS).tanh();
        WavelengthDistribution::Visible {
            range,
            t_min: t(range.min()),
            t_max: t(range.max()),
        }
    }

    /// A histogram of `bins` bins over `range` proportional to `importance` evaluated at
    /// each bin's centre (finite, >= 0, not zero everywhere).
    pub fn tabulated(
        range: WavelengthRange,
        bins: usize,
        importance: impl Fn(f64) -> f64,
    ) -> Result<Self, SamplingError> {
        if bins == 0 {
            return Err(SamplingError::Empty);
        }
        let (lo, hi) = (f64::from(range.min()), f64::from(range.max()));
        let width = (hi - lo) / bins as f64;
        let values: Vec<f64> = (0..bins)
            .map(|i| importance(lo + (i as f64 + 0.5) * width))
            .collect();
        Ok(WavelengthDistribution::Tabulated {
            range,
            histogram: PiecewiseConstant1D::new(&values, lo, hi)?,
        })
    }

    /// Camera-response sampling (camera wavelength sampling by
    /// the camera's response): a histogram of the sum of the response curves, each normalized to unit
    /// area over the range so that every channel gets the same share of samples. Pass the
    /// CIE colour matching functions as curves for an XYZ (human) observer, or measured
    /// camera responses for a camera.
    pub fn response(
        range: WavelengthRange,
        bins: usize,
        curves: &[&dyn Fn(f64) -> f64],
    ) -> Result<Self, SamplingError> {
        let areas: Vec<f64> = curves.iter().map(|c| bin_area(range, bins, c)).collect();
        if let Some(i) = areas.iter().position(|a| !(a.is_finite() && *a >= 0.0)) {
            return Err(SamplingError::InvalidParameter(format!(
                "response curve {i} has area {} over the range",
                areas[i]
            )));
        }
        Self::tabulated(range, bins, |l| {
            curves
                .iter()
                .zip(&areas)
                .filter(|(_, a)| **a > 0.0)
                .map(|(c, a)| c(l).max(0.0) / a)
                .sum()
        })
    }

    /// Light-SPD sampling: a histogram of `response(lambda) * sum_i spd_i(lambda)`, where
    /// each `spd_i` is the absolute spectral power (or average radiance times area) of a
    /// light, so that lights keep their relative power. Normalizing each light's SPD on
    /// its own would be wrong: a dim light would get as many
    /// samples as the sun. A spatially varying light passes its average SPD.
    ///
    /// The result is mixed with the response density as a defence,
    /// p = (1 - `defensive`) p_spd + `defensive` p_response, so that no wavelength the
    /// camera sees has zero density (`defensive` in (0, 1]; 0.1 is a good default).
    pub fn light_spd(
        range: WavelengthRange,
        bins: usize,
        lights: &[&dyn Fn(f64) -> f64],
        response: &dyn Fn(f64) -> f64,
        defensive: f64,
    ) -> Result<Self, SamplingError> {
        if !(defensive > 0.0 && defensive <= 1.0) {
            return Err(SamplingError::InvalidParameter(format!(
                "defensive mixture weight {defensive} must be in (0, 1]"
            )));
        }
        let spd = |l: f64| response(l).max(0.0) * lights.iter().map(|s| s(l).max(0.0)).sum::<f64>();
        let spd_area = bin_area(range, bins, &spd);
        let response_area = bin_area(range, bins, &|l| response(l).max(0.0));
        if !(response_area > 0.0 && response_area.is_finite() && spd_area.is_finite()) {
            return Err(SamplingError::InvalidParameter(
                "the response is zero over the range, or a light's power is not finite".into(),
            ));
        }
        let spd_weight = if spd_area > 0.0 {
            (1.0 - defensive) / spd_area
        } else {
            0.0
        };
        let response_weight = if spd_area > 0.0 { defensive } else { 1.0 } / response_area;
        Self::tabulated(range, bins, |l| {
            spd_weight * spd(l) + response_weight * response(l).max(0.0)
        })
    }

    /// The range.
    pub fn range(&self) -> WavelengthRange {
        match self {
            WavelengthDistribution::Uniform(r) => *r,
            WavelengthDistribution::Visible { range, .. }
            | WavelengthDistribution::Tabulated { range, .. } => *range,
        }
    }

    /// A wavelength (nm) with this density; `u` is clamped into [0, 1). The result lies
    /// in the range and has positive density.
    pub fn sample(&self, u: f64) -> f64 {
        let u = clamp_unit(u);
        let range = self.range();
        let (lo, hi) = (f64::from(range.min()), f64::from(range.max()));
        let lambda = match self {
            WavelengthDistribution::Uniform(_) => lo + u * (hi - lo),
            WavelengthDistribution::Visible { t_min, t_max, .. } => {
                VISIBLE_CENTER_NM + (t_min + u * (t_max - t_min)).atanh() / VISIBLE_SHARPNESS
            }
            WavelengthDistribution::Tabulated { histogram, .. } => histogram.sample(u).value,
        };
        lambda.clamp(lo, hi)
    }

    /// The density at `lambda`, per nm (0 outside the range).
    pub fn pdf(&self, lambda: f64) -> f64 {
        let range = self.range();
        let (lo, hi) = (f64::from(range.min()), f64::from(range.max()));
        if !(lambda >= lo && lambda <= hi) {
            return 0.0;
        }
        match self {
            WavelengthDistribution::Uniform(_) => 1.0 / (hi - lo),
            WavelengthDistribution::Visible { t_min, t_max, .. } => {
                // 1 / cosh^2 x = 4 e / (1 + e)^2 with e = exp(-2 |x|) <= 1: one exp, no
                // cancellation, no overflow (cosh costs an exp and more, per lane per path).
                let e = (-2.0 * ((lambda - VISIBLE_CENTER_NM) * VISIBLE_SHARPNESS).abs()).exp();
                VISIBLE_SHARPNESS * 4.0 * e / ((t_max - t_min) * (1.0 + e) * (1.0 + e))
            }
            // The histogram's domain is half-open; its last point belongs to the last bin.
            WavelengthDistribution::Tabulated { histogram, .. } => {
                histogram.pdf(lambda.min(hi - (hi - lo) * 1e-12))
            }
        }
    }

    /// The densities at each lane's `lambda` as f32, per nm (0 outside the range): what
    /// [`WavelengthDistribution::pdf`] gives, to within 1e-6 relative, and never 0 inside
    /// the range where `pdf` is positive. The visible density is computed on all lanes at
    /// once, in f32 (a package evaluates it per lane per path).
    pub fn pdf_lanes<const N: usize>(&self, lambda: &[f32; N]) -> [f32; N] {
        match self {
            WavelengthDistribution::Visible {
                range,
                t_min,
                t_max,
            } => {
                let scale = (VISIBLE_SHARPNESS * 4.0 / (t_max - t_min)) as f32;
                let mut density = [0.0; N];
                visible_density(lambda, &mut density, scale, *range);
                density
            }
            _ => lambda.map(|l| density_f32(self.pdf(f64::from(l)))),
        }
    }

    /// The CDF at `lambda`: the `u` that [`WavelengthDistribution::sample`] maps to it.
    pub fn cdf(&self, lambda: f64) -> f64 {
        let range = self.range();
        let (lo, hi) = (f64::from(range.min()), f64::from(range.max()));
        if lambda.is_nan() || lambda <= lo {
            return 0.0;
        }
        if lambda >= hi {
            return 1.0;
        }
        match self {
            WavelengthDistribution::Uniform(_) => (lambda - lo) / (hi - lo),
            WavelengthDistribution::Visible { t_min, t_max, .. } => {
                let t = ((lambda - VISIBLE_CENTER_NM) * VISIBLE_SHARPNESS).tanh();
                ((t - t_min) / (t_max - t_min)).clamp(0.0, 1.0)
            }
            WavelengthDistribution::Tabulated { histogram, .. } => histogram.invert(lambda),
        }
    }
}

/// The visible density at each of `lambda` into `density`, in f32: 1 / cosh^2 x as
/// 4 e / (1 + e)^2 with e = exp(-2 |x|), times `scale`, and 0 outside `range`. A loop
/// over slices, out of line: LLVM's loop vectorizer computes four lanes per instruction,
/// while a package's eight lanes, unrolled as a fixed-size array, stayed scalar (measured:
/// fewer instructions per path on the Cornell box, the same densities to the bit).
#[inline(never)]
fn visible_density(lambda: &[f32], density: &mut [f32], scale: f32, range: WavelengthRange) {
    let (center, sharpness) = (VISIBLE_CENTER_NM as f32, VISIBLE_SHARPNESS as f32);
    for (d, &l) in density.iter_mut().zip(lambda) {
        let e = exp_lane(-2.0 * ((l - center) * sharpness).abs());
        *d = if l >= range.min() && l <= range.max() {
            (scale * e / ((1.0 + e) * (1.0 + e))).max(f32::MIN_POSITIVE)
        } else {
            0.0
        };
    }
}

/// The integral of `f` over the range by the same bin-centre rule the histograms use.
fn bin_area(range: WavelengthRange, bins: usize, f: &dyn Fn(f64) -> f64) -> f64 {
    let (lo, hi) = (f64::from(range.min()), f64::from(range.max()));
    let width = (hi - lo) / bins.max(1) as f64;
    (0..bins)
        .map(|i| f(lo + (i as f64 + 0.5) * width).max(0.0))
        .sum::<f64>()
        * width
}
