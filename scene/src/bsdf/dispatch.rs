//! The BSDF at one hit, whichever model its material became: one enum, so that the
//! integrator evaluates and samples it without dynamic dispatch.

use glam::{Vec2, Vec3};
use prism_spectrum::SampledSpectrum;

use super::microfacet::Microfacet;
use super::{
    BsdfSample, Diffuse, Distribution, Layered, MetallicRoughness, Plastic, RoughConductor,
    RoughDielectric, Sheet, ThinDielectric, Transmissive,
};

/// A BSDF at one hit, in the local frame whose z is the surface normal.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum Bsdf<'a, const N: usize> {
    /// Lambertian.
    Diffuse(Diffuse<N>),
    /// glTF metallic-roughness.
    MetallicRoughness(MetallicRoughness<'a, N>),
    /// glTF metallic-roughness under a sheen or a clear coat.
    Layered(Box<Layered<'a, N>>),
    /// glTF metallic-roughness in part (or wholly) glass.
    Transmissive(Box<Transmissive<'a, N>>),
    /// Smooth or rough dielectric.
    Dielectric(RoughDielectric<N>),
    /// Smooth or rough conductor.
    Conductor(RoughConductor<N>),
    /// A diffuse substrate under a dielectric coating.
    Plastic(Plastic<'a, N>),
    /// A polarizing filter or a wave plate.
    Sheet(Sheet<N>),
    /// Another BSDF about a tilted normal (Mitsuba's normal and bump maps).
    Perturbed(Box<super::perturbed::Perturbed<'a, N>>),
    /// Mitsuba's `principled`.
    Principled(Box<super::Principled<N>>),
    /// Mitsuba's `principledthin`.
    PrincipledThin(Box<super::PrincipledThin<N>>),
    /// Smooth or rough dielectric with a distribution chosen at load time (Mitsuba's
    /// Beckmann, or anisotropic roughness).
    MicrofacetDielectric(RoughDielectric<N, Distribution>),
    /// Smooth or rough conductor with a distribution chosen at load time.
    MicrofacetConductor(RoughConductor<N, Distribution>),
    /// A thin dielectric sheet (Mitsuba's `thindielectric`).
    ThinDielectric(ThinDielectric<N>),
    /// Mitsuba's rough plastic.
    RoughPlastic(super::RoughPlastic<'a, N>),
    /// A weighted mix of two BSDFs (Mitsuba's `blendbsdf`).
    Blend(Box<super::Blend<'a, N>>),
}

impl<const N: usize> Bsdf<'_, N> {
    /// f(wo, wi) per lane.
    #[inline(always)]
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        // Lambertian, the commonest, where it is asked: the others' code (large, once
        // inlined into one match) stays out of line.
        match self {
            Bsdf::Diffuse(b) => b.f(wo, wi),
            _ => self.f_other(wo, wi),
        }
    }

    #[inline(never)]
    fn f_other(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        match self {
            Bsdf::Diffuse(b) => b.f(wo, wi),
            Bsdf::MetallicRoughness(b) => b.f(wo, wi),
            Bsdf::Layered(b) => b.f(wo, wi),
            Bsdf::Transmissive(b) => b.f(wo, wi),
            Bsdf::Dielectric(b) => b.f(wo, wi),
            Bsdf::Conductor(b) => b.f(wo, wi),
            Bsdf::Plastic(b) => b.f(wo, wi),
            Bsdf::Sheet(_) => SampledSpectrum::splat(0.0),
            Bsdf::Perturbed(b) => b.f(wo, wi),
            Bsdf::Principled(b) => b.f(wo, wi),
            Bsdf::PrincipledThin(b) => b.f(wo, wi),
            Bsdf::MicrofacetDielectric(b) => b.f(wo, wi),
            Bsdf::MicrofacetConductor(b) => b.f(wo, wi),
            Bsdf::ThinDielectric(b) => b.f(wo, wi),
            Bsdf::RoughPlastic(b) => b.f(wo, wi),
            Bsdf::Blend(b) => b.f(wo, wi),
        }
    }

    /// The solid-angle density of sampling `wi` (the hero lane's, where lanes differ).
    #[inline(always)]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self {
            Bsdf::Diffuse(b) => b.pdf(wo, wi),
            _ => self.pdf_other(wo, wi),
        }
    }

    #[inline(never)]
    fn pdf_other(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self {
            Bsdf::Diffuse(b) => b.pdf(wo, wi),
            Bsdf::MetallicRoughness(b) => b.pdf(wo, wi),
            Bsdf::Layered(b) => b.pdf(wo, wi),
            Bsdf::Transmissive(b) => b.pdf(wo, wi),
            Bsdf::Dielectric(b) => b.pdf(wo, wi),
            Bsdf::Conductor(b) => b.pdf(wo, wi),
            Bsdf::Plastic(b) => b.pdf(wo, wi),
            Bsdf::Sheet(_) => 0.0,
            Bsdf::Perturbed(b) => b.pdf(wo, wi),
            Bsdf::Principled(b) => b.pdf(wo, wi),
            Bsdf::PrincipledThin(b) => b.pdf(wo, wi),
            Bsdf::MicrofacetDielectric(b) => b.pdf(wo, wi),
            Bsdf::MicrofacetConductor(b) => b.pdf(wo, wi),
            Bsdf::ThinDielectric(b) => b.pdf(wo, wi),
            Bsdf::RoughPlastic(b) => b.pdf(wo, wi),
            Bsdf::Blend(b) => b.pdf(wo, wi),
        }
    }

    /// Samples an incident direction with `uc` (lobe choice) and `u`.
    #[inline(always)]
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        match self {
            Bsdf::Diffuse(b) => b.sample(wo, u),
            Bsdf::MetallicRoughness(b) => b.sample(wo, uc, u),
            Bsdf::Layered(b) => b.sample(wo, uc, u),
            Bsdf::Transmissive(b) => b.sample(wo, uc, u),
            Bsdf::Dielectric(b) => b.sample(wo, uc, u),
            Bsdf::Conductor(b) => b.sample(wo, u),
            Bsdf::Plastic(b) => b.sample(wo, uc, u),
            Bsdf::Sheet(b) => b.sample(wo),
            Bsdf::Perturbed(b) => b.sample(wo, uc, u),
            Bsdf::Principled(b) => b.sample(wo, uc, u),
            Bsdf::PrincipledThin(b) => b.sample(wo, uc, u),
            Bsdf::MicrofacetDielectric(b) => b.sample(wo, uc, u),
            Bsdf::MicrofacetConductor(b) => b.sample(wo, u),
            Bsdf::ThinDielectric(b) => b.sample(wo, uc, u),
            Bsdf::RoughPlastic(b) => b.sample(wo, uc, u),
            Bsdf::Blend(b) => b.sample(wo, uc, u),
        }
    }

    /// Whether every lobe is a delta or a GGX lobe of roughness alpha at most `alpha`
    /// (on either axis): light through it is focused, a caustic. Light paths carry what
    /// reaches the camera through such a surface after a first bounce elsewhere.
    pub fn is_narrow(&self, alpha: f32) -> bool {
        match self {
            Bsdf::Dielectric(b) => b.distribution.alpha_x.max(b.distribution.alpha_y) <= alpha,
            Bsdf::Conductor(b) => b.distribution.alpha_x.max(b.distribution.alpha_y) <= alpha,
            Bsdf::Transmissive(b) => b.is_narrow(alpha),
            Bsdf::Sheet(_) => true,
            Bsdf::Perturbed(b) => b.inner.is_narrow(alpha),
            Bsdf::Blend(b) => b.is_narrow(alpha),
            Bsdf::MicrofacetDielectric(b) => b.distribution.max_alpha() <= alpha,
            Bsdf::MicrofacetConductor(b) => b.distribution.max_alpha() <= alpha,
            Bsdf::ThinDielectric(b) => b.distribution.effectively_smooth(),
            _ => false,
        }
    }

    /// Whether every lobe is a delta (light sampling cannot help).
    pub fn is_delta(&self) -> bool {
        match self {
            Bsdf::Dielectric(b) => b.distribution.effectively_smooth(),
            Bsdf::Conductor(b) => b.distribution.effectively_smooth(),
            Bsdf::Transmissive(b) => b.is_delta(),
            Bsdf::Sheet(_) => true,
            Bsdf::Perturbed(b) => b.inner.is_delta(),
            Bsdf::Blend(b) => b.is_delta(),
            Bsdf::MicrofacetDielectric(b) => b.distribution.effectively_smooth(),
            Bsdf::MicrofacetConductor(b) => b.distribution.effectively_smooth(),
            Bsdf::ThinDielectric(b) => b.distribution.effectively_smooth(),
            _ => false,
        }
    }
}
