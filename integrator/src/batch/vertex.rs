//! A batch's Lambertian vertices: next-event estimation and the bounce, lane-wide where
//! every path computes alike, per lane where the scene answers (the light sample, the
//! shadow ray, the spawned ray's origin).

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};
use prism_sampling::lanes::real::{Real, V3};
use prism_sampling::mis::power_heuristic_of;
use prism_sampling::stream::{SampleStream, SobolStream};
use prism_scene::bsdf::{TransportMode, lambertian_pdf, lambertian_sample};
use prism_scene::geometry::Frames;
use prism_scene::world::{Bsdf, Hit, Scene};

use super::paths::{Exact, Paths, Spectra};
use crate::path::{ROULETTE_DEPTH, roulette};

/// A bounce's draws for every lane (what dead lanes hold is never read).
pub(super) struct Draws<const W: usize> {
    light: [Vec2; W],
    bsdf: [Exact<W>; 2],
    roulette: Exact<W>,
}

impl<const W: usize> Draws<W> {
    /// The draws of the bounce whose block starts at `dimension`, from each live lane's
    /// stream, in the path tracer's order (light, lobe, direction, roulette).
    #[inline(always)]
    pub fn from_streams(streams: &mut [SobolStream; W], alive: &[bool; W], dimension: u64) -> Self {
        let mut light = [Vec2::ZERO; W];
        let (mut bsdf, mut u_roulette) = ([[0.0f32; W]; 2], [0.0f32; W]);
        for (i, stream) in streams.iter_mut().enumerate() {
            if !alive[i] {
                continue;
            }
            stream.set_dimension(dimension);
            light[i] = stream.next_2d();
            // The lobe's number: a Lambertian surface has one lobe.
            let _ = stream.next_1d();
            let u = stream.next_2d();
            (bsdf[0][i], bsdf[1][i]) = (u.x, u.y);
            u_roulette[i] = stream.next_1d();
        }
        Self {
            light,
            bsdf: bsdf.map(|u| Exact::from_fn(|i| u[i])),
            roulette: Exact::from_fn(|i| u_roulette[i]),
        }
    }
}

/// The vertices `hits` (each with the direction back along its ray) of a batch's live
/// paths, every one Lambertian: next-event estimation, then the bounce and Russian
/// roulette.
#[inline(always)]
pub(super) fn lambertian_vertex<const N: usize, const W: usize>(
    scene: &Scene,
    paths: &mut Paths<N, W>,
    hits: &[Option<(Hit, Vec3)>; W],
    draws: &Draws<W>,
) {
    let zero = Exact::<W>::splat(0.0);
    let mut reflectance: Spectra<N, W> = [zero; N];
    let (mut normal, mut back) = ([Vec3::Z; W], [Vec3::Z; W]);
    for (i, slot) in hits.iter().enumerate() {
        let (Some((hit, wo_world)), Some(lambdas)) = (slot, &paths.lambdas[i]) else {
            continue;
        };
        match scene.bsdf_cached(hit, lambdas, TransportMode::Radiance, &mut paths.caches[i]) {
            Bsdf::Diffuse(d) => {
                for (r, value) in reflectance.iter_mut().zip(d.reflectance.0) {
                    r.0.0[i] = value;
                }
            }
            // `super::unsupported` lets only Lambertian scenes here.
            _ => {
                debug_assert!(false, "a non-Lambertian vertex in the batch tracer");
                paths.alive[i] = false;
            }
        }
        (normal[i], back[i]) = (hit.shading_normal, *wo_world);
    }
    let frames = Frames::<Exact<W>>::from_normal(V3::from_fn(|i| normal[i]));
    let wo = frames.to_local(V3::from_fn(|i| back[i]));
    // f = R / pi on wo's side: the Lambertian BSDF (`Diffuse::f`).
    let f = |wi: V3<Exact<W>>| -> Spectra<N, W> {
        let same_side = (wo.z * wi.z).gt(zero);
        reflectance.map(|r| Exact::select(same_side, r * Exact::splat(FRAC_1_PI), zero))
    };
    next_event(scene, paths, hits, draws, &frames, wo, &f);
    bounce(paths, hits, draws, &frames, wo, &f);
}

/// Next-event estimation at every live lane's vertex, MIS by the power heuristic against
/// the Lambertian density (`Tracer::next_event` lane by lane).
#[inline(always)]
fn next_event<const N: usize, const W: usize>(
    scene: &Scene,
    paths: &mut Paths<N, W>,
    hits: &[Option<(Hit, Vec3)>; W],
    draws: &Draws<W>,
    frames: &Frames<Exact<W>>,
    wo: V3<Exact<W>>,
    f: &impl Fn(V3<Exact<W>>) -> Spectra<N, W>,
) {
    let zero = Exact::<W>::splat(0.0);
    let mut samples = [None; W];
    let (mut towards, mut pdf, mut delta) = ([Vec3::Z; W], [1.0f32; W], [0u32; W]);
    let mut radiance: Spectra<N, W> = [zero; N];
    for (i, slot) in hits.iter().enumerate() {
        let (true, Some((hit, _)), Some(lambdas)) = (paths.alive[i], slot, &paths.lambdas[i])
        else {
            continue;
        };
        let Some(light) = scene.sample_light(hit, draws.light[i], lambdas, &mut paths.caches[i])
        else {
            continue;
        };
        (towards[i], pdf[i]) = (light.wi, light.pdf);
        delta[i] = if light.delta { u32::MAX } else { 0 };
        for (r, value) in radiance.iter_mut().zip(light.radiance.0) {
            r.0.0[i] = value;
        }
        samples[i] = Some(light);
    }
    let wi = frames.to_local(V3::from_fn(|i| towards[i]));
    let cosine = wi.z.abs();
    let f = f(wi).map(|f| f * cosine);
    let light_pdf = Exact::from_fn(|i| pdf[i]);
    let mis = power_heuristic_of(light_pdf, lambertian_pdf(wo.z, wi.z));
    let delta = prism_sampling::lanes::real::LaneMask(prism_sampling::lanes::Lanes(delta));
    let weight = Exact::select(delta, Exact::splat(1.0), mis) / light_pdf;
    // Shadow rays where the light and the BSDF are not dark at every wavelength.
    let mut lit = [0u32; W];
    for (i, sample) in samples.iter().enumerate() {
        let (Some(light), Some((hit, _))) = (sample, &hits[i]) else {
            continue;
        };
        let dark = |s: &Spectra<N, W>| s.iter().all(|x| x.lane(i) == 0.0);
        if dark(&f) || dark(&radiance) {
            continue;
        }
        paths.results[i].rays += 1;
        if !scene.occluded(&hit.spawn_to(light.wi, light.distance)) {
            lit[i] = u32::MAX;
        }
    }
    let lit = prism_sampling::lanes::real::LaneMask(prism_sampling::lanes::Lanes(lit));
    for j in 0..N {
        let added = paths.beta[j] * f[j] * radiance[j] * weight;
        paths.radiance[j] = Exact::select(lit, paths.radiance[j] + added, paths.radiance[j]);
    }
}

/// The Lambertian bounce of every live lane (`Diffuse::sample`, `Walk::follow` and
/// `Walk::survives_roulette` lane by lane): a cosine-distributed direction, the
/// throughput scaled by f cos / pdf, the ray spawned, roulette from `ROULETTE_DEPTH`.
#[inline(always)]
fn bounce<const N: usize, const W: usize>(
    paths: &mut Paths<N, W>,
    hits: &[Option<(Hit, Vec3)>; W],
    draws: &Draws<W>,
    frames: &Frames<Exact<W>>,
    wo: V3<Exact<W>>,
    f: &impl Fn(V3<Exact<W>>) -> Spectra<N, W>,
) {
    let zero = Exact::<W>::splat(0.0);
    let (wi, pdf, exists) = lambertian_sample(wo.z, draws.bsdf);
    let usable = exists & pdf.gt(zero) & pdf.is_finite();
    let weight = wi.z.abs() / pdf;
    let f = f(wi);
    for (beta, f) in paths.beta.iter_mut().zip(f) {
        *beta = *beta * (f * weight);
    }
    paths.previous_pdf = pdf;
    let towards = frames.to_world(wi);
    for (i, slot) in hits.iter().enumerate() {
        let Some((hit, _)) = slot else { continue };
        paths.alive[i] &= usable.get(i);
        paths.rays[i] = hit.spawn(towards.lane(i));
        paths.previous_p[i] = hit.p;
    }
    paths.depth += 1;
    if paths.depth >= ROULETTE_DEPTH {
        let largest = paths
            .beta
            .iter()
            .fold(Exact::splat(f32::NEG_INFINITY), |m, b| m.max(*b));
        // The path tracer's eta_scale is 1 on Lambertian paths without splitting.
        let (survives, q) = roulette(largest * Exact::splat(1.0), draws.roulette);
        let scale = Exact::splat(1.0) / q;
        for beta in &mut paths.beta {
            *beta = Exact::select(survives, *beta * scale, *beta);
        }
        for (i, alive) in paths.alive.iter_mut().enumerate() {
            *alive &= survives.get(i);
        }
    }
}
