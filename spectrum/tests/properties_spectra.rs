//! Numerical stability of the spectrum representations at the extremes.

use prism_spectrum::constants::{BOLTZMANN, PLANCK, SPEED_OF_LIGHT};
use prism_spectrum::spectra::{
    Blackbody, Constant, DenselySampled, Extrapolation, Gaussian, PiecewiseLinear, planck_radiance,
};
use prism_spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};
use proptest::prelude::*;

mod common;
use common::any_f64;

/// Log-uniform in [lo, hi].
fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..=hi.ln()).prop_map(f64::exp)
}

/// An independent f64 formulation of Planck's law, accurate where it is used: the Wien
/// form e^-x / (1 - e^-x) for x > 1e-3, with e^-x applied as two halves so that no
/// intermediate is subnormal (e^-732 alone would keep only ~5 digits), and the
/// Rayleigh-Jeans series 1/x - 1/2 + x/12 below.
fn planck_reference(lambda_m: f64, kelvin: f64) -> f64 {
    let x = PLANCK * SPEED_OF_LIGHT / (lambda_m * BOLTZMANN * kelvin);
    let c1 = 2.0 * PLANCK * SPEED_OF_LIGHT * SPEED_OF_LIGHT;
    let prefactor = c1 / lambda_m.powi(5);
    if x > 1e-3 {
        let half = (-x / 2.0).exp();
        prefactor * half * half / (1.0 - (-x).exp())
    } else {
        prefactor * (1.0 / x - 0.5 + x / 12.0)
    }
}

proptest! {
    /// T in [1 K, 1e9 K], lambda in [1 nm, 1 mm]: finite, non-negative, 1e-12 relative to
    /// the independent f64 form in f64 and 1e-5 in the renderer's f32 lanes wherever the
    /// value is representable in f32.
    #[test]
    fn planck_is_finite_and_accurate(kelvin in log_uniform(1.0, 1e9), lambda_m in log_uniform(1e-9, 1e-3)) {
        let got = planck_radiance(lambda_m, kelvin);
        prop_assert!(got.is_finite() && got >= 0.0);
        let reference = planck_reference(lambda_m, kelvin);
        if reference > 1e-300 {
            prop_assert!(((got - reference) / reference).abs() < 1e-12, "{got} vs {reference}");
        } else {
            prop_assert!(got <= 1e-290);
        }
        let body = Blackbody::new(kelvin).unwrap();
        let lambda_nm = lambda_m * 1e9;
        let lane = body.sample(&SampledWavelengths::new([lambda_nm as f32], [1.0]).unwrap()).0[0];
        prop_assert!(lane.is_finite() && lane >= 0.0);
        let per_nm = planck_radiance(f64::from(lambda_nm as f32) * 1e-9, kelvin) * 1e-9;
        if per_nm > 1e-30 && per_nm < 1e38 {
            prop_assert!(((f64::from(lane) - per_nm) / per_nm).abs() < 1e-5, "{lane} vs {per_nm}");
        }
    }

    /// The normalized blackbody is in [0, 1] everywhere, with no 0/0 anywhere, and 1 at
    /// the Wien peak.
    #[test]
    fn normalized_blackbody_is_bounded(kelvin in log_uniform(1.0, 1e9), lambda in any_f64()) {
        let body = Blackbody::normalized(kelvin).unwrap();
        let v = body.evaluate(lambda);
        prop_assert!(v.is_finite() && (0.0..=1.0).contains(&v), "{v}");
        let peak = body.evaluate(body.peak_nm());
        prop_assert!((peak - 1.0).abs() < 1e-12, "{peak}");
    }

    /// Planck never overflows, never NaNs, for any input at all.
    #[test]
    fn planck_total(lambda in any_f64(), kelvin in any_f64()) {
        let v = planck_radiance(lambda, kelvin);
        prop_assert!(v.is_finite() && v >= 0.0);
        match Blackbody::new(kelvin) {
            Ok(b) => {
                prop_assert!(b.evaluate(lambda).is_finite());
                prop_assert!(b.max_value().is_finite());
            }
            Err(_) => prop_assert!(!(kelvin > 0.0 && kelvin.is_finite())),
        }
    }

    /// Tabulated spectra evaluate finitely everywhere and stay inside the table's range.
    #[test]
    fn piecewise_linear_is_finite_and_bounded(
        values in prop::collection::vec(-1e6..1e6f64, 2..50),
        start in -1e3..1e3f64,
        lambda in any_f64(),
        clamp in any::<bool>(),
    ) {
        let lambdas: Vec<f64> = (0..values.len()).map(|i| start + 3.0 * i as f64).collect();
        let extrapolation = if clamp { Extrapolation::Clamp } else { Extrapolation::Zero };
        let s = PiecewiseLinear::new(lambdas, values.clone(), extrapolation).unwrap();
        let v = s.evaluate(lambda);
        let lo = values.iter().copied().fold(0.0f64, f64::min);
        let hi = values.iter().copied().fold(0.0f64, f64::max);
        prop_assert!(v.is_finite() && v >= lo - 1e-9 && v <= hi + 1e-9);
        prop_assert!(v <= s.max_value() + 1e-9);
    }

    /// Malformed tables are errors, never panics.
    #[test]
    fn piecewise_linear_rejects_bad_tables(
        lambdas in prop::collection::vec(any_f64(), 0..6),
        values in prop::collection::vec(any_f64(), 0..6),
    ) {
        let ok = PiecewiseLinear::new(lambdas.clone(), values.clone(), Extrapolation::Zero).is_ok();
        let valid = lambdas.len() == values.len()
            && lambdas.len() >= 2
            && lambdas.iter().chain(&values).all(|v| v.is_finite())
            && lambdas.windows(2).all(|w| w[0] < w[1]);
        prop_assert_eq!(ok, valid);
    }

    /// CSV parsing never panics, whatever the text.
    #[test]
    fn csv_parsing_is_total(text in ".{0,200}") {
        let _ = PiecewiseLinear::from_csv_str(&text, Extrapolation::Zero);
    }

    #[test]
    fn gaussian_and_constant_are_total(c in any_f64(), w in any_f64(), p in any_f64(), lambda in any_f64()) {
        if let Ok(g) = Gaussian::new(c, w, p) {
            prop_assert!(g.evaluate(lambda).is_finite());
        }
        if let Ok(k) = Constant::new(c) {
            prop_assert!(k.evaluate(lambda).is_finite());
        }
    }

    #[test]
    fn dense_sampling_is_total(kelvin in log_uniform(100.0, 1e6), lambda in any_f64()) {
        let dense = DenselySampled::from_spectrum(&Blackbody::normalized(kelvin).unwrap(), 300, 1000).unwrap();
        let v = dense.evaluate(lambda);
        prop_assert!(v.is_finite() && (0.0..=1.0).contains(&v));
    }

    /// Lane arithmetic: division by zero gives 0, never inf or NaN; colour of finite lanes
    /// is finite.
    #[test]
    fn sampled_spectrum_arithmetic_is_finite(
        a in prop::array::uniform4(-1e6f32..1e6),
        b in prop::array::uniform4(prop_oneof![Just(0.0f32), -1e6f32..1e6]),
        lambda in prop::array::uniform4(300.0f32..900.0),
        pdf in prop::array::uniform4(prop_oneof![Just(0.0f32), Just(1e-38f32), 1e-6f32..1.0]),
    ) {
        let (sa, sb) = (SampledSpectrum(a), SampledSpectrum(b));
        prop_assert!((sa / sb).is_finite());
        prop_assert!((sa * sb + sa - sb).is_finite());
        let wl = SampledWavelengths::new(lambda, pdf).unwrap();
        let xyz = sa.to_xyz(&wl, Default::default());
        prop_assert!(xyz.x.is_finite() && xyz.y.is_finite() && xyz.z.is_finite());
    }
}

proptest! {
    /// The f32 lanes renderers sample agree with the f64 evaluation: inside the range to
    /// f32 rounding of the values, 0 outside it and for NaN, at both ends exactly.
    #[test]
    fn dense_lanes_match_evaluate(
        first in 200i32..500,
        values in prop::collection::vec(0.0..1e3f64, 1..600),
        lambdas in prop::array::uniform8(prop_oneof![150.0..1200.0f32, Just(f32::NAN), Just(f32::INFINITY), Just(-0.0f32)]),
    ) {
        let dense = DenselySampled::from_values(f64::from(first), values.clone()).unwrap();
        let lanes = dense.evaluate_lanes(&lambdas);
        for (l, v) in lambdas.iter().zip(lanes) {
            let want = dense.evaluate(f64::from(*l));
            prop_assert!(v.is_finite());
            prop_assert!(
                (f64::from(v) - want).abs() <= 1e-6 * dense.max_value() + 1e-30,
                "{l} nm: lanes {v}, evaluate {want}"
            );
        }
        let ends = [first as f32, (first as usize + values.len() - 1) as f32];
        let at_ends = dense.evaluate_lanes(&ends);
        prop_assert_eq!(at_ends[0], values[0] as f32);
        prop_assert_eq!(at_ends[1], values[values.len() - 1] as f32);
    }
}

/// Mostly ordinary values, else any f32 bit pattern or an edge value: packages with one
/// bad lane among good ones are common.
fn any_f32_bits() -> impl Strategy<Value = f32> {
    prop_oneof![
        6 => 1e-3..2e3f32,
        1 => any::<u32>().prop_map(f32::from_bits),
        2 => prop::sample::select(vec![
            0.0f32,
            -0.0,
            f32::MIN_POSITIVE,
            f32::from_bits(1),
            -f32::from_bits(1),
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
            1.0,
            -1.0,
            550.0,
        ]),
    ]
}

proptest! {
    // Cheap cases, and single bad lanes (-0 densities, say) are rare: many of them.
    #![proptest_config(ProptestConfig::with_cases(4096))]

    /// Packages are accepted exactly when every wavelength is finite and > 0 and every
    /// density finite and >= 0 (the constructor checks on the bits).
    #[test]
    fn packages_accept_exactly_the_valid_lanes(
        lambda in prop::array::uniform4(any_f32_bits()),
        pdf in prop::array::uniform4(any_f32_bits()),
    ) {
        let valid = lambda.iter().all(|l| l.is_finite() && *l > 0.0)
            && pdf.iter().all(|p| p.is_finite() && *p >= 0.0);
        prop_assert_eq!(SampledWavelengths::new(lambda, pdf).is_ok(), valid, "{:?} {:?}", lambda, pdf);
    }
}

#[test]
fn packages_at_the_edges() {
    let ok = |l: f32, p: f32| SampledWavelengths::new([550.0, l], [1.0, p]).is_ok();
    assert!(ok(f32::from_bits(1), 0.0), "the smallest subnormal is > 0");
    assert!(ok(f32::MAX, f32::MAX));
    assert!(ok(550.0, -0.0), "-0 is >= 0");
    assert!(ok(550.0, f32::from_bits(1)));
    for bad in [
        0.0,
        -0.0,
        -1.0,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        -f32::NAN,
    ] {
        assert!(!ok(bad, 1.0), "wavelength {bad}");
    }
    for bad in [
        -f32::from_bits(1),
        -1.0,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        -f32::NAN,
    ] {
        assert!(!ok(550.0, bad), "density {bad}");
    }
}

proptest! {
    /// Blackbody lanes (the path's per-sample form) agree with the f64 evaluation: the
    /// shape with peak 1 within 1.2e-5 relative (the rounding of x = hc / lambda k T in f32
    /// grows with x: 1e-6 near the peak, 1e-5 where the value is 1e-36 of it), or 1e-29
    /// absolute where f32's expm1 overflows; absolute radiance as f64 rounded; 0 and
    /// never NaN for any bit pattern of a wavelength, at any temperature.
    #[test]
    fn blackbody_lanes_match_evaluate(
        kelvin in prop_oneof![log_uniform(1.0, 1e6), Just(f64::MIN_POSITIVE), Just(1e300)],
        lambdas in prop::array::uniform8(any_f32_bits()),
    ) {
        for b in [Blackbody::normalized(kelvin).unwrap(), Blackbody::new(kelvin).unwrap()] {
            let lanes = b.evaluate_lanes(&lambdas);
            for (l, v) in lambdas.iter().zip(lanes) {
                let want = b.evaluate(f64::from(*l));
                prop_assert!(!v.is_nan(), "{b:?} at {l}: NaN");
                if want as f32 != f32::INFINITY {
                    prop_assert!(v.is_finite(), "{b:?} at {l}: {v}");
                    prop_assert!(
                        (f64::from(v) - want).abs() <= 1.2e-5 * want.abs() + 1e-29,
                        "{b:?} at {l}: lanes {v}, evaluate {want}"
                    );
                }
            }
        }
    }

    /// Gaussian lanes agree with the f64 evaluation within 1.2e-5 relative (the exponent's
    /// f32 rounding grows with its size: 1e-7 near the centre) or 1e-37 absolute where f32
    /// underflows, for any centre, width and peak and any wavelength bits.
    #[test]
    fn gaussian_lanes_match_evaluate(
        center in prop_oneof![200.0..900.0f64, any_f64()],
        fwhm in prop_oneof![log_uniform(1e-3, 1e4), Just(f64::MAX)],
        peak in prop_oneof![0.0..1e3f64, Just(0.0), Just(1e30), Just(-1.0)],
        lambdas in prop::array::uniform8(any_f32_bits()),
    ) {
        let Ok(g) = Gaussian::new(center, fwhm, peak) else { return Ok(()) };
        let lanes = g.evaluate_lanes(&lambdas);
        for (l, v) in lambdas.iter().zip(lanes) {
            let want = g.evaluate(f64::from(*l));
            prop_assert!(v.is_finite(), "{g:?} at {l}: {v}");
            prop_assert!(
                (f64::from(v) - want).abs() <= 1.2e-5 * want.abs() + 1e-37 * peak.abs().max(1.0),
                "{g:?} at {l}: lanes {v}, evaluate {want}"
            );
        }
    }
}
