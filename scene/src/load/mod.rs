//! Loading glTF 2.0 scenes. This crate touches no files: the caller hands over the bytes
//! of the `.gltf` or `.glb` and a resolver for external buffer URIs.

mod accessor;
mod base64;
pub(crate) mod environment;
mod extensions;
mod geometry;
mod gltf_scene;
pub(crate) mod images;
mod instancing;
mod lights;
mod material_layers;
mod materials;
pub mod meshes;
mod meshopt;
#[cfg(feature = "mitsuba")]
pub mod mitsuba;
mod primitive;
pub mod prism_spectral;
mod summary;
mod tangents;
mod tex_coord_sets;
mod textures;
mod volume_scatter;

pub use crate::error::{LoadError, Resolver};
pub(crate) use base64::uri_bytes;
pub use environment::{EnvironmentImage, HdrImage, decode_hdr_image, environment_map};
pub use geometry::{LoadOptions, LoadedGeometry, MeshInstance, load_geometry, load_scene};
pub use images::{DecodedImage, decode_image};
pub use lights::LightDesc;
pub(crate) use materials::Upsampler;
pub use materials::{MaterialDesc, Upsampling};
