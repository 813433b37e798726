//! The anisotropic Beckmann microfacet distribution, Mitsuba 3's default for its rough
//! plugins (`include/mitsuba/render/microfacet.h`): Walter, Marschner, Li and Torrance,
//! "Microfacet models for refraction through rough surfaces", EGSR 2007, eq. 25 (D) and
//! eq. 27 (Smith's G1, with its rational approximation, which is Mitsuba's), sampled by
//! visible normals as W. Jakob, "An improved visible normal sampling routine for the
//! Beckmann distribution", 2014 (Heitz and d'Eon, EGSR 2014, §4, with the inverse CDF
//! of the slope found by Newton's method in the erf domain).
//!
//! The value uses Mitsuba's separable masking-shadowing G1(wo) G1(wi) with the rational
//! G1 (relative error below 0.35%); the sampling density uses the exact G1, which is what
//! the sampler draws from, so that f / pdf and MIS stay consistent with what is drawn.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::erf::{erf, erfinv};
use super::microfacet::{Microfacet, SMOOTH_ALPHA};

/// 1 / sqrt(pi).
const INV_SQRT_PI: f32 = 0.564_189_6;

/// Beckmann with roughness `alpha_x`, `alpha_y` (the RMS slopes along the tangent and the
/// bitangent), clamped to at least 1e-4 as Mitsuba does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Beckmann {
    /// Roughness along the tangent.
    pub alpha_x: f32,
    /// Roughness along the bitangent.
    pub alpha_y: f32,
}

impl Beckmann {
    /// A distribution; NaN roughness is 1, and roughness is kept in [1e-4, 100].
    pub fn new(alpha_x: f32, alpha_y: f32) -> Self {
        let floor = |a: f32| {
            if a.is_nan() {
                1.0
            } else {
                a.clamp(1e-4, 100.0)
            }
        };
        Self {
            alpha_x: floor(alpha_x),
            alpha_y: floor(alpha_y),
        }
    }

    /// 1 / (alpha tan(theta)) of `w` in the direction's plane, and whether `w` is the
    /// normal itself (no masking).
    fn a(&self, w: Vec3) -> (f32, bool) {
        let xy = (self.alpha_x * w.x).powi(2) + (self.alpha_y * w.y).powi(2);
        (w.z.abs() / xy.sqrt(), xy == 0.0)
    }

    /// Mitsuba's rational approximation of Smith's G1 (Walter et al. 2007, eq. 27).
    pub fn g1(&self, w: Vec3) -> f32 {
        let (a, normal) = self.a(w);
        if normal || a >= 1.6 {
            return 1.0;
        }
        (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a)
    }

    /// Smith's exact G1 = 1 / (1 + Lambda), Lambda = (erf(a) - 1) / 2 + exp(-a^2) /
    /// (2 a sqrt(pi)) (Heitz 2014, "Understanding the masking-shadowing function", eq. 80).
    pub fn g1_exact(&self, w: Vec3) -> f32 {
        let (a, normal) = self.a(w);
        if normal {
            return 1.0;
        }
        if a == 0.0 || a.is_nan() {
            return 0.0;
        }
        let lambda = 0.5 * (erf(a) - 1.0) + 0.5 * INV_SQRT_PI * (-a * a).exp() / a;
        1.0 / (1.0 + lambda.max(0.0))
    }

    /// The slopes of a visible normal of the unit-roughness distribution seen at
    /// cos(theta) `cos`, by Jakob's numerical inversion (three Newton steps in the erf
    /// domain from the analytic solution at grazing incidence).
    fn sample_slopes_unit(cos: f32, u: Vec2) -> Vec2 {
        let cos = cos.clamp(1e-6, 1.0);
        let tan = (1.0 - cos * cos).max(0.0).sqrt() / cos;
        let cot = 1.0 / tan;
        let maxval = erf(cot);
        let u = u.clamp(Vec2::splat(1e-6), Vec2::splat(1.0 - 1e-6));
        let mut x = maxval - (maxval + 1.0) * erf((-u.x.ln()).sqrt());
        // The CDF's normalization (its value at maxval).
        let target = u.x * (1.0 + maxval + INV_SQRT_PI * tan * (-cot * cot).exp());
        for _ in 0..3 {
            let slope = erfinv(x);
            let value = 1.0 + x + INV_SQRT_PI * tan * (-slope * slope).exp() - target;
            let derivative = 1.0 - slope * tan;
            let step = value / derivative;
            if step.is_finite() {
                x -= step;
            }
        }
        let limit = 1.0 - 1e-6;
        Vec2::new(
            erfinv(x.clamp(-limit, limit)),
            erfinv((2.0 * u.y - 1.0).clamp(-limit, limit)),
        )
    }
}

impl Microfacet for Beckmann {
    fn d(&self, wm: Vec3) -> f32 {
        let cos2 = wm.z * wm.z;
        if cos2 <= 0.0 {
            return 0.0;
        }
        let e = ((wm.x / self.alpha_x).powi(2) + (wm.y / self.alpha_y).powi(2)) / cos2;
        let d = (-e).exp() / (PI * self.alpha_x * self.alpha_y * cos2 * cos2);
        // Mitsuba drops values whose projection underflows.
        if d.is_finite() && d * wm.z.abs() > 1e-20 {
            d
        } else {
            0.0
        }
    }

    fn g(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.g1(wo) * self.g1(wi)
    }

    fn d_visible(&self, w: Vec3, wm: Vec3) -> f32 {
        let cos = w.z.abs();
        if cos == 0.0 {
            return 0.0;
        }
        self.g1_exact(w) * w.dot(wm).max(0.0) * self.d(wm) / cos
    }

    fn sample_visible_normal(&self, w: Vec3, u: Vec2) -> Vec3 {
        let flip = w.z < 0.0;
        let w = if flip { -w } else { w };
        // Stretch to unit roughness, sample the slopes there, rotate back to the
        // direction's azimuth and unstretch.
        let ws = Vec3::new(self.alpha_x * w.x, self.alpha_y * w.y, w.z).normalize_or(Vec3::Z);
        let r = Vec2::new(ws.x, ws.y).length();
        let (cos_phi, sin_phi) = if r > 0.0 {
            (ws.x / r, ws.y / r)
        } else {
            (1.0, 0.0)
        };
        let s = Self::sample_slopes_unit(ws.z, u);
        let slope = Vec2::new(
            (cos_phi * s.x - sin_phi * s.y) * self.alpha_x,
            (sin_phi * s.x + cos_phi * s.y) * self.alpha_y,
        );
        let wm = Vec3::new(-slope.x, -slope.y, 1.0).normalize_or(Vec3::Z);
        if flip { -wm } else { wm }
    }

    fn effectively_smooth(&self) -> bool {
        self.alpha_x.max(self.alpha_y) < SMOOTH_ALPHA
    }

    fn max_alpha(&self) -> f32 {
        self.alpha_x.max(self.alpha_y)
    }
}

/// A microfacet distribution chosen at load time (Mitsuba's `distribution`), for the
/// BSDFs that take either.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Distribution {
    /// GGX (Trowbridge-Reitz).
    Ggx(super::Ggx),
    /// Beckmann.
    Beckmann(Beckmann),
}

impl Microfacet for Distribution {
    fn d(&self, wm: Vec3) -> f32 {
        match self {
            Distribution::Ggx(d) => d.d(wm),
            Distribution::Beckmann(d) => Microfacet::d(d, wm),
        }
    }
    fn g(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self {
            Distribution::Ggx(d) => d.g(wo, wi),
            Distribution::Beckmann(d) => Microfacet::g(d, wo, wi),
        }
    }
    fn d_visible(&self, w: Vec3, wm: Vec3) -> f32 {
        match self {
            Distribution::Ggx(d) => d.d_visible(w, wm),
            Distribution::Beckmann(d) => Microfacet::d_visible(d, w, wm),
        }
    }
    fn sample_visible_normal(&self, w: Vec3, u: Vec2) -> Vec3 {
        match self {
            Distribution::Ggx(d) => d.sample_visible_normal(w, u),
            Distribution::Beckmann(d) => Microfacet::sample_visible_normal(d, w, u),
        }
    }
    fn effectively_smooth(&self) -> bool {
        match self {
            Distribution::Ggx(d) => d.effectively_smooth(),
            Distribution::Beckmann(d) => Microfacet::effectively_smooth(d),
        }
    }
    fn max_alpha(&self) -> f32 {
        match self {
            Distribution::Ggx(d) => Microfacet::max_alpha(d),
            Distribution::Beckmann(d) => Microfacet::max_alpha(d),
        }
    }
}

impl Distribution {
    /// Smith's masking G1(w) of the BSDF's value: the rational one for Beckmann (as
    /// Mitsuba), GGX's exact one.
    pub fn g1(&self, w: Vec3) -> f32 {
        match self {
            Distribution::Ggx(d) => d.g1(w),
            Distribution::Beckmann(d) => d.g1(w),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The normals' projected areas sum to the macro-surface's: integral of D cos = 1, and
    /// the visible-normal density integrates to 1 from any direction.
    #[test]
    fn d_is_normalized_and_visible_density_integrates_to_one() {
        for (ax, ay) in [(0.1f32, 0.1f32), (0.3, 0.3), (0.2, 0.6), (1.0, 1.0)] {
            let b = Beckmann::new(ax, ay);
            let n = 800;
            let (mut projected, mut visible) = (0.0f64, 0.0f64);
            let w = Vec3::new(0.6, 0.2, 0.3).normalize();
            for i in 0..n {
                for j in 0..2 * n {
                    // Uniform in (cos theta, phi) over the upper hemisphere.
                    let z = (i as f32 + 0.5) / n as f32;
                    let phi = std::f32::consts::PI * (j as f32 + 0.5) / n as f32;
                    let r = (1.0 - z * z).sqrt();
                    let wm = Vec3::new(r * phi.cos(), r * phi.sin(), z);
                    let cell = f64::from(std::f32::consts::TAU) / (2 * n * n) as f64;
                    projected += f64::from(b.d(wm) * z) * cell;
                    visible += f64::from(b.d_visible(w, wm)) * cell;
                }
            }
            assert!((projected - 1.0).abs() < 5e-3, "{ax}x{ay}: {projected}");
            assert!((visible - 1.0).abs() < 5e-3, "{ax}x{ay}: {visible}");
        }
    }

    /// The rational G1 is Mitsuba's approximation of the exact one (0.35%).
    #[test]
    fn rational_masking_approximates_the_exact_one() {
        let b = Beckmann::new(0.4, 0.4);
        for k in 1..100 {
            let cos = k as f32 / 100.0;
            let w = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
            let (approx, exact) = (b.g1(w), b.g1_exact(w));
            assert!(
                (approx - exact).abs() <= 4e-3 * exact + 1e-6,
                "{cos}: {approx} vs {exact}"
            );
        }
        assert_eq!(b.g1_exact(Vec3::Z), 1.0);
        assert_eq!(b.g1_exact(Vec3::X), 0.0);
    }
}
