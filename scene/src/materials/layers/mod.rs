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
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use crate::bsdf::{
    Bsdf, Ggx, Glass, Layered, MetallicRoughness, RoughDielectric, ThinDielectric, Transmissive,
    TransportMode,
};
use crate::geometry::Frame;
use crate::textures::TexCoords;

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

/// What the extensions of a metallic-roughness material need at a hit.
pub(crate) struct HitParameters<'m, const N: usize> {
    pub layers: Option<&'m Layers>,
    pub iridescence: Option<&'m IridescenceDesc>,
    pub at: &'m TexCoords,
    pub frame: Option<&'m SurfaceFrame>,
    pub mode: TransportMode,
    /// The base colour at the hit (tinted), which also tints what crosses glass.
    pub base: SampledSpectrum<N>,
    pub metallic: f32,
    pub roughness: f32,
}

/// The BSDF of a metallic-roughness material with extensions: `bsdf` (the bare base)
/// with specular, diffuse transmission, anisotropy and a film, then under a sheen and a
/// coat, or in part glass. Out of line, so that scenes without extensions keep the plain
/// material's code as it was (measured with callgrind on the Cornell box).
#[inline(never)]
pub(crate) fn extended_bsdf<'a, const N: usize>(
    mut bsdf: MetallicRoughness<'a, N>,
    hit: HitParameters<'_, N>,
    wavelengths: &SampledWavelengths<N>,
) -> Bsdf<'a, N> {
    let at = hit.at;
    if let Some(layers) = hit.layers {
        if let Some(specular) = &layers.specular {
            bsdf = bsdf.with_specular(specular.at(at, wavelengths));
        }
        if let Some(dt) = &layers.diffuse_transmission {
            bsdf = bsdf.with_diffuse_transmission(dt.at(at, wavelengths));
        }
        if let Some((strength, direction)) = layers
            .anisotropy
            .as_ref()
            .zip(hit.frame)
            .and_then(|(a, frame)| a.at(at, frame))
        {
            bsdf = bsdf.with_anisotropy(strength, direction);
        }
    }
    if let Some(film) = hit.iridescence {
        bsdf = bsdf.with_iridescence(film.at(at, wavelengths));
    }
    match hit.layers {
        Some(Layers {
            transmission: Some(t),
            ..
        }) => {
            let alpha = hit.roughness * hit.roughness;
            let distribution = Ggx::new(alpha, alpha);
            let eta = t.ior.at(wavelengths).0.map(|e| e.max(1e-3));
            let glass = if t.thin {
                Glass::Thin(ThinDielectric { distribution, eta })
            } else {
                Glass::Thick(RoughDielectric {
                    distribution,
                    eta,
                    mode: hit.mode,
                })
            };
            Bsdf::Transmissive(Box::new(Transmissive {
                glass,
                tint: hit.base,
                opaque: bsdf,
                // Metal does not transmit (glTF's mix of dielectric and metal by
                // `metallic`).
                transmission: t.factor_at(at) * (1.0 - hit.metallic.clamp(0.0, 1.0)),
            }))
        }
        Some(l) if l.sheen.is_some() || l.clearcoat.is_some() => Bsdf::Layered(Box::new(Layered {
            base: bsdf,
            sheen: l.sheen.as_ref().map(|s| s.at(at, wavelengths)),
            clearcoat: l.clearcoat.as_ref().map(|c| c.at(at, hit.frame)),
            mode: hit.mode,
        })),
        _ => Bsdf::MetallicRoughness(bsdf),
    }
}
