//! Light from infinity: a uniform environment (a spectrum from every direction) or an
//! environment image ([`EnvironmentMap`]), and the convention that makes a number or an
//! RGB texel mean what an emissive colour means.

mod latlong;
mod map;

pub use map::EnvironmentMap;

use std::sync::{Arc, LazyLock};

use prism_spectrum::color::RgbSpaceId;
use prism_spectrum::spectra::DenselySampled;

use crate::textures::SceneSpectrum;

/// CIE D65 (the sRGB white's illuminant) normalized to luminance 1 (Y = 1 under the
/// CIE 1931 observer): what an emissive colour of RGB (1, 1, 1) emits, glTF colours being
/// linear sRGB.
pub fn unit_d65() -> Arc<DenselySampled> {
    static D65: LazyLock<Arc<DenselySampled>> = LazyLock::new(|| {
        prism_upsample::normalized_illuminant(&RgbSpaceId::Srgb.illuminant())
            .expect("D65 is a constant table with luminance")
    });
    D65.clone()
}

/// A grey environment of emissive-colour value `value`: D65 scaled so that a white
/// Lambertian surface under it renders as RGB (`value`, `value`, `value`) in sRGB, as an
/// emissive colour of that value would look.
pub fn grey_environment(value: f64) -> SceneSpectrum {
    SceneSpectrum::Scaled(Arc::new(SceneSpectrum::Dense(unit_d65())), value)
}

/// The emissive-colour value of the environment that lights a scene without lights: a
/// white Lambertian surface under it renders as RGB 1.
pub const DEFAULT_ENVIRONMENT: f64 = 1.0;

/// What lights a scene from infinity.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum Environment {
    /// The same radiance from every direction.
    Uniform(SceneSpectrum),
    /// An environment image.
    Map(Arc<EnvironmentMap>),
}

impl Environment {
    /// The light it is.
    pub fn light(&self) -> super::Light {
        match self {
            Environment::Uniform(radiance) => super::Light::Environment {
                radiance: radiance.clone(),
            },
            Environment::Map(map) => super::Light::EnvironmentMap { map: map.clone() },
        }
    }

    /// Its radiance's spectrum: the uniform one, or an image's mean over the sphere.
    pub fn spectrum(&self) -> &SceneSpectrum {
        match self {
            Environment::Uniform(radiance) => radiance,
            Environment::Map(map) => map.mean(),
        }
    }
}
