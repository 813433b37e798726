//! `KHR_materials_specular` as a material describes it.

use std::sync::Arc;

use prism_spectrum::SampledWavelengths;

use crate::bsdf::Specular;
use crate::textures::{RgbTexture, SceneSpectrum, TexCoords};

/// The strength and colour of the dielectric base's reflection.
#[derive(Debug, Clone)]
pub struct SpecularDesc {
    /// `specularFactor` (default 1).
    pub factor: f32,
    /// `specularTexture`'s alpha channel times the factor, in every channel; None: the
    /// factor everywhere.
    pub texture: Option<Arc<RgbTexture>>,
    /// `specularColorFactor` times `specularColorTexture`, as a reflectance-like spectrum
    /// (it may exceed 1: Blender writes a specular level above 0.5 so).
    pub color: SceneSpectrum,
}

impl SpecularDesc {
    /// At texture coordinates `at`, for a path at `wavelengths`.
    pub fn at<const N: usize>(
        &self,
        at: &TexCoords,
        wavelengths: &SampledWavelengths<N>,
    ) -> Specular<N> {
        Specular {
            weight: match &self.texture {
                Some(t) => t.sample_at(at)[0],
                None => self.factor,
            },
            color: self.color.at_uv(*at, wavelengths),
        }
    }

    /// Whether a texture varies it.
    pub fn textured(&self) -> bool {
        self.texture.is_some()
            || matches!(self.color, SceneSpectrum::Texture(_))
            || matches!(&self.color, SceneSpectrum::Scaled(inner, _) if matches!(**inner, SceneSpectrum::Texture(_)))
    }
}
