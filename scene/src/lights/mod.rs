//! Lights of a render-ready scene (`light`: emissive triangles, punctual lights and the
//! environment, [`Lights`] choosing among them by power), the choice by power at a path's
//! wavelengths when their spectra differ (`light_choice`), light from infinity
//! (`environment/`) and a path's cache of emission spectra at its wavelengths
//! (`emission_cache`).

mod emission_cache;
mod environment;
mod light;
mod light_choice;
mod spot_texture;

pub use emission_cache::EmissionCache;
pub use environment::{
    DEFAULT_ENVIRONMENT, Environment, EnvironmentMap, grey_environment, unit_d65,
};
pub use light::{CausticTarget, EmissionSample, Light, LightSample, Lights, SpotFalloff};

/// The former name of [`CausticTarget`].
#[deprecated(note = "renamed CausticTarget: where light paths aim")]
pub type Aim = CausticTarget;
pub(crate) use light::{light_extent, light_spectrum, solid_angle_sampled, texture_coverage};
pub use light_choice::MAX_GROUPS;
pub use spot_texture::SpotTexture;
