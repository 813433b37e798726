//! The error of this crate.

use std::fmt;
use std::sync::Arc;

/// The error of this crate: why a scene could not be loaded or built. Every variant
/// displays as one line naming the problem; the caller prefixes the file name. Variants
/// that wrap another error (an I/O error of a file the scene refers to, the gltf crate's
/// parse error) give it as [`std::error::Error::source`].
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum LoadError {
    /// Not valid glTF (JSON syntax, schema, GLB framing).
    Invalid {
        /// What is wrong, in words.
        reason: String,
        /// The glTF parser's error, when it found the problem.
        source: Option<Arc<dyn std::error::Error + Send + Sync>>,
    },
    /// A file the scene refers to could not be read (the resolver failed).
    Resource {
        /// What refers to it, for example "buffer 0".
        referrer: String,
        /// The URI as the file gives it.
        uri: String,
        /// Why the resolver failed.
        source: Arc<std::io::Error>,
    },
    /// A buffer is missing, malformed or shorter than declared.
    Buffer(String),
    /// An accessor, index or attribute that cannot be read as geometry.
    Geometry(String),
    /// A scene index that does not exist, a scene with nothing to render, or scene parts
    /// that do not fit together (for example a normal map without tangents).
    Scene(String),
    /// A spectral description (`PRISM_spectral` or an overlay) that cannot be used.
    Spectral(String),
    /// A glTF extension the file requires that prism does not read.
    Unsupported(String),
    /// A fluorescent material whose re-radiation cannot be built (absorption or emission
    /// outside the range, a quantum yield above 1...).
    Fluorescence(String),
    /// An image that cannot be decoded (not PNG, JPEG, WebP, OpenEXR or Radiance, or
    /// malformed).
    Image(String),
    /// A Mitsuba XML scene that cannot be read: malformed XML, an unknown tag, a missing
    /// attribute, a bad number, an undefined `$name`, an unknown reference, an include
    /// that is missing or circular.
    Mitsuba {
        /// Where: `file:line`.
        at: String,
        /// What is wrong, in words.
        reason: String,
    },
    /// A name that is not one of the accepted ones.
    UnknownName {
        /// What kind of thing was named, for example "upsampling".
        kind: &'static str,
        /// The name given.
        name: String,
        /// The accepted names, comma separated.
        valid: &'static str,
    },
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LoadError::Invalid { reason, .. } => write!(f, "invalid glTF: {reason}"),
            LoadError::Resource {
                referrer,
                uri,
                source,
            } => write!(f, "{referrer}: cannot read '{uri}': {source}"),
            LoadError::Buffer(m) => write!(f, "buffer: {m}"),
            LoadError::Geometry(m) => write!(f, "geometry: {m}"),
            LoadError::Scene(m) => write!(f, "scene: {m}"),
            LoadError::Spectral(m) => write!(f, "spectral description: {m}"),
            LoadError::Fluorescence(m) => write!(f, "fluorescent material: {m}"),
            LoadError::Unsupported(m) | LoadError::Image(m) => write!(f, "{m}"),
            LoadError::Mitsuba { at, reason } => write!(f, "{at}: {reason}"),
            LoadError::UnknownName { kind, name, valid } => {
                write!(f, "unknown {kind} '{name}' (valid: {valid})")
            }
        }
    }
}

impl std::error::Error for LoadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            LoadError::Invalid {
                source: Some(e), ..
            } => Some(e.as_ref() as &(dyn std::error::Error + 'static)),
            LoadError::Resource { source, .. } => Some(source.as_ref()),
            _ => None,
        }
    }
}

/// What resolves the URIs a scene refers to (buffers, images, spectra in CSV files) to
/// their bytes: typically a read of the file relative to the scene's directory.
pub type Resolver<'a> = dyn Fn(&str) -> std::io::Result<Vec<u8>> + 'a;
