//! BSDFs in a local shading frame (z is the shading normal), evaluated, sampled and given
//! a density per wavelength lane.
//!
//! A BSDF is built per hit with its spectral parameters already sampled at the path's
//! wavelengths (a `SampledSpectrum<N>`), as in *PBR* 4th ed. §9.1: the integrator never
//! sees RGB or dynamic spectra in its inner loop. Directions point away from the surface.

mod beckmann;
mod blend;
mod clearcoat;
mod coating_albedo;
mod conductor;
mod dielectric;
mod diffuse;
mod dispatch;
mod erf;
mod fluorescent;
mod gauss_legendre;
mod layered;
mod metallic_roughness;
mod microfacet;
mod perturbed;
mod plastic;
mod principled;
mod principled_lobes;
mod principled_thin;
mod rough_conductor;
mod rough_dielectric;
mod rough_plastic;
mod sheen;
mod sheet;
mod table;
mod thin_dielectric;
mod thin_film;
mod transmissive;

pub use beckmann::{Beckmann, Distribution};
pub use blend::Blend;
pub use clearcoat::{CLEARCOAT_IOR, Clearcoat, clearcoat_albedo};
pub use coating_albedo::CoatingAlbedo;
pub use conductor::{SmoothConductor, fresnel_conductor, fresnel_conductor_lanes};
pub use dielectric::{SmoothDielectric, TransportMode, fresnel_dielectric, refract};
pub use diffuse::{Diffuse, lambertian_pdf, lambertian_sample};
pub use dispatch::Bsdf;
pub use fluorescent::{
    FluorescentDiffuse, FluorescentSample, fluorescence_matrix, reradiation_matrix,
};
pub use layered::{Layered, LayeredParts};
pub use metallic_roughness::{
    DiffuseTransmission, Iridescence, MetallicRoughness, Specular, SpecularParts,
};
pub use microfacet::{Ggx, Microfacet, SMOOTH_ALPHA};
pub use perturbed::{Perturbed, shadow_terminator};
pub use plastic::{Plastic, PlasticCoating};
pub use principled::{Principled, PrincipledParams, PrincipledRates};
pub use principled_lobes::principled_luminance;
pub use principled_thin::{PrincipledThin, PrincipledThinParams, PrincipledThinRates};
pub use rough_conductor::RoughConductor;
pub use rough_dielectric::RoughDielectric;
pub use rough_plastic::{RoughPlastic, RoughPlasticCoating};
pub use sheen::{MIN_SHEEN_ROUGHNESS, Sheen};
pub use sheet::{Sheet, SheetElement};
pub use thin_dielectric::ThinDielectric;
pub use thin_film::{ThinFilm, conductor_index_from_reflectance};
pub use transmissive::{Glass, Transmissive};

use glam::Vec3;
use prism_spectrum::SampledSpectrum;

/// A sampled incident direction with its value and density.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BsdfSample<const N: usize> {
    /// Incident direction (local frame), unit length.
    pub wi: Vec3,
    /// The BSDF value f(wo, wi) per lane (for a delta lobe, the weight of the delta).
    pub f: SampledSpectrum<N>,
    /// The density of `wi` per lane, with respect to solid angle (for a delta lobe, the
    /// discrete probability of choosing it). Lanes differ only where the direction depends
    /// on wavelength (dispersion).
    pub pdf: [f32; N],
    /// Whether the lobe is a Dirac delta (specular): not reachable by light sampling.
    pub delta: bool,
    /// Whether the direction was chosen for the hero wavelength only (a dispersive delta):
    /// the path must terminate its secondary wavelengths.
    pub wavelength_dependent: bool,
    /// The relative index of refraction the hero lane crossed (the index of the side `wi`
    /// points into over that of `wo`'s side; 1 for a reflection). Radiance transported
    /// through a refraction is scaled by 1 / eta^2, and Russian roulette undoes that
    /// scale so that it does not end paths inside glass for being there (*PBR* 4th ed.
    /// §13.4, `etaScale`).
    pub eta: f32,
}

impl<const N: usize> BsdfSample<N> {
    /// A direction of a lobe with a density, whichever wavelength chose it, leaving the
    /// index of refraction as it was (a reflection, or a crossing of a thin sheet).
    pub(crate) fn smooth(wi: Vec3, f: SampledSpectrum<N>, pdf: [f32; N]) -> Self {
        Self {
            wi,
            f,
            pdf,
            delta: false,
            wavelength_dependent: false,
            eta: 1.0,
        }
    }

    /// A Dirac delta's direction, the same for every wavelength, leaving the index of
    /// refraction as it was: `pdf` is the discrete probability of choosing it.
    pub(crate) fn specular(wi: Vec3, f: SampledSpectrum<N>, pdf: [f32; N]) -> Self {
        Self {
            delta: true,
            ..Self::smooth(wi, f, pdf)
        }
    }
}

/// cos(theta) of a local direction.
pub(crate) fn cos_theta(w: Vec3) -> f32 {
    w.z
}

/// Whether two local directions lie in the same hemisphere.
pub(crate) fn same_hemisphere(a: Vec3, b: Vec3) -> bool {
    a.z * b.z > 0.0
}
