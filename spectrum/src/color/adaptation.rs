use super::Mat3;
use crate::colorimetry::WhitePoint;
use crate::error::SpectrumError;

/// A von Kries-type chromatic adaptation transform: the cone-like space in which the
/// white is scaled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AdaptationMethod {
    /// Bradford (Lam 1985; as in ICC.1 Annex E).
    Bradford,
    /// CAT02 (CIE 159:2004, CIECAM02).
    Cat02,
    /// von Kries with the Hunt-Pointer-Estevez cone fundamentals normalized to D65
    /// (Fairchild, *Color Appearance Models*, 3rd ed., §9.1).
    VonKries,
}

impl AdaptationMethod {
    /// Names accepted by [`AdaptationMethod::from_name`].
    pub const NAMES: &'static str = "bradford, cat02, von-kries";

    /// Parses a method name, any case.
    pub fn from_name(name: &str) -> Result<Self, SpectrumError> {
        match name.to_ascii_lowercase().replace(['_', ' '], "-").as_str() {
            "bradford" => Ok(Self::Bradford),
            "cat02" => Ok(Self::Cat02),
            "von-kries" | "vonkries" => Ok(Self::VonKries),
            _ => Err(SpectrumError::UnknownName {
                kind: "chromatic adaptation method",
                name: name.to_string(),
                valid: Self::NAMES.to_string(),
            }),
        }
    }

    /// The XYZ-to-cone-response matrix.
    pub fn cone_matrix(self) -> Mat3 {
        match self {
            AdaptationMethod::Bradford => Mat3([
                [0.8951, 0.2664, -0.1614],
                [-0.7502, 1.7135, 0.0367],
                [0.0389, -0.0685, 1.0296],
            ]),
            AdaptationMethod::Cat02 => Mat3([
                [0.7328, 0.4296, -0.1624],
                [-0.7036, 1.6975, 0.0061],
                [0.0030, 0.0136, 0.9834],
            ]),
            AdaptationMethod::VonKries => Mat3([
                [0.40024, 0.7076, -0.08081],
                [-0.2263, 1.16532, 0.0457],
                [0.0, 0.0, 0.91822],
            ]),
        }
    }
}

/// The XYZ-to-XYZ matrix that maps colours seen under `source` white to the corresponding
/// colours under `destination` white: `M^-1 diag(rho_dst / rho_src) M`.
pub fn adaptation_matrix(
    source: WhitePoint,
    destination: WhitePoint,
    method: AdaptationMethod,
) -> Mat3 {
    let cone = method.cone_matrix();
    let rho_src = cone.apply(source.xyz().to_array());
    let rho_dst = cone.apply(destination.xyz().to_array());
    let gain = std::array::from_fn(|i| {
        // Cone responses of a valid white are positive for all three methods; guard anyway
        // so that a pathological white cannot produce inf.
        if rho_src[i] != 0.0 {
            rho_dst[i] / rho_src[i]
        } else {
            1.0
        }
    });
    // The cone matrices are fixed and invertible (tests check it).
    let inverse = cone.inverse().unwrap_or(Mat3::IDENTITY);
    inverse.mul(&Mat3::diagonal(gain)).mul(&cone)
}
