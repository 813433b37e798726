//! Plastic (a Lambertian substrate under a dielectric coating): against Mitsuba 3's
//! `plastic` and `roughplastic` (fixture made by scene/tools/make_plastic_fixtures.py),
//! the white furnace, chi-square of its sampling, reciprocity, and finite values at the
//! extremes.

use glam::{Vec2, Vec3};
use prism_sampling::stream::{IndependentStream, SampleStream};
use prism_scene::bsdf::{Plastic, PlasticCoating};
use prism_spectrum::SampledSpectrum;
use proptest::prelude::*;

#[path = "support/albedo.rs"]
mod albedo;
#[path = "support/chi_square.rs"]
mod chi_square;
#[path = "support/directions.rs"]
mod directions;
use albedo::{albedo, split};
use chi_square::chi_square_directions;
use directions::extreme_direction;

fn fixture() -> serde_json::Value {
    serde_json::from_str(include_str!("fixtures/plastic.json")).unwrap()
}

fn vector(v: &serde_json::Value) -> Vec3 {
    let c: Vec<f32> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap() as f32)
        .collect();
    Vec3::new(c[0], c[1], c[2])
}

fn number(v: &serde_json::Value, key: &str) -> f32 {
    v[key].as_f64().unwrap() as f32
}

/// The smooth coating over a grey substrate is Mitsuba 3's `plastic`, linear and
/// nonlinear (Mitsuba's eval is f cos(theta_o) with its wo; prism's `f` is f alone), to
/// 0.3%: Mitsuba's internal reflectance is a fitted polynomial, prism's a quadrature.
#[test]
fn a_smooth_coating_is_mitsubas_plastic() {
    for case in fixture()["smooth"].as_array().unwrap() {
        let coating = PlasticCoating::new(number(case, "ior"), 0.0);
        let bsdf = Plastic::<4>::new(
            SampledSpectrum::splat(number(case, "reflectance")),
            &coating,
            case["nonlinear"].as_bool().unwrap(),
        );
        for pair in case["pairs"].as_array().unwrap() {
            let (wi, wo) = (vector(&pair["wi"]), vector(&pair["wo"]));
            let mitsuba = number(pair, "diffuse") / wo.z;
            let f = bsdf.f(wi, wo)[0];
            assert!(
                (f - mitsuba).abs() < 3e-3 * mitsuba,
                "ior {}, nonlinear {}: {f} vs Mitsuba {mitsuba} at {wi} {wo}",
                case["ior"],
                case["nonlinear"]
            );
        }
    }
}

/// What a rough coating lets through, t = 1 - E, against a quadrature of the GGX lobe
/// over the outgoing hemisphere (the fixture's, independent of the visible-normal grid
/// prism's table is made on), within the table's linear interpolation near grazing.
#[test]
fn a_rough_coating_lets_through_what_its_lobe_does_not_reflect() {
    for case in fixture()["coating"].as_array().unwrap() {
        let coating = PlasticCoating::new(number(case, "ior"), number(case, "alpha"));
        for entry in case["albedo"].as_array().unwrap() {
            let mu = number(entry, "mu");
            let expected = 1.0 - number(entry, "albedo");
            let t = coating.transmittance(mu);
            assert!(
                (t - expected).abs() < 5e-3,
                "alpha {}, ior {}, mu {mu}: t {t} vs {expected}",
                case["alpha"],
                case["ior"]
            );
        }
    }
}

fn outgoing() -> [Vec3; 4] {
    [
        Vec3::Z,
        Vec3::new(0.6, 0.3, 0.74).normalize(),
        Vec3::new(0.95, 0.0, 0.1f32.sqrt()).normalize(),
        Vec3::new(-0.3, 0.2, -0.9).normalize(),
    ]
}

/// A white substrate under any coating reflects everything: what the coating does not
/// reflect reaches the substrate and leaves again (eta^2 (1 - r_i) = 1 - E_avg), in
/// both the linear and the nonlinear form. A grey one reflects less.
#[test]
fn a_white_substrate_reflects_everything() {
    for alpha in [0.0f32, 0.0025, 0.05, 0.2, 0.5, 1.0] {
        for eta in [1.2f32, 1.49, 2.0] {
            let coating = PlasticCoating::new(eta, alpha);
            for nonlinear in [false, true] {
                let white = Plastic::new(SampledSpectrum([1.0; 4]), &coating, nonlinear);
                let grey = Plastic::new(SampledSpectrum([0.5; 4]), &coating, nonlinear);
                for wo in outgoing() {
                    let a = albedo(|w, uc, u| white.sample(w, uc, u), wo);
                    assert!(
                        (a[0] - 1.0).abs() < 0.012,
                        "alpha {alpha}, eta {eta}, nonlinear {nonlinear}, wo {wo}: {a:?}"
                    );
                    let g = albedo(|w, uc, u| grey.sample(w, uc, u), wo)[0];
                    assert!(g < a[0] && g > 0.0, "grey {g}");
                }
            }
        }
    }
}

#[test]
fn sampling_matches_its_density_and_is_reciprocal() {
    for (alpha, eta, rho) in [(0.2f32, 1.49f32, 0.8f32), (0.5, 1.8, 0.1), (0.08, 1.3, 0.5)] {
        let coating = PlasticCoating::new(eta, alpha);
        let bsdf = Plastic::new(SampledSpectrum([rho, 0.2, 0.9, 0.0]), &coating, false);
        for wo in [
            Vec3::new(0.5, 0.2, 0.84).normalize(),
            Vec3::new(0.9, 0.0, 0.2).normalize(),
        ] {
            chi_square_directions(
                &format!("plastic alpha {alpha} eta {eta}"),
                |u| {
                    let (uc, u) = split(u);
                    bsdf.sample(wo, uc, u).map(|s| s.wi)
                },
                |wi| f64::from(bsdf.pdf(wo, wi)),
            );
        }
        let mut stream = IndependentStream::new(67, 0, 0);
        for _ in 0..2000 {
            let a = prism_sampling::warp::cosine_hemisphere(stream.next_2d());
            let b = prism_sampling::warp::cosine_hemisphere(stream.next_2d());
            let (x, y) = (bsdf.f(a, b), bsdf.f(b, a));
            for k in 0..4 {
                assert!((x[k] - y[k]).abs() <= 1e-4 * x[k].abs().max(1.0));
            }
        }
    }
}

/// A smooth coating's mirror is a delta of weight F, chosen with the probability the
/// density leaves out: its sample's value over that probability, plus the diffuse lobe's
/// albedo, is the furnace's 1 (above); here, the mirror direction and the flag.
#[test]
fn a_smooth_coating_samples_its_mirror_as_a_delta() {
    let coating = PlasticCoating::new(1.5, 0.0);
    let bsdf = Plastic::<4>::new(SampledSpectrum([0.5; 4]), &coating, false);
    let wo = Vec3::new(0.6, 0.0, 0.8);
    let s = bsdf.sample(wo, 0.0, Vec2::splat(0.5)).unwrap();
    assert!(s.delta);
    assert!((s.wi - Vec3::new(-0.6, 0.0, 0.8)).length() < 1e-6);
    let diffuse = bsdf.sample(wo, 0.999_999, Vec2::splat(0.5)).unwrap();
    assert!(!diffuse.delta && diffuse.wi.z > 0.0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]
    /// No NaN or infinity leaves f, pdf or sample, for any coating and direction,
    /// grazing, zero and NaN included.
    #[test]
    fn plastic_is_total(
        alpha in prop_oneof![Just(0.0f32), Just(1e-6), Just(1.0), Just(f32::NAN), 0.0..1.0f32],
        eta in prop_oneof![Just(1.000_01f32), Just(4.0), 1.0..3.0f32],
        rho in prop_oneof![Just(0.0f32), Just(1.0), Just(f32::NAN), Just(-1.0), Just(7.0), 0.0..1.0f32],
        nonlinear in any::<bool>(),
        wo in extreme_direction(),
        wi in extreme_direction(),
        uc in 0.0..1.0f32,
        u in (0.0..1.0f32, 0.0..1.0f32),
    ) {
        let coating = PlasticCoating::new(eta, alpha);
        let bsdf = Plastic::<4>::new(SampledSpectrum::splat(rho), &coating, nonlinear);
        let f = bsdf.f(wo, wi);
        prop_assert!((0..4).all(|k| f[k].is_finite() && f[k] >= 0.0), "f {f:?}");
        let pdf = bsdf.pdf(wo, wi);
        prop_assert!(pdf.is_finite() && pdf >= 0.0, "pdf {pdf}");
        if let Some(s) = bsdf.sample(wo, uc, Vec2::new(u.0, u.1)) {
            prop_assert!(s.wi.is_finite() && (0..4).all(|k| s.f[k].is_finite() && s.pdf[k] > 0.0));
        }
    }
}
