//! One camera path: unidirectional path tracing with next-event estimation, MIS by the
//! power heuristic between light and BSDF sampling, Russian roulette, and a package of
//! wavelengths that is split at dispersive delta events.

use glam::{Vec2, Vec3};
use prism_sampling::distribution::positive_finite;
use prism_sampling::mis::power_heuristic;
use prism_sampling::stream::{SampleStream, SobolStream};
use prism_sampling::wavelength::{
    PackageScheme, ReradiationSampler, WavelengthDistribution, WavelengthPackage,
};
use prism_scene::bsdf::{Diffuse, TransportMode};
use prism_scene::geometry::Ray;
use prism_scene::world::{Bsdf, EmissionCache, Hit, Material, Scene, SceneSpectrum};
use prism_spectrum::colorimetry::Observer;
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use crate::reuse::{First, Record, Second};
use crate::throughput::{Arrival, Carried, Throughput, Vertex};

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
    /// Whether light paths carry the caustics seen directly (light, then one or more
    /// delta bounces, then a non-delta, non-fluorescent surface the camera sees): camera
    /// paths then leave those to them, so that each path is counted by one estimator.
    pub light_caustics: bool,
    /// Whether camera rays that leave the scene show nothing (a transparent background).
    pub transparent: bool,
    /// How wide a pixel's footprint is where a path meets a surface, for filtering
    /// textures (None: the scene has no texture to filter).
    pub footprint: Option<Footprint>,
    /// The polarized camera frame (read only by polarized renders).
    pub camera_frame: crate::throughput::CameraFrame,
    /// The instant or exposure rendered on the scene's clock (None: the steady state,
    /// every source always on).
    pub clock: Option<Clock>,
    /// Continuations per camera sample from its first non-delta vertex (1: none split).
    pub splits: u32,
}

/// A pixel's footprint at a point, as pbrt-v4 approximates it for every vertex of a path
/// (`Camera::Approximate_dp_dxy`): the width a camera ray's pixel cone would have there,
/// halved, since the pixel filter averages the samples too (pbrt-v4 narrows it by
/// max(1/8, 1/sqrt(spp)); a fixed factor keeps an image independent of how its samples
/// are split between passes and machines, and 1/2 is pbrt-v4's at 4 spp).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Footprint {
    /// The camera's position (perspective) or None (orthographic: the width is constant).
    pub origin: Option<Vec3>,
    /// Width per unit of distance from the camera (perspective), or the width itself.
    pub width: f32,
}

impl Footprint {
    /// For `camera` rendering `height` rows.
    pub(crate) fn new(camera: &prism_scene::camera::Camera, height: u32) -> Self {
        let narrowing = 0.5;
        let rows = height.max(1) as f32;
        match camera.projection {
            prism_scene::camera::Projection::Perspective { yfov } => Self {
                origin: Some(camera.to_world.transform_point3(Vec3::ZERO)),
                width: 2.0 * (0.5 * yfov).tan() / rows * narrowing,
            },
            prism_scene::camera::Projection::Orthographic { ymag, .. } => Self {
                origin: None,
                width: 2.0 * ymag / rows * narrowing,
            },
        }
    }

    /// The footprint's width at `p`.
    pub(crate) fn at(&self, p: Vec3) -> f32 {
        match self.origin {
            Some(o) => self.width * (p - o).length(),
            None => self.width,
        }
    }
}

/// The sample-stream dimensions: the wavelength and the film position first, then a fixed
/// block per bounce so that bounce k always draws from the same dimensions.
pub(crate) const FIRST_BOUNCE_DIMENSION: u64 = 3;
const DIMENSIONS_PER_BOUNCE: u64 = 8;

/// When a path sees the scene: an instant, or a time drawn uniformly from an exposure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Clock {
    At(f64),
    Shutter(f64, f64),
}

/// The sample-stream dimension an exposure's time is drawn from: far past any bounce's,
/// so that it changes no other dimension.
const TIME_DIMENSION: u64 = 1 << 24;

impl Clock {
    /// The clock of `settings` (None: the steady state).
    pub(crate) fn of(settings: &crate::RenderSettings) -> Option<Self> {
        match (settings.at, settings.shutter) {
            (Some(t), _) => Some(Clock::At(t)),
            (None, Some((open, close))) => Some(Clock::Shutter(open, close)),
            (None, None) => None,
        }
    }

    /// The time of the path whose stream is `stream` (an instant's is fixed; an
    /// exposure's uniform in it). Leaves the stream at another dimension.
    pub(crate) fn time(&self, stream: &mut SobolStream) -> f64 {
        match *self {
            Clock::At(t) => t,
            Clock::Shutter(open, close) => {
                stream.set_dimension(TIME_DIMENSION);
                let u = f64::from(stream.next_1d());
                (open + u * (close - open)).min(close)
            }
        }
    }
}

/// The first bounce at which Russian roulette may end a path.
const ROULETTE_DEPTH: u32 = 3;

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
    /// Whether the camera ray met geometry (the pixel's coverage, its alpha).
    pub covered: bool,
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

/// What the light a path meets is weighed with: the wavelengths and times it is evaluated
/// at, and the last bounce's BSDF density and origin (None after the camera or a delta
/// bounce), for MIS against light sampling.
struct Arrived<'p, const N: usize> {
    transport: &'p SampledWavelengths<N>,
    times: Option<&'p [f64; N]>,
    previous: Option<(f32, Vec3)>,
}

impl<'a> Tracer<'a> {
    /// The package of wavelengths a sample draws with `u_lambda` (its hero's number).
    pub(crate) fn package<const N: usize>(&self, u_lambda: f32) -> WavelengthPackage<N> {
        WavelengthPackage::<N>::sample(self.distribution, f64::from(u_lambda), self.scheme)
    }

    /// Darkens the lanes of `le`, light `light`'s, whose time finds it off.
    fn gate<const N: usize>(
        &self,
        light: Option<u32>,
        times: &[f64; N],
        le: &mut SampledSpectrum<N>,
    ) {
        let Some(light) = light else { return };
        let timeline = self.scene.timeline();
        for (j, t) in times.iter().enumerate() {
            if !timeline.on(light, *t) {
                le[j] = 0.0;
            }
        }
    }

    /// At a phosphor, sends each re-emitting lane back to when its light was absorbed: a
    /// delay drawn with `u` from the decay law restricted to when some source shone,
    /// weighing the lane by the law's mass there (`prism_sampling::decay`); a lane with
    /// nothing to absorb is dark.
    fn delay<const N: usize>(
        &self,
        decay: &prism_sampling::decay::Decay,
        u: f32,
        reemitted: &[bool; N],
        times: &mut [f64; N],
        weights: &mut SampledSpectrum<N>,
    ) {
        let on = self.scene.timeline().any_on();
        for j in 0..N {
            if !reemitted[j] {
                continue;
            }
            let windows = prism_sampling::decay::delay_windows(times[j], on);
            match decay.sample_within(f64::from(u), &windows) {
                Some((d, mass)) => {
                    times[j] -= d;
                    weights[j] *= mass as f32;
                }
                None => weights[j] = 0.0,
            }
        }
    }

    /// At a fluorescent vertex of reflectance `reflectance` and re-radiation `reradiation`,
    /// the wavelength each lane's light arrived at, the lane's weight, and whether it was
    /// re-emitted (drawn with `u_wavelength`): unchanged with probability R / (R + F)
    /// (weight R + F), else from the re-radiation column F or the lights' spectra, one-sample
    /// MIS with the balance heuristic (weight (R + F) / F * M / p_mix).
    #[inline]
    fn reradiated<const N: usize>(
        &self,
        hit: &Hit,
        reflectance: &SceneSpectrum,
        reradiation: &ReradiationSampler,
        transport: &SampledWavelengths<N>,
        u_wavelength: f32,
    ) -> ([f32; N], SampledSpectrum<N>, [bool; N]) {
        let guide = self.scene.light_wavelengths(hit);
        let r = reflectance.at_uv(hit.tex, transport);
        let mut incident = *transport.lambdas();
        let mut weights = SampledSpectrum::splat(1.0);
        let mut reemitted = [false; N];
        for j in 0..N {
            let out = transport.lambda(j);
            let f = reradiation.incident_integral(out) as f32;
            let total = r[j] + f;
            let mut weight = total;
            if total > 0.0 && f > 0.0 && u_wavelength * total >= r[j] {
                let u = ((u_wavelength * total - r[j]) / f).min(0.999_999_9);
                let lambda = match guide {
                    None => reradiation
                        .sample_incident(out, f64::from(u))
                        .map(|s| s.lambda),
                    Some(_) if u < 0.5 => reradiation
                        .sample_incident(out, f64::from(2.0 * u))
                        .map(|s| s.lambda),
                    Some(g) => Some(g.sample(f64::from(2.0 * u - 1.0)).value as f32),
                };
                weight = match lambda {
                    Some(l) => {
                        let p_column = reradiation.pdf_incident(l, out);
                        let p = match guide {
                            None => p_column,
                            Some(g) => 0.5 * p_column + 0.5 * g.pdf(f64::from(l)) as f32,
                        };
                        incident[j] = l;
                        reemitted[j] = true;
                        if p > 0.0 {
                            total / f * reradiation.value(l, out) as f32 / p
                        } else {
                            0.0
                        }
                    }
                    None => 0.0,
                };
            }
            weights[j] = weight;
        }
        (incident, weights, reemitted)
    }

    /// Adds the light of the environment a ray that left the scene arrives from, weighed by
    /// MIS against light sampling after a bounce.
    #[inline(always)]
    fn add_escaped<const N: usize, T: Throughput<N>>(
        &self,
        ray: &Ray,
        arrived: &Arrived<'_, N>,
        emission: &mut EmissionCache<N>,
        beta: &T,
        radiance: &mut T::Radiance,
    ) {
        let Some((mut le, light_pdf)) =
            self.scene
                .escaped(ray.direction.normalize(), arrived.transport, emission)
        else {
            return;
        };
        if let Some(times) = arrived.times {
            self.gate(self.scene.environment_light(), times, &mut le);
        }
        let w = arrived.previous.map_or(1.0, |(bsdf_pdf, _)| {
            power_heuristic(1, bsdf_pdf, 1, light_pdf)
        });
        beta.add_emitted(radiance, &le, w);
    }

    /// Adds the light `hit` emits towards `wo_world`, weighed by MIS against light
    /// sampling after a bounce.
    #[inline(always)]
    fn add_hit_emission<const N: usize, T: Throughput<N>>(
        &self,
        hit: &Hit,
        wo_world: Vec3,
        arrived: &Arrived<'_, N>,
        emission: &mut EmissionCache<N>,
        beta: &T,
        radiance: &mut T::Radiance,
    ) {
        let mut le = self
            .scene
            .emitted(hit, wo_world, arrived.transport, emission);
        if le.is_black() {
            return;
        }
        if let Some(times) = arrived.times {
            self.gate(self.scene.light_of(hit), times, &mut le);
            if le.is_black() {
                return;
            }
        }
        let w = arrived.previous.map_or(1.0, |(bsdf_pdf, from)| {
            let light_pdf = self.scene.light_pdf(from, hit, arrived.transport, emission);
            power_heuristic(1, bsdf_pdf, 1, light_pdf)
        });
        beta.add_emitted(radiance, &le, w);
    }

    /// Next-event estimation at `vertex` (not a delta): a light sampled with `u_light`, its
    /// shadow ray traced unless the light or the BSDF is dark at every wavelength, and what
    /// arrives added to `radiance` with the power heuristic against BSDF sampling. Returns
    /// the rays traced.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn next_event<const N: usize, T: Throughput<N>>(
        &self,
        hit: &Hit,
        vertex: &Vertex<'_, '_, N>,
        u_light: Vec2,
        transport: &SampledWavelengths<N>,
        times: Option<&[f64; N]>,
        emission: &mut EmissionCache<N>,
        beta: &T,
        radiance: &mut T::Radiance,
    ) -> u64 {
        let Some(mut light) = self.scene.sample_light(hit, u_light, transport, emission) else {
            return 0;
        };
        if let Some(times) = times {
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
            beta.add_scattered(radiance, vertex, arrival, || {
                let p = self.scene.light_polarization(light.light)?;
                Some(p.stokes(-light.wi))
            });
        }
        1
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
    /// (`crate::reuse`; never with `SPLIT`): where its first vertex is Lambertian and its
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
        record: &mut Record<'a, N, T::Radiance>,
        emission: &mut EmissionCache<N>,
    ) -> PathResult {
        let first_package = *first_package;
        let Some(first_lambdas) = wavelengths(&first_package) else {
            return PathResult {
                valid: false,
                rays: 0,
                covered: false,
            };
        };
        let first_times = self.clock.map(|clock| [clock.time(stream); N]);
        let camera_ray: Ray = self.scene.camera().generate_ray(film, aspect);
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
            let mut package = first_package;
            let mut lambdas = first_lambdas;
            // The wavelengths light is evaluated at. They are the film's (`lambdas`, whose
            // densities weigh the estimate) until a fluorescent vertex changes them: past it,
            // each lane carries the incident wavelength it sampled, while its radiance still
            // counts at the film wavelength it started with.
            let mut transport = lambdas;
            // The time each lane's light is evaluated at, when rendering an instant: the
            // camera's, until a phosphor sends a lane back to when its light was absorbed.
            let mut times = first_times;
            let mut ray = camera_ray;
            let mut radiance = T::black();
            let mut beta = T::start(ray.direction.normalize(), &self.camera_frame);
            // The BSDF density and origin of the last bounce, for MIS on emitters it hits;
            // None after the camera or a delta bounce (no light sampling competed).
            let mut previous: Option<(f32, Vec3)> = None;
            let mut depth = 0u32;
            // The product of eta^2 over the refractions so far, and the split count: beta
            // carries 1 / eta^2 from each refraction and 1 / splits from the split, neither of
            // which Russian roulette may read as lost energy.
            let mut eta_scale = 1.0f32;
            // Whether the path so far is one that light paths carry: a first vertex that is
            // neither a delta nor fluorescent, then only delta bounces (at least one).
            let mut caustic_prefix = false;
            let mut light_caustic = false;
            // The stream of this split's bounces (set at the first vertex).
            let mut bounces = stream.clone();
            loop {
                // A later split's first vertex repeats the first one's without its light: the
                // emission the camera sees and the light sample there were counted once.
                let replay = SPLIT && depth == 0 && split > 0;
                let hit = match &first_hit {
                    Some(hit) if replay => *hit,
                    _ => {
                        rays += 1;
                        let hit = self.scene.intersect(&ray);
                        if SPLIT && depth == 0 {
                            first_hit = Some(hit);
                        }
                        if depth == 0 {
                            covered = hit.is_some();
                        }
                        hit
                    }
                };
                let Some(mut hit) = hit else {
                    if depth == 0 && self.transparent {
                        break;
                    }
                    let arrived = Arrived {
                        transport: &transport,
                        times: times.as_ref(),
                        previous,
                    };
                    self.add_escaped(&ray, &arrived, emission, &beta, &mut radiance);
                    break;
                };
                let wo_world = -ray.direction.normalize();
                if let Some(footprint) = &self.footprint {
                    let width = footprint.at(hit.p);
                    self.scene.set_footprint(&mut hit, wo_world, width);
                }
                absorb(self.scene, &ray, &hit, &transport, &mut beta);
                // Light a light path carries, or a split's replay has counted, is not added.
                if !light_caustic && !replay {
                    let arrived = Arrived {
                        transport: &transport,
                        times: times.as_ref(),
                        previous,
                    };
                    self.add_hit_emission(&hit, wo_world, &arrived, emission, &beta, &mut radiance);
                }
                if REUSE && depth == 1 && record.first.is_some() && self.scene.reflects_alike(&hit)
                {
                    // From here the path estimates what the second vertex reflects, per unit
                    // of throughput: the tile's pixels share it. Russian roulette still reads
                    // the path's whole throughput.
                    eta_scale *= beta.max_value();
                    beta = T::start(ray.direction.normalize(), &self.camera_frame);
                    record.second = Some(Second::at(&hit, &ray, wo_world));
                    record.own = std::mem::replace(&mut radiance, T::black());
                }
                if depth >= self.max_depth {
                    break;
                }
                let dimension = sample_base + u64::from(depth) * DIMENSIONS_PER_BOUNCE;
                // The first vertex's own draws are the camera sample's; the rest the split's.
                let here: &mut SobolStream = if SPLIT && depth > 0 {
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
                let bsdf = match material {
                    Material::Fluorescent {
                        reflectance,
                        reradiation,
                    } if FLUORESCENCE => {
                        // Each lane picks the wavelength its light arrived at (`reradiated`);
                        // the surface is Lambertian either way.
                        let u_wavelength = here.next_1d();
                        let (incident, mut weights, reemitted) = self.reradiated(
                            &hit,
                            reflectance,
                            reradiation,
                            &transport,
                            u_wavelength,
                        );
                        if let (Some(times), Some(decay)) = (&mut times, self.scene.decay_at(&hit))
                        {
                            self.delay(decay, here.next_1d(), &reemitted, times, &mut weights);
                        }
                        beta.scale(weights);
                        transport = match SampledWavelengths::new(incident, *transport.pdfs()) {
                            Ok(t) => t,
                            Err(_) => break,
                        };
                        Bsdf::Diffuse(Diffuse::new(SampledSpectrum::splat(1.0)))
                    }
                    _ => {
                        self.scene
                            .bsdf_cached(&hit, &transport, TransportMode::Radiance, emission)
                    }
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
                    rays += self.next_event(
                        &hit,
                        &vertex,
                        u_light,
                        &transport,
                        times.as_ref(),
                        emission,
                        &beta,
                        &mut radiance,
                    );
                }

                if SPLIT && depth == 0 {
                    if split == 0 && !bsdf.is_delta() {
                        splits = self.splits.max(1);
                    }
                    bounces = stream.split(split, splits);
                    if splits > 1 {
                        beta.scale_uniform(1.0 / splits as f32);
                        eta_scale *= splits as f32;
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
                if REUSE
                    && depth == 0
                    && !sample.delta
                    && !sample.wavelength_dependent
                    && matches!(material, Material::Diffuse { .. })
                {
                    record.first = Some(First {
                        hit,
                        frame,
                        wo,
                        bsdf: bsdf.clone(),
                        wi: sample.wi,
                        pdf,
                    });
                }
                beta.scatter(
                    &vertex,
                    sample.wi,
                    &sample.f,
                    sample.delta,
                    sample.wi.z.abs() / pdf,
                );
                eta_scale *= sample.eta * sample.eta;
                if sample.wavelength_dependent && !package.secondary_terminated() {
                    // The secondaries' light so far was estimated with the whole package; it
                    // goes to the film with the package's densities before they change.
                    sink(&radiance, &lambdas);
                    radiance = T::black();
                    package.terminate_secondary();
                    lambdas = match wavelengths(&package) {
                        Some(l) => l,
                        None => break,
                    };
                    if !FLUORESCENCE {
                        transport = lambdas;
                    }
                }
                if depth == 0 {
                    caustic_prefix =
                        self.light_caustics && !sample.delta && !material.fluorescent();
                } else {
                    caustic_prefix &= sample.delta;
                    light_caustic = caustic_prefix;
                }
                previous = (!sample.delta).then_some((pdf, hit.p));
                let wi_world = frame.to_world(sample.wi);
                ray = hit.spawn(wi_world);
                depth += 1;

                // Russian roulette on the throughput, from the third bounce: survivors are
                // divided by their survival probability, so it is unbiased. Survival is capped
                // at 0.95 so that a path in a closed scene of albedo 1 (throughput never below
                // 1) still ends. The throughput is read without the refractions' 1 / eta^2
                // (what a path inside glass regains on leaving it): with it, paths inside
                // glass died at every bounce with probability 1 - 1/eta^2 (56% at 1.5).
                if depth >= ROULETTE_DEPTH {
                    let q = (beta.max_value() * eta_scale / ROULETTE_THROUGHPUT).min(0.95);
                    if q.is_nan() || q <= 0.0 || u_roulette >= q {
                        break;
                    }
                    beta.scale_uniform(1.0 / q);
                }
            }
            if REUSE && record.second.is_some() {
                sink(&record.own, &lambdas);
                record.reflected = radiance;
            } else {
                sink(&radiance, &lambdas);
            }
            split += 1;
        }
        PathResult {
            valid: true,
            rays,
            covered,
        }
    }
}
