//! Plastic: a Lambertian substrate under a smooth or rough dielectric coating, the model
//! of Weidlich and Wilkie ("Arbitrarily layered micro-facet surfaces", GRAPHITE 2007) as
//! Mitsuba's `plastic`/`roughplastic` define it (Mitsuba 3 documentation, "Rough plastic
//! material"; W. Jakob's Mitsuba 0.5 manual, §8.2.8), so that scenes written for it look
//! the same here:
//!
//! f(wo, wi) = F(wo.h) D(h) G(wo, wi) / (4 cos_o cos_i)
//!           + rho / (1 - r_i) / (pi eta^2) t(cos_o) t(cos_i)
//!
//! - the first term is the coating's GGX reflection (Fresnel of the coating's index eta);
//! - t(mu) = 1 - E(mu) is what the coating lets through from outside, E its directional
//!   albedo;
//! - 1 / eta^2 spreads the light leaving the denser coating over the wider outside cone;
//! - r_i is what the coating reflects back inside, averaged over the cosine-weighted
//!   hemisphere: 1 / (1 - r_i) keeps the texture's colour (Mitsuba's default),
//!   1 / (1 - rho r_i) follows the inner bounces and darkens and saturates colours
//!   (`nonlinear`).
//!
//! r_i is taken from reciprocity, eta^2 (1 - r_i) = 1 - E_avg (what leaves the coating
//! from inside over all directions equals what enters it from outside: exact for a smooth
//! coating's Fresnel by the interface's reciprocity and the eta^2 scaling of radiance
//! across it, *PBR* 4th ed. §9.5.2), so a white substrate reflects everything
//! in a white furnace: E + t (1 - E_avg) / (eta^2 (1 - r_i)) = 1. A single-scattering
//! quadrature of the rough inner reflection would lose what its masking removes (at alpha
//! 0.2 and index 1.49 it gives r_i = 0.49 where reciprocity gives 0.58), and a white
//! substrate would reflect less: Mitsuba's `roughplastic` reflects 0.96 of the light at
//! alpha 0.05, 0.91 at 0.1 and 0.69 at 0.3 in a white furnace (mitsuba3 issue #1155). The
//! smooth coating is Mitsuba's `plastic` exactly (within 0.1%, scene/tests/plastic.rs).

use glam::{Vec2, Vec3};
use prism_sampling::distribution::positive_finite;
use prism_sampling::warp::{cosine_hemisphere, cosine_hemisphere_pdf};
use prism_spectrum::SampledSpectrum;

use super::coating_albedo::visible_normal_quadrature;
use super::microfacet::Ggx;
use super::{BsdfSample, fresnel_dielectric, same_hemisphere};

/// Cosines at which the coating's transmittance is tabulated (0, 1/63, ..., 1), linearly
/// interpolated between.
const NODES: usize = 64;
/// Cosines (midpoints) of the average E_avg.
const AVERAGE_STEPS: usize = 128;
/// Cells a side of the visible-normal quadrature per entry (the coarser grid of the glTF
/// coating's 32 x 32 table errs by up to 2% at alpha 0.1; this one, for 192 entries, by
/// under 0.3% against a quadrature over the outgoing hemisphere).
const QUADRATURE_SIDE: usize = 48;

/// What a plastic's coating lets through, per index and roughness: made once per material
/// at load.
#[derive(Debug, Clone, PartialEq)]
pub struct PlasticCoating {
    eta: f32,
    distribution: Ggx,
    transmittance: [f32; NODES],
    internal_reflectance: f32,
}

impl PlasticCoating {
    /// The coating of relative index `eta` (coating over outside, above 1) and GGX
    /// roughness `alpha`.
    pub fn new(eta: f32, alpha: f32) -> Self {
        let distribution = Ggx::new(alpha, alpha);
        let smooth = distribution.effectively_smooth();
        let albedo = |mu: f32, eta: f32| -> f32 {
            let mu = mu.clamp(1e-4, 1.0);
            if smooth {
                return fresnel_dielectric(mu, eta);
            }
            let wo = Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
            let [e, _] = visible_normal_quadrature(&distribution, wo, QUADRATURE_SIDE, |wm, wi| {
                let kept = distribution.g(wo, wi) / distribution.g1(wo);
                [fresnel_dielectric(wo.dot(wm), eta) * kept, 0.0]
            });
            e.clamp(0.0, 1.0)
        };
        let transmittance =
            std::array::from_fn(|i| 1.0 - albedo(i as f32 / (NODES - 1) as f32, eta));
        let average = (0..AVERAGE_STEPS)
            .map(|i| {
                let mu = (i as f32 + 0.5) / AVERAGE_STEPS as f32;
                2.0 * albedo(mu, eta) * mu / AVERAGE_STEPS as f32
            })
            .sum::<f32>();
        let internal_reflectance = (1.0 - (1.0 - average) / (eta * eta)).clamp(0.0, 0.999);
        Self {
            eta,
            distribution,
            transmittance,
            internal_reflectance,
        }
    }

    /// The coating's index.
    pub fn eta(&self) -> f32 {
        self.eta
    }

    /// The coating's microfacet distribution.
    pub fn distribution(&self) -> Ggx {
        self.distribution
    }

    /// t(mu) = 1 - E(mu): the fraction of light from cosine `mu` outside that crosses
    /// (Fresnel's exactly for a smooth coating, the table's otherwise).
    pub fn transmittance(&self, mu: f32) -> f32 {
        if self.distribution.effectively_smooth() {
            return 1.0 - fresnel_dielectric(mu.abs().min(1.0), self.eta);
        }
        let x = mu.abs().min(1.0) * (NODES - 1) as f32;
        let i = (x as usize).min(NODES - 2);
        let w = x - i as f32;
        self.transmittance[i] * (1.0 - w) + self.transmittance[i + 1] * w
    }

    /// r_i: the cosine-weighted average of what the coating reflects back inside (by
    /// reciprocity from the outside's average).
    pub fn internal_reflectance(&self) -> f32 {
        self.internal_reflectance
    }
}

/// A plastic at one hit ([`PlasticCoating`] with the substrate's reflectance sampled at
/// the path's wavelengths). Two-sided, as prism's other opaque surfaces.
#[derive(Debug, Clone, Copy)]
pub struct Plastic<'a, const N: usize> {
    coating: &'a PlasticCoating,
    /// rho / (1 - r_i) / (pi eta^2) per lane (or with rho r_i, nonlinear).
    diffuse: SampledSpectrum<N>,
    /// The share of samples the coating's lobe would get if it reflected everything:
    /// 1 / (1 + mean rho), as Mitsuba steers them.
    specular_weight: f32,
}

impl<'a, const N: usize> Plastic<'a, N> {
    /// The plastic with substrate `reflectance` (clamped to [0, 1]) under `coating`.
    pub fn new(
        reflectance: SampledSpectrum<N>,
        coating: &'a PlasticCoating,
        nonlinear: bool,
    ) -> Self {
        let rho: SampledSpectrum<N> = SampledSpectrum::from_fn(|i| {
            let r = reflectance[i];
            if r.is_nan() { 0.0 } else { r.clamp(0.0, 1.0) }
        });
        let r_i = coating.internal_reflectance;
        let scale = std::f32::consts::FRAC_1_PI / (coating.eta * coating.eta);
        let diffuse = SampledSpectrum::from_fn(|i| {
            let kept = if nonlinear {
                1.0 - rho[i] * r_i
            } else {
                1.0 - r_i
            };
            rho[i] / kept * scale
        });
        let mean = (0..N).map(|i| rho[i]).sum::<f32>() / N as f32;
        Self {
            coating,
            diffuse,
            specular_weight: 1.0 / (1.0 + mean),
        }
    }

    /// The coating's index.
    pub fn eta(&self) -> f32 {
        self.coating.eta
    }

    /// The coating's lobe alone at (wo, wi), with its microfacet normal (+z side): None
    /// where it has none (opposite sides, a smooth coating).
    pub fn specular_part(&self, wo: Vec3, wi: Vec3) -> Option<(Vec3, f32)> {
        let ggx = &self.coating.distribution;
        if !same_hemisphere(wo, wi) || ggx.effectively_smooth() {
            return None;
        }
        let wm = (wo + wi).try_normalize()?;
        let wm = if wm.z < 0.0 { -wm } else { wm };
        let value =
            fresnel_dielectric(wo.dot(wm).abs(), self.coating.eta) * ggx.d(wm) * ggx.g(wo, wi)
                / (4.0 * wo.z.abs() * wi.z.abs());
        Some((wm, value))
    }

    /// f(wo, wi) per lane (0 on opposite sides; a smooth coating's delta is not in it).
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        if !same_hemisphere(wo, wi) {
            return SampledSpectrum::splat(0.0);
        }
        let through = self.coating.transmittance(wo.z) * self.coating.transmittance(wi.z);
        let specular = self.specular_part(wo, wi).map_or(0.0, |(_, v)| v);
        self.diffuse * through + SampledSpectrum::splat(specular)
    }

    /// The probability of sampling the coating's lobe from `wo`: Mitsuba's, the lobe's
    /// weight times what the coating reflects at wo against the substrate's.
    fn specular_probability(&self, wo: Vec3) -> f32 {
        let t = self.coating.transmittance(wo.z);
        let s = (1.0 - t) * self.specular_weight;
        let d = t * (1.0 - self.specular_weight);
        if s + d > 0.0 { s / (s + d) } else { 0.0 }
    }

    /// The density of [`Plastic::sample`] returning `wi`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if !same_hemisphere(wo, wi) {
            return 0.0;
        }
        self.pdf_given(self.specular_probability(wo), wo, wi)
    }

    /// [`Plastic::pdf`] of `wi` in `wo`'s hemisphere, the coating's lobe chosen with
    /// probability `p` (what `sample` has already computed).
    fn pdf_given(&self, p: f32, wo: Vec3, wi: Vec3) -> f32 {
        let diffuse = (1.0 - p) * cosine_hemisphere_pdf(Vec3::new(wi.x, wi.y, wi.z.abs()));
        if p == 0.0 || self.coating.distribution.effectively_smooth() {
            return diffuse;
        }
        let Some(wm) = (wo + wi).try_normalize() else {
            return diffuse;
        };
        let wm = if wm.z * wo.z < 0.0 { -wm } else { wm };
        let ggx = &self.coating.distribution;
        let cos = wo.dot(wm).abs();
        if cos == 0.0 {
            return diffuse;
        }
        diffuse + p * ggx.d_visible(wo, wm) / (4.0 * cos)
    }

    /// The coating's lobe with probability [`Plastic::pdf`]'s share (`uc` chooses; a
    /// smooth coating's is a delta), the substrate's cosine lobe otherwise.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        if wo.z == 0.0 || !wo.is_finite() {
            return None;
        }
        let p = self.specular_probability(wo);
        let ggx = &self.coating.distribution;
        let wi = if uc < p {
            if ggx.effectively_smooth() {
                // The smooth coating's mirror: a delta of weight F, chosen with p.
                let cos = wo.z.abs();
                let f = fresnel_dielectric(cos, self.coating.eta) / cos;
                return Some(BsdfSample::specular(
                    Vec3::new(-wo.x, -wo.y, wo.z),
                    SampledSpectrum::splat(f),
                    [p; N],
                ));
            }
            let wm = ggx.sample_visible_normal(wo, u);
            2.0 * wo.dot(wm) * wm - wo
        } else {
            let w = cosine_hemisphere(u);
            if wo.z < 0.0 { -w } else { w }
        };
        if !same_hemisphere(wo, wi) {
            return None;
        }
        let pdf = self.pdf_given(p, wo, wi);
        if !positive_finite(pdf) {
            return None;
        }
        Some(BsdfSample::smooth(wi, self.f(wo, wi), [pdf; N]))
    }
}
