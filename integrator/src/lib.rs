#![doc = include_str!("../README.md")]
//!
//! ## In detail
//!
//! Renders a [`prism_scene::world::Scene`] by solving the rendering equation per
//! wavelength: unidirectional path tracing with next-event estimation and multiple
//! importance sampling (power heuristic) between light and BSDF sampling, Russian roulette,
//! light paths for the caustics the camera sees directly (in scenes with smooth glass or
//! metal), and hero-wavelength packages of 1 to 16 wavelengths (Wilkie et al. 2014). Each path's
//! spectral radiance becomes XYZ with its wavelengths' densities and is accumulated on an
//! f64 [`Film`]; the film is encoded as EXR or PNG bytes.
//!
//! ## Where things are
//!
//! In layers, lowest first; a file imports from its own layer or below
//! (`python3 .ci/circles.py integrator/src --check` finds no circle):
//!
//! - `settings.rs`, `error.rs`: what a render is asked for, and its one error type.
//! - `film/`: the f64 film and its sums, the pixel filter and light paths' splats by it,
//!   what a sample brings (`radiance.rs`: a spectrum, or Stokes vectors) and its value in
//!   the film's units (`sample_value.rs`, with a `Sensor`: the observer or a camera's
//!   response), spectral bands, and the feature buffers' names and sums (`aov.rs`,
//!   `aov_sums.rs`).
//! - `io/`: EXR and PNG encodings (and the polarization PNG), lossless accumulation files
//!   of every film channel, image comparison, a denoised image's EXR (bytes only).
//! - `transport/`: light transport. `context.rs` holds what every path of a render shares
//!   (the `Integrator`: scene, wavelengths, sensor, camera, clock) and the sample stream's
//!   dimensions; `throughput.rs` what a camera path carries (a spectrum, or per-lane
//!   Mueller matrices for `--polarized`, each specialization compiled apart); `path/` the
//!   hero-wavelength path tracer (the bounce loop in `mod.rs`, a continuation's state,
//!   scattering and Russian roulette in `walk.rs`, the light it meets, MIS-weighed, in
//!   `light.rs`, fluorescent vertices in `fluorescence.rs`); `volume/` the volumetric path
//!   tracer for scenes with media (a flight through one stretch of medium in `segment.rs`,
//!   collisions in a medium with a fluorescent dye in `dye.rs`, the lanes' density ratios
//!   and their balance-heuristic weights in `ratios.rs`, met light and next-event
//!   estimation in `light.rs`, shadow rays' ratio tracking in `shadow.rs`, the nesting of
//!   volumes in `stack.rs`); `light_path.rs` light paths for the caustics seen directly
//!   (unpolarized renders); `reuse_record.rs` what a camera path records for path reuse;
//!   `clock.rs` an instant or an exposure of the scene's clock; `footprint.rs` texture
//!   footprints.
//! - `adaptive/`: adaptive sampling's map of samples per tile, and what its pilot measures
//!   in each output.
//! - `pixels/`: a pass's sample plan (`sample_plan.rs`), one camera sample traced by the
//!   tracer its scene needs (`sample.rs`, the one place that chooses), rows of pixels
//!   summed in index order (`rows.rs`), the feature buffers' rays (`features.rs`) and light
//!   paths' splats collected per row (`splats.rs`).
//! - `reuse/`: path reuse across tiles of pixels: each pixel's first vertex gathers its
//!   tile's second vertices by multiple importance sampling, in `gather.rs` eight first
//!   vertices at a time in SIMD lanes over `prism_sampling::lanes::real::Real`; a tile's
//!   paths share one package of wavelengths and one cache of the spectra at them.
//! - `plan/`: the one place a render's settings become its estimators
//!   (`estimators.rs`: [`Estimators`], each with why), what every pass shares
//!   (`setup.rs`), and the pilots that choose what is left to them: splits and reuse
//!   (`modes.rs`) and adaptive sampling's map (`adaptive_pilot.rs`).
//! - `render.rs`: runs the plan ([`Renderer`], [`render`], [`render_into`]).
//!
//! Key types: `RenderSettings`, `Splits`, `Reuse`, `Renderer`, `Estimators`, `render`,
//! `render_into`, `Film`, `Filter`, `encode_exr`, `encode_png`, `encode_polarization_png`,
//! `encode_accumulation`, `decode_accumulation`, `merge_accumulations`.
//!
//! ## Why it is designed so
//! - **Deterministic by construction.** Every random number is a pure function of (seed,
//!   pixel, sample index, dimension) (`prism-sampling`'s Owen-scrambled Sobol stream) and
//!   every pixel sums its samples in index order on one thread, so an image depends only on
//!   the scene, the settings and the seed, never on thread count or scheduling; a sample
//!   range rendered elsewhere merges into the same sums. Light paths land anywhere on the
//!   film, so their splats are collected per row and added in row order.
//! - **Caustics by the estimator that can find them.** Light, then delta bounces, then a
//!   surface the camera sees: light paths count exactly these paths and camera paths skip
//!   them, a partition of path space rather than MIS (`light_path`), so the image stays
//!   unbiased while a spot light through a prism casts its spectrum.
//! - **Light lost to a split package is not counted twice.** At a dispersive delta event
//!   the radiance gathered so far goes to the film with the whole package's densities,
//!   then the secondaries end and the hero carries on alone with its density divided by C
//!   (the film never sees a terminated lane as if it had been traced).
//! - **Russian roulette tuned for time to equal error, not paths per second**: a path is
//!   at risk only once its throughput (with the 1 / eta^2 of each refraction undone: it
//!   returns when the path leaves the glass) falls below a quarter. Measured on five
//!   scenes, this is more efficient than survival equal to the throughput on every one,
//!   for fewer paths per second (the repository's docs/trade-offs.md, "Russian roulette").
//! - **Non-finite samples are rejected and counted**, never written: they count as zero
//!   in the pixel's normalization, and the count is reported.
//! - **RGB never reaches here.** The scene hands over spectra and BSDFs; this crate does not
//!   depend on `prism-upsample`.
//!
//! ## References
//! - E. Veach, *Robust Monte Carlo Methods for Light Transport Simulation*, PhD thesis,
//!   1997, §9 (multiple importance sampling, the power heuristic).
//! - A. Wilkie, S. Nawaz, M. Droske, A. Weidlich, J. Hanika, "Hero wavelength spectral
//!   sampling", EGSR 2014, §4 (packages, spectral MIS).
//! - E. Veach, 1997 (above), §5.3 (adjoint BSDFs with shading normals), §10.2 (light
//!   tracing and the camera's importance).
//! - M. Pharr, W. Jakob, G. Humphreys, *PBR* 4th ed., §13.4 (path tracing with NEE, and
//!   its `etaScale` for roulette through glass), §5.4 (film), §4.5.4 (sampled spectra
//!   to XYZ).

mod adaptive;
mod error;
mod film;
mod io;
mod pixels;
mod plan;
mod render;
mod reuse;
mod settings;
mod transport;

/// glam, whose types appear in this crate's and prism-scene's public APIs.
pub use glam;
/// prism-scene, whose `Scene` this crate renders (re-exported so that callers name the same
/// version).
pub use prism_scene;

pub use error::RenderError;
pub use film::Film;
pub use film::aov::{Aov, Aovs};
pub use film::aov_sums::AovSums;
pub use film::bands::SpectralBands;
pub use film::camera_response::{CameraResponse, ResponseCurve};
pub use film::filter::Filter;
#[cfg(feature = "exr")]
pub use io::accumulation::{
    Accumulation, decode_accumulation, encode_accumulation, merge_accumulations,
    settings_difference,
};
#[cfg(feature = "exr")]
pub use io::compare::decode_exr;
pub use io::compare::{ChannelImage, Comparison, compare_images};
#[cfg(feature = "exr")]
pub use io::denoised::{NOISY_LAYER, replace_rgb_exr};
pub use io::image::{DisplaySettings, encode_png, encode_png_rgb, encode_polarization_png};
#[cfg(feature = "exr")]
pub use io::image::{ExrMetadata, encode_exr};
pub use io::ztest::{MITSUBA_PASS_SHARE, MITSUBA_SIGNIFICANCE, ZTest, z_test};
pub use plan::estimators::{Estimators, TracerKind};
pub use render::{RenderStats, Renderer, render, render_into};
pub use settings::{
    LambdaSampler, MAX_REUSE, MAX_SPLITS, MAX_THREADS, RenderSettings, Reuse, Splits, Tracing,
};
