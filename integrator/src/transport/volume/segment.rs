//! A camera path's flight through one stretch of medium: emission gathered at every
//! tentative collision, and each collision real (scattered, its absorption a weight) or
//! passed (null) by the hero's probabilities, the other lanes' densities kept in the
//! ratios (pbrt-v4's `VolPathIntegrator::Li`, *PBR* 4th ed. §14.2.3; Miller, Georgiev and
//! Jarosz 2019, §4-5). Choosing by the hero and weighing every lane by its own density is
//! what keeps a chromatic medium right (the mistake of Mitsuba 3 issue #1387: a null-collision
//! probability from the hero alone, with no ratio to correct the other lanes).

use glam::{Vec2, Vec3};
use prism_sampling::distribution::positive_finite;
use prism_sampling::stream::{IndependentStream, SampleStream};
use prism_scene::geometry::Ray;
use prism_scene::medium::track::{Collision, sample_majorant_at};
use prism_scene::medium::{Medium, MediumPoint};
use prism_spectrum::SampledSpectrum;

use super::ratios::{Ratios, spectral_weight};
use crate::transport::path::walk::Walk;
use crate::transport::throughput::Throughput;

/// How a stretch of medium ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Flight {
    /// The path reached the stretch's end (a surface, or nothing).
    Through,
    /// The path scattered at this point.
    Scattered(Vec3),
    /// The path's light was re-emitted at this point by a fluorescent dye (which emits
    /// alike in every direction): it goes on at the incident wavelengths it drew.
    Fluoresced(Vec3),
    /// The path was absorbed, or no lane has weight left.
    Ended,
}

/// The numbers a path's flights draw: free-flight distances, and the collisions' kinds.
/// Independent of the Sobol dimensions, whose bounces need the same dimensions whatever
/// number of collisions came before; except that the first collision of a bounce's
/// first stretch may be drawn from a stratified pair (`first`), as its own dimensions
/// of the sample's Sobol stream.
pub(crate) struct FlightStreams {
    pub distances: IndependentStream,
    pub kinds: IndependentStream,
    /// (distance, kind) numbers for the next flight's first collision, used once.
    pub first: Option<Vec2>,
}

impl FlightStreams {
    pub(crate) fn new(seed: u64, pixel: u64, sample: u64) -> Self {
        // Streams of their own, apart from every other stream of the sample.
        const DISTANCES: u64 = 0x6d65_6469_756d_0001;
        const KINDS: u64 = 0x6d65_6469_756d_0002;
        Self {
            distances: IndependentStream::new(seed ^ DISTANCES, pixel, sample),
            kinds: IndependentStream::new(seed ^ KINDS, pixel, sample),
            first: None,
        }
    }
}

/// The null-collision coefficient per lane at a collision: what the majorant adds to the
/// medium's extinction there.
#[inline]
pub(crate) fn null_coefficient<const N: usize>(c: &Collision<N>) -> SampledSpectrum<N> {
    SampledSpectrum::from_fn(|j| {
        (c.sigma_maj[j] - c.point.sigma_a[j] - c.point.sigma_s[j]).max(0.0)
    })
}

/// Flies `walk` from `origin` along unit `direction` for `length` (infinite where nothing
/// is met) through `medium`, whose coefficients at the walk's wavelengths are `base`.
/// Emission is gathered at each tentative collision by the collision estimator unless the
/// path has used its bounces (`emits`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn fly<const N: usize, T: Throughput<N>>(
    medium: &Medium,
    base: &MediumPoint<N>,
    origin: Vec3,
    direction: Vec3,
    length: f32,
    emits: bool,
    walk: &mut Walk<N, T>,
    ratios: &mut Ratios<N>,
    numbers: &mut FlightStreams,
) -> Flight {
    let wavelengths = walk.transport;
    let emits = emits && medium.emissive();
    let mut flight = Flight::Through;
    let (u, mut first_kind) = match numbers.first.take() {
        Some(pair) => (pair.x, Some(pair.y)),
        None => (numbers.distances.next_1d(), None),
    };
    let FlightStreams {
        distances, kinds, ..
    } = numbers;
    let t_maj = sample_majorant_at(
        medium,
        base,
        &Ray::new(origin, direction, length),
        u,
        &mut || distances.next_1d(),
        &wavelengths,
        |c| {
            let hero_density = c.sigma_maj[0] * c.t_maj[0];
            if emits {
                // The collision estimator: emission epsilon at every tentative collision,
                // over the density of stopping there (sigma_maj T_maj); its strategy's
                // ratios are r_u's, times that density per lane.
                let r_e = ratios.r_u * c.sigma_maj * c.t_maj / hero_density;
                let weight = spectral_weight(&walk.package, &r_e);
                let le = c.point.emission * c.t_maj / hero_density * weight;
                walk.beta.add_emitted(&mut walk.radiance, &le, 1.0);
            }
            let u = first_kind.take().unwrap_or_else(|| kinds.next_1d());
            let decided = match medium.fluorescence() {
                None => collide(c, u, walk, ratios),
                Some(dye) => super::dye::collide(c, u, &mut || kinds.next_1d(), dye, walk, ratios),
            };
            match decided {
                Some(end) => {
                    flight = end;
                    false
                }
                None => true,
            }
        },
    );
    if flight == Flight::Through {
        // The stretch from the last collision to the end, crossed by both strategies.
        if !positive_finite(t_maj[0]) {
            return Flight::Ended;
        }
        let factor = t_maj / t_maj[0];
        walk.beta.scale(factor);
        if medium.transmittance_in_closed_form() {
            // Light sampling crosses such a medium by the closed form, with density 1
            // (`shadow`): its ratio is one over the hero's density of flying through.
            ratios.r_u *= factor;
            ratios.r_l *= 1.0 / t_maj[0];
        } else {
            ratios.scale(&factor);
        }
        if !alive(walk, ratios) {
            return Flight::Ended;
        }
    }
    flight
}

/// A tentative collision decided by the hero's probabilities: `u` over the majorant,
/// [0, sigma_t) is a real collision, the rest null. A real collision always scatters, its
/// absorption a weight (sigma_s / sigma_t per lane, over the hero's density of a real
/// collision): survival biasing, as Mitsuba 3's `volpath` does, where pbrt-v4's analog
/// scheme ends the path with probability sigma_a / sigma_maj. Absorbing ends nothing that
/// the path integral counts here (emission is gathered at every tentative collision), so
/// the weight loses no light an absorbed path would have found, and Russian roulette after
/// the scattering ends paths whose weight has faded. None: the path goes straight on;
/// else how its flight ends. Where rounding leaves no null coefficient, what would be null
/// is the real collision it is.
#[inline]
fn collide<const N: usize, T: Throughput<N>>(
    c: &Collision<N>,
    u: f32,
    walk: &mut Walk<N, T>,
    ratios: &mut Ratios<N>,
) -> Option<Flight> {
    let t = c.point.sigma_a[0] + c.point.sigma_s[0];
    let n = (c.sigma_maj[0] - t).max(0.0);
    let u = u * c.sigma_maj[0];
    if !(t > 0.0 || n > 0.0) {
        return Some(Flight::Ended);
    }
    if u < t || n <= 0.0 {
        // Lane j as hero would have collided for real with density T_maj sigma_t.
        let hero = c.t_maj[0] * t;
        let sigma_t = c.point.sigma_a + c.point.sigma_s;
        walk.beta.scale(c.t_maj * c.point.sigma_s / hero);
        ratios.r_u *= c.t_maj * sigma_t / hero;
        return Some(if alive(walk, ratios) {
            Flight::Scattered(c.p)
        } else {
            Flight::Ended
        });
    }
    // Both ratios are over the density the hero actually sampled this null collision
    // with, T_maj[0] sigma_n[0]; light sampling would have crossed it by ratio tracking,
    // with density T_maj sigma_maj per lane.
    let sigma_n = null_coefficient(c);
    let pdf = c.t_maj[0] * n;
    let factor = c.t_maj * sigma_n / pdf;
    walk.beta.scale(factor);
    ratios.r_u *= factor;
    ratios.r_l *= c.t_maj * c.sigma_maj / pdf;
    if alive(walk, ratios) {
        None
    } else {
        Some(Flight::Ended)
    }
}

/// Whether a path still carries light: some throughput, and some lane whose
/// unidirectional strategy could have made it.
#[inline]
pub(crate) fn alive<const N: usize, T: Throughput<N>>(
    walk: &Walk<N, T>,
    ratios: &Ratios<N>,
) -> bool {
    let beta = walk.beta.max_value();
    beta > 0.0 && beta.is_finite() && ratios.r_u.max_value() > 0.0
}
