use super::TransferFunction;

/// How radiance above display white is compressed into [0, 1] for viewing.
///
/// Operators act on linear RGB in the output colour space after exposure; none of them is
/// physically meaningful, they only make an image viewable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ToneMap {
    /// Clip each channel to [0, 1].
    Clamp,
    /// Reinhard, Stark, Shirley and Ferwerda, "Photographic tone reproduction for digital
    /// images", SIGGRAPH 2002, eq. 4, on luminance: L (1 + L / white^2) / (1 + L), with
    /// the RGB scaled by the ratio so hue is kept. `white` is the luminance that maps to 1.
    ReinhardExtended {
        /// Smallest luminance mapped to pure white (> 0).
        white: f64,
    },
    /// Narkowicz's fit of the ACES reference rendering and output transforms ("ACES Filmic
    /// Tone Mapping Curve", 2015): x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14) per
    /// channel, after the customary 0.6 pre-scale.
    AcesFilmic,
}

impl ToneMap {
    /// Names accepted by [`ToneMap::from_name`].
    pub const NAMES: &'static str = "clamp, reinhard[:WHITE], aces";

    /// Parses `clamp`, `reinhard` (white 4), `reinhard:W` or `aces`.
    pub fn from_name(name: &str) -> Result<Self, crate::SpectrumError> {
        let lower = name.to_ascii_lowercase();
        let error = || crate::SpectrumError::UnknownName {
            kind: "tone map",
            name: name.to_string(),
            valid: Self::NAMES.to_string(),
        };
        match lower.as_str() {
            "clamp" => Ok(Self::Clamp),
            "aces" | "aces-filmic" => Ok(Self::AcesFilmic),
            "reinhard" => Ok(Self::ReinhardExtended { white: 4.0 }),
            other => match other.strip_prefix("reinhard:").map(str::parse::<f64>) {
                Some(Ok(w)) if w.is_finite() && w > 0.0 => Ok(Self::ReinhardExtended { white: w }),
                _ => Err(error()),
            },
        }
    }

    /// Maps linear `rgb` to display-linear values in [0, 1]. `luminance_weights` are the
    /// output space's Y row ([`super::RgbColorSpace::luminance_weights`]). Non-finite and
    /// negative channels become 0; +inf becomes 1.
    pub fn apply(self, rgb: [f64; 3], luminance_weights: [f64; 3]) -> [f64; 3] {
        let clean = rgb.map(|v| if v.is_nan() { 0.0 } else { v.max(0.0) });
        let mapped = match self {
            ToneMap::Clamp => clean,
            ToneMap::ReinhardExtended { white } => {
                let white = if white.is_finite() && white > 0.0 {
                    white
                } else {
                    1.0
                };
                let l: f64 = (0..3).map(|i| clean[i] * luminance_weights[i]).sum();
                if l.is_nan() || l <= 0.0 {
                    [0.0; 3]
                } else if !l.is_finite() {
                    [1.0; 3]
                } else {
                    // L_d / L as one ratio of moderate numbers, finite for any finite L.
                    let scale = (1.0 + l / (white * white)) / (1.0 + l);
                    clean.map(|c| c * scale)
                }
            }
            ToneMap::AcesFilmic => clean.map(|c| {
                if !c.is_finite() {
                    return 1.0;
                }
                let x = 0.6 * c;
                (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)
            }),
        };
        mapped.map(|v| {
            if v.is_finite() {
                v.clamp(0.0, 1.0)
            } else {
                1.0
            }
        })
    }
}

/// Linear RGB radiance to an 8-bit display pixel: multiply by 2^`exposure_stops`, tone
/// map, encode with `transfer`, round to 0..=255.
pub fn display_8bit(
    rgb: [f64; 3],
    exposure_stops: f64,
    tone_map: ToneMap,
    luminance_weights: [f64; 3],
    transfer: TransferFunction,
) -> [u8; 3] {
    let gain = if exposure_stops.is_finite() {
        exposure_stops.exp2()
    } else {
        1.0
    };
    let mapped = tone_map.apply(rgb.map(|c| c * gain), luminance_weights);
    mapped.map(|v| (transfer.encode(v).clamp(0.0, 1.0) * 255.0).round() as u8)
}
