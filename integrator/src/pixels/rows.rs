//! Rows of pixels: a pass's film cut into rows, and a row's samples traced and added to
//! its sums in index order, so that every pixel's sum is the same sequence of additions
//! whatever the thread count.

use crate::adaptive::samples_of;
use crate::film::filter::FilterSampler;
use crate::film::sample_value::SampleValue;
use crate::film::{Film, FilmSums};
use crate::pixels::sample::trace_sample;
use crate::pixels::sample_plan::SamplePlan;
use crate::transport::context::{Integrator, PathResult};
use crate::transport::throughput::Throughput;

/// `pass`'s sums cut into rows of a `width` x `height` image; a film without spectral,
/// energy or Stokes sums gives each row an empty slice of them.
pub(crate) fn row_outputs(pass: &mut Film, width: usize, height: u32) -> Vec<RowOutput<'_>> {
    let spectral_width = width * pass.spectral_width();
    let FilmSums {
        xyz,
        spectral,
        energy,
        stokes,
        coverage,
        replica,
    } = pass.sums_mut();
    xyz.chunks_mut(width)
        .zip(rows_of(spectral, spectral_width, height))
        .zip(rows_of(energy, width, height))
        .zip(rows_of(stokes, width, height))
        .zip(coverage.chunks_mut(width))
        .zip(rows_of(replica, width, height))
        .map(
            |(((((xyz, spectral), energy), stokes), coverage), replica)| RowOutput {
                xyz,
                spectral,
                energy,
                stokes,
                coverage,
                replica,
            },
        )
        .collect()
}

/// `sums` in rows of `row` values, or `height` empty rows where there are none.
fn rows_of<T>(sums: &mut [T], row: usize, height: u32) -> Vec<&mut [T]> {
    if row == 0 || sums.is_empty() {
        (0..height).map(|_| -> &mut [T] { &mut [] }).collect()
    } else {
        sums.chunks_mut(row).collect()
    }
}

/// One row's sums: XYZ, spectral bands (empty when not spectral), energy (empty
/// without energy output), Stokes components (empty unless polarized) and coverage.
pub(crate) struct RowOutput<'a> {
    xyz: &'a mut [[f64; 3]],
    spectral: &'a mut [f64],
    energy: &'a mut [[f64; 2]],
    stokes: &'a mut [[[f64; 3]; 3]],
    coverage: &'a mut [f64],
    /// The second replicate's colour and samples (empty without the variance AOV).
    replica: &'a mut [[f64; 4]],
}

impl RowOutput<'_> {
    /// Adds pixel `x`'s sample `s` (`result`, `value`) to the sums with `weight` (1, or
    /// adaptive sampling's); returns whether it was rejected (invalid wavelengths or a
    /// non-finite value).
    pub(crate) fn add(
        &mut self,
        x: usize,
        s: u64,
        result: &PathResult,
        value: &SampleValue,
        rows: &SamplePlan,
        weight: f64,
    ) -> bool {
        self.coverage[x] += f64::from(u8::from(result.covered)) * weight;
        let replica = match self.replica.get_mut(x) {
            Some(r) if rows.replicas.group(s) == 1 => {
                r[3] += 1.0;
                Some(r)
            }
            _ => None,
        };
        if !(result.valid && value.finite()) {
            return true;
        }
        let band_count = rows.outputs.spectral_width();
        let spectral = self
            .spectral
            .get_mut(x * band_count..(x + 1) * band_count)
            .unwrap_or_default();
        let scale = value.clamp_scale(rows.clamp) * weight;
        value.add_to(
            scale,
            &mut self.xyz[x],
            spectral,
            self.energy.get_mut(x),
            self.stokes.get_mut(x),
        );
        if let Some(r) = replica {
            for (a, b) in r.iter_mut().zip(value.xyz) {
                *a += b * scale;
            }
        }
        false
    }
}

/// A row tracer: traces every sample of every pixel of row `y`; returns rays traced and
/// samples rejected.
pub(crate) type RowTracer =
    fn(&Integrator, &FilterSampler, &SamplePlan, u32, &mut RowOutput) -> (u64, u64);

/// Traces every sample of every pixel of row `y`; returns rays traced and samples rejected.
pub(crate) fn trace_row<const N: usize, const FLUORESCENCE: bool, T: Throughput<N>>(
    integrator: &Integrator,
    filter: &FilterSampler,
    settings: &SamplePlan,
    y: u32,
    out: &mut RowOutput,
) -> (u64, u64) {
    let (mut rays, mut rejected) = (0u64, 0u64);
    let mut value = SampleValue::default();
    let map = settings.map.as_deref();
    for x in 0..settings.width {
        for pass in settings.samples.clone() {
            let (samples, weight) = samples_of(map, x, y, pass);
            for s in samples {
                let result = trace_sample::<N, FLUORESCENCE, T>(
                    integrator, filter, settings, x, y, s, &mut value,
                );
                rays += result.rays;
                rejected += u64::from(out.add(x as usize, s, &result, &value, settings, weight));
            }
        }
    }
    (rays, rejected)
}
