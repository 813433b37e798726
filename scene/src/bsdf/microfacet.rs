//! The anisotropic GGX (Trowbridge-Reitz) microfacet distribution with visible-normal
//! sampling: E. Heitz, "Sampling the GGX distribution of visible normals", JCGT 7(4),
//! 2018; masking-shadowing after Heitz, "Understanding the masking-shadowing function",
//! JCGT 3(2), 2014 (height-correlated form). [`Microfacet`] is what the rough BSDFs ask
//! of a distribution, so that they take Mitsuba's Beckmann distribution
//! ([`super::beckmann::Beckmann`]) as well, each compiled for the one it holds.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};
use prism_sampling::warp::uniform_disk_concentric;

/// Roughness below which a surface is treated as perfectly smooth (a delta lobe).
pub const SMOOTH_ALPHA: f32 = 1e-3;

/// GGX with roughness `alpha_x`, `alpha_y` (clamped to at least [`SMOOTH_ALPHA`] / 10 so
/// the density stays finite).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ggx {
    /// Roughness along the tangent.
    pub alpha_x: f32,
    /// Roughness along the bitangent.
    pub alpha_y: f32,
}

impl Ggx {
    /// A distribution; NaN or tiny roughness is raised to the floor.
    pub fn new(alpha_x: f32, alpha_y: f32) -> Self {
        let floor = |a: f32| {
            if a.is_nan() {
                1.0
            } else {
                a.clamp(SMOOTH_ALPHA * 0.1, 1.0)
            }
        };
        Self {
            alpha_x: floor(alpha_x),
            alpha_y: floor(alpha_y),
        }
    }

    /// Whether the surface is effectively smooth.
    pub fn effectively_smooth(&self) -> bool {
        self.alpha_x.max(self.alpha_y) < SMOOTH_ALPHA
    }

    /// D(wm): the density of microfacet normals (projected area per solid angle).
    pub fn d(&self, wm: Vec3) -> f32 {
        let cos2 = wm.z * wm.z;
        if cos2 <= 0.0 {
            return 0.0;
        }
        let e = (wm.x / self.alpha_x).powi(2) + (wm.y / self.alpha_y).powi(2) + cos2;
        1.0 / (PI * self.alpha_x * self.alpha_y * e * e)
    }

    /// Smith's Lambda(w).
    pub fn lambda(&self, w: Vec3) -> f32 {
        let cos2 = w.z * w.z;
        if cos2 == 0.0 {
            return f32::INFINITY;
        }
        let a2_tan2 = ((w.x * self.alpha_x).powi(2) + (w.y * self.alpha_y).powi(2)) / cos2;
        ((1.0 + a2_tan2).sqrt() - 1.0) / 2.0
    }

    /// G1(w) = 1 / (1 + Lambda(w)).
    pub fn g1(&self, w: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Height-correlated G(wo, wi) = 1 / (1 + Lambda(wo) + Lambda(wi)).
    pub fn g(&self, wo: Vec3, wi: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// The density of visible normals from `w`: G1(w) max(0, w.wm) D(wm) / |cos w|.
    pub fn d_visible(&self, w: Vec3, wm: Vec3) -> f32 {
        let cos = w.z.abs();
        if cos == 0.0 {
            return 0.0;
        }
        self.g1(w) * w.dot(wm).max(0.0) * self.d(wm) / cos
    }

    /// A visible normal from `w` (Heitz 2018, Listing 1), in `w`'s hemisphere.
    pub fn sample_visible_normal(&self, w: Vec3, u: Vec2) -> Vec3 {
        let flip = w.z < 0.0;
        let w = if flip { -w } else { w };
        // Stretch to the hemisphere configuration.
        let wh = Vec3::new(self.alpha_x * w.x, self.alpha_y * w.y, w.z).normalize_or(Vec3::Z);
        let t1 = if wh.z < 0.99999 {
            Vec3::Z.cross(wh).normalize()
        } else {
            Vec3::X
        };
        let t2 = wh.cross(t1);
        // A point on the projected hemisphere: a disk squashed on one side.
        let mut p = uniform_disk_concentric(u);
        let h = (1.0 - p.x * p.x).max(0.0).sqrt();
        let s = 0.5 * (1.0 + wh.z);
        p.y = (1.0 - s) * h + s * p.y;
        let pz = (1.0 - p.length_squared()).max(0.0).sqrt();
        let nh = p.x * t1 + p.y * t2 + pz * wh;
        let wm = Vec3::new(self.alpha_x * nh.x, self.alpha_y * nh.y, nh.z.max(1e-6)).normalize();
        if flip { -wm } else { wm }
    }
}

/// What a microfacet BSDF asks of its distribution of normals (local frame, z the
/// macro-surface normal).
pub trait Microfacet: Copy + std::fmt::Debug + PartialEq {
    /// D(wm): the density of microfacet normals (projected area per solid angle).
    fn d(&self, wm: Vec3) -> f32;
    /// The masking-shadowing term G(wo, wi) of the BSDF's value.
    fn g(&self, wo: Vec3, wi: Vec3) -> f32;
    /// The density of [`Microfacet::sample_visible_normal`] returning `wm` from `w`.
    fn d_visible(&self, w: Vec3, wm: Vec3) -> f32;
    /// A normal visible from `w`, in `w`'s hemisphere.
    fn sample_visible_normal(&self, w: Vec3, u: Vec2) -> Vec3;
    /// Whether the surface is effectively smooth (a delta lobe).
    fn effectively_smooth(&self) -> bool;
    /// The larger of the two roughnesses.
    fn max_alpha(&self) -> f32;
}

impl Microfacet for Ggx {
    #[inline(always)]
    fn d(&self, wm: Vec3) -> f32 {
        Ggx::d(self, wm)
    }
    #[inline(always)]
    fn g(&self, wo: Vec3, wi: Vec3) -> f32 {
        Ggx::g(self, wo, wi)
    }
    #[inline(always)]
    fn d_visible(&self, w: Vec3, wm: Vec3) -> f32 {
        Ggx::d_visible(self, w, wm)
    }
    #[inline(always)]
    fn sample_visible_normal(&self, w: Vec3, u: Vec2) -> Vec3 {
        Ggx::sample_visible_normal(self, w, u)
    }
    #[inline(always)]
    fn effectively_smooth(&self) -> bool {
        Ggx::effectively_smooth(self)
    }
    #[inline(always)]
    fn max_alpha(&self) -> f32 {
        self.alpha_x.max(self.alpha_y)
    }
}
