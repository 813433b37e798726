//! Spectral descriptions: what glTF cannot say about spectra, said either in the glTF file
//! itself (the `PRISM_spectral` extension on materials, `KHR_lights_punctual` lights,
//! cameras (their thin lens) and the root) or in a TOML overlay that names a glTF file and its materials and lights.
//! The format, with an example per feature, is documented in `docs/scene-format.md`.
//!
//! Both forms are JSON values by the time they are read (TOML is converted), so one parser
//! checks them: every spectrum is finite and non-negative, fractions stay in [0, 1],
//! fluorescent materials conserve energy, and unknown keys are errors rather than being
//! silently ignored.

mod camera;
mod light;
mod material;
mod medium;
mod overlay;
mod value;

pub use light::{SpectralLight, SpectralScene};
pub use material::{FLUORESCENCE_RANGE_NM, MATERIAL_TYPES, SpectralMaterial};
pub use overlay::Overlay;
pub use value::{IOR_FORMS, Role, SPECTRUM_FORMS};

pub(crate) use camera::{Optics, optics};
pub(crate) use light::{light, scene};
pub(crate) use material::material;
pub(crate) use value::Context;

/// The extension's name.
pub const EXTENSION: &str = "PRISM_spectral";
