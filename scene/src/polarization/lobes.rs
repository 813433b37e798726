//! The polarized counterparts of the BSDF lobes whose only polarizing factor is Fresnel's
//! at the microfacet normal: the scalar BSDF's value per lane, carried by the Fresnel
//! Mueller matrix of that lane's index (Mitsuba 3's rough conductor does the same).

use glam::Vec3;
use num_complex::Complex64;

use super::{Interaction, fresnel_amplitudes};
use crate::bsdf::RoughConductor;

/// Per lane, the interaction of light arriving from `wi` and leaving towards `wo` (local
/// frame, z the normal) at a rough conductor: Fresnel's Mueller matrix at the half vector
/// with the lane's complex index, scaled to the lane's value of [`RoughConductor::f`].
/// Directions the lobe does not connect give zero matrices.
pub fn rough_conductor<const N: usize>(
    bsdf: &RoughConductor<N>,
    wo: Vec3,
    wi: Vec3,
) -> [Interaction; N] {
    let f = bsdf.f(wo, wi);
    let m = (wo + wi).try_normalize().unwrap_or(Vec3::Z);
    let m = if m.z < 0.0 { -m } else { m };
    let cos = f64::from(wi.dot(m).abs());
    std::array::from_fn(|lane| {
        let eta = Complex64::new(f64::from(bsdf.eta[lane]), f64::from(bsdf.k[lane]));
        Interaction::fresnel(wi, wo, m, &fresnel_amplitudes(cos, eta), f[lane])
    })
}
