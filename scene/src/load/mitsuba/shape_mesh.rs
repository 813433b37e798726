//! A Mitsuba shape as triangles in world space, with what Mitsuba shades them by: its
//! vertex normals (the shading frame), texture coordinates and mesh attributes.
//!
//! Mitsuba 3 gives every shape a shading normal (`si.sh_frame.n`) and decides by it
//! which side a surface faces: an area emitter emits towards it (`emitters/area.cpp`,
//! `cos_theta(si.wi) > 0`), a one-sided BSDF reflects on it. prism's front side is the
//! side the winding faces, so each triangle is wound to face where Mitsuba's normals at
//! its corners point. The normals follow Mitsuba's rules: a mesh's file normals are
//! transformed by the inverse transpose of `to_world` (so a mirroring transform turns the
//! winding but not them), a mesh without normals gets angle-weighted ones computed in
//! world space (`Mesh::recompute_vertex_normals`), `face_normals` shades by the winding's
//! own normal, and `flip_normals` turns whichever it is around.

use glam::{DMat3, DMat4, Vec2, Vec3, Vec4};

use crate::load::LoadedGeometry;
use crate::load::meshes::{MeshAttribute, TriangleMesh, angle_weighted_normals};

/// A shape's triangles in world space.
#[derive(Debug, Clone, Default)]
pub(crate) struct ShapeMesh {
    pub(crate) positions: Vec<Vec3>,
    /// Unit shading normals per vertex, or empty for faceted shading. A zero normal (a
    /// vertex no usable triangle touches) shades by its triangle's own normal.
    pub(crate) normals: Vec<Vec3>,
    /// Texture coordinates per vertex, or empty: Mitsuba's default, each triangle's
    /// barycentric coordinates (0, 0), (1, 0), (0, 1) at its corners.
    pub(crate) uvs: Vec<Vec2>,
    pub(crate) triangles: Vec<[u32; 3]>,
    /// For faceted shading: whether Mitsuba's normal is opposite the winding's.
    pub(crate) flat_flipped: bool,
    pub(crate) attributes: Vec<MeshAttribute>,
}

impl ShapeMesh {
    /// A mesh file's mesh placed by `to_world`, shaded as Mitsuba's mesh plugins shade
    /// it (`face_normals`, `flip_normals`).
    pub(crate) fn from_file(
        mesh: TriangleMesh,
        to_world: &DMat4,
        face_normals: bool,
        flip_normals: bool,
    ) -> Result<ShapeMesh, String> {
        let normal_matrix = normal_matrix(to_world)?;
        let positions = place_points(&mesh.positions, to_world)?;
        let face_normals = face_normals || mesh.face_normals;
        let mut normals = if face_normals {
            Vec::new()
        } else {
            let mut normals: Vec<Vec3> = mesh
                .normals
                .iter()
                .map(|n| unit(normal_matrix * n.as_dvec3()))
                .collect();
            // Vertices without a usable normal in the file get Mitsuba's computed one.
            if normals.is_empty() || normals.contains(&Vec3::ZERO) {
                let computed = angle_weighted_normals(&positions, &mesh.triangles);
                if normals.is_empty() {
                    normals = computed;
                } else {
                    for (n, c) in normals.iter_mut().zip(computed) {
                        if *n == Vec3::ZERO {
                            *n = c;
                        }
                    }
                }
            }
            normals
        };
        if flip_normals {
            normals.iter_mut().for_each(|n| *n = -*n);
        }
        Ok(ShapeMesh {
            positions,
            normals,
            uvs: mesh
                .uvs
                .iter()
                .map(|uv| if uv.is_finite() { *uv } else { Vec2::ZERO })
                .collect(),
            triangles: mesh.triangles,
            flat_flipped: face_normals && flip_normals,
            attributes: mesh.attributes,
        })
    }

    /// The mesh moved by `transform` (an instance's `to_world`): points by it, normals by
    /// its inverse transpose, as Mitsuba's `instance` transforms a hit
    /// (`shapes/instance.cpp`); a mirroring transform turns a faceted mesh's winding, not
    /// its normal, so the flag flips.
    pub(crate) fn transformed(&self, transform: &DMat4) -> Result<ShapeMesh, String> {
        let normal_matrix = normal_matrix(transform)?;
        Ok(ShapeMesh {
            positions: place_points(&self.positions, transform)?,
            normals: self
                .normals
                .iter()
                .map(|n| unit(normal_matrix * n.as_dvec3()))
                .collect(),
            uvs: self.uvs.clone(),
            triangles: self.triangles.clone(),
            flat_flipped: self.flat_flipped ^ (transform.determinant() < 0.0),
            attributes: self.attributes.clone(),
        })
    }

    /// The attribute called `name`, if the mesh has it.
    pub(crate) fn attribute(&self, name: &str) -> Option<&MeshAttribute> {
        self.attributes.iter().find(|a| a.name == name)
    }

    /// Appends the triangles to `out` with their normals and texture coordinates (and
    /// vertex colours where `colors` gives them per triangle corner), each wound to face
    /// where Mitsuba's normals point. Returns the number of triangles.
    pub(crate) fn append(&self, colors: Option<&[[Vec4; 3]]>, out: &mut LoadedGeometry) -> usize {
        let first = out.triangles.len();
        // Earlier shapes without normals (faceted) get their face normals once a shape
        // brings vertex normals; earlier shapes without colours, white.
        let keep_normals = !self.normals.is_empty() || !out.normals.is_empty();
        if keep_normals && out.normals.len() < first {
            let from = out.normals.len();
            let flat: Vec<[Vec3; 3]> = out.triangles[from..first]
                .iter()
                .map(|t| [face_normal(t); 3])
                .collect();
            out.normals.extend(flat);
        }
        let keep_colors = colors.is_some() || !out.colors.is_empty();
        if keep_colors {
            out.colors.resize(first, [Vec4::ONE; 3]);
        }
        // Every Mitsuba shape has texture coordinates (barycentric ones by default).
        out.uvs.resize(first, [Vec2::ZERO; 3]);
        let barycentric = [Vec2::ZERO, Vec2::X, Vec2::Y];
        for (k, t) in self.triangles.iter().enumerate() {
            let p = t.map(|i| self.positions[i as usize]);
            let winding = (p[1] - p[0]).cross(p[2] - p[0]);
            let turned = if self.normals.is_empty() {
                self.flat_flipped
            } else {
                let sum: Vec3 = t.iter().map(|&i| self.normals[i as usize]).sum();
                sum.dot(winding) < 0.0
            };
            let order = if turned { [0, 2, 1] } else { [0, 1, 2] };
            let placed = order.map(|c| p[c]);
            out.triangles.push(placed);
            if keep_normals {
                let own = face_normal(&placed);
                out.normals
                    .push(order.map(|c| match self.normals.get(t[c] as usize) {
                        Some(n) if *n != Vec3::ZERO => *n,
                        _ => own,
                    }));
            }
            out.uvs.push(if self.uvs.is_empty() {
                order.map(|c| barycentric[c])
            } else {
                order.map(|c| self.uvs[t[c] as usize])
            });
            if keep_colors {
                out.colors
                    .push(colors.map_or([Vec4::ONE; 3], |c| order.map(|o| c[k][o])));
            }
        }
        self.triangles.len()
    }
}

/// The unit normal the winding of `t` faces (zero for a degenerate triangle).
fn face_normal(t: &[Vec3; 3]) -> Vec3 {
    (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero()
}

/// The inverse transpose of a transform's linear part, which carries normals.
pub(crate) fn normal_matrix(transform: &DMat4) -> Result<DMat3, String> {
    let linear = DMat3::from_mat4(*transform);
    let det = linear.determinant();
    if det == 0.0 || !det.is_finite() {
        return Err("to_world is singular (it flattens the shape)".into());
    }
    Ok(linear.inverse().transpose())
}

/// Points moved by `transform`, each finite.
fn place_points(points: &[Vec3], transform: &DMat4) -> Result<Vec<Vec3>, String> {
    points
        .iter()
        .map(|p| {
            let q = transform.transform_point3(p.as_dvec3()).as_vec3();
            if q.is_finite() {
                Ok(q)
            } else {
                Err("to_world takes a vertex out of range".into())
            }
        })
        .collect()
}

/// A unit vector, zero where the input has no direction.
pub(crate) fn unit(v: glam::DVec3) -> Vec3 {
    let n = v.normalize_or_zero().as_vec3();
    if n.is_finite() { n } else { Vec3::ZERO }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad(normals: Vec<Vec3>) -> TriangleMesh {
        TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
            normals,
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            ..TriangleMesh::default()
        }
    }

    fn placed(mesh: &ShapeMesh) -> LoadedGeometry {
        let mut out = LoadedGeometry::default();
        mesh.append(None, &mut out);
        out
    }

    #[test]
    fn a_mirroring_transform_keeps_file_normals_and_turns_the_winding_to_them() {
        let mirror = DMat4::from_scale(glam::DVec3::new(1.0, 1.0, -1.0));
        let mesh = ShapeMesh::from_file(quad(vec![Vec3::Z; 4]), &mirror, false, false).unwrap();
        // The normal (0, 0, 1) under diag(1, 1, -1)'s inverse transpose is (0, 0, -1).
        assert_eq!(mesh.normals[0], Vec3::NEG_Z);
        let out = placed(&mesh);
        let t = out.triangles[0];
        assert!((t[1] - t[0]).cross(t[2] - t[0]).z < 0.0);
        assert_eq!(out.normals[0], [Vec3::NEG_Z; 3]);
        // No texture coordinates: each triangle's barycentrics, kept with their corners.
        assert_eq!(out.uvs[0], [Vec2::ZERO, Vec2::Y, Vec2::X]);
    }

    #[test]
    fn computed_normals_follow_the_placed_winding() {
        let mirror = DMat4::from_scale(glam::DVec3::new(-1.0, 1.0, 1.0));
        let mesh = ShapeMesh::from_file(quad(Vec::new()), &mirror, false, false).unwrap();
        // Computed in world space from the mirrored winding, as Mitsuba computes them.
        assert_eq!(mesh.normals[0], Vec3::NEG_Z);
        let flipped = ShapeMesh::from_file(quad(Vec::new()), &mirror, false, true).unwrap();
        assert_eq!(flipped.normals[0], Vec3::Z);
        let t = placed(&flipped).triangles[0];
        assert!((t[1] - t[0]).cross(t[2] - t[0]).z > 0.0);
    }

    #[test]
    fn face_normals_shade_flat_and_flip_the_winding() {
        let mesh =
            ShapeMesh::from_file(quad(vec![Vec3::Z; 4]), &DMat4::IDENTITY, true, true).unwrap();
        assert!(mesh.normals.is_empty());
        let out = placed(&mesh);
        assert!(out.normals.is_empty());
        let t = out.triangles[0];
        assert!((t[1] - t[0]).cross(t[2] - t[0]).z < 0.0);
        // An instance that mirrors turns it back.
        let mirrored = mesh
            .transformed(&DMat4::from_scale(glam::DVec3::new(1.0, 1.0, -1.0)))
            .unwrap();
        assert!(!mirrored.flat_flipped);
    }

    #[test]
    fn faceted_shapes_before_smooth_ones_get_their_face_normals() {
        let flat = ShapeMesh::from_file(quad(Vec::new()), &DMat4::IDENTITY, true, false).unwrap();
        let smooth =
            ShapeMesh::from_file(quad(vec![Vec3::Z; 4]), &DMat4::IDENTITY, false, false).unwrap();
        let mut out = LoadedGeometry::default();
        flat.append(None, &mut out);
        smooth.append(None, &mut out);
        assert_eq!(out.normals.len(), 4);
        assert_eq!(out.normals[0], [Vec3::Z; 3]);
        assert_eq!(out.uvs.len(), 4);
    }

    #[test]
    fn a_singular_transform_is_refused() {
        let flat = DMat4::from_scale(glam::DVec3::new(1.0, 0.0, 1.0));
        assert!(ShapeMesh::from_file(quad(Vec::new()), &flat, false, false).is_err());
    }
}
