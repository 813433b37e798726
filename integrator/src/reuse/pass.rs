//! A pass of path reuse over the whole image: bands of tile rows in parallel.

use rayon::prelude::*;

use crate::film::filter::FilterSampler;
use crate::pixels::rows::RowOutput;
use crate::pixels::sample_plan::SamplePlan;
use crate::reuse::trace_band;
use crate::transport::context::Integrator;

/// Traces sample `s` of every pixel in tiles whose paths share their second vertices
/// (`crate::reuse`): bands of tile rows in parallel, each band's tiles in order. Returns
/// rays traced and samples rejected.
pub(crate) fn reuse_pass<const N: usize>(
    integrator: &Integrator,
    filter: &FilterSampler,
    rows: &SamplePlan,
    size: u32,
    outs: &mut [RowOutput],
    s: u64,
) -> (u64, u64) {
    let bands: Vec<(u32, &mut [RowOutput])> = outs
        .chunks_mut(size as usize)
        .enumerate()
        .map(|(i, band)| (i as u32 * size, band))
        .collect();
    let totals: Vec<(u64, u64)> = bands
        .into_par_iter()
        .map(|(y0, band)| {
            let (mut rays, mut rejected) = (0u64, 0u64);
            let ys = y0..y0 + band.len() as u32;
            trace_band::<N>(
                integrator,
                filter,
                rows,
                size,
                ys,
                s,
                &mut |pixel, sample, weight| {
                    rays += pixel.result.rays;
                    rejected += u64::from(band[(pixel.y - y0) as usize].add(
                        pixel.x as usize,
                        sample,
                        &pixel.result,
                        &pixel.value,
                        rows,
                        weight,
                    ));
                },
            );
            (rays, rejected)
        })
        .collect();
    totals
        .into_iter()
        .fold((0, 0), |(a, b), (r, n)| (a + r, b + n))
}
