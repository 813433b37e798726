//! Tabulated distributions: chi-square tests, normalization, sample/pdf agreement and
//! inversion.

mod common;

use common::{assert_chi_square, uniforms};
use prism_sampling::SamplingError;
use prism_sampling::distribution::{
    AliasTable, PiecewiseConstant1D, PiecewiseConstant2D, PiecewiseLinear1D,
};

const SAMPLES: usize = 200_000;

/// A bumpy function with zero runs, tiny values and large ones.
fn test_values(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| match i % 7 {
            0 | 1 => 0.0,
            2 => 1e-3,
            _ => 1.0 + (i as f64 * 0.37).sin().abs() * 10.0,
        })
        .collect()
}

#[test]
fn piecewise_constant_matches_its_bins() {
    let values = test_values(64);
    let d = PiecewiseConstant1D::new(&values, -2.0, 3.0).unwrap();
    let mut u = uniforms("pc1d");
    let mut counts = vec![0u64; 64];
    for _ in 0..SAMPLES {
        let s = d.sample(u());
        assert!(values[s.bin] > 0.0, "a zero bin was sampled");
        assert!(
            (s.pdf - d.pdf(s.value)).abs() <= 1e-12 * s.pdf,
            "sample and pdf disagree"
        );
        counts[s.bin] += 1;
    }
    let total: f64 = values.iter().sum();
    let expected: Vec<f64> = values.iter().map(|v| v / total * SAMPLES as f64).collect();
    assert_chi_square("piecewise constant 1D", &counts, &expected);
}

#[test]
fn piecewise_constant_normalizes_and_inverts() {
    let values = test_values(50);
    let d = PiecewiseConstant1D::new(&values, 10.0, 20.0).unwrap();
    let width = 10.0 / 50.0;
    let integral: f64 = (0..50)
        .map(|i| d.pdf(10.0 + (i as f64 + 0.5) * width) * width)
        .sum();
    assert!((integral - 1.0).abs() < 1e-12);
    let mut u = uniforms("pc1d-invert");
    for _ in 0..10_000 {
        let x = u();
        let s = d.sample(x);
        assert!(
            (d.invert(s.value) - x).abs() < 1e-9,
            "invert(sample({x})) = {}",
            d.invert(s.value)
        );
    }
}

#[test]
fn degenerate_inputs_are_errors() {
    assert_eq!(
        PiecewiseConstant1D::new(&[], 0.0, 1.0),
        Err(SamplingError::Empty)
    );
    assert_eq!(
        PiecewiseConstant1D::new(&[0.0, 0.0], 0.0, 1.0),
        Err(SamplingError::AllZero)
    );
    assert!(matches!(
        PiecewiseConstant1D::new(&[1.0, f64::NAN], 0.0, 1.0),
        Err(SamplingError::InvalidValue { index: 1, .. })
    ));
    assert!(PiecewiseConstant1D::new(&[1.0, -1.0], 0.0, 1.0).is_err());
    assert!(PiecewiseConstant1D::new(&[1.0, f64::INFINITY], 0.0, 1.0).is_err());
    assert!(PiecewiseConstant1D::new(&[1.0], 1.0, 1.0).is_err());
    assert!(
        PiecewiseConstant1D::new(&[f64::MAX, f64::MAX], 0.0, 10.0).is_err(),
        "overflowing integral"
    );
    assert!(AliasTable::new(&[0.0]).is_err());
    assert!(PiecewiseLinear1D::new(&[1.0], 0.0, 1.0).is_err());
    assert!(PiecewiseConstant2D::new(&[1.0; 6], 4, 2, [[0.0, 1.0], [0.0, 1.0]]).is_err());
}

#[test]
fn alias_table_matches_its_weights() {
    let weights = test_values(37);
    let table = AliasTable::new(&weights).unwrap();
    let mut u = uniforms("alias");
    let mut counts = vec![0u64; 37];
    for _ in 0..SAMPLES {
        let (i, p) = table.sample(u());
        assert!(weights[i] > 0.0, "a zero-weight entry was chosen");
        assert_eq!(p, table.pmf(i));
        counts[i] += 1;
    }
    let total: f64 = weights.iter().sum();
    let expected: Vec<f64> = weights.iter().map(|w| w / total * SAMPLES as f64).collect();
    assert_chi_square("alias table", &counts, &expected);
    let sum: f64 = (0..37).map(|i| table.pmf(i)).sum();
    assert!((sum - 1.0).abs() < 1e-12);
}

/// What `sample_remapped` leaves of u is uniform within every chosen entry (10 bins per
/// entry, chi-square over all of them), and the entry is `sample`'s.
#[test]
fn alias_table_remapped_numbers_are_uniform_within_each_entry() {
    let weights = test_values(13);
    let table = AliasTable::new(&weights).unwrap();
    let mut u = uniforms("alias remapped");
    const BINS: usize = 10;
    let mut counts = vec![0u64; 13 * BINS];
    for _ in 0..SAMPLES {
        let x = u();
        let (i, p, rest) = table.sample_remapped(x);
        assert_eq!((i, p), table.sample(x));
        assert!((0.0..1.0).contains(&rest), "{rest}");
        counts[i * BINS + (rest * BINS as f64) as usize] += 1;
    }
    let total: f64 = weights.iter().sum();
    let expected: Vec<f64> = (0..13 * BINS)
        .map(|k| weights[k / BINS] / total * SAMPLES as f64 / BINS as f64)
        .collect();
    assert_chi_square("alias table remapped", &counts, &expected);
}

#[test]
fn two_dimensional_distribution_matches_its_cells() {
    let (w, h) = (12, 9);
    let values: Vec<f64> = (0..w * h)
        .map(|i| {
            if i / w == 4 {
                0.0
            } else {
                test_values(w * h)[i]
            }
        })
        .collect();
    let d = PiecewiseConstant2D::new(&values, w, h, [[0.0, 2.0], [-1.0, 1.0]]).unwrap();
    let mut u = uniforms("pc2d");
    let mut counts = vec![0u64; w * h];
    for _ in 0..SAMPLES {
        let s = d.sample([u(), u()]);
        let cx = ((s.point[0] / 2.0 * w as f64) as usize).min(w - 1);
        let cy = (((s.point[1] + 1.0) / 2.0 * h as f64) as usize).min(h - 1);
        assert!((s.pdf - d.pdf(s.point)).abs() <= 1e-9 * s.pdf);
        counts[cy * w + cx] += 1;
    }
    let total: f64 = values.iter().sum();
    let expected: Vec<f64> = values.iter().map(|v| v / total * SAMPLES as f64).collect();
    assert_chi_square("piecewise constant 2D", &counts, &expected);
    let cell_area = (2.0 / w as f64) * (2.0 / h as f64);
    let integral: f64 = (0..w * h)
        .map(|i| {
            let (x, y) = (
                ((i % w) as f64 + 0.5) * 2.0 / w as f64,
                ((i / w) as f64 + 0.5) * 2.0 / h as f64 - 1.0,
            );
            d.pdf([x, y]) * cell_area
        })
        .sum();
    assert!((integral - 1.0).abs() < 1e-12);
}

#[test]
fn piecewise_linear_matches_its_density() {
    let values = [0.0, 2.0, 2.0, 0.5, 0.0, 0.0, 3.0];
    let d = PiecewiseLinear1D::new(&values, 0.0, 6.0).unwrap();
    // 60 sub-bins; expected mass of each by the trapezoid of the exact linear density.
    let bins = 60;
    let mut u = uniforms("pl1d");
    let mut counts = vec![0u64; bins];
    for _ in 0..SAMPLES {
        let (x, pdf) = d.sample(u());
        assert!(pdf > 0.0 && (pdf - d.pdf(x)).abs() < 1e-9);
        counts[((x / 6.0 * bins as f64) as usize).min(bins - 1)] += 1;
    }
    let expected: Vec<f64> = (0..bins)
        .map(|b| {
            let (x0, x1) = (b as f64 * 0.1, (b + 1) as f64 * 0.1);
            0.5 * (d.pdf(x0) + d.pdf(x1 - 1e-12)) * 0.1 * SAMPLES as f64
        })
        .collect();
    assert_chi_square("piecewise linear 1D", &counts, &expected);
    // The density integrates to 1 (trapezoid rule is exact for a piecewise-linear function
    // on a grid that contains its knots).
    let n = 6000;
    let integral: f64 = (0..n)
        .map(|i| {
            0.5 * (d.pdf(i as f64 * 6.0 / n as f64) + d.pdf((i + 1) as f64 * 6.0 / n as f64)) * 6.0
                / n as f64
        })
        .sum();
    assert!((integral - 1.0).abs() < 1e-9, "{integral}");
}
