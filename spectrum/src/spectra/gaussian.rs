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
