#![doc = include_str!("../README.md")]
//!
//! ## In detail
//!
//! The world prism renders: the geometry (rays, the watertight ray-triangle test, robust
//! spawn offsets, a four-wide BVH collapsed from obvhs's binary one), glTF loading (`load`: node
//! hierarchies, transforms, GLB, data URIs, cameras, metallic-roughness materials with RGB
//! upsampled to spectra, emissive and `KHR_lights_punctual` lights), BSDFs (Lambertian,
//! conductors, dielectrics with per-wavelength IOR, glTF metallic-roughness with the
//! material extensions layered per wavelength: specular, anisotropy, clear coat, sheen,
//! thin-film iridescence solved exactly, thin-walled and partial transmission, diffuse
//! transmission; fluorescent diffuse), spectral descriptions (`spectral`: the `PRISM_spectral` extension and TOML
//! overlays, see docs/scene-format.md), and the render-ready scene (`world`) the
//! integrator consumes, with shading normals, base colour textures (RGB filtered, then
//! upsampled per lookup through a coefficient table fitted at load when a texture needs
//! it), metallic-roughness textures (linear data, read per hit), normal textures (in the
//! mesh's tangent frame, or one derived from its texture coordinates), and absorbing
//! volumes (`KHR_materials_volume`, spectral Beer-Lambert absorption applied by the
//! integrator when a ray leaves through a boundary's inside). Emissive textures make
//! lights whose emission varies across them (read where a light is sampled and where a ray
//! hits it; each triangle is chosen by the light of its own texels). Occlusion textures are
//! ignored: they fake what a path tracer computes.
//!
//! ## Why it is designed so
//! - **Watertight and robust by construction.** Rays through shared edges and vertices hit
//!   exactly one of the adjacent triangles (Woop, Benthin and Wald 2013), and spawned rays
//!   start outside the floating-point error box of their origin (Pharr, Jakob and
//!   Humphreys, *PBR* 4th ed. §6.8), so neither light leaks nor self-shadowing acne depend
//!   on a tuned epsilon.
//! - **RGB stops here.** `world::Scene` hands the integrator spectra (`SceneSpectrum`, a
//!   closed enum sampled per package without dynamic dispatch) and per-hit BSDFs, so the
//!   integrator does not depend on `prism-upsample`.
//! - **One traversal, prism's own intersection.** obvhs builds a binary BVH (PLOC with
//!   reinsertion); prism collapses it into a four-wide tree whose leaves are packets of
//!   four triangles and traverses it one ray at a time with SSE, testing four boxes or four
//!   triangles per instruction. The packet test is the scalar watertight test lane by lane,
//!   bit for bit, so its guarantees hold for every query. (obvhs's compressed eight-wide
//!   tree was measured 8% slower on the Cornell box and 17% on the bunny box, in whole
//!   renders.) The collapse is planned by the surface area heuristic, bottom-up, rather
//!   than greedy.
//! - **Light sampling by what the receiver sees.** Lights are chosen by power (an alias
//!   table), or, when their spectra differ in ways a package of wavelengths can see
//!   (narrow bands, ultraviolet), by power at the path's own wavelengths
//!   (`world/light_choice.rs`: lights grouped by spectral shape, a 1 nm proxy of each, a
//!   defensive floor); an emissive triangle is then sampled uniformly in the solid angle it
//!   subtends when that angle is large enough for its cos / d^2 to vary (0.05 sr and up),
//!   by area otherwise, and `Scene::light_pdf` reports the density of the same choice for
//!   MIS (the trade is measured in `world/light.rs`).
//!
//! ## References
//! - S. Woop, C. Benthin, I. Wald, "Watertight ray/triangle intersection", JCGT 2(1), 2013.
//! - I. Wald, C. Benthin, S. Boulos, "Getting rid of packets: efficient SIMD single-ray
//!   traversal using multi-branching BVHs", RT 2008, §3-4 (the four-wide collapse and
//!   traversal).
//! - H. Ylitie, T. Karras, S. Laine, "Efficient incoherent ray traversal on GPUs through
//!   compressed wide BVHs", HPG 2017, §4.1 (the optimal collapse by dynamic programming).
//! - D. Meister, J. Bittner, "Parallel locally-ordered clustering for bounding volume
//!   hierarchy construction", IEEE TVCG 24(3), 2018 (PLOC, obvhs's builder).
//! - M. Pharr, W. Jakob, G. Humphreys, *PBR* 4th ed., §6.5.3 (triangle test), §6.8
//!   (floating-point error bounds and ray origins), §9 (BSDFs, Fresnel).
//! - J. Arvo, "Stratified sampling of spherical triangles", SIGGRAPH 1995 (solid-angle
//!   sampling of triangle lights; *PBR* 4th ed. §6.5.4 for the bounds of its use).
//! - E. Heitz, "Sampling the GGX distribution of visible normals", JCGT 7(4), 2018.
//! - B. Walter et al., "Microfacet models for refraction through rough surfaces", EGSR 2007.
//! - A. Wilkie et al., "Fluorescence in bi-spectral rendering", EGSR 2006 (re-radiation
//!   matrices; the photon-to-energy factor l_i / l_o).
//! - M. Hullin et al., "Acquisition and analysis of bispectral bidirectional reflectance
//!   and reradiation distribution functions", ACM TOG 29(4), 2010 (measured re-radiation
//!   matrices, the full-matrix form).

/// glam, whose vector and matrix types are in this crate's public API (re-exported so
/// that callers use the same version).
pub use glam;

pub mod bsdf;
pub mod camera;
mod error;
pub mod geometry;
#[cfg(feature = "gltf")]
pub mod load;
pub mod medium;
pub mod polarization;
#[cfg(feature = "gltf")]
pub mod spectral;
pub mod world;

pub use error::{LoadError, Resolver};
