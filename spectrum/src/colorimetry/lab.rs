use super::{Chromaticity, Xyz};
use crate::error::SpectrumError;

/// A reference white: XYZ with Y = 1 and X, Z positive. The type guarantees what CIELAB
/// and chromatic adaptation divide by is never zero.
///
/// ```
/// use prism_spectrum::color::RgbSpaceId;
/// use prism_spectrum::colorimetry::{emission_xyz, Lab, Observer, WhitePoint, Xyz};
/// use prism_spectrum::illuminant::StandardIlluminant;
///
/// // sRGB's white is the rounded D65 of the standards...
/// assert_eq!(RgbSpaceId::Srgb.space().white(), WhitePoint::D65);
/// // ...which is not quite the white of the CIE D65 spectrum.
/// let spectral = WhitePoint::from_xyz(emission_xyz(
///     &StandardIlluminant::D65.spectrum(),
///     Observer::Cie1931,
/// ))?;
/// let grey = Xyz::new(0.2, 0.2, 0.2);
/// let (a, b) = (Lab::from_xyz(grey, WhitePoint::D65), Lab::from_xyz(grey, spectral));
/// assert!((a.a - b.a).abs() > 1e-3 && (a.a - b.a).abs() < 0.05);
/// # Ok::<(), prism_spectrum::SpectrumError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WhitePoint {
    xyz: Xyz,
    xy: Chromaticity,
}

impl WhitePoint {
    /// CIE D65 as the RGB standards round it, xy (0.3127, 0.3290): the white of sRGB,
    /// Rec.709, Display P3, Rec.2020 and Adobe RGB, so it is what
    /// `RgbSpaceId::Srgb.space().white()` returns. The CIE D65 *spectrum* integrates to
    /// (0.31272, 0.32903); the two whites give CIELAB values that differ by about 0.01,
    /// so use the space's white when comparing with RGB tools and
    /// [`WhitePoint::from_xyz`] of the spectrum when comparing with spectral ones.
    pub const D65: WhitePoint = WhitePoint::from_xy_const(0.3127, 0.3290);
    /// CIE D50 as ICC profiles and ProPhoto RGB round it, xy (0.3457, 0.3585).
    pub const D50: WhitePoint = WhitePoint::from_xy_const(0.3457, 0.3585);
    /// The equal-energy white E, xy (1/3, 1/3).
    pub const E: WhitePoint = WhitePoint::from_xy_const(1.0 / 3.0, 1.0 / 3.0);
    /// The ACES white (SMPTE ST 2065-1), xy (0.32168, 0.33767).
    pub const ACES: WhitePoint = WhitePoint::from_xy_const(0.32168, 0.33767);
    /// The DCI theatrical white (SMPTE RP 431-2), xy (0.314, 0.351).
    pub const DCI: WhitePoint = WhitePoint::from_xy_const(0.314, 0.351);

    /// For the named constants, whose chromaticities are valid by inspection.
    const fn from_xy_const(x: f64, y: f64) -> Self {
        Self {
            xyz: Xyz::new(x / y, 1.0, (1.0 - x - y) / y),
            xy: Chromaticity::new(x, y),
        }
    }

    /// The white with chromaticity `xy` (needs x > 0, y > 0, x + y < 1, all finite).
    pub fn from_xy(xy: Chromaticity) -> Result<Self, SpectrumError> {
        let ok = xy.x.is_finite() && xy.y.is_finite() && xy.x > 0.0 && xy.y > 0.0;
        if !ok || xy.x + xy.y >= 1.0 {
            return Err(SpectrumError::Degenerate(format!(
                "({}, {}) is not a white point chromaticity (need x > 0, y > 0, x + y < 1)",
                xy.x, xy.y
            )));
        }
        let xyz = Xyz::new(xy.x / xy.y, 1.0, (1.0 - xy.x - xy.y) / xy.y);
        Ok(Self { xyz, xy })
    }

    /// The white with the chromaticity of `xyz` (any positive luminance).
    pub fn from_xyz(xyz: Xyz) -> Result<Self, SpectrumError> {
        Self::from_xy(xyz.chromaticity()?)
    }

    /// XYZ with Y = 1.
    pub fn xyz(&self) -> Xyz {
        self.xyz
    }

    /// Chromaticity.
    pub fn xy(&self) -> Chromaticity {
        self.xy
    }
}

/// CIE 1976 L*a*b* (CIE 015:2018 §8.2.1).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Lab {
    /// Lightness L*, 0 (black) to 100 (the white).
    pub l: f64,
    /// Red-green opponent axis a*.
    pub a: f64,
    /// Yellow-blue opponent axis b*.
    pub b: f64,
}

// The CIE constants in their exact rational form (CIE 015:2018 §8.2.1, note 5).
const EPSILON: f64 = 216.0 / 24389.0;
const KAPPA: f64 = 24389.0 / 27.0;

fn f(t: f64) -> f64 {
    if t > EPSILON {
        t.cbrt()
    } else {
        (KAPPA * t + 16.0) / 116.0
    }
}

fn f_inverse(ft: f64) -> f64 {
    let t3 = ft * ft * ft;
    if t3 > EPSILON {
        t3
    } else {
        (116.0 * ft - 16.0) / KAPPA
    }
}

impl Lab {
    /// Lab from its components.
    pub const fn new(l: f64, a: f64, b: f64) -> Self {
        Self { l, a, b }
    }

    /// L*a*b* of `xyz` relative to `white` (both on the same luminance scale, the white's
    /// Y = 1). Finite for finite input.
    pub fn from_xyz(xyz: Xyz, white: WhitePoint) -> Self {
        let w = white.xyz();
        let (fx, fy, fz) = (f(xyz.x / w.x), f(xyz.y / w.y), f(xyz.z / w.z));
        Self::new(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz))
    }

    /// The XYZ of this colour relative to `white`.
    pub fn to_xyz(self, white: WhitePoint) -> Xyz {
        let fy = (self.l + 16.0) / 116.0;
        let fx = fy + self.a / 500.0;
        let fz = fy - self.b / 200.0;
        let w = white.xyz();
        let y = if self.l > KAPPA * EPSILON {
            fy * fy * fy
        } else {
            self.l / KAPPA
        };
        Xyz::new(f_inverse(fx) * w.x, y * w.y, f_inverse(fz) * w.z)
    }

    /// Chroma C*ab.
    pub fn chroma(self) -> f64 {
        self.a.hypot(self.b)
    }
}

#[cfg(test)]
mod named_whites {
    use super::{Chromaticity, WhitePoint};

    #[test]
    fn constants_equal_the_validated_constructor() {
        for (named, x, y) in [
            (WhitePoint::D65, 0.3127, 0.3290),
            (WhitePoint::D50, 0.3457, 0.3585),
            (WhitePoint::E, 1.0 / 3.0, 1.0 / 3.0),
            (WhitePoint::ACES, 0.32168, 0.33767),
            (WhitePoint::DCI, 0.314, 0.351),
        ] {
            assert_eq!(named, WhitePoint::from_xy(Chromaticity::new(x, y)).unwrap());
        }
    }
}
