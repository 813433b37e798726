//! The pieces Mitsuba 3's principled BSDFs share (`src/bsdfs/principledhelpers.h`):
//! Schlick's Fresnel weights, the GTR1 distribution of the clear coat, the separable
//! Smith masking-shadowing Mitsuba's microfacet lobes use, and the roughness-to-alpha map
//! with anisotropy of Burley's 2012 notes.
//!
//! B. Burley, "Physically Based Shading at Disney", SIGGRAPH 2012 course notes (§5.4 and
//! Appendix B: GTR, anisotropy, Schlick); B. Burley, "Extending the Disney BRDF to a BSDF
//! with Integrated Subsurface Scattering", SIGGRAPH 2015 course notes (§3: the
//! transmissive lobe, the thin surface).

use std::f32::consts::{PI, TAU};

use glam::{Vec2, Vec3};

use super::Ggx;

/// Schlick's weight (1 - cos)^5, cos clamped into [0, 1].
pub(crate) fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Schlick's Fresnel R0 + (1 - R0)(1 - cos)^5 at a microfacet with `cos_i` (signed: the
/// side of the relative index `eta`), on the denser side's angle: the refracted cosine
/// where light goes into the rarer medium (Mitsuba's `calc_schlick`).
pub(crate) fn schlick(r0: f32, cos_i: f32, eta: f32) -> f32 {
    let eta_it = if cos_i >= 0.0 { eta } else { 1.0 / eta };
    let cos = if eta_it > 1.0 {
        cos_i.abs()
    } else {
        let sin2_t = (1.0 - cos_i * cos_i) / (eta_it * eta_it);
        (1.0 - sin2_t).max(0.0).sqrt()
    };
    r0 + (1.0 - r0) * schlick_weight(cos)
}

/// R0 of a dielectric of relative index `eta`: ((eta - 1) / (eta + 1))^2.
pub(crate) fn schlick_r0(eta: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    r * r
}

/// GGX alphas of Burley's roughness and anisotropy (2012 notes, Appendix B.2: aspect
/// sqrt(1 - 0.9 anisotropic)), each at least 0.001 as Mitsuba's `calc_dist_params`. Not
/// clamped above: an anisotropic lobe's long axis may pass 1, as in Mitsuba.
pub(crate) fn alphas(roughness: f32, anisotropic: f32) -> Ggx {
    let r2 = roughness * roughness;
    let aspect = (1.0 - 0.9 * anisotropic).max(1e-4).sqrt();
    let a = |v: f32| if v.is_nan() { 1.0 } else { v.max(1e-3) };
    Ggx {
        alpha_x: a(r2 / aspect),
        alpha_y: a(r2 * aspect),
    }
}

/// Smith's G1 for GGX of `ggx` at microfacet `m`, zero where `v` sees the microfacet's
/// back (Mitsuba's `MicrofacetDistribution::smith_g1`).
pub(crate) fn smith_g1(ggx: &Ggx, v: Vec3, m: Vec3) -> f32 {
    if v.dot(m) * v.z <= 0.0 {
        return 0.0;
    }
    ggx.g1(v)
}

/// Separable masking-shadowing G1(wo) G1(wi), as Mitsuba's microfacet lobes use (not
/// the height-correlated form of prism's own GGX lobes).
pub(crate) fn smith_g(ggx: &Ggx, wo: Vec3, wi: Vec3, m: Vec3) -> f32 {
    smith_g1(ggx, wo, m) * smith_g1(ggx, wi, m)
}

/// The density of visible normals from `w` (on the upper side) at `m`, zero where `m`
/// faces away.
pub(crate) fn visible_pdf(ggx: &Ggx, w: Vec3, m: Vec3) -> f32 {
    let d = ggx.d_visible(w, m);
    if d.is_finite() { d } else { 0.0 }
}

/// Burley's GTR1 (Berry's) distribution of the clear coat, with roughness `alpha`
/// (2012 notes, Appendix B.1 eq. 4), isotropic.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Gtr1 {
    alpha: f32,
}

impl Gtr1 {
    /// The clear coat's distribution for Burley's `gloss` (alpha from 0.1 to 0.001).
    pub(crate) fn of_gloss(gloss: f32) -> Self {
        Self {
            alpha: 0.1 + (0.001 - 0.1) * gloss.clamp(0.0, 1.0),
        }
    }

    /// D(m).
    pub(crate) fn d(&self, m: Vec3) -> f32 {
        let a2 = self.alpha * self.alpha;
        let cos2 = m.z * m.z;
        let d = (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * cos2));
        if d * m.z > 1e-20 && d.is_finite() {
            d
        } else {
            0.0
        }
    }

    /// The density of [`Gtr1::sample`]: D(m) cos(m).
    pub(crate) fn pdf(&self, m: Vec3) -> f32 {
        if m.z < 0.0 { 0.0 } else { m.z * self.d(m) }
    }

    /// A microfacet normal distributed as D(m) cos(m) (2012 notes, Appendix B.1 eq. 5).
    pub(crate) fn sample(&self, u: Vec2) -> Vec3 {
        let a2 = self.alpha * self.alpha;
        let cos2 = (1.0 - a2.powf(1.0 - u.y)) / (1.0 - a2);
        let sin = (1.0 - cos2).max(0.0).sqrt();
        let cos = cos2.max(0.0).sqrt();
        let (s, c) = (TAU * u.x).sin_cos();
        Vec3::new(c * sin, s * sin, cos)
    }
}

/// Mitsuba's `smith_ggx1` of the clear coat (GGX's G1 of a fixed `alpha`), zero where
/// `v` sees the microfacet's back.
pub(crate) fn clearcoat_g1(v: Vec3, m: Vec3, alpha: f32) -> f32 {
    if v.dot(m) * v.z <= 0.0 {
        return 0.0;
    }
    if v.z == 1.0 {
        return 1.0;
    }
    let cos2 = v.z * v.z;
    let tan2 = (1.0 - cos2) / cos2;
    2.0 / (1.0 + (1.0 + alpha * alpha * tan2).sqrt())
}

/// Burley's diffuse with retro-reflection, blended towards his Hanrahan-Krueger-like
/// "fake subsurface" by `flatness` (2012 notes §5.3; 2015 notes §3), without 1/pi or the
/// colour: `cos_o`, `cos_i` the two directions' cosines (absolute), `cos_d` the half
/// vector's with either.
pub(crate) fn burley_diffuse(
    roughness: f32,
    flatness: f32,
    cos_o: f32,
    cos_i: f32,
    cos_d: f32,
) -> f32 {
    let (fo, fi) = (schlick_weight(cos_o), schlick_weight(cos_i));
    let f_diff = (1.0 - 0.5 * fi) * (1.0 - 0.5 * fo);
    let rr = 2.0 * roughness * cos_d * cos_d;
    let f_retro = rr * (fo + fi + fo * fi * (rr - 1.0));
    let lambert = f_diff + f_retro;
    if flatness == 0.0 {
        return lambert;
    }
    let fss90 = rr / 2.0;
    let fss = (1.0 + (fss90 - 1.0) * fo) * (1.0 + (fss90 - 1.0) * fi);
    let f_ss = 1.25 * (fss * (1.0 / (cos_o + cos_i) - 0.5) + 0.5);
    lambert + (f_ss - lambert) * flatness
}

/// Mitsuba's `luminance` of a sampled spectrum in its spectral variants: the mean over
/// the lanes of the value times the CIE 1931 y-bar at the lane's wavelength (not divided
/// by the wavelengths' density: Mitsuba's tint normalization, kept so that tints come out
/// as in Mitsuba's renders).
pub fn principled_luminance<const N: usize>(value: &[f32; N], lambdas: &[f32; N]) -> f32 {
    let observer = prism_spectrum::colorimetry::Observer::Cie1931;
    let sum: f64 = (0..N)
        .map(|k| f64::from(value[k]) * observer.cmf(f64::from(lambdas[k]))[1])
        .sum();
    (sum / N as f64) as f32
}

/// The base colour over its luminance `lum` (1 where the luminance is not positive):
/// the tint of Burley's specular and sheen tints.
pub(crate) fn tint(base: f32, lum: f32) -> f32 {
    if lum > 0.0 { base / lum } else { 1.0 }
}

/// Reflection of `v` about `m`.
pub(crate) fn reflect(v: Vec3, m: Vec3) -> Vec3 {
    2.0 * v.dot(m) * m - v
}

/// Whether `wo` and `wi` lie on the sides of microfacet `m` (oriented to `wo`'s side of
/// the surface) that a reflection (`reflection`) or a refraction needs (Mitsuba's
/// `mac_mic_compatibility`).
pub(crate) fn compatible(m: Vec3, wo: Vec3, wi: Vec3, reflection: bool) -> bool {
    let m = if wo.z < 0.0 { -m } else { m };
    if reflection {
        wo.dot(m) > 0.0 && wi.dot(m) > 0.0
    } else {
        wo.dot(m) > 0.0 && wi.dot(m) < 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gtr1_samples_its_density() {
        // The density integrates to one over the hemisphere (midpoint rule in cos).
        let g = Gtr1::of_gloss(0.3);
        let n = 4000;
        let mut total = 0.0f64;
        for i in 0..n {
            let c = (i as f32 + 0.5) / n as f32;
            let m = Vec3::new((1.0 - c * c).sqrt(), 0.0, c);
            total += f64::from(g.pdf(m)) * std::f64::consts::TAU / n as f64;
        }
        assert!((total - 1.0).abs() < 2e-2, "{total}");
        let m = g.sample(Vec2::new(0.3, 0.7));
        assert!((m.length() - 1.0).abs() < 1e-5 && m.z > 0.0);
    }

    #[test]
    fn schlick_is_r0_at_normal_incidence_and_one_at_grazing() {
        assert!((schlick(0.04, 1.0, 1.5) - 0.04).abs() < 1e-6);
        assert!((schlick(0.04, 0.0, 1.5) - 1.0).abs() < 1e-6);
        // From inside, past the critical angle: the refracted cosine is 0.
        assert!((schlick(0.04, -0.3, 1.5) - 1.0).abs() < 1e-6);
    }
}
