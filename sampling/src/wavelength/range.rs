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

    /// `lambda` clamped into the range (NaN to `min`). `f32::max` takes the operand that
    /// is not NaN; no `f32::clamp`, whose check that min <= max is a branch per lane of
    /// every package (the constructor guarantees it).
    pub fn clamp(&self, lambda: f32) -> f32 {
        lambda.max(self.min).min(self.max)
    }
}

impl Default for WavelengthRange {
    fn default() -> Self {
        Self::VISIBLE
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::WavelengthRange;

    proptest! {
        /// Any f32 (NaN, infinities, subnormals, either sign) lands in the range, as
        /// `f32::clamp` would put it there, NaN at the minimum.
        #[test]
        fn clamp_is_the_clamp_with_nan_at_the_minimum(bits in any::<u32>(), lo in 1.0..500.0f32, width in 1e-3..700.0f32) {
            let range = WavelengthRange::new(lo, lo + width).unwrap();
            let x = f32::from_bits(bits);
            let expected = if x.is_nan() { range.min() } else { x.clamp(range.min(), range.max()) };
            prop_assert_eq!(range.clamp(x).to_bits(), expected.to_bits());
        }
    }
}
