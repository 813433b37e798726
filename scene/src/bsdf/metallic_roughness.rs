use glam::{Vec2, Vec3};
use prism_sampling::distribution::positive_finite;
use prism_sampling::warp::{cosine_hemisphere, cosine_hemisphere_pdf};
use prism_spectrum::SampledSpectrum;

use super::coating_albedo::CoatingAlbedo;
use super::microfacet::Ggx;
use super::{BsdfSample, fresnel_dielectric, same_hemisphere};

/// The glTF metallic-roughness material (glTF 2.0 specification, Appendix B) as a
/// physically based, energy-conserving BSDF:
///
/// - dielectric: a GGX coating reflecting with the exact dielectric Fresnel term
///   (index `eta`, 1.5 by default) over a diffuse base whose lobe is
///   `base (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg))`, E the coating's directional
///   albedo ([`CoatingAlbedo`]). With a white base the total albedo is
///   E(mu_o) + (1 - E(mu_o)) = 1 exactly (up to the table's accuracy), and the form is
///   reciprocal (Kulla and Conty 2017).
/// - metal: GGX reflection with Schlick's Fresnel, F0 = base colour, as glTF defines it.
/// - blended by `metallic`: f = (1 - m) f_dielectric + m f_metal.
///
/// Roughness is glTF's perceptual roughness; alpha = roughness^2.
#[derive(Debug, Clone, Copy)]
pub struct MetallicRoughness<'a, const N: usize> {
    base: SampledSpectrum<N>,
    metallic: f32,
    distribution: Ggx,
    coating: &'a CoatingAlbedo,
}

impl<'a, const N: usize> MetallicRoughness<'a, N> {
    /// The material at one hit. `base` and `metallic` are clamped into [0, 1]; `coating`
    /// must be the albedo table for the material's index (glTF default 1.5).
    pub fn new(
        base: SampledSpectrum<N>,
        metallic: f32,
        roughness: f32,
        coating: &'a CoatingAlbedo,
    ) -> Self {
        let unit = |v: f32| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        let roughness = unit(roughness);
        let alpha = roughness * roughness;
        Self {
            base: base.map(unit),
            metallic: unit(metallic),
            distribution: Ggx::new(alpha, alpha),
            coating,
        }
    }

    fn alpha(&self) -> f32 {
        self.distribution.alpha_x
    }

    /// The probability of sampling the microfacet reflection lobe rather than the diffuse
    /// base: the metal's share plus the coating's albedo.
    fn specular_probability(&self, mu_o: f32) -> f32 {
        self.metallic + (1.0 - self.metallic) * self.coating.albedo(mu_o, self.alpha())
    }

    /// f(wo, wi); reflection only (0 across the surface).
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        if !same_hemisphere(wo, wi) {
            return SampledSpectrum::splat(0.0);
        }
        let (mu_o, mu_i) = (wo.z.abs(), wi.z.abs());
        let Some(wm) = (wo + wi).try_normalize() else {
            return SampledSpectrum::splat(0.0);
        };
        let wm = if wm.z < 0.0 { -wm } else { wm };
        let d = &self.distribution;
        let microfacet = d.d(wm) * d.g(wo, wi) / (4.0 * mu_o * mu_i);
        let cos_h = wo.dot(wm).abs();
        let coating = microfacet * fresnel_dielectric(cos_h, self.coating.eta());
        let alpha = self.alpha();
        let diffuse_weight = (1.0 - self.coating.albedo(mu_o, alpha))
            * (1.0 - self.coating.albedo(mu_i, alpha))
            / (std::f32::consts::PI * (1.0 - self.coating.average(alpha)));
        let schlick = (1.0 - cos_h).powi(5);
        let m = self.metallic;
        SampledSpectrum::from_fn(|i| {
            let dielectric = coating + self.base[i] * diffuse_weight;
            let metal = microfacet * (self.base[i] + (1.0 - self.base[i]) * schlick);
            (1.0 - m) * dielectric + m * metal
        })
    }

    /// The density of [`MetallicRoughness::sample`] returning `wi`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if !same_hemisphere(wo, wi) {
            return 0.0;
        }
        let Some(wm) = (wo + wi).try_normalize() else {
            return 0.0;
        };
        let wm = if wm.z * wo.z < 0.0 { -wm } else { wm };
        let specular = self.distribution.d_visible(wo, wm) / (4.0 * wo.dot(wm).abs());
        let diffuse = cosine_hemisphere_pdf(Vec3::new(wi.x, wi.y, wi.z.abs()));
        let q = self.specular_probability(wo.z.abs());
        q * specular + (1.0 - q) * diffuse
    }

    /// Chooses the reflection lobe (visible normals) or the diffuse base (cosine) with
    /// `uc`, returning the mixture density.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        if wo.z == 0.0 || !wo.is_finite() {
            return None;
        }
        let wi = if uc < self.specular_probability(wo.z.abs()) {
            let wm = self.distribution.sample_visible_normal(wo, u);
            2.0 * wo.dot(wm) * wm - wo
        } else {
            let w = cosine_hemisphere(u);
            if wo.z < 0.0 {
                Vec3::new(w.x, w.y, -w.z)
            } else {
                w
            }
        };
        if !same_hemisphere(wo, wi) {
            return None;
        }
        let pdf = self.pdf(wo, wi);
        if !positive_finite(pdf) {
            return None;
        }
        Some(BsdfSample {
            wi,
            f: self.f(wo, wi),
            pdf: [pdf; N],
            delta: false,
            wavelength_dependent: false,
            eta: 1.0,
        })
    }
}
