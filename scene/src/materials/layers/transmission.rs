//! `KHR_materials_transmission` as a material describes it when it is more than clear
//! thick glass: a share of glass (`transmissionFactor`, its texture), thin-walled without
//! `KHR_materials_volume`, its transmitted light tinted by the base colour.

use std::sync::Arc;

use crate::textures::{RgbTexture, SceneSpectrum, TexCoords};

/// The glass share of a glTF material.
#[derive(Debug, Clone)]
pub struct TransmissionDesc {
    /// `transmissionFactor`, in [0, 1].
    pub factor: f32,
    /// `transmissionTexture` (linear; red multiplies the factor).
    pub texture: Option<Arc<RgbTexture>>,
    /// The glass's index of refraction (per wavelength with `KHR_materials_dispersion`).
    pub ior: SceneSpectrum,
    /// Thin-walled (no `KHR_materials_volume`, or a thickness of 0): light crosses the
    /// surface without bending.
    pub thin: bool,
    /// The volume's absorption coefficient (thick only), as
    /// [`crate::materials::Material::Dielectric`]'s.
    pub absorption: Option<SceneSpectrum>,
}

impl TransmissionDesc {
    /// The glass share at texture coordinates `at`.
    pub fn factor_at(&self, at: &TexCoords) -> f32 {
        match &self.texture {
            Some(t) => self.factor * t.sample_at(at)[0],
            None => self.factor,
        }
    }
}
