//! Collisions in a medium with a fluorescent dye, whose in-scattering adds light from other
//! wavelengths without attenuating (`prism_scene::medium::Fluorescence`).
//!
//! At a tentative collision the path integral has three terms that continue the path: real
//! scattering (sigma_s), the dye's re-emission (sigma_fo, from other wavelengths) and the
//! null collision (sigma_n = sigma_maj - sigma_a - sigma_s, straight on). The hero chooses
//! among the three in proportion to their coefficients, whose sum is S, and absorption is a
//! weight (S / sigma_maj per collision: survival biasing, as in a medium without a dye,
//! `segment`; Russian roulette ends paths). Every term keeps a positive probability wherever
//! it is positive, so the majorant needs no room of its own for the dye. The lanes keep
//! their densities as ratios, as everywhere in the volumetric tracer.

use prism_scene::medium::Fluorescence;
use prism_scene::medium::track::Collision;
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use super::ratios::Ratios;
use super::segment::{Flight, alive, null_coefficient};
use crate::transport::path::walk::Walk;
use crate::transport::throughput::Throughput;

/// Per lane, sigma_maj / S: the hero's density of an event is T_maj sigma_maj times the
/// event's coefficient over S, that is T_maj times this times the coefficient.
#[inline]
fn density_scale<const N: usize>(c: &Collision<N>) -> SampledSpectrum<N> {
    let sigma_n = null_coefficient(c);
    SampledSpectrum::from_fn(|j| {
        let total = c.point.sigma_s[j] + c.point.sigma_fo[j] + sigma_n[j];
        if total > 0.0 {
            c.sigma_maj[j] / total
        } else {
            0.0
        }
    })
}

/// The unidirectional strategy's density, per lane and over T_maj, of going straight on at
/// a collision in a medium with a dye: what shadow rays' r_u multiply by.
#[inline]
pub(crate) fn straight_density<const N: usize>(c: &Collision<N>) -> SampledSpectrum<N> {
    density_scale(c) * null_coefficient(c)
}

/// Decides a tentative collision `c` with `u` (and `next_u` for the dye's wavelengths): None
/// where the path goes straight on, else how its flight ends.
#[inline]
pub(crate) fn collide<const N: usize, T: Throughput<N>>(
    c: &Collision<N>,
    u: f32,
    next_u: &mut impl FnMut() -> f32,
    dye: &Fluorescence,
    walk: &mut Walk<N, T>,
    ratios: &mut Ratios<N>,
) -> Option<Flight> {
    let sigma_n = null_coefficient(c);
    let (s, f, n) = (c.point.sigma_s[0], c.point.sigma_fo[0], sigma_n[0]);
    let total = s + f + n;
    if total.is_nan() || total <= 0.0 {
        return Some(Flight::Ended);
    }
    let scale = density_scale(c);
    let u = u * total;
    // The event's coefficient per lane, and the hero's density over T_maj[0].
    let (coefficient, event) = if u < s {
        (c.point.sigma_s, Flight::Scattered(c.p))
    } else if u < s + f {
        (c.point.sigma_fo, Flight::Fluoresced(c.p))
    } else {
        (sigma_n, Flight::Through)
    };
    let hero = c.t_maj[0] * scale[0] * coefficient[0];
    walk.beta.scale(c.t_maj * coefficient / hero);
    ratios.r_u *= c.t_maj * scale * coefficient / hero;
    match event {
        Flight::Through => {
            ratios.r_l *= c.t_maj * c.sigma_maj / hero;
            if alive(walk, ratios) {
                None
            } else {
                Some(Flight::Ended)
            }
        }
        Flight::Fluoresced(_) => {
            // Each lane goes on at an incident wavelength drawn from the dye's kernel or
            // where the lights shine (sigma_fo is in the weight already; the draw's own
            // weight K / (pdf sigma_fo) is 1 from the kernel alone).
            let u_lambda = f64::from(next_u());
            let mut incident = *walk.transport.lambdas();
            let mut weights = SampledSpectrum::splat(0.0);
            for (j, lambda) in incident.iter_mut().enumerate() {
                if let Some((l, w)) = dye.sample_incident(*lambda, u_lambda) {
                    *lambda = l;
                    weights[j] = w;
                }
            }
            walk.beta.scale(weights);
            match SampledWavelengths::new(incident, *walk.transport.pdfs()) {
                Ok(w) if alive(walk, ratios) => {
                    walk.transport = w;
                    Some(event)
                }
                _ => Some(Flight::Ended),
            }
        }
        _ => Some(if alive(walk, ratios) {
            event
        } else {
            Flight::Ended
        }),
    }
}
