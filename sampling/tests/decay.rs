//! Phosphorescent delays: single and multi-exponential decays sampled whole and
//! restricted to windows (the times some light was on) have the densities they claim
//! (chi-square), the masses they report (closed forms), and no NaN at the extremes.

mod common;

use common::{assert_chi_square, uniforms};
use prism_sampling::SamplingError;
use prism_sampling::decay::{Decay, delay_windows};
use proptest::prelude::*;

const SAMPLES: usize = 200_000;

/// Histogram of `SAMPLES` delays from `decay` within `windows` over `bins` bins of
/// [0, top), against the density restricted to the windows (bin masses by the closed
/// form), and every sample's reported mass against the windows' mass.
fn check(name: &str, decay: &Decay, windows: &[(f64, f64)], top: f64, bins: usize) {
    let z: f64 = windows.iter().map(|&(a, b)| decay.mass(a, b)).sum();
    let mut u = uniforms(name);
    let mut counts = vec![0u64; bins];
    for _ in 0..SAMPLES {
        let (d, mass) = decay.sample_within(u(), windows).expect("a delay");
        assert!((mass - z).abs() <= 1e-12 * z, "{name}: mass {mass} vs {z}");
        assert!(
            windows.iter().any(|&(a, b)| d >= a && d <= b),
            "{name}: {d} outside {windows:?}"
        );
        let bin = ((d / top) * bins as f64) as usize;
        if bin < bins {
            counts[bin] += 1;
        }
    }
    let expected: Vec<f64> = (0..bins)
        .map(|i| {
            let (lo, hi) = (
                top * i as f64 / bins as f64,
                top * (i + 1) as f64 / bins as f64,
            );
            let m: f64 = windows
                .iter()
                .map(|&(a, b)| {
                    let (a, b) = (a.max(lo), b.min(hi));
                    if b > a { decay.mass(a, b) } else { 0.0 }
                })
                .sum();
            m / z * SAMPLES as f64
        })
        .collect();
    // The tail past `top` is one more bin.
    let tail: f64 = SAMPLES as f64 - expected.iter().sum::<f64>();
    let mut observed = counts.clone();
    observed.push(SAMPLES as u64 - counts.iter().sum::<u64>());
    let mut expected = expected;
    expected.push(tail.max(0.0));
    assert_chi_square(name, &observed, &expected);
}

#[test]
fn exponential_delays_have_their_density() {
    let decay = Decay::exponential(2.0).unwrap();
    check("exp whole", &decay, &[(0.0, f64::INFINITY)], 12.0, 48);
    // Light on from 1 s to 3 s before the present, and again from 6 s to 6.5 s before.
    check("exp windows", &decay, &[(1.0, 3.0), (6.0, 6.5)], 8.0, 64);
    // A window far out in the tail.
    check("exp tail", &decay, &[(40.0, 41.0)], 42.0, 84);
}

#[test]
fn multi_exponential_delays_have_their_density() {
    // A fast and a slow component, as real phosphors have (SrAl2O4: seconds and minutes).
    let decay = Decay::multi(&[(0.5, 0.7), (20.0, 0.3)]).unwrap();
    check("multi whole", &decay, &[(0.0, f64::INFINITY)], 60.0, 60);
    check(
        "multi windows",
        &decay,
        &[(0.2, 1.0), (10.0, 30.0)],
        32.0,
        64,
    );
}

#[test]
fn masses_are_the_closed_forms() {
    let decay = Decay::multi(&[(1.0, 0.25), (4.0, 0.75)]).unwrap();
    let closed = |a: f64, b: f64| {
        0.25 * ((-a).exp() - (-b).exp()) + 0.75 * ((-a / 4.0).exp() - (-b / 4.0).exp())
    };
    for (a, b) in [
        (0.0, 1.0),
        (0.5, 2.0),
        (3.0, f64::INFINITY),
        (0.0, f64::INFINITY),
    ] {
        assert!((decay.mass(a, b) - closed(a, b)).abs() < 1e-15, "{a}..{b}");
    }
    assert_eq!(decay.mass(2.0, 1.0), 0.0);
    assert!((decay.mass(0.0, f64::INFINITY) - 1.0).abs() < 1e-15);
    // The density integrates to the masses (midpoint rule on a fine grid).
    let n = 200_000;
    let integral: f64 = (0..n)
        .map(|i| decay.pdf((i as f64 + 0.5) * 1e-4) * 1e-4)
        .sum();
    assert!((integral - decay.mass(0.0, 20.0)).abs() < 1e-6);
}

/// Light on during [0, 5] s, seen at 8 s: delays 3-8 s; at 2 s: 0-2 s; at -1 s (before
/// it shone): none; a source without a schedule (always on): every delay.
#[test]
fn windows_follow_the_schedule() {
    assert_eq!(delay_windows(8.0, &[(0.0, 5.0)]), vec![(3.0, 8.0)]);
    assert_eq!(delay_windows(2.0, &[(0.0, 5.0)]), vec![(0.0, 2.0)]);
    assert!(delay_windows(-1.0, &[(0.0, 5.0)]).is_empty());
    assert_eq!(
        delay_windows(3.0, &[(f64::NEG_INFINITY, f64::INFINITY)]),
        vec![(0.0, f64::INFINITY)]
    );
    let decay = Decay::exponential(1.0).unwrap();
    assert!(decay.sample_within(0.5, &[]).is_none());
}

#[test]
fn bad_decays_are_errors() {
    assert!(matches!(
        Decay::exponential(0.0),
        Err(SamplingError::InvalidParameter(_))
    ));
    assert!(Decay::exponential(-1.0).is_err());
    assert!(Decay::exponential(f64::NAN).is_err());
    assert!(Decay::exponential(f64::INFINITY).is_err());
    assert!(Decay::multi(&[]).is_err());
    assert!(Decay::multi(&[(1.0, 0.5), (2.0, 0.4)]).is_err());
    assert!(Decay::multi(&[(1.0, -0.5), (2.0, 1.5)]).is_err());
}

proptest! {
    /// Any decay, window and uniform: a finite delay inside the windows and a mass in
    /// (0, 1], or None; never NaN.
    #[test]
    fn delays_are_finite_and_inside(
        tau in prop_oneof![Just(1e-12), Just(1e12), 1e-6f64..1e6],
        second in 1e-9f64..1e9,
        w in 0.0f64..=1.0,
        a in prop_oneof![Just(0.0), 0.0f64..1e9],
        width in prop_oneof![Just(f64::INFINITY), Just(1e-300), 0.0f64..1e9],
        u in prop_oneof![Just(0.0), Just(1.0), Just(f64::NAN), 0.0f64..1.0],
    ) {
        let decay = Decay::multi(&[(tau, w), (second, 1.0 - w)]).unwrap();
        let windows = [(a, a + width)];
        if let Some((d, mass)) = decay.sample_within(u, &windows) {
            prop_assert!(d.is_finite() && d >= a && d <= a + width, "{d}");
            prop_assert!(mass > 0.0 && mass <= 1.0 + 1e-12, "{mass}");
        }
        prop_assert!(decay.pdf(a).is_finite());
        prop_assert!(decay.mass(a, a + width).is_finite());
    }
}
