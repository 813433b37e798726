//! prism-scene: BVH build time and ray throughput on the bunny box
//! (scenes/cornell-bunny.gltf, 69 451 bunny triangles plus walls) and the Cornell box (36
//! triangles): closest hits of coherent rays (a 256 x 256 pinhole camera) and incoherent
//! ones (random points and directions inside the box), and shadow rays (random segments
//! inside the box); then what a path tracer traces from its first vertex, in pixel order:
//! bounce rays (from where the camera rays hit, in random directions) and shadow rays
//! (from there to random points of the ceiling light). And camera rays themselves: a
//! pinhole's against a thin lens's.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use prism_scene::geometry::{Bvh, BvhQuality, NodeLanes, Ray, triangle_normal};
use prism_scene::load::load_geometry;

fn triangles(scene: &str) -> Vec<[Vec3; 3]> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let bytes = std::fs::read(dir.join(scene)).expect("the scene is in scenes/");
    load_geometry(&bytes, &|uri| std::fs::read(dir.join(uri)), None)
        .expect("the scene loads")
        .triangles
}

/// Uniform numbers in [0, 1) from a xorshift generator seeded with `seed`.
fn uniform(mut s: u64) -> impl FnMut() -> f32 {
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f32 / (1u64 << 53) as f32
    }
}

/// Camera rays, random rays and random segments (shadow rays).
fn rays() -> (Vec<Ray>, Vec<Ray>, Vec<Ray>) {
    let n = 256;
    let eye = Vec3::new(0.0, 0.0, 3.9);
    let coherent = (0..n * n)
        .map(|i| {
            let (x, y) = (
                (i % n) as f32 / n as f32 - 0.5,
                (i / n) as f32 / n as f32 - 0.5,
            );
            Ray::new(eye, Vec3::new(x * 0.7, y * 0.7, -1.0), f32::INFINITY)
        })
        .collect();
    let mut unit = uniform(0x9e37_79b9_7f4a_7c15);
    let mut next = move || unit() * 2.0 - 1.0;
    let incoherent = (0..n * n)
        .map(|_| {
            let origin = Vec3::new(next(), next(), next()) * 0.95;
            Ray::new(origin, Vec3::new(next(), next(), next()), f32::INFINITY)
        })
        .collect();
    let segments = (0..n * n)
        .map(|_| {
            let from = Vec3::new(next(), next(), next()) * 0.95;
            let to = Vec3::new(next(), next(), next()) * 0.95;
            Ray::new(from, to - from, 1.0)
        })
        .collect();
    (coherent, incoherent, segments)
}

/// Bounce rays and shadow rays from where `camera` rays hit `bvh`, in their order.
fn first_vertex(bvh: &Bvh, camera: &[Ray]) -> (Vec<Ray>, Vec<Ray>) {
    let mut next = uniform(0x2545_f491_4f6c_dd1d);
    let mut bounces = Vec::new();
    let mut shadows = Vec::new();
    for ray in camera {
        let Some(hit) = bvh.intersect(ray) else {
            continue;
        };
        let n = triangle_normal(hit.vertices);
        let n = if n.dot(ray.direction) > 0.0 { -n } else { n };
        let p = ray.at(hit.hit.t) + n * 1e-4;
        let mut d = Vec3::new(next() * 2.0 - 1.0, next() * 2.0 - 1.0, next() * 2.0 - 1.0);
        if d.dot(n) < 0.0 {
            d = -d;
        }
        bounces.push(Ray::new(p, d, f32::INFINITY));
        // The ceiling light of both scenes spans x -0.24..0.23, z -0.22..0.16 at y 0.99.
        let light = Vec3::new(next() * 0.47 - 0.24, 0.98, next() * 0.38 - 0.22);
        shadows.push(Ray::new(p, light - p, 1.0 - 1e-4));
    }
    (bounces, shadows)
}

fn scene(c: &mut Criterion) {
    let bunny = triangles("cornell-bunny.gltf");
    let mut group = c.benchmark_group("bvh build (bunny box)");
    group.sample_size(10);
    group.bench_function("medium", |b| {
        b.iter(|| black_box(Bvh::build(black_box(&bunny), BvhQuality::Medium)))
    });
    group.finish();
    let (coherent, incoherent, segments) = rays();
    for (name, scene) in [
        ("bunny box", bunny),
        ("Cornell box", triangles("cornell-box.gltf")),
    ] {
        let mut bvh = Bvh::build(&scene, BvhQuality::Medium);
        let (bounces, shadows) = first_vertex(&bvh, &coherent);
        // Both node tests where the CPU has AVX (the renderer takes the widest).
        for lanes in [NodeLanes::Eight, NodeLanes::Four] {
            if !bvh.use_node_lanes(lanes) {
                continue;
            }
            let bvh = &bvh;
            let mut group = c.benchmark_group(format!("rays ({name}, {lanes:?} lanes)"));
            group.throughput(Throughput::Elements(coherent.len() as u64));
            group.sample_size(10);
            let closest = |rays: &[Ray]| rays.iter().filter(|r| bvh.intersect(r).is_some()).count();
            group.bench_function("closest, coherent 256x256", |b| {
                b.iter(|| closest(&coherent))
            });
            group.bench_function("closest, incoherent 65536", |b| {
                b.iter(|| closest(&incoherent))
            });
            group.bench_function("occluded, segments 65536", |b| {
                b.iter(|| segments.iter().filter(|r| bvh.occluded(r)).count())
            });
            group.bench_function("closest, bounces", |b| b.iter(|| closest(&bounces)));
            group.bench_function("occluded, shadows", |b| {
                b.iter(|| shadows.iter().filter(|r| bvh.occluded(r)).count())
            });
            group.finish();
        }
    }
}

/// Camera rays per film point: the pinhole's, and a thin lens's (a round and a six-bladed
/// aperture, focused at 3 units), each drawing its lens point from a uniform pair.
fn camera_rays(c: &mut Criterion) {
    use prism_scene::camera::{ApertureShape, ApertureSize, Camera, Focus, ThinLens};
    let camera = Camera {
        lens: Some(ThinLens::new(ApertureSize::FNumber(2.0))),
        system: None,
        ..Camera::look_at(Vec3::new(0.0, 0.0, 3.9), Vec3::ZERO, Vec3::Y, 0.68)
    };
    let mut u = uniform(7);
    let points: Vec<(glam::Vec2, glam::Vec2)> = (0..4096)
        .map(|_| (glam::Vec2::new(u(), u()), glam::Vec2::new(u(), u())))
        .collect();
    let mut group = c.benchmark_group("camera rays");
    group.throughput(Throughput::Elements(points.len() as u64));
    group.bench_function("pinhole", |b| {
        b.iter(|| {
            for (film, _) in &points {
                black_box(camera.generate_ray(*film, 1.0));
            }
        })
    });
    for (name, shape) in [
        ("thin lens, disk", ApertureShape::Disk),
        (
            "thin lens, 6 blades",
            ApertureShape::Polygon {
                blades: 6,
                rotation: 0.0,
            },
        ),
    ] {
        let focus = Focus {
            radius: 0.05,
            shape,
            distance: 3.0,
        };
        group.bench_function(name, |b| {
            b.iter(|| {
                for (film, lens) in &points {
                    black_box(camera.generate_ray_through(*film, 1.0, Some(&focus), *lens));
                }
            })
        });
    }
    // Lens systems, wide open and focused at 3 m on a full-frame film, at 550 nm: a ray that
    // the elements stop costs its tracing too (counted as a ray).
    for (name, file) in [
        ("double Gauss 50 mm", "dgauss.50mm.dat"),
        ("wide angle 28 mm", "wide.28mm.dat"),
    ] {
        let path = format!("{}/../scenes/lenses/{file}", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).expect("the repository's lenses");
        let system = prism_scene::camera::system::parse_prescription(&text).unwrap();
        let focused =
            prism_scene::camera::FocusedSystem::new(&system, 36.0, 1.0, None, 3000.0).unwrap();
        group.bench_function(name, |b| {
            b.iter(|| {
                for (film, lens) in &points {
                    black_box(camera.generate_ray_system(*film, &focused, *lens, 550.0));
                }
            })
        });
    }
    group.finish();
}

criterion_group!(benches, scene, camera_rays);
criterion_main!(benches);
