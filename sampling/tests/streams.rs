//! Sample streams: determinism, uniformity, and stratification of the Sobol stream.

mod common;

use common::assert_chi_square;
use glam::Vec2;
use prism_sampling::stream::{IndependentStream, SampleStream, SobolStream};

/// The values depend only on (seed, pixel, sample, dimension): the same sample drawn in
/// any order, or after skipping dimensions, is the same.
#[test]
fn streams_are_pure_functions_of_their_coordinates() {
    for kind in 0..2 {
        let make = |seed, pixel, sample| -> Box<dyn SampleStream> {
            if kind == 0 {
                Box::new(IndependentStream::new(seed, pixel, sample))
            } else {
                Box::new(SobolStream::new(seed, pixel, sample))
            }
        };
        let take =
            |mut s: Box<dyn SampleStream>| [s.next_1d(), s.next_1d(), s.next_2d().x, s.next_1d()];
        let forward: Vec<_> = (0..64).map(|i| take(make(7, 1234, i))).collect();
        let backward: Vec<_> = (0..64).rev().map(|i| take(make(7, 1234, i))).collect();
        assert!(
            forward.iter().eq(backward.iter().rev()),
            "kind {kind}: order matters"
        );
        assert_ne!(
            take(make(7, 1234, 3)),
            take(make(8, 1234, 3)),
            "kind {kind}: seed ignored"
        );
        assert_ne!(
            take(make(7, 1234, 3)),
            take(make(7, 1235, 3)),
            "kind {kind}: pixel ignored"
        );
        let all = forward.iter().flatten().copied().collect::<Vec<f32>>();
        assert!(all.iter().all(|v| (0.0..1.0).contains(v)));
    }
    let mut a = IndependentStream::new(1, 2, 3);
    let mut b = IndependentStream::new(1, 2, 3);
    a.next_1d();
    a.next_1d();
    b.set_dimension(2);
    assert_eq!(a.next_1d(), b.next_1d());
}

/// Uniformity in 2D over many pixels and samples, for each stream and a few dimensions.
#[test]
fn streams_are_uniform() {
    let n = 16;
    for kind in ["independent", "sobol"] {
        for dimension in [0u64, 2, 10] {
            let mut counts = vec![0u64; n * n];
            let total = 100_000;
            for k in 0..total as u64 {
                let (pixel, sample) = (k / 64, k % 64);
                let p = if kind == "independent" {
                    let mut s = IndependentStream::new(99, pixel, sample);
                    s.set_dimension(dimension);
                    s.next_2d()
                } else {
                    let mut s = SobolStream::new(99, pixel, sample);
                    s.set_dimension(dimension);
                    s.next_2d()
                };
                counts[(p.y * n as f32) as usize * n + (p.x * n as f32) as usize] += 1;
            }
            assert_chi_square(
                &format!("{kind} stream dim {dimension}"),
                &counts,
                &vec![total as f64 / (n * n) as f64; n * n],
            );
        }
    }
}

/// Any power-of-two prefix of a pixel's Sobol samples is a (0, m, 2)-net: each elementary
/// interval of area 2^-m, of every shape 2^-a x 2^-(m-a), holds exactly one point. This is
/// what makes Sobol converge faster than independent sampling, and what scrambling and
/// index shuffling must preserve.
#[test]
fn sobol_prefixes_are_stratified_nets() {
    for pixel in [0u64, 17, 123_456] {
        for dimension in [0u64, 2, 6] {
            for m in [2u32, 5, 8] {
                let count = 1usize << m;
                let points: Vec<Vec2> = (0..count as u64)
                    .map(|i| {
                        let mut s = SobolStream::new(42, pixel, i);
                        s.set_dimension(dimension);
                        s.next_2d()
                    })
                    .collect();
                for a in 0..=m {
                    let (nx, ny) = (1usize << a, 1usize << (m - a));
                    let mut seen = vec![0u32; count];
                    for p in &points {
                        let cell = (p.y * ny as f32) as usize * nx + (p.x * nx as f32) as usize;
                        seen[cell] += 1;
                    }
                    assert!(
                        seen.iter().all(|&c| c == 1),
                        "pixel {pixel} dim {dimension} m {m}: intervals {nx}x{ny} not stratified"
                    );
                }
            }
        }
    }
}

/// Different dimension pairs of one pixel are decorrelated (the padding works): the
/// points of pair 0 and pair 1 are not the same set.
#[test]
fn sobol_dimension_pairs_differ() {
    let pair = |d: u64| -> Vec<(u32, u32)> {
        (0..16)
            .map(|i| {
                let mut s = SobolStream::new(3, 5, i);
                s.set_dimension(d);
                let p = s.next_2d();
                ((p.x * 16.0) as u32, (p.y * 16.0) as u32)
            })
            .collect()
    };
    assert_ne!(pair(0), pair(2));
}
