//! A BSDF evaluated about a tilted shading normal (Mitsuba's `normalmap` and `bumpmap`):
//! the local frame's z is the tilted normal, and `n` the surface's own shading normal in
//! that frame. Light on the other side of the tilted normal than of `n` gives nothing,
//! and the rest is weighed by Estevez et al.'s shadowing term, as Mitsuba's adapters do
//! (see `crate::materials::Perturbation`).

use glam::{Vec2, Vec3};
use prism_spectrum::SampledSpectrum;

use super::{Bsdf, BsdfSample};

/// The nested BSDF about a tilted normal.
#[derive(Debug, Clone)]
pub struct Perturbed<'a, const N: usize> {
    /// The nested BSDF, in the tilted frame.
    pub inner: Bsdf<'a, N>,
    /// The surface's own shading normal in the tilted frame.
    pub n: Vec3,
}

impl<const N: usize> Perturbed<'_, N> {
    /// The shadowing term at `wi`, zero where `wi` lies on different sides of the two
    /// normals.
    fn weight(&self, wi: Vec3) -> f32 {
        let cos = wi.dot(self.n);
        if cos * wi.z <= 0.0 {
            return 0.0;
        }
        shadow_terminator(self.n.z, cos)
    }

    /// f(wo, wi).
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        match self.weight(wi) {
            0.0 => SampledSpectrum::splat(0.0),
            g => self.inner.f(wo, wi) * g,
        }
    }

    /// The density of sampling `wi`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wi.dot(self.n) * wi.z <= 0.0 {
            0.0
        } else {
            self.inner.pdf(wo, wi)
        }
    }

    /// The nested BSDF's sample, weighed (None where it falls on the wrong side).
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        let mut sample = self.inner.sample(wo, uc, u)?;
        match self.weight(sample.wi) {
            0.0 => None,
            g => {
                sample.f *= g;
                Some(sample)
            }
        }
    }
}

/// Estevez et al.'s shadowing term for a tilted normal whose cosine to the shading
/// normal is `cos_tilt`, at a direction of cosine `cos` to the shading normal: 1 for
/// no tilt, falling towards 0 at grazing directions (Mitsuba's `eval_shadow_terminator`).
pub fn shadow_terminator(cos_tilt: f32, cos: f32) -> f32 {
    let tan2 = |c: f32| {
        let c2 = c * c;
        (1.0 - c2).max(0.0) / c2
    };
    let alpha2 = (0.125 * tan2(cos_tilt)).min(1.0);
    let g = 2.0 / (1.0 + (1.0 + alpha2 * tan2(cos)).sqrt());
    if g.is_finite() { g } else { 0.0 }
}
