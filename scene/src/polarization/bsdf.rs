//! The polarized counterparts of prism's BSDFs: per lane, a Mueller matrix with its frames
//! whose unpolarized entry `[0][0]` is the scalar BSDF's value, so that a polarized render
//! carries exactly the unpolarized render's intensity for unpolarized light at one bounce
//! and adds what Fresnel's equations say about the rest.
//!
//! - Smooth and rough dielectrics and conductors: Fresnel's Mueller matrix at the
//!   (micro)facet normal with the lane's index (reflection, refraction, total internal
//!   reflection's retardance, a metal's ellipticity), as Mitsuba 3's `dielectric`,
//!   `roughdielectric`, `conductor` and `roughconductor` do in their polarized variants.
//! - Polarizing sheets (filters and wave plates): the ideal element's matrix with its axis
//!   projected across the direction of travel.
//! - Lambertian and fluorescent surfaces depolarize.
//! - glTF's metallic-roughness material: its dielectric coating's lobe by Fresnel at the
//!   microfacet normal with the coating's index (an iridescent film's amplitudes where it
//!   has one), its metal's lobe by Fresnel with the complex index that reflects the base
//!   colour at normal incidence ([`crate::bsdf::conductor_index_from_reflectance`]), the
//!   diffuse base depolarizing; each lobe carries its share of the scalar f. (Mitsuba 3's
//!   `principled` depolarizes as a whole.) Under a clear coat, the coat's lobe is
//!   Fresnel's at its index (1.5) and the base's matrices are scaled by what the coat and
//!   the sheen leave it; the sheen's lobe (a dusty fibre layer) depolarizes. The opaque
//!   part of a transmissive material depolarizes; a transmissive material's glass sampled
//!   as a smooth delta is the smooth dielectric's.
//! - Plastic: its coating's lobe (or a smooth coating's mirror) by Fresnel at the coating's
//!   index, the substrate depolarizing (what leaves it was scattered diffusely), as
//!   Mitsuba 3's polarized `plastic` does for the smooth case.

use glam::Vec3;
use num_complex::Complex64;
use prism_spectrum::SampledSpectrum;

use super::{FresnelAmplitudes, Interaction, Mueller, fresnel_amplitudes, s_axis};
use crate::bsdf::Bsdf;
use crate::bsdf::{
    CLEARCOAT_IOR, Glass, Layered, MetallicRoughness, Plastic, RoughConductor, RoughDielectric,
    Sheet, SheetElement, conductor_index_from_reflectance,
};

/// Per lane, the interaction of light arriving from `wi` and leaving towards `wo` (local
/// frame, z the shading normal) at `bsdf`, each matrix scaled so that `[0][0]` is the
/// lane's `value`: the scalar f(wo, wi) for a direction evaluated (times any factor the
/// caller folds in), or a delta lobe's weight for a sampled delta (`delta`). Directions a
/// lobe does not connect, and zero values, give zero matrices.
pub fn interactions<const N: usize>(
    bsdf: &Bsdf<'_, N>,
    wo: Vec3,
    wi: Vec3,
    value: &SampledSpectrum<N>,
    delta: bool,
) -> [Interaction; N] {
    match bsdf {
        Bsdf::Dielectric(d) => dielectric(d, wo, wi, value),
        Bsdf::Conductor(c) => conductor(c, wo, wi, value),
        Bsdf::Sheet(s) => sheet(s, wo, value),
        Bsdf::MetallicRoughness(b) => metallic_roughness(b, wo, wi, value),
        Bsdf::Layered(b) => layered(b, wo, wi, value),
        Bsdf::Plastic(b) => plastic(b, wo, wi, value, delta),
        Bsdf::Transmissive(t) if delta => match &t.glass {
            Glass::Thick(d) => dielectric(d, wo, wi, value),
            Glass::Thin(_) => depolarizing(wo, wi, value),
        },
        _ => depolarizing(wo, wi, value),
    }
}

/// Whether [`interactions`] gives `bsdf` (for a sampled delta: `delta`) anything but
/// depolarizers, whose frames do not matter: a renderer may then skip the frames.
pub fn polarizes<const N: usize>(bsdf: &Bsdf<'_, N>, delta: bool) -> bool {
    match bsdf {
        Bsdf::Dielectric(_)
        | Bsdf::Conductor(_)
        | Bsdf::Sheet(_)
        | Bsdf::MetallicRoughness(_)
        | Bsdf::Layered(_)
        | Bsdf::Plastic(_) => true,
        Bsdf::Transmissive(t) => delta && matches!(t.glass, Glass::Thick(_)),
        _ => false,
    }
}

fn depolarizing<const N: usize>(
    wo: Vec3,
    wi: Vec3,
    value: &SampledSpectrum<N>,
) -> [Interaction; N] {
    std::array::from_fn(|lane| Interaction::depolarizing(wi, wo, value[lane]))
}

/// The microfacet normal on the outside (+z) of an effectively smooth surface or of the
/// half vector `h`.
fn outside(smooth: bool, h: Option<Vec3>) -> Vec3 {
    match (smooth, h) {
        (false, Some(h)) if h.z < 0.0 => -h,
        (false, Some(h)) => h,
        _ => Vec3::Z,
    }
}

/// A dielectric interface: Fresnel at the half vector of each lane's index (the
/// generalized half vector wo + eta wi of Walter et al. 2007 for a refraction), light
/// arriving from `wi`'s side (inside when wi.z < 0, where the index inverts and total
/// internal reflection's phase appears).
fn dielectric<const N: usize>(
    d: &RoughDielectric<N>,
    wo: Vec3,
    wi: Vec3,
    value: &SampledSpectrum<N>,
) -> [Interaction; N] {
    let smooth = d.distribution.effectively_smooth();
    let reflected = wo.z * wi.z > 0.0;
    std::array::from_fn(|lane| {
        let eta = d.eta[lane];
        let h = if reflected {
            (wo + wi).try_normalize()
        } else {
            let crossing = if wo.z > 0.0 { eta } else { 1.0 / eta };
            (wi * crossing + wo).try_normalize()
        };
        let m = outside(smooth, h);
        let amplitudes =
            fresnel_amplitudes(f64::from(wi.dot(m)), Complex64::new(f64::from(eta), 0.0));
        Interaction::fresnel(wi, wo, m, &amplitudes, value[lane])
    })
}

/// A conductor: Fresnel at the half vector with the lane's complex index (a conductor has
/// no inside: the cosine's magnitude).
fn conductor<const N: usize>(
    c: &RoughConductor<N>,
    wo: Vec3,
    wi: Vec3,
    value: &SampledSpectrum<N>,
) -> [Interaction; N] {
    let m = outside(
        c.distribution.effectively_smooth(),
        (wo + wi).try_normalize(),
    );
    let cos = f64::from(wi.dot(m).abs());
    std::array::from_fn(|lane| {
        let eta = Complex64::new(f64::from(c.eta[lane]), f64::from(c.k[lane]));
        Interaction::fresnel(wi, wo, m, &fresnel_amplitudes(cos, eta), value[lane])
    })
}

/// A sheet crossed straight through (light travelling along `wo` before and after): the
/// element in the frame whose basis is its axis projected across the direction of travel.
fn sheet<const N: usize>(s: &Sheet<N>, wo: Vec3, value: &SampledSpectrum<N>) -> [Interaction; N] {
    let across = s.axis - wo * s.axis.dot(wo);
    let basis = across
        .try_normalize()
        .unwrap_or_else(|| wo.any_orthonormal_vector());
    std::array::from_fn(|lane| {
        let element = match s.element {
            SheetElement::Polarizer => Mueller::linear_polarizer(1.0),
            SheetElement::Retarder(phase) => Mueller::linear_retarder(phase[lane]),
        };
        let unpolarized = element.rows()[0][0];
        let scale = if value[lane].is_finite() {
            value[lane] / unpolarized
        } else {
            0.0
        };
        Interaction {
            mueller: element.scaled(scale),
            incident_basis: basis,
            outgoing_basis: basis,
        }
    })
}

/// glTF's metallic-roughness material: per lane, the coating's and the metal's Fresnel
/// matrices carrying their shares of f and a depolarizer the diffuse rest, all scaled by
/// `value / f` (the caller's factor). Across the surface (diffuse transmission) it
/// depolarizes.
fn metallic_roughness<const N: usize>(
    b: &MetallicRoughness<'_, N>,
    wo: Vec3,
    wi: Vec3,
    value: &SampledSpectrum<N>,
) -> [Interaction; N] {
    let Some(parts) = b.specular_parts(wo, wi) else {
        return depolarizing(wo, wi, value);
    };
    let f = b.f(wo, wi);
    let m = parts.half;
    let cos = wi.dot(m).abs();
    let eta = b.coating_ior();
    std::array::from_fn(|lane| {
        if !(f[lane] > 0.0 && value[lane].is_finite()) {
            return Interaction::depolarizing(wi, wo, 0.0);
        }
        let film = b.film().filter(|film| film.factor > 0.0);
        let amplitudes = |base_eta: f32, base_k: f32| match film {
            Some(film) => {
                let (s, p) =
                    film.film_at(lane)
                        .amplitudes(cos, film.lambdas[lane], 1.0, base_eta, base_k);
                FresnelAmplitudes {
                    s,
                    p,
                    transmitted_s: 0.0,
                    transmitted_p: 0.0,
                }
            }
            None => fresnel_amplitudes(
                f64::from(cos),
                Complex64::new(f64::from(base_eta), f64::from(base_k)),
            ),
        };
        let coating = Interaction::fresnel(wi, wo, m, &amplitudes(eta, 0.0), parts.coating[lane]);
        // A dielectric (metallic 0, most materials) has no metal lobe to evaluate.
        let metal = if parts.metal[lane] > 0.0 {
            let (eta_m, k_m) = conductor_index_from_reflectance(b.base_color()[lane]);
            let metal = Interaction::fresnel(wi, wo, m, &amplitudes(eta_m, k_m), parts.metal[lane]);
            metal.mueller.matrix()
        } else {
            glam::Mat4::ZERO
        };
        let diffuse = (f[lane] - parts.coating[lane] - parts.metal[lane]).max(0.0);
        let sum = coating.mueller.matrix() + metal + Mueller::depolarizer(diffuse).matrix();
        Interaction {
            mueller: Mueller::from_matrix(sum * (value[lane] / f[lane])),
            ..coating
        }
    })
}

/// A plastic: per lane, the coating's Fresnel matrix carrying its share of f (a sampled
/// smooth coating's mirror carries all of `value`) and a depolarizer the substrate's, all
/// scaled by `value / f`.
fn plastic<const N: usize>(
    b: &Plastic<'_, N>,
    wo: Vec3,
    wi: Vec3,
    value: &SampledSpectrum<N>,
    delta: bool,
) -> [Interaction; N] {
    let eta = Complex64::new(f64::from(b.eta()), 0.0);
    if delta {
        let amplitudes = fresnel_amplitudes(f64::from(wi.z.abs()), eta);
        return std::array::from_fn(|lane| {
            Interaction::fresnel(wi, wo, Vec3::Z, &amplitudes, value[lane])
        });
    }
    let Some((m, specular)) = b.specular_part(wo, wi) else {
        return depolarizing(wo, wi, value);
    };
    let f = b.f(wo, wi);
    let amplitudes = fresnel_amplitudes(f64::from(wi.dot(m).abs()), eta);
    std::array::from_fn(|lane| {
        if !(f[lane] > 0.0 && value[lane].is_finite()) {
            return Interaction::depolarizing(wi, wo, 0.0);
        }
        let coating = Interaction::fresnel(wi, wo, m, &amplitudes, specular);
        let substrate = Mueller::depolarizer((f[lane] - specular).max(0.0));
        let sum = coating.mueller.matrix() + substrate.matrix();
        Interaction {
            mueller: Mueller::from_matrix(sum * (value[lane] / f[lane])),
            ..coating
        }
    })
}

/// glTF's metallic-roughness under a sheen or a clear coat: the coat's lobe by Fresnel at
/// its index, the sheen depolarizing, the base's own matrices weighted by what the layers
/// leave it, all scaled by `value / f`.
fn layered<const N: usize>(
    b: &Layered<'_, N>,
    wo: Vec3,
    wi: Vec3,
    value: &SampledSpectrum<N>,
) -> [Interaction; N] {
    let Some(parts) = b.parts(wo, wi) else {
        return depolarizing(wo, wi, value);
    };
    let f = b.f(wo, wi);
    let base_f = b.base.f(wo, wi);
    let base = metallic_roughness(&b.base, wo, wi, &(base_f * parts.base_weight));
    let m = outside(false, (wo + wi).try_normalize());
    let m = if wo.z < 0.0 { -m } else { m };
    let coat_amplitudes = fresnel_amplitudes(
        f64::from(wi.dot(m).abs()),
        Complex64::new(f64::from(CLEARCOAT_IOR), 0.0),
    );
    std::array::from_fn(|lane| {
        if !(f[lane] > 0.0 && value[lane].is_finite()) {
            return Interaction::depolarizing(wi, wo, 0.0);
        }
        // Every part in the base's frame (the s axis of the half vector's plane), which the
        // coat's shares; the sheen's depolarizer has no frame.
        let coat = parts.coat.map_or(glam::Mat4::ZERO, |lobe| {
            Interaction::fresnel(wi, wo, m, &coat_amplitudes, lobe)
                .mueller
                .matrix()
        });
        let sum =
            base[lane].mueller.matrix() + coat + Mueller::depolarizer(parts.sheen[lane]).matrix();
        Interaction {
            mueller: Mueller::from_matrix(sum * (value[lane] / f[lane])),
            incident_basis: s_axis(m, -wi),
            outgoing_basis: s_axis(m, -wi),
        }
    })
}
