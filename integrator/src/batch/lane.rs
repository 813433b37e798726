//! One lane of a batch: its pixel's camera path, as the path tracer's `Walk`, with the
//! sample stream, the spectra cache and the counts of its own; and what the lane does
//! alone (the scene's answers for its ray).

use glam::{Vec2, Vec3};
use prism_sampling::distribution::positive_finite;
use prism_sampling::stream::{SampleStream, SobolStream};
use prism_scene::bsdf::TransportMode;
use prism_scene::geometry::Frame;
use prism_scene::world::{Bsdf, EmissionCache, Hit, Material};
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use crate::filter::FilterSampler;
use crate::path::{
    DIMENSIONS_PER_BOUNCE, FIRST_BOUNCE_DIMENSION, PathResult, Tracer, Walk, absorb, wavelengths,
};
use crate::render::{Rows, camera_sample};
use crate::throughput::Vertex;

/// A live path of a batch (unpolarized: it carries a spectrum).
pub(super) struct Lane<const N: usize> {
    pub walk: Walk<N, SampledSpectrum<N>>,
    pub stream: SobolStream,
    pub cache: EmissionCache<N>,
    pub rays: u64,
    pub covered: bool,
}

/// A lane's vertex, where its path goes on: the hit, the direction back along the ray,
/// the material and its BSDF there, the bounce's draws.
pub(super) struct At<'s, const N: usize> {
    pub hit: Hit,
    pub wo_world: Vec3,
    pub material: &'s Material,
    pub bsdf: Bsdf<'s, N>,
    pub u_light: Vec2,
    pub u_lobe: f32,
    pub u_bsdf: Vec2,
    pub u_roulette: f32,
}

impl<const N: usize> Lane<N> {
    /// Sample `s` of pixel (`x`, `y`) leaving the camera, as the path tracer starts it
    /// (`render::trace_sample`, `Tracer::trace`); None where its wavelengths are invalid.
    #[inline(never)]
    pub fn start(
        tracer: &Tracer,
        filter: &FilterSampler,
        rows: &Rows,
        (x, y): (u32, u32),
        s: u64,
    ) -> Option<Self> {
        let (mut stream, u_lambda, film) = camera_sample(filter, rows, x, y, s);
        let package = tracer.package::<N>(u_lambda);
        let lambdas = wavelengths(&package)?;
        let times = tracer.clock.map(|clock| [clock.time(&mut stream); N]);
        let aspect = rows.width as f32 / rows.height as f32;
        let (ray, weight) = tracer.camera_ray(film, aspect, &stream, package.lambda[0])?;
        let mut walk = Walk::new(package, lambdas, times, ray, &tracer.camera_frame);
        walk.weigh_camera_ray(weight);
        Some(Self {
            walk,
            stream,
            cache: EmissionCache::new(),
            rays: 0,
            covered: false,
        })
    }

    /// The path's result so far.
    pub fn result(&self) -> PathResult {
        PathResult {
            valid: true,
            rays: self.rays,
            connections: 0,
            covered: self.covered,
        }
    }

    /// Traces the path's ray and adds the light it meets (the environment where it leaves
    /// the scene, the emission of the surface it hits), as the path tracer's loop does;
    /// then draws the bounce's numbers and finds the BSDF. None where the path ends.
    #[inline(never)]
    pub fn meet<'s, const FLUORESCENCE: bool>(&mut self, tracer: &Tracer<'s>) -> Option<At<'s, N>> {
        let scene = tracer.scene;
        let walk = &mut self.walk;
        self.rays += 1;
        let hit = scene.intersect(&walk.ray);
        if walk.depth == 0 {
            self.covered = hit.is_some();
        }
        let Some(mut hit) = hit else {
            if walk.depth > 0 || !tracer.transparent {
                tracer.add_escaped(walk, &mut self.cache);
            }
            return None;
        };
        let wo_world = -walk.ray.direction.normalize();
        if let Some(footprint) = &tracer.footprint {
            let width = footprint.at(hit.p);
            scene.set_footprint(&mut hit, wo_world, width);
        }
        absorb(scene, &walk.ray, &hit, &walk.transport, &mut walk.beta);
        if !walk.light_caustic {
            tracer.add_hit_emission(&hit, wo_world, walk, &mut self.cache);
        }
        if walk.depth >= tracer.max_depth {
            return None;
        }
        let here = &mut self.stream;
        here.set_dimension(FIRST_BOUNCE_DIMENSION + u64::from(walk.depth) * DIMENSIONS_PER_BOUNCE);
        let u_light = here.next_2d();
        let u_lobe = here.next_1d();
        let u_bsdf = here.next_2d();
        let u_roulette = here.next_1d();
        let material = scene.material(&hit);
        let bsdf = match material {
            Material::Fluorescent {
                reflectance,
                reradiation,
            } if FLUORESCENCE => tracer.fluoresce(&hit, reflectance, reradiation, here, walk)?,
            _ => scene.bsdf_cached(
                &hit,
                &walk.transport,
                TransportMode::Radiance,
                &mut self.cache,
            ),
        };
        Some(At {
            hit,
            wo_world,
            material,
            bsdf,
            u_light,
            u_lobe,
            u_bsdf,
            u_roulette,
        })
    }

    /// The vertex `at` handled by this lane alone, with the path tracer's code: next-event
    /// estimation unless the BSDF is a delta, the sampled bounce, Russian roulette. Light
    /// a dispersive bounce ends goes to `sink`. False where the path ends.
    #[inline(never)]
    pub fn scatter_alone<const FLUORESCENCE: bool>(
        &mut self,
        tracer: &Tracer,
        at: &At<'_, N>,
        sink: &mut dyn FnMut(&SampledSpectrum<N>, &SampledWavelengths<N>),
    ) -> bool {
        let frame = Frame::from_normal(at.hit.shading_normal);
        let wo = frame.to_local(at.wo_world);
        let vertex = Vertex {
            bsdf: &at.bsdf,
            frame: &frame,
            wo,
        };
        if !at.bsdf.is_delta() {
            self.rays += tracer.next_event(
                &at.hit,
                &vertex,
                at.u_light,
                &mut self.walk,
                &mut self.cache,
            );
        }
        let Some(sample) = at.bsdf.sample(wo, at.u_lobe, at.u_bsdf) else {
            return false;
        };
        let pdf = sample.pdf[0];
        if !positive_finite(pdf) {
            return false;
        }
        let caustic_start = tracer.light_caustics && !at.material.fluorescent();
        self.walk.follow::<FLUORESCENCE>(
            &at.hit,
            &vertex,
            &sample,
            pdf,
            caustic_start,
            &mut |r, l| sink(r, l),
        ) && self.walk.survives_roulette(at.u_roulette)
    }
}

/// What a lane does alone, compiled for scenes with fluorescence or without (as the path
/// tracer is), chosen once per render: the lane-wide code is compiled once for both.
pub(super) struct LaneCode<const N: usize> {
    pub meet: for<'s> fn(&mut Lane<N>, &Tracer<'s>) -> Option<At<'s, N>>,
    #[allow(clippy::type_complexity)]
    pub scatter_alone: fn(
        &mut Lane<N>,
        &Tracer,
        &At<'_, N>,
        &mut dyn FnMut(&SampledSpectrum<N>, &SampledWavelengths<N>),
    ) -> bool,
}

impl<const N: usize> LaneCode<N> {
    /// The code for scenes with re-radiating materials (`fluorescence`) or without.
    pub fn of(fluorescence: bool) -> Self {
        if fluorescence {
            Self {
                meet: Lane::meet::<true>,
                scatter_alone: Lane::scatter_alone::<true>,
            }
        } else {
            Self {
                meet: Lane::meet::<false>,
                scatter_alone: Lane::scatter_alone::<false>,
            }
        }
    }
}
