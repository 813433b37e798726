//! Burley's thin-surface principled BSDF as Mitsuba 3 defines it (`principledthin`,
//! `src/bsdfs/principledthin.cpp`): a sheet with no inside, alike from both sides. Light
//! reflects diffusely (Burley's diffuse, retro-reflection, fake subsurface, sheen),
//! crosses diffusely (`diff_trans`, 0 to 2 as Burley's), reflects specularly off a GGX
//! dielectric of index `eta`, and crosses specularly through it unbent, its lobe's
//! roughness scaled by (0.65 eta - 0.35) (Burley 2015 notes §3, "thin surface" and eq.
//! 3). Only `spec_trans` turns on the specular lobes: at 0 the sheet is diffuse.
//!
//! As [`super::Principled`], prism follows Mitsuba where it departs from the notes (the
//! separable masking-shadowing, the transmission's 1 / (4 cos) of a mirrored
//! reflection), and `f` is Mitsuba's `eval` without the cosine.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};
use prism_spectrum::SampledSpectrum;

use super::principled_lobes::{
    alphas, burley_diffuse, compatible, reflect, schlick, schlick_r0, schlick_weight, smith_g,
    tint, visible_pdf,
};
use super::{BsdfSample, Ggx, fresnel_dielectric};

/// The thin principled BSDF's numbers at a hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrincipledThinParams {
    /// Roughness of the specular lobes.
    pub roughness: f32,
    /// Anisotropy of the specular lobes.
    pub anisotropic: f32,
    /// Share of the specular lobes (reflection and transmission).
    pub spec_trans: f32,
    /// Tint of the specular reflection towards the base colour.
    pub spec_tint: f32,
    /// Sheen's strength.
    pub sheen: f32,
    /// Sheen's tint.
    pub sheen_tint: f32,
    /// Blend of the diffuse lobe towards the fake subsurface.
    pub flatness: f32,
    /// Diffuse transmission, 0 to 2 (Mitsuba's range; halved into a share).
    pub diff_trans: f32,
    /// The sheet's index of refraction.
    pub eta: f32,
}

/// Mitsuba's sampling rates of the thin BSDF's four lobes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrincipledThinRates {
    /// Specular reflection's.
    pub specular_reflection: f32,
    /// Specular transmission's.
    pub specular_transmission: f32,
    /// Diffuse reflection's.
    pub diffuse_reflection: f32,
    /// Diffuse transmission's.
    pub diffuse_transmission: f32,
}

impl Default for PrincipledThinRates {
    fn default() -> Self {
        Self {
            specular_reflection: 1.0,
            specular_transmission: 1.0,
            diffuse_reflection: 1.0,
            diffuse_transmission: 1.0,
        }
    }
}

/// The thin principled BSDF at one hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrincipledThin<const N: usize> {
    base: SampledSpectrum<N>,
    lum: f32,
    p: PrincipledThinParams,
    rates: PrincipledThinRates,
    /// The reflection's distribution and the transmission's (scaled roughness).
    reflection: Ggx,
    transmission: Ggx,
    axis: Vec2,
}

impl<const N: usize> PrincipledThin<N> {
    /// The BSDF of base colour `base` (clamped into [0, 1]) with Mitsuba's luminance
    /// `lum`, its parameters clamped into their ranges.
    pub fn new(
        base: SampledSpectrum<N>,
        lum: f32,
        p: PrincipledThinParams,
        rates: PrincipledThinRates,
    ) -> Self {
        let unit = |v: f32| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        let eta = if p.eta.is_finite() && p.eta > 0.0 {
            p.eta.clamp(1e-3, 1e3)
        } else {
            1.5
        };
        let p = PrincipledThinParams {
            roughness: unit(p.roughness),
            anisotropic: unit(p.anisotropic),
            spec_trans: unit(p.spec_trans),
            spec_tint: unit(p.spec_tint),
            sheen: unit(p.sheen),
            sheen_tint: unit(p.sheen_tint),
            flatness: unit(p.flatness),
            diff_trans: unit(p.diff_trans / 2.0),
            eta,
        };
        let rate = |v: f32| if v.is_finite() { v.max(0.0) } else { 0.0 };
        Self {
            base: base.map(|b| if b.is_nan() { 0.0 } else { b.clamp(0.0, 1.0) }),
            lum: if lum.is_finite() { lum } else { 0.0 },
            reflection: alphas(p.roughness, p.anisotropic),
            transmission: alphas((0.65 * eta - 0.35) * p.roughness, p.anisotropic),
            p,
            rates: PrincipledThinRates {
                specular_reflection: rate(rates.specular_reflection),
                specular_transmission: rate(rates.specular_transmission),
                diffuse_reflection: rate(rates.diffuse_reflection),
                diffuse_transmission: rate(rates.diffuse_transmission),
            },
            axis: Vec2::X,
        }
    }

    /// The same BSDF with its anisotropy along `axis` (local xy).
    pub fn with_axis(mut self, axis: Vec2) -> Self {
        if let Some(a) = axis.try_normalize() {
            self.axis = a;
        }
        self
    }

    /// `w` in the frame of the anisotropy's axis, turned to the upper side by `flip`.
    fn local(&self, w: Vec3, flip: f32) -> Vec3 {
        let (c, s) = (self.axis.x, self.axis.y);
        Vec3::new(c * w.x + s * w.y, -s * w.x + c * w.y, w.z) * flip
    }

    fn world(&self, w: Vec3, flip: f32) -> Vec3 {
        let (c, s) = (self.axis.x, self.axis.y);
        let w = w * flip;
        Vec3::new(c * w.x - s * w.y, s * w.x + c * w.y, w.z)
    }

    /// The lobes' probabilities: specular reflection, specular transmission, diffuse
    /// reflection, diffuse transmission.
    fn probabilities(&self) -> [f32; 4] {
        let (st, dt, r) = (self.p.spec_trans, self.p.diff_trans, &self.rates);
        let p = [
            st * r.specular_reflection / 2.0,
            st * r.specular_transmission / 2.0,
            r.diffuse_reflection * (1.0 - st) * (1.0 - dt),
            r.diffuse_transmission * (1.0 - st) * dt,
        ];
        let total: f32 = p.iter().sum();
        if total > 0.0 && total.is_finite() {
            p.map(|x| x / total)
        } else {
            [0.0; 4]
        }
    }

    /// The half vector of `wo` and `wi` mirrored to `wo`'s side (both local, `wo` up).
    fn half_vector(wo: Vec3, wi: Vec3) -> Option<Vec3> {
        (wo + Vec3::new(wi.x, wi.y, wi.z.abs())).try_normalize()
    }

    /// f(wo, wi) per lane.
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        let zero = SampledSpectrum::splat(0.0);
        if wo.z == 0.0 || wi.z == 0.0 || !(wo.is_finite() && wi.is_finite()) {
            return zero;
        }
        let flip = wo.z.signum();
        let (wo, wi) = (self.local(wo, flip), self.local(wi, flip));
        let Some(wh) = Self::half_vector(wo, wi) else {
            return zero;
        };
        let (ci, co) = (wo.z, wi.z);
        let p = &self.p;
        let reflect = co > 0.0;
        let mut value = zero;
        if p.spec_trans > 0.0 {
            let f_d = fresnel_dielectric(wo.dot(wh), p.eta);
            if reflect && compatible(wh, wo, wi, true) {
                let d = self.reflection.d(wh);
                let g = smith_g(&self.reflection, wo, wi, wh);
                let spec = p.spec_trans * d * g / (4.0 * ci * co);
                let r0 = schlick_r0(p.eta);
                let (lum, st) = (self.lum, p.spec_tint);
                value += self.base.map(|b| {
                    let tinted = if st > 0.0 {
                        schlick(tint(b, lum) * r0, wo.dot(wh), p.eta)
                    } else {
                        0.0
                    };
                    (f_d + (tinted - f_d) * st) * spec
                });
            }
            if !reflect && compatible(wh, wo, wi, false) {
                let d = self.transmission.d(wh);
                let g = smith_g(&self.transmission, wo, wi, wh);
                let t = p.spec_trans * (1.0 - f_d) * d * g / (4.0 * ci * co.abs());
                if t.is_finite() {
                    value += self.base * t;
                }
            }
        }
        if reflect && p.spec_trans < 1.0 && p.diff_trans < 1.0 {
            let cos_d = wh.dot(wi);
            let share = (1.0 - p.spec_trans) * (1.0 - p.diff_trans);
            let diffuse = burley_diffuse(p.roughness, p.flatness, co, ci, cos_d);
            value += self.base * (share * FRAC_1_PI * diffuse);
            if p.sheen > 0.0 {
                let w = p.sheen * share * schlick_weight(cos_d.abs());
                let (lum, st) = (self.lum, p.sheen_tint);
                value += self.base.map(|b| w * (1.0 + (tint(b, lum) - 1.0) * st));
            }
        }
        if !reflect && p.spec_trans < 1.0 && p.diff_trans > 0.0 {
            value += self.base * ((1.0 - p.spec_trans) * p.diff_trans * FRAC_1_PI);
        }
        value.map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 })
    }

    /// The solid-angle density of sampling `wi`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z == 0.0 || wi.z == 0.0 || !(wo.is_finite() && wi.is_finite()) {
            return 0.0;
        }
        let flip = wo.z.signum();
        self.pdf_local(self.local(wo, flip), self.local(wi, flip))
    }

    fn pdf_local(&self, wo: Vec3, wi: Vec3) -> f32 {
        let [p_sr, p_st, p_dr, p_dt] = self.probabilities();
        let co = wi.z;
        let reflect = co > 0.0;
        let mut pdf = 0.0;
        if self.p.spec_trans > 0.0
            && let Some(wh) = Self::half_vector(wo, wi)
        {
            let mirrored = Vec3::new(wi.x, wi.y, co.abs());
            let jacobian = (1.0 / (4.0 * mirrored.dot(wh))).abs();
            if reflect && compatible(wh, wo, wi, true) {
                pdf += p_sr * visible_pdf(&self.reflection, wo, wh) * jacobian;
            }
            if !reflect && compatible(wh, wo, wi, false) {
                pdf += p_st * visible_pdf(&self.transmission, wo, wh) * jacobian;
            }
        }
        pdf += if reflect { p_dr * co } else { p_dt * -co } * FRAC_1_PI;
        if pdf.is_finite() { pdf.max(0.0) } else { 0.0 }
    }

    /// Samples a lobe with `uc` (specular reflection, specular transmission, diffuse
    /// reflection, diffuse transmission, in Mitsuba's order) and its direction with `u`.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        if wo.z == 0.0 || !wo.is_finite() {
            return None;
        }
        let flip = wo.z.signum();
        let wo_l = self.local(wo, flip);
        let [p_sr, p_st, p_dr, _] = self.probabilities();
        let wi = if uc < p_sr {
            let m = self.reflection.sample_visible_normal(wo_l, u);
            let wi = reflect(wo_l, m);
            if wi.z <= 0.0 || !compatible(m, wo_l, wi, true) {
                return None;
            }
            wi
        } else if uc < p_sr + p_st {
            let m = self.transmission.sample_visible_normal(wo_l, u);
            let r = reflect(wo_l, m);
            let wi = Vec3::new(r.x, r.y, -r.z);
            if wi.z >= 0.0 || !compatible(m, wo_l, wi, false) {
                return None;
            }
            wi
        } else {
            let mut wi = Vec3::from(prism_sampling::warp::cosine_direction([u.x, u.y]));
            if uc >= p_sr + p_st + p_dr {
                wi.z = -wi.z;
            }
            if wi.z == 0.0 {
                return None;
            }
            wi
        };
        let wi = wi.try_normalize()?;
        let pdf = self.pdf_local(wo_l, wi);
        if pdf.is_nan() || pdf <= 0.0 {
            return None;
        }
        let wi = self.world(wi, flip);
        Some(BsdfSample::smooth(wi, self.f(wo, wi), [pdf; N]))
    }
}
