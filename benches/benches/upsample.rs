//! prism-upsample: one exact fit, a whole table fit (16^3 and 32^3), a table lookup
//! (trilinear and refined), and evaluation of a sigmoid polynomial per wavelength in
//! packages of 4 and 16 lanes.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use prism_spectrum::color::RgbSpaceId;
use prism_upsample::sigmoid::sigmoid_polynomial_lanes;
use prism_upsample::{CoefficientTable, FitContext};

fn colours() -> Vec<[f64; 3]> {
    let mut x = 0x2545_f491_4f6c_dd1du64;
    (0..1024)
        .map(|_| {
            std::array::from_fn(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 11) as f64 / (1u64 << 53) as f64
            })
        })
        .collect()
}

fn upsample(c: &mut Criterion) {
    let id = RgbSpaceId::Srgb;
    let context = FitContext::new(id.space(), &id.illuminant()).expect("valid");
    let rgb = colours();
    let mut i = 0usize;
    c.bench_function("exact fit (neutral start)", |b| {
        b.iter(|| {
            i = (i + 1) % rgb.len();
            black_box(context.fit(black_box(rgb[i]), [0.0; 3]))
        })
    });
    // A whole table: what a scene with textures pays at load (and `prism table fit`).
    let mut group = c.benchmark_group("table fit");
    group.sample_size(10);
    for res in [16usize, 32] {
        group.bench_function(BenchmarkId::from_parameter(res), |b| {
            b.iter(|| black_box(CoefficientTable::fit(&context, res, &|_| {}).expect("valid")))
        });
    }
    group.finish();
    let mut group = c.benchmark_group("table lookup");
    for res in [16usize, 32, 64] {
        let (table, _) = CoefficientTable::fit(&context, res, &|_| {}).expect("valid");
        // A pass over all the colours per iteration: the time per colour is then the
        // lookup's, without the harness's per-call overhead.
        group.throughput(Throughput::Elements(rgb.len() as u64));
        group.bench_function(BenchmarkId::new("trilinear", res), |b| {
            b.iter(|| {
                for colour in &rgb {
                    black_box(table.lookup(black_box(*colour)));
                }
            })
        });
        // The same colours as one batch (the same spectra, four colours' front ends at
        // once in SIMD lanes).
        group.bench_function(BenchmarkId::new("trilinear many", res), |b| {
            b.iter(|| black_box(table.lookup_many(black_box(&rgb))))
        });
        group.throughput(Throughput::Elements(1));
        group.bench_function(BenchmarkId::new("refined 1 step", res), |b| {
            b.iter(|| {
                i = (i + 1) % rgb.len();
                black_box(table.lookup_refined(&context, black_box(rgb[i]), 1))
            })
        });
    }
    group.finish();
    let coefficients = [6.98e-5f32, -6.48e-2, 13.8];
    let mut group = c.benchmark_group("sigmoid polynomial evaluation");
    let lanes4 = [450.0f32, 550.0, 650.0, 750.0];
    let lanes16: [f32; 16] = std::array::from_fn(|k| 360.0 + 29.0 * k as f32);
    group.throughput(Throughput::Elements(4));
    group.bench_function("4 wavelengths", |b| {
        b.iter(|| {
            black_box(sigmoid_polynomial_lanes(
                black_box(coefficients),
                black_box(&lanes4),
            ))
        })
    });
    group.throughput(Throughput::Elements(16));
    group.bench_function("16 wavelengths", |b| {
        b.iter(|| {
            black_box(sigmoid_polynomial_lanes(
                black_box(coefficients),
                black_box(&lanes16),
            ))
        })
    });
    group.finish();
}

criterion_group!(benches, upsample);
criterion_main!(benches);
