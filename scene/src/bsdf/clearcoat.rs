//! The clear coat of `KHR_materials_clearcoat`: a dielectric layer of index 1.5 on top of
//! everything, reflecting by GGX microfacets about its own normal (the coat's normal
//! texture tilts it independently of the base's).

use std::sync::OnceLock;

use glam::{Vec2, Vec3};

use super::coating_albedo::CoatingAlbedo;
use super::fresnel_dielectric;
use super::microfacet::Ggx;

/// The coat's index of refraction, fixed by the extension.
pub const CLEARCOAT_IOR: f32 = 1.5;

/// The albedo table of a coat of index [`CLEARCOAT_IOR`], built once per process.
pub fn clearcoat_albedo() -> &'static CoatingAlbedo {
    static TABLE: OnceLock<CoatingAlbedo> = OnceLock::new();
    TABLE.get_or_init(|| CoatingAlbedo::new(CLEARCOAT_IOR))
}

/// The coat at one hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clearcoat {
    /// `clearcoatFactor` (times its texture), in [0, 1]: the layer's weight.
    factor: f32,
    distribution: Ggx,
    /// The coat's normal in the local frame (z where the coat follows the base).
    normal: Vec3,
    /// The frame about `normal`: tangent and bitangent.
    tangent: Vec3,
    bitangent: Vec3,
}

impl Clearcoat {
    /// A coat of weight `factor` and perceptual `roughness` (both clamped into [0, 1])
    /// whose normal is `normal` in the local frame (None or an unusable normal: the
    /// base's).
    pub fn new(factor: f32, roughness: f32, normal: Option<Vec3>) -> Self {
        let unit = |v: f32| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        let alpha = unit(roughness) * unit(roughness);
        let normal = normal
            .and_then(|n| n.try_normalize())
            .filter(|n| n.z > 0.0)
            .unwrap_or(Vec3::Z);
        let (tangent, bitangent) = normal.any_orthonormal_pair();
        Self {
            factor: unit(factor),
            distribution: Ggx::new(alpha, alpha),
            normal,
            tangent,
            bitangent,
        }
    }

    /// The layer's weight.
    pub fn factor(&self) -> f32 {
        self.factor
    }

    fn in_coat_frame(&self, w: Vec3) -> Vec3 {
        Vec3::new(
            w.dot(self.tangent),
            w.dot(self.bitangent),
            w.dot(self.normal),
        )
    }

    fn out_of_coat_frame(&self, w: Vec3) -> Vec3 {
        w.x * self.tangent + w.y * self.bitangent + w.z * self.normal
    }

    /// What the coat reflects from `w` (its weight times its directional albedo about
    /// its own normal): what the layers below lose, seen from `w`.
    pub fn reflected(&self, w: Vec3) -> f32 {
        let mu = self.in_coat_frame(w).z;
        if mu <= 0.0 {
            return 0.0;
        }
        self.factor * clearcoat_albedo().albedo(mu, self.distribution.alpha_x)
    }

    /// The coat's lobe times its weight, f(wo, wi) for directions above both the base and
    /// the coat, with the cosine about the coat's normal where the base's will be applied
    /// (so that a tilted coat reflects its own albedo).
    pub fn f(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 || self.factor == 0.0 {
            return 0.0;
        }
        let (o, i) = (self.in_coat_frame(wo), self.in_coat_frame(wi));
        if o.z <= 0.0 || i.z <= 0.0 {
            return 0.0;
        }
        let Some(wm) = (o + i).try_normalize() else {
            return 0.0;
        };
        let d = &self.distribution;
        let lobe =
            d.d(wm) * d.g(o, i) * fresnel_dielectric(o.dot(wm), CLEARCOAT_IOR) / (4.0 * o.z * i.z);
        let f = self.factor * lobe * i.z / wi.z;
        if f.is_finite() { f } else { 0.0 }
    }

    /// The density of [`Clearcoat::sample`] returning `wi`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let (o, i) = (self.in_coat_frame(wo), self.in_coat_frame(wi));
        if o.z <= 0.0 || i.z <= 0.0 {
            return 0.0;
        }
        let Some(wm) = (o + i).try_normalize() else {
            return 0.0;
        };
        let pdf = self.distribution.d_visible(o, wm) / (4.0 * o.dot(wm));
        if pdf.is_finite() { pdf } else { 0.0 }
    }

    /// A direction reflected about a visible microfacet normal of the coat.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<Vec3> {
        let o = self.in_coat_frame(wo);
        if o.z <= 0.0 {
            return None;
        }
        let wm = self.distribution.sample_visible_normal(o, u);
        let i = 2.0 * o.dot(wm) * wm - o;
        (i.z > 0.0).then(|| self.out_of_coat_frame(i))
    }
}
