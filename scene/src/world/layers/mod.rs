//! The glTF material extensions layered on the metallic-roughness base, as a material
//! describes them (factors, textures, colours as spectra); at a hit each becomes its part
//! of the BSDF ([`crate::bsdf::MetallicRoughness`]'s specular, anisotropy and thin film,
//! [`crate::bsdf::Layered`]'s sheen and clear coat).

mod anisotropy;
mod clearcoat;
mod diffuse_transmission;
mod iridescence;
mod sheen;
mod specular;
mod transmission;

pub use anisotropy::AnisotropyDesc;
pub use clearcoat::ClearcoatDesc;
pub use diffuse_transmission::DiffuseTransmissionDesc;
pub use iridescence::IridescenceDesc;
pub use sheen::SheenDesc;
pub use specular::SpecularDesc;
pub use transmission::TransmissionDesc;

use glam::{Vec3, Vec4};

use crate::geometry::Frame;

/// The extensions a metallic-roughness material has beyond the thin film (each None
/// when absent or without effect).
#[derive(Debug, Clone, Default)]
pub struct Layers {
    /// `KHR_materials_specular`.
    pub specular: Option<SpecularDesc>,
    /// `KHR_materials_anisotropy`.
    pub anisotropy: Option<AnisotropyDesc>,
    /// `KHR_materials_clearcoat`.
    pub clearcoat: Option<ClearcoatDesc>,
    /// `KHR_materials_sheen`.
    pub sheen: Option<SheenDesc>,
    /// `KHR_materials_transmission` beyond clear thick glass (a share, a texture, thin
    /// walls, a tint).
    pub transmission: Option<TransmissionDesc>,
    /// `KHR_materials_diffuse_transmission`.
    pub diffuse_transmission: Option<DiffuseTransmissionDesc>,
}

impl Layers {
    /// Whether there is nothing to layer.
    pub fn is_empty(&self) -> bool {
        self.specular.is_none()
            && self.anisotropy.is_none()
            && self.clearcoat.is_none()
            && self.sheen.is_none()
            && self.transmission.is_none()
            && self.diffuse_transmission.is_none()
    }

    /// Whether a texture varies any of them.
    pub fn textured(&self) -> bool {
        self.specular.as_ref().is_some_and(SpecularDesc::textured)
            || self
                .anisotropy
                .as_ref()
                .is_some_and(AnisotropyDesc::textured)
            || self.clearcoat.as_ref().is_some_and(ClearcoatDesc::textured)
            || self.sheen.as_ref().is_some_and(SheenDesc::textured)
            || self
                .transmission
                .as_ref()
                .is_some_and(|t| t.texture.is_some())
            || self
                .diffuse_transmission
                .as_ref()
                .is_some_and(DiffuseTransmissionDesc::textured)
    }

    /// Whether the BSDF needs the surface's tangent at a hit (an anisotropy direction or
    /// a coat's normal texture).
    pub fn oriented(&self) -> bool {
        self.anisotropy.is_some()
            || self
                .clearcoat
                .as_ref()
                .is_some_and(|c| c.normal_texture.is_some())
    }
}

/// The surface's orientation at a hit: what anisotropy and a coat's normal texture are
/// read in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceFrame {
    /// The local shading frame (z: the shading normal), as the integrator builds it.
    pub frame: Frame,
    /// The tangent (world, xyz) with glTF's bitangent sign in w; zero where the mesh has
    /// none.
    pub tangent: Vec4,
}

impl SurfaceFrame {
    /// The frame about shading normal `normal` with `tangent`.
    pub fn new(normal: Vec3, tangent: Vec4) -> Self {
        Self {
            frame: Frame::from_normal(normal),
            tangent,
        }
    }

    /// The tangent and bitangent (world, orthonormal to the normal); None without a
    /// usable tangent.
    pub fn tangents(&self) -> Option<(Vec3, Vec3)> {
        let n = self.frame.z;
        let t = self.tangent.truncate();
        let t = (t - n * n.dot(t)).try_normalize()?;
        let sign = if self.tangent.w < 0.0 { -1.0 } else { 1.0 };
        Some((t, n.cross(t) * sign))
    }
}
