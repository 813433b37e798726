//! MikkTSpace tangents (Mikkelsen, "Simulation of Wrinkled Surfaces Revisited", 2008), the
//! tangents glTF 2.0 asks for when a normal-mapped mesh has no `TANGENT` (§3.7.2.1:
//! "client implementations SHOULD calculate tangents using default MikkTSpace
//! algorithms"), so that normal maps baked against them (Blender, Substance) shade
//! smoothly across a curved mesh rather than facet by facet.

use bevy_mikktspace::{Geometry, StdOps, TangentSpace, generate_tangents};
use glam::{Vec2, Vec3, Vec4};

/// One primitive's triangles as MikkTSpace reads them.
struct Mesh<'a> {
    positions: &'a [Vec3],
    normals: Option<&'a [Vec3]>,
    uvs: &'a [Vec2],
    indices: &'a [u32],
    /// Per face, per corner: the tangent found (None where MikkTSpace gives none).
    out: Vec<[Option<Vec4>; 3]>,
}

impl Mesh<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.indices[3 * face + vert] as usize
    }

    fn face_normal(&self, face: usize) -> Vec3 {
        let p = [0, 1, 2].map(|k| self.positions[self.vertex(face, k)]);
        (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero()
    }
}

impl Geometry<StdOps> for Mesh<'_> {
    fn num_faces(&self) -> usize {
        self.indices.len() / 3
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.positions[self.vertex(face, vert)].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        match self.normals {
            Some(n) => n[self.vertex(face, vert)].to_array(),
            None => self.face_normal(face).to_array(),
        }
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.uvs[self.vertex(face, vert)].to_array()
    }

    fn set_tangent(&mut self, tangent: Option<TangentSpace>, face: usize, vert: usize) {
        // MikkTSpace's bitangent follows +v; glTF's texture v runs down the image, so its
        // handedness is the opposite sign (as three.js's glTF loader also negates it).
        self.out[face][vert] = tangent
            .map(|t| Vec4::from(t.tangent_encoded()) * Vec4::new(1.0, 1.0, 1.0, -1.0))
            .filter(|t| t.is_finite() && t.truncate() != Vec3::ZERO);
    }
}

/// Per triangle of `indices` (in file order), the MikkTSpace tangent at each corner in
/// the primitive's own space, with glTF's handedness in w; None where the algorithm finds
/// none (degenerate texture coordinates). None for the whole primitive when it fails.
pub(super) fn mikktspace(
    positions: &[Vec3],
    normals: Option<&[Vec3]>,
    uvs: &[Vec2],
    indices: &[u32],
) -> Option<Vec<[Option<Vec4>; 3]>> {
    let mut mesh = Mesh {
        positions,
        normals,
        uvs,
        indices,
        out: vec![[None; 3]; indices.len() / 3],
    };
    generate_tangents(&mut mesh).ok()?;
    Some(mesh.out)
}
