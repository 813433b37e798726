//! Thin lenses: the aperture's samplers against their shapes (chi-square), camera rays
//! through the lens and connections to it inverse to each other, and no NaN at the
//! extremes (the scene format's lenses: `lens_format.rs`).

use std::f32::consts::PI;

use glam::{Mat4, Vec2, Vec3};
use prism_sampling::stats::chi_square_test;
use prism_sampling::stream::{IndependentStream, SampleStream};
use prism_scene::camera::{
    ApertureImage, ApertureShape, ApertureSize, Camera, Focus, Projection, ThinLens,
};
use proptest::prelude::*;

const SHAPES: [ApertureShape; 4] = [
    ApertureShape::Disk,
    ApertureShape::Polygon {
        blades: 3,
        rotation: 0.3,
    },
    ApertureShape::Polygon {
        blades: 6,
        rotation: 0.0,
    },
    ApertureShape::Polygon {
        blades: 9,
        rotation: -1.0,
    },
];

/// The share of each of `bins` x `bins` cells of [-1, 1]^2 the shape covers, by counting
/// 64 x 64 points per cell.
fn cell_areas(shape: &ApertureShape, bins: usize) -> Vec<f64> {
    const SUB: usize = 64;
    let cell = 2.0 / bins as f32;
    let mut areas = vec![0.0; bins * bins];
    for (i, area) in areas.iter_mut().enumerate() {
        let (cx, cy) = ((i % bins) as f32, (i / bins) as f32);
        let mut inside = 0;
        for s in 0..SUB * SUB {
            let p = Vec2::new(
                -1.0 + cell * (cx + ((s % SUB) as f32 + 0.5) / SUB as f32),
                -1.0 + cell * (cy + ((s / SUB) as f32 + 0.5) / SUB as f32),
            );
            inside += usize::from(shape.contains(p));
        }
        *area = inside as f64 / (SUB * SUB) as f64 * f64::from(cell * cell);
    }
    areas
}

fn histogram(sample: impl Fn(Vec2) -> Vec2, bins: usize, n: usize) -> Vec<u64> {
    let mut stream = IndependentStream::new(11, 0, 0);
    let mut counts = vec![0u64; bins * bins];
    for _ in 0..n {
        let p = sample(stream.next_2d());
        let cell = |v: f32| (((v + 1.0) * 0.5 * bins as f32) as usize).min(bins - 1);
        counts[cell(p.y) * bins + cell(p.x)] += 1;
    }
    counts
}

#[test]
fn apertures_are_sampled_uniformly_over_their_shapes() {
    let (bins, n) = (16, 200_000);
    for shape in SHAPES {
        let areas = cell_areas(&shape, bins);
        let total: f64 = areas.iter().sum();
        assert!(
            (total - f64::from(shape.area())).abs() < 2e-3 * total,
            "{shape:?}: area {} against {total}",
            shape.area()
        );
        let expected: Vec<f64> = areas.iter().map(|a| a / total * n as f64).collect();
        let counts = histogram(|u| shape.sample(u), bins, n);
        let p = chi_square_test(&counts, &expected).p_value;
        assert!(p > 1e-3, "{shape:?}: p = {p:.2e}");
    }
}

/// An aperture image: a 24 x 24 grid of transmissions, graded across it, with a hole and
/// a dark border, drawn in proportion to its transmission (16 bins that do not align with
/// its pixels), with a density that integrates to one.
#[test]
fn aperture_images_are_sampled_by_their_transmission() {
    let side = 24usize;
    let values: Vec<f32> = (0..side * side)
        .map(|k| {
            let (i, j) = (k % side, k / side);
            let (x, y) = (i as f32 / side as f32, j as f32 / side as f32);
            if i == 0 || j == side - 1 || ((x - 0.6).powi(2) + (y - 0.4).powi(2)) < 0.02 {
                0.0
            } else {
                0.2 + 0.8 * x * (1.0 - 0.5 * y)
            }
        })
        .collect();
    let image = ApertureImage::new(side, side, values).unwrap();
    let shape = ApertureShape::Image(std::sync::Arc::new(image.clone()));
    let (bins, n, sub) = (16usize, 400_000usize, 48usize);
    let cell = 2.0 / bins as f32;
    let mass: Vec<f64> = (0..bins * bins)
        .map(|c| {
            let (cx, cy) = ((c % bins) as f32, (c / bins) as f32);
            (0..sub * sub)
                .map(|s| {
                    let p = Vec2::new(
                        -1.0 + cell * (cx + ((s % sub) as f32 + 0.5) / sub as f32),
                        -1.0 + cell * (cy + ((s / sub) as f32 + 0.5) / sub as f32),
                    );
                    f64::from(image.transmission(p))
                })
                .sum::<f64>()
        })
        .collect();
    let total: f64 = mass.iter().sum();
    let expected: Vec<f64> = mass.iter().map(|m| m / total * n as f64).collect();
    let counts = histogram(|u| shape.sample(u), bins, n);
    let p = chi_square_test(&counts, &expected).p_value;
    assert!(p > 1e-3, "aperture image: p = {p:.2e}");
    // Drawn upside down (rows read from the bottom), it fails.
    let flipped = histogram(|u| shape.sample(u) * Vec2::new(1.0, -1.0), bins, n);
    assert!(chi_square_test(&flipped, &expected).p_value < 1e-6);
    // Its density integrates to one over the square.
    let grid = 200;
    let integral: f64 = (0..grid * grid)
        .map(|k| {
            let p = Vec2::new(
                -1.0 + 2.0 * ((k % grid) as f32 + 0.5) / grid as f32,
                -1.0 + 2.0 * ((k / grid) as f32 + 0.5) / grid as f32,
            );
            f64::from(image.pdf(p))
        })
        .sum::<f64>()
        * 4.0
        / (grid * grid) as f64;
    assert!((integral - 1.0).abs() < 0.01, "{integral}");
    // Black, ill-sized and out-of-range images are errors.
    assert!(ApertureImage::new(2, 2, vec![0.0; 4]).is_err());
    assert!(ApertureImage::new(2, 3, vec![1.0; 4]).is_err());
    assert!(ApertureImage::new(2, 2, vec![1.0, 2.0, 0.5, f32::NAN]).is_err());
}

/// The test has power: a disk drawn at radius u (not sqrt u), denser at the centre, fails.
#[test]
fn chi_square_rejects_a_disk_denser_at_its_centre() {
    let (bins, n) = (16, 200_000);
    let areas = cell_areas(&ApertureShape::Disk, bins);
    let total: f64 = areas.iter().sum();
    let expected: Vec<f64> = areas.iter().map(|a| a / total * n as f64).collect();
    let counts = histogram(
        |u| {
            let a = 2.0 * PI * u.y;
            u.x * Vec2::new(a.cos(), a.sin())
        },
        bins,
        n,
    );
    assert!(chi_square_test(&counts, &expected).p_value < 1e-6);
}

fn camera() -> Camera {
    Camera {
        name: "lens".into(),
        to_world: Mat4::from_translation(Vec3::new(0.3, -0.2, 5.0)) * Mat4::from_rotation_y(0.4),
        projection: Projection::Perspective { yfov: 0.6 },
        aspect_ratio: None,
        lens: Some(ThinLens::new(ApertureSize::Radius(0.1))),
        system: None,
    }
}

/// A ray through film point f from lens point u, followed to any point, projects back to
/// f through the same lens point: what light paths rely on to land where camera rays
/// leave.
#[test]
fn projection_through_the_lens_inverts_its_rays() {
    let camera = camera();
    for distance in [2.0, 5.0, f32::INFINITY] {
        let focus = Focus {
            radius: 0.1,
            shape: ApertureShape::Polygon {
                blades: 5,
                rotation: 0.2,
            },
            distance,
        };
        let mut stream = IndependentStream::new(3, 0, 0);
        for _ in 0..1000 {
            let (film, u) = (stream.next_2d(), stream.next_2d());
            let ray = camera.generate_ray_through(film, 1.5, Some(&focus), u);
            let t = 0.5 + 10.0 * stream.next_1d();
            let seen = camera
                .project_through(ray.origin + t * ray.direction, 1.5, Some(&focus), u)
                .expect("the point is in view");
            assert!(
                (seen.film - film).length() < 1e-3,
                "{film} -> {}",
                seen.film
            );
            assert!((seen.distance - t * ray.direction.length()).abs() < 1e-3 * t);
        }
    }
}

/// The aperture's radius from an f-number is f / (2 N), f from the field of view and
/// the sensor: a 36 mm sensor behind a 39.6 degree horizontal view is a 50 mm lens.
#[test]
fn an_f_number_means_what_it_means_on_a_camera() {
    let lens = ThinLens::new(ApertureSize::FNumber(2.0));
    let hfov = 2.0 * (18.0f32 / 50.0).atan();
    let aspect = 1.5;
    let yfov = 2.0 * ((0.5 * hfov).tan() / aspect).atan();
    assert!((lens.focal_length(yfov, aspect) - 0.050).abs() < 1e-6);
    assert!((lens.radius(yfov, aspect) - 0.0125).abs() < 1e-6);
}

proptest! {
    /// Rays and connections at the extremes (film corners, the aperture's rim, tiny and
    /// huge apertures and focus distances) are finite or refused, never NaN.
    #[test]
    fn lens_rays_stay_finite(
        film in (0.0f32..=1.0, 0.0f32..=1.0),
        u in (0.0f32..=1.0, 0.0f32..=1.0),
        radius in prop::sample::select(vec![1e-8f32, 1e-3, 0.1, 10.0, 1e6]),
        distance in prop::sample::select(vec![1e-6f32, 0.01, 3.0, 1e8, f32::INFINITY]),
        blades in 0u32..10,
        point in (-1e3f32..1e3, -1e3f32..1e3, -1e3f32..1e3),
    ) {
        let camera = camera();
        let shape = if blades < 3 { ApertureShape::Disk } else { ApertureShape::Polygon { blades, rotation: 0.1 } };
        let focus = Focus { radius, shape, distance };
        let (film, u) = (Vec2::new(film.0, film.1), Vec2::new(u.0, u.1));
        let ray = camera.generate_ray_through(film, 1.0, Some(&focus), u);
        prop_assert!(ray.origin.is_finite() && ray.direction.is_finite());
        prop_assert!((ray.direction.length() - 1.0).abs() < 1e-3);
        if let Some(seen) = camera.project_through(Vec3::new(point.0, point.1, point.2), 1.0, Some(&focus), u) {
            prop_assert!(seen.film.is_finite() && seen.direction.is_finite());
            prop_assert!(seen.distance.is_finite() && seen.importance.is_finite() && seen.importance > 0.0);
        }
    }
}
