//! The one error type of this crate.

use std::fmt;

/// Why a distribution or sampler could not be built.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum SamplingError {
    /// No function values were given.
    Empty,
    /// A function value is negative, NaN or infinite (index and value).
    InvalidValue {
        /// Position of the offending value.
        index: usize,
        /// The value.
        value: f64,
    },
    /// Every value is zero: there is nothing to sample.
    AllZero,
    /// A parameter outside its domain, described in words.
    InvalidParameter(String),
}

impl fmt::Display for SamplingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SamplingError::Empty => f.write_str("cannot sample an empty function"),
            SamplingError::InvalidValue { index, value } => write!(
                f,
                "function value {value} at index {index} is not a finite number >= 0"
            ),
            SamplingError::AllZero => {
                f.write_str("cannot sample a function that is zero everywhere")
            }
            SamplingError::InvalidParameter(msg) => f.write_str(msg),
        }
    }
}

impl std::error::Error for SamplingError {}

/// Checks that every value is finite and non-negative, and that there is at least one.
pub(crate) fn validate(values: &[f64]) -> Result<(), SamplingError> {
    if values.is_empty() {
        return Err(SamplingError::Empty);
    }
    match values.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
        Some(index) => Err(SamplingError::InvalidValue {
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}
