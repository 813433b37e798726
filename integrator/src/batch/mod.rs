//! The batch tracer (issue 30, part (b)): the paths of neighbouring pixels of a row, one
//! per lane, advance together bounce by bounce, the way Mitsuba 3 runs its integrators
//! over Dr.Jit's arrays and pbrt-v4 its wavefront.
//!
//! Each lane is the path tracer's `Walk` (`lane.rs`). A bounce first traces every live
//! lane's ray and adds the light it meets, lane by lane (traversal per ray, as the issue's
//! plan has it). Then the vertices split: Lambertian ones, the commonest, are scattered
//! lane-wide (`lambertian.rs`) by the code the path tracer runs for one path, written
//! once over [`Real`](prism_sampling::lanes::real::Real): the shading frame
//! ([`Frames`](prism_scene::geometry::Frames)), the Lambertian direction and density
//! ([`lambertian_sample`](prism_scene::bsdf::lambertian_sample)), the power heuristic
//! ([`power_heuristic_of`](prism_sampling::mis::power_heuristic_of)), Russian roulette
//! ([`crate::path::roulette`]), the spectra carried and gathered; the scene's answers
//! there (the light sample, the shadow ray) per lane. Every other vertex (glass, metals,
//! the glTF materials, a fluorescent surface, a phosphor, a dispersive split of the
//! package) is scattered by its lane alone with the path tracer's own functions.
//!
//! The lanes run libm's sine per lane (`Reals<W, true>`), so each lane is its pixel's
//! path to the bit: the images are the path tracer's, byte for byte, at any lane width
//! (`tests/batch.rs`). The width is the CPU's ([`native_width`]: 16 with AVX-512, 8 with
//! AVX2, else 4), chosen at run time; the lane-wide code is compiled for each width's
//! instruction set.
//!
//! It serves unpolarized renders of 4, 8 or 16 wavelengths per path, unsplit and without
//! path reuse (`plan::estimators` refuses the rest).

mod lambertian;
mod lane;
mod paths;

use prism_sampling::lanes::native_width;

use crate::filter::FilterSampler;
use crate::path::Tracer;
use crate::render::{RowOutput, Rows};
use crate::sample_value::SampleValue;

use lane::LaneCode;
use paths::{Space, trace_batch};

/// A row tracer: traces every sample of every pixel of row `y`; returns rays traced and
/// samples rejected.
pub(crate) type RowTracer = fn(&Tracer, &FilterSampler, &Rows, u32, &mut RowOutput) -> (u64, u64);

/// The batch tracer's row `width` lanes wide (None: the CPU's width), for packages of `N`
/// wavelengths.
pub(crate) fn row_tracer<const N: usize>(width: Option<usize>) -> RowTracer {
    match width.unwrap_or_else(native_width) {
        16 => row::<N, 16>,
        8 => row::<N, 8>,
        _ => row::<N, 4>,
    }
}

/// The row in batches of `W` pixels: each batch traces sample after sample, and each
/// pixel's samples reach its sums in order, as in the path tracer's row.
fn row<const N: usize, const W: usize>(
    tracer: &Tracer,
    filter: &FilterSampler,
    rows: &Rows,
    y: u32,
    out: &mut RowOutput,
) -> (u64, u64) {
    let (mut rays, mut rejected) = (0u64, 0u64);
    let mut values: [SampleValue; W] = std::array::from_fn(|_| SampleValue::default());
    let code = LaneCode::<N>::of(tracer.scene.features().fluorescence);
    let mut space = Space::new(W);
    let mut x0 = 0u32;
    while x0 < rows.width {
        let count = (rows.width - x0).min(W as u32) as usize;
        for s in rows.samples.clone() {
            let results = trace_batch::<N, W>(
                tracer,
                filter,
                rows,
                (x0, y),
                count,
                s,
                &mut values,
                &code,
                &mut space,
            );
            for (i, (result, value)) in results.iter().zip(&values).take(count).enumerate() {
                rays += result.rays;
                rejected += u64::from(out.add(x0 as usize + i, s, result, value, rows, 1.0));
            }
        }
        x0 += W as u32;
    }
    (rays, rejected)
}
