//! The volumetric path tracer: a camera path through participating media and surfaces
//! alike, for scenes that have media (fog, media inside interfaces and dielectrics).
//!
//! It follows the null-scattering path integral of Miller, Georgiev and Jarosz ("A
//! null-scattering path integral formulation of light transport", SIGGRAPH 2019, §4-5) as
//! pbrt-v4's `VolPathIntegrator` does (*PBR* 4th ed. §14.2.3): free-flight distances drawn
//! against a majorant, real (scattering, absorption a weight) and null collisions chosen
//! by the hero's probabilities (`segment`), every lane's density kept as a ratio to the hero's
//! (`ratios`) so that the balance heuristic over every lane as hero and over unidirectional
//! and light sampling weighs each contribution (`light`); next-event estimation through
//! media by ratio tracking (`shadow`); and the nesting of volumes a path is in (`stack`).
//! No lane is ever terminated by a chromatic medium: the package is what makes a medium
//! whose extinction varies with wavelength converge.
//!
//! Scenes without media never reach this module: the renderer runs the path tracer of
//! `crate::transport::path`, compiled without any of it.

mod dye;
mod light;
mod ratios;
mod segment;
mod shadow;
mod stack;

pub(crate) use glam::Vec2;
use prism_sampling::distribution::positive_finite;
use prism_sampling::stream::{SampleStream, SobolStream};
use prism_sampling::wavelength::WavelengthPackage;
use prism_scene::geometry::Ray;
use prism_scene::materials::Material;
use prism_scene::medium::Phase;
use prism_scene::world::EmissionCache;
use prism_spectrum::SampledWavelengths;
pub(crate) use segment::FlightStreams;
pub(crate) use stack::MediumStack;

use crate::transport::context::absorb;
use crate::transport::context::{DIMENSIONS_PER_BOUNCE, Integrator, PathResult, ROULETTE_DEPTH};
use crate::transport::path::walk::Walk;
use crate::transport::path::walk::roulette_capped;
use crate::transport::reuse_record::{FirstVertex, ReuseRecord};
use crate::transport::throughput::{Throughput, Vertex};
use light::Scatterer;
use prism_scene::geometry::Frame;
use ratios::{Ratios, spectral_weight};
use segment::{Flight, fly};

/// The Sobol dimension of bounce 0's first-collision numbers (bounce k's are this + 2k and
/// the next): far above any bounce's block, so that drawing them moves no other number.
const FLIGHT_DIMENSION: u64 = 1 << 32;

/// The most likely a path that still carries light survives Russian roulette after a
/// scattering: in a medium a path's light comes after many scatterings (most of the
/// medium box's block's light comes after its first bounce), and the path tracer's cap of
/// 0.95 ended 5% of paths at each of them whatever they carried, multiplying the rest by
/// 1 / 0.95 each time. At 0.99 the milk bunny reaches equal error sooner, the medium box
/// as soon, the hot plume unchanged (docs/trade-offs.md, "Participating media: the
/// volumetric tracer against Mitsuba's volpathmis"); a path in a closed scene that absorbs
/// nothing still ends, after a hundred bounces on average.
const SURVIVAL_CAP: f32 = 0.99;

/// Interfaces a path crosses between two vertices at most (coplanar or degenerate
/// boundaries would otherwise hold it forever).
const MAX_INTERFACES: u32 = 256;

impl<'a> Integrator<'a> {
    /// Traces the path of sample `stream` through film point `film` in a scene with media,
    /// as [`Integrator::trace`] does in a vacuum (unsplit, without reuse or light paths); the
    /// flights through media draw from `numbers`.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn trace_volume<
        const N: usize,
        const FLUORESCENCE: bool,
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
        numbers: &mut FlightStreams,
    ) -> PathResult {
        let start = match self.start_camera_path(stream, first_package, film, aspect) {
            Ok(start) => start,
            Err(nothing) => return nothing,
        };
        let mut walk = Walk::<N, T>::from_camera(*first_package, &start, &self.camera_frame);
        let mut ratios = Ratios::<N>::one();
        let mut media = self.camera_media;
        let (mut rays, mut covered, mut interfaces) = (0u64, false, 0u32);
        // The bounce whose first flight has drawn its stratified pair.
        let mut stratified: Option<u32> = None;
        // Straight crossings of thin sheets that count no bounce: Mitsuba's
        // `thindielectric` transmits as a null event (`BSDFFlags::Null` in
        // src/bsdfs/thindielectric.cpp), which its `volpath` leaves out of `max_depth`
        // (src/integrators/volpath.cpp, `non_null_bsdf`). Only where crossing sets the
        // medium (Mitsuba's scenes); `walk.depth` still counts them, so that every vertex
        // draws its own sample dimensions.
        let mut free_crossings = 0u32;
        loop {
            rays += 1;
            let hit = self.scene.intersect(&walk.ray);
            if walk.depth == 0 && interfaces == 0 {
                covered = hit.is_some();
            }
            let direction = walk.ray.direction.normalize();
            if let Some(m) = media.current() {
                let length = hit.map_or(f32::INFINITY, |h| h.t * walk.ray.direction.length());
                let emits = walk.depth - free_crossings < self.max_depth;
                let medium = self.scene.media().get(m);
                let origin = walk.ray.origin;
                // A bounce's first flight takes its first collision from the sample's
                // Sobol stream (a pair of its own, apart from the bounce's block), so
                // that the pixel's samples stratify it; later stretches of the same
                // bounce, after an interface, draw independent numbers, since the first
                // flight's outcome conditions that pair.
                numbers.first = (stratified != Some(walk.depth)).then(|| {
                    stratified = Some(walk.depth);
                    // Two 1D draws, each its own scrambled (0, 1)-sequence: stratified
                    // alone, never worse than independent numbers (Owen 1997), where a
                    // joint 2D net can be up to twice as bad (it was worse on the hot
                    // plume of scenes/media.gltf).
                    let mut numbers = stream.clone();
                    numbers.set_dimension(FLIGHT_DIMENSION + 2 * u64::from(walk.depth));
                    let distance = numbers.next_1d();
                    Vec2::new(distance, numbers.next_1d())
                });
                let base = emission.medium(m, medium, &walk.transport);
                let flight = fly(
                    medium,
                    &base,
                    origin,
                    direction,
                    length,
                    emits,
                    &mut walk,
                    &mut ratios,
                    numbers,
                );
                let (p, phase) = match flight {
                    Flight::Ended => break,
                    Flight::Through => (None, *medium.phase()),
                    Flight::Scattered(p) => (Some(p), *medium.phase()),
                    // A dye re-emits alike in every direction.
                    Flight::Fluoresced(p) => (Some(p), Phase::HenyeyGreenstein { g: 0.0 }),
                };
                if let Some(p) = p {
                    if walk.depth - free_crossings >= self.max_depth {
                        break;
                    }
                    interfaces = 0;
                    rays += self.scatter_in_medium(
                        p,
                        direction,
                        phase,
                        &media,
                        stream,
                        sample_base,
                        &mut walk,
                        &mut ratios,
                        numbers,
                        emission,
                    );
                    if !self.survives(&mut walk, &ratios, stream) {
                        break;
                    }
                    continue;
                }
            }
            let Some(hit) = hit else {
                if walk.depth > 0 || !self.transparent {
                    self.add_volume_escaped(&mut walk, &ratios, emission);
                }
                break;
            };
            let wo_world = -direction;
            self.add_volume_hit_emission(&hit, wo_world, &mut walk, &ratios, emission);
            // Path reuse shares second vertices met in vacuum, straight from a first
            // vertex in vacuum: ratios are one there, and the light from the second vertex
            // on does not depend on the path before it.
            if REUSE
                && walk.depth == 1
                && interfaces == 0
                && record.first.is_some()
                && media.current().is_none()
                && self.scene.reflects_alike(&hit)
            {
                walk.restart_at_second(&hit, wo_world, &self.camera_frame, record);
            }
            if self.scene.is_interface(&hit) {
                // Light crosses unchanged: the path goes on into the next medium, at the
                // same bounce, its last vertex still the one light sampling left from.
                interfaces += 1;
                if interfaces > MAX_INTERFACES {
                    break;
                }
                media.cross(self.scene, &hit, direction);
                walk.ray = hit.spawn(direction);
                continue;
            }
            // Whether the ray to this vertex crossed no boundary of a medium.
            let unbounded = std::mem::take(&mut interfaces) == 0;
            absorb(self.scene, &walk.ray, &hit, &walk.transport, &mut walk.beta);
            let sheet = self.scene.media().crossing_sets()
                && matches!(self.scene.material(&hit), Material::ThinDielectric { .. });
            let exhausted = walk.depth - free_crossings >= self.max_depth;
            // A sheet met with the bounces spent may still be crossed (no bounce), not
            // reflected off.
            if exhausted && !sheet {
                break;
            }
            let here = &mut *stream;
            here.set_dimension(sample_base + u64::from(walk.depth) * DIMENSIONS_PER_BOUNCE);
            let u_light = here.next_2d();
            let u_lobe = here.next_1d();
            let u_bsdf = here.next_2d();
            let u_roulette = here.next_1d();
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
            if !bsdf.is_delta() {
                rays += self.volume_next_event(
                    Scatterer::Surface(&hit, &vertex),
                    |wi| media.after(self.scene, &hit, direction, wi),
                    u_light,
                    &mut walk,
                    &ratios,
                    numbers,
                    emission,
                );
            }
            let Some(sample) = bsdf.sample(wo, u_lobe, u_bsdf) else {
                break;
            };
            let pdf = sample.pdf[0];
            if !positive_finite(pdf) {
                break;
            }
            let crossed = sheet && sample.delta && wo.z * sample.wi.z < 0.0;
            if exhausted && !crossed {
                break;
            }
            if REUSE && walk.depth == 0 && unbounded && media.current().is_none() {
                let material = self.scene.material(&hit);
                record.first = FirstVertex::recorded(material, hit, frame, wo, &bsdf, &sample, pdf);
            }
            if !walk.follow::<FLUORESCENCE>(&hit, &vertex, &sample, pdf, false, sink) {
                break;
            }
            free_crossings += u32::from(crossed);
            // Light sampling's density of this direction is the light's, known only where
            // a light is met; its ratio so far is the unidirectional one over the bounce's.
            ratios.r_l = ratios.r_u / pdf;
            media = media.after(self.scene, &hit, direction, frame.to_world(sample.wi));
            if !self.survives_at(&mut walk, &ratios, u_roulette) {
                break;
            }
        }
        if REUSE && record.second.is_some() {
            sink(&record.own, &walk.lambdas);
            record.reflected = walk.radiance;
        } else {
            sink(&walk.radiance, &walk.lambdas);
        }
        PathResult {
            valid: true,
            rays,
            connections: 0,
            covered,
        }
    }

    /// Scatters the path at particle `p` by `phase` (it arrived along unit `incoming`,
    /// inside `media`): next-event estimation, then a direction drawn from the phase
    /// function. Returns the rays traced.
    #[allow(clippy::too_many_arguments)]
    fn scatter_in_medium<const N: usize, T: Throughput<N>>(
        &self,
        p: glam::Vec3,
        incoming: glam::Vec3,
        phase: Phase,
        media: &MediumStack,
        stream: &mut SobolStream,
        sample_base: u64,
        walk: &mut Walk<N, T>,
        ratios: &mut Ratios<N>,
        numbers: &mut FlightStreams,
        emission: &mut EmissionCache<N>,
    ) -> u64 {
        stream.set_dimension(sample_base + u64::from(walk.depth) * DIMENSIONS_PER_BOUNCE);
        let u_light = stream.next_2d();
        let u_phase = stream.next_2d();
        let rays = self.volume_next_event(
            Scatterer::Particle(p, phase, incoming),
            |_| *media,
            u_light,
            walk,
            ratios,
            numbers,
            emission,
        );
        // Both phase functions are sampled exactly: p / pdf = 1 at every wavelength (and
        // in polarized renders what remains is Rayleigh's Mueller matrix over p).
        let sample = phase.sample(incoming, u_phase);
        walk.beta
            .scatter_phase(&phase, incoming, sample.outgoing, sample.p / sample.pdf);
        ratios.r_l = ratios.r_u / sample.pdf;
        walk.previous = Some((sample.pdf, p));
        walk.ray = Ray::new(p, sample.outgoing, f32::INFINITY);
        walk.depth += 1;
        rays
    }

    /// Russian roulette after a scattering in a medium, drawing from the bounce's
    /// dimensions.
    fn survives<const N: usize, T: Throughput<N>>(
        &self,
        walk: &mut Walk<N, T>,
        ratios: &Ratios<N>,
        stream: &mut SobolStream,
    ) -> bool {
        let u = stream.next_1d();
        self.survives_at(walk, ratios, u)
    }

    /// Russian roulette on what the path would add per unit of light (its throughput under
    /// the lanes' MIS weights, without the refractions' 1 / eta^2), with `u`; as the path
    /// tracer's from its third bounce.
    fn survives_at<const N: usize, T: Throughput<N>>(
        &self,
        walk: &mut Walk<N, T>,
        ratios: &Ratios<N>,
        u: f32,
    ) -> bool {
        if walk.beta.max_value() <= 0.0 {
            return false;
        }
        if walk.depth < ROULETTE_DEPTH {
            return true;
        }
        let weight = spectral_weight(&walk.package, &ratios.r_u).max_value();
        let throughput = walk.beta.max_value() * weight * walk.eta_scale;
        let (survives, q) = roulette_capped(throughput, u, SURVIVAL_CAP);
        if !survives {
            return false;
        }
        walk.beta.scale_uniform(1.0 / q);
        true
    }
}
