//! A batch's Lambertian vertices, lane-wide: the shading frames, next-event estimation's
//! BSDF values and MIS weights, the cosine-distributed bounce, the throughput and radiance
//! updates and Russian roulette, each by the code the path tracer runs for one path
//! (written over `Real`); the scene's answers (the light sample, the shadow ray, the
//! spawned ray's origin) per lane.

use std::f32::consts::FRAC_1_PI;

use glam::Vec3;
use prism_sampling::lanes::real::{LaneMask, Real, Reals, V3};
use prism_sampling::mis::power_heuristic_of;
use prism_scene::bsdf::{lambertian_pdf, lambertian_sample};
use prism_scene::geometry::Frames;
use prism_scene::world::{Bsdf, LightSample};
use prism_spectrum::SampledSpectrum;

use super::lane::{At, Lane};
use crate::path::{ROULETTE_DEPTH, Tracer, roulette};

/// Lanes of reals, libm's sine in each (each lane its path's values to the bit).
type Exact<const W: usize> = Reals<W, true>;

/// Spectra in lanes: one lane array per wavelength.
type Spectra<const N: usize, const W: usize> = [Exact<W>; N];

/// Whether the lane-wide code takes a lane's vertex `at`: where it is Lambertian.
pub(super) fn takes<const N: usize>(at: &At<'_, N>) -> bool {
    matches!(at.bsdf, Bsdf::Diffuse(_))
}

/// The Lambertian vertices `at` of the lanes `taken` marks (see [`takes`]): next-event
/// estimation, the bounce and Russian roulette, as `Lane::scatter_alone` would do lane by
/// lane. Returns the lanes whose paths end here. Compiled for the instruction set whose
/// registers hold `W` lanes where the CPU has it (AVX-512 for 16, AVX2 for 8), else for
/// the build's baseline.
pub(super) fn scatter_wide<const N: usize, const W: usize>(
    tracer: &Tracer,
    lanes: &mut [Option<Lane<N>>],
    at: &[Option<At<'_, N>>],
    taken: [bool; W],
) -> [bool; W] {
    #[cfg(target_arch = "x86_64")]
    #[allow(
        unsafe_code,
        reason = "code compiled for AVX-512 or AVX2, entered where the CPU has it"
    )]
    {
        // SAFETY: each is entered only where the CPU has what it is compiled for.
        if W == 16 && std::arch::is_x86_feature_detected!("avx512f") {
            let taken16: [bool; 16] = std::array::from_fn(|i| taken[i]);
            let ended = unsafe { scatter_avx512::<N>(tracer, lanes, at, taken16) };
            return std::array::from_fn(|i| ended[i]);
        }
        if W == 8 && std::arch::is_x86_feature_detected!("avx2") {
            let taken8: [bool; 8] = std::array::from_fn(|i| taken[i]);
            let ended = unsafe { scatter_avx2::<N>(tracer, lanes, at, taken8) };
            return std::array::from_fn(|i| ended[i]);
        }
    }
    scatter::<N, W>(tracer, lanes, at, taken)
}

/// [`scatter`] sixteen lanes wide, compiled for AVX-512.
///
/// # Safety
/// The CPU must have AVX-512F and AVX2.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "compiled for AVX-512, entered where the CPU has it"
)]
#[target_feature(enable = "avx512f,avx2")]
unsafe fn scatter_avx512<const N: usize>(
    tracer: &Tracer,
    lanes: &mut [Option<Lane<N>>],
    at: &[Option<At<'_, N>>],
    taken: [bool; 16],
) -> [bool; 16] {
    scatter::<N, 16>(tracer, lanes, at, taken)
}

/// [`scatter`] eight lanes wide, compiled for AVX2.
///
/// # Safety
/// The CPU must have AVX2.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "compiled for AVX2, entered where the CPU has it"
)]
#[target_feature(enable = "avx2")]
unsafe fn scatter_avx2<const N: usize>(
    tracer: &Tracer,
    lanes: &mut [Option<Lane<N>>],
    at: &[Option<At<'_, N>>],
    taken: [bool; 8],
) -> [bool; 8] {
    scatter::<N, 8>(tracer, lanes, at, taken)
}

#[inline(always)]
fn scatter<const N: usize, const W: usize>(
    tracer: &Tracer,
    lanes: &mut [Option<Lane<N>>],
    at: &[Option<At<'_, N>>],
    taken: [bool; W],
) -> [bool; W] {
    let zero = Exact::<W>::splat(0.0);
    let mut reflectance: Spectra<N, W> = [zero; N];
    let (mut beta, mut radiance): (Spectra<N, W>, Spectra<N, W>) = ([zero; N], [zero; N]);
    let (mut normal, mut back, mut eta_scale) = ([Vec3::Z; W], [Vec3::Z; W], [1.0f32; W]);
    for i in lanes_of(taken) {
        let (Some(lane), Some(at)) = (&mut lanes[i], &at[i]) else {
            continue;
        };
        if let Bsdf::Diffuse(d) = &at.bsdf {
            set_lane(&mut reflectance, i, &d.reflectance);
        }
        let walk = &lane.walk;
        set_lane(&mut beta, i, &walk.beta);
        set_lane(&mut radiance, i, &walk.radiance);
        (normal[i], back[i], eta_scale[i]) = (at.hit.shading_normal, at.wo_world, walk.eta_scale);
    }
    let frames = Frames::<Exact<W>>::from_normal(V3::from_fn(|i| normal[i]));
    let wo = frames.to_local(V3::from_fn(|i| back[i]));
    // f = R / pi on wo's side: `Diffuse::f`.
    let f = |wi: V3<Exact<W>>| -> Spectra<N, W> {
        let same_side = (wo.z * wi.z).gt(zero);
        reflectance.map(|r| Exact::select(same_side, r * Exact::splat(FRAC_1_PI), zero))
    };

    // Next-event estimation (`Tracer::next_event`).
    let mut lights: [Option<LightSample<N>>; W] = [None; W];
    for i in lanes_of(taken) {
        let (Some(lane), Some(at)) = (&mut lanes[i], &at[i]) else {
            continue;
        };
        let walk = &lane.walk;
        let sampled =
            tracer
                .scene
                .sample_light(&at.hit, at.u_light, &walk.transport, &mut lane.cache);
        if let Some(mut light) = sampled {
            if let Some(times) = &walk.times {
                tracer.gate(Some(light.light), times, &mut light.radiance);
            }
            lights[i] = Some(light);
        }
    }
    let towards = V3::from_fn(|i| lights[i].map_or(Vec3::Z, |l| l.wi));
    let light_pdf = Exact::from_fn(|i| lights[i].map_or(1.0, |l| l.pdf));
    let delta = LaneMask::from_fn(|i| lights[i].is_some_and(|l| l.delta));
    let mut arriving: Spectra<N, W> = [zero; N];
    for (i, light) in lights.iter().enumerate() {
        if let Some(light) = light {
            set_lane(&mut arriving, i, &light.radiance);
        }
    }
    let wi = frames.to_local(towards);
    let cosine = wi.z.abs();
    let f_light = f(wi).map(|f| f * cosine);
    let mis = power_heuristic_of(light_pdf, lambertian_pdf(wo.z, wi.z));
    let weight = Exact::select(delta, Exact::splat(1.0), mis) / light_pdf;
    let mut lit = [false; W];
    for (i, light) in lights.iter().enumerate() {
        let (Some(light), Some(lane), Some(at)) = (light, &mut lanes[i], &at[i]) else {
            continue;
        };
        // A light or a BSDF dark at every wavelength needs no shadow ray.
        let dark = |s: &Spectra<N, W>| s.iter().all(|x| x.lane(i) == 0.0);
        if dark(&f_light) || dark(&arriving) {
            continue;
        }
        lane.rays += 1;
        lit[i] = !tracer
            .scene
            .occluded(&at.hit.spawn_to(light.wi, light.distance));
    }
    let lit = LaneMask::from_fn(|i| lit[i]);
    for j in 0..N {
        let added = beta[j] * f_light[j] * arriving[j] * weight;
        radiance[j] = Exact::select(lit, radiance[j] + added, radiance[j]);
    }

    // The bounce (`Diffuse::sample`, `Walk::follow`, `Walk::survives_roulette`).
    let (wi, pdf, exists) = lambertian_sample(
        wo.z,
        [0, 1].map(|k| Exact::from_fn(|i| at[i].as_ref().map_or(0.5, |a| a.u_bsdf[k]))),
    );
    let usable = exists & pdf.gt(zero) & pdf.is_finite();
    let scale = wi.z.abs() / pdf;
    for (b, f) in beta.iter_mut().zip(f(wi)) {
        *b = *b * (f * scale);
    }
    let wi_world = frames.to_world(wi);
    let mut ended = [false; W];
    let mut at_risk = [false; W];
    for i in lanes_of(taken) {
        let (Some(lane), Some(at)) = (&mut lanes[i], &at[i]) else {
            continue;
        };
        if !usable.get(i) {
            ended[i] = true;
            continue;
        }
        // A Lambertian bounce is no refraction: eta_scale stays as it was.
        let caustic_start = tracer.light_caustics && !at.material.fluorescent();
        lane.walk.advance(
            &at.hit,
            false,
            false,
            pdf.lane(i),
            wi_world.lane(i),
            caustic_start,
        );
        at_risk[i] = lane.walk.depth >= ROULETTE_DEPTH;
    }
    let largest = beta
        .iter()
        .fold(Exact::splat(f32::NEG_INFINITY), |m, b| m.max(*b));
    let u = Exact::from_fn(|i| at[i].as_ref().map_or(0.0, |a| a.u_roulette));
    let (survives, q) = roulette(largest * Exact::from_fn(|i| eta_scale[i]), u);
    let at_risk = LaneMask::from_fn(|i| at_risk[i]);
    let survival = Exact::splat(1.0) / q;
    for b in &mut beta {
        *b = Exact::select(at_risk & survives, *b * survival, *b);
    }
    for i in lanes_of(taken) {
        let Some(lane) = &mut lanes[i] else { continue };
        lane.walk.beta = lane_of(&beta, i);
        lane.walk.radiance = lane_of(&radiance, i);
        ended[i] |= at_risk.get(i) && !survives.get(i);
    }
    ended
}

/// The indices of the lanes `set` marks.
fn lanes_of<const W: usize>(set: [bool; W]) -> impl Iterator<Item = usize> {
    (0..W).filter(move |&i| set[i])
}

/// Lane `i` of `lanes` set to `spectrum`.
fn set_lane<const N: usize, const W: usize>(
    lanes: &mut Spectra<N, W>,
    i: usize,
    spectrum: &SampledSpectrum<N>,
) {
    for (l, v) in lanes.iter_mut().zip(spectrum.0) {
        l.0.0[i] = v;
    }
}

/// Lane `i` of `lanes`.
fn lane_of<const N: usize, const W: usize>(lanes: &Spectra<N, W>, i: usize) -> SampledSpectrum<N> {
    SampledSpectrum::from_fn(|j| lanes[j].lane(i))
}
