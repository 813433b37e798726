//! The sigmoid is finite, bounded, monotone and free of cancellation for every input.

use prism_spectrum::Spectrum;
use prism_upsample::sigmoid::{sigmoid, sigmoid_derivative, sigmoid_f32, sigmoid_polynomial_lanes};
use prism_upsample::{SigmoidPolynomial, inverse_sigmoid};
use proptest::prelude::*;

fn any_x() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(-0.0),
        Just(5e-324),
        Just(-5e-324),
        Just(1e30),
        Just(-1e30),
        Just(1e200),
        Just(-1e200),
        Just(f64::MAX),
        Just(f64::MIN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        -1e3..1e3f64,
        any::<f64>(),
    ]
}

proptest! {
    #[test]
    fn bounded_symmetric_and_monotone(x in any_x(), y in any_x()) {
        prop_assume!(!x.is_nan() && !y.is_nan());
        let (sx, sy) = (sigmoid(x), sigmoid(y));
        prop_assert!((0.0..=1.0).contains(&sx));
        prop_assert!((sigmoid(-x) - (1.0 - sx)).abs() < 1e-15);
        if x <= y { prop_assert!(sx <= sy); }
        prop_assert!(sigmoid_derivative(x).is_finite() && sigmoid_derivative(x) >= 0.0);
        let f = sigmoid_f32(x as f32);
        prop_assert!((0.0..=1.0).contains(&f));
        prop_assert!((f64::from(f) - sigmoid(f64::from(x as f32))).abs() < 2e-7);
    }

    /// Where the textbook formula is safe it agrees; for large negative x the stable form
    /// keeps full relative precision (the textbook form returns 0 or garbage there).
    #[test]
    fn accurate(x in -1e3..1e3f64, big in 1e4..1e150f64) {
        let textbook = 0.5 + x / (2.0 * (1.0 + x * x).sqrt());
        prop_assert!((sigmoid(x) - textbook).abs() < 1e-15);
        // S(-a) = 1 / (4 a^2) (1 - 3 / (4 a^2) + ...) for large a.
        let asymptotic = 1.0 / (4.0 * big * big) * (1.0 - 3.0 / (4.0 * big * big));
        prop_assert!(((sigmoid(-big) - asymptotic) / asymptotic).abs() < 1e-12);
    }

    #[test]
    fn inverse_inverts(v in 0.0..=1.0f64) {
        let back = sigmoid(inverse_sigmoid(v));
        prop_assert!((back - v).abs() < 1e-15, "{v} -> {back}");
    }

    /// The lane form equals the scalar form, and a sigmoid polynomial stays in [0, 1] at
    /// every wavelength whatever its coefficients.
    #[test]
    fn lanes_and_spectra(c in prop::array::uniform3(prop_oneof![Just(0.0f64), Just(1e30), Just(-1e30), -1.0..1.0f64]), l in prop::array::uniform8(300.0f32..1000.0)) {
        let lanes = sigmoid_polynomial_lanes(c.map(|v| v as f32), &l);
        let poly = SigmoidPolynomial { coefficients: c };
        for (i, v) in lanes.iter().enumerate() {
            prop_assert!((0.0..=1.0).contains(v));
            let x = (c[0] as f32 * l[i] + c[1] as f32) * l[i] + c[2] as f32;
            prop_assert_eq!(*v, sigmoid_f32(x));
            let e = poly.evaluate(f64::from(l[i]));
            prop_assert!((0.0..=1.0).contains(&e) && e <= poly.max_value() + 1e-12);
        }
    }
}

#[test]
fn limits_are_exact() {
    assert_eq!(sigmoid(f64::INFINITY), 1.0);
    assert_eq!(sigmoid(f64::NEG_INFINITY), 0.0);
    assert_eq!(sigmoid(0.0), 0.5);
    assert_eq!(sigmoid(f64::NAN), 0.5);
    assert_eq!(sigmoid_f32(f32::INFINITY), 1.0);
    assert_eq!(sigmoid_f32(f32::NEG_INFINITY), 0.0);
    assert_eq!(sigmoid_derivative(f64::INFINITY), 0.0);
    assert_eq!(inverse_sigmoid(1.0), f64::INFINITY);
    assert_eq!(inverse_sigmoid(0.0), f64::NEG_INFINITY);
}
