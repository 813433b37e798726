//! A mix of two BSDFs by a weight (Mitsuba's `blendbsdf`: f = (1 - w) f_0 + w f_1, the
//! weight a number or a texture read at the hit). Sampling picks one by the weight and
//! gives the mixture's value and density at what it drew, as Mitsuba's does; a delta
//! lobe (which the other BSDF cannot reach) keeps its own value and density times its
//! share.

use glam::{Vec2, Vec3};
use prism_spectrum::SampledSpectrum;

use super::{Bsdf, BsdfSample};

/// Two BSDFs and the second's weight.
#[derive(Debug, Clone)]
pub struct Blend<'a, const N: usize> {
    /// The BSDF weighed by 1 - `weight`.
    pub first: Bsdf<'a, N>,
    /// The BSDF weighed by `weight`.
    pub second: Bsdf<'a, N>,
    /// The second's weight, in [0, 1].
    pub weight: f32,
}

impl<const N: usize> Blend<'_, N> {
    /// f(wo, wi).
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        let w = self.weight;
        let mut f = SampledSpectrum::splat(0.0);
        if w < 1.0 {
            f += self.first.f(wo, wi) * (1.0 - w);
        }
        if w > 0.0 {
            f += self.second.f(wo, wi) * w;
        }
        f
    }

    /// The density of [`Blend::sample`] returning `wi`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let w = self.weight;
        let mut pdf = 0.0;
        if w < 1.0 {
            pdf += self.first.pdf(wo, wi) * (1.0 - w);
        }
        if w > 0.0 {
            pdf += self.second.pdf(wo, wi) * w;
        }
        pdf
    }

    /// One of the two by `uc` against the weight (the rest of `uc` rescaled for it).
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        let w = self.weight;
        let second = uc < w;
        let (chosen, other, share, uc) = if second {
            (&self.second, &self.first, w, uc / w)
        } else {
            (&self.first, &self.second, 1.0 - w, (uc - w) / (1.0 - w))
        };
        let mut s = chosen.sample(wo, uc.clamp(0.0, 1.0 - f32::EPSILON), u)?;
        // A delta (or a direction only the hero's wavelength took) is the chosen lobe's
        // alone: the other BSDF has no density there.
        if s.delta || s.wavelength_dependent || share >= 1.0 {
            s.f *= share;
            s.pdf = s.pdf.map(|p| p * share);
            return Some(s);
        }
        let other_pdf = other.pdf(wo, s.wi) * (1.0 - share);
        s.pdf = s.pdf.map(|p| p * share + other_pdf);
        s.f = self.f(wo, s.wi);
        Some(s)
    }

    /// Whether both are narrow ([`Bsdf::is_narrow`]).
    pub fn is_narrow(&self, alpha: f32) -> bool {
        self.first.is_narrow(alpha) && self.second.is_narrow(alpha)
    }

    /// Whether both are deltas.
    pub fn is_delta(&self) -> bool {
        self.first.is_delta() && self.second.is_delta()
    }
}
