//! Shared by the statistical tests: one significance level for the whole suite.

#![allow(dead_code)]

use prism_sampling::stats::chi_square_test;
use prism_sampling::stream::IndependentStream;

/// Upper bound on the number of chi-square tests in this crate's suite (counted by hand;
/// raise it when adding tests). With fixed seeds the tests are deterministic; the level is
/// corrected so that the family-wise false-alarm rate of the suite stays at 1%.
pub const CHI_SQUARE_TESTS: f64 = 90.0;
/// Per-test significance level (Bonferroni).
pub const ALPHA: f64 = 0.01 / CHI_SQUARE_TESTS;

/// Asserts that `observed` counts are consistent with `expected` counts.
pub fn assert_chi_square(name: &str, observed: &[u64], expected: &[f64]) {
    let result = chi_square_test(observed, expected);
    assert!(
        result.p_value > ALPHA,
        "{name}: chi-square {:.2} with {} dof, p = {:.3e} < {ALPHA:.1e}",
        result.statistic,
        result.degrees_of_freedom,
        result.p_value
    );
}

/// A deterministic stream of uniform f64s for test `name` (seeded by the name).
pub fn uniforms(name: &str) -> impl FnMut() -> f64 + use<> {
    let seed = name
        .bytes()
        .fold(0u64, |h, b| h.wrapping_mul(31).wrapping_add(u64::from(b)));
    let mut stream = IndependentStream::new(seed, 0, 0);
    move || stream.next_f64()
}
