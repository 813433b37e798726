//! Light paths for caustics: light leaving an emitter, focused by one or more bounces off
//! smooth or nearly smooth glass and metal, landing on surfaces, and seen by the camera
//! there or after further bounces (a caustic on the floor lights the walls too). A camera
//! path can only find such light by hitting the emitter through the focusing chain with a
//! BSDF-sampled direction, which is hopeless for small lights and impossible for punctual
//! ones (a spot light through a prism casts no spectrum in a pure path tracer). A light
//! path finds it by following the light and connecting every non-delta surface it lands
//! on to the pinhole (light tracing: Veach 1997, §10.2; *PBR* 4th ed. §13.4, whose camera
//! importance this uses).
//!
//! The two estimators split path space between them rather than combine by MIS. A bounce
//! is *focused* when it is a delta or off a narrow surface (every lobe a delta or GGX with
//! alpha at most [`CAUSTIC_ALPHA`], `Bsdf::is_narrow`). Light paths count exactly the
//! paths light -> x_1 -> ... -> x_k -> camera whose bounce at x_1 is focused, with x_k not
//! narrow (a glossy highlight seen directly is the camera's to find), k >= 2 and no vertex
//! fluorescent; camera paths skip the light found along such paths (`Walk::advance`: a
//! first bounce that is not focused, no fluorescent vertex, and a focused bounce onto the
//! emitter or out to the environment; `Integrator::next_event`: no light sample from a narrow
//! surface past the first bounce). Everything else stays with the camera paths, so the
//! sum is unbiased and each
//! path is counted once.
//!
//! Light from infinity (a directional light, the environment: the sun in an HDR sky,
//! focused by a metal sphere onto the floor) leaves a disk that covers only the surfaces
//! where a first bounce can be focused (`Material::focuses`, their bounding sphere
//! `Integrator::aim`), not the whole scene: every other ray would end at its first hit.

use glam::Vec2;
use prism_sampling::distribution::positive_finite;
use prism_sampling::stream::{SampleStream, SobolStream};
use prism_sampling::wavelength::WavelengthPackage;
use prism_scene::bsdf::TransportMode;
use prism_spectrum::SampledWavelengths;

use crate::transport::context::{Integrator, absorb, wavelengths};
use crate::transport::light_throughput::LightThroughput;
use crate::transport::throughput::Vertex;
use prism_scene::geometry::Frame;

/// The roughest GGX lobe (alpha, roughness 0.35) whose light counts as focused: light
/// leaving an emitter through such surfaces (or smooth ones) is carried by light paths,
/// like a caustic through glass. Measured as time to equal error on the glossy box,
/// counting lobes about this narrow pays; counting rougher ones too (copper at 0.15,
/// aluminium at 0.3) gives some of it back. What light paths buy: docs/trade-offs.md,
/// "Light paths for caustics".
pub(crate) const CAUSTIC_ALPHA: f32 = 0.12;

/// Sample-stream dimensions of a light path: the wavelength (0), the light choice, its
/// position and direction (1-5), then a fixed block per bounce.
const FIRST_BOUNCE_DIMENSION: u64 = 6;
const DIMENSIONS_PER_BOUNCE: u64 = 4;

/// The first bounce at which Russian roulette may end a light path.
const ROULETTE_DEPTH: u32 = 3;

/// The seed of light paths' streams, apart from the camera paths' so that the two
/// estimators are independent.
pub(crate) fn light_seed(seed: u64) -> u64 {
    seed ^ 0x6c69_6768_745f_7061
}

impl Integrator<'_> {
    /// Where the camera sees `point` (a light path's vertex at `depth`), connecting it to
    /// the pinhole or to a point of the lens the light path's stream chooses.
    fn seen(
        &self,
        point: glam::Vec3,
        aspect: f32,
        stream: &SobolStream,
        depth: u32,
    ) -> Option<prism_scene::camera::FilmPoint> {
        let camera = self.scene.camera();
        match &self.focus {
            None => camera.project(point, aspect),
            Some(focus) => {
                let mut lens = stream.clone();
                lens.set_dimension(
                    crate::transport::context::LENS_DIMENSION + 2 * u64::from(depth),
                );
                camera.project_through(point, aspect, Some(focus), lens.next_2d())
            }
        }
    }

    /// Traces one light path with `stream` (positioned at dimension 0) for an image of
    /// aspect ratio `aspect`; every connection to the camera goes to `sink` with its film
    /// position, its radiance (the contribution to the film's mean in that pixel, given
    /// one light path per pixel and sample) and the wavelengths it was estimated with.
    /// Returns the rays traced. `L` is what the path carries: a spectrum, or Stokes
    /// vectors for polarized renders.
    pub(crate) fn trace_light<const N: usize, L: LightThroughput<N>>(
        &self,
        stream: &mut SobolStream,
        aspect: f32,
        sink: &mut impl FnMut(Vec2, &L::Radiance, &SampledWavelengths<N>),
    ) -> u64 {
        let u_lambda = stream.next_1d();
        let mut package =
            WavelengthPackage::<N>::sample(self.distribution, f64::from(u_lambda), self.scheme);
        let Some(mut lambdas) = wavelengths(&package) else {
            return 0;
        };
        let u_choice = stream.next_1d();
        let u_position = stream.next_2d();
        let u_direction = stream.next_2d();
        let Some(emitted) =
            self.scene
                .sample_emission(u_choice, u_position, u_direction, &lambdas, self.aim)
        else {
            return 0;
        };
        // At an instant, a light that is off sends nothing (light paths never meet a
        // phosphor: they stop at fluorescent surfaces).
        if let Some(clock) = self.clock {
            let mut time_stream = stream.clone();
            if !self
                .scene
                .timeline()
                .on(emitted.light, clock.time(&mut time_stream))
            {
                return 0;
            }
        }
        let mut ray = emitted.ray;
        let mut beta = L::start(emitted.beta, ray.direction.normalize(), || {
            let p = self.scene.light_polarization(emitted.light)?;
            Some(p.stokes(ray.direction.normalize()))
        });
        let initial = beta.max_value();
        let mut rays = 0u64;
        let mut depth = 0u32;
        loop {
            rays += 1;
            let Some(hit) = self.scene.intersect(&ray) else {
                break;
            };
            absorb(self.scene, &ray, &hit, &lambdas, &mut beta);
            let material = self.scene.material(&hit);
            if material.fluorescent() {
                // Re-radiation changes wavelength: this light stays with camera paths.
                break;
            }
            // Light whose first bounce cannot be focused is no caustic (the test below,
            // made before building the BSDF: most light from infinity lands so).
            if depth == 0 && !material.focuses(CAUSTIC_ALPHA) {
                break;
            }
            let bsdf = self.scene.bsdf(&hit, &lambdas, TransportMode::Importance);
            let frame = Frame::from_normal(hit.shading_normal);
            let wo_world = -ray.direction.normalize();
            let wo = frame.to_local(wo_world);
            let vertex = Vertex {
                bsdf: &bsdf,
                frame: &frame,
                wo,
            };
            // Adjoint BSDFs with shading normals (Veach 1997, §5.3): light paths weigh a
            // bounce by |wo.ns| |wi.ng| / |wo.ng| where camera paths use |wi.ns|.
            let shading = |wi_world: glam::Vec3| {
                let geometric_wo = wo_world.dot(hit.normal).abs();
                if geometric_wo > 0.0 {
                    wo.z.abs() * wi_world.dot(hit.normal).abs() / geometric_wo
                } else {
                    0.0
                }
            };

            // This vertex would be the path's (depth + 1)-th bounce; camera paths keep at
            // most max_depth.
            if depth >= self.max_depth {
                break;
            }
            // After at least one delta bounce, a surface the camera can see is where the
            // caustic lands.
            if depth > 0
                && !bsdf.is_narrow(CAUSTIC_ALPHA)
                && let Some(seen) = self.seen(hit.p, aspect, stream, depth)
            {
                let wi_world = -seen.direction;
                let wi = frame.to_local(wi_world);
                let f = bsdf.f(wo, wi);
                let weight = shading(wi_world) * seen.importance / (seen.distance * seen.distance);
                if !f.is_black() && weight > 0.0 && weight.is_finite() {
                    rays += 1;
                    if !self.scene.occluded(&hit.spawn_to(wi_world, seen.distance)) {
                        let radiance =
                            beta.seen(&vertex, wi, wi_world, &f, weight, &self.camera_frame);
                        sink(seen.film, &radiance, &lambdas);
                    }
                }
            }
            stream.set_dimension(FIRST_BOUNCE_DIMENSION + u64::from(depth) * DIMENSIONS_PER_BOUNCE);
            let u_lobe = stream.next_1d();
            let u_bsdf = stream.next_2d();
            let u_roulette = stream.next_1d();
            let Some(sample) = bsdf.sample(wo, u_lobe, u_bsdf) else {
                break;
            };
            // Light leaving the light's first surface by a non-delta bounce is no caustic:
            // camera paths carry it. Past the first delta bounce the path goes on, and
            // connects to the camera from every non-delta surface it lands on.
            if depth == 0 && !sample.delta && !bsdf.is_narrow(CAUSTIC_ALPHA) {
                break;
            }
            let pdf = sample.pdf[0];
            if !positive_finite(pdf) {
                break;
            }
            let wi_world = frame.to_world(sample.wi);
            beta.bounce(&vertex, sample.wi, &sample.f, shading(wi_world) / pdf);
            if sample.wavelength_dependent && !package.secondary_terminated() {
                // A dispersive refraction sends only the hero on; the connections made so
                // far went to the film with the whole package.
                package.terminate_secondary();
                lambdas = match wavelengths(&package) {
                    Some(l) => l,
                    None => break,
                };
            }
            ray = hit.spawn(wi_world);
            depth += 1;

            // Russian roulette relative to the light's initial throughput (light paths
            // carry power, not a fraction of one).
            if depth >= ROULETTE_DEPTH {
                let q = (beta.max_value() / initial).min(0.95);
                if q.is_nan() || q <= 0.0 || u_roulette >= q {
                    break;
                }
                beta.scale_uniform(1.0 / q);
            }
        }
        rays
    }
}
