//! Warps: chi-square tests of every warp against its density, on partitions whose exact
//! probabilities are known in closed form.

mod common;

use std::f32::consts::PI;

use common::{assert_chi_square, uniforms};
use glam::{Vec2, Vec3};
use prism_sampling::warp::*;

const SAMPLES: usize = 200_000;

fn u2(u: &mut impl FnMut() -> f64) -> Vec2 {
    Vec2::new(u() as f32, u() as f32)
}

/// Bins a direction by (t, phi) on a `n x n` grid where t is a coordinate in which the
/// warp's density is uniform.
fn grid_test(
    name: &str,
    n: usize,
    mut warp: impl FnMut(Vec2) -> (Vec3, f32),
    t_of: impl Fn(Vec3) -> f32,
) {
    let mut u = uniforms(name);
    let mut counts = vec![0u64; n * n];
    for _ in 0..SAMPLES {
        let (w, _) = warp(u2(&mut u));
        assert!((w.length() - 1.0).abs() < 1e-5, "{name}: not unit length");
        let t = t_of(w).clamp(0.0, 0.999_999);
        let phi = (w.y.atan2(w.x) / (2.0 * PI)).rem_euclid(1.0).min(0.999_999);
        counts[(t * n as f32) as usize * n + (phi * n as f32) as usize] += 1;
    }
    assert_chi_square(name, &counts, &vec![SAMPLES as f64 / (n * n) as f64; n * n]);
}

#[test]
fn cosine_hemisphere_is_cosine_distributed() {
    // Under cos/pi the projected radius sin^2(theta) = 1 - cos^2 is uniform in [0, 1].
    grid_test(
        "cosine hemisphere",
        12,
        |u| {
            let w = cosine_hemisphere(u);
            (w, cosine_hemisphere_pdf(w))
        },
        |w| 1.0 - w.z * w.z,
    );
    // The pdf integrates to 1: sum over a fine grid of the hemisphere in (cos, phi).
    let n = 400;
    let integral: f32 = (0..n)
        .map(|i| {
            let z = (i as f32 + 0.5) / n as f32;
            cosine_hemisphere_pdf(Vec3::new((1.0 - z * z).sqrt(), 0.0, z)) * 2.0 * PI / n as f32
        })
        .sum();
    assert!((integral - 1.0).abs() < 1e-4, "{integral}");
}

#[test]
fn uniform_sphere_is_uniform() {
    grid_test(
        "uniform sphere",
        12,
        |u| (uniform_sphere(u), uniform_sphere_pdf()),
        |w| (1.0 - w.z) / 2.0,
    );
    assert!((uniform_sphere_pdf() * 4.0 * PI - 1.0).abs() < 1e-6);
}

#[test]
fn uniform_cone_is_uniform_in_the_cone() {
    for cos_max in [0.9f32, 0.2, -0.5] {
        grid_test(
            &format!("uniform cone {cos_max}"),
            10,
            |u| (uniform_cone(u, cos_max), uniform_cone_pdf(cos_max)),
            |w| (1.0 - w.z) / (1.0 - cos_max),
        );
        assert!((uniform_cone_pdf(cos_max) * 2.0 * PI * (1.0 - cos_max) - 1.0).abs() < 1e-5);
    }
    assert!(
        uniform_cone_pdf(1.0).is_infinite(),
        "a zero-width cone is a delta"
    );
}

#[test]
fn concentric_disk_is_uniform() {
    // Uniform on the disk: r^2 and the angle are independent and uniform.
    let n = 12;
    let mut u = uniforms("concentric disk");
    let mut counts = vec![0u64; n * n];
    for _ in 0..SAMPLES {
        let d = uniform_disk_concentric(u2(&mut u));
        let r2 = d.length_squared().min(0.999_999);
        let phi = (d.y.atan2(d.x) / (2.0 * PI)).rem_euclid(1.0).min(0.999_999);
        counts[(r2 * n as f32) as usize * n + (phi * n as f32) as usize] += 1;
    }
    assert_chi_square(
        "concentric disk",
        &counts,
        &vec![SAMPLES as f64 / (n * n) as f64; n * n],
    );
}

#[test]
fn uniform_triangle_is_uniform() {
    // n^2 congruent sub-triangles of the barycentric simplex, each of probability 1/n^2.
    let n = 8;
    let mut u = uniforms("uniform triangle");
    let mut counts = vec![0u64; n * n * 2];
    for _ in 0..SAMPLES {
        let [b0, b1, b2] = uniform_triangle(u2(&mut u));
        assert!(b0 >= 0.0 && b1 >= 0.0 && b2 >= 0.0 && (b0 + b1 + b2 - 1.0).abs() < 1e-5);
        let (i, j, k) = (
            (b0 * n as f32) as usize,
            (b1 * n as f32) as usize,
            (b2 * n as f32) as usize,
        );
        let up = i + j + k == n - 1;
        counts[(i.min(n - 1) * n + j.min(n - 1)) * 2 + usize::from(up)] += 1;
    }
    // Of the 2 n^2 (i, j, up) slots, n(n+1)/2 "up" and n(n-1)/2 "down" triangles exist.
    let expected: Vec<f64> = (0..n * n * 2)
        .map(|slot| {
            let (cell, up) = (slot / 2, slot % 2 == 1);
            let (i, j) = (cell / n, cell % n);
            let exists = if up { i + j < n } else { i + j + 1 < n };
            if exists {
                SAMPLES as f64 / (n * n) as f64
            } else {
                0.0
            }
        })
        .collect();
    assert_chi_square("uniform triangle", &counts, &expected);
    assert_eq!(uniform_triangle_pdf(Vec3::ZERO, Vec3::X, Vec3::Y), 2.0);
    assert_eq!(
        uniform_triangle_pdf(Vec3::ZERO, Vec3::X, Vec3::X * 2.0),
        0.0
    );
}

/// Midpoint subdivision of a triangle into 4^levels sub-triangles.
fn subdivide(t: [Vec3; 3], levels: u32) -> Vec<[Vec3; 3]> {
    if levels == 0 {
        return vec![t];
    }
    let [a, b, c] = t;
    let (ab, bc, ca) = ((a + b) / 2.0, (b + c) / 2.0, (c + a) / 2.0);
    [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
        .into_iter()
        .flat_map(|s| subdivide(s, levels - 1))
        .collect()
}

/// Whether the ray from `p` along `d` crosses triangle `t` (Moller-Trumbore, f64).
fn hits(p: Vec3, d: Vec3, t: [Vec3; 3]) -> bool {
    let (p, d) = (p.as_dvec3(), d.as_dvec3());
    let [a, b, c] = t.map(|v| v.as_dvec3());
    let (e1, e2) = (b - a, c - a);
    let q = d.cross(e2);
    let det = e1.dot(q);
    if det.abs() < 1e-15 {
        return false;
    }
    let s = p - a;
    let u = s.dot(q) / det;
    let r = s.cross(e1);
    let v = d.dot(r) / det;
    let t = e2.dot(r) / det;
    // Directions are f32 (relative error ~1e-7, amplified by distance over size): allow
    // 1e-4 in a level-2 sub-triangle's barycentrics (2.5e-5 of the whole triangle).
    u >= -1e-4 && v >= -1e-4 && u + v <= 1.0 + 1e-4 && t > 0.0
}

#[test]
fn spherical_triangle_is_uniform_in_solid_angle() {
    let cases: [(&str, Vec3, [Vec3; 3]); 3] = [
        (
            "near",
            Vec3::new(0.1, 0.2, 0.0),
            [
                Vec3::new(-1.0, -1.0, 1.0),
                Vec3::new(1.5, -0.5, 1.2),
                Vec3::new(0.0, 1.0, 0.8),
            ],
        ),
        (
            "far",
            Vec3::ZERO,
            [
                Vec3::new(9.0, 0.0, 10.0),
                Vec3::new(11.0, 0.5, 10.0),
                Vec3::new(10.0, 2.0, 10.5),
            ],
        ),
        (
            "grazing",
            Vec3::ZERO,
            [
                Vec3::new(-1.0, 0.05, 1.0),
                Vec3::new(1.0, 0.05, 1.0),
                Vec3::new(0.0, 3.0, 0.2),
            ],
        ),
    ];
    for (name, p, tri) in cases {
        let parts = subdivide(tri, 2);
        let total = spherical_triangle_solid_angle(p, tri);
        let mut u = uniforms(name);
        let mut counts = vec![0u64; parts.len()];
        let mut missed = 0;
        for _ in 0..SAMPLES / 4 {
            let s = spherical_triangle(p, tri, u2(&mut u)).expect("non-degenerate");
            assert!(
                (s.pdf * total - 1.0).abs() < 2e-3,
                "{name}: pdf {} vs 1/{total}",
                s.pdf
            );
            match parts.iter().position(|&t| hits(p, s.direction, t)) {
                Some(i) => counts[i] += 1,
                None => missed += 1,
            }
        }
        assert_eq!(missed, 0, "{name}: {missed} directions missed the triangle");
        let omegas: Vec<f64> = parts
            .iter()
            .map(|&t| f64::from(spherical_triangle_solid_angle(p, t)))
            .collect();
        let sum: f64 = omegas.iter().sum();
        assert!(
            (sum / f64::from(total) - 1.0).abs() < 1e-3,
            "{name}: parts do not add up"
        );
        let hits_total = (SAMPLES / 4 - missed) as f64;
        let expected: Vec<f64> = omegas.iter().map(|o| o / sum * hits_total).collect();
        assert_chi_square(&format!("spherical triangle {name}"), &counts, &expected);
    }
}

#[test]
fn degenerate_spherical_triangles_are_refused() {
    let p = Vec3::ZERO;
    // p in the triangle's plane, a collinear triangle, a vertex at p.
    assert!(spherical_triangle(p, [Vec3::X, Vec3::Y, -Vec3::X], Vec2::splat(0.5)).is_none());
    assert!(
        spherical_triangle(p, [Vec3::Z, Vec3::Z * 2.0, Vec3::Z * 3.0], Vec2::splat(0.5)).is_none()
    );
    assert!(
        spherical_triangle(
            p,
            [Vec3::ZERO, Vec3::X + Vec3::Z, Vec3::Y + Vec3::Z],
            Vec2::splat(0.5)
        )
        .is_none()
    );
}
