//! One camera path: unidirectional path tracing with next-event estimation, MIS by the
//! power heuristic between light and BSDF sampling, Russian roulette, and a package of
//! wavelengths that is split at dispersive delta events.

mod fluorescence;
mod light;
pub(crate) mod walk;

use glam::Vec2;
use prism_sampling::distribution::positive_finite;
use prism_sampling::stream::{SampleStream, SobolStream};
use prism_sampling::wavelength::WavelengthPackage;
use prism_scene::geometry::Frame;
use prism_scene::world::EmissionCache;
use prism_spectrum::SampledWavelengths;

use walk::Walk;

use crate::transport::context::{DIMENSIONS_PER_BOUNCE, Integrator, PathResult, absorb};
use crate::transport::reuse_record::{FirstVertex, ReuseRecord};
use crate::transport::throughput::{Throughput, Vertex};

impl<'a> Integrator<'a> {
    /// Traces the path of sample `stream` through film point `film` (in [0, 1]^2) of an
    /// image with aspect ratio `aspect`. The stream must be positioned after the film
    /// dimensions; `first_package` holds the sample's wavelengths ([`Integrator::package`]),
    /// and `emission` caches spectra at them (a cache from another path is refilled if its
    /// wavelengths differ). The path's radiance goes to `sink` with the wavelengths and
    /// densities it was estimated with: once at the end, and once more before a package
    /// split (the estimate so far, with the whole package's densities).
    ///
    /// `FLUORESCENCE` is whether the scene has re-radiating materials: without it the
    /// wavelengths light is evaluated at are always the film's, and no vertex pays for
    /// the check (the renderer picks the specialization from the scene's features). `T`
    /// is what the path carries: a spectrum, or Mueller matrices for polarized renders.
    ///
    /// `REUSE` is whether the path shares its second vertex with its tile's other pixels
    /// (`crate::reuse`; never with `SPLIT`): where its first vertex can share (Lambertian,
    /// or a plastic under a rough coating) and its
    /// second reflects alike in every direction, what the path gathers from the second
    /// vertex on goes to `record` instead of `sink`, and the first vertex and the bounce
    /// to the second are recorded with it.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn trace<
        const N: usize,
        const FLUORESCENCE: bool,
        const SPLIT: bool,
        const REUSE: bool,
        T: Throughput<N>,
    >(
        &self,
        stream: &mut SobolStream,
        sample_base: u64,
        first_package: &WavelengthPackage<N>,
        film: Vec2,
        aspect: f32,
        sink: &mut impl FnMut(&T::Radiance, &SampledWavelengths<N>),
        record: &mut ReuseRecord<'a, N, T::Radiance>,
        emission: &mut EmissionCache<N>,
    ) -> PathResult {
        let first_package = *first_package;
        let start = match self.start_camera_path(stream, &first_package, film, aspect) {
            Ok(start) => start,
            Err(nothing) => return nothing,
        };
        let mut rays = 0u64;
        let mut covered = false;
        // Splitting (Arvo and Kirk's, as production renderers' "diffuse samples"): the
        // camera ray, the emission it meets and the first vertex's light sample are traced
        // once, and `splits` continuations from that vertex each carry 1 / splits of its
        // throughput. Split k draws its bounces from sample `s * splits + k` of the pixel's
        // stream (`SobolStream::split`), so a pixel's continuations together are the first
        // `spp * splits` points of every pair of dimensions. Decided at the first vertex
        // (1: the camera ray left the scene, the path ended there, or the vertex is a delta).
        let mut splits = 1u32;
        // The camera ray's hit, once traced: the later splits start from it.
        let mut first_hit: Option<Option<prism_scene::world::Hit>> = None;
        let mut split = 0u32;
        while split < splits {
            let mut walk = Walk::<N, T>::from_camera(first_package, &start, &self.camera_frame);
            // The stream of this split's bounces (set at the first vertex).
            let mut bounces = stream.clone();
            loop {
                // A later split's first vertex repeats the first one's without its light: the
                // emission the camera sees and the light sample there were counted once.
                let replay = SPLIT && walk.depth == 0 && split > 0;
                let hit = match &first_hit {
                    Some(hit) if replay => *hit,
                    _ => {
                        rays += 1;
                        let hit = self.scene.intersect(&walk.ray);
                        if SPLIT && walk.depth == 0 {
                            first_hit = Some(hit);
                        }
                        if walk.depth == 0 {
                            covered = hit.is_some();
                        }
                        hit
                    }
                };
                let Some(mut hit) = hit else {
                    if walk.depth > 0 || !self.transparent {
                        self.add_escaped(&mut walk, emission);
                    }
                    break;
                };
                let wo_world = -walk.ray.direction.normalize();
                if let Some(footprint) = &self.footprint {
                    let width = footprint.at(hit.p);
                    self.scene.set_footprint(&mut hit, wo_world, width);
                }
                absorb(self.scene, &walk.ray, &hit, &walk.transport, &mut walk.beta);
                // Light a light path carries, or a split's replay has counted, is not added.
                if !walk.light_caustic && !replay {
                    self.add_hit_emission(&hit, wo_world, &mut walk, emission);
                }
                if REUSE
                    && walk.depth == 1
                    && record.first.is_some()
                    && self.scene.reflects_alike(&hit)
                {
                    walk.restart_at_second(&hit, wo_world, &self.camera_frame, record);
                }
                if walk.depth >= self.max_depth {
                    break;
                }
                let dimension = sample_base + u64::from(walk.depth) * DIMENSIONS_PER_BOUNCE;
                // The first vertex's own draws are the camera sample's; the rest the split's.
                let here: &mut SobolStream = if SPLIT && walk.depth > 0 {
                    &mut bounces
                } else {
                    stream
                };
                here.set_dimension(dimension);
                let u_light = here.next_2d();
                // A split first vertex draws these again below, from its continuation.
                let mut u_lobe = here.next_1d();
                let mut u_bsdf = here.next_2d();
                let mut u_roulette = here.next_1d();

                let material = self.scene.material(&hit);
                let Some(bsdf) =
                    self.vertex_bsdf::<N, FLUORESCENCE, T>(&hit, here, &mut walk, emission)
                else {
                    break;
                };
                let frame = Frame::from_normal(hit.shading_normal);
                let wo = frame.to_local(wo_world);
                let vertex = Vertex {
                    bsdf: &bsdf,
                    frame: &frame,
                    wo,
                };

                // Next-event estimation.
                if !bsdf.is_delta() && !replay {
                    rays += self.next_event(&hit, &vertex, u_light, &mut walk, emission);
                }

                if SPLIT && walk.depth == 0 {
                    if split == 0 && !bsdf.is_delta() {
                        splits = self.splits.max(1);
                    }
                    bounces = stream.split(split, splits);
                    if splits > 1 {
                        walk.beta.scale_uniform(1.0 / splits as f32);
                        walk.eta_scale *= splits as f32;
                    }
                    bounces.set_dimension(dimension + 2);
                    u_lobe = bounces.next_1d();
                    u_bsdf = bounces.next_2d();
                    u_roulette = bounces.next_1d();
                }

                // BSDF sampling.
                let Some(sample) = bsdf.sample(wo, u_lobe, u_bsdf) else {
                    break;
                };
                let pdf = sample.pdf[0];
                if !positive_finite(pdf) {
                    break;
                }
                if REUSE && walk.depth == 0 {
                    record.first =
                        FirstVertex::recorded(material, hit, frame, wo, &bsdf, &sample, pdf);
                }
                let caustic_start = self.light_caustics && !material.fluorescent();
                if !walk.follow::<FLUORESCENCE>(&hit, &vertex, &sample, pdf, caustic_start, sink)
                    || !walk.survives_roulette(u_roulette)
                {
                    break;
                }
            }
            if REUSE && record.second.is_some() {
                sink(&record.own, &walk.lambdas);
                record.reflected = walk.radiance;
            } else {
                sink(&walk.radiance, &walk.lambdas);
            }
            split += 1;
        }
        PathResult {
            valid: true,
            rays,
            connections: 0,
            covered,
        }
    }
}
