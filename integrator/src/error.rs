use std::fmt;
use std::sync::Arc;

/// The error of this crate: why a render could not be set up, or an image written, read
/// or merged. Each variant displays as one line naming the offending input; those that
/// wrap the EXR library's error give it as [`std::error::Error::source`].
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum RenderError {
    /// A setting out of its range.
    Setting(String),
    /// The image could not be encoded.
    Encode {
        /// What failed, in words.
        reason: String,
        /// The EXR library's error, where it failed.
        source: Option<Arc<dyn std::error::Error + Send + Sync>>,
    },
    /// A file that is not the image it should be (not an EXR, not a prism accumulation
    /// file, truncated, missing channels).
    Decode {
        /// What is wrong, in words.
        reason: String,
        /// The EXR library's error, where it found the problem.
        source: Option<Arc<dyn std::error::Error + Send + Sync>>,
    },
    /// Films that cannot be added together (sizes, bands or channels differ).
    Merge(String),
    /// Two images cannot be compared (sizes or channels differ, a sample is not finite).
    Comparison(String),
}

impl RenderError {
    /// An encoding failure of the EXR library.
    #[cfg(feature = "exr")]
    pub(crate) fn exr_encode(what: &str, error: exr::error::Error) -> Self {
        RenderError::Encode {
            reason: format!("{what}: {error}"),
            source: Some(Arc::new(error)),
        }
    }
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::Setting(m) => write!(f, "render setting: {m}"),
            RenderError::Encode { reason, .. } => write!(f, "image encoding: {reason}"),
            RenderError::Decode { reason, .. } => write!(f, "cannot read: {reason}"),
            RenderError::Merge(m) => write!(f, "cannot merge: {m}"),
            RenderError::Comparison(m) => write!(f, "cannot compare: {m}"),
        }
    }
}

impl std::error::Error for RenderError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            RenderError::Encode {
                source: Some(e), ..
            }
            | RenderError::Decode {
                source: Some(e), ..
            } => Some(e.as_ref() as &(dyn std::error::Error + 'static)),
            _ => None,
        }
    }
}
