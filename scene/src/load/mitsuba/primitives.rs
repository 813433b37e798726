//! Mitsuba's built-in shapes as meshes: `rectangle` and `cube` exactly (Mitsuba 3 builds
//! them as meshes too), `disk`, `cylinder` and `sphere` tessellated, since prism's
//! geometry is triangles. Each keeps Mitsuba's texture coordinates and shading normals
//! ("Shapes" plugin reference; `src/shapes/*.cpp` of mitsuba3 for what the page leaves
//! out).
//!
//! How fine: a sphere is 256 segments around by 128 rings (65,024 triangles), a disk 256
//! segments, a cylinder 256 segments around. A chord of 2 pi / 256 lies within 7.5e-5 of
//! the radius of the true surface, far below a pixel at any distance the shape fills
//! less than ten thousand pixels across; the shading normals are the true surface's at
//! the vertices, interpolated between, and the texture coordinates the true ones at the
//! vertices, interpolated linearly between (exact for a cylinder's height and a disk's
//! radius along the rim).

use std::f64::consts::PI;

use glam::{DMat4, DVec3, Vec2, Vec3};

use super::shape_mesh::ShapeMesh;
use crate::load::meshes::TriangleMesh;

/// Segments around a sphere, disk or cylinder.
pub(crate) const SEGMENTS: u32 = 256;
/// Rings from pole to pole of a sphere.
pub(crate) const RINGS: u32 = 128;

/// `rectangle`: [-1, 1]^2 in the z = 0 plane, facing +z, (u, v) = ((x + 1) / 2, (y + 1) /
/// 2), as Mitsuba's four vertices and two triangles (`src/shapes/rectangle.cpp`).
pub(crate) fn rectangle(to_world: &DMat4, flip_normals: bool) -> Result<ShapeMesh, String> {
    let corner = |i: u32| {
        let (x, y) = ((i & 1) as f32, (i >> 1) as f32);
        (
            Vec3::new(2.0 * x - 1.0, 2.0 * y - 1.0, 0.0),
            Vec2::new(x, y),
        )
    };
    let mesh = TriangleMesh {
        positions: (0..4).map(|i| corner(i).0).collect(),
        normals: vec![Vec3::Z; 4],
        uvs: (0..4).map(|i| corner(i).1).collect(),
        triangles: vec![[1, 2, 0], [1, 3, 2]],
        ..TriangleMesh::default()
    };
    ShapeMesh::from_file(mesh, to_world, false, flip_normals)
}

/// `cube`: [-1, 1]^3, Mitsuba's 24 vertices (four per face, each face its own texture
/// coordinates from (0, 1) round to (0, 0)) and 12 triangles (`src/shapes/cube.cpp`).
pub(crate) fn cube(to_world: &DMat4, flip_normals: bool) -> Result<ShapeMesh, String> {
    // Per face: its outward normal and its four corners in Mitsuba's order.
    let faces: [(Vec3, [[f32; 3]; 4]); 6] = [
        (
            Vec3::NEG_Y,
            [
                [1., -1., -1.],
                [1., -1., 1.],
                [-1., -1., 1.],
                [-1., -1., -1.],
            ],
        ),
        (
            Vec3::Y,
            [[1., 1., -1.], [-1., 1., -1.], [-1., 1., 1.], [1., 1., 1.]],
        ),
        (
            Vec3::X,
            [[1., -1., -1.], [1., 1., -1.], [1., 1., 1.], [1., -1., 1.]],
        ),
        (
            Vec3::Z,
            [[1., -1., 1.], [1., 1., 1.], [-1., 1., 1.], [-1., -1., 1.]],
        ),
        (
            Vec3::NEG_X,
            [
                [-1., -1., 1.],
                [-1., 1., 1.],
                [-1., 1., -1.],
                [-1., -1., -1.],
            ],
        ),
        (
            Vec3::NEG_Z,
            [
                [1., 1., -1.],
                [1., -1., -1.],
                [-1., -1., -1.],
                [-1., 1., -1.],
            ],
        ),
    ];
    let uvs = [Vec2::Y, Vec2::ONE, Vec2::X, Vec2::ZERO];
    let mut mesh = TriangleMesh::default();
    for (f, (normal, corners)) in faces.iter().enumerate() {
        let base = 4 * f as u32;
        mesh.positions
            .extend(corners.iter().map(|c| Vec3::from(*c)));
        mesh.normals.extend([*normal; 4]);
        mesh.uvs.extend(uvs);
        mesh.triangles
            .extend([[base, base + 1, base + 2], [base + 3, base, base + 2]]);
    }
    ShapeMesh::from_file(mesh, to_world, false, flip_normals)
}

/// `disk`: the unit disk in the z = 0 plane facing +z, (u, v) = (r, phi / 2 pi)
/// (`src/shapes/disk.cpp`); a fan of [`SEGMENTS`] triangles, each with a centre vertex of
/// its own so that v is the segment's there.
pub(crate) fn disk(to_world: &DMat4, flip_normals: bool) -> Result<ShapeMesh, String> {
    let mut mesh = TriangleMesh::default();
    for j in 0..=SEGMENTS {
        let v = j as f64 / SEGMENTS as f64;
        let phi = 2.0 * PI * v;
        mesh.positions
            .push(DVec3::new(phi.cos(), phi.sin(), 0.0).as_vec3());
        mesh.uvs.push(Vec2::new(1.0, v as f32));
    }
    for j in 0..SEGMENTS {
        let centre = mesh.positions.len() as u32;
        mesh.positions.push(Vec3::ZERO);
        mesh.uvs
            .push(Vec2::new(0.0, ((j as f64 + 0.5) / SEGMENTS as f64) as f32));
        mesh.triangles.push([centre, j, j + 1]);
    }
    mesh.normals = vec![Vec3::Z; mesh.positions.len()];
    // Mitsuba flips a disk by mirroring z in its to_world: for a flat disk that is its
    // normal turned, which `from_file` does.
    ShapeMesh::from_file(mesh, to_world, false, flip_normals)
}

/// `cylinder`: the open tube of radius `radius` from `p0` to `p1` (no caps), (u, v) = (phi
/// / 2 pi, height from p0 as a fraction of the length), its normals pointing out whatever
/// the transform mirrors (`src/shapes/cylinder.cpp`: a mirroring `to_world` turns both the
/// computed normal and the flag back).
pub(crate) fn cylinder(
    to_world: &DMat4,
    p0: DVec3,
    p1: DVec3,
    radius: f64,
    flip_normals: bool,
) -> Result<ShapeMesh, String> {
    let axis = p1 - p0;
    let length = axis.length();
    if !(length > 0.0 && length.is_finite() && radius > 0.0 && radius.is_finite()) {
        return Err("a cylinder needs p0 and p1 apart and a positive radius".into());
    }
    let (s, t) = coordinate_system(axis / length);
    let frame = DMat4::from_cols(
        s.extend(0.0),
        t.extend(0.0),
        (axis / length).extend(0.0),
        glam::DVec4::W,
    );
    let placed = *to_world
        * DMat4::from_translation(p0)
        * frame
        * DMat4::from_scale(DVec3::new(radius, radius, length));
    let mut mesh = TriangleMesh::default();
    for z in [0.0, 1.0] {
        for j in 0..=SEGMENTS {
            let u = j as f64 / SEGMENTS as f64;
            let (sin, cos) = (2.0 * PI * u).sin_cos();
            mesh.positions.push(DVec3::new(cos, sin, z).as_vec3());
            mesh.normals.push(DVec3::new(cos, sin, 0.0).as_vec3());
            mesh.uvs.push(Vec2::new(u as f32, z as f32));
        }
    }
    let ring = SEGMENTS + 1;
    for j in 0..SEGMENTS {
        mesh.triangles
            .extend([[j, j + 1, ring + j + 1], [j, ring + j + 1, ring + j]]);
    }
    // The inverse transpose of any to_world keeps the normal (x, y, 0) pointing out.
    ShapeMesh::from_file(mesh, &placed, false, flip_normals)
}

/// `sphere`: centre `center`, radius `radius`, then `to_world`; (u, v) = (phi / 2 pi, theta
/// / pi) of the point in the sphere's own frame (`src/shapes/sphere.cpp`). Mitsuba keeps a
/// true sphere (its centre and the length of `to_world`'s x axis as radius) whatever the
/// transform's scales, and turns its normals inwards under a mirroring transform; so does
/// this one.
pub(crate) fn sphere(
    to_world: &DMat4,
    center: DVec3,
    radius: f64,
    flip_normals: bool,
) -> Result<ShapeMesh, String> {
    let placed =
        *to_world * DMat4::from_translation(center) * DMat4::from_scale(DVec3::splat(radius));
    let linear = glam::DMat3::from_mat4(placed);
    let world_centre = placed.transform_point3(DVec3::ZERO);
    let world_radius = linear.x_axis.length();
    if !(world_radius > 0.0 && world_radius.is_finite() && world_centre.is_finite()) {
        return Err("a sphere needs a positive, finite radius".into());
    }
    let inward = flip_normals ^ (linear.determinant() < 0.0);
    let mut mesh = ShapeMesh::default();
    let mut vertex = |theta: f64, phi: f64| {
        let local = DVec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        );
        let direction = (linear * local).normalize_or_zero();
        mesh.positions
            .push((world_centre + world_radius * direction).as_vec3());
        let n = direction.as_vec3();
        mesh.normals.push(if inward { -n } else { n });
        mesh.uvs
            .push(Vec2::new((phi / (2.0 * PI)) as f32, (theta / PI) as f32));
        mesh.positions.len() as u32 - 1
    };
    let angle = |k: u32, of: u32, range: f64| range * k as f64 / of as f64;
    // Rings 1..RINGS-1 with a seam vertex at each end; the poles one vertex per segment,
    // at the segment's middle phi.
    let mut rows = Vec::new();
    for i in 1..RINGS {
        let theta = angle(i, RINGS, PI);
        let first = vertex(theta, 0.0);
        for j in 1..=SEGMENTS {
            vertex(theta, angle(j, SEGMENTS, 2.0 * PI));
        }
        rows.push(first);
    }
    let mid = |j: u32| angle(2 * j + 1, 2 * SEGMENTS, 2.0 * PI);
    let north: Vec<u32> = (0..SEGMENTS).map(|j| vertex(0.0, mid(j))).collect();
    let south: Vec<u32> = (0..SEGMENTS).map(|j| vertex(PI, mid(j))).collect();
    let (top, bottom) = (rows[0], rows[rows.len() - 1]);
    for j in 0..SEGMENTS {
        mesh.triangles
            .push([north[j as usize], top + j, top + j + 1]);
        mesh.triangles
            .push([south[j as usize], bottom + j + 1, bottom + j]);
        for r in rows.windows(2) {
            let (a, b) = (r[0] + j, r[1] + j);
            mesh.triangles.extend([[a, b, b + 1], [a, b + 1, a + 1]]);
        }
    }
    if mesh.positions.iter().any(|p| !p.is_finite()) {
        return Err("to_world takes the sphere out of range".into());
    }
    Ok(mesh)
}

/// Mitsuba's orthonormal basis around a unit vector (`coordinate_system`, after Duff et
/// al., "Building an orthonormal basis, revisited", JCGT 6(1), 2017): it fixes where a
/// cylinder's phi starts.
fn coordinate_system(n: DVec3) -> (DVec3, DVec3) {
    let sign = 1f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Where a ray first meets the mesh: the hit's texture coordinates and interpolated
    /// shading normal (Möller and Trumbore's test over every triangle).
    fn probe(mesh: &ShapeMesh, origin: Vec3, direction: Vec3) -> Option<(Vec2, Vec3)> {
        let mut best: Option<(f32, Vec2, Vec3)> = None;
        for t in &mesh.triangles {
            let p = t.map(|i| mesh.positions[i as usize]);
            let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
            let h = direction.cross(e2);
            let det = e1.dot(h);
            if det.abs() < 1e-12 {
                continue;
            }
            let s = origin - p[0];
            let b1 = s.dot(h) / det;
            let q = s.cross(e1);
            let b2 = direction.dot(q) / det;
            let d = e2.dot(q) / det;
            if b1 < 0.0 || b2 < 0.0 || b1 + b2 > 1.0 || d <= 0.0 {
                continue;
            }
            if best.is_none_or(|(bd, _, _)| d < bd) {
                let b = [1.0 - b1 - b2, b1, b2];
                let uv = (0..3).map(|k| b[k] * mesh.uvs[t[k] as usize]).sum();
                let n: Vec3 = (0..3).map(|k| b[k] * mesh.normals[t[k] as usize]).sum();
                best = Some((d, uv, n.normalize()));
            }
        }
        best.map(|(_, uv, n)| (uv, n))
    }

    fn close(a: Vec2, b: [f32; 2], tolerance: f32) -> bool {
        (a - Vec2::from(b)).abs().max_element() < tolerance
    }

    // The expected values below are pip Mitsuba 3.9's (`scalar_spectral`) for the same
    // rays: `scene.ray_intersect(...)` giving `si.uv` and `si.n`.

    #[test]
    fn sphere_texture_coordinates_and_normals_are_mitsubas() {
        let cases = [
            (DMat4::IDENTITY, [0.033_617_4, 0.403_013], 0.932_738),
            // A mirroring transform: Mitsuba turns the normals in.
            (
                DMat4::from_scale(DVec3::new(-1.0, 1.0, 1.0)),
                [0.466_383, 0.403_013],
                -0.932_738,
            ),
        ];
        for (to_world, uv, nx) in cases {
            let mesh = sphere(&to_world, DVec3::ZERO, 1.0, false).unwrap();
            let (got, n) = probe(&mesh, Vec3::new(5.0, 0.2, 0.3), Vec3::NEG_X).unwrap();
            assert!(close(got, uv, 2e-3), "{got} vs {uv:?}");
            assert!((n.x - nx).abs() < 1e-3, "{n}");
        }
        assert_eq!(
            sphere(&DMat4::IDENTITY, DVec3::ZERO, 1.0, false)
                .unwrap()
                .triangles
                .len() as u32,
            2 * SEGMENTS * (RINGS - 1)
        );
    }

    #[test]
    fn cylinder_texture_coordinates_follow_mitsubas_frame() {
        let mesh = cylinder(&DMat4::IDENTITY, DVec3::ZERO, DVec3::ONE, 0.5, false).unwrap();
        let (uv, n) = probe(&mesh, Vec3::new(5.0, 0.2, 0.3), Vec3::NEG_X).unwrap();
        assert!(close(uv, [0.935_75, 0.452_073], 2e-3), "{uv}");
        assert!(
            (n - Vec3::new(0.808_29, -0.504_145, -0.304_145)).length() < 2e-3,
            "{n}"
        );
        // Mirrored in x: the normal still points out.
        let mirrored = cylinder(
            &DMat4::from_scale(DVec3::new(-1.0, 1.0, 1.0)),
            DVec3::ZERO,
            DVec3::Z,
            1.0,
            false,
        )
        .unwrap();
        let (uv, n) = probe(&mirrored, Vec3::new(5.0, 0.2, 0.3), Vec3::NEG_X).unwrap();
        assert!(close(uv, [0.467_953, 0.3], 2e-3), "{uv}");
        assert!(n.x > 0.97, "{n}");
    }

    #[test]
    fn disk_and_rectangle_texture_coordinates_are_mitsubas() {
        let disk = disk(&DMat4::IDENTITY, false).unwrap();
        let (uv, n) = probe(&disk, Vec3::new(0.3, 0.2, 5.0), Vec3::NEG_Z).unwrap();
        assert!(close(uv, [0.360_555, 0.093_583_5], 2e-3), "{uv}");
        assert_eq!(n, Vec3::Z);
        let rect = rectangle(&DMat4::IDENTITY, false).unwrap();
        let (uv, _) = probe(&rect, Vec3::new(0.3, 0.2, 5.0), Vec3::NEG_Z).unwrap();
        assert!(close(uv, [0.65, 0.6], 1e-6), "{uv}");
        let flipped = rectangle(&DMat4::IDENTITY, true).unwrap();
        assert_eq!(flipped.normals[0], Vec3::NEG_Z);
    }

    #[test]
    fn cube_texture_coordinates_are_mitsubas() {
        let cube = cube(&DMat4::IDENTITY, false).unwrap();
        let (uv, n) = probe(&cube, Vec3::new(5.0, 0.2, 0.3), Vec3::NEG_X).unwrap();
        assert!(close(uv, [0.6, 0.35], 1e-6), "{uv}");
        assert_eq!(n, Vec3::X);
    }

    #[test]
    fn the_basis_is_mitsubas() {
        let (s, t) = coordinate_system(DVec3::splat(1.0 / 3f64.sqrt()));
        assert!((s - DVec3::new(0.788_675, -0.211_325, -0.577_35)).length() < 1e-6);
        assert!((t - DVec3::new(-0.211_325, 0.788_675, -0.577_35)).length() < 1e-6);
    }
}
