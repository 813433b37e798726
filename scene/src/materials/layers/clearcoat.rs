//! `KHR_materials_clearcoat` as a material describes it.

use std::sync::Arc;

use crate::bsdf::Clearcoat;
use crate::materials::NormalMap;
use crate::textures::{RgbTexture, TexCoords};

use super::SurfaceFrame;

/// A clear coat: its weight, roughness and own normal texture.
#[derive(Debug, Clone)]
pub struct ClearcoatDesc {
    /// `clearcoatFactor`.
    pub factor: f32,
    /// `clearcoatTexture` (linear; red multiplies the factor).
    pub texture: Option<Arc<RgbTexture>>,
    /// `clearcoatRoughnessFactor` (perceptual).
    pub roughness: f32,
    /// `clearcoatRoughnessTexture` (linear; green multiplies the roughness).
    pub roughness_texture: Option<Arc<RgbTexture>>,
    /// `clearcoatNormalTexture`: the coat's own normal (None: the base's shading normal).
    pub normal_texture: Option<Arc<NormalMap>>,
}

impl ClearcoatDesc {
    /// At texture coordinates `at`; `frame` orients the coat's normal texture (without
    /// it, or where the texel tilts the normal to or past the surface, the coat follows
    /// the base).
    pub fn at(&self, at: &TexCoords, frame: Option<&SurfaceFrame>) -> Clearcoat {
        let factor = match &self.texture {
            Some(t) => self.factor * t.sample_at(at)[0],
            None => self.factor,
        };
        let roughness = match &self.roughness_texture {
            Some(t) => self.roughness * t.sample_at(at)[1],
            None => self.roughness,
        };
        let normal = match (&self.normal_texture, frame) {
            (Some(map), Some(frame)) => map
                .perturb(frame.frame.z, frame.tangent, *at)
                .map(|n| frame.frame.to_local(n)),
            _ => None,
        };
        Clearcoat::new(factor, roughness, normal)
    }

    /// Whether a texture varies it.
    pub fn textured(&self) -> bool {
        self.texture.is_some() || self.roughness_texture.is_some()
    }
}
