//! Geometry: watertightness, traversal against brute force, the -0.0 regression,
//! degenerate triangles and self-intersection-free spawn offsets.

use glam::Vec3;
use prism_scene::geometry::{
    Bvh, BvhQuality, Ray, intersect_triangle, offset_ray_origin, triangle_point_error,
};
use proptest::prelude::*;

/// A closed triangulated sphere: an octahedron subdivided `levels` times, projected.
fn sphere(levels: u32, radius: f32, center: Vec3) -> Vec<[Vec3; 3]> {
    let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
    let mut tris = vec![
        [x, y, z],
        [y, -x, z],
        [-x, -y, z],
        [-y, x, z],
        [y, x, -z],
        [-x, y, -z],
        [-y, -x, -z],
        [x, -y, -z],
    ];
    for _ in 0..levels {
        tris = tris
            .into_iter()
            .flat_map(|[a, b, c]| {
                let (ab, bc, ca) = (
                    (a + b).normalize(),
                    (b + c).normalize(),
                    (c + a).normalize(),
                );
                [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
            })
            .collect();
    }
    tris.into_iter()
        .map(|t| t.map(|v| center + radius * v.normalize()))
        .collect()
}

/// Pseudo-random unit vectors.
fn directions(n: usize, mut seed: u64) -> Vec<Vec3> {
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f32 / (1u64 << 53) as f32 * 2.0 - 1.0
    };
    (0..n)
        .filter_map(|_| Vec3::new(next(), next(), next()).try_normalize())
        .collect()
}

/// From inside a closed mesh every ray hits, including rays aimed exactly at shared
/// vertices and through shared edges, where a non-watertight test leaks.
#[test]
fn closed_meshes_do_not_leak() {
    let mesh = sphere(4, 3.0, Vec3::new(0.5, -1.0, 2.0));
    let bvh = Bvh::build(&mesh, BvhQuality::Medium);
    let center = Vec3::new(0.5, -1.0, 2.0);
    let mut targets: Vec<Vec3> = mesh
        .iter()
        .flat_map(|t| [t[0], t[1], t[2], (t[0] + t[1]) / 2.0])
        .collect();
    targets.extend(directions(20_000, 3).into_iter().map(|d| center + d));
    for origin in [center, center + Vec3::new(0.3, 0.2, -0.1)] {
        for target in &targets {
            let ray = Ray::new(origin, *target - origin, f32::INFINITY);
            assert!(
                bvh.intersect(&ray).is_some(),
                "leak from {origin} towards {target}"
            );
        }
    }
}

/// The BVH finds exactly the closest hit that testing every triangle finds.
#[test]
fn traversal_equals_brute_force() {
    let mut mesh = sphere(3, 1.0, Vec3::ZERO);
    mesh.extend(sphere(2, 0.5, Vec3::new(2.0, 0.0, 0.0)));
    mesh.extend(sphere(2, 0.7, Vec3::new(-1.5, 1.0, 0.5)));
    let bvh = Bvh::build(&mesh, BvhQuality::Slow);
    for (k, d) in directions(5_000, 9).into_iter().enumerate() {
        let origin = Vec3::new(
            0.1 * (k % 7) as f32 - 3.0,
            0.2,
            4.0 - 0.01 * (k % 13) as f32,
        );
        let ray = Ray::new(origin, d, f32::INFINITY);
        let brute = mesh
            .iter()
            .enumerate()
            .filter_map(|(i, t)| intersect_triangle(&ray, *t).map(|h| (i, h.t)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        let hit = bvh.intersect(&ray);
        if let Some(h) = hit {
            assert_eq!(h.vertices, mesh[h.triangle], "ray {k}: the hit's vertices");
        }
        let found = hit.map(|h| (h.triangle, h.hit.t));
        assert_eq!(found.map(|f| f.1), brute.map(|b| b.1), "ray {k}");
    }
}

/// Regression: obvhs 0.4 picks its traversal octant from `d < 0` but inverts -0.0 to a
/// negative number, so axis-aligned rays with a -0.0 component missed. `Ray::new`
/// canonicalizes directions; these rays must all hit the unit-sphere mesh.
#[test]
fn axis_aligned_rays_with_negative_zero_hit() {
    let bvh = Bvh::build(&sphere(3, 1.0, Vec3::ZERO), BvhQuality::Medium);
    for axis in 0..3 {
        for sign in [1.0f32, -1.0] {
            let mut d = Vec3::splat(-0.0);
            d[axis] = sign;
            let origin = -3.0 * d + Vec3::splat(1e-3);
            let ray = Ray::new(origin, d, f32::INFINITY);
            assert!(
                bvh.intersect(&ray).is_some(),
                "axis {axis} sign {sign}: {d:?}"
            );
        }
    }
}

#[test]
fn degenerate_triangles_are_skipped_and_never_hit() {
    let good = [
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];
    let line = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
    let point = [Vec3::ONE; 3];
    let nan = [Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X, Vec3::Y];
    let bvh = Bvh::build(&[line, good, point, nan], BvhQuality::Medium);
    assert_eq!((bvh.len(), bvh.skipped()), (1, 3));
    let hit = bvh
        .intersect(&Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z, f32::INFINITY))
        .unwrap();
    assert_eq!(hit.triangle, 1, "indices refer to the input slice");
    assert!(
        intersect_triangle(
            &Ray::new(Vec3::new(0.5, 0.0, 1.0), -Vec3::Z, f32::INFINITY),
            line
        )
        .is_none()
    );
    assert!(
        Bvh::build(&[], BvhQuality::Medium)
            .intersect(&Ray::new(Vec3::ZERO, Vec3::X, 1.0))
            .is_none()
    );
}

/// Rays spawned from hit points with the error-bound offset never hit their own triangle
/// again, far from the origin too; spawned without it, some do (so the test can fail).
#[test]
fn offset_origins_prevent_self_intersection() {
    let base = Vec3::new(1.0e4, -3.0e3, 2.0e3);
    let tri = [
        base + Vec3::new(-1.0, -1.0, 0.1),
        base + Vec3::new(1.3, -0.8, -0.2),
        base + Vec3::new(0.1, 1.2, 0.05),
    ];
    let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize();
    let (mut naive_hits, mut offset_hits) = (0, 0);
    for (k, d) in directions(20_000, 17).into_iter().enumerate() {
        let target = base + 0.3 * Vec3::new((k % 5) as f32 * 0.1, (k % 7) as f32 * 0.08, 0.0);
        let incoming = Ray::new(target + 5.0 * n, -n, f32::INFINITY);
        let Some(h) = intersect_triangle(&incoming, tri) else {
            continue;
        };
        let p = incoming.at(h.hit_t());
        let out = if d.dot(n) > 0.0 { d } else { -d };
        if intersect_triangle(&Ray::new(p, out, f32::INFINITY), tri).is_some() {
            naive_hits += 1;
        }
        let b = h.barycentric;
        let exact = tri[0] * b[0] + tri[1] * b[1] + tri[2] * b[2];
        let error = triangle_point_error(tri, b);
        let origin = offset_ray_origin(exact, error, n, out);
        if intersect_triangle(&Ray::new(origin, out, f32::INFINITY), tri).is_some() {
            offset_hits += 1;
        }
    }
    assert_eq!(offset_hits, 0, "offset origins re-hit their own triangle");
    assert!(
        naive_hits > 0,
        "the naive origin never self-intersected: the test has no power here"
    );
}

/// A plane through the origin (y = 0, as a floor usually is) has a zero error bound
/// along its normal, so the spawn offset is nothing; rays leaving it must still not
/// re-hit it (they did at t ~ 3e-7, darkening 10% of a floor's direct light in places,
/// until the conservative t test of *PBR* 4th ed. §6.5.3).
#[test]
fn rays_leaving_a_plane_through_the_origin_do_not_rehit_it() {
    let floor = [
        Vec3::new(-4.0, 0.0, -4.0),
        Vec3::new(-4.0, 0.0, 4.0),
        Vec3::new(4.0, 0.0, 4.0),
    ];
    let n = Vec3::Y;
    let mut rehits = 0;
    for (k, d) in directions(20_000, 5).into_iter().enumerate() {
        let out = if d.y > 0.0 { d } else { -d };
        let target = Vec3::new(
            -0.8 + (k % 97) as f32 * 0.013,
            0.0,
            2.0 - (k % 89) as f32 * 0.017,
        );
        let eye = Vec3::new(0.1, 3.0, 0.2);
        let incoming = Ray::new(eye, (target - eye).normalize(), f32::INFINITY);
        let Some(h) = intersect_triangle(&incoming, floor) else {
            continue;
        };
        let b = h.barycentric;
        let p = floor[0] * b[0] + floor[1] * b[1] + floor[2] * b[2];
        let origin = offset_ray_origin(p, triangle_point_error(floor, b), n, out);
        if intersect_triangle(&Ray::new(origin, out, f32::INFINITY), floor).is_some() {
            rehits += 1;
        }
    }
    assert_eq!(rehits, 0, "rays re-hit the plane they leave");
}

trait HitT {
    fn hit_t(&self) -> f32;
}
impl HitT for prism_scene::geometry::TriangleHit {
    fn hit_t(&self) -> f32 {
        self.t
    }
}

proptest! {
    /// Any ray against any triangle: no panic, and a hit has finite t in range and
    /// barycentrics in [0, 1] summing to 1.
    #[test]
    fn intersection_is_total(
        v in prop::array::uniform9(prop_oneof![Just(0.0f32), Just(-0.0f32), Just(1e30f32), Just(f32::NAN), Just(f32::INFINITY), -10.0..10.0f32]),
        o in prop::array::uniform3(-10.0..10.0f32),
        d in prop::array::uniform3(prop_oneof![Just(0.0f32), Just(-0.0f32), Just(1e-30f32), -1.0..1.0f32]),
        t_max in prop_oneof![Just(f32::INFINITY), 0.0..100.0f32],
    ) {
        let tri = [Vec3::new(v[0], v[1], v[2]), Vec3::new(v[3], v[4], v[5]), Vec3::new(v[6], v[7], v[8])];
        let ray = Ray::new(Vec3::from(o), Vec3::from(d), t_max);
        if let Some(h) = intersect_triangle(&ray, tri) {
            prop_assert!(h.t.is_finite() && h.t > 0.0 && h.t < t_max);
            prop_assert!(h.barycentric.iter().all(|b| (-1e-6..=1.0 + 1e-6).contains(b)));
            prop_assert!((h.barycentric.iter().sum::<f32>() - 1.0).abs() < 1e-4);
        }
        let bvh = Bvh::build(&[tri], BvhQuality::Medium);
        let _ = bvh.intersect(&ray);
    }

    /// BVHs over triangles whose coordinates reach f32's limit (so that box areas, and
    /// every surface-area cost, overflow to infinity) build without panicking, and find
    /// the closest hit the scalar test finds among all triangles.
    #[test]
    fn bvh_over_extreme_coordinates_equals_brute_force(
        coords in prop::collection::vec(
            prop::array::uniform9(prop_oneof![
                Just(0.0f32), Just(-0.0f32), Just(3.0e38f32), Just(-3.0e38f32), Just(1e30f32),
                Just(f32::MIN_POSITIVE / 8.0), -2.0..2.0f32,
            ]),
            2..40,
        ),
        o in prop::array::uniform3(-3.0..3.0f32),
        d in prop::array::uniform3(-1.0..1.0f32),
    ) {
        let triangles: Vec<[Vec3; 3]> = coords
            .iter()
            .map(|v| [0, 1, 2].map(|k| Vec3::new(v[3 * k], v[3 * k + 1], v[3 * k + 2])))
            .collect();
        let bvh = Bvh::build(&triangles, BvhQuality::Medium);
        let ray = Ray::new(Vec3::from(o), Vec3::from(d), f32::INFINITY);
        let brute = triangles
            .iter()
            .filter_map(|t| intersect_triangle(&ray, *t).map(|h| h.t))
            .min_by(f32::total_cmp);
        prop_assert_eq!(bvh.intersect(&ray).map(|h| h.hit.hit_t()), brute);
        prop_assert_eq!(bvh.occluded(&ray), brute.is_some());
    }
}
