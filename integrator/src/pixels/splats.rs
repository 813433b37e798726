//! Light paths' splats: each row's light paths traced in parallel, their splats kept in
//! the order they were made and added to the film row by row, so that the sums do not
//! depend on the threads.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use glam::Vec2;
use prism_spectrum::SampledSpectrum;
use rayon::prelude::*;

use crate::RenderSettings;
use crate::film::Film;
use crate::film::filter::FilterSampler;
use crate::film::sample_value::SampleValue;
use crate::film::splatter::Splatter;
use crate::pixels::sample_plan::SamplePlan;
use crate::transport::context::Integrator;
use crate::transport::light_path::light_seed;
use crate::transport::light_throughput::{LightThroughput, PolarizedLight};

/// A light path's contribution to the film, at a film position.
struct Splat {
    film: Vec2,
    value: SampleValue,
    /// Whether its sample is in the second replicate (`Replicas`).
    second: bool,
}

/// The splats of one row's light paths, in the order they were made.
#[derive(Default)]
struct RowSplats {
    splats: Vec<Splat>,
    rays: u64,
    rejected: u64,
}

/// Traces the light paths of every sample of every pixel of row `y` (one per camera
/// sample: the film's mean divides by the samples per pixel, and light paths' camera
/// importance is per pixel).
fn light_row<const N: usize, L: LightThroughput<N>>(
    integrator: &Integrator,
    settings: &SamplePlan,
    y: u32,
) -> RowSplats {
    let w = settings.width;
    let aspect = w as f32 / settings.height as f32;
    let mut out = RowSplats::default();
    for x in 0..w {
        let pixel = u64::from(y) * u64::from(w) + u64::from(x);
        for s in settings.samples.clone() {
            let mut stream = settings.stream(light_seed(settings.seed), pixel, s);
            out.rays += integrator.trace_light::<N, L>(
                &mut stream,
                aspect,
                &mut |film, radiance, lambdas| {
                    let mut value = SampleValue::default();
                    value.add(integrator.sensor(), settings.outputs, radiance, lambdas);
                    if value.finite() {
                        out.splats.push(Splat {
                            film,
                            value,
                            second: settings.replicas.group(s) == 1,
                        });
                    } else {
                        out.rejected += 1;
                    }
                },
            );
        }
    }
    out
}

/// Traces the light paths of the caustics seen directly (`crate::transport::light_path`)
/// for one pass of `plan` in `pool` and splats them into `pass` with `filter`, counting
/// their rays and rejected samples in `counts`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn add_light_paths(
    pool: &rayon::ThreadPool,
    integrator: &Integrator,
    filter: &FilterSampler,
    plan: &SamplePlan,
    settings: &RenderSettings,
    pass: &mut Film,
    cancel: &AtomicBool,
    counts: (&AtomicU64, &AtomicU64),
) {
    let (rays, nonfinite) = counts;
    macro_rules! light_by_width {
        ($carrier:ident) => {
            match settings.wavelengths {
                1 => light_row::<1, $carrier<1>>,
                2 => light_row::<2, $carrier<2>>,
                4 => light_row::<4, $carrier<4>>,
                8 => light_row::<8, $carrier<8>>,
                _ => light_row::<16, $carrier<16>>,
            }
        };
    }
    let light_row = if settings.is_polarized() {
        light_by_width!(PolarizedLight)
    } else {
        light_by_width!(SampledSpectrum)
    };
    // Rows of light paths run in parallel in batches, and each batch's splats are
    // added in row order: the sums do not depend on the threads, and the batch
    // bounds the splats held at once.
    const BATCH_ROWS: u32 = 16;
    let mut splatter = Splatter::new(pass, filter);
    for first in (0..settings.height).step_by(BATCH_ROWS as usize) {
        if cancel.load(Ordering::Relaxed) {
            break;
        }
        let last = (first + BATCH_ROWS).min(settings.height);
        let batch: Vec<RowSplats> = pool.install(|| {
            (first..last)
                .into_par_iter()
                .map(|y| light_row(integrator, plan, y))
                .collect()
        });
        for row in batch {
            rays.fetch_add(row.rays, Ordering::Relaxed);
            nonfinite.fetch_add(row.rejected, Ordering::Relaxed);
            for splat in &row.splats {
                splatter.add(splat.film, &splat.value, settings.clamp, splat.second);
            }
        }
    }
}
