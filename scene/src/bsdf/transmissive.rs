//! The glTF dielectric with `KHR_materials_transmission`: a share of it glass (thick, by
//! `KHR_materials_volume`, or a thin-walled sheet), the rest the opaque base, the glass's
//! transmitted light tinted by the base colour (glTF's specular_btdf times baseColor).

use glam::{Vec2, Vec3};
use prism_spectrum::SampledSpectrum;

use super::{BsdfSample, MetallicRoughness, RoughDielectric, ThinDielectric};

/// The glass part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Glass<const N: usize> {
    /// A volume's boundary: light refracts in and out.
    Thick(RoughDielectric<N>),
    /// A thin-walled sheet: light crosses without bending.
    Thin(ThinDielectric<N>),
}

impl<const N: usize> Glass<N> {
    fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        match self {
            Glass::Thick(g) => g.f(wo, wi),
            Glass::Thin(g) => g.f(wo, wi),
        }
    }

    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self {
            Glass::Thick(g) => g.pdf(wo, wi),
            Glass::Thin(g) => g.pdf(wo, wi),
        }
    }

    fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        match self {
            Glass::Thick(g) => g.sample(wo, uc, u),
            Glass::Thin(g) => g.sample(wo, uc, u),
        }
    }

    /// Whether its lobes have roughness alpha at most `alpha`.
    pub fn is_narrow(&self, alpha: f32) -> bool {
        let d = match self {
            Glass::Thick(g) => &g.distribution,
            Glass::Thin(g) => &g.distribution,
        };
        d.alpha_x.max(d.alpha_y) <= alpha
    }

    /// Whether its lobes are deltas.
    pub fn is_delta(&self) -> bool {
        match self {
            Glass::Thick(g) => g.distribution.effectively_smooth(),
            Glass::Thin(g) => g.distribution.effectively_smooth(),
        }
    }
}

/// f = t tint(wi) f_glass + (1 - t) f_opaque, with tint the base colour for directions
/// across the surface and 1 for reflections; sampled by choosing the glass with
/// probability t.
#[derive(Debug, Clone)]
pub struct Transmissive<'a, const N: usize> {
    /// The glass.
    pub glass: Glass<N>,
    /// What light crossing the glass is multiplied by (the base colour).
    pub tint: SampledSpectrum<N>,
    /// The opaque part (the metallic-roughness base).
    pub opaque: MetallicRoughness<'a, N>,
    /// `transmissionFactor` (times its texture), in [0, 1].
    pub transmission: f32,
}

impl<const N: usize> Transmissive<'_, N> {
    fn share(&self) -> f32 {
        if self.transmission.is_nan() {
            0.0
        } else {
            self.transmission.clamp(0.0, 1.0)
        }
    }

    fn tinted(&self, f: SampledSpectrum<N>, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        if wo.z * wi.z < 0.0 {
            f * self
                .tint
                .map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 })
        } else {
            f
        }
    }

    /// f(wo, wi) per lane, without the glass's deltas.
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        let t = self.share();
        let glass = self.tinted(self.glass.f(wo, wi), wo, wi) * t;
        if t < 1.0 {
            glass + self.opaque.f(wo, wi) * (1.0 - t)
        } else {
            glass
        }
    }

    /// The density of [`Transmissive::sample`] returning `wi` (the hero's), without the
    /// glass's deltas.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let t = self.share();
        let opaque = if t < 1.0 {
            self.opaque.pdf(wo, wi)
        } else {
            0.0
        };
        t * self.glass.pdf(wo, wi) + (1.0 - t) * opaque
    }

    /// The glass with probability t (its delta lobes weighted by it), else the opaque
    /// base; non-delta directions get the mixture's value and density.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        let t = self.share();
        let sample = if uc < t {
            let mut s = self.glass.sample(wo, (uc / t).min(1.0 - f32::EPSILON), u)?;
            if s.delta {
                s.f = self.tinted(s.f, wo, s.wi) * t;
                s.pdf = s.pdf.map(|p| p * t);
                return Some(s);
            }
            s
        } else {
            let uc = ((uc - t) / (1.0 - t)).clamp(0.0, 1.0 - f32::EPSILON);
            self.opaque.sample(wo, uc, u)?
        };
        let f = self.f(wo, sample.wi);
        let opaque_pdf = if t < 1.0 {
            self.opaque.pdf(wo, sample.wi)
        } else {
            0.0
        };
        // The glass's density per lane where a dispersive refraction gave the lanes
        // their own, else the hero's.
        let glass_hero = self.glass.pdf(wo, sample.wi);
        let pdf = std::array::from_fn(|lane| {
            let glass = if sample.wavelength_dependent {
                sample.pdf[lane]
            } else {
                glass_hero
            };
            t * glass + (1.0 - t) * opaque_pdf
        });
        Some(BsdfSample { f, pdf, ..sample })
    }

    /// Whether every lobe is a delta (all glass, smooth).
    pub fn is_delta(&self) -> bool {
        self.share() >= 1.0 && self.glass.is_delta()
    }

    /// Whether it is all glass of roughness alpha at most `alpha`.
    pub fn is_narrow(&self, alpha: f32) -> bool {
        self.share() >= 1.0 && self.glass.is_narrow(alpha)
    }
}
