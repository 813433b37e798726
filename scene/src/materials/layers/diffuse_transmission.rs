//! `KHR_materials_diffuse_transmission` as a material describes it: thin translucent
//! surfaces (leaves, paper, lampshades), or the boundary of a dense volume.

use std::sync::Arc;

use prism_spectrum::SampledWavelengths;

use crate::bsdf::DiffuseTransmission;
use crate::textures::{RgbTexture, SceneSpectrum, TexCoords};

/// The share of the diffuse base transmitted, and its colour.
#[derive(Debug, Clone)]
pub struct DiffuseTransmissionDesc {
    /// `diffuseTransmissionFactor`.
    pub factor: f32,
    /// `diffuseTransmissionTexture`'s alpha channel times the factor, in every channel.
    pub texture: Option<Arc<RgbTexture>>,
    /// `diffuseTransmissionColorFactor` times its (sRGB) texture, as a reflectance-like
    /// spectrum.
    pub color: SceneSpectrum,
    /// The volume's absorption coefficient with `KHR_materials_volume`, as
    /// [`crate::materials::Material::Dielectric`]'s.
    pub absorption: Option<SceneSpectrum>,
}

impl DiffuseTransmissionDesc {
    /// At texture coordinates `at`, for a path at `wavelengths`.
    pub fn at<const N: usize>(
        &self,
        at: &TexCoords,
        wavelengths: &SampledWavelengths<N>,
    ) -> DiffuseTransmission<N> {
        DiffuseTransmission {
            factor: match &self.texture {
                Some(t) => t.sample_at(at)[0],
                None => self.factor,
            },
            color: self.color.at_uv(*at, wavelengths),
        }
    }

    /// Whether a texture varies it.
    pub fn textured(&self) -> bool {
        self.texture.is_some() || matches!(self.color, SceneSpectrum::Texture(_))
    }
}
