//! The reference frames of an interaction at a surface: the s-p frames of the plane of
//! incidence in which [`Mueller::reflection`] and [`Mueller::transmission`] are written.

use glam::Vec3;

use super::{FresnelAmplitudes, Mueller};

/// The s axis of light travelling along `travel` that meets a (micro)surface of normal
/// `normal`: perpendicular to the plane of incidence, `normal x travel` normalized. At
/// normal incidence every axis perpendicular to `travel` is one; a fixed one is returned.
pub fn s_axis(normal: Vec3, travel: Vec3) -> Vec3 {
    let s = normal.cross(travel);
    if s.length_squared() > 1e-12 {
        s.normalize()
    } else {
        travel.any_orthonormal_vector()
    }
}

/// A Mueller matrix together with the frames it is written in: it maps Stokes vectors of
/// the arriving light (travelling along `-wi`, basis `incident_basis`) to those of the
/// leaving light (travelling along `wo`, basis `outgoing_basis`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interaction {
    /// The matrix.
    pub mueller: Mueller,
    /// The basis vector of the arriving light's frame.
    pub incident_basis: Vec3,
    /// The basis vector of the leaving light's frame.
    pub outgoing_basis: Vec3,
}

impl Interaction {
    /// Light arriving from `wi` (pointing away from the surface) reflected or refracted
    /// into `wo` at a microsurface of normal `m` with Fresnel amplitudes `fresnel`, the
    /// matrix scaled so that its unpolarized entry `[0][0]` is `value` (the BSDF's scalar
    /// value with the unpolarized Fresnel term it already contains): the polarized
    /// counterpart of any BSDF whose only polarizing factor is Fresnel's at `m`.
    pub fn fresnel(wi: Vec3, wo: Vec3, m: Vec3, fresnel: &FresnelAmplitudes, value: f32) -> Self {
        let reflected = wi.dot(m) * wo.dot(m) > 0.0;
        let matrix = if reflected {
            Mueller::reflection(fresnel)
        } else {
            Mueller::transmission(fresnel)
        };
        let unpolarized = matrix.rows()[0][0];
        let scale = if unpolarized > 0.0 && value.is_finite() {
            value / unpolarized
        } else {
            0.0
        };
        // The plane of incidence holds -wi, m and wo, so one s axis serves both frames.
        let s = s_axis(m, -wi);
        Self {
            mueller: matrix.scaled(scale),
            incident_basis: s,
            outgoing_basis: s,
        }
    }

    /// A depolarizing interaction of scalar value `value` (diffuse reflection): any frames.
    pub fn depolarizing(wi: Vec3, wo: Vec3, value: f32) -> Self {
        Self {
            mueller: Mueller::depolarizer(value),
            incident_basis: (-wi).any_orthonormal_vector(),
            outgoing_basis: wo.any_orthonormal_vector(),
        }
    }
}
