use crate::error::SpectrumError;

/// An opto-electronic transfer function: linear light to encoded signal and back.
///
/// Negative inputs are handled by odd extension (`encode(-x) = -encode(x)`), the
/// convention of extended-range sRGB, so out-of-gamut values survive a round trip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TransferFunction {
    /// No encoding.
    Linear,
    /// IEC 61966-2-1 sRGB (piecewise: linear below 0.0031308, 1.055 x^(1/2.4) - 0.055 above).
    Srgb,
    /// ITU-R BT.709-6 OETF (linear below 0.018, 1.099 x^0.45 - 0.099 above).
    Rec709,
    /// A pure power law with this exponent: encode(x) = x^(1/gamma).
    Gamma(f64),
}

impl TransferFunction {
    /// Parses `linear`, `srgb`, `rec709` or `gamma:G` (G > 0).
    pub fn from_name(name: &str) -> Result<Self, SpectrumError> {
        let lower = name.to_ascii_lowercase();
        match lower.as_str() {
            "linear" => Ok(Self::Linear),
            "srgb" => Ok(Self::Srgb),
            "rec709" | "bt709" => Ok(Self::Rec709),
            _ => match lower.strip_prefix("gamma:").map(str::parse::<f64>) {
                Some(Ok(g)) if g.is_finite() && g > 0.0 => Ok(Self::Gamma(g)),
                _ => Err(SpectrumError::UnknownName {
                    kind: "transfer function",
                    name: name.to_string(),
                    valid: "linear, srgb, rec709, gamma:G (G > 0)".into(),
                }),
            },
        }
    }

    /// Linear light to signal. NaN becomes 0; infinities stay infinite (callers tone map
    /// before encoding).
    pub fn encode(self, linear: f64) -> f64 {
        if linear.is_nan() {
            return 0.0;
        }
        let (sign, x) = (linear.signum(), linear.abs());
        let encoded = match self {
            TransferFunction::Linear => x,
            TransferFunction::Srgb => {
                if x <= 0.003_130_8 {
                    12.92 * x
                } else {
                    1.055 * x.powf(1.0 / 2.4) - 0.055
                }
            }
            TransferFunction::Rec709 => {
                if x < 0.018 {
                    4.5 * x
                } else {
                    1.099 * x.powf(0.45) - 0.099
                }
            }
            TransferFunction::Gamma(g) => x.powf(1.0 / sanitize_gamma(g)),
        };
        sign * encoded
    }

    /// Signal to linear light; the inverse of [`TransferFunction::encode`].
    pub fn decode(self, signal: f64) -> f64 {
        if signal.is_nan() {
            return 0.0;
        }
        let (sign, v) = (signal.signum(), signal.abs());
        let linear = match self {
            TransferFunction::Linear => v,
            TransferFunction::Srgb => {
                if v <= 0.040_45 {
                    v / 12.92
                } else {
                    ((v + 0.055) / 1.055).powf(2.4)
                }
            }
            TransferFunction::Rec709 => {
                if v < 0.081 {
                    v / 4.5
                } else {
                    ((v + 0.099) / 1.099).powf(1.0 / 0.45)
                }
            }
            TransferFunction::Gamma(g) => v.powf(sanitize_gamma(g)),
        };
        sign * linear
    }
}

/// A gamma built directly from the enum may be anything; treat invalid ones as 1.
fn sanitize_gamma(g: f64) -> f64 {
    if g.is_finite() && g > 0.0 { g } else { 1.0 }
}
