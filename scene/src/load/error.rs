use std::fmt;

/// Why a scene could not be loaded. Every variant names the problem in one line; the
/// caller prefixes the file name.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum LoadError {
    /// Not valid glTF (JSON syntax, schema, GLB framing), as the gltf crate reports it.
    Invalid(String),
    /// A buffer could not be obtained or is shorter than declared.
    Buffer(String),
    /// An accessor, index or attribute that cannot be read as geometry.
    Geometry(String),
    /// A scene index that does not exist, or a scene with nothing to render.
    Scene(String),
    /// A spectral description (`PRISM_spectral` or an overlay) that cannot be used.
    Spectral(String),
    /// A glTF extension the file requires that prism does not read.
    Unsupported(String),
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LoadError::Invalid(m) => write!(f, "invalid glTF: {m}"),
            LoadError::Buffer(m) => write!(f, "buffer: {m}"),
            LoadError::Geometry(m) => write!(f, "geometry: {m}"),
            LoadError::Scene(m) => write!(f, "scene: {m}"),
            LoadError::Spectral(m) => write!(f, "spectral description: {m}"),
            LoadError::Unsupported(m) => write!(f, "{m}"),
        }
    }
}

impl std::error::Error for LoadError {}
