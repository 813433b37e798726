//! prism-integrator: whole-render throughput in paths per second on the Cornell box and the
//! bunny box at a small size (64 x 64, 4 spp, unbounded depth, C = 8, visible sampler), on
//! one thread so that the number is per core, unsplit. The Mitsuba comparison is
//! `benches/peer/compare.py` (whole renders, both renderers in one run).

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use prism_integrator::{RenderSettings, Splits, render};
use prism_scene::load::load_geometry;
use prism_scene::world::Scene;

fn scene(name: &str) -> Scene {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let bytes = std::fs::read(dir.join(name)).expect("the scene file");
    let loaded =
        load_geometry(&bytes, &|uri| std::fs::read(dir.join(uri)), None).expect("the scene loads");
    Scene::from_loaded(loaded, &Default::default()).expect("the scene builds")
}

fn integrator(c: &mut Criterion) {
    let settings = RenderSettings::default()
        .width(64)
        .height(64)
        .samples(0..4)
        .threads(1)
        // Paths per second of the tracer itself: the automatic choice's pilot would be
        // most of a render this small.
        .splits(Splits::Fixed(1));
    let paths = u64::from(settings.width * settings.height) * 4;
    let mut group = c.benchmark_group("render 64x64x4 one thread");
    group.throughput(Throughput::Elements(paths));
    group.sample_size(20);
    for (label, file) in [
        ("cornell box", "cornell-box.gltf"),
        ("bunny box", "cornell-bunny.gltf"),
    ] {
        let s = scene(file);
        let mut seed = 0;
        group.bench_function(label, |b| {
            b.iter(|| {
                seed += 1;
                black_box(render(&s, &settings.clone().seed(seed)))
            })
        });
    }
    group.finish();
}

criterion_group!(benches, integrator);
criterion_main!(benches);
