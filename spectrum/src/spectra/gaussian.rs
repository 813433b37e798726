use crate::Spectrum;
use crate::error::{SpectrumError, require_finite, require_positive};

/// A Gaussian band `peak * exp(-(lambda - center)^2 / (2 sigma^2))`, described by its
/// centre and full width at half maximum (FWHM = 2 sqrt(2 ln 2) sigma).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gaussian {
    center_nm: f64,
    sigma_nm: f64,
    peak: f64,
}

impl Gaussian {
    /// A band centred at `center_nm` with full width at half maximum `fwhm_nm` and the
    /// given `peak` value. Centre and peak must be finite, the width finite and positive.
    pub fn new(center_nm: f64, fwhm_nm: f64, peak: f64) -> Result<Self, SpectrumError> {
        let fwhm = require_positive("Gaussian FWHM (nm)", fwhm_nm)?;
        let sigma_nm = fwhm / (2.0 * (2.0 * std::f64::consts::LN_2).sqrt());
        // A subnormal width would make sigma 0 (or lose all precision): reject it.
        if !sigma_nm.is_normal() {
            return Err(SpectrumError::InvalidValue {
                what: "Gaussian FWHM (nm)",
                value: fwhm_nm,
                expected: "a normal (not subnormal) positive number",
            });
        }
        Ok(Self {
            center_nm: require_finite("Gaussian centre (nm)", center_nm)?,
            sigma_nm,
            peak: require_finite("Gaussian peak", peak)?,
        })
    }

    /// Centre wavelength, nm.
    pub fn center_nm(&self) -> f64 {
        self.center_nm
    }

    /// Standard deviation, nm.
    pub fn sigma_nm(&self) -> f64 {
        self.sigma_nm
    }
}

impl Gaussian {
    /// [`Spectrum::evaluate`] at every lane of a package with one `expf` per lane instead
    /// of an f64 `exp` (the distance to the centre and the peak stay f64, so no scale of
    /// parameters can make an infinity times a zero): within 1.2e-5 relative of
    /// `evaluate` (1e-7 near the centre; the exponent rounds to f32, and the error grows
    /// with it), or 1e-37 absolute where f32 underflows. 0 for non-finite wavelengths, never NaN.
    pub fn evaluate_lanes<const N: usize>(&self, lambda: &[f32; N]) -> [f32; N] {
        lambda.map(|l| {
            if !l.is_finite() {
                return 0.0;
            }
            let t = (f64::from(l) - self.center_nm) / self.sigma_nm;
            let falloff = ((-0.5 * t * t) as f32).exp();
            (self.peak * f64::from(falloff)) as f32
        })
    }
}

impl Spectrum for Gaussian {
    /// 0 for non-finite wavelengths.
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        if !lambda_nm.is_finite() {
            return 0.0;
        }
        // t^2 can overflow to inf for absurd inputs; exp(-inf) = 0 keeps the result finite.
        let t = (lambda_nm - self.center_nm) / self.sigma_nm;
        self.peak * (-0.5 * t * t).exp()
    }
    fn max_value(&self) -> f64 {
        self.peak.max(0.0)
    }
}
