//! Sigmoid-polynomial spectra and the spectrum kinds built on them.

use prism_spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};

use crate::sigmoid::{sigmoid, sigmoid_polynomial_lanes};

/// f(l) = S(c0 l^2 + c1 l + c2) with l in nm: a smooth spectrum in [0, 1] (Jakob and
/// Hanika 2019, eq. 4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SigmoidPolynomial {
    /// Coefficients (c0, c1, c2) of the polynomial in nanometres.
    pub coefficients: [f64; 3],
}

impl SigmoidPolynomial {
    /// The constant spectrum `value` (clamped into [0, 1]): c0 = c1 = 0 and
    /// c2 = S^-1(value), so every wavelength gives exactly S(c2).
    pub fn constant(value: f64) -> Self {
        Self {
            coefficients: [0.0, 0.0, inverse_sigmoid(value)],
        }
    }

    /// The polynomial at `lambda_nm`.
    pub fn polynomial(&self, lambda_nm: f64) -> f64 {
        let [c0, c1, c2] = self.coefficients;
        (c0 * lambda_nm + c1) * lambda_nm + c2
    }
}

/// S^-1(v) = (2v - 1) / sqrt(1 - (2v - 1)^2) for v in [0, 1] (clamped); +-inf at the ends.
pub fn inverse_sigmoid(v: f64) -> f64 {
    let v = if v.is_nan() { 0.5 } else { v.clamp(0.0, 1.0) };
    let y = 2.0 * v - 1.0;
    // 1 - y^2 = 4 v (1 - v) without cancellation near the ends.
    let d = (4.0 * v * (1.0 - v)).sqrt();
    if d == 0.0 { y * f64::INFINITY } else { y / d }
}

impl Spectrum for SigmoidPolynomial {
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        if lambda_nm.is_nan() {
            return 0.0;
        }
        sigmoid(self.polynomial(lambda_nm))
    }

    fn max_value(&self) -> f64 {
        // S is monotone, so the maximum over all wavelengths is S at the polynomial's
        // maximum: +inf (value 1) unless c0 < 0, then at the vertex.
        let [c0, c1, _] = self.coefficients;
        if c0 < 0.0 {
            sigmoid(self.polynomial(-c1 / (2.0 * c0)))
        } else if c0 == 0.0 && c1 == 0.0 {
            sigmoid(self.coefficients[2])
        } else {
            1.0
        }
    }

    fn sample<const N: usize>(&self, wavelengths: &SampledWavelengths<N>) -> SampledSpectrum<N> {
        SampledSpectrum(sigmoid_polynomial_lanes(
            self.coefficients.map(|c| c as f32),
            wavelengths.lambdas(),
        ))
    }
}
