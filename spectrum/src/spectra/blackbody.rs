use crate::Spectrum;
use crate::constants::{BOLTZMANN, PLANCK, SPEED_OF_LIGHT, WIEN_DISPLACEMENT, WIEN_X};
use crate::error::{SpectrumError, require_positive};

/// Planck's law: spectral radiance of a blackbody at `kelvin`, at vacuum wavelength
/// `lambda_m` (metres), in W m^-2 sr^-1 m^-1 (SI, per metre of wavelength).
///
/// Domain: every input. Non-positive or non-finite wavelengths and temperatures give 0
/// (no emission); the result is never NaN or infinite. It is 0 where the true value is
/// below the smallest `f64`, and also where it would exceed the largest (only possible
/// for wavelengths below 1e-12 m at absurd temperatures). Accuracy: better than 1e-12 relative, because the
/// Rayleigh-Jeans side (x = hc / lambda k T <= 1) divides by `exp_m1(x)`, which has no
/// cancellation, and the Wien side evaluates `exp(ln(2hc^2/lambda^5) - x) / (1 - e^-x)`,
/// which neither overflows (as `e^x` would past x = 709) nor loses the prefactor.
pub fn planck_radiance(lambda_m: f64, kelvin: f64) -> f64 {
    if !(lambda_m > 0.0 && kelvin > 0.0 && lambda_m.is_finite() && kelvin.is_finite()) {
        return 0.0;
    }
    let x = PLANCK * SPEED_OF_LIGHT / (lambda_m * BOLTZMANN * kelvin);
    // ln(2 h c^2 / lambda^5): finite for every positive finite lambda.
    let ln_prefactor = (2.0 * PLANCK * SPEED_OF_LIGHT * SPEED_OF_LIGHT).ln() - 5.0 * lambda_m.ln();
    let value = if x <= 1.0 {
        ln_prefactor.exp() / x.exp_m1()
    } else {
        (ln_prefactor - x).exp() / -(-x).exp_m1()
    };
    if value.is_finite() { value } else { 0.0 }
}

/// Whether a [`Blackbody`] evaluates to absolute radiance or to its shape with peak 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Normalization {
    /// Spectral radiance in W m^-2 sr^-1 nm^-1 (prism's radiance unit).
    Absolute,
    /// Divided by the value at the Wien peak, so the maximum over all wavelengths is 1.
    PeakOne,
}

/// The emission of an ideal blackbody radiator (Planck's law).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Blackbody {
    kelvin: f64,
    normalization: Normalization,
}

impl Blackbody {
    /// Absolute spectral radiance, W m^-2 sr^-1 nm^-1, at `kelvin` (finite, > 0).
    pub fn new(kelvin: f64) -> Result<Self, SpectrumError> {
        Ok(Self {
            kelvin: require_positive("blackbody temperature (K)", kelvin)?,
            normalization: Normalization::Absolute,
        })
    }

    /// The blackbody's spectral shape with peak value 1, at `kelvin` (finite, > 0).
    pub fn normalized(kelvin: f64) -> Result<Self, SpectrumError> {
        Ok(Self {
            normalization: Normalization::PeakOne,
            ..Self::new(kelvin)?
        })
    }

    /// Temperature, K.
    pub fn kelvin(&self) -> f64 {
        self.kelvin
    }

    /// Wavelength of maximum spectral radiance (Wien's displacement law), nm.
    pub fn peak_nm(&self) -> f64 {
        WIEN_DISPLACEMENT / self.kelvin * 1e9
    }

    /// Spectral radiance in SI units, W m^-2 sr^-1 m^-1, at `lambda_m` metres.
    pub fn radiance_si(&self, lambda_m: f64) -> f64 {
        planck_radiance(lambda_m, self.kelvin)
    }

    /// [`Spectrum::evaluate`] at every lane of a package, in f32: what a path pays per
    /// light sample. The shape with peak 1 is the same ratio in f32 (one `expm1f` instead
    /// of an f64 `expm1` per lane), within 1.2e-5 relative of `evaluate` (1e-6 near the
    /// peak: x = hc / lambda k T rounds in f32, and e^x's error grows with x); where that
    /// `expm1f` overflows (x > 88.7, below a sixteenth of the peak wavelength, values
    /// under 1e-30) it is 0. Absolute radiance keeps the f64 evaluation. 0 for
    /// non-positive or non-finite wavelengths, never NaN.
    pub fn evaluate_lanes<const N: usize>(&self, lambda: &[f32; N]) -> [f32; N] {
        match self.normalization {
            Normalization::Absolute => lambda.map(|l| self.evaluate(f64::from(l)) as f32),
            Normalization::PeakOne => {
                let peak = self.peak_nm() as f32;
                lambda.map(|l| {
                    if !(l > 0.0 && l.is_finite()) {
                        return 0.0;
                    }
                    let ratio = peak / l;
                    let r2 = ratio * ratio;
                    let value =
                        r2 * r2 * ratio * (WIEN_X_EXPM1 as f32) / (WIEN_X as f32 * ratio).exp_m1();
                    if value.is_finite() {
                        value.min(1.0)
                    } else {
                        0.0
                    }
                })
            }
        }
    }
}

/// e^WIEN_X - 1, the peak's denominator (a libm call per evaluation otherwise: measured,
/// a large share of the blackbody's expm1 calls in the default scene). Equal to `WIEN_X.exp_m1()`
/// (tested).
const WIEN_X_EXPM1: f64 = 142.324_921_594_055_78;

impl Spectrum for Blackbody {
    /// 0 for non-positive or non-finite wavelengths.
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        match self.normalization {
            Normalization::Absolute => planck_radiance(lambda_nm * 1e-9, self.kelvin) * 1e-9,
            Normalization::PeakOne => {
                if !(lambda_nm > 0.0 && lambda_nm.is_finite()) {
                    return 0.0;
                }
                // B(l) / B(l_peak) = (l_peak / l)^5 (e^x_peak - 1) / (e^x - 1): a ratio of
                // modest numbers, so neither overflows even where B itself would.
                let ratio = self.peak_nm() / lambda_nm;
                let x = WIEN_X * ratio;
                let r2 = ratio * ratio;
                let value = r2 * r2 * ratio * WIEN_X_EXPM1 / x.exp_m1();
                if value.is_finite() {
                    value.min(1.0)
                } else {
                    0.0
                }
            }
        }
    }

    fn max_value(&self) -> f64 {
        match self.normalization {
            Normalization::Absolute => self.evaluate(self.peak_nm()),
            Normalization::PeakOne => 1.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_peak_denominator_is_expm1_of_wien_x() {
        assert_eq!(WIEN_X_EXPM1, WIEN_X.exp_m1());
    }
}
