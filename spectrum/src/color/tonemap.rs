use super::TransferFunction;

/// How radiance above display white is compressed into [0, 1] for viewing.
///
/// Operators act on linear RGB in the output colour space after exposure; none of them is
/// physically meaningful, they only make an image viewable.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
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
    /// The Khronos PBR Neutral tone mapper (Khronos Group, 2024; the specification in
    /// KhronosGroup/ToneMapping, PBR_Neutral/README.md), the default of the glTF Sample
    /// Viewer and model-viewer: colours below 0.76 keep their hue and value (less an
    /// offset of at most F90 = 0.04 that rasterizers' specular adds back), brighter ones
    /// are compressed towards 1 and desaturated towards white, so base colours of a
    /// lit product shot come out as authored.
    PbrNeutral,
}

impl ToneMap {
    /// Names accepted by [`ToneMap::from_name`].
    pub const NAMES: &'static str = "neutral, clamp, reinhard[:WHITE], aces";

    /// Parses `neutral` (Khronos PBR Neutral), `clamp`, `reinhard` (white 4),
    /// `reinhard:W` or `aces`.
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
            "neutral" | "pbr-neutral" | "khronos" => Ok(Self::PbrNeutral),
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
            ToneMap::PbrNeutral => pbr_neutral(clean),
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

/// The Khronos PBR Neutral curve on non-negative `c` (the specification's symbols: F90,
/// K_s, K_d, f, p, p_n, g).
fn pbr_neutral(c: [f64; 3]) -> [f64; 3] {
    const F90: f64 = 0.04;
    const KS: f64 = 0.8 - F90;
    const KD: f64 = 0.15;
    if c.iter().any(|v| !v.is_finite()) {
        return [1.0; 3];
    }
    let x = c[0].min(c[1]).min(c[2]);
    let f = if x <= 2.0 * F90 {
        x - x * x / (4.0 * F90)
    } else {
        F90
    };
    let shifted = c.map(|v| v - f);
    let p = shifted[0].max(shifted[1]).max(shifted[2]);
    if p <= KS {
        return shifted;
    }
    let pn = 1.0 - (1.0 - KS) * (1.0 - KS) / (p + 1.0 - 2.0 * KS);
    let g = 1.0 / (KD * (p - pn) + 1.0);
    shifted.map(|v| v * (pn / p) * g + pn * (1.0 - g))
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

#[cfg(test)]
mod tests {
    use super::*;

    const REC709: [f64; 3] = [0.2126, 0.7152, 0.0722];

    /// Values worked by hand from the specification's formulas.
    #[test]
    fn pbr_neutral_follows_its_specification() {
        let map = |c: [f64; 3]| ToneMap::PbrNeutral.apply(c, REC709);
        // Below the knee: only the offset f (x - x^2 / 0.16 for x <= 0.08, else 0.04).
        assert_eq!(map([0.0; 3]), [0.0; 3]);
        let grey = map([0.5; 3])[0];
        assert!((grey - 0.46).abs() < 1e-12, "{grey}");
        let dark = map([0.04, 0.3, 0.2]);
        let f = 0.04 - 0.04 * 0.04 / 0.16;
        for (out, c) in dark.iter().zip([0.04, 0.3, 0.2]) {
            assert!((out - (c - f)).abs() < 1e-12);
        }
        // Above it: p = 2 - 0.04 = 1.96, p_n = 1 - 0.0576 / (1.96 + 0.48), g = 1 / (0.15 (p -
        // p_n) + 1); a grey stays grey at p_n.
        let p: f64 = 1.96;
        let pn = 1.0 - 0.24 * 0.24 / (p + 1.0 - 2.0 * 0.76);
        let out = map([2.0; 3]);
        assert!((out[0] - pn).abs() < 1e-12, "{out:?} vs {pn}");
        // Continuous at the knee, monotonic in brightness, and never above 1.
        let below = map([0.8 - 1e-9; 3])[0];
        let above = map([0.8 + 1e-9; 3])[0];
        assert!((above - below).abs() < 1e-6);
        let mut last = 0.0;
        for k in 0..200 {
            let v = map([0.1 * f64::from(k), 0.05 * f64::from(k), 0.02 * f64::from(k)]);
            assert!(v.iter().all(|c| (0.0..=1.0).contains(c)));
            assert!(v[0] >= last);
            last = v[0];
        }
        // Bright saturated colours move towards white.
        let red = map([20.0, 1.0, 1.0]);
        assert!(red[1] > 0.5 && red[0] > red[1], "{red:?}");
    }
}
