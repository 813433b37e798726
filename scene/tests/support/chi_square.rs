//! The chi-square harness of the BSDF tests: sampled directions binned on a (cos theta,
//! phi) grid of the sphere against the density integrated over each cell.

use glam::{Vec2, Vec3};
use prism_sampling::stats::chi_square_test;
use prism_sampling::stream::{IndependentStream, SampleStream};

/// One significance level for the crate's BSDF chi-square tests (Bonferroni over at most
/// 40 tests, family-wise 1%).
pub const ALPHA: f64 = 0.01 / 40.0;

/// Chi-square of sampled directions against the density integrated over a (cos theta,
/// phi) grid of the sphere, the density integrated numerically per cell.
pub fn chi_square_directions(
    name: &str,
    sample: impl Fn(Vec2) -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f64,
) {
    let p = chi_square_p_value(name, sample, pdf);
    assert!(p > ALPHA, "{name}: p = {p:.2e}");
}

pub fn chi_square_p_value(
    name: &str,
    sample: impl Fn(Vec2) -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f64,
) -> f64 {
    let (nt, np, samples) = (20usize, 40usize, 200_000usize);
    let mut stream = IndependentStream::new(name.len() as u64, 0, 0);
    let mut counts = vec![0u64; nt * np];
    let mut valid = 0u64;
    for _ in 0..samples {
        if let Some(w) = sample(stream.next_2d()) {
            let t = (((w.z + 1.0) / 2.0 * nt as f32) as usize).min(nt - 1);
            let p = ((w.y.atan2(w.x) / std::f32::consts::TAU).rem_euclid(1.0) * np as f32) as usize;
            counts[t * np + p.min(np - 1)] += 1;
            valid += 1;
        }
    }
    // Expected counts: integrate the pdf over each cell by a q x q midpoint rule, fine
    // enough for peaked lobes (GGX at alpha 0.1 is ~0.1 rad wide, a cell ~0.16 rad).
    const Q: usize = 24;
    let expected: Vec<f64> = (0..nt * np)
        .map(|cell| {
            let (ti, pi) = (cell / np, cell % np);
            let mut mass = 0.0;
            for a in 0..Q {
                for b in 0..Q {
                    let z = -1.0 + 2.0 * (ti as f64 + (a as f64 + 0.5) / Q as f64) / nt as f64;
                    let phi = std::f64::consts::TAU * (pi as f64 + (b as f64 + 0.5) / Q as f64)
                        / np as f64;
                    let r = (1.0 - z * z).max(0.0).sqrt();
                    let w = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
                    mass += pdf(w);
                }
            }
            mass / (Q * Q) as f64
                * (2.0 / nt as f64)
                * (std::f64::consts::TAU / np as f64)
                * samples as f64
        })
        .collect();
    let total: f64 = expected.iter().sum();
    assert!(
        (total / samples as f64 - valid as f64 / samples as f64).abs() < 0.01,
        "{name}: pdf mass {total} vs valid samples {valid}"
    );
    chi_square_test(&counts, &expected).p_value
}
