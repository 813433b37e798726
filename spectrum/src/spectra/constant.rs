use crate::Spectrum;
use crate::error::{SpectrumError, require_finite};

/// The same value at every wavelength.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Constant {
    value: f64,
}

impl Constant {
    /// A spectrum equal to `value` everywhere; `value` must be finite.
    pub fn new(value: f64) -> Result<Self, SpectrumError> {
        Ok(Self {
            value: require_finite("constant spectrum value", value)?,
        })
    }

    /// The constant value.
    pub fn value(&self) -> f64 {
        self.value
    }
}

impl Spectrum for Constant {
    fn evaluate(&self, _lambda_nm: f64) -> f64 {
        self.value
    }
    fn max_value(&self) -> f64 {
        self.value
    }
}
