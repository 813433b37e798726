//! The batch tracer (issue 30, part (b), stage 2): the paths of neighbouring pixels of a
//! row, one per lane, advance together bounce by bounce, the way Mitsuba 3 runs its
//! integrators over Dr.Jit's arrays and pbrt-v4 its wavefront.
//!
//! What a vertex computes for every path alike is done lane-wide, by the code the path
//! tracer runs for one path, written once over [`Real`](prism_sampling::lanes::real::Real):
//! the shading frame ([`Frames`](prism_scene::geometry::Frames)), the Lambertian direction
//! and density ([`lambertian_sample`](prism_scene::bsdf::lambertian_sample)), the power
//! heuristic ([`power_heuristic_of`](prism_sampling::mis::power_heuristic_of)), Russian
//! roulette ([`crate::path::roulette`]), the spectra carried and gathered. What depends on
//! the scene's data is asked per lane, as the plan has it: traversal, the light
//! sample, the emission a ray meets, the reflectance at a hit.
//!
//! The lanes run libm's sine per lane (`Reals<W, true>`), so each lane is its pixel's
//! path to the bit: the images are the path tracer's, byte for byte, at any lane width
//! (`tests/batch.rs`). The width is the CPU's ([`native_width`]: 16 with AVX-512, 8 with
//! AVX2, else 4), chosen at run time, each width compiled for its instruction set.
//!
//! This stage serves what [`unsupported`] allows: scenes whose every material is
//! Lambertian, unpolarized, in the steady state, unsplit and without path reuse. Glass,
//! metals, the glTF materials, fluorescence and time are the next stage's.

mod paths;
mod vertex;

use prism_sampling::lanes::native_width;
use prism_scene::world::{Material, Scene};
use prism_spectrum::SampledSpectrum;

use crate::RenderSettings;
use crate::filter::FilterSampler;
use crate::path::Tracer;
use crate::render::{RowOutput, Rows};
use crate::sample_value::SampleValue;

use paths::trace_batch;

/// Why the batch tracer cannot render `scene` with `settings` (None: it can).
pub(crate) fn unsupported(scene: &Scene, settings: &RenderSettings) -> Option<String> {
    if let Some(other) = scene
        .materials()
        .iter()
        .find(|m| !matches!(m, Material::Diffuse { .. }))
    {
        return Some(format!(
            "it renders Lambertian materials only so far, and this scene has {}",
            kind(other)
        ));
    }
    if settings.is_polarized() {
        return Some("it does not render polarization yet".into());
    }
    if settings.at.is_some() || settings.shutter.is_some() {
        return Some("it renders the steady state only (no --at or --shutter)".into());
    }
    None
}

/// What a material is, in the words of an error message.
fn kind(material: &Material) -> &'static str {
    match material {
        Material::Diffuse { .. } => "a Lambertian material",
        Material::MetallicRoughness { .. } => "a glTF metallic-roughness material",
        Material::Dielectric { .. } => "glass",
        Material::Conductor { .. } => "a metal",
        Material::Fluorescent { .. } => "a fluorescent material",
        Material::Polarizer { .. } => "a polarizer",
        Material::Retarder { .. } => "a retarder",
        _ => "a material other than Lambertian",
    }
}

/// A row tracer: traces every sample of every pixel of row `y`; returns rays traced and
/// samples rejected.
pub(crate) type RowTracer = fn(&Tracer, &FilterSampler, &Rows, u32, &mut RowOutput) -> (u64, u64);

/// The batch tracer's row `width` lanes wide (None: the CPU's width), for packages of `N`
/// wavelengths.
pub(crate) fn row_tracer<const N: usize>(width: Option<usize>) -> RowTracer {
    match width.unwrap_or_else(native_width) {
        16 => wide_row::<N, 16>,
        8 => wide_row::<N, 8>,
        _ => row::<N, 4>,
    }
}

/// [`row`], compiled for the instruction set whose registers hold `W` lanes where the CPU
/// has it (AVX-512 for 16, AVX2 for 8), else for the build's baseline.
fn wide_row<const N: usize, const W: usize>(
    tracer: &Tracer,
    filter: &FilterSampler,
    rows: &Rows,
    y: u32,
    out: &mut RowOutput,
) -> (u64, u64) {
    #[cfg(target_arch = "x86_64")]
    #[allow(
        unsafe_code,
        reason = "code compiled for AVX-512 or AVX2, entered where the CPU has it"
    )]
    {
        // SAFETY: each is entered only where the CPU has what it is compiled for.
        if W == 16 && std::arch::is_x86_feature_detected!("avx512f") {
            return unsafe { row_avx512::<N>(tracer, filter, rows, y, out) };
        }
        if W == 8 && std::arch::is_x86_feature_detected!("avx2") {
            return unsafe { row_avx2::<N>(tracer, filter, rows, y, out) };
        }
    }
    row::<N, W>(tracer, filter, rows, y, out)
}

/// [`row`] sixteen lanes wide, compiled for AVX-512.
///
/// # Safety
/// The CPU must have AVX-512F and AVX2.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "compiled for AVX-512, entered where the CPU has it"
)]
#[target_feature(enable = "avx512f,avx2")]
unsafe fn row_avx512<const N: usize>(
    tracer: &Tracer,
    filter: &FilterSampler,
    rows: &Rows,
    y: u32,
    out: &mut RowOutput,
) -> (u64, u64) {
    row::<N, 16>(tracer, filter, rows, y, out)
}

/// [`row`] eight lanes wide, compiled for AVX2.
///
/// # Safety
/// The CPU must have AVX2.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "compiled for AVX2, entered where the CPU has it"
)]
#[target_feature(enable = "avx2")]
unsafe fn row_avx2<const N: usize>(
    tracer: &Tracer,
    filter: &FilterSampler,
    rows: &Rows,
    y: u32,
    out: &mut RowOutput,
) -> (u64, u64) {
    row::<N, 8>(tracer, filter, rows, y, out)
}

/// The row in batches of `W` pixels: each batch traces sample after sample, and each
/// pixel's samples reach its sums in order, as in the path tracer's row.
#[inline(always)]
fn row<const N: usize, const W: usize>(
    tracer: &Tracer,
    filter: &FilterSampler,
    rows: &Rows,
    y: u32,
    out: &mut RowOutput,
) -> (u64, u64) {
    let (mut rays, mut rejected) = (0u64, 0u64);
    let mut values: [SampleValue; W] = std::array::from_fn(|_| SampleValue::default());
    let mut x0 = 0u32;
    while x0 < rows.width {
        let count = (rows.width - x0).min(W as u32) as usize;
        for s in rows.samples.clone() {
            let results = trace_batch::<N, W>(tracer, filter, rows, (x0, y), count, s, &mut values);
            for (i, (result, value)) in results.iter().zip(&values).take(count).enumerate() {
                rays += result.rays;
                rejected += u64::from(out.add(x0 as usize + i, result, value, rows));
            }
        }
        x0 += W as u32;
    }
    (rays, rejected)
}

/// Lane `i` of spectra held as one lane array per wavelength.
fn lane_spectrum<const N: usize, const W: usize>(
    spectra: &[prism_sampling::lanes::real::Reals<W, true>; N],
    i: usize,
) -> SampledSpectrum<N> {
    SampledSpectrum::from_fn(|j| spectra[j].lane(i))
}
