//! What a medium's particles do to polarization: Rayleigh scattering polarizes, Henyey-
//! Greenstein (a phenomenological fit with no polarization of its own) depolarizes.
//!
//! Rayleigh's Mueller matrix in the frame whose basis vector is perpendicular to the
//! scattering plane (Chandrasekhar, *Radiative Transfer*, 1950, §17; Hovenier, van der Mee
//! and Domke, *Transfer of Polarized Light in Planetary Atmospheres*, 2004, §2.7): the
//! component perpendicular to the plane scatters unchanged, the parallel one by cos theta,
//! so with Q = I_perp - I_par,
//!
//! M = 3 / (16 pi) [[1 + c^2, 1 - c^2, 0, 0], [1 - c^2, 1 + c^2, 0, 0], [0, 0, 2c, 0],
//!                  [0, 0, 0, 2c]],  c = cos theta,
//!
//! whose first entry is the phase function: unpolarized light scattered at 90 degrees is
//! polarized perpendicular to the scattering plane, completely.

use glam::Vec3;

use super::Mueller;
use crate::medium::Phase;

/// The Mueller matrix of `phase` for light travelling along unit `incoming` that leaves
/// along unit `outgoing`, and its frame's basis vector (the same for the light before and
/// after: perpendicular to both directions). None for a phase function that depolarizes
/// (Henyey-Greenstein: p times a depolarizer).
pub fn phase_interaction(phase: &Phase, incoming: Vec3, outgoing: Vec3) -> Option<(Mueller, Vec3)> {
    match phase {
        Phase::HenyeyGreenstein { .. } => None,
        Phase::Rayleigh => {
            let c = incoming.dot(outgoing).clamp(-1.0, 1.0);
            let basis = incoming
                .cross(outgoing)
                .try_normalize()
                .unwrap_or_else(|| incoming.any_orthonormal_vector());
            let k = 3.0 / (16.0 * std::f32::consts::PI);
            let (a, b, d) = (k * (1.0 + c * c), k * (1.0 - c * c), k * 2.0 * c);
            Some((
                Mueller::from_rows([
                    [a, b, 0.0, 0.0],
                    [b, a, 0.0, 0.0],
                    [0.0, 0.0, d, 0.0],
                    [0.0, 0.0, 0.0, d],
                ]),
                basis,
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polarization::Stokes;

    /// At 90 degrees unpolarized light leaves completely polarized perpendicular to the
    /// scattering plane (Q = I in its frame); forward it stays unpolarized; the first
    /// entry is the phase function; Henyey-Greenstein depolarizes.
    #[test]
    fn rayleigh_polarizes_at_right_angles() {
        let (m, basis) = phase_interaction(&Phase::Rayleigh, Vec3::X, Vec3::Y).unwrap();
        assert!((basis - Vec3::Z).length() < 1e-6);
        let out = m.apply(Stokes::unpolarized(1.0)).0;
        assert!((out.x - out.y).abs() < 1e-7 && out.x > 0.0, "{out}");
        assert!((out.x - Phase::Rayleigh.p(0.0)).abs() < 1e-7);
        let (m, _) = phase_interaction(&Phase::Rayleigh, Vec3::X, Vec3::X).unwrap();
        let out = m.apply(Stokes::unpolarized(1.0)).0;
        assert!(out.y.abs() < 1e-7 && (out.x - Phase::Rayleigh.p(1.0)).abs() < 1e-7);
        let hg = Phase::henyey_greenstein(0.5).unwrap();
        assert!(phase_interaction(&hg, Vec3::X, Vec3::Y).is_none());
    }
}
