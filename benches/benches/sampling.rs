//! prism-sampling: ns per wavelength package for each sampler and package size, and ns per
//! 1D sample from tables of 1e2 and 1e5 bins.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use prism_sampling::distribution::{AliasTable, PiecewiseConstant1D};
use prism_sampling::stream::{IndependentStream, SampleStream, SobolLanes, SobolStream};
use prism_sampling::wavelength::{
    PackageScheme, WavelengthDistribution, WavelengthPackage, WavelengthRange,
};

fn y_bar(l: f64) -> f64 {
    (-0.5 * ((l - 555.0) / 45.0).powi(2)).exp()
}

fn samplers() -> Vec<(&'static str, WavelengthDistribution)> {
    let range = WavelengthRange::VISIBLE;
    vec![
        ("uniform", WavelengthDistribution::uniform(range)),
        ("visible", WavelengthDistribution::visible(range)),
        (
            "response",
            WavelengthDistribution::response(range, 470, &[&y_bar]).expect("valid"),
        ),
        (
            "spd",
            WavelengthDistribution::light_spd(range, 470, &[&|l| l / 1000.0], &y_bar, 0.1)
                .expect("valid"),
        ),
    ]
}

fn package<const N: usize>(c: &mut Criterion, group_name: &str) {
    let mut group = c.benchmark_group(group_name);
    group.throughput(Throughput::Elements(1));
    for (name, d) in samplers() {
        for scheme in [PackageScheme::HeroRotation, PackageScheme::Stratified] {
            let mut u = 0.123_f64;
            group.bench_function(BenchmarkId::new(name, format!("{scheme:?}")), |b| {
                b.iter(|| {
                    u = (u + 0.618_033_988_749_894_9).fract();
                    black_box(WavelengthPackage::<N>::sample(black_box(&d), u, scheme))
                })
            });
        }
    }
    group.finish();
}

fn packages(c: &mut Criterion) {
    package::<1>(c, "wavelength package C=1");
    package::<4>(c, "wavelength package C=4");
    package::<8>(c, "wavelength package C=8");
    package::<16>(c, "wavelength package C=16");
}

fn tables(c: &mut Criterion) {
    let mut group = c.benchmark_group("1D sample");
    group.throughput(Throughput::Elements(1));
    for bins in [100usize, 100_000] {
        let values: Vec<f64> = (0..bins)
            .map(|i| 1.0 + (i as f64 * 0.1).sin().abs())
            .collect();
        let table = PiecewiseConstant1D::new(&values, 0.0, 1.0).expect("valid");
        let alias = AliasTable::new(&values).expect("valid");
        let mut u = 0.5_f64;
        group.bench_function(BenchmarkId::new("piecewise constant", bins), |b| {
            b.iter(|| {
                u = (u + 0.618_033_988_749_894_9).fract();
                black_box(table.sample(u))
            })
        });
        group.bench_function(BenchmarkId::new("alias table", bins), |b| {
            b.iter(|| {
                u = (u + 0.618_033_988_749_894_9).fract();
                black_box(alias.sample(u))
            })
        });
    }
    group.finish();
}

fn streams(c: &mut Criterion) {
    let mut group = c.benchmark_group("stream 2D sample");
    group.throughput(Throughput::Elements(1));
    let mut i = 0u64;
    group.bench_function("independent", |b| {
        b.iter(|| {
            i += 1;
            black_box(IndependentStream::new(7, i >> 6, i & 63).next_2d())
        })
    });
    group.bench_function("sobol", |b| {
        b.iter(|| {
            i += 1;
            black_box(SobolStream::new(7, i >> 6, i & 63).next_2d())
        })
    });
    group.finish();
    // A bounce's draws (2D, 1D, 2D, 1D: light, lobe, BSDF, roulette) for sixteen
    // consecutive samples of a pixel: sixteen scalar streams, or lanes of them.
    let mut group = c.benchmark_group("stream bounce of 16 samples");
    group.throughput(Throughput::Elements(16));
    let mut pixel = 0u64;
    group.bench_function("16 scalar streams", |b| {
        b.iter(|| {
            pixel += 1;
            let mut acc = 0.0f32;
            for s in 0..16 {
                let mut stream = SobolStream::new(7, pixel, s);
                stream.set_dimension(3);
                acc +=
                    stream.next_2d().x + stream.next_1d() + stream.next_2d().y + stream.next_1d();
            }
            black_box(acc)
        })
    });
    fn lanes<const W: usize>(pixel: u64) -> f32 {
        let mut acc = 0.0f32;
        for first in (0..16).step_by(W) {
            let mut stream = SobolLanes::<W>::new(7, pixel, first);
            stream.set_dimension(3);
            let [x, _] = stream.next_2d();
            let a = stream.next_1d();
            let [_, y] = stream.next_2d();
            let b = stream.next_1d();
            acc += (x + a + y + b).0.iter().sum::<f32>();
        }
        acc
    }
    group.bench_function("lanes of 8", |b| {
        b.iter(|| {
            pixel += 1;
            black_box(lanes::<8>(pixel))
        })
    });
    group.bench_function("lanes of 16", |b| {
        b.iter(|| {
            pixel += 1;
            black_box(lanes::<16>(pixel))
        })
    });
    group.finish();
}

/// Sixteen light samples from sixteen points (a quad light's triangle overhead, as the
/// Cornell box's): sixteen scalar spherical-triangle warps, or the same warp over lanes of
/// 8 or 16, compiled for the build's baseline and, where the CPU has them, for AVX2 and
/// AVX-512 (the widths `native_width` reports).
fn light_warps(c: &mut Criterion) {
    use prism_sampling::glam::{Vec2, Vec3};
    use prism_sampling::lanes::real::{Reals, V3};
    use prism_sampling::warp::{spherical_triangle, spherical_triangle_sample};

    let v = [
        Vec3::new(-0.3, 1.0, -0.2),
        Vec3::new(0.3, 1.0, -0.2),
        Vec3::new(0.3, 1.0, 0.3),
    ];
    let points: Vec<Vec3> = (0..16)
        .map(|i| {
            Vec3::new(
                i as f32 * 0.1 - 0.8,
                -0.9 + 0.05 * i as f32,
                0.3 - 0.04 * i as f32,
            )
        })
        .collect();
    let us: Vec<Vec2> = (0..16)
        .map(|i| Vec2::new((i as f32 + 0.5) / 16.0, ((i * 7) % 16) as f32 / 16.0))
        .collect();
    #[inline(always)]
    fn lanes<const W: usize>(points: &[Vec3], us: &[Vec2], v: &[Vec3; 3]) -> f32 {
        let mut acc = 0.0;
        for first in (0..16).step_by(W) {
            let p = V3::<Reals<W>>::from_fn(|i| points[first + i]);
            let u = [
                Reals::from_fn(|i| us[first + i].x),
                Reals::from_fn(|i| us[first + i].y),
            ];
            let (d, pdf, _) = spherical_triangle_sample(p, v.map(|q| V3::from_fn(|_| q)), u);
            acc += (d.x + d.y + d.z + pdf).0.0.iter().sum::<f32>();
        }
        acc
    }
    let mut group = c.benchmark_group("spherical triangle for 16 points");
    group.throughput(Throughput::Elements(16));
    group.bench_function("16 scalar warps", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for (p, u) in points.iter().zip(&us) {
                if let Some(s) = spherical_triangle(black_box(*p), v, *u) {
                    acc += s.direction.x + s.direction.y + s.direction.z + s.pdf;
                }
            }
            black_box(acc)
        })
    });
    group.bench_function("lanes of 8", |b| {
        b.iter(|| black_box(lanes::<8>(black_box(&points), &us, &v)))
    });
    group.bench_function("lanes of 16", |b| {
        b.iter(|| black_box(lanes::<16>(black_box(&points), &us, &v)))
    });
    #[cfg(target_arch = "x86_64")]
    {
        #[target_feature(enable = "avx2")]
        fn avx2(points: &[Vec3], us: &[Vec2], v: &[Vec3; 3]) -> f32 {
            lanes::<8>(points, us, v)
        }
        #[target_feature(enable = "avx512f")]
        fn avx512(points: &[Vec3], us: &[Vec2], v: &[Vec3; 3]) -> f32 {
            lanes::<16>(points, us, v)
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2 (checked above).
            #[allow(unsafe_code)]
            group.bench_function("lanes of 8, AVX2", |b| {
                b.iter(|| black_box(unsafe { avx2(black_box(&points), &us, &v) }))
            });
        }
        if std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: the CPU has AVX-512F (checked above).
            #[allow(unsafe_code)]
            group.bench_function("lanes of 16, AVX-512", |b| {
                b.iter(|| black_box(unsafe { avx512(black_box(&points), &us, &v) }))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, packages, tables, streams, light_warps);
criterion_main!(benches);
