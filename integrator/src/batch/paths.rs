//! A batch's paths from the camera to their ends, bounce by bounce.

use super::lambertian;
use super::lane::{At, Lane, LaneCode};
use crate::filter::FilterSampler;
use crate::path::{PathResult, Tracer};
use crate::render::Rows;
use crate::sample_value::SampleValue;
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

/// Traces sample `s` of the `count` (<= W) pixels of row `y` from `x0` on, each into its
/// `values` entry (cleared first), and returns their results, as the path tracer's
/// `trace_sample` would pixel by pixel. Lanes advance together: each bounce traces every
/// live lane's ray, then scatters the Lambertian vertices lane-wide and the others lane by
/// lane.
#[allow(clippy::too_many_arguments)]
pub(super) fn trace_batch<'s, const N: usize, const W: usize>(
    tracer: &Tracer<'s>,
    filter: &FilterSampler,
    rows: &Rows,
    (x0, y): (u32, u32),
    count: usize,
    s: u64,
    values: &mut [SampleValue; W],
    code: &LaneCode<N>,
    space: &mut Space<'s, N>,
) -> [PathResult; W] {
    let mut results: [PathResult; W] = std::array::from_fn(|_| PathResult::nothing(false));
    let Space { lanes, at } = space;
    for (i, (lane, value)) in lanes.iter_mut().zip(values.iter_mut()).enumerate() {
        value.clear();
        *lane = (i < count)
            .then(|| Lane::start(tracer, filter, rows, (x0 + i as u32, y), s))
            .flatten();
    }
    let mut sink_into = |value: &mut SampleValue, radiance: &SampledSpectrum<N>, lambdas: &_| {
        value.add(tracer.sensor(), rows.outputs, radiance, lambdas);
    };
    loop {
        let mut taken = [false; W];
        for i in 0..W {
            let Some(lane) = &mut lanes[i] else {
                at[i] = None;
                continue;
            };
            at[i] = (code.meet)(lane, tracer);
            match &at[i] {
                Some(vertex) => taken[i] = lambertian::takes(vertex),
                None => end(
                    &mut lanes[i],
                    &mut results[i],
                    &mut values[i],
                    &mut sink_into,
                ),
            }
        }
        if lanes.iter().all(Option::is_none) {
            break;
        }
        // Vertices the lanes handle alone first: their light goes to their own values.
        for i in 0..W {
            let (Some(lane), Some(vertex), false) = (&mut lanes[i], &at[i], taken[i]) else {
                continue;
            };
            let value = &mut values[i];
            let goes_on =
                (code.scatter_alone)(lane, tracer, vertex, &mut |r, l| sink_into(value, r, l));
            if !goes_on {
                end(
                    &mut lanes[i],
                    &mut results[i],
                    &mut values[i],
                    &mut sink_into,
                );
            }
        }
        if taken.contains(&true) {
            let ended = lambertian::scatter_wide::<N, W>(tracer, lanes, at, taken);
            for i in 0..W {
                if ended[i] {
                    end(
                        &mut lanes[i],
                        &mut results[i],
                        &mut values[i],
                        &mut sink_into,
                    );
                }
            }
        }
    }
    results
}

/// Where a row's batches keep their lanes and vertices (on the heap, reused batch after
/// batch): W of each.
pub(super) struct Space<'s, const N: usize> {
    lanes: Vec<Option<Lane<N>>>,
    at: Vec<Option<At<'s, N>>>,
}

impl<const N: usize> Space<'_, N> {
    /// Room for `width` lanes.
    pub fn new(width: usize) -> Self {
        Self {
            lanes: (0..width).map(|_| None).collect(),
            at: (0..width).map(|_| None).collect(),
        }
    }
}

/// Ends the path in `slot`: its light to `value`, its counts to `result`.
#[inline(always)]
fn end<const N: usize>(
    slot: &mut Option<Lane<N>>,
    result: &mut PathResult,
    value: &mut SampleValue,
    sink: &mut impl FnMut(&mut SampleValue, &SampledSpectrum<N>, &SampledWavelengths<N>),
) {
    if let Some(lane) = slot.take() {
        sink(value, &lane.walk.radiance, &lane.walk.lambdas);
        *result = lane.result();
    }
}
