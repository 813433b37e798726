use std::fmt;

/// Why a render could not be set up or its output encoded. Each variant is one line naming
/// the offending input.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum RenderError {
    /// A setting out of its range.
    Setting(String),
    /// The image could not be encoded.
    Encode(String),
    /// Two images cannot be compared (sizes or channels differ, a sample is not finite).
    Comparison(String),
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::Setting(m) => write!(f, "render setting: {m}"),
            RenderError::Encode(m) => write!(f, "image encoding: {m}"),
            RenderError::Comparison(m) => write!(f, "cannot compare: {m}"),
        }
    }
}

impl std::error::Error for RenderError {}
