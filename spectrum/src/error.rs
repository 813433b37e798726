//! The one error type of this crate.

use std::fmt;

/// What went wrong when building or evaluating a spectral quantity.
///
/// Every variant renders as one line that names the offending input, so a command-line
/// tool can print it as it is.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum SpectrumError {
    /// A numeric argument outside its domain (negative temperature, NaN wavelength...).
    InvalidValue {
        /// What the value is (for example "temperature").
        what: &'static str,
        /// The value that was given.
        value: f64,
        /// The domain it must lie in, in words.
        expected: &'static str,
    },
    /// A table that cannot describe a spectrum (unsorted, mismatched lengths, malformed text).
    InvalidTable(String),
    /// A name that is not in a catalogue; `valid` lists the accepted names.
    UnknownName {
        /// What kind of thing was looked up (for example "illuminant").
        kind: &'static str,
        /// The name that was given.
        name: String,
        /// The accepted names, comma separated.
        valid: String,
    },
    /// A computation whose answer does not exist for this input (a spectrum with zero
    /// luminance cannot be normalized, collinear primaries span no colour space...).
    Degenerate(String),
}

impl fmt::Display for SpectrumError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SpectrumError::InvalidValue {
                what,
                value,
                expected,
            } => write!(
                f,
                "invalid {what} {}: expected {expected}",
                Readable(*value)
            ),
            SpectrumError::InvalidTable(msg) => write!(f, "invalid spectral table: {msg}"),
            SpectrumError::UnknownName { kind, name, valid } => {
                write!(f, "unknown {kind} '{name}' (valid: {valid})")
            }
            SpectrumError::Degenerate(msg) => f.write_str(msg),
        }
    }
}

impl std::error::Error for SpectrumError {}

/// A number as a message shows it: as f64's `Display` does, except that huge and tiny
/// magnitudes are in scientific notation (`Display` writes every digit: 1e300 is 301 of
/// them, 1e-45 is 46). For error messages that quote a user's input.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Readable(pub f64);

impl fmt::Display for Readable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if x.is_finite() && (x.abs() >= 1e6 || (x != 0.0 && x.abs() < 1e-6)) {
            write!(f, "{x:e}")
        } else {
            write!(f, "{x}")
        }
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn require_positive(what: &'static str, value: f64) -> Result<f64, SpectrumError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(SpectrumError::InvalidValue {
            what,
            value,
            expected: "a finite number > 0",
        })
    }
}

/// Checks that `value` is finite.
pub(crate) fn require_finite(what: &'static str, value: f64) -> Result<f64, SpectrumError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(SpectrumError::InvalidValue {
            what,
            value,
            expected: "a finite number",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::SpectrumError;

    #[test]
    fn invalid_values_print_short() {
        let message = |value: f64| {
            SpectrumError::InvalidValue {
                what: "temperature (K)",
                value,
                expected: "a finite number > 0",
            }
            .to_string()
        };
        assert_eq!(
            message(1e300),
            "invalid temperature (K) 1e300: expected a finite number > 0"
        );
        assert!(message(-2.5e-300).contains(" -2.5e-300: "));
        assert!(message(-1.0).contains(" -1: "));
        assert!(message(6500.0).contains(" 6500: "));
        assert!(message(0.0).contains(" 0: "));
        assert!(message(f64::NAN).contains(" NaN: "));
        assert!(message(f64::INFINITY).contains(" inf: "));
    }

    #[test]
    fn tables_quote_huge_and_tiny_wavelengths_short() {
        let error = |csv: &str| {
            crate::spectra::PiecewiseLinear::from_csv_str(csv, crate::spectra::Extrapolation::Zero)
                .unwrap_err()
                .to_string()
        };
        let tiny = error("550,1\n1e-45,1\n");
        assert!(
            tiny.ends_with("550 nm at row 1 is followed by 1e-45 nm"),
            "{tiny}"
        );
        let huge = error("400,1\n1e300,1\n1e200,2\n");
        assert!(
            huge.ends_with("1e300 nm at row 2 is followed by 1e200 nm"),
            "{huge}"
        );
    }
}
