//! Wavelength samplers and packages: chi-square tests, normalization, inversion,
//! unbiasedness for every sampler, scheme and package size, secondary termination,
//! spectral MIS and fluorescence re-radiation.

mod common;

use common::{assert_chi_square, uniforms};
use prism_sampling::wavelength::*;

fn ranges() -> [WavelengthRange; 2] {
    [
        WavelengthRange::VISIBLE,
        WavelengthRange::new(300.0, 1000.0).unwrap(),
    ]
}

/// A smooth stand-in for the CIE y-bar curve (a camera response), for the response and
/// SPD samplers.
fn y_bar(l: f64) -> f64 {
    (-0.5 * ((l - 555.0) / 45.0).powi(2)).exp()
}
fn x_bar(l: f64) -> f64 {
    1.06 * (-0.5 * ((l - 600.0) / 38.0).powi(2)).exp()
        + 0.36 * (-0.5 * ((l - 445.0) / 20.0).powi(2)).exp()
}
fn z_bar(l: f64) -> f64 {
    1.78 * (-0.5 * ((l - 450.0) / 25.0).powi(2)).exp()
}
/// What a camera integrates against: the sum of its response curves.
fn sensor(l: f64) -> f64 {
    x_bar(l) + y_bar(l) + z_bar(l)
}
/// A blackbody-ish warm light and a narrow cool one with 20x less power.
fn warm(l: f64) -> f64 {
    20.0 * (l / 1000.0).powi(3)
}
fn cool_line(l: f64) -> f64 {
    if (440.0..450.0).contains(&l) {
        0.1
    } else {
        0.0
    }
}

fn samplers(range: WavelengthRange) -> Vec<(&'static str, WavelengthDistribution)> {
    vec![
        ("uniform", WavelengthDistribution::uniform(range)),
        ("visible", WavelengthDistribution::visible(range)),
        (
            "response",
            WavelengthDistribution::response(range, 94, &[&x_bar, &y_bar, &z_bar]).unwrap(),
        ),
        (
            "spd",
            WavelengthDistribution::light_spd(range, 94, &[&warm, &cool_line], &sensor, 0.1)
                .unwrap(),
        ),
    ]
}

/// Integral of f over [a, b] by the midpoint rule on 100 000 intervals (smooth f: error
/// far below the tolerances that use it).
fn integrate(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let n = 100_000;
    let h = (b - a) / n as f64;
    (0..n).map(|i| f(a + (i as f64 + 0.5) * h)).sum::<f64>() * h
}

#[test]
fn visible_normalization_is_derived_not_pasted() {
    // pbrt-v4 hard-codes 0.0039398042 for 360-830 nm; the closed form gives it.
    let d = WavelengthDistribution::visible(WavelengthRange::VISIBLE);
    let c = (0.0072f64 * (538.0 - 538.0)).cosh();
    let peak = d.pdf(538.0) * c * c;
    assert!((peak - 0.003_939_804_2).abs() < 1e-9, "{peak}");
}

/// The lane densities a package uses are the f64 densities to within 1e-6 relative,
/// everywhere: inside the range, at its ends, just outside it and at NaN.
#[test]
fn lane_densities_are_the_densities() {
    for range in ranges() {
        let (lo, hi) = (range.min(), range.max());
        for (name, d) in samplers(range) {
            let mut lambdas = vec![
                lo.next_down(),
                hi.next_up(),
                0.0,
                -1.0,
                1e30,
                f32::NAN,
                lo,
                hi,
            ];
            lambdas.extend((0..4000).map(|i| lo + (hi - lo) * i as f32 / 4000.0));
            for chunk in lambdas.chunks_exact(8) {
                let lanes = d.pdf_lanes(&<[f32; 8]>::try_from(chunk).unwrap());
                for (l, lane) in chunk.iter().zip(lanes) {
                    let exact = d.pdf(f64::from(*l));
                    let error = (f64::from(lane) - exact).abs();
                    assert!(error <= 1e-6 * exact, "{name} at {l}: {lane} vs {exact}");
                    assert_eq!(lane > 0.0, exact > 0.0, "{name} at {l}");
                }
            }
        }
    }
}

#[test]
fn densities_integrate_to_one_and_invert() {
    for range in ranges() {
        let (lo, hi) = (f64::from(range.min()), f64::from(range.max()));
        for (name, d) in samplers(range) {
            let total = integrate(|l| d.pdf(l), lo, hi);
            // Midpoint quadrature of a histogram errs at its 94 jumps (~1e-6 here); smooth
            // densities integrate to 1e-9.
            let tolerance = if name == "uniform" || name == "visible" {
                1e-9
            } else {
                1e-5
            };
            assert!(
                (total - 1.0).abs() < tolerance,
                "{name} {lo}-{hi}: integral {total}"
            );
            let mut u = uniforms(name);
            for _ in 0..5_000 {
                let x = u();
                let l = d.sample(x);
                assert!(range.contains(l as f32) && d.pdf(l) > 0.0, "{name}: {l}");
                assert!(
                    (d.cdf(l) - x).abs() < 1e-9,
                    "{name}: cdf(sample({x})) = {}",
                    d.cdf(l)
                );
            }
        }
    }
}

#[test]
fn samplers_match_their_densities() {
    let bins = 47;
    let samples = 200_000;
    for range in ranges() {
        let (lo, hi) = (f64::from(range.min()), f64::from(range.max()));
        let width = (hi - lo) / bins as f64;
        for (name, d) in samplers(range) {
            let mut u = uniforms(name);
            let mut counts = vec![0u64; bins];
            for _ in 0..samples {
                let l = d.sample(u());
                counts[(((l - lo) / width) as usize).min(bins - 1)] += 1;
            }
            let expected: Vec<f64> = (0..bins)
                .map(|b| d.cdf(lo + (b + 1) as f64 * width) - d.cdf(lo + b as f64 * width))
                .map(|p| p * samples as f64)
                .collect();
            assert_chi_square(&format!("{name} {lo}-{hi}"), &counts, &expected);
        }
    }
}

/// Globally normalized SPD sampling: the dim line gets its share of power, not an equal
/// share (local normalization would give the 10 nm line as much as the whole warm light).
#[test]
fn light_spd_keeps_relative_power() {
    let range = WavelengthRange::VISIBLE;
    let d =
        WavelengthDistribution::light_spd(range, 470, &[&warm, &cool_line], &y_bar, 0.1).unwrap();
    let line_mass = d.cdf(450.0) - d.cdf(440.0);
    let product = |l: f64| y_bar(l) * (warm(l) + cool_line(l));
    // The interval's mass: its share of response x (sum of absolute SPDs), mixed 9:1 with
    // its share of the response. 1 nm bins resolve the line's edges exactly.
    let expected_line = 0.9 * integrate(product, 440.0, 450.0) / integrate(product, 360.0, 830.0)
        + 0.1 * integrate(y_bar, 440.0, 450.0) / integrate(y_bar, 360.0, 830.0);
    assert!(
        (line_mass - expected_line).abs() < 1e-3 * expected_line,
        "{line_mass} vs {expected_line}"
    );
    // Locally normalized SPDs would give the dim line half of the SPD samples.
    assert!(line_mass < 0.01);
    // The defensive mixture keeps every wavelength the response sees sampleable.
    assert!(d.pdf(700.0) > 0.0 && d.pdf(380.0) > 0.0);
}

/// A smooth random test spectrum: constant plus three Gaussians, parameterized by `k`.
fn test_spectrum(k: u64) -> impl Fn(f64) -> f64 {
    let mut u = uniforms(&format!("spectrum {k}"));
    let params: Vec<(f64, f64, f64)> = (0..3)
        .map(|_| (250.0 + 800.0 * u(), 10.0 + 80.0 * u(), 2.0 * u()))
        .collect();
    let base = u();
    move |l| {
        base + params
            .iter()
            .map(|(c, w, a)| a * (-0.5 * ((l - c) / w).powi(2)).exp())
            .sum::<f64>()
    }
}

/// Mean and standard error of `samples` draws of `estimate`.
fn monte_carlo(samples: usize, mut estimate: impl FnMut() -> f64) -> (f64, f64) {
    let (mut sum, mut sum2) = (0.0, 0.0);
    for _ in 0..samples {
        let e = estimate();
        assert!(e.is_finite(), "non-finite estimate");
        sum += e;
        sum2 += e * e;
    }
    let mean = sum / samples as f64;
    let variance = (sum2 / samples as f64 - mean * mean).max(0.0);
    (mean, (variance / samples as f64).sqrt())
}

fn check_unbiased<const N: usize>(terminate: bool) {
    let samples = 20_000;
    for range in ranges() {
        let (lo, hi) = (f64::from(range.min()), f64::from(range.max()));
        for (name, d) in samplers(range) {
            for scheme in [PackageScheme::HeroRotation, PackageScheme::Stratified] {
                for k in 0..2 {
                    // Densities shaped by a sensor vanish (to ~1e-9) where it does, so they are
                    // tested on sensor-weighted integrands, as every rendering integrand is;
                    // on a raw spectrum they are unbiased but of unbounded variance.
                    let raw = test_spectrum(k);
                    let weighted = name == "response" || name == "spd";
                    let f = move |l: f64| if weighted { raw(l) * sensor(l) } else { raw(l) };
                    let exact = integrate(&f, lo, hi);
                    let mut u = uniforms(&format!("{name} {scheme:?} {N} {k}"));
                    let (mean, error) = monte_carlo(samples, || {
                        let mut p = WavelengthPackage::<N>::sample(&d, u(), scheme);
                        if terminate {
                            p.terminate_secondary();
                        }
                        (0..N)
                            .filter(|&j| p.pdf[j] > 0.0)
                            .map(|j| f(f64::from(p.lambda[j])) / f64::from(p.pdf[j]))
                            .sum::<f64>()
                            / N as f64
                    });
                    // 5 standard errors: with ~2000 such checks the chance of a false
                    // alarm is ~1e-3; a bias of 1% of the integral is ~20 errors here.
                    assert!(
                        (mean - exact).abs() < 5.0 * error + 1e-3 * exact,
                        "{name} {scheme:?} C={N} {lo}-{hi} terminated={terminate}: {mean} vs {exact} (+-{error})"
                    );
                }
            }
        }
    }
}

#[test]
fn packages_are_unbiased_for_every_sampler_scheme_and_size() {
    check_unbiased::<1>(false);
    check_unbiased::<2>(false);
    check_unbiased::<4>(false);
    check_unbiased::<8>(false);
    check_unbiased::<16>(false);
}

#[test]
fn secondary_termination_keeps_the_estimator_unbiased() {
    check_unbiased::<4>(true);
    check_unbiased::<16>(true);
}

#[test]
fn secondary_termination_is_idempotent_and_zeroes_every_secondary() {
    let d = WavelengthDistribution::visible(WavelengthRange::VISIBLE);
    let mut p = WavelengthPackage::<8>::sample(&d, 0.3, PackageScheme::HeroRotation);
    let hero_pdf = p.hero_pdf[0];
    p.terminate_secondary();
    let once = p;
    p.terminate_secondary();
    assert_eq!(p, once, "terminating twice changes the package");
    assert!(p.secondary_terminated());
    assert_eq!(p.pdf[0], hero_pdf / 8.0);
    assert!(
        p.pdf[1..].iter().all(|&x| x == 0.0),
        "a secondary lane survived: {:?}",
        p.pdf
    );
    // A package whose secondary has zero density for another reason still terminates.
    let narrow = WavelengthDistribution::tabulated(WavelengthRange::VISIBLE, 47, |l| {
        if l < 400.0 { 1.0 } else { 0.0 }
    })
    .unwrap();
    let mut q = WavelengthPackage::<4>::sample(&narrow, 0.5, PackageScheme::HeroRotation);
    assert!(q.hero_pdf[1..].contains(&0.0));
    let hero = q.hero_pdf[0];
    q.terminate_secondary();
    assert_eq!(q.pdf[0], hero / 4.0);
}

/// Wavelength-dependent path sampling: x in [0, 1] drawn from q(x | hero) = 1 + s(lambda)
/// (2x - 1); the balance-heuristic package estimate of the double integral of
/// f(lambda) g(x, lambda) is unbiased (the seed lecture's HWS MIS).
#[test]
fn spectral_mis_is_unbiased_when_paths_depend_on_wavelength() {
    let slope = |l: f64| 0.9 * ((l - 360.0) / 470.0 * 6.0).sin();
    let q = |x: f64, l: f64| 1.0 + slope(l) * (2.0 * x - 1.0);
    let sample_x = |u: f64, l: f64| {
        // Inverse CDF of the linear density 1 + s (2x - 1) on [0, 1].
        let s = slope(l);
        if s.abs() < 1e-9 {
            u
        } else {
            ((s - 1.0) + ((1.0 - s).powi(2) + 4.0 * s * u).sqrt()) / (2.0 * s)
        }
    };
    let raw = test_spectrum(7);
    let f = |l: f64| raw(l) * sensor(l);
    let g = |x: f64, l: f64| (x * 3.0 + l / 300.0).cos() + 1.5;
    let range = WavelengthRange::VISIBLE;
    // The inner integral of g over x in closed form: x + sin(3x + c) / 3 with c = l / 300.
    let inner = |l: f64| 1.5 + ((3.0 + l / 300.0).sin() - (l / 300.0).sin()) / 3.0;
    let exact = integrate(|l| f(l) * inner(l), 360.0, 830.0);
    for (name, d) in samplers(range) {
        for scheme in [PackageScheme::HeroRotation, PackageScheme::Stratified] {
            let mut u = uniforms(&format!("mis {name} {scheme:?}"));
            let (mean, error) = monte_carlo(40_000, || {
                let p = WavelengthPackage::<4>::sample(&d, u(), scheme);
                let x = sample_x(u(), f64::from(p.hero()));
                let path_pdf = p.lambda.map(|l| q(x, f64::from(l)) as f32);
                let pdf = p.balance_pdf(&path_pdf);
                let weights = p.mis_weights(&path_pdf);
                assert!((weights.iter().sum::<f32>() - 1.0).abs() < 1e-5);
                // The two forms of the estimator agree lane by lane.
                for j in 0..4 {
                    let own = f64::from(p.hero_pdf[j]) * f64::from(path_pdf[j]);
                    let via_weight = f64::from(weights[j]) / own;
                    assert!(
                        (via_weight * f64::from(pdf[j]) * 4.0 - 1.0).abs() < 1e-4 || own == 0.0
                    );
                }
                (0..4)
                    .map(|j| {
                        f(f64::from(p.lambda[j])) * g(x, f64::from(p.lambda[j])) / f64::from(pdf[j])
                    })
                    .sum::<f64>()
                    / 4.0
            });
            assert!(
                (mean - exact).abs() < 5.0 * error + 1e-3 * exact,
                "{name} {scheme:?}: {mean} vs {exact} (+-{error})"
            );
        }
    }
}

/// Each lane of a stratified package is distributed by p; the hero of a rotation package
/// too.
#[test]
fn package_lanes_have_the_documented_marginals() {
    let range = WavelengthRange::VISIBLE;
    let d = WavelengthDistribution::visible(range);
    let bins = 47;
    let samples = 100_000;
    for (scheme, lane) in [
        (PackageScheme::Stratified, 3usize),
        (PackageScheme::HeroRotation, 0),
    ] {
        let mut u = uniforms(&format!("marginal {scheme:?}"));
        let mut counts = vec![0u64; bins];
        for _ in 0..samples {
            let p = WavelengthPackage::<4>::sample(&d, u(), scheme);
            counts[(((p.lambda[lane] - 360.0) / 470.0 * bins as f32) as usize).min(bins - 1)] += 1;
        }
        let expected: Vec<f64> = (0..bins)
            .map(|b| {
                (d.cdf(360.0 + (b + 1) as f64 * 10.0) - d.cdf(360.0 + b as f64 * 10.0))
                    * samples as f64
            })
            .collect();
        assert_chi_square(&format!("lane {lane} of {scheme:?}"), &counts, &expected);
    }
}

/// A re-radiation matrix: a reflectance diagonal plus a UV-to-blue band. The sampled
/// incident wavelength given an outgoing one follows the column; outgoing given incident
/// follows the row; weight times pdf is the matrix entry.
#[test]
fn reradiation_sampling_follows_the_matrix() {
    let range = WavelengthRange::new(300.0, 800.0).unwrap();
    let bins = 50;
    let mut m = vec![0.0; bins * bins];
    for i in 0..bins {
        m[i * bins + i] = 0.5 / 10.0;
        for o in 0..bins {
            let (li, lo) = (305.0 + 10.0 * i as f64, 305.0 + 10.0 * o as f64);
            if li < 400.0 && (420.0..520.0).contains(&lo) {
                m[i * bins + o] += 0.8 * (-0.5 * ((lo - 460.0) / 20.0f64).powi(2)).exp() / 100.0;
            }
        }
    }
    let sampler = ReradiationSampler::new(range, bins, &m).unwrap();
    let samples = 100_000;
    for (label, given, incident) in [
        ("incident given 455 nm", 455.0f32, true),
        ("outgoing given 355 nm", 355.0, false),
    ] {
        let mut u = uniforms(label);
        let mut counts = vec![0u64; bins];
        for _ in 0..samples {
            let s = if incident {
                sampler.sample_incident(given, u())
            } else {
                sampler.sample_outgoing(given, u())
            }
            .unwrap();
            let (li, lo) = if incident {
                (s.lambda, given)
            } else {
                (given, s.lambda)
            };
            let entry = sampler.value(li, lo) as f32;
            let pdf = if incident {
                sampler.pdf_incident(li, lo)
            } else {
                sampler.pdf_outgoing(lo, li)
            };
            assert!((s.pdf - pdf).abs() <= 1e-6 * pdf);
            assert!(
                (s.weight * s.pdf - entry).abs() <= 1e-5 * entry.max(1e-12),
                "weight * pdf != M"
            );
            counts[sampler.bin(s.lambda).unwrap()] += 1;
        }
        let g = sampler.bin(given).unwrap();
        let line: Vec<f64> = (0..bins)
            .map(|k| {
                if incident {
                    m[k * bins + g]
                } else {
                    m[g * bins + k]
                }
            })
            .collect();
        let total: f64 = line.iter().sum();
        let expected: Vec<f64> = line.iter().map(|v| v / total * samples as f64).collect();
        assert_chi_square(label, &counts, &expected);
    }
    // A wavelength nothing re-radiates into cannot be sampled; outside the range neither.
    let empty = ReradiationSampler::new(range, 2, &[1.0, 0.0, 1.0, 0.0]).unwrap();
    assert!(empty.sample_incident(700.0, 0.5).is_none());
    assert!(sampler.sample_incident(900.0, 0.5).is_none());
    assert!(ReradiationSampler::new(range, 3, &[1.0; 8]).is_err());
}

/// Regression: the first version of the stratified scheme used the rotation scheme's
/// density (1/C) sum_k p(lambda_k) q_k. That is biased, because rotation in primary
/// sample space does not preserve wavelength measure. This shows the check above has the
/// power to see it.
#[test]
fn stratified_lanes_with_rotation_density_are_biased() {
    let range = WavelengthRange::VISIBLE;
    let d = WavelengthDistribution::visible(range);
    let f = test_spectrum(3);
    let exact = integrate(&f, 360.0, 830.0);
    let mut u = uniforms("regression stratified");
    let (mean, error) = monte_carlo(20_000, || {
        let p = WavelengthPackage::<4>::sample(&d, u(), PackageScheme::Stratified);
        let wrong = p.hero_pdf.iter().map(|&x| f64::from(x)).sum::<f64>() / 4.0;
        (0..4)
            .map(|j| f(f64::from(p.lambda[j])) / wrong)
            .sum::<f64>()
            / 4.0
    });
    assert!(
        (mean - exact).abs() > 10.0 * error,
        "the wrong density went unnoticed: {mean} vs {exact}"
    );
}
