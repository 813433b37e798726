//! The light a volumetric path meets, weighed by the balance heuristic over every lane as
//! hero and both strategies (unidirectional sampling and next-event estimation): emission
//! a path hits or escapes to, and next-event estimation from a surface or a medium
//! particle through the media between (*PBR* 4th ed. §14.2.3, `VolPathIntegrator::Li`'s
//! emitted light and `SampleLd`).

use glam::{Vec2, Vec3};
use prism_sampling::distribution::positive_finite;
use prism_scene::geometry::Ray;
use prism_scene::medium::Phase;
use prism_scene::world::{EmissionCache, Hit};
use prism_spectrum::SampledSpectrum;

use super::ratios::{Ratios, spectral_weight};
use super::segment::FlightStreams;
use super::stack::MediumStack;
use crate::transport::context::Integrator;
use crate::transport::path::walk::Walk;
use crate::transport::throughput::{Arrival, Throughput, Vertex};

/// Where a path scatters: on a surface (its hit and BSDF vertex), or at a particle of a
/// medium (where, its phase function, and the direction the path arrived along).
#[derive(Clone, Copy)]
pub(crate) enum Scatterer<'h, 'v, 'b, const N: usize> {
    Surface(&'h Hit, &'h Vertex<'v, 'b, N>),
    Particle(Vec3, Phase, Vec3),
}

impl<const N: usize> Scatterer<'_, '_, '_, N> {
    /// The shadow ray towards unit `wi`, stopping just short of `distance`.
    fn shadow_ray(&self, wi: Vec3, distance: f32) -> Ray {
        match self {
            Scatterer::Surface(hit, _) => hit.spawn_to(wi, distance),
            Scatterer::Particle(p, ..) => {
                let t_max = if distance.is_finite() {
                    distance * (1.0 - 1e-4)
                } else {
                    f32::INFINITY
                };
                Ray::new(*p, wi, t_max)
            }
        }
    }

    /// What the scattering does to light arriving from world direction `wi` (towards the
    /// light): f times the cosine for a surface, p for a particle, and the density with
    /// which the path's own sampling would have chosen that direction.
    fn towards(&self, wi: Vec3) -> (SampledSpectrum<N>, f32) {
        match self {
            Scatterer::Surface(_, vertex) => {
                let local = vertex.frame.to_local(wi);
                (
                    vertex.bsdf.f(vertex.wo, local) * local.z.abs(),
                    vertex.bsdf.pdf(vertex.wo, local),
                )
            }
            Scatterer::Particle(_, phase, d) => {
                let p = phase.eval(*d, wi);
                (SampledSpectrum::splat(p), p)
            }
        }
    }
}

impl Integrator<'_> {
    /// Adds light `le` (before MIS) that the path's last ray met, emitted by the scene's
    /// light `light` and found by unidirectional sampling: after the camera or a delta
    /// bounce no other strategy could have found it (`light_pdf` is not asked for), else
    /// light sampling from the previous vertex competes with density `light_pdf()`.
    #[inline]
    pub(crate) fn add_met_light<const N: usize, T: Throughput<N>>(
        &self,
        walk: &mut Walk<N, T>,
        ratios: &Ratios<N>,
        mut le: SampledSpectrum<N>,
        light: Option<u32>,
        light_pdf: impl FnOnce(Vec3) -> f32,
    ) {
        if let Some(times) = &walk.times {
            self.gate(light, times, &mut le);
        }
        if le.is_black() {
            return;
        }
        let r = match walk.previous {
            None => ratios.r_u,
            Some((_, from)) => ratios.r_u + ratios.r_l * light_pdf(from),
        };
        let le = le * spectral_weight(&walk.package, &r);
        walk.beta.add_emitted(&mut walk.radiance, &le, 1.0);
    }

    /// Adds the emission of surface `hit` towards `wo_world` (see [`Integrator::add_met_light`]).
    #[inline]
    pub(crate) fn add_volume_hit_emission<const N: usize, T: Throughput<N>>(
        &self,
        hit: &Hit,
        wo_world: Vec3,
        walk: &mut Walk<N, T>,
        ratios: &Ratios<N>,
        emission: &mut EmissionCache<N>,
    ) {
        let le = self.scene.emitted(hit, wo_world, &walk.transport, emission);
        if le.is_black() {
            return;
        }
        let transport = walk.transport;
        self.add_met_light(walk, ratios, le, self.scene.light_of(hit), |from| {
            self.scene.light_pdf(from, hit, &transport, emission)
        });
    }

    /// Adds the environment's light for a path whose ray left the scene.
    #[inline]
    pub(crate) fn add_volume_escaped<const N: usize, T: Throughput<N>>(
        &self,
        walk: &mut Walk<N, T>,
        ratios: &Ratios<N>,
        emission: &mut EmissionCache<N>,
    ) {
        let direction = walk.ray.direction.normalize();
        let Some((le, light_pdf)) = self.scene.escaped(direction, &walk.transport, emission) else {
            return;
        };
        self.add_met_light(walk, ratios, le, self.scene.environment_light(), |_| {
            light_pdf
        });
    }

    /// Next-event estimation at `at` inside `media` (the media a ray leaving towards the
    /// light starts in): a light sampled with `u_light`, the scattering evaluated towards
    /// it, the transmittance to it estimated by ratio tracking, and the light added with the
    /// balance heuristic over lanes and strategies (through the surface's or the particle's
    /// polarization in polarized renders). Returns the rays traced.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn volume_next_event<const N: usize, T: Throughput<N>>(
        &self,
        at: Scatterer<'_, '_, '_, N>,
        media: impl Fn(Vec3) -> MediumStack,
        u_light: Vec2,
        walk: &mut Walk<N, T>,
        ratios: &Ratios<N>,
        numbers: &mut FlightStreams,
        emission: &mut EmissionCache<N>,
    ) -> u64 {
        let light = match at {
            Scatterer::Surface(hit, _) => {
                self.scene
                    .sample_light(hit, u_light, &walk.transport, emission)
            }
            Scatterer::Particle(p, ..) => {
                self.scene
                    .sample_light_at(p, u_light, &walk.transport, emission)
            }
        };
        let Some(mut light) = light else {
            return 0;
        };
        if let Some(times) = &walk.times {
            self.gate(Some(light.light), times, &mut light.radiance);
        }
        let (f, pdf) = at.towards(light.wi);
        if f.is_black() || light.radiance.is_black() || !positive_finite(light.pdf) {
            return 0;
        }
        let ray = at.shadow_ray(light.wi, light.distance);
        let (shadow, rays) = self.shadow(ray, media(light.wi), &walk.transport, numbers, emission);
        let Some(shadow) = shadow else {
            return rays;
        };
        // The shadow ray's ratios times the path's up to here, with each strategy's density
        // of the direction: the light's, and the path's own sampling's (none for a delta
        // light, which only light sampling finds).
        let r_l = shadow.ratios.r_l * ratios.r_u * light.pdf;
        let r = if light.delta {
            r_l
        } else {
            r_l + shadow.ratios.r_u * ratios.r_u * pdf
        };
        let arriving = shadow.transmittance * light.radiance * spectral_weight(&walk.package, &r);
        let polarization = || {
            let p = self.scene.light_polarization(light.light)?;
            Some(p.stokes(-light.wi))
        };
        match at {
            Scatterer::Surface(_, vertex) => {
                let arrival = Arrival {
                    wi: vertex.frame.to_local(light.wi),
                    f: &f,
                    radiance: &arriving,
                    weight: 1.0,
                };
                walk.beta
                    .add_scattered(&mut walk.radiance, vertex, arrival, polarization);
            }
            Scatterer::Particle(_, phase, d) => {
                walk.beta.add_phase_scattered(
                    &mut walk.radiance,
                    &phase,
                    d,
                    light.wi,
                    &arriving,
                    polarization,
                );
            }
        }
        rays
    }
}
