use crate::error::SamplingError;

/// A closed wavelength interval `[min, max]` in nm, `0 < min < max`, both finite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WavelengthRange {
    min: f32,
    max: f32,
}

impl WavelengthRange {
    /// The range of the CIE colour-matching functions, 360-830 nm: the default.
    pub const VISIBLE: WavelengthRange = WavelengthRange {
        min: 360.0,
        max: 830.0,
    };

    /// `[min, max]` in nm.
    pub fn new(min: f32, max: f32) -> Result<Self, SamplingError> {
        if min.is_finite() && max.is_finite() && min > 0.0 && min < max {
            Ok(Self { min, max })
        } else {
            Err(SamplingError::InvalidParameter(format!(
                "wavelength range {min}-{max} nm must satisfy 0 < min < max, both finite"
            )))
        }
    }

    /// Shortest wavelength, nm.
    pub fn min(&self) -> f32 {
        self.min
    }

    /// Longest wavelength, nm.
    pub fn max(&self) -> f32 {
        self.max
    }

    /// `max - min`, nm.
    pub fn width(&self) -> f32 {
        self.max - self.min
    }

    /// Whether `lambda` lies in the range (false for NaN).
    pub fn contains(&self, lambda: f32) -> bool {
        lambda >= self.min && lambda <= self.max
    }

    /// `lambda` clamped into the range (NaN to `min`).
    pub fn clamp(&self, lambda: f32) -> f32 {
        if lambda.is_nan() {
            self.min
        } else {
            lambda.clamp(self.min, self.max)
        }
    }
}

impl Default for WavelengthRange {
    fn default() -> Self {
        Self::VISIBLE
    }
}
