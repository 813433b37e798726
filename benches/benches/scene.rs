//! prism-scene: BVH build time and ray throughput (closest hit) on the bunny box
//! (scenes/cornell-bunny.gltf, 69 451 bunny triangles plus walls), with coherent rays (a
//! 256 x 256 pinhole camera) and incoherent ones (random points and directions inside the
//! box).

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use prism_scene::geometry::{Bvh, BvhQuality, Ray};
use prism_scene::load::load_geometry;

fn bunny() -> Vec<[Vec3; 3]> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let bytes = std::fs::read(dir.join("cornell-bunny.gltf")).expect("scenes/cornell-bunny.gltf");
    load_geometry(
        &bytes,
        &|uri| std::fs::read(dir.join(uri)).map_err(|e| e.to_string()),
        None,
    )
    .expect("the bunny box loads")
    .triangles
}

fn rays() -> (Vec<Ray>, Vec<Ray>) {
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
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f32 / (1u64 << 53) as f32 * 2.0 - 1.0
    };
    let incoherent = (0..n * n)
        .map(|_| {
            let origin = Vec3::new(next(), next(), next()) * 0.95;
            Ray::new(origin, Vec3::new(next(), next(), next()), f32::INFINITY)
        })
        .collect();
    (coherent, incoherent)
}

fn scene(c: &mut Criterion) {
    let triangles = bunny();
    let mut group = c.benchmark_group("bvh build (bunny box)");
    group.sample_size(10);
    group.bench_function("medium", |b| {
        b.iter(|| black_box(Bvh::build(black_box(&triangles), BvhQuality::Medium)))
    });
    group.finish();
    let bvh = Bvh::build(&triangles, BvhQuality::Medium);
    let (coherent, incoherent) = rays();
    let mut group = c.benchmark_group("closest hit (bunny box)");
    group.throughput(Throughput::Elements(coherent.len() as u64));
    group.sample_size(10);
    group.bench_function("coherent 256x256", |b| {
        b.iter(|| {
            coherent
                .iter()
                .filter(|r| bvh.intersect(r).is_some())
                .count()
        })
    });
    group.bench_function("incoherent 65536", |b| {
        b.iter(|| {
            incoherent
                .iter()
                .filter(|r| bvh.intersect(r).is_some())
                .count()
        })
    });
    group.finish();
}

criterion_group!(benches, scene);
criterion_main!(benches);
