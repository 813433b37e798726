//! Triangle mesh files that scene formats refer to: Wavefront OBJ (`obj`), Stanford PLY
//! (`ply`) and Mitsuba's `serialized` meshes, each read as Mitsuba 3's plugin of that
//! name reads it.
//!
//! A reader takes the file's bytes (this crate touches no files) and returns a
//! [`TriangleMesh`] in the file's own space; the scene format places it. Every count a
//! file declares is checked against the bytes present before anything is allocated from
//! it, and no input makes a reader panic.

#[cfg(feature = "mitsuba")]
pub mod obj;
#[cfg(feature = "mitsuba")]
pub mod ply;
#[cfg(feature = "mitsuba")]
mod ply_header;
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
    /// Per-vertex normals, as many as `positions`, or empty where the file has none. A
    /// vertex the file gives no normal (an OBJ corner without one) has zero.
    pub normals: Vec<Vec3>,
    /// Per-vertex texture coordinates, as many as `positions`, or empty.
    pub uvs: Vec<Vec2>,
    /// Vertex indices, each below `positions.len()`.
    pub triangles: Vec<[u32; 3]>,
    /// Whether the file asks for faceted shading (face normals) over its vertex normals.
    pub face_normals: bool,
    /// Further values per vertex or per triangle (a PLY file's colours and other
    /// properties), named as Mitsuba names them: `vertex_color`, `face_weight`...
    pub attributes: Vec<MeshAttribute>,
    /// What the reader tells the user about the file (a property it skips), one line each.
    pub warnings: Vec<String>,
}

/// Values a mesh carries per vertex or per triangle beyond its geometry.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshAttribute {
    /// The name, starting `vertex_` (one value set per vertex) or `face_` (per triangle:
    /// a polygon's value is each of its triangles').
    pub name: String,
    /// Values per vertex or triangle: 1 or 3 (a colour's RGB), 4 for RGBA colours.
    pub dim: usize,
    /// `dim` values per vertex or triangle, in order.
    pub values: Vec<f32>,
}

impl MeshAttribute {
    /// Whether the values are per vertex (else per triangle).
    pub fn per_vertex(&self) -> bool {
        self.name.starts_with("vertex_")
    }
}

/// Smooth vertex normals of a mesh without any: each triangle's unit normal weighted by
/// its angle at the vertex (Thürmer and Wüthrich, "Computing vertex normals from polygonal
/// facets", JGT 3(1), 1998), the weighting Mitsuba 3's `Mesh::recompute_vertex_normals`
/// uses. Zero for a vertex no non-degenerate triangle touches.
pub fn angle_weighted_normals(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
    let mut normals = vec![Vec3::ZERO; positions.len()];
    for t in triangles {
        let corners = t.map(|i| i as usize);
        if corners.iter().any(|&i| i >= positions.len()) {
            continue;
        }
        let v = corners.map(|i| positions[i]);
        let n = (v[1] - v[0]).cross(v[2] - v[0]);
        let length = n.length();
        if !(length > 0.0 && length.is_finite()) {
            continue;
        }
        let n = n / length;
        for k in 0..3 {
            let a = (v[(k + 1) % 3] - v[k]).normalize_or_zero();
            let b = (v[(k + 2) % 3] - v[k]).normalize_or_zero();
            let angle = unit_angle(a, b);
            normals[t[k] as usize] += n * angle;
        }
    }
    for n in &mut normals {
        *n = n.normalize_or_zero();
    }
    normals
}

/// The angle between unit vectors, accurate near 0 and pi (the half-chord form).
fn unit_angle(a: Vec3, b: Vec3) -> f32 {
    if a.dot(b) < 0.0 {
        std::f32::consts::PI - 2.0 * ((a + b).length() * 0.5).min(1.0).asin()
    } else {
        2.0 * ((b - a).length() * 0.5).min(1.0).asin()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cube_corner_gets_the_diagonal() {
        // Three faces of a cube meeting at the origin, each a right angle there.
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
        let triangles = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2]];
        let n = angle_weighted_normals(&positions, &triangles);
        let diagonal = -Vec3::ONE.normalize();
        assert!((n[0] - diagonal).length() < 1e-6, "{:?}", n[0]);
    }

    #[test]
    fn weights_are_angles_not_counts() {
        // Two triangles in one plane and one folded up: the fold's angle at vertex 0 is
        // 90 degrees, the flat pair's 45 each, so the normal is the bisector.
        let positions = vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::Y,
            Vec3::Z,
        ];
        let triangles = vec![[0, 1, 2], [0, 2, 3], [0, 4, 1]];
        let n = angle_weighted_normals(&positions, &triangles);
        let expected = (Vec3::Z + Vec3::Y).normalize();
        assert!((n[0] - expected).length() < 1e-6, "{:?}", n[0]);
        // Vertex 3 only sees the flat pair.
        assert!((n[3] - Vec3::Z).length() < 1e-6);
    }

    #[test]
    fn degenerate_and_untouched_vertices_are_zero() {
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0, Vec3::Y];
        let n = angle_weighted_normals(&positions, &[[0, 1, 2], [0, 9, 1]]);
        assert!(n.iter().all(|v| *v == Vec3::ZERO));
    }
}
