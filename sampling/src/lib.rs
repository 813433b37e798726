#![doc = include_str!("../README.md")]
//!
//! ## In detail
//!
//! The Monte Carlo machinery of the prism spectral renderer, usable on its own: it knows
//! nothing of scenes or spectrum types (wavelength data comes in as closures and tables),
//! and its only dependency is `glam` for directions.
//!
//! ## What is here
//! - [`distribution`]: piecewise-constant 1D and 2D distributions, piecewise-linear 1D,
//!   Walker/Vose alias tables.
//! - [`warp`]: cosine hemisphere, uniform sphere and cone, concentric disk, uniform
//!   triangle, spherical triangle (solid-angle sampling of area lights).
//! - [`stream`]: deterministic per-(pixel, sample, dimension) uniform streams, independent
//!   (counter-based hashing) and Owen-scrambled Sobol.
//! - [`wavelength`]: wavelength ranges and densities (uniform, visible, camera response,
//!   light SPD with a defensive mixture), hero-wavelength packages with balance-heuristic
//!   MIS, spectral MIS weights, secondary termination, fluorescence re-radiation sampling.
//! - [`mis`]: balance and power heuristics. [`stats`]: chi-square testing.
//! - [`decay`]: phosphorescent delays, single and multi-exponential, restricted to the
//!   times light sources were on.
//!
//! ## Where things are
//!
//! Monte Carlo machinery with no knowledge of scenes or spectrum types: distributions,
//! warps, deterministic sample streams (and `SobolLanes`, W consecutive samples drawn at
//! once, bit-identical to W scalar streams), lanes (`lanes`: `Lanes<T, W>`, in which path
//! reuse's gather connects a tile's vertices eight at a time, `Word` for code shared by one word
//! and lanes of them, `Real` and `V3` for arithmetic shared by one `f32` and lanes of them
//! (`Reals<W, EXACT>`; the cosine-hemisphere, concentric-disk and spherical-triangle warps
//! are written once over it, libm for `f32`, the branch-free `lanes::trig` sine, arcsine
//! and arctangent for lanes), `native_width()` from the CPU), wavelength samplers and hero
//! packages, re-radiation sampling, phosphorescent delays (`decay`), MIS, chi-square
//! statistics.
//!
//! Key types: `PiecewiseConstant1D`, `AliasTable`, `SobolStream`, `SobolLanes`, `Lanes`,
//! `Real`, `Reals`, `IndependentStream`, `WavelengthDistribution`, `WavelengthPackage<N>`,
//! `PackageScheme`, `ReradiationSampler`, `decay::Decay`, `stats::chi_square_test`.
//!
//! ## Why it is designed so
//! - **Determinism by construction.** Streams are pure functions of (seed, pixel, sample,
//!   dimension); no generator state crosses samples, so threads and tiles cannot change an
//!   image, and any sample range can be rendered on another machine.
//! - **A package carries the density its estimator needs.** `WavelengthPackage::pdf` is
//!   chosen so that `(1/C) sum_j L_j / pdf_j` is the balance-heuristic estimator of the
//!   chosen scheme; consumers (the film) need not know which scheme produced it.
//! - **Total functions.** Every sampling routine clamps its uniform input into [0, 1) and
//!   never returns NaN; every constructor validates and returns [`SamplingError`].
//! - **Proven by statistics.** Each sampler has a chi-square test (fixed seeds, Bonferroni
//!   corrected) and each estimator an unbiasedness test, in `tests/`.
//!
//! ## References
//! - A. Wilkie, S. Nawaz, M. Droske, A. Weidlich, J. Hanika, "Hero wavelength spectral
//!   sampling", Computer Graphics Forum 33(4), 2014, §3-4.
//! - E. Veach, PhD thesis, Stanford 1997, §9.2 (MIS heuristics).
//! - M. Pharr, W. Jakob, G. Humphreys, *Physically Based Rendering*, 4th ed., §A.4-A.5
//!   (tabulated distributions), §6.5.4 (spherical triangles), §8.7 (Sobol samplers).
//! - J. Arvo, "Stratified sampling of spherical triangles", SIGGRAPH 1995.
//! - B. Burley, "Practical hash-based Owen scrambling", JCGT 9(4), 2020.
//! - S. Joe, F. Y. Kuo, SIAM J. Sci. Comput. 30(5), 2008 (Sobol direction numbers).
//! - A. J. Walker, ACM TOMS 3(3), 1977; M. D. Vose, IEEE TSE 17(9), 1991 (alias method).
//! - P. Shirley, K. Chiu, JGT 2(3), 1997 (concentric disk); E. Heitz, 2019 (triangle).
//! - M. Radziszewski, K. Boryczko, W. Alda, WSCG 2009 (visible wavelength density).

pub mod decay;
pub mod distribution;
mod error;
pub mod lanes;
mod lanes_exp;
pub mod mis;
pub mod stats;
pub mod stream;
pub mod warp;
pub mod wavelength;

pub use error::SamplingError;
/// glam, whose vectors are in this crate's public API (warps take and return them).
pub use glam;
