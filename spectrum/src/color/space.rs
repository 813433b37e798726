use std::sync::LazyLock;

use super::{Mat3, TransferFunction};
use crate::colorimetry::{Chromaticity, WhitePoint, Xyz};
use crate::error::SpectrumError;

/// An additive RGB colour space: three primaries and a white point (chromaticities), from
/// which the RGB <-> XYZ matrices are derived, plus the transfer function of its encoding.
#[derive(Debug, Clone, PartialEq)]
pub struct RgbColorSpace {
    name: String,
    primaries: [Chromaticity; 3],
    white: WhitePoint,
    transfer: TransferFunction,
    rgb_to_xyz: Mat3,
    xyz_to_rgb: Mat3,
}

impl RgbColorSpace {
    /// A colour space from its red, green and blue primaries and white point.
    ///
    /// The matrix is the normalized primary matrix of SMPTE RP 177-1993 §3.3: the columns
    /// are the primaries' XYZ (at Y = 1) scaled so that RGB (1, 1, 1) maps to the white
    /// with Y = 1. Primaries may lie outside the spectral locus (ACES AP0's blue has
    /// y < 0). Errors when a primary has y = 0 or is not finite, when the white
    /// is invalid, or when the primaries are collinear (no gamut).
    pub fn new(
        name: impl Into<String>,
        primaries: [Chromaticity; 3],
        white: Chromaticity,
        transfer: TransferFunction,
    ) -> Result<Self, SpectrumError> {
        let name = name.into();
        let white = WhitePoint::from_xy(white)?;
        let columns = primaries
            .iter()
            .map(|p| primary_xyz(&name, *p))
            .collect::<Result<Vec<_>, _>>()?;
        let p = Mat3::from_columns([columns[0], columns[1], columns[2]]);
        let degenerate = || {
            SpectrumError::Degenerate(format!(
                "colour space '{name}': the primaries are collinear"
            ))
        };
        let p_inverse = p.inverse().ok_or_else(degenerate)?;
        let scale = p_inverse.apply(white.xyz().to_array());
        let rgb_to_xyz = p.mul(&Mat3::diagonal(scale));
        let xyz_to_rgb = rgb_to_xyz.inverse().ok_or_else(degenerate)?;
        Ok(Self {
            name,
            primaries,
            white,
            transfer,
            rgb_to_xyz,
            xyz_to_rgb,
        })
    }

    /// The space's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Red, green and blue primaries.
    pub fn primaries(&self) -> [Chromaticity; 3] {
        self.primaries
    }

    /// The white point.
    pub fn white(&self) -> WhitePoint {
        self.white
    }

    /// The transfer function of the space's encoded form.
    pub fn transfer(&self) -> TransferFunction {
        self.transfer
    }

    /// Linear RGB to XYZ.
    pub fn rgb_to_xyz_matrix(&self) -> Mat3 {
        self.rgb_to_xyz
    }

    /// XYZ to linear RGB.
    pub fn xyz_to_rgb_matrix(&self) -> Mat3 {
        self.xyz_to_rgb
    }

    /// Linear RGB of `xyz` (no chromatic adaptation: XYZ is taken as absolute).
    ///
    /// ```
    /// use prism_spectrum::color::RgbSpaceId;
    ///
    /// let srgb = RgbSpaceId::Srgb.space();
    /// // The white maps to RGB (1, 1, 1); a round trip returns what went in.
    /// let white = srgb.xyz_to_rgb(srgb.white().xyz());
    /// assert!(white.iter().all(|c| (c - 1.0).abs() < 1e-12));
    /// let back = srgb.xyz_to_rgb(srgb.rgb_to_xyz([0.2, 0.5, 0.8]));
    /// assert!((back[1] - 0.5).abs() < 1e-12);
    /// // Encoded for display with the space's transfer function.
    /// assert!((srgb.transfer().encode(0.5) - 0.7354).abs() < 1e-4);
    /// ```
    pub fn xyz_to_rgb(&self, xyz: Xyz) -> [f64; 3] {
        self.xyz_to_rgb.apply(xyz.to_array())
    }

    /// XYZ of linear `rgb`.
    pub fn rgb_to_xyz(&self, rgb: [f64; 3]) -> Xyz {
        let [x, y, z] = self.rgb_to_xyz.apply(rgb);
        Xyz::new(x, y, z)
    }

    /// The luminance (Y) of each primary at full intensity: the weights of
    /// Y = w_r R + w_g G + w_b B.
    pub fn luminance_weights(&self) -> [f64; 3] {
        self.rgb_to_xyz.0[1]
    }
}

/// XYZ of a primary at Y = 1; imaginary primaries (y < 0) are allowed, y = 0 is not.
fn primary_xyz(space: &str, p: Chromaticity) -> Result<[f64; 3], SpectrumError> {
    if !(p.x.is_finite() && p.y.is_finite()) || p.y.abs() < 1e-12 {
        return Err(SpectrumError::Degenerate(format!(
            "colour space '{space}': primary ({}, {}) needs finite x, y with y != 0",
            p.x, p.y
        )));
    }
    Ok([p.x / p.y, 1.0, (1.0 - p.x - p.y) / p.y])
}

/// The built-in colour spaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RgbSpaceId {
    /// IEC 61966-2-1 sRGB: Rec.709 primaries, D65, sRGB transfer.
    Srgb,
    /// ITU-R BT.709-6: sRGB's primaries and white with the BT.709 OETF.
    Rec709,
    /// Display P3 (Apple): DCI-P3 primaries, D65, sRGB transfer.
    DisplayP3,
    /// SMPTE RP 431-2 DCI-P3: the theatrical white (0.314, 0.351), gamma 2.6.
    DciP3,
    /// ITU-R BT.2020-2, D65, BT.2020 OETF (the BT.709 curve).
    Rec2020,
    /// SMPTE ST 2065-1 ACES2065-1 (AP0 primaries, ACES white), linear.
    Aces2065_1,
    /// ACEScg (AP1 primaries, ACES white), linear: S-2014-004.
    AcesCg,
    /// ROMM / ProPhoto RGB (ISO 22028-2), D50, gamma 1.8.
    ProPhoto,
    /// Adobe RGB (1998), D65, gamma 563/256.
    AdobeRgb,
}

impl RgbSpaceId {
    /// Every built-in space.
    pub const ALL: [RgbSpaceId; 9] = [
        RgbSpaceId::Srgb,
        RgbSpaceId::Rec709,
        RgbSpaceId::DisplayP3,
        RgbSpaceId::DciP3,
        RgbSpaceId::Rec2020,
        RgbSpaceId::Aces2065_1,
        RgbSpaceId::AcesCg,
        RgbSpaceId::ProPhoto,
        RgbSpaceId::AdobeRgb,
    ];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            RgbSpaceId::Srgb => "srgb",
            RgbSpaceId::Rec709 => "rec709",
            RgbSpaceId::DisplayP3 => "display-p3",
            RgbSpaceId::DciP3 => "dci-p3",
            RgbSpaceId::Rec2020 => "rec2020",
            RgbSpaceId::Aces2065_1 => "aces2065-1",
            RgbSpaceId::AcesCg => "acescg",
            RgbSpaceId::ProPhoto => "prophoto",
            RgbSpaceId::AdobeRgb => "adobe-rgb",
        }
    }

    /// Parses a name from [`RgbSpaceId::name`], any case, `_` for `-` accepted.
    pub fn from_name(name: &str) -> Result<Self, SpectrumError> {
        let wanted = name.to_ascii_lowercase().replace('_', "-");
        Self::ALL
            .into_iter()
            .find(|id| id.name() == wanted)
            .ok_or_else(|| SpectrumError::UnknownName {
                kind: "colour space",
                name: name.to_string(),
                valid: Self::ALL.map(RgbSpaceId::name).join(", "),
            })
    }

    /// The illuminant whose white the space is defined for, as a spectrum: CIE D65 for
    /// sRGB, Rec.709, Display P3, Rec.2020 and Adobe RGB; CIE D50 for ProPhoto; CIE
    /// daylight near the ACES white for ACES2065-1 and ACEScg (6000 K on the old
    /// radiation-constant scale, like the CIE's own D-names: xy (0.3217, 0.3378) against
    /// the ACES white (0.32168, 0.33767)); and for DCI-P3, whose theatrical white
    /// (0.314, 0.351) is no CIE illuminant (it lies 0.019 above the daylight locus in y),
    /// CIE daylight at 6300 K. Reflectance upsampling fits relative to this spectrum's own
    /// white, so RGB (1, 1, 1) is the perfect reflector under it in every case.
    pub fn illuminant(self) -> crate::spectra::PiecewiseLinear {
        use crate::illuminant::{StandardIlluminant, daylight};
        let nominal = |kelvin: f64| {
            daylight(kelvin * 1.4388 / 1.4380)
                .unwrap_or_else(|_| StandardIlluminant::D65.spectrum())
        };
        match self {
            RgbSpaceId::ProPhoto => StandardIlluminant::D50.spectrum(),
            RgbSpaceId::Aces2065_1 | RgbSpaceId::AcesCg => nominal(6000.0),
            RgbSpaceId::DciP3 => nominal(6300.0),
            _ => StandardIlluminant::D65.spectrum(),
        }
    }

    /// The colour space, built once on first use.
    pub fn space(self) -> &'static RgbColorSpace {
        static SPACES: LazyLock<Vec<RgbColorSpace>> =
            LazyLock::new(|| RgbSpaceId::ALL.iter().map(|id| id.build()).collect());
        &SPACES[Self::ALL.iter().position(|id| *id == self).unwrap_or(0)]
    }

    fn build(self) -> RgbColorSpace {
        let xy = Chromaticity::new;
        let rec709 = [xy(0.64, 0.33), xy(0.30, 0.60), xy(0.15, 0.06)];
        let p3 = [xy(0.680, 0.320), xy(0.265, 0.690), xy(0.150, 0.060)];
        let d65 = xy(0.3127, 0.3290);
        let d50 = xy(0.3457, 0.3585);
        let aces_white = xy(0.32168, 0.33767);
        let (primaries, white, transfer) = match self {
            RgbSpaceId::Srgb => (rec709, d65, TransferFunction::Srgb),
            RgbSpaceId::Rec709 => (rec709, d65, TransferFunction::Rec709),
            RgbSpaceId::DisplayP3 => (p3, d65, TransferFunction::Srgb),
            RgbSpaceId::DciP3 => (p3, xy(0.314, 0.351), TransferFunction::Gamma(2.6)),
            RgbSpaceId::Rec2020 => (
                [xy(0.708, 0.292), xy(0.170, 0.797), xy(0.131, 0.046)],
                d65,
                TransferFunction::Rec709,
            ),
            RgbSpaceId::Aces2065_1 => (
                [xy(0.7347, 0.2653), xy(0.0, 1.0), xy(0.0001, -0.0770)],
                aces_white,
                TransferFunction::Linear,
            ),
            RgbSpaceId::AcesCg => (
                [xy(0.713, 0.293), xy(0.165, 0.830), xy(0.128, 0.044)],
                aces_white,
                TransferFunction::Linear,
            ),
            RgbSpaceId::ProPhoto => (
                [xy(0.7347, 0.2653), xy(0.1596, 0.8404), xy(0.0366, 0.0001)],
                d50,
                TransferFunction::Gamma(1.8),
            ),
            RgbSpaceId::AdobeRgb => (
                [xy(0.64, 0.33), xy(0.21, 0.71), xy(0.15, 0.06)],
                d65,
                TransferFunction::Gamma(563.0 / 256.0),
            ),
        };
        // Built-in definitions are valid (every one is exercised by the tests).
        RgbColorSpace::new(self.name(), primaries, white, transfer)
            .unwrap_or_else(|e| unreachable!("built-in colour space {}: {e}", self.name()))
    }
}
