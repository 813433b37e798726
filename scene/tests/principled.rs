//! Mitsuba's principled BSDFs (`principled`, `principledthin`): against Mitsuba 3's own
//! eval and pdf (fixture made by scene/tools/make_principled_fixtures.py), chi-square of
//! their sampling against their densities, energy bounds in a white furnace, and finite
//! values at the extremes.

use glam::{Vec2, Vec3};
use prism_scene::bsdf::{
    BsdfSample, Principled, PrincipledParams, PrincipledRates, PrincipledThin,
    PrincipledThinParams, PrincipledThinRates, TransportMode,
};
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
    serde_json::from_str(include_str!("fixtures/principled.json")).unwrap()
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

fn get(params: &serde_json::Value, key: &str, default: f32) -> f32 {
    params[key].as_f64().map_or(default, |v| v as f32)
}

fn principled_params(p: &serde_json::Value) -> PrincipledParams {
    let eta = match p["eta"].as_f64() {
        Some(e) => e as f32,
        None => {
            let s = get(p, "specular", 0.5);
            2.0 / (1.0 - (0.08 * s).sqrt()) - 1.0
        }
    };
    PrincipledParams {
        roughness: get(p, "roughness", 0.5),
        anisotropic: get(p, "anisotropic", 0.0),
        metallic: get(p, "metallic", 0.0),
        spec_trans: get(p, "spec_trans", 0.0),
        spec_tint: get(p, "spec_tint", 0.0),
        sheen: get(p, "sheen", 0.0),
        sheen_tint: get(p, "sheen_tint", 0.0),
        flatness: get(p, "flatness", 0.0),
        clearcoat: get(p, "clearcoat", 0.0),
        clearcoat_gloss: get(p, "clearcoat_gloss", 0.0),
        eta,
    }
}

fn thin_params(p: &serde_json::Value) -> PrincipledThinParams {
    PrincipledThinParams {
        roughness: get(p, "roughness", 0.5),
        anisotropic: get(p, "anisotropic", 0.0),
        spec_trans: get(p, "spec_trans", 0.0),
        spec_tint: get(p, "spec_tint", 0.0),
        sheen: get(p, "sheen", 0.0),
        sheen_tint: get(p, "sheen_tint", 0.0),
        flatness: get(p, "flatness", 0.0),
        diff_trans: get(p, "diff_trans", 0.0),
        eta: get(p, "eta", 1.5),
    }
}

/// The fixture's colour as three lanes (a fourth, unused).
fn base(f: &serde_json::Value) -> (SampledSpectrum<4>, f32) {
    let b = vector(&f["base"]);
    (
        SampledSpectrum([b.x, b.y, b.z, 0.0]),
        f["luminance"].as_f64().unwrap() as f32,
    )
}

/// Mitsuba's eval is f cos(theta_o) with its wo (prism's wi); its wi is prism's wo.
fn compare(
    name: &str,
    case: &serde_json::Value,
    f: impl Fn(Vec3, Vec3) -> SampledSpectrum<4>,
    pdf: impl Fn(Vec3, Vec3) -> f32,
) {
    for pair in case["pairs"].as_array().unwrap() {
        let (wo, wi) = (vector(&pair["wi"]), vector(&pair["wo"]));
        let value = f(wo, wi);
        for k in 0..3 {
            let mitsuba = pair["eval"][k].as_f64().unwrap() as f32;
            let ours = value[k] * wi.z.abs();
            assert!(
                (ours - mitsuba).abs() <= 2e-3 * mitsuba.abs() + 1e-5,
                "{name} {}: channel {k}: {ours} vs Mitsuba {mitsuba} at wo {wo} wi {wi}",
                case["params"]
            );
        }
        let mitsuba = pair["pdf"].as_f64().unwrap() as f32;
        let ours = pdf(wo, wi);
        assert!(
            (ours - mitsuba).abs() <= 2e-3 * mitsuba.abs() + 1e-5,
            "{name} {}: pdf {ours} vs Mitsuba {mitsuba} at wo {wo} wi {wi}",
            case["params"]
        );
    }
}

#[test]
fn principled_is_mitsubas() {
    let f = fixture();
    let (b, lum) = base(&f);
    for case in f["principled"].as_array().unwrap() {
        let bsdf = Principled::new(
            b,
            lum,
            principled_params(&case["params"]),
            PrincipledRates::default(),
            TransportMode::Radiance,
        );
        compare(
            "principled",
            case,
            |o, i| bsdf.f(o, i),
            |o, i| bsdf.pdf(o, i),
        );
    }
}

#[test]
fn principled_thin_is_mitsubas() {
    let f = fixture();
    let (b, lum) = base(&f);
    for case in f["principledthin"].as_array().unwrap() {
        let bsdf = PrincipledThin::new(
            b,
            lum,
            thin_params(&case["params"]),
            PrincipledThinRates::default(),
        );
        compare(
            "principledthin",
            case,
            |o, i| bsdf.f(o, i),
            |o, i| bsdf.pdf(o, i),
        );
    }
}

/// Parameter sets that turn each lobe on, for the sampling and energy tests.
fn principled_sets() -> Vec<PrincipledParams> {
    let base = PrincipledParams {
        roughness: 0.5,
        anisotropic: 0.0,
        metallic: 0.0,
        spec_trans: 0.0,
        spec_tint: 0.0,
        sheen: 0.0,
        sheen_tint: 0.0,
        flatness: 0.0,
        clearcoat: 0.0,
        clearcoat_gloss: 0.0,
        eta: 1.5,
    };
    vec![
        base,
        PrincipledParams {
            metallic: 0.6,
            roughness: 0.3,
            clearcoat: 0.9,
            clearcoat_gloss: 0.3,
            ..base
        },
        PrincipledParams {
            spec_trans: 0.7,
            roughness: 0.35,
            sheen: 0.5,
            eta: 1.33,
            ..base
        },
        PrincipledParams {
            anisotropic: 0.8,
            roughness: 0.4,
            spec_trans: 0.3,
            flatness: 0.5,
            ..base
        },
    ]
}

fn thin_sets() -> Vec<PrincipledThinParams> {
    let base = PrincipledThinParams {
        roughness: 0.5,
        anisotropic: 0.0,
        spec_trans: 0.0,
        spec_tint: 0.0,
        sheen: 0.0,
        sheen_tint: 0.0,
        flatness: 0.0,
        diff_trans: 0.0,
        eta: 1.5,
    };
    vec![
        base,
        PrincipledThinParams {
            spec_trans: 0.6,
            roughness: 0.35,
            diff_trans: 0.8,
            eta: 1.33,
            ..base
        },
        PrincipledThinParams {
            spec_trans: 0.4,
            anisotropic: 0.7,
            roughness: 0.4,
            diff_trans: 1.6,
            sheen: 0.4,
            ..base
        },
    ]
}

fn grey() -> SampledSpectrum<4> {
    SampledSpectrum([0.8, 0.5, 0.3, 1.0])
}

#[test]
fn principled_samples_its_density() {
    let wos = [
        Vec3::new(0.3, 0.1, 0.95),
        Vec3::new(0.8, -0.2, 0.4),
        Vec3::new(-0.5, 0.3, -0.7),
    ];
    for (s, p) in principled_sets().into_iter().enumerate() {
        let bsdf = Principled::new(
            grey(),
            0.5,
            p,
            PrincipledRates::default(),
            TransportMode::Radiance,
        )
        .with_axis(Vec2::new(0.6, 0.8));
        for (k, wo) in wos.iter().enumerate() {
            let wo = wo.normalize();
            // From the back only a transmissive share samples anything.
            if wo.z < 0.0 && p.spec_trans == 0.0 {
                continue;
            }
            chi_square_directions(
                &format!("principled set {s} wo {k}"),
                |u| {
                    let (uc, u) = split(u);
                    bsdf.sample(wo, uc, u).map(|s| s.wi)
                },
                |wi| f64::from(bsdf.pdf(wo, wi)),
            );
        }
    }
}

#[test]
fn principled_thin_samples_its_density() {
    for (s, p) in thin_sets().into_iter().enumerate() {
        let bsdf = PrincipledThin::new(grey(), 0.5, p, PrincipledThinRates::default())
            .with_axis(Vec2::new(0.0, 1.0));
        for (k, wo) in [Vec3::new(0.3, 0.1, 0.95), Vec3::new(-0.7, 0.2, -0.5)]
            .iter()
            .enumerate()
        {
            let wo = wo.normalize();
            chi_square_directions(
                &format!("principledthin set {s} wo {k}"),
                |u| {
                    let (uc, u) = split(u);
                    bsdf.sample(wo, uc, u).map(|s| s.wi)
                },
                |wi| f64::from(bsdf.pdf(wo, wi)),
            );
        }
    }
}

/// A sample's weight is f cos / pdf of the same f and pdf (what the estimator relies on).
fn consistent(s: &BsdfSample<4>, f: SampledSpectrum<4>, pdf: f32) {
    assert!(
        (s.pdf[0] - pdf).abs() <= 1e-4 * pdf,
        "{} vs {pdf}",
        s.pdf[0]
    );
    for k in 0..4 {
        assert!((s.f[k] - f[k]).abs() <= 1e-4 * f[k].abs() + 1e-6);
    }
}

/// In a white furnace the lobes that conserve energy reflect at most what they receive:
/// a white metal (GGX single scattering: less than 1), a clear dielectric's reflection
/// and transmission together (importance transport: no 1 / eta^2), Burley's diffuse at
/// roughness 0 (its retro-reflection off) with the dielectric's reflection on top, and a
/// thin sheet of each lobe. Burley's
/// retro-reflection and sheen add energy by design (2012 notes §5.3), so the whole model
/// is bounded loosely: below 1.25 at every roughness.
#[test]
fn white_furnace_bounds() {
    let white = SampledSpectrum::splat(1.0);
    let mut p = principled_sets()[0];
    let at = |p: PrincipledParams, wo: Vec3| {
        let bsdf = Principled::new(
            white,
            1.0,
            p,
            PrincipledRates::default(),
            TransportMode::Importance,
        );
        if let Some(s) = bsdf.sample(wo, 0.5, Vec2::new(0.3, 0.6)) {
            consistent(&s, bsdf.f(wo, s.wi), bsdf.pdf(wo, s.wi));
        }
        albedo(|wo, uc, u| bsdf.sample(wo, uc, u), wo)[0]
    };
    for wo in [
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.6, 0.0, 0.8),
        Vec3::new(0.95, 0.0, 0.312),
    ] {
        let wo = wo.normalize();
        for roughness in [0.05, 0.3, 0.7, 1.0] {
            p.roughness = roughness;
            let metal = at(PrincipledParams { metallic: 1.0, ..p }, wo);
            // Single scattering loses what bounces twice: much at roughness 1.
            let low = if roughness < 0.5 { 0.8 } else { 0.2 };
            assert!(
                metal <= 1.005 && metal > low,
                "metal {roughness} {wo}: {metal}"
            );
            let glass = at(
                PrincipledParams {
                    spec_trans: 1.0,
                    ..p
                },
                wo,
            );
            assert!(
                glass <= 1.005 && glass > low,
                "glass {roughness} {wo}: {glass}"
            );
            let all = at(
                PrincipledParams {
                    sheen: 1.0,
                    clearcoat: 1.0,
                    ..p
                },
                wo,
            );
            assert!(all <= 1.25, "whole model {roughness} {wo}: {all}");
        }
        // Burley adds the dielectric's reflection (4% at normal incidence) to the diffuse
        // lobe without taking it from it: at most 1 + F over.
        p.roughness = 0.0;
        let diffuse = at(p, wo);
        let bound = 1.005 + f64::from(prism_scene::bsdf::fresnel_dielectric(wo.z, 1.5));
        assert!(
            diffuse <= bound && diffuse > 0.7,
            "diffuse {wo}: {diffuse} > {bound}"
        );
        for thin in [
            PrincipledThinParams {
                roughness: 0.0,
                ..thin_sets()[0]
            },
            PrincipledThinParams {
                roughness: 0.0,
                diff_trans: 2.0,
                ..thin_sets()[0]
            },
            PrincipledThinParams {
                spec_trans: 1.0,
                roughness: 0.3,
                ..thin_sets()[0]
            },
        ] {
            let bsdf = PrincipledThin::new(white, 1.0, thin, PrincipledThinRates::default());
            let a = albedo(|wo, uc, u| bsdf.sample(wo, uc, u), wo)[0];
            assert!(a <= 1.005 && a > 0.5, "thin {thin:?} {wo}: {a}");
        }
    }
}

fn unit_or_extreme() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0f32),
        Just(1.0),
        Just(1e-30),
        Just(-1.0),
        Just(2.0),
        Just(f32::NAN),
        Just(f32::INFINITY),
        0.0..1.0f32
    ]
}

proptest! {
    #[test]
    fn principled_values_stay_finite(
        wo in extreme_direction(),
        wi in extreme_direction(),
        r in unit_or_extreme(),
        a in unit_or_extreme(),
        m in unit_or_extreme(),
        t in unit_or_extreme(),
        c in unit_or_extreme(),
        eta in prop_oneof![Just(1.0f32), Just(1e-6), Just(1e6), Just(f32::NAN), 0.5..3.0f32],
        uc in 0.0..1.0f32,
        u in (0.0..1.0f32, 0.0..1.0f32),
    ) {
        let p = PrincipledParams {
            roughness: r, anisotropic: a, metallic: m, spec_trans: t, spec_tint: c,
            sheen: c, sheen_tint: r, flatness: a, clearcoat: c, clearcoat_gloss: r, eta,
        };
        let b = Principled::new(grey(), 0.4, p, PrincipledRates::default(), TransportMode::Radiance);
        prop_assert!(b.f(wo, wi).0.iter().all(|v| v.is_finite() && *v >= 0.0));
        let pdf = b.pdf(wo, wi);
        prop_assert!(pdf.is_finite() && pdf >= 0.0);
        if let Some(s) = b.sample(wo, uc, Vec2::new(u.0, u.1)) {
            prop_assert!(s.wi.is_finite() && s.pdf[0].is_finite() && s.pdf[0] > 0.0);
            prop_assert!(s.f.0.iter().all(|v| v.is_finite() && *v >= 0.0));
        }
        let q = PrincipledThinParams {
            roughness: r, anisotropic: a, spec_trans: t, spec_tint: c, sheen: c,
            sheen_tint: r, flatness: a, diff_trans: m * 2.0, eta,
        };
        let b = PrincipledThin::new(grey(), 0.4, q, PrincipledThinRates::default());
        prop_assert!(b.f(wo, wi).0.iter().all(|v| v.is_finite() && *v >= 0.0));
        let pdf = b.pdf(wo, wi);
        prop_assert!(pdf.is_finite() && pdf >= 0.0);
        if let Some(s) = b.sample(wo, uc, Vec2::new(u.0, u.1)) {
            prop_assert!(s.wi.is_finite() && s.pdf[0].is_finite() && s.pdf[0] > 0.0);
            prop_assert!(s.f.0.iter().all(|v| v.is_finite() && *v >= 0.0));
        }
    }
}
