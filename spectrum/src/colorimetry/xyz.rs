use crate::error::SpectrumError;

/// CIE XYZ tristimulus values.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Xyz {
    /// X.
    pub x: f64,
    /// Y (luminance, relative or absolute depending on where the value came from).
    pub y: f64,
    /// Z.
    pub z: f64,
}

/// CIE 1931 xy chromaticity coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chromaticity {
    /// x = X / (X + Y + Z).
    pub x: f64,
    /// y = Y / (X + Y + Z).
    pub y: f64,
}

/// CIE 1960 UCS chromaticity coordinates (u, v), in which CCT is defined.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Uv {
    /// u = 4X / (X + 15Y + 3Z).
    pub u: f64,
    /// v = 6Y / (X + 15Y + 3Z).
    pub v: f64,
}

impl Xyz {
    /// XYZ from its components.
    pub const fn new(x: f64, y: f64, z: f64) -> Self {
        Self { x, y, z }
    }

    /// The components as an array.
    pub fn to_array(self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }

    /// XYZ with luminance `luminance` at chromaticity `xy` (xyY to XYZ). Errors when
    /// `xy.y <= 0` (no colour has it), an input is not finite, or the XYZ would overflow.
    pub fn from_xy_luminance(xy: Chromaticity, luminance: f64) -> Result<Self, SpectrumError> {
        let scale = luminance / xy.y;
        let xyz = Self::new(xy.x * scale, luminance, (1.0 - xy.x - xy.y) * scale);
        if xy.y > 0.0 && xyz.to_array().iter().all(|v| v.is_finite()) {
            Ok(xyz)
        } else {
            Err(SpectrumError::Degenerate(format!(
                "chromaticity ({}, {}) with luminance {} has no finite XYZ (need y > 0)",
                xy.x, xy.y, luminance
            )))
        }
    }

    /// The chromaticity, or an error for a colour with X + Y + Z = 0 (black).
    pub fn chromaticity(self) -> Result<Chromaticity, SpectrumError> {
        let sum = self.x + self.y + self.z;
        if sum == 0.0 || !sum.is_finite() {
            return Err(SpectrumError::Degenerate(format!(
                "XYZ ({}, {}, {}) has no chromaticity (X + Y + Z = {sum})",
                self.x, self.y, self.z
            )));
        }
        Ok(Chromaticity {
            x: self.x / sum,
            y: self.y / sum,
        })
    }

    /// CIE 1960 (u, v), or an error where X + 15Y + 3Z = 0.
    pub fn uv(self) -> Result<Uv, SpectrumError> {
        let d = self.x + 15.0 * self.y + 3.0 * self.z;
        if d == 0.0 || !d.is_finite() {
            return Err(SpectrumError::Degenerate(format!(
                "XYZ ({}, {}, {}) has no (u, v) chromaticity",
                self.x, self.y, self.z
            )));
        }
        Ok(Uv {
            u: 4.0 * self.x / d,
            v: 6.0 * self.y / d,
        })
    }

    /// Scaled so that Y = 1, or an error if Y is zero or not finite.
    pub fn normalized_to_unit_y(self) -> Result<Self, SpectrumError> {
        if self.y == 0.0 || !self.y.is_finite() {
            return Err(SpectrumError::Degenerate(format!(
                "cannot normalize to Y = 1: the spectrum has luminance Y = {}",
                self.y
            )));
        }
        Ok(Self::new(self.x / self.y, 1.0, self.z / self.y))
    }
}

impl Chromaticity {
    /// xy from its components.
    pub const fn new(x: f64, y: f64) -> Self {
        Self { x, y }
    }
}
