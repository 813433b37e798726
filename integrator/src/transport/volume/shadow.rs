//! Next-event estimation through media: a shadow ray crosses interfaces (any other
//! surface blocks it), and its transmittance through each medium on the way is estimated
//! by ratio tracking against the majorant, with the ratios of both strategies
//! (*PBR* 4th ed. §14.2.3 `SampleLd`; Novák, Selle and Jarosz 2014 for ratio tracking),
//! and Russian roulette where little is left. Through a medium whose majorant is its
//! extinction (homogeneous, neither glowing nor dyed) ratio tracking could only say all or
//! nothing, so the transmittance there is the closed form exp(-sigma_t d), as Mitsuba 3's
//! `volpath` does for homogeneous media; the path side's ratios match it (`segment`).

use prism_sampling::distribution::positive_finite;
use prism_sampling::stream::SampleStream;
use prism_scene::geometry::Ray;
use prism_scene::medium::track::{self, sample_majorant_at};
use prism_scene::world::EmissionCache;
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use super::dye::straight_density;
use super::ratios::Ratios;
use super::segment::{FlightStreams, null_coefficient};
use super::stack::MediumStack;
use crate::transport::context::Integrator;

/// Interfaces a shadow ray crosses at most (coplanar or degenerate boundaries end it).
const MAX_CROSSINGS: u32 = 256;

/// The transmittance estimate below which ratio tracking plays Russian roulette.
const ROULETTE_BELOW: f32 = 0.05;

/// What a shadow ray found between a vertex and a light.
pub(crate) struct Shadow<const N: usize> {
    /// The ratio-tracking transmittance per lane (over the hero's tracking density).
    pub transmittance: SampledSpectrum<N>,
    /// The shadow ray's own r_u, r_l (as [`Ratios`]).
    pub ratios: Ratios<N>,
}

impl Integrator<'_> {
    /// Traces `ray` (unit direction, ending short of the light) from a vertex inside
    /// `media`, at `wavelengths` (the media's coefficients there kept in `cache`): None
    /// where a surface other than an interface blocks it or no light is left, else the
    /// transmittance and ratios, and the rays traced.
    pub(crate) fn shadow<const N: usize>(
        &self,
        mut ray: Ray,
        mut media: MediumStack,
        wavelengths: &SampledWavelengths<N>,
        numbers: &mut FlightStreams,
        cache: &mut EmissionCache<N>,
    ) -> (Option<Shadow<N>>, u64) {
        let mut transmittance = SampledSpectrum::splat(1.0);
        let mut ratios = Ratios::one();
        let mut rays = 0;
        let direction = ray.direction;
        for _ in 0..MAX_CROSSINGS {
            rays += 1;
            let hit = self.scene.intersect(&ray);
            if let Some(h) = &hit
                && !self.scene.is_interface(h)
            {
                return (None, rays);
            }
            if let Some(m) = media.current() {
                let medium = self.scene.media().get(m);
                let base = cache.medium(m, medium, wavelengths);
                let length = hit.as_ref().map_or(ray.t_max, |h| h.t);
                if medium.transmittance_in_closed_form() {
                    // Light sampling crosses the stretch with density 1 and the exact
                    // transmittance; unidirectional sampling would have flown through it
                    // with density T per lane (no null collisions to meet in such a medium).
                    let crossed = track::transmittance(&(base.sigma_a + base.sigma_s), length);
                    transmittance *= crossed;
                    ratios.r_u *= crossed;
                    if transmittance.is_black() {
                        return (None, rays);
                    }
                } else {
                    let dyed = medium.fluorescence().is_some();
                    let u = numbers.distances.next_1d();
                    let FlightStreams {
                        distances, kinds, ..
                    } = numbers;
                    let t_maj = sample_majorant_at(
                        medium,
                        &base,
                        &Ray::new(ray.origin, direction, length),
                        u,
                        &mut || distances.next_1d(),
                        wavelengths,
                        |c| {
                            let sigma_n = null_coefficient(c);
                            let hero_density = c.t_maj[0] * c.sigma_maj[0];
                            transmittance *= c.t_maj * sigma_n / hero_density;
                            ratios.r_l *= c.t_maj * c.sigma_maj / hero_density;
                            // Unidirectional sampling would have gone straight on here:
                            // with density T_maj sigma_n, or its share under a dye (`dye`).
                            let straight = if dyed { straight_density(c) } else { sigma_n };
                            ratios.r_u *= c.t_maj * straight / hero_density;
                            let estimate =
                                (transmittance / (ratios.r_l + ratios.r_u).average()).max_value();
                            if estimate < ROULETTE_BELOW {
                                if kinds.next_1d() < 0.75 {
                                    transmittance = SampledSpectrum::splat(0.0);
                                } else {
                                    transmittance *= 1.0 / 0.25;
                                }
                            }
                            transmittance.max_value() > 0.0
                        },
                    );
                    if !positive_finite(t_maj[0]) {
                        return (None, rays);
                    }
                    let factor = t_maj / t_maj[0];
                    transmittance *= factor;
                    ratios.scale(&factor);
                    if !positive_finite(transmittance.max_value()) {
                        return (None, rays);
                    }
                }
            }
            let Some(h) = hit else {
                return (
                    Some(Shadow {
                        transmittance,
                        ratios,
                    }),
                    rays,
                );
            };
            media.cross(self.scene, &h, direction);
            let rest = ray.t_max - h.t;
            ray = h.spawn_to(direction, rest);
        }
        (None, rays)
    }
}
