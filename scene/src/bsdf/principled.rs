//! Burley's principled BSDF as Mitsuba 3 defines it (`principled`,
//! `src/bsdfs/principled.cpp`): a diffuse lobe with retro-reflection and a flattening
//! "fake subsurface" term, a sheen, a clear coat (GTR1), and one GGX specular lobe that
//! reflects a blend of dielectric, tinted and metallic Fresnel and, by `spec_trans`,
//! refracts through a rough dielectric of index `eta`.
//!
//! B. Burley, "Physically Based Shading at Disney", SIGGRAPH 2012 course notes; B.
//! Burley, "Extending the Disney BRDF to a BSDF with Integrated Subsurface Scattering",
//! SIGGRAPH 2015 course notes. Where Mitsuba departs from the notes prism follows Mitsuba,
//! so that a Mitsuba scene renders as Mitsuba renders it: the clear coat's value is
//! 0.25 clearcoat F D G without the notes' 1 / (4 cos_o cos_i), masking-shadowing is
//! separable, the transmitted light is tinted by sqrt(base colour), and the tints divide
//! by Mitsuba's per-path luminance ([`super::principled_luminance`]).
//!
//! The side of the surface matters as in Mitsuba: from the front (z > 0) every lobe; from
//! the back (inside an object of index `eta`) only the dielectric's reflection and
//! refraction, weighted by (1 - metallic) spec_trans. prism's `wo` is Mitsuba's `si.wi`
//! (towards the viewer) and its `wi` Mitsuba's `wo`; prism's `f` is Mitsuba's `eval`
//! without the cosine.

use glam::{Vec2, Vec3};
use prism_spectrum::SampledSpectrum;

use super::principled_lobes::{
    Gtr1, alphas, burley_diffuse, clearcoat_g1, compatible, reflect, schlick, schlick_r0,
    schlick_weight, smith_g, tint, visible_pdf,
};
use super::{BsdfSample, Ggx, TransportMode, fresnel_dielectric};

/// The principled BSDF's numbers at a hit (Mitsuba's parameters, each in [0, 1] but
/// `eta`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrincipledParams {
    /// Roughness of the specular lobe (alpha = roughness^2).
    pub roughness: f32,
    /// Anisotropy of the specular lobe (0: isotropic).
    pub anisotropic: f32,
    /// Metallic blend.
    pub metallic: f32,
    /// Share of the dielectric that transmits (the BSDF lobe).
    pub spec_trans: f32,
    /// Tint of the dielectric reflection towards the base colour.
    pub spec_tint: f32,
    /// Sheen's strength.
    pub sheen: f32,
    /// Sheen's tint towards the base colour.
    pub sheen_tint: f32,
    /// Blend of the diffuse lobe towards the fake subsurface.
    pub flatness: f32,
    /// Clear coat's strength.
    pub clearcoat: f32,
    /// Clear coat's gloss (roughness 0.1 at 0, 0.001 at 1).
    pub clearcoat_gloss: f32,
    /// Relative index of refraction (inside over outside), > 0.
    pub eta: f32,
}

/// Mitsuba's sampling rates of the lobes (its `*_sampling_rate` parameters).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrincipledRates {
    /// The diffuse lobe's.
    pub diffuse: f32,
    /// The main specular lobe's (reflection and transmission together).
    pub specular: f32,
    /// The clear coat's.
    pub clearcoat: f32,
}

impl Default for PrincipledRates {
    fn default() -> Self {
        Self {
            diffuse: 1.0,
            specular: 1.0,
            clearcoat: 1.0,
        }
    }
}

/// The principled BSDF at one hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Principled<const N: usize> {
    base: SampledSpectrum<N>,
    /// Mitsuba's luminance of the base colour (what the tints divide by).
    lum: f32,
    p: PrincipledParams,
    rates: PrincipledRates,
    ggx: Ggx,
    mode: TransportMode,
    /// The direction of anisotropy in the local frame (cos, sin of its angle from x).
    axis: Vec2,
}

impl<const N: usize> Principled<N> {
    /// The BSDF of base colour `base` (clamped into [0, 1]) with luminance `lum`, its
    /// parameters clamped into their ranges, transporting `mode`.
    pub fn new(
        base: SampledSpectrum<N>,
        lum: f32,
        p: PrincipledParams,
        rates: PrincipledRates,
        mode: TransportMode,
    ) -> Self {
        let unit = |v: f32| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        let p = PrincipledParams {
            roughness: unit(p.roughness),
            anisotropic: unit(p.anisotropic),
            metallic: unit(p.metallic),
            spec_trans: unit(p.spec_trans),
            spec_tint: unit(p.spec_tint),
            sheen: unit(p.sheen),
            sheen_tint: unit(p.sheen_tint),
            flatness: unit(p.flatness),
            clearcoat: unit(p.clearcoat),
            clearcoat_gloss: unit(p.clearcoat_gloss),
            eta: if p.eta.is_finite() && p.eta > 0.0 {
                p.eta.clamp(1e-3, 1e3)
            } else {
                1.5
            },
        };
        let rate = |v: f32| if v.is_finite() { v.max(0.0) } else { 0.0 };
        Self {
            base: base.map(|b| if b.is_nan() { 0.0 } else { b.clamp(0.0, 1.0) }),
            lum: if lum.is_finite() { lum } else { 0.0 },
            ggx: alphas(p.roughness, p.anisotropic),
            p,
            rates: PrincipledRates {
                diffuse: rate(rates.diffuse),
                specular: rate(rates.specular),
                clearcoat: rate(rates.clearcoat),
            },
            mode,
            axis: Vec2::X,
        }
    }

    /// The same BSDF with its anisotropy along `axis` (local xy, from the surface's
    /// tangent) rather than the local frame's x.
    pub fn with_axis(mut self, axis: Vec2) -> Self {
        if let Some(a) = axis.try_normalize() {
            self.axis = a;
        }
        self
    }

    /// A local direction in the frame whose x is the anisotropy's axis.
    fn along_axis(&self, w: Vec3) -> Vec3 {
        let (c, s) = (self.axis.x, self.axis.y);
        Vec3::new(c * w.x + s * w.y, -s * w.x + c * w.y, w.z)
    }

    fn out_of_axis(&self, w: Vec3) -> Vec3 {
        let (c, s) = (self.axis.x, self.axis.y);
        Vec3::new(c * w.x - s * w.y, s * w.x + c * w.y, w.z)
    }

    /// Weights of the metallic-free dielectric's reflection (`brdf`) and transmission.
    fn weights(&self) -> (f32, f32) {
        let dielectric = 1.0 - self.p.metallic;
        (
            dielectric * (1.0 - self.p.spec_trans),
            dielectric * self.p.spec_trans,
        )
    }

    /// The lobes' probabilities (specular reflection, transmission, clear coat,
    /// diffuse), normalized, for a specular microfacet of dielectric Fresnel `f_d`.
    fn probabilities(&self, front: bool, f_d: f32) -> [f32; 4] {
        let (brdf, bsdf) = self.weights();
        let r = &self.rates;
        let p = if front {
            [
                r.specular * (1.0 - bsdf * (1.0 - f_d)),
                r.specular * bsdf * (1.0 - f_d),
                0.25 * self.p.clearcoat * r.clearcoat,
                brdf * r.diffuse,
            ]
        } else if self.p.spec_trans > 0.0 {
            [f_d, 1.0 - f_d, 0.0, 0.0]
        } else {
            // Mitsuba samples no transmission where the plugin has none.
            [f_d, 0.0, 0.0, 0.0]
        };
        let total: f32 = p.iter().sum();
        if total > 0.0 && total.is_finite() {
            p.map(|x| x / total)
        } else {
            [0.0; 4]
        }
    }

    /// The half vector of `wo` and `wi` (upper side; refraction's generalized one),
    /// with eta along the path.
    fn half_vector(&self, wo: Vec3, wi: Vec3) -> Option<(Vec3, f32)> {
        let reflect = wo.z * wi.z > 0.0;
        let eta_path = if wo.z > 0.0 {
            self.p.eta
        } else {
            1.0 / self.p.eta
        };
        let wh = (wo + wi * if reflect { 1.0 } else { eta_path }).try_normalize()?;
        Some((if wh.z < 0.0 { -wh } else { wh }, eta_path))
    }

    /// f(wo, wi) per lane.
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        let zero = SampledSpectrum::splat(0.0);
        let (wo, wi) = (self.along_axis(wo), self.along_axis(wi));
        let (ci, co) = (wo.z, wi.z);
        if ci == 0.0 || co == 0.0 || !(wo.is_finite() && wi.is_finite()) {
            return zero;
        }
        let Some((wh, eta_path)) = self.half_vector(wo, wi) else {
            return zero;
        };
        let reflect = ci * co > 0.0;
        let front = ci > 0.0;
        let p = &self.p;
        let (brdf, bsdf) = self.weights();
        let dot_o = wo.dot(wh);
        let dot_i = wi.dot(wh);
        let f_d = fresnel_dielectric(dot_o, p.eta);
        let d = self.ggx.d(wh);
        let g = smith_g(&self.ggx, wo, wi, wh);
        let mut value = zero;
        if reflect && compatible(wh, wo, wi, true) {
            if f_d > 0.0 {
                let spec = d * g / (4.0 * ci.abs() * co.abs());
                let fresnel = self.principled_fresnel(f_d, dot_o, front, bsdf);
                value += fresnel * spec;
            }
            if front && p.clearcoat > 0.0 {
                let fcc = schlick(0.04, dot_o, p.eta);
                let dcc = Gtr1::of_gloss(p.clearcoat_gloss).d(wh);
                let gcc = clearcoat_g1(wo, wh, 0.25) * clearcoat_g1(wi, wh, 0.25);
                // Mitsuba's clear coat: no 1 / (4 cos_o cos_i).
                value += SampledSpectrum::splat(0.25 * p.clearcoat * fcc * dcc * gcc);
            }
        }
        if !reflect && bsdf > 0.0 && f_d < 1.0 && compatible(wh, wo, wi, false) {
            let scale = match self.mode {
                TransportMode::Radiance => 1.0 / (eta_path * eta_path),
                TransportMode::Importance => 1.0,
            };
            let denom = dot_o + eta_path * dot_i;
            let t = (scale * (1.0 - f_d) * d * g * eta_path * eta_path * dot_o * dot_i
                / (ci * denom * denom * co))
                .abs();
            if t.is_finite() {
                value += self.base.map(f32::sqrt) * (bsdf * t);
            }
        }
        if reflect && front && brdf > 0.0 {
            let cos_d = wh.dot(wi);
            let diffuse = burley_diffuse(p.roughness, p.flatness, co.abs(), ci.abs(), cos_d);
            value += self.base * (brdf * std::f32::consts::FRAC_1_PI * diffuse);
            if p.sheen > 0.0 && p.metallic < 1.0 {
                let fd = schlick_weight(cos_d.abs());
                let w = p.sheen * (1.0 - p.metallic) * fd;
                let lum = self.lum;
                let st = p.sheen_tint;
                value += self.base.map(|b| w * (1.0 + (tint(b, lum) - 1.0) * st));
            }
        }
        value.map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 })
    }

    /// Mitsuba's `principled_fresnel`: in front, the dielectric's Fresnel blended with
    /// Schlick's of the base colour (metallic) and of the tinted dielectric; behind, the
    /// dielectric's alone, weighted by the transmissive share `bsdf`.
    fn principled_fresnel(
        &self,
        f_d: f32,
        cos_i: f32,
        front: bool,
        bsdf: f32,
    ) -> SampledSpectrum<N> {
        let p = &self.p;
        if !front {
            return SampledSpectrum::splat(bsdf * f_d);
        }
        let eta_it = if cos_i >= 0.0 { p.eta } else { 1.0 / p.eta };
        let r0 = schlick_r0(eta_it);
        let lum = self.lum;
        self.base.map(|b| {
            let metal = p.metallic * schlick(b, cos_i, p.eta);
            let tinted = if p.spec_tint > 0.0 {
                (1.0 - p.metallic) * p.spec_tint * schlick(tint(b, lum) * r0, cos_i, p.eta)
            } else {
                0.0
            };
            (1.0 - p.metallic) * (1.0 - p.spec_tint) * f_d + metal + tinted
        })
    }

    /// The solid-angle density of sampling `wi`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let (wo, wi) = (self.along_axis(wo), self.along_axis(wi));
        self.pdf_local(wo, wi)
    }

    fn pdf_local(&self, wo: Vec3, wi: Vec3) -> f32 {
        let (ci, co) = (wo.z, wi.z);
        if ci == 0.0 || co == 0.0 || !(wo.is_finite() && wi.is_finite()) {
            return 0.0;
        }
        let Some((wh, eta_path)) = self.half_vector(wo, wi) else {
            return 0.0;
        };
        let reflect = ci * co > 0.0;
        let front = ci > 0.0;
        let dot_o = wo.dot(wh);
        let dot_i = wi.dot(wh);
        let f_d = fresnel_dielectric(dot_o, self.p.eta);
        let [p_sr, p_st, p_cc, p_d] = self.probabilities(front, f_d);
        let jacobian = if reflect {
            (1.0 / (4.0 * dot_i)).abs()
        } else {
            let denom = dot_o + eta_path * dot_i;
            (eta_path * eta_path * dot_i / (denom * denom)).abs()
        };
        let up = if ci < 0.0 { -wo } else { wo };
        let mut pdf = 0.0;
        if reflect {
            if compatible(wh, wo, wi, true) {
                pdf += p_sr * visible_pdf(&self.ggx, up, wh) * jacobian;
                if p_cc > 0.0 {
                    pdf += p_cc * Gtr1::of_gloss(self.p.clearcoat_gloss).pdf(wh) * jacobian;
                }
            }
            pdf += p_d * co.max(0.0) * std::f32::consts::FRAC_1_PI;
        } else if p_st > 0.0 && compatible(wh, wo, wi, false) {
            pdf += p_st * visible_pdf(&self.ggx, up, wh) * jacobian;
        }
        if pdf.is_finite() { pdf.max(0.0) } else { 0.0 }
    }

    /// Samples a lobe with `uc` (diffuse, clear coat, transmission, reflection, in
    /// Mitsuba's order) and its direction with `u`.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        let wo_l = self.along_axis(wo);
        let ci = wo_l.z;
        if ci == 0.0 || !wo_l.is_finite() {
            return None;
        }
        let front = ci > 0.0;
        let (_, bsdf) = self.weights();
        if !front && bsdf <= 0.0 {
            return None;
        }
        let up = if front { wo_l } else { -wo_l };
        let m = self.ggx.sample_visible_normal(up, u);
        let dot_o = wo_l.dot(m);
        let f_d = fresnel_dielectric(dot_o, self.p.eta);
        let [_, p_st, p_cc, p_d] = self.probabilities(front, f_d);
        let mut eta = 1.0;
        let wi = if uc < p_d {
            let wi = Vec3::from(prism_sampling::warp::cosine_direction([u.x, u.y]));
            if wi.z <= 0.0 {
                return None;
            }
            wi
        } else if uc < p_d + p_cc {
            let m = Gtr1::of_gloss(self.p.clearcoat_gloss).sample(u);
            let wi = reflect(wo_l, m);
            if ci * wi.z <= 0.0 || !compatible(m, wo_l, wi, true) {
                return None;
            }
            wi
        } else if uc < p_d + p_cc + p_st {
            let eta_it = if dot_o >= 0.0 {
                self.p.eta
            } else {
                1.0 / self.p.eta
            };
            let eta_ti = 1.0 / eta_it;
            let cos2_t = 1.0 - (1.0 - dot_o * dot_o) * eta_ti * eta_ti;
            if cos2_t <= 0.0 {
                return None;
            }
            let cos_t = -cos2_t.sqrt().copysign(dot_o);
            let wi = m * (dot_o * eta_ti + cos_t) - wo_l * eta_ti;
            if ci * wi.z >= 0.0 || !compatible(m, wo_l, wi, false) {
                return None;
            }
            eta = eta_it;
            wi
        } else {
            let wi = reflect(wo_l, m);
            if ci * wi.z <= 0.0 || !compatible(m, wo_l, wi, true) {
                return None;
            }
            wi
        };
        let wi = wi.try_normalize()?;
        let pdf = self.pdf_local(wo_l, wi);
        if pdf.is_nan() || pdf <= 0.0 {
            return None;
        }
        let wi = self.out_of_axis(wi);
        let mut s = BsdfSample::smooth(wi, self.f(wo, wi), [pdf; N]);
        s.eta = eta;
        Some(s)
    }
}
