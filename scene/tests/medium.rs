//! Media: phase-function samplers against their densities (chi-square), the tracking
//! estimators of transmittance against exp(-tau), and the extremes (no NaN or infinity
//! out of any public function, whatever the coefficients).

#[path = "support/chi_square.rs"]
mod chi_square;
use chi_square::{chi_square_directions, chi_square_p_value};

use glam::{Vec2, Vec3};
use prism_sampling::stream::{IndependentStream, SampleStream};
use prism_scene::geometry::Ray;
use prism_scene::medium::track::{sample_majorant, transmittance};
use prism_scene::medium::{Grid, Media, Medium, Phase};
use prism_scene::world::SceneSpectrum;
use prism_spectrum::{SampledSpectrum, SampledWavelengths};
use proptest::prelude::*;

/// Directions of travel to scatter from: the pole, the equator, and oblique ones.
fn incoming_directions() -> Vec<Vec3> {
    vec![
        Vec3::Z,
        -Vec3::Z,
        Vec3::X,
        Vec3::new(0.3, -0.5, 0.8).normalize(),
        Vec3::new(-0.9, 0.1, -0.2).normalize(),
    ]
}

fn phases() -> Vec<(String, Phase)> {
    let mut out: Vec<(String, Phase)> = [-0.7, -0.3, 0.0, 5e-4, 0.5, 0.9]
        .into_iter()
        .map(|g| (format!("hg {g}"), Phase::henyey_greenstein(g).unwrap()))
        .collect();
    out.push(("rayleigh".into(), Phase::Rayleigh));
    out
}

#[test]
fn phase_sampling_matches_its_density() {
    for (name, phase) in phases() {
        for (k, incoming) in incoming_directions().into_iter().enumerate() {
            // The harness's grid is uniform in z: a lobe as narrow as g = 0.9's (0.01 wide
            // in cos theta) around a pole falls between its quadrature points, so the
            // narrow lobe is tested around the equator, where the grid resolves it.
            if phase.mean_cosine() > 0.8 && incoming.z.abs() > 0.5 {
                continue;
            }
            chi_square_directions(
                &format!("{name} incoming {k}"),
                |u| Some(phase.sample(incoming, u).outgoing),
                |w| f64::from(phase.eval(incoming, w)),
            );
        }
    }
}

/// The harness has power: forward Henyey-Greenstein samples judged against the isotropic
/// density, and Rayleigh's against a Henyey-Greenstein of the same mean cosine, fail.
#[test]
fn chi_square_rejects_a_wrong_phase_density() {
    let hg = Phase::henyey_greenstein(0.3).unwrap();
    let p = chi_square_p_value(
        "hg against isotropic",
        |u| Some(hg.sample(Vec3::Z, u).outgoing),
        |_| 1.0 / (4.0 * std::f64::consts::PI),
    );
    assert!(p < 1e-12, "p = {p}");
    let p = chi_square_p_value(
        "rayleigh against isotropic",
        |u| Some(Phase::Rayleigh.sample(Vec3::Z, u).outgoing),
        |_| 1.0 / (4.0 * std::f64::consts::PI),
    );
    assert!(p < 1e-12, "p = {p}");
}

/// Each phase function integrates to 1 over the sphere, has the mean cosine it says, and
/// its samples' p equals its density (p / pdf = 1 at every wavelength).
#[test]
fn phase_functions_are_normalized_with_their_mean_cosine() {
    for (name, phase) in phases() {
        let n = 200_000;
        let (mut integral, mut mean_cos) = (0.0f64, 0.0f64);
        for i in 0..n {
            // Midpoint rule in cos theta (p depends on cos theta alone).
            let c = -1.0 + (i as f64 + 0.5) * 2.0 / n as f64;
            let p = f64::from(phase.p(c as f32)) * std::f64::consts::TAU * 2.0 / n as f64;
            integral += p;
            mean_cos += p * c;
        }
        assert!((integral - 1.0).abs() < 1e-3, "{name}: integral {integral}");
        let expected = f64::from(phase.mean_cosine());
        assert!(
            (mean_cos - expected).abs() < 2e-3,
            "{name}: mean cosine {mean_cos}"
        );
        let mut stream = IndependentStream::new(3, 0, 0);
        for _ in 0..1000 {
            let s = phase.sample(Vec3::Y, stream.next_2d());
            assert_eq!(s.p, s.pdf);
            assert!((s.outgoing.length() - 1.0).abs() < 1e-4);
            let eval = phase.eval(Vec3::Y, s.outgoing);
            assert!(
                (eval - s.p).abs() <= 1e-3 * s.p,
                "{name}: {eval} vs {}",
                s.p
            );
        }
    }
}

fn wavelengths() -> SampledWavelengths<4> {
    SampledWavelengths::new([420.0, 500.0, 580.0, 660.0], [1.0 / 300.0; 4]).unwrap()
}

/// sigma rising linearly from `lo` at 400 nm to `hi` at 700 nm.
fn linear(lo: f64, hi: f64) -> SceneSpectrum {
    SceneSpectrum::Table(std::sync::Arc::new(
        prism_spectrum::spectra::PiecewiseLinear::new(
            vec![400.0, 700.0],
            vec![lo, hi],
            prism_spectrum::spectra::Extrapolation::Clamp,
        )
        .unwrap(),
    ))
}

/// Delta tracking (the hero's collisions, each real with probability sigma_t / sigma_maj)
/// and ratio tracking (the product of sigma_n / sigma_maj over the collisions, every lane)
/// are unbiased estimators of exp(-sigma_t d), in a medium whose majorant exceeds its
/// extinction (an emissive one: its floor) and in one where they are equal.
#[test]
fn tracking_estimates_transmittance_without_bias() {
    let lambdas = wavelengths();
    let emission = Some(SceneSpectrum::Constant(1.0));
    for (name, medium, d) in [
        (
            "floored",
            Medium::new(
                linear(0.1, 0.4),
                linear(0.2, 0.1),
                Phase::Rayleigh,
                emission,
            )
            .unwrap(),
            1.7f32,
        ),
        (
            "tight",
            Medium::new(
                linear(0.5, 2.0),
                SceneSpectrum::Constant(0.0),
                Phase::henyey_greenstein(0.0).unwrap(),
                None,
            )
            .unwrap(),
            0.8,
        ),
    ] {
        let point = medium.at(&lambdas);
        let sigma_t = point.sigma_a + point.sigma_s;
        let exact = transmittance(&sigma_t, d);
        let mut stream = IndependentStream::new(11, 0, 0);
        let n = 200_000u64;
        let (mut delta, mut ratio) = (0.0f64, [0.0f64; 4]);
        let (mut delta_sq, mut ratio_sq) = (0.0f64, [0.0f64; 4]);
        for i in 0..n {
            // Delta tracking with the hero lane: survives if every collision is null.
            let mut survived = true;
            let u = stream.next_1d();
            let mut numbers = IndependentStream::new(12, 0, i);
            let mut kinds = IndependentStream::new(13, 0, i);
            let tail = sample_majorant(
                &medium,
                &Ray::new(Vec3::ZERO, Vec3::Z, d),
                u,
                &mut || numbers.next_1d(),
                &lambdas,
                |c| {
                    let sigma_n = c.sigma_maj[0] - c.point.sigma_a[0] - c.point.sigma_s[0];
                    if kinds.next_1d() * c.sigma_maj[0] >= sigma_n {
                        survived = false;
                    }
                    survived
                },
            );
            assert!(tail.0.iter().all(|t| t.is_finite()));
            let x = if survived { 1.0 } else { 0.0 };
            delta += x;
            delta_sq += x * x;
            // Ratio tracking, every lane by the hero's majorant.
            let mut t = SampledSpectrum::<4>::splat(1.0);
            let u = stream.next_1d();
            let tail = sample_majorant(
                &medium,
                &Ray::new(Vec3::ZERO, Vec3::Z, d),
                u,
                &mut || stream.next_1d(),
                &lambdas,
                |c| {
                    let hero = c.t_maj[0] * c.sigma_maj[0];
                    t *= SampledSpectrum::from_fn(|j| {
                        c.t_maj[j] * (c.sigma_maj[j] - c.point.sigma_a[j] - c.point.sigma_s[j])
                    }) / hero;
                    true
                },
            );
            let t = t * tail / tail[0];
            for j in 0..4 {
                let x = f64::from(t[j]);
                ratio[j] += x;
                ratio_sq[j] += x * x;
            }
        }
        let n = n as f64;
        let check = |what: &str, sum: f64, sum_sq: f64, expected: f32| {
            let mean = sum / n;
            let error = ((sum_sq / n - mean * mean).max(0.0) / n).sqrt();
            let expected = f64::from(expected);
            assert!(
                (mean - expected).abs() < 5.0 * error + 1e-4,
                "{name} {what}: {mean} vs exp(-tau) = {expected} (+-{error})"
            );
        };
        check("delta tracking", delta, delta_sq, exact[0]);
        for j in 0..4 {
            check(
                &format!("ratio tracking lane {j}"),
                ratio[j],
                ratio_sq[j],
                exact[j],
            );
        }
    }
}

/// Media are checked where they are made: negative or non-finite coefficients, |g| >= 1
/// and indices naming no medium are errors, never a medium that renders NaN.
#[test]
fn bad_media_are_errors() {
    let phase = Phase::henyey_greenstein(0.0).unwrap();
    let c = SceneSpectrum::Constant;
    assert!(Medium::new(c(-1.0), c(0.0), phase, None).is_err());
    assert!(Medium::new(c(0.0), c(f64::NAN), phase, None).is_err());
    assert!(Medium::new(c(0.0), c(f64::INFINITY), phase, None).is_err());
    assert!(Medium::new(c(0.0), c(1.0), phase, Some(c(-2.0))).is_err());
    for g in [1.0, -1.0, 1.5, f64::NAN, f64::INFINITY] {
        assert!(Phase::henyey_greenstein(g).is_err(), "g = {g}");
    }
    let medium = Medium::new(c(1.0), c(1.0), phase, None).unwrap();
    assert!(Media::new(vec![medium.clone()], vec![Some(1)], None).is_err());
    assert!(Media::new(vec![medium.clone()], vec![], Some(3)).is_err());
    assert!(Media::new(vec![medium], vec![None, Some(0)], Some(0)).is_ok());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Phase functions give finite, non-negative values and unit directions for every g a
    /// scene may give (up to |g| = 0.999), every cosine (NaN too) and every random number.
    #[test]
    fn phase_functions_stay_finite(
        g in -0.999f64..=0.999,
        cos in prop_oneof![-1.5f32..1.5, Just(f32::NAN), Just(1.0f32), Just(-1.0f32)],
        u in prop_oneof![
            (0.0f32..1.0, 0.0f32..1.0).prop_map(|(a, b)| Vec2::new(a, b)),
            Just(Vec2::new(0.0, 0.0)),
            Just(Vec2::new(1.0 - f32::EPSILON, 1.0 - f32::EPSILON)),
            Just(Vec2::new(f32::NAN, 0.5)),
        ],
        x in -1.0f32..1.0, y in -1.0f32..1.0, z in -1.0f32..1.0,
    ) {
        let incoming = Vec3::new(x, y, z).try_normalize().unwrap_or(Vec3::Z);
        for phase in [Phase::henyey_greenstein(g).unwrap(), Phase::Rayleigh] {
            let p = phase.p(cos);
            prop_assert!(p.is_finite() && p >= 0.0, "{phase:?} p({cos}) = {p}");
            let s = phase.sample(incoming, u);
            prop_assert!(s.p.is_finite() && s.p > 0.0, "{phase:?}: {s:?}");
            prop_assert!((s.outgoing.length() - 1.0).abs() < 1e-3, "{phase:?}: {s:?}");
        }
    }

    /// Tracking through coefficients from 0 to 1e8 per unit, over distances from 0 to
    /// infinity, ends, and gives finite majorant transmittances in [0, 1] with collisions
    /// inside the segment.
    #[test]
    fn tracking_stays_finite_at_the_extremes(
        sigma_a in prop_oneof![Just(0.0f64), Just(1e-8), Just(1e8), 0.0f64..1e3],
        sigma_s in prop_oneof![Just(0.0f64), Just(1e-8), Just(1e8), 0.0f64..1e3],
        emissive in any::<bool>(),
        d in prop_oneof![Just(0.0f32), Just(f32::INFINITY), Just(f32::NAN), 0.0f32..1e4],
        u in 0.0f32..1.0,
    ) {
        let c = SceneSpectrum::Constant;
        let medium = Medium::new(
            c(sigma_a),
            c(sigma_s),
            Phase::Rayleigh,
            emissive.then(|| c(1.0)),
        ).unwrap();
        // The same medium through an empty grid, and through one of a single dense voxel.
        let empty = medium.clone().with_density(
            Grid::new(glam::UVec3::splat(3), Vec3::splat(-1.0), Vec3::splat(1.0), vec![0.0; 27]).unwrap(),
        );
        let single = medium.clone().with_density(
            Grid::new(glam::UVec3::ONE, Vec3::splat(-1.0), Vec3::splat(1.0), vec![1e8]).unwrap(),
        );
        for m in [&empty, &single] {
            let mut stream = IndependentStream::new(4, 5, 6);
            let mut collisions = 0u32;
            let tail = sample_majorant(m, &Ray::new(Vec3::new(-2.0, 0.1, 0.2), Vec3::X, d), u, &mut || stream.next_1d(), &wavelengths(), |c| {
                collisions += 1;
                assert!(c.point.sigma_a.0.iter().chain(&c.point.sigma_s.0).all(|s| s.is_finite()));
                collisions < 64
            });
            prop_assert!(tail.0.iter().all(|t| t.is_finite() && (0.0..=1.0).contains(t)), "{tail:?}");
        }
        let lambdas = wavelengths();
        let mut stream = IndependentStream::new(1, 2, 3);
        let mut collisions = 0u32;
        let tail = sample_majorant(&medium, &Ray::new(Vec3::ZERO, Vec3::X, d), u, &mut || stream.next_1d(), &lambdas, |c| {
            collisions += 1;
            assert!(c.t.is_finite() && c.t >= 0.0);
            assert!(c.t_maj.0.iter().all(|t| (0.0..=1.0).contains(t)));
            // Stop after a while: a majorant of 1e8 over 1e4 units collides 1e12 times.
            collisions < 64
        });
        prop_assert!(tail.0.iter().all(|t| t.is_finite() && (0.0..=1.0).contains(t)), "{tail:?}");
        for sigma in [0.0f32, 1e-8, 1e8, f32::INFINITY] {
            let t = transmittance(&SampledSpectrum::<4>::splat(sigma), d);
            prop_assert!(t.0.iter().all(|t| t.is_finite() && (0.0..=1.0).contains(t)), "{sigma} {d}: {t:?}");
        }
    }
}

/// A smooth blob of smoke on a 24^3 grid over [-1, 1]^3: density 3 exp(-4 r^2) at the
/// voxel centres (`wisp`: a thin shell of it only, 0 elsewhere).
fn blob(wisp: bool) -> Grid {
    let n = 24u32;
    let values = (0..n * n * n)
        .map(|i| {
            let c = glam::UVec3::new(i % n, (i / n) % n, i / (n * n)).as_vec3();
            let p = (c + 0.5) / n as f32 * 2.0 - 1.0;
            let r = p.length();
            if wisp {
                if (r - 0.6).abs() < 0.05 && p.y > 0.3 {
                    2.0
                } else {
                    0.0
                }
            } else {
                3.0 * (-4.0 * r * r).exp()
            }
        })
        .collect();
    Grid::new(
        glam::UVec3::splat(n),
        Vec3::splat(-1.0),
        Vec3::splat(1.0),
        values,
    )
    .unwrap()
}

/// The optical depth along `ray` through `medium`'s grid per lane, by a fine midpoint rule
/// over the grid's own lookups (independent of the majorant grid and the tracker).
fn optical_depth(
    medium: &Medium,
    ray: &Ray,
    lambdas: &SampledWavelengths<4>,
) -> SampledSpectrum<4> {
    let base = medium.at(lambdas);
    let steps = 20_000;
    let dt = ray.t_max / steps as f32;
    let integral: f64 = (0..steps)
        .map(|i| {
            f64::from(
                medium
                    .density()
                    .unwrap()
                    .lookup(ray.origin + ray.direction * (i as f32 + 0.5) * dt),
            )
        })
        .sum::<f64>()
        * f64::from(dt);
    (base.sigma_a + base.sigma_s) * integral as f32
}

/// Ratio tracking through a heterogeneous medium, stepping through the coarse majorant
/// grid, is an unbiased estimator of exp(-tau) per lane, tau the integral of sigma_t d(p).
#[test]
fn grid_tracking_estimates_transmittance_without_bias() {
    let lambdas = wavelengths();
    let medium = Medium::new(
        linear(0.3, 1.2),
        linear(0.8, 0.2),
        Phase::henyey_greenstein(0.2).unwrap(),
        None,
    )
    .unwrap()
    .with_density(blob(false));
    for (k, ray) in [
        Ray::new(Vec3::new(-1.5, 0.1, 0.0), Vec3::X, 3.0),
        Ray::new(
            Vec3::new(0.3, -2.0, -0.2),
            Vec3::new(0.1, 1.0, 0.2).normalize(),
            4.0,
        ),
        Ray::new(
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 1.0).normalize(),
            2.5,
        ),
    ]
    .into_iter()
    .enumerate()
    {
        let exact = transmittance(&optical_depth(&medium, &ray, &lambdas), 1.0);
        let n = 100_000u64;
        let (mut sum, mut sum_sq) = ([0.0f64; 4], [0.0f64; 4]);
        let mut stream = IndependentStream::new(21, k as u64, 0);
        for _ in 0..n {
            let mut t = SampledSpectrum::<4>::splat(1.0);
            let u = stream.next_1d();
            let tail = sample_majorant(&medium, &ray, u, &mut || stream.next_1d(), &lambdas, |c| {
                let hero = c.t_maj[0] * c.sigma_maj[0];
                t *= SampledSpectrum::from_fn(|j| {
                    c.t_maj[j] * (c.sigma_maj[j] - c.point.sigma_a[j] - c.point.sigma_s[j])
                }) / hero;
                true
            });
            let t = t * tail / tail[0];
            for j in 0..4 {
                sum[j] += f64::from(t[j]);
                sum_sq[j] += f64::from(t[j]).powi(2);
            }
        }
        for j in 0..4 {
            let mean = sum[j] / n as f64;
            let error = ((sum_sq[j] / n as f64 - mean * mean).max(0.0) / n as f64).sqrt();
            let expected = f64::from(exact[j]);
            assert!(
                (mean - expected).abs() < 5.0 * error + 1e-3,
                "ray {k} lane {j}: {mean} vs exp(-tau) = {expected} (+-{error})"
            );
        }
    }
}

/// A wisp in a big box costs what the wisp holds: tentative collisions along rays through
/// a thin shell of smoke, drawn against the coarse majorant grid, against the same grid
/// with one global majorant (the densest voxel's everywhere). Prints both counts.
#[test]
fn a_wisp_costs_what_it_holds_not_its_densest_voxel() {
    let lambdas = wavelengths();
    let base = Medium::new(
        SceneSpectrum::Constant(0.5),
        SceneSpectrum::Constant(2.0),
        Phase::Rayleigh,
        None,
    )
    .unwrap();
    let count = |grid: Grid| {
        let medium = base.clone().with_density(grid);
        let mut stream = IndependentStream::new(5, 0, 0);
        let mut collisions = 0u64;
        for i in 0..2000 {
            let a = i as f32 * 0.618;
            let origin = Vec3::new(-2.0, 0.9 * (a.sin()), 0.9 * (a * 1.7).cos());
            let ray = Ray::new(origin, Vec3::X, 4.0);
            let u = stream.next_1d();
            sample_majorant(&medium, &ray, u, &mut || stream.next_1d(), &lambdas, |_| {
                collisions += 1;
                true
            });
        }
        collisions
    };
    let coarse = count(blob(true));
    let global = count(blob(true).with_majorant_cells(1));
    eprintln!(
        "tentative collisions over 2000 rays: majorant grid {coarse}, one global majorant {global}"
    );
    assert!(coarse * 4 < global, "{coarse} vs {global}");
}
