//! Path reuse across a tile of pixels (Bekaert, Sbert and Halton 2002, "Accelerating path
//! tracing by re-using paths", EGRW): the pixels of a T x T tile trace sample s with the
//! same wavelengths, and each pixel's first vertex x1 gathers the reflected radiance of
//! every tile pixel's second vertex x2_k, not only its own. Each x2_k was sampled by its
//! own pixel's BSDF from x1_k; seen from pixel i it is one sample of T^2 techniques (one
//! per pixel's first vertex), combined by the balance heuristic over all of them (the
//! multi-sample estimator of Veach's thesis §9.2.2, one sample per technique): pixel i
//! adds f_i G_i V_i S_k / sum_m p_m(x2_k) for every k, where p_m is technique m's density
//! of x2_k in area measure (zero where x2_k is hidden from x1_m) and S_k the radiance
//! x2_k reflects. Unbiased, provided S_k is the same towards every x1_i: x2 must be a
//! constant Lambertian surface, seen from x1_i on the same side as from x1_k. Any other
//! second vertex (or a first vertex that is not Lambertian) stays its own pixel's alone.
//!
//! A reuse costs a shadow ray per pair of pixels (T^2 (T^2 - 1) per tile) and gives each
//! pixel T^2 continuations where splitting would trace them.

use glam::{Vec2, Vec3};
use prism_sampling::distribution::positive_finite;
use prism_sampling::mis::power_heuristic;
use prism_sampling::stream::{SampleStream, SobolStream};
use prism_sampling::wavelength::WavelengthPackage;
use prism_scene::geometry::Ray;
use prism_scene::world::{Bsdf, EmissionCache, Hit, Material, Scene};
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use crate::filter::FilterSampler;
use crate::path::{FIRST_BOUNCE_DIMENSION, Frame, Tracer, absorb, wavelengths};
use crate::render::Rows;
use crate::sample_value::SampleValue;

const DIMENSIONS_PER_BOUNCE: u64 = 8;
const ROULETTE_DEPTH: u32 = 3;
const ROULETTE_THROUGHPUT: f32 = 0.25;

/// A pixel's first vertex, when it is one that other pixels' second vertices can be
/// reached from (a Lambertian surface: its technique is cosine sampling).
struct First<'s, const N: usize> {
    hit: Hit,
    frame: Frame,
    wo: Vec3,
    bsdf: Bsdf<'s, N>,
}

/// A pixel's second vertex on a constant Lambertian surface, with the radiance it
/// reflects towards the side its first vertex is on.
struct Second<const N: usize> {
    p: Vec3,
    normal: Vec3,
    shading_normal: Vec3,
    /// Which side of the shading normal x1 is on (the reflected radiance is that side's).
    side: bool,
    /// The direction from x1 it was sampled in (local to x1's frame), and its density.
    wi: Vec3,
    pdf: f32,
    distance: f32,
    reflected: SampledSpectrum<N>,
}

/// One tile pixel's sample.
struct Pixel<'s, const N: usize> {
    film: Vec2,
    covered: bool,
    rays: u64,
    /// Everything the pixel's own path estimated except what reuse adds.
    own: SampledSpectrum<N>,
    first: Option<First<'s, N>>,
    second: Option<Second<N>>,
}

impl<'a> Tracer<'a> {
    /// Traces sample `s` of the tile's pixels `pixels` ((x, y) each) with the wavelengths
    /// of `u_lambda`, and returns each pixel's film position, radiance, rays and coverage.
    pub(crate) fn trace_tile<const N: usize>(
        &self,
        filter: &FilterSampler,
        rows: &Rows,
        pixels: &[(u32, u32)],
        s: u64,
        out: &mut Vec<(Vec2, SampledSpectrum<N>, u64, bool)>,
        lambdas_out: &mut Option<SampledWavelengths<N>>,
    ) {
        out.clear();
        let (w, h) = (rows.width, rows.height);
        let (x0, y0) = pixels[0];
        let tile_pixel = u64::from(y0) * u64::from(w) + u64::from(x0);
        let u_lambda = SobolStream::new(rows.seed, tile_pixel, s).next_1d();
        let package =
            WavelengthPackage::<N>::sample(self.distribution, f64::from(u_lambda), self.scheme);
        let Some(lambdas) = wavelengths(&package) else {
            *lambdas_out = None;
            return;
        };
        *lambdas_out = Some(lambdas);
        let aspect = w as f32 / h as f32;
        let mut emission = EmissionCache::new();
        let mut tile: Vec<Pixel<'a, N>> = Vec::with_capacity(pixels.len());
        for &(x, y) in pixels {
            let pixel = u64::from(y) * u64::from(w) + u64::from(x);
            let mut stream = SobolStream::new(rows.seed, pixel, s);
            let _ = stream.next_1d();
            let offset = filter.offset(stream.next_2d());
            let film = Vec2::new(
                (x as f32 + 0.5 + offset.x) / w as f32,
                (y as f32 + 0.5 + offset.y) / h as f32,
            );
            tile.push(self.prefix(&mut stream, film, aspect, &lambdas, &mut emission));
        }
        // Reuse: every pair (m, k) of a reusable first vertex and a Lambertian second one.
        let n = tile.len();
        let mut area_pdf = vec![0.0f32; n * n];
        let mut gathered = vec![SampledSpectrum::<N>::splat(0.0); n * n];
        let mut extra_rays = vec![0u64; n];
        for k in 0..n {
            let Some(second) = &tile[k].second else {
                continue;
            };
            let mut denominator = 0.0f32;
            for m in 0..n {
                let Some(first) = &tile[m].first else { continue };
                let (wi_world, distance, wi) = if m == k {
                    (first.frame.to_world(second.wi), second.distance, second.wi)
                } else {
                    let to = second.p - first.hit.p;
                    let distance = to.length();
                    if !positive_finite(distance) {
                        continue;
                    }
                    let wi_world = to / distance;
                    // x1_m must see x2_k's reflecting side.
                    if ((first.hit.p - second.p).dot(second.shading_normal) > 0.0) != second.side
                    {
                        continue;
                    }
                    (wi_world, distance, first.frame.to_local(wi_world))
                };
                let pdf = if m == k {
                    second.pdf
                } else {
                    first.bsdf.pdf(first.wo, wi)
                };
                if !positive_finite(pdf) {
                    continue;
                }
                let cos2 = second.normal.dot(wi_world).abs();
                let jacobian = cos2 / (distance * distance);
                if !positive_finite(jacobian) {
                    continue;
                }
                if m != k {
                    extra_rays[m] += 1;
                    if self
                        .scene
                        .occluded(&first.hit.spawn_to(wi_world, distance))
                    {
                        continue;
                    }
                }
                let p = pdf * jacobian;
                area_pdf[m * n + k] = p;
                denominator += p;
                let f = first.bsdf.f(first.wo, wi) * (wi.z.abs() * jacobian);
                gathered[m * n + k] = f * second.reflected;
            }
            if !positive_finite(denominator) {
                for m in 0..n {
                    gathered[m * n + k] = SampledSpectrum::splat(0.0);
                }
                continue;
            }
            for m in 0..n {
                if area_pdf[m * n + k] > 0.0 {
                    gathered[m * n + k] = gathered[m * n + k] * (1.0 / denominator);
                }
            }
        }
        for (m, pixel) in tile.iter().enumerate() {
            let mut radiance = pixel.own;
            for k in 0..n {
                if area_pdf[m * n + k] > 0.0 {
                    radiance += gathered[m * n + k];
                }
            }
            out.push((
                pixel.film,
                radiance,
                pixel.rays + extra_rays[m],
                pixel.covered,
            ));
        }
    }

    /// A pixel's camera ray, first vertex (its emission and light sample), the bounce to
    /// its second vertex and the path beyond.
    fn prefix<const N: usize>(
        &self,
        stream: &mut SobolStream,
        film: Vec2,
        aspect: f32,
        lambdas: &SampledWavelengths<N>,
        emission: &mut EmissionCache<N>,
    ) -> Pixel<'a, N> {
        let mut pixel = Pixel {
            film,
            covered: false,
            rays: 1,
            own: SampledSpectrum::splat(0.0),
            first: None,
            second: None,
        };
        let ray: Ray = self.scene.camera().generate_ray(film, aspect);
        let Some(mut hit) = self.scene.intersect(&ray) else {
            if !self.transparent
                && let Some((le, _)) =
                    self.scene
                        .escaped(ray.direction.normalize(), lambdas, emission)
            {
                pixel.own += le;
            }
            return pixel;
        };
        pixel.covered = true;
        let wo_world = -ray.direction.normalize();
        if let Some(footprint) = &self.footprint {
            let width = footprint.at(hit.p);
            self.scene.set_footprint(&mut hit, wo_world, width);
        }
        let mut beta = SampledSpectrum::<N>::splat(1.0);
        absorb(self.scene, &ray, &hit, lambdas, &mut beta);
        let le = self.scene.emitted(&hit, wo_world, lambdas, emission);
        pixel.own += beta * le;
        if self.max_depth == 0 {
            return pixel;
        }
        let dimension = FIRST_BOUNCE_DIMENSION;
        stream.set_dimension(dimension);
        let u_light = stream.next_2d();
        let u_lobe = stream.next_1d();
        let u_bsdf = stream.next_2d();
        let _u_roulette = stream.next_1d();
        let material = self.scene.material(&hit);
        let bsdf = self.scene.bsdf_cached(
            &hit,
            lambdas,
            prism_scene::bsdf::TransportMode::Radiance,
            emission,
        );
        let frame = Frame::from_normal(hit.shading_normal);
        let wo = frame.to_local(wo_world);
        pixel.rays += self.light_sample(&hit, &bsdf, &frame, wo, u_light, lambdas, emission, &beta, &mut pixel.own);
        let Some(sample) = bsdf.sample(wo, u_lobe, u_bsdf) else {
            return pixel;
        };
        let pdf = sample.pdf[0];
        if !positive_finite(pdf) {
            return pixel;
        }
        let b2 = beta * sample.f * (sample.wi.z.abs() / pdf);
        let wi_world = frame.to_world(sample.wi);
        let next = hit.spawn(wi_world);
        let reusable = !sample.delta && matches!(material, Material::Diffuse { .. });
        pixel.rays += 1;
        let previous = (!sample.delta).then_some((pdf, hit.p));
        let Some(mut hit2) = self.scene.intersect(&next) else {
            if let Some((le, light_pdf)) =
                self.scene.escaped(wi_world, lambdas, emission)
            {
                let w = previous.map_or(1.0, |(b, _)| power_heuristic(1, b, 1, light_pdf));
                pixel.own += b2 * le * w;
            }
            if reusable {
                pixel.first = Some(First { hit, frame, wo, bsdf });
            }
            return pixel;
        };
        let wo2 = -wi_world;
        if let Some(footprint) = &self.footprint {
            let width = footprint.at(hit2.p);
            self.scene.set_footprint(&mut hit2, wo2, width);
        }
        let mut b2 = b2;
        absorb(self.scene, &next, &hit2, lambdas, &mut b2);
        let le = self.scene.emitted(&hit2, wo2, lambdas, emission);
        if !le.is_black() {
            let w = previous.map_or(1.0, |(b, from)| {
                let light_pdf = self.scene.light_pdf(from, &hit2, lambdas, emission);
                power_heuristic(1, b, 1, light_pdf)
            });
            pixel.own += b2 * le * w;
        }
        let constant_lambertian = matches!(
            self.scene.material(&hit2),
            Material::Diffuse { reflectance } if !matches!(reflectance, prism_scene::world::SceneSpectrum::Texture(_))
        );
        let mut stream = stream.clone();
        if reusable && constant_lambertian {
            let scale = b2.max_value();
            let reflected =
                self.continuation(hit2, &next, SampledSpectrum::splat(1.0), scale, previous, &mut stream, lambdas, emission, &mut pixel.rays);
            pixel.second = Some(Second {
                p: hit2.p,
                normal: hit2.normal,
                shading_normal: hit2.shading_normal,
                side: wo2.dot(hit2.shading_normal) > 0.0,
                wi: sample.wi,
                pdf,
                distance: hit2.t * next.direction.length(),
                reflected,
            });
        } else {
            pixel.own += self.continuation(hit2, &next, b2, 1.0, previous, &mut stream, lambdas, emission, &mut pixel.rays);
        }
        if reusable {
            pixel.first = Some(First { hit, frame, wo, bsdf });
        }
        pixel
    }

    /// Next-event estimation at a vertex: adds to `radiance`, returns the rays traced.
    #[allow(clippy::too_many_arguments)]
    fn light_sample<const N: usize>(
        &self,
        hit: &Hit,
        bsdf: &Bsdf<'_, N>,
        frame: &Frame,
        wo: Vec3,
        u_light: Vec2,
        lambdas: &SampledWavelengths<N>,
        emission: &mut EmissionCache<N>,
        beta: &SampledSpectrum<N>,
        radiance: &mut SampledSpectrum<N>,
    ) -> u64 {
        if bsdf.is_delta() {
            return 0;
        }
        let Some(light) = self.scene.sample_light(hit, u_light, lambdas, emission) else {
            return 0;
        };
        let wi = frame.to_local(light.wi);
        let f = bsdf.f(wo, wi) * wi.z.abs();
        if f.is_black() || light.radiance.is_black() {
            return 0;
        }
        if !self.scene.occluded(&hit.spawn_to(light.wi, light.distance)) {
            let w = if light.delta {
                1.0
            } else {
                power_heuristic(1, light.pdf, 1, bsdf.pdf(wo, wi))
            };
            *radiance += *beta * f * light.radiance * (w / light.pdf);
        }
        1
    }

    /// The path from its second vertex `hit` (reached by `ray`; its emission already
    /// counted) on, with throughput `beta` there; Russian roulette reads the throughput
    /// times `scale`. Returns the radiance it gathered.
    #[allow(clippy::too_many_arguments)]
    fn continuation<const N: usize>(
        &self,
        first: Hit,
        ray: &Ray,
        mut beta: SampledSpectrum<N>,
        scale: f32,
        mut previous: Option<(f32, Vec3)>,
        stream: &mut SobolStream,
        lambdas: &SampledWavelengths<N>,
        emission: &mut EmissionCache<N>,
        rays: &mut u64,
    ) -> SampledSpectrum<N> {
        let mut radiance = SampledSpectrum::splat(0.0);
        let mut hit = first;
        let mut ray = *ray;
        let mut depth = 1u32;
        let mut eta_scale = 1.0f32;
        loop {
            let wo_world = -ray.direction.normalize();
            if depth > 1 {
                if let Some(footprint) = &self.footprint {
                    let width = footprint.at(hit.p);
                    self.scene.set_footprint(&mut hit, wo_world, width);
                }
                absorb(self.scene, &ray, &hit, lambdas, &mut beta);
                let le = self.scene.emitted(&hit, wo_world, lambdas, emission);
                if !le.is_black() {
                    let w = previous.map_or(1.0, |(b, from)| {
                        let light_pdf = self.scene.light_pdf(from, &hit, lambdas, emission);
                        power_heuristic(1, b, 1, light_pdf)
                    });
                    radiance += beta * le * w;
                }
            }
            if depth >= self.max_depth {
                break;
            }
            stream.set_dimension(FIRST_BOUNCE_DIMENSION + u64::from(depth) * DIMENSIONS_PER_BOUNCE);
            let u_light = stream.next_2d();
            let u_lobe = stream.next_1d();
            let u_bsdf = stream.next_2d();
            let u_roulette = stream.next_1d();
            let bsdf = self.scene.bsdf_cached(
                &hit,
                lambdas,
                prism_scene::bsdf::TransportMode::Radiance,
                emission,
            );
            let frame = Frame::from_normal(hit.shading_normal);
            let wo = frame.to_local(wo_world);
            *rays += self.light_sample(&hit, &bsdf, &frame, wo, u_light, lambdas, emission, &beta, &mut radiance);
            let Some(sample) = bsdf.sample(wo, u_lobe, u_bsdf) else {
                break;
            };
            let pdf = sample.pdf[0];
            if !positive_finite(pdf) {
                break;
            }
            beta *= sample.f * (sample.wi.z.abs() / pdf);
            eta_scale *= sample.eta * sample.eta;
            previous = (!sample.delta).then_some((pdf, hit.p));
            let wi_world = frame.to_world(sample.wi);
            ray = hit.spawn(wi_world);
            depth += 1;
            if depth >= ROULETTE_DEPTH {
                let q = (beta.max_value() * scale * eta_scale / ROULETTE_THROUGHPUT).min(0.95);
                if q.is_nan() || q <= 0.0 || u_roulette >= q {
                    break;
                }
                beta *= 1.0 / q;
            }
            *rays += 1;
            match self.scene.intersect(&ray) {
                Some(h) => hit = h,
                None => {
                    if let Some((le, light_pdf)) =
                        self.scene.escaped(wi_world, lambdas, emission)
                    {
                        let w = previous.map_or(1.0, |(b, _)| power_heuristic(1, b, 1, light_pdf));
                        radiance += beta * le * w;
                    }
                    break;
                }
            }
        }
        radiance
    }
}

/// Traces every sample of the pixels of rows `y0..y0 + rows_here` in tiles of `size`
/// pixels; `xyz` and `coverage` are those rows' sums. Returns rays traced and samples
/// rejected.
pub(crate) fn trace_band<const N: usize>(
    tracer: &Tracer,
    filter: &FilterSampler,
    rows: &Rows,
    size: u32,
    y0: u32,
    xyz: &mut [[f64; 3]],
    coverage: &mut [f64],
) -> (u64, u64) {
    let w = rows.width;
    let y1 = (y0 + size).min(rows.height);
    let (mut rays, mut rejected) = (0u64, 0u64);
    let mut value = SampleValue::default();
    let mut out = Vec::new();
    let mut pixels = Vec::new();
    let mut lambdas = None;
    for x0 in (0..w).step_by(size as usize) {
        pixels.clear();
        for y in y0..y1 {
            for x in x0..(x0 + size).min(w) {
                pixels.push((x, y));
            }
        }
        for s in rows.samples.clone() {
            tracer.trace_tile::<N>(filter, rows, &pixels, s, &mut out, &mut lambdas);
            let Some(l) = &lambdas else {
                rejected += pixels.len() as u64;
                continue;
            };
            for (&(x, y), (_, radiance, r, covered)) in pixels.iter().zip(&out) {
                let index = ((y - y0) * w + x) as usize;
                rays += r;
                coverage[index] += f64::from(u8::from(*covered));
                value.clear();
                value.add(tracer, rows.outputs, radiance, l);
                if value.finite() {
                    value.add_to(value.clamp_scale(rows.clamp), &mut xyz[index], &mut [], None, None);
                } else {
                    rejected += 1;
                }
            }
        }
    }
    (rays, rejected)
}
