//! Triangle mesh files that scene formats refer to: Mitsuba's `serialized` meshes (more
//! formats join as the loaders that name them do).
//!
//! A reader takes the file's bytes (this crate touches no files) and returns a
//! [`TriangleMesh`] in the file's own space; the scene format places it.

#[cfg(feature = "mitsuba")]
pub mod serialized;

use glam::{Vec2, Vec3};

/// An indexed triangle mesh as a file stores it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriangleMesh {
    /// The mesh's name in the file (empty where the format names none).
    pub name: String,
    /// Vertex positions, in the file's space.
    pub positions: Vec<Vec3>,
    /// Per-vertex normals, as many as `positions`, or empty where the file has none.
    pub normals: Vec<Vec3>,
    /// Per-vertex texture coordinates, as many as `positions`, or empty.
    pub uvs: Vec<Vec2>,
    /// Vertex indices, each below `positions.len()`.
    pub triangles: Vec<[u32; 3]>,
    /// Whether the file asks for faceted shading (face normals) over its vertex normals.
    pub face_normals: bool,
}
