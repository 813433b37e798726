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
//! transmission; fluorescent diffuse), spectral descriptions (`load::prism_spectral`: the
//! `PRISM_spectral` extension and TOML overlays, see docs/scene-format.md), and the
//! render-ready scene (`world`) the integrator consumes, with shading normals, base colour
//! textures (RGB filtered, then upsampled per lookup through a coefficient table fitted
//! at load when a texture needs it), metallic-roughness textures (linear data, read per
//! hit), normal textures (in the mesh's tangent frame, or one derived from its texture
//! coordinates), and absorbing volumes (`KHR_materials_volume`, spectral Beer-Lambert
//! absorption applied by the integrator when a ray leaves through a boundary's inside).
//! Emissive textures make lights whose emission varies across them (read where a light is
//! sampled and where a ray hits it; each triangle is chosen by the light of its own
//! texels). Occlusion textures are ignored: they fake what a path tracer computes.
//!
//! ## Where things are
//!
//! The folders, lowest layer first; a folder imports only folders before it in this list
//! (`python3 .ci/circles.py scene/src --folders --check`), and every folder may use the
//! crate's errors (`error`).
//!
//! - `geometry/`: rays, the watertight triangle test, spawn offsets, the local shading frame
//!   the integrator and the scene share (`Frame`), and the BVH (`bvh/`: an eight-wide tree
//!   with leaves of triangle packets, collapsed by a surface-area-cost plan from the binary
//!   tree obvhs builds; single-ray traversal whose node test is four lanes wide (SSE) or,
//!   where the CPU has AVX2, eight wide in a traversal compiled for x86-64-v3 (`avx`),
//!   chosen at run time (`NodeLanes`) and equal to the bit).
//! - `textures/`: textures (`texture`: base colour and emission upsampled per lookup,
//!   metallic-roughness and normal maps read as linear data), base colour and
//!   metallic-roughness mipmapped (`mipmap`) and read at each hit's footprint
//!   (`Scene::set_footprint`); two texture coordinate sets per triangle, each texture
//!   reading its own (`tex_coords`: a hit's `TexCoords`, with a footprint per set); the
//!   spectra a scene is described with (`spectrum`: `SceneSpectrum`).
//! - `bsdf/`: BSDFs (`thin_film`: the exact Airy reflectance of a film over a dielectric or
//!   conductor, per wavelength; `metallic_roughness`: the glTF base with
//!   `KHR_materials_specular`'s remapped Fresnel, anisotropic GGX and the film; `layered`:
//!   sheen (`sheen`, the Charlie lobe and its albedo table) and clear coat (`clearcoat`, its
//!   own normal) over the base by albedo scaling per wavelength; `coating_albedo`:
//!   directional albedos of the dielectric and mirror lobes, `table`: their lookups), and
//!   the BSDF at a hit, whichever model it is (`dispatch`: the enum `Bsdf`).
//! - `camera/`: pinhole and orthographic projections, the thin lens (`lens`: aperture size
//!   by radius or f-number, focus) and its aperture shapes (`aperture`: disk, bladed
//!   polygon, image), real lens systems (`system/`: prescriptions in pbrt-v4's format with
//!   a glass per element, tracing per wavelength in f64, first-order properties by
//!   near-axis rays, focus by the thick-lens approximation, exit-pupil bounds;
//!   `MountedLens` is a scene's lens on a camera, `FocusedSystem` the lens made ready for a
//!   film, making camera rays and their weights).
//! - `medium/`: participating media: `Medium` (spectral sigma_a, sigma_s, emission;
//!   optional density and temperature grids and a fluorescent dye (`fluorescence`)),
//!   `Media` (which material holds which medium, and the world's fog), phase functions
//!   (`phase`: Henyey-Greenstein, Rayleigh), grids with their coarse majorant grids and DDA
//!   (`grid`), grid files: OpenVDB's `.vdb` (`vdb/`: the header and grid descriptors, the
//!   5-4-3 tree, node values, Blosc buffers) and Mitsuba's `.vol` (`vol`), tracking
//!   against the majorant (`track::sample_majorant`).
//! - `polarization/`: Stokes vectors, Mueller matrices of interfaces from complex Fresnel
//!   amplitudes, polarizers, retarders, frame rotations, the s-p frames of a surface
//!   interaction (`surface`), iridescent films' amplitudes (`ThinFilm::amplitudes`), every
//!   BSDF's per-lane interactions (`bsdf`: Fresnel at the microfacet normal for dielectrics
//!   and conductors, the sheets' elements, depolarizers for the rest), media's phase
//!   functions (`phase`: Rayleigh's Mueller matrix; Henyey-Greenstein depolarizes) and
//!   polarized light emission (`light`), in Mitsuba 3's conventions; the polarizing sheets
//!   (`bsdf::Sheet`, materials `Polarizer` and `Retarder`) are thin delta BSDFs that
//!   unpolarized renders see as grey filters.
//! - `materials/`: materials to per-hit BSDFs (`material`: `Material`); the glTF material
//!   extensions as described (`layers/`: specular, anisotropy, clear coat, sheen,
//!   iridescence), each becoming its part of the BSDF at a hit, oriented by the hit's
//!   tangent frame where it needs one (`SurfaceFrame`); normal maps (`normal_map`); alpha
//!   coverage (`alpha`: MASK cut-outs and BLEND stochastic transparency, intersected
//!   through only in scenes that have them).
//! - `lights/`: lights chosen by power, or by power at the path's wavelengths when their
//!   spectra differ in narrow bands or the ultraviolet (`light_choice`), near triangles
//!   sampled by solid angle, emission and light densities for MIS, emissive textures read
//!   where lights are sampled and hit (`light`); a per-path cache of emission spectra at
//!   the path's wavelengths (`emission_cache`); light from infinity (`environment/`: the
//!   uniform environment, the environment image with its importance sampler, the
//!   emissive-colour convention and the default light of a scene without one).
//! - `world/`: the render-ready scene the integrator consumes (`Scene`: triangles in the
//!   BVH, a material per triangle, the lights, the camera, features; hits, with vertex
//!   colours tinting the base colour (`Scene::bsdf`)); scenes in code (`builder`:
//!   materials, triangles, emitters as lights); where re-radiating vertices look for the
//!   wavelengths light arrives at (`guide`); where a vertex's shadow rays leave it
//!   (`departure`); time (`time/`: `Schedule`, when a source shines, and `Timeline`, the
//!   scene's schedules by light and decay laws by material, with the union of the times
//!   anything shines). It re-exports the types of `textures`, `materials`, `lights` and
//!   `bsdf::Bsdf`, so that `world::{Material, Light, SceneSpectrum, ...}` name them too.
//! - `load/`: glTF loading (geometry, cameras, materials, area and punctual lights; a mesh
//!   primitive's attributes read, checked against each other and placed in the world
//!   (`primitive`); every accessor checked (`accessor`) before it is read, float or
//!   quantized (`KHR_mesh_quantization`) through one reader, and what the node graph
//!   instances counted (`instancing`) before anything is instanced; which extensions prism
//!   reads and the error or warning for the others (`extensions`: warnings travel in
//!   `LoadedGeometry::warnings` for the CLI to print); HDR environment images decoded
//!   (`environment`: OpenEXR, Radiance), `EXT_meshopt_compression` views decoded
//!   (`meshopt`), MikkTSpace tangents (`tangents`), which texture coordinate sets a
//!   material's textures read (`tex_coord_sets`: the base colour's first), the glTF
//!   material extensions read (`material_layers`), `KHR_materials_volume_scatter`
//!   (`volume_scatter`)); the scene format (`prism_spectral/`: the `PRISM_spectral`
//!   extension and TOML overlays, one parser, documented in docs/scene-format.md, media in
//!   `prism_spectral/medium.rs`; also named `prism_scene::spectral`); the render-ready
//!   scene of a loaded file (`gltf_scene`: `Scene::from_loaded`). Nothing imports it.
//!
//! Key types: `geometry::{Ray, Bvh}`, `load::{load_geometry, load_scene, LoadedGeometry,
//! LightDesc}`, `load::prism_spectral::{Overlay, SpectralMaterial}`, `camera::Camera`
//! (`look_at` for cameras in code), `bsdf::*` (with `Bsdf`), `textures::{SceneSpectrum,
//! SpectralTexture, TexCoords}`, `materials::{Material, NormalMap}`, `lights::{Light,
//! EmissionCache, Environment, EnvironmentMap}`, `world::{Scene, SceneParts, SceneBuilder
//! (scenes in code: materials, triangles, emitters as lights), Features}`, `medium::{Medium,
//! Media}`.
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
//!   reinsertion); prism collapses it into an eight-wide tree, each node two groups of
//!   four boxes, whose leaves are one or two packets of four triangles, and traverses it
//!   one ray at a time with SSE, testing four boxes or four triangles per instruction (all
//!   eight boxes in one test where the CPU has AVX2, to the same bits). The packet test is
//!   the scalar watertight test lane by lane, bit for bit, so its guarantees hold for
//!   every query. (obvhs's compressed eight-wide tree measured slower in whole renders:
//!   decoding its quantized boxes costs more than it saves on a CPU; docs/trade-offs.md,
//!   "The BVH and its node test".) The collapse is planned by the surface area heuristic,
//!   bottom-up, rather than greedy.
//! - **Light sampling by what the receiver sees.** Lights are chosen by power (an alias
//!   table), or, when their spectra differ in ways a package of wavelengths can see
//!   (narrow bands, ultraviolet), by power at the path's own wavelengths
//!   (`lights/light_choice.rs`: lights grouped by spectral shape, a 1 nm proxy of each, a
//!   defensive floor); an emissive triangle is then sampled uniformly in the solid angle it
//!   subtends when that angle is large enough for its cos / d^2 to vary (0.05 sr and up),
//!   by area otherwise, and `Scene::light_pdf` reports the density of the same choice for
//!   MIS (the trade is measured in `lights/light.rs`).
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
pub mod lights;
#[cfg(feature = "gltf")]
pub mod load;
pub mod materials;
pub mod medium;
pub mod polarization;
pub mod textures;
pub mod world;

pub use error::{LoadError, Resolver};
/// The `PRISM_spectral` extension and TOML overlays ([`load::prism_spectral`]).
#[cfg(feature = "gltf")]
pub use load::prism_spectral as spectral;
