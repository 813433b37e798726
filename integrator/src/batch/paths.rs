//! A batch's paths from the camera to their ends: the loop over bounces, with every lane's
//! state between them.

use glam::Vec3;
use prism_sampling::lanes::real::Reals;
use prism_sampling::mis::power_heuristic;
use prism_sampling::stream::SobolStream;
use prism_scene::geometry::Ray;
use prism_scene::world::{EmissionCache, Hit, Scene};
use prism_spectrum::SampledWavelengths;

use super::lane_spectrum;
use super::vertex::{Draws, lambertian_vertex};
use crate::filter::FilterSampler;
use crate::path::{DIMENSIONS_PER_BOUNCE, FIRST_BOUNCE_DIMENSION, PathResult, Tracer, wavelengths};
use crate::render::{Rows, camera_sample};
use crate::sample_value::SampleValue;

/// Lanes of reals, libm's sine in each (each lane its path's values to the bit).
pub(super) type Exact<const W: usize> = Reals<W, true>;

/// Spectra in lanes: one lane array per wavelength of the package.
pub(super) type Spectra<const N: usize, const W: usize> = [Exact<W>; N];

/// The batch between bounces: what each lane's path carries, and what it needs of its own.
pub(super) struct Paths<const N: usize, const W: usize> {
    /// Whether the lane's path goes on.
    pub alive: [bool; W],
    pub streams: [SobolStream; W],
    /// Each lane's wavelengths (None: its sample's were invalid, or no pixel is in it).
    pub lambdas: [Option<SampledWavelengths<N>>; W],
    pub caches: [EmissionCache<N>; W],
    pub results: [PathResult; W],
    /// The ray each live path follows next.
    pub rays: [Ray; W],
    pub beta: Spectra<N, W>,
    pub radiance: Spectra<N, W>,
    /// The last bounce's density and origin, for MIS on the emitters a ray meets (read
    /// after the first bounce: every vertex this tracer serves is non-delta).
    pub previous_pdf: Exact<W>,
    pub previous_p: [Vec3; W],
    /// Bounces so far (the same in every live lane).
    pub depth: u32,
}

/// Traces sample `s` of the `count` (<= W) pixels of row `y` from `x0` on, each into its
/// `values` entry (cleared first), and returns their results, as the path tracer's
/// `trace_sample` would pixel by pixel.
#[inline(always)]
pub(super) fn trace_batch<const N: usize, const W: usize>(
    tracer: &Tracer,
    filter: &FilterSampler,
    rows: &Rows,
    (x0, y): (u32, u32),
    count: usize,
    s: u64,
    values: &mut [SampleValue; W],
) -> [PathResult; W] {
    let mut paths = Paths::<N, W>::start(tracer, filter, rows, (x0, y), count, s);
    let scene = tracer.scene;
    loop {
        let mut hits: [Option<(Hit, Vec3)>; W] = [None; W];
        for (i, hit) in hits.iter_mut().enumerate() {
            *hit = paths.meet(tracer, i);
        }
        if !paths.alive.contains(&true) {
            break;
        }
        let dimension = FIRST_BOUNCE_DIMENSION + u64::from(paths.depth) * DIMENSIONS_PER_BOUNCE;
        let draws = Draws::from_streams(&mut paths.streams, &paths.alive, dimension);
        lambertian_vertex(scene, &mut paths, &hits, &draws);
    }
    for (i, value) in values.iter_mut().enumerate().take(count) {
        value.clear();
        if let Some(lambdas) = &paths.lambdas[i] {
            let radiance = lane_spectrum(&paths.radiance, i);
            value.add(tracer, rows.outputs, &radiance, lambdas);
        }
    }
    paths.results
}

impl<const N: usize, const W: usize> Paths<N, W> {
    /// The camera rays of sample `s` of the batch's pixels; lanes past `count`, and
    /// samples whose wavelengths are invalid, start dead.
    #[inline(always)]
    fn start(
        tracer: &Tracer,
        filter: &FilterSampler,
        rows: &Rows,
        (x0, y): (u32, u32),
        count: usize,
        s: u64,
    ) -> Self {
        let aspect = rows.width as f32 / rows.height as f32;
        let mut alive = [false; W];
        let mut rays = [Ray::new(Vec3::ZERO, Vec3::Z, 0.0); W];
        let mut lambdas = [None; W];
        let streams: [SobolStream; W] = std::array::from_fn(|i| {
            if i >= count {
                return SobolStream::new(rows.seed, 0, s);
            }
            let (stream, u_lambda, film) = camera_sample(filter, rows, x0 + i as u32, y, s);
            if let Some(l) = wavelengths(&tracer.package::<N>(u_lambda)) {
                lambdas[i] = Some(l);
                alive[i] = true;
                rays[i] = tracer.scene.camera().generate_ray(film, aspect);
            }
            stream
        });
        Self {
            results: std::array::from_fn(|i| PathResult {
                valid: alive[i],
                rays: 0,
                covered: false,
            }),
            alive,
            streams,
            lambdas,
            caches: std::array::from_fn(|_| EmissionCache::new()),
            rays,
            beta: [Exact::from_fn(|_| 1.0); N],
            radiance: [Exact::from_fn(|_| 0.0); N],
            previous_pdf: Exact::from_fn(|_| 0.0),
            previous_p: [Vec3::ZERO; W],
            depth: 0,
        }
    }

    /// Traces lane `i`'s ray, if its path is alive, and adds the light it meets: the
    /// environment where it leaves the scene, the emission of the surface it hits. Returns
    /// the hit and the direction back along the ray where the path goes on from it.
    #[inline(always)]
    fn meet(&mut self, tracer: &Tracer, i: usize) -> Option<(Hit, Vec3)> {
        let (true, Some(lambdas)) = (self.alive[i], self.lambdas[i]) else {
            return None;
        };
        let scene = tracer.scene;
        let ray = self.rays[i];
        self.results[i].rays += 1;
        let hit = scene.intersect(&ray);
        if self.depth == 0 {
            self.results[i].covered = hit.is_some();
        }
        let Some(mut hit) = hit else {
            self.alive[i] = false;
            if self.depth > 0 || !tracer.transparent {
                self.add_escaped(scene, i, &lambdas);
            }
            return None;
        };
        let wo_world = -ray.direction.normalize();
        if let Some(footprint) = &tracer.footprint {
            let width = footprint.at(hit.p);
            scene.set_footprint(&mut hit, wo_world, width);
        }
        let le = scene.emitted(&hit, wo_world, &lambdas, &mut self.caches[i]);
        if !le.is_black() {
            let w = if self.depth == 0 {
                1.0
            } else {
                let light_pdf =
                    scene.light_pdf(self.previous_p[i], &hit, &lambdas, &mut self.caches[i]);
                power_heuristic(1, self.previous_pdf.lane(i), 1, light_pdf)
            };
            self.add_emitted(i, &le, w);
        }
        if self.depth >= tracer.max_depth {
            self.alive[i] = false;
            return None;
        }
        Some((hit, wo_world))
    }

    /// Adds the environment's light along lane `i`'s ray, which left the scene.
    fn add_escaped(&mut self, scene: &Scene, i: usize, lambdas: &SampledWavelengths<N>) {
        let direction = self.rays[i].direction.normalize();
        let Some((le, light_pdf)) = scene.escaped(direction, lambdas, &mut self.caches[i]) else {
            return;
        };
        let w = if self.depth == 0 {
            1.0
        } else {
            power_heuristic(1, self.previous_pdf.lane(i), 1, light_pdf)
        };
        self.add_emitted(i, &le, w);
    }

    /// radiance += beta le w in lane `i` (the path tracer's order of operations).
    fn add_emitted(&mut self, i: usize, le: &prism_spectrum::SampledSpectrum<N>, w: f32) {
        for j in 0..N {
            let added = self.beta[j].lane(i) * le[j] * w;
            self.radiance[j].0.0[i] += added;
        }
    }
}
