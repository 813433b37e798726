//! Adaptive sampling's pilot (`crate::adaptive`): every pixel traced once under each of
//! two seeds of its own, in the render's modes, without light paths (they are not
//! spread), and a map whose rates follow each pixel's error per ray traced.

use rayon::prelude::*;

use crate::adaptive::SampleMap;
use crate::adaptive::error::{PilotMeasure, PixelError};
use crate::film::filter::FilterSampler;
use crate::film::sample_value::SampleValue;
use crate::pixels::sample::trace_sample;
use crate::pixels::sample_plan::SamplePlan;
use crate::plan::setup::{Setup, specialized, specialized_by_width};
use crate::transport::context::{Integrator, PathResult};
use crate::transport::throughput::Throughput;

/// Adaptive sampling's map for a render of `setup` with `splits` continuations per
/// sample and reuse tiles of `reuse` pixels: a pixel's rate follows its error per ray
/// traced, so that its rays go where they lower the error most.
pub(crate) fn sample_map(setup: &Setup, splits: u32, reuse: u32) -> Option<SampleMap> {
    let settings = setup.settings();
    let integrator = setup.integrator(splits);
    let (width, height) = (settings.width, settings.height);
    let pixels = (width * height) as usize;
    let seeds =
        crate::adaptive::PILOT_SEEDS.map(|seed| setup.pilot_plan(settings.seed ^ seed, 0..1));
    let measure = PilotMeasure::new(seeds[0].outputs, settings.range, settings.observer);
    let size = reuse;
    let filter = setup.filter();
    let pilot: Vec<Vec<PilotPixel>> = setup.pool.install(|| {
        if size > 1 {
            let band = specialized_by_width!(setup, pilot_band);
            (0..height.div_ceil(size))
                .into_par_iter()
                .map(|b| band(&integrator, filter, &seeds, &measure, size, b * size))
                .collect()
        } else {
            let row = specialized!(setup, pilot_row);
            (0..height)
                .into_par_iter()
                .map(|y| row(&integrator, filter, &seeds, &measure, y))
                .collect()
        }
    });
    let (mut errors, mut costs) = (vec![0.0; pixels], vec![0.0; pixels]);
    let mut bands = vec![[0.0; 2]; pixels];
    for pixel in pilot.into_iter().flatten() {
        let i = (pixel.y * width + pixel.x) as usize;
        errors[i] = pixel.error.error;
        bands[i] = pixel.error.bands;
        costs[i] = pixel.rays as f64 / 2.0;
    }
    let smooth = |values: &[f64]| crate::adaptive::smoothed(values, width, height);
    if let Some(band_errors) = measure.band_error(&bands, smooth) {
        for (e, b) in errors.iter_mut().zip(band_errors) {
            *e += b;
        }
    }
    SampleMap::from_errors(width, height, SampleMap::tile_side(reuse), &errors, &costs)
}

/// Adaptive sampling's pilot of row `y`: each pixel's first sample of both `seeds`, its
/// weighted error by `measure` and the rays both traced.
fn pilot_row<const N: usize, const FLUORESCENCE: bool, T: Throughput<N>>(
    integrator: &Integrator,
    filter: &FilterSampler,
    seeds: &[SamplePlan; 2],
    measure: &PilotMeasure,
    y: u32,
) -> Vec<PilotPixel> {
    let mut value = SampleValue::default();
    let mut channels = [Vec::new(), Vec::new()];
    (0..seeds[0].width)
        .map(|x| {
            let mut rays = 0;
            for (rows, out) in seeds.iter().zip(&mut channels) {
                let s = rows.samples.start;
                let result = trace_sample::<N, FLUORESCENCE, T>(
                    integrator, filter, rows, x, y, s, &mut value,
                );
                measure.channels(&value, pilot_scale(&result, &value, rows), out);
                rays += result.rays;
            }
            PilotPixel {
                x,
                y,
                error: measure.error(&channels[0], &channels[1]),
                rays,
            }
        })
        .collect()
}

/// Adaptive sampling's pilot of the tiles of reuse (`size` pixels) in the band from row
/// `y0`, as [`pilot_row`].
fn pilot_band<const N: usize>(
    integrator: &Integrator,
    filter: &FilterSampler,
    seeds: &[SamplePlan; 2],
    measure: &PilotMeasure,
    size: u32,
    y0: u32,
) -> Vec<PilotPixel> {
    let mut out = Vec::new();
    let (width, height) = (seeds[0].width, seeds[0].height);
    let ys = y0..(y0 + size).min(height);
    let mut tile = crate::reuse::Tile::new();
    let mut first: Vec<(Vec<f64>, u64)> = Vec::new();
    let mut channels = Vec::new();
    for x0 in (0..width).step_by(size as usize) {
        let xs = x0..(x0 + size).min(width);
        for (k, rows) in seeds.iter().enumerate() {
            let s = rows.samples.start;
            crate::reuse::trace_tile_at::<N>(
                integrator,
                filter,
                rows,
                xs.clone(),
                ys.clone(),
                s,
                &mut tile,
            );
            first.resize_with(tile.pixels().len(), Default::default);
            for (pixel, kept) in tile.pixels().iter().zip(&mut first) {
                let scale = pilot_scale(&pixel.result, &pixel.value, rows);
                if k == 0 {
                    measure.channels(&pixel.value, scale, &mut kept.0);
                    kept.1 = pixel.result.rays;
                } else {
                    measure.channels(&pixel.value, scale, &mut channels);
                    out.push(PilotPixel {
                        x: pixel.x,
                        y: pixel.y,
                        error: measure.error(&kept.0, &channels),
                        rays: kept.1 + pixel.result.rays,
                    });
                }
            }
        }
    }
    out
}

/// One pixel of adaptive sampling's pilot: its weighted error and the rays its two
/// samples traced.
struct PilotPixel {
    x: u32,
    y: u32,
    error: PixelError,
    rays: u64,
}

/// The factor a pilot sample is added with, as the film would add it: its clamp's, or 0
/// where it would be rejected.
fn pilot_scale(result: &PathResult, value: &SampleValue, rows: &SamplePlan) -> f64 {
    if result.valid && value.finite() {
        value.clamp_scale(rows.clamp)
    } else {
        0.0
    }
}
