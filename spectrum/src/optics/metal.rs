use crate::Spectrum;
use crate::data::metals;
use crate::error::SpectrumError;
use crate::spectra::{Extrapolation, PiecewiseLinear};

/// A complex index of refraction n = eta + i k as two spectra, for conductors.
/// Outside the measured range the nearest measured value is used (clamp).
#[derive(Debug, Clone, PartialEq)]
pub struct ComplexIor {
    /// Real part.
    pub eta: PiecewiseLinear,
    /// Extinction coefficient (imaginary part).
    pub k: PiecewiseLinear,
    /// Where the measurements come from.
    pub source: &'static str,
}

impl ComplexIor {
    /// Reflectance at normal incidence from air, ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2).
    pub fn normal_reflectance(&self, lambda_nm: f64) -> f64 {
        let (n, k) = (self.eta.evaluate(lambda_nm), self.k.evaluate(lambda_nm));
        ((n - 1.0).powi(2) + k * k) / ((n + 1.0).powi(2) + k * k)
    }
}

/// Names accepted by [`named_metal`].
pub const METAL_NAMES: &str = "au (gold), ag (silver), cu (copper), al (aluminium)";

/// Measured complex index of a metal: `au`/`gold`, `ag`/`silver`, `cu`/`copper`,
/// `al`/`aluminium`/`aluminum`.
pub fn named_metal(name: &str) -> Result<ComplexIor, SpectrumError> {
    let (nm, eta, k, source): (&[f64], &[f64], &[f64], &'static str) =
        match name.trim().to_ascii_lowercase().as_str() {
            "au" | "gold" => (
                &metals::AU_NM,
                &metals::AU_ETA,
                &metals::AU_K,
                JOHNSON_CHRISTY,
            ),
            "ag" | "silver" => (
                &metals::AG_NM,
                &metals::AG_ETA,
                &metals::AG_K,
                JOHNSON_CHRISTY,
            ),
            "cu" | "copper" => (
                &metals::CU_NM,
                &metals::CU_ETA,
                &metals::CU_K,
                JOHNSON_CHRISTY,
            ),
            "al" | "aluminium" | "aluminum" => {
                (&metals::AL_NM, &metals::AL_ETA, &metals::AL_K, RAKIC)
            }
            _ => {
                return Err(SpectrumError::UnknownName {
                    kind: "metal",
                    name: name.to_string(),
                    valid: METAL_NAMES.to_string(),
                });
            }
        };
    Ok(ComplexIor {
        eta: PiecewiseLinear::new(nm.to_vec(), eta.to_vec(), Extrapolation::Clamp)?,
        k: PiecewiseLinear::new(nm.to_vec(), k.to_vec(), Extrapolation::Clamp)?,
        source,
    })
}

const JOHNSON_CHRISTY: &str =
    "P. B. Johnson and R. W. Christy, Phys. Rev. B 6, 4370 (1972), 188-1937 nm";
const RAKIC: &str = "A. D. Rakic, Appl. Opt. 34, 4755 (1995), 207-2066 nm";
