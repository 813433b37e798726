//! The light a path meets: the environment after an escape, a surface's emission, and
//! next-event estimation, each weighed by MIS against the other strategy.

use glam::{Vec2, Vec3};
use prism_sampling::mis::power_heuristic;
use prism_scene::world::{EmissionCache, Hit};

use super::walk::Walk;
use crate::transport::context::Integrator;
use crate::transport::light_path::CAUSTIC_ALPHA;
use crate::transport::throughput::{Arrival, Throughput, Vertex};

impl Integrator<'_> {
    /// Adds the light of the environment a ray that left the scene arrives from, weighed by
    /// MIS against light sampling after a bounce.
    #[inline(always)]
    pub(crate) fn add_escaped<const N: usize, T: Throughput<N>>(
        &self,
        walk: &mut Walk<N, T>,
        emission: &mut EmissionCache<N>,
    ) {
        // Light a light path carries (they leave the environment too).
        if walk.light_caustic {
            return;
        }
        let Some((mut le, light_pdf)) =
            self.scene
                .escaped(walk.ray.direction.normalize(), &walk.transport, emission)
        else {
            return;
        };
        if let Some(times) = &walk.times {
            self.gate(self.scene.environment_light(), times, &mut le);
        }
        let w = walk.previous.map_or(1.0, |(bsdf_pdf, _)| {
            power_heuristic(1, bsdf_pdf, 1, light_pdf)
        });
        walk.beta.add_emitted(&mut walk.radiance, &le, w);
    }

    /// Adds the light `hit` emits towards `wo_world`, weighed by MIS against light
    /// sampling after a bounce.
    #[inline(always)]
    pub(crate) fn add_hit_emission<const N: usize, T: Throughput<N>>(
        &self,
        hit: &Hit,
        wo_world: Vec3,
        walk: &mut Walk<N, T>,
        emission: &mut EmissionCache<N>,
    ) {
        let mut le = self.scene.emitted(hit, wo_world, &walk.transport, emission);
        if le.is_black() {
            return;
        }
        if let Some(times) = &walk.times {
            self.gate(self.scene.light_of(hit), times, &mut le);
            if le.is_black() {
                return;
            }
        }
        let w = walk.previous.map_or(1.0, |(bsdf_pdf, from)| {
            let light_pdf = self.scene.light_pdf(from, hit, &walk.transport, emission);
            power_heuristic(1, bsdf_pdf, 1, light_pdf)
        });
        walk.beta.add_emitted(&mut walk.radiance, &le, w);
    }

    /// Next-event estimation at `vertex` (not a delta): a light sampled with `u_light`, its
    /// shadow ray traced unless the light or the BSDF is dark at every wavelength, and what
    /// arrives added to the walk's radiance with the power heuristic against BSDF sampling. Returns
    /// the rays traced.
    #[inline(always)]
    pub(crate) fn next_event<const N: usize, T: Throughput<N>>(
        &self,
        hit: &Hit,
        vertex: &Vertex<'_, '_, N>,
        u_light: Vec2,
        walk: &mut Walk<N, T>,
        emission: &mut EmissionCache<N>,
    ) -> u64 {
        let Some(mut light) = self
            .scene
            .sample_light(hit, u_light, &walk.transport, emission)
        else {
            return 0;
        };
        // Light reaching a narrow surface past the path's first bounce is the light paths'.
        if walk.depth > 0 && walk.caustic_eligible && vertex.bsdf.is_narrow(CAUSTIC_ALPHA) {
            return 0;
        }
        if let Some(times) = &walk.times {
            self.gate(Some(light.light), times, &mut light.radiance);
        }
        let wi = vertex.frame.to_local(light.wi);
        let f = vertex.bsdf.f(vertex.wo, wi) * wi.z.abs();
        // A light dark at every wavelength of the path (chosen by the defensive share of a
        // spectral choice, or by power) needs no shadow ray.
        if f.is_black() || light.radiance.is_black() {
            return 0;
        }
        if !self.scene.occluded(&hit.spawn_to(light.wi, light.distance)) {
            let w = if light.delta {
                1.0
            } else {
                power_heuristic(1, light.pdf, 1, vertex.bsdf.pdf(vertex.wo, wi))
            };
            let arrival = Arrival {
                wi,
                f: &f,
                radiance: &light.radiance,
                weight: w / light.pdf,
            };
            walk.beta
                .add_scattered(&mut walk.radiance, vertex, arrival, || {
                    let p = self.scene.light_polarization(light.light)?;
                    Some(p.stokes(-light.wi))
                });
        }
        1
    }
}
