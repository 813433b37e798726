use glam::{Vec2, Vec3};
use prism_sampling::distribution::positive_finite;
use prism_spectrum::SampledSpectrum;

use super::microfacet::{Ggx, Microfacet};
use super::{BsdfSample, SmoothConductor, fresnel_conductor_lanes, same_hemisphere};

/// A rough conductor: microfacets (GGX unless `D` says otherwise: Mitsuba's Beckmann,
/// [`super::Distribution`]) with complex Fresnel per lane, f = D F G / (4 cos_o cos_i)
/// (Torrance-Sparrow), sampled by visible normals. Effectively smooth roughness falls back
/// to the mirror.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughConductor<const N: usize, D = Ggx> {
    /// The microfacet distribution.
    pub distribution: D,
    /// Real part of the index per lane.
    pub eta: SampledSpectrum<N>,
    /// Extinction coefficient per lane.
    pub k: SampledSpectrum<N>,
}

impl<const N: usize, D: Microfacet> RoughConductor<N, D> {
    fn fresnel(&self, cos: f32) -> SampledSpectrum<N> {
        fresnel_conductor_lanes(cos, &self.eta, &self.k)
    }

    /// f(wo, wi) for directions on the same side (0 otherwise, and for smooth surfaces,
    /// whose lobe is a delta).
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        if !same_hemisphere(wo, wi) || self.distribution.effectively_smooth() {
            return SampledSpectrum::splat(0.0);
        }
        let (cos_o, cos_i) = (wo.z.abs(), wi.z.abs());
        let Some(wm) = (wo + wi).try_normalize() else {
            return SampledSpectrum::splat(0.0);
        };
        let wm = if wm.z < 0.0 { -wm } else { wm };
        let scale = self.distribution.d(wm) * self.distribution.g(wo, wi) / (4.0 * cos_o * cos_i);
        self.fresnel(wo.dot(wm).abs()) * scale
    }

    /// The density of [`RoughConductor::sample`] returning `wi`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if !same_hemisphere(wo, wi) || self.distribution.effectively_smooth() {
            return 0.0;
        }
        let Some(wm) = (wo + wi).try_normalize() else {
            return 0.0;
        };
        let wm = if wm.z * wo.z < 0.0 { -wm } else { wm };
        let cos = wo.dot(wm).abs();
        if cos == 0.0 {
            return 0.0;
        }
        self.distribution.d_visible(wo, wm) / (4.0 * cos)
    }

    /// Reflects `wo` about a visible normal; None if that lands below the horizon.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample<N>> {
        if self.distribution.effectively_smooth() {
            return SmoothConductor {
                eta: self.eta,
                k: self.k,
            }
            .sample(wo);
        }
        if wo.z == 0.0 || !wo.is_finite() {
            return None;
        }
        let wm = self.distribution.sample_visible_normal(wo, u);
        let wi = 2.0 * wo.dot(wm) * wm - wo;
        if !same_hemisphere(wo, wi) {
            return None;
        }
        let pdf = self.pdf(wo, wi);
        if !positive_finite(pdf) {
            return None;
        }
        Some(BsdfSample::smooth(wi, self.f(wo, wi), [pdf; N]))
    }
}
