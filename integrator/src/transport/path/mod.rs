//! One camera path: unidirectional path tracing with next-event estimation, MIS by the
//! power heuristic between light and BSDF sampling, Russian roulette, and a package of
//! wavelengths that is split at dispersive delta events.

mod clock;
mod fluorescence;
mod footprint;
mod light;
mod walk;

use glam::Vec2;
use prism_sampling::distribution::positive_finite;
use prism_sampling::stream::{SampleStream, SobolStream};
use prism_sampling::wavelength::{PackageScheme, WavelengthDistribution, WavelengthPackage};
use prism_scene::geometry::Ray;
use prism_scene::world::{EmissionCache, Scene};
use prism_spectrum::colorimetry::Observer;
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

pub(crate) use clock::Clock;
pub(crate) use footprint::Footprint;
pub(crate) use walk::Walk;
pub(crate) use walk::roulette_capped;

use crate::transport::reuse_record::{FirstVertex, ReuseRecord};
use crate::transport::throughput::{Carried, Throughput, Vertex};

/// What every path of a render shares.
pub(crate) struct Tracer<'a> {
    pub scene: &'a Scene,
    pub distribution: &'a WavelengthDistribution,
    pub scheme: PackageScheme,
    pub observer: Observer,
    /// A camera's response curves replacing the observer, if any.
    pub camera: Option<&'a crate::CameraResponse>,
    /// Bounces after which a path ends (u32::MAX: unbounded).
    pub max_depth: u32,
    /// Whether light paths carry caustics (light, then one or more delta bounces, then
    /// non-fluorescent surfaces, the last a non-delta one the camera sees): camera paths
    /// then leave those to them, so that each path is counted by one estimator.
    pub light_caustics: bool,
    /// Light paths' aim at the surfaces where their first bounce can be focused
    /// (`Material::focuses`): light from infinity crosses their bounding sphere (None: no
    /// light paths).
    pub aim: Option<&'a prism_scene::world::Aim>,
    /// Whether camera rays that leave the scene show nothing (a transparent background).
    pub transparent: bool,
    /// How wide a pixel's footprint is where a path meets a surface, for filtering
    /// textures (None: the scene has no texture to filter).
    pub footprint: Option<Footprint>,
    /// The polarized camera frame (read only by polarized renders).
    pub camera_frame: crate::transport::throughput::CameraFrame,
    /// The instant or exposure rendered on the scene's clock (None: the steady state,
    /// every source always on).
    pub clock: Option<Clock>,
    /// Continuations per camera sample from its first non-delta vertex (1: none split).
    pub splits: u32,
    /// The media the camera is in (read only by the volumetric path tracer).
    pub camera_media: crate::transport::volume::MediumStack,
    /// The camera's thin lens, ready (None: a pinhole).
    pub focus: Option<prism_scene::camera::Focus>,
    /// The camera's lens system, focused (None: a pinhole or a thin lens).
    pub system: Option<std::sync::Arc<prism_scene::camera::FocusedSystem>>,
}

/// The sample-stream dimension of a camera ray's point on the lens: far past any bounce's,
/// so that a pinhole camera's samples draw what they always did.
pub(crate) const LENS_DIMENSION: u64 = 1 << 40;

/// The sample-stream dimensions: the wavelength and the film position first, then a fixed
/// block per bounce so that bounce k always draws from the same dimensions.
pub(crate) const FIRST_BOUNCE_DIMENSION: u64 = 3;
pub(crate) const DIMENSIONS_PER_BOUNCE: u64 = 8;

/// The first bounce at which Russian roulette may end a path.
pub(crate) const ROULETTE_DEPTH: u32 = 3;

/// The throughput below which Russian roulette puts a path at risk: it survives with
/// probability min(0.95, throughput / ROULETTE_THROUGHPUT), so survivors carry at least
/// this much. Survival equal to the throughput (1 here) ended too many paths that still
/// had light to bring: measured as efficiency, 1 / (seconds x relative MSE), on five
/// scenes (docs/trade-offs.md), 0.25 is 10-23% more efficient on the Cornell box, the
/// bunny box, the glass bunny and the effects stage and twice as efficient under the
/// blacklight, for 5-13% fewer paths per second; 0.5 and 0.125 gain less.
const ROULETTE_THROUGHPUT: f32 = 0.25;

pub(crate) use prism_scene::geometry::Frame;

/// The result of one path; its light went to the caller's sink.
pub(crate) struct PathResult {
    /// Whether the path could be traced (its wavelengths were valid).
    pub valid: bool,
    /// Rays traced (camera, continuation and shadow rays).
    pub rays: u64,
    /// Of `rays`, path reuse's connections to other pixels' second vertices (each a
    /// shadow ray, and cheaper than a ray of the path with the work around it).
    pub connections: u64,
    /// Whether the camera ray met geometry (the pixel's coverage, its alpha).
    pub covered: bool,
}

impl PathResult {
    /// A path that traced nothing: a sample of invalid wavelengths (not `valid`, not
    /// counted), or one whose camera ray a lens stopped (`valid`: a black sample).
    pub(crate) const fn nothing(valid: bool) -> Self {
        Self {
            valid,
            rays: 0,
            connections: 0,
            covered: false,
        }
    }
}

/// Beer-Lambert absorption of the segment `ray` just traced to `hit`, if it ran inside an
/// absorbing volume (the ray meets the inside of its boundary).
pub(crate) fn absorb<const N: usize>(
    scene: &Scene,
    ray: &Ray,
    hit: &prism_scene::world::Hit,
    transport: &SampledWavelengths<N>,
    beta: &mut impl Carried<N>,
) {
    if let Some(sigma) = scene.material(hit).absorption()
        && ray.direction.dot(hit.normal) > 0.0
    {
        let distance = hit.t * ray.direction.length();
        let sigma = sigma.at(transport);
        beta.scale(SampledSpectrum::from_fn(|i| (-sigma[i] * distance).exp()));
    }
}

pub(crate) fn wavelengths<const N: usize>(
    package: &WavelengthPackage<N>,
) -> Option<SampledWavelengths<N>> {
    SampledWavelengths::new(package.lambda, package.pdf).ok()
}

impl<'a> Tracer<'a> {
    /// What turns this render's spectra into the film's colour.
    #[inline(always)]
    pub(crate) fn sensor(&self) -> crate::film::sample_value::Sensor<'a> {
        crate::film::sample_value::Sensor {
            observer: self.observer,
            camera: self.camera,
        }
    }

    /// The camera ray of the sample `stream` belongs to (at any dimension) through film
    /// point `film`, for the hero wavelength `lambda` (nm), and its weight: through the
    /// pinhole (weight 1), from the thin lens's point the sample's lens dimensions choose
    /// (weight 1), or through a lens system's elements along the path those dimensions
    /// choose. None where a lens system's elements stop the ray: the sample sees black.
    #[inline(always)]
    pub(crate) fn camera_ray(
        &self,
        film: Vec2,
        aspect: f32,
        stream: &SobolStream,
        lambda: f32,
    ) -> Option<(Ray, f32)> {
        let camera = self.scene.camera();
        let lens_numbers = || {
            let mut lens = stream.clone();
            lens.set_dimension(LENS_DIMENSION);
            lens.next_2d()
        };
        if let Some(system) = &self.system {
            return camera.generate_ray_system(film, system, lens_numbers(), lambda);
        }
        Some(match &self.focus {
            None => (camera.generate_ray(film, aspect), 1.0),
            Some(focus) => (
                camera.generate_ray_through(film, aspect, Some(focus), lens_numbers()),
                1.0,
            ),
        })
    }

    /// The package of wavelengths a sample draws with `u_lambda` (its hero's number): only
    /// the hero behind a lens system whose glass disperses, since each wavelength's camera
    /// ray takes its own way through the elements.
    pub(crate) fn package<const N: usize>(&self, u_lambda: f32) -> WavelengthPackage<N> {
        let mut package =
            WavelengthPackage::<N>::sample(self.distribution, f64::from(u_lambda), self.scheme);
        if self.system.as_ref().is_some_and(|s| s.dispersive()) {
            package.terminate_secondary();
        }
        package
    }

    /// Traces the path of sample `stream` through film point `film` (in [0, 1]^2) of an
    /// image with aspect ratio `aspect`. The stream must be positioned after the film
    /// dimensions; `first_package` holds the sample's wavelengths ([`Tracer::package`]),
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
        let Some(first_lambdas) = wavelengths(&first_package) else {
            return PathResult::nothing(false);
        };
        let first_times = self.clock.map(|clock| [clock.time(stream); N]);
        let Some((camera_ray, lens_weight)) =
            self.camera_ray(film, aspect, stream, first_package.lambda[0])
        else {
            return PathResult::nothing(true);
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
            let mut walk = Walk::<N, T>::new(
                first_package,
                first_lambdas,
                first_times,
                camera_ray,
                &self.camera_frame,
            );
            walk.weigh_camera_ray(lens_weight);
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
                    record.first = FirstVertex::recorded(material, hit, frame, wo, &bsdf, &sample, pdf);
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
