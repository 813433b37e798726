//! Mueller matrices against Mitsuba 3 (an independent implementation; fixture made by
//! scene/tools/make_mueller_fixtures.py) and against closed forms, and the validity of
//! every matrix at the extremes.

use num_complex::Complex64;
use prism_scene::glam::{Vec3, Vec4, Vec4Swizzles};
use prism_scene::polarization::{Mueller, Stokes, fresnel_amplitudes, rotate_frame};
use proptest::prelude::*;

fn fixture() -> serde_json::Value {
    serde_json::from_str(include_str!("fixtures/mueller_mitsuba3.json")).unwrap()
}

fn rows(value: &serde_json::Value) -> [[f32; 4]; 4] {
    let mut out = [[0.0; 4]; 4];
    for (r, row) in value.as_array().unwrap().iter().enumerate() {
        for (c, v) in row.as_array().unwrap().iter().enumerate() {
            out[r][c] = v.as_f64().unwrap() as f32;
        }
    }
    out
}

fn assert_close(ours: &Mueller, theirs: [[f32; 4]; 4], what: &str) {
    let ours = ours.rows();
    for r in 0..4 {
        for c in 0..4 {
            assert!(
                (ours[r][c] - theirs[r][c]).abs() < 2e-5,
                "{what}: entry ({r}, {c}) is {} where Mitsuba 3 has {}\nours {ours:?}\ntheirs {theirs:?}",
                ours[r][c],
                theirs[r][c]
            );
        }
    }
}

fn number(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap()
}

#[test]
fn reflection_and_transmission_match_mitsuba_3() {
    let data = fixture();
    let mut count = 0;
    for case in data["reflection"].as_array().unwrap() {
        let (cos, eta) = (number(&case["cos_i"]), &case["eta"]);
        let eta = Complex64::new(number(&eta[0]), number(&eta[1]));
        let m = Mueller::reflection(&fresnel_amplitudes(cos, eta));
        assert_close(
            &m,
            rows(&case["m"]),
            &format!("reflection cos {cos} eta {eta}"),
        );
        count += 1;
    }
    for case in data["transmission"].as_array().unwrap() {
        let (cos, eta) = (number(&case["cos_i"]), number(&case["eta"]));
        let m = Mueller::transmission(&fresnel_amplitudes(cos, Complex64::new(eta, 0.0)));
        assert_close(
            &m,
            rows(&case["m"]),
            &format!("transmission cos {cos} eta {eta}"),
        );
        count += 1;
    }
    assert!(count > 100);
}

#[test]
fn elements_and_frame_rotations_match_mitsuba_3() {
    let data = fixture();
    for case in data["elements"].as_array().unwrap() {
        let kind = case["kind"].as_str().unwrap();
        let v = &case["value"];
        let ours = match kind {
            "rotator" => Mueller::rotator(number(v) as f32),
            "rotated_polarizer" => {
                Mueller::rotated(number(v) as f32, &Mueller::linear_polarizer(1.0))
            }
            "retarder" => Mueller::linear_retarder(number(v) as f32),
            "polarizer" => Mueller::linear_polarizer(number(v) as f32),
            "depolarizer" => Mueller::depolarizer(number(v) as f32),
            "diattenuator" => Mueller::diattenuator(number(&v[0]) as f32, number(&v[1]) as f32),
            other => panic!("unknown element {other}"),
        };
        assert_close(&ours, rows(&case["m"]), &format!("{kind} {v}"));
    }
    let vector = |v: &serde_json::Value| {
        Vec3::new(
            number(&v[0]) as f32,
            number(&v[1]) as f32,
            number(&v[2]) as f32,
        )
    };
    for case in data["frames"].as_array().unwrap() {
        let m = rotate_frame(
            vector(&case["w"]),
            vector(&case["from"]),
            vector(&case["to"]),
        );
        assert_close(&m, rows(&case["m"]), &format!("frame {case}"));
    }
}

/// Brewster's angle: p-polarized light is not reflected at tan(theta_B) = n (Born and
/// Wolf §1.5.3), so unpolarized light reflects fully s-polarized there.
#[test]
fn reflection_at_brewsters_angle_is_fully_s_polarized() {
    for n in [1.33, 1.5, 1.9] {
        let cos_b = (1.0f64 / (1.0 + n * n)).sqrt();
        let r = fresnel_amplitudes(cos_b, Complex64::new(n, 0.0));
        assert!(
            r.p.norm_sqr() < 1e-12,
            "R_p = {} at Brewster's angle",
            r.p.norm_sqr()
        );
        let reflected = Mueller::reflection(&r).apply(Stokes::unpolarized(1.0));
        assert!((reflected.degree_linear() - 1.0).abs() < 1e-5);
        assert!(reflected.0.y > 0.0, "s is the frame's x axis: S1 > 0");
        // Away from it, the degree of polarization is (R_s - R_p) / (R_s + R_p).
        let r = fresnel_amplitudes(0.7, Complex64::new(n, 0.0));
        let (rs, rp) = (r.s.norm_sqr(), r.p.norm_sqr());
        let dolp = Mueller::reflection(&r)
            .apply(Stokes::unpolarized(1.0))
            .degree_linear();
        assert!((f64::from(dolp) - (rs - rp) / (rs + rp)).abs() < 1e-5);
    }
}

/// Fresnel's intensities at normal incidence ((n - 1) / (n + 1))^2 and energy conservation
/// R + T = 1 for each polarization below the critical angle.
#[test]
fn dielectric_intensities_are_fresnels() {
    let n = 1.5;
    let normal = fresnel_amplitudes(1.0, Complex64::new(n, 0.0));
    let r0 = ((n - 1.0) / (n + 1.0)).powi(2);
    assert!((normal.s.norm_sqr() - r0).abs() < 1e-12 && (normal.p.norm_sqr() - r0).abs() < 1e-12);
    for cos in [0.05, 0.3, 0.7, 1.0] {
        let f = fresnel_amplitudes(cos, Complex64::new(n, 0.0));
        assert!((f.s.norm_sqr() + f.transmitted_s - 1.0).abs() < 1e-12);
        assert!((f.p.norm_sqr() + f.transmitted_p - 1.0).abs() < 1e-12);
    }
    // From inside, the index inverts: the same as the outside of an n = 1/1.5 interface.
    let inside = fresnel_amplitudes(-0.9, Complex64::new(n, 0.0));
    let outside = fresnel_amplitudes(0.9, Complex64::new(1.0 / n, 0.0));
    assert_eq!(inside, outside);
}

/// Total internal reflection keeps all the light and shifts s against p by
/// delta = 2 atan(cos_i sqrt(sin_i^2 - n^2) / sin_i^2) (Born and Wolf §1.5.4, eq. 60, n the
/// relative index < 1): linear light at 45 degrees comes out elliptical.
#[test]
fn total_internal_reflection_retards() {
    let n = 1.0 / 1.5;
    for cos in [0.1f64, 0.3, 0.5, 0.7] {
        let sin2 = 1.0 - cos * cos;
        assert!(sin2 > n * n, "beyond the critical angle");
        let f = fresnel_amplitudes(cos, Complex64::new(n, 0.0));
        assert!((f.s.norm() - 1.0).abs() < 1e-12 && (f.p.norm() - 1.0).abs() < 1e-12);
        assert_eq!((f.transmitted_s, f.transmitted_p), (0.0, 0.0));
        let expected = 2.0 * (cos * (sin2 - n * n).sqrt() / sin2).atan();
        let delta = (f.s * f.p.conj()).arg().abs();
        assert!(
            (delta - expected).abs() < 1e-9,
            "cos {cos}: {delta} vs {expected}"
        );
        let out =
            Mueller::reflection(&f).apply(Stokes::linear(1.0, 1.0, std::f32::consts::FRAC_PI_4));
        assert!((out.intensity() - 1.0).abs() < 1e-6);
        assert!(
            (out.0.w.abs() - (delta as f32).sin()).abs() < 1e-5,
            "{out:?}"
        );
    }
}

/// Malus's law: a polarizer at angle theta passes cos^2(theta) of linearly polarized
/// light, and half of unpolarized light; crossed polarizers pass nothing.
#[test]
fn polarizers_follow_malus() {
    let polarizer = |theta: f32| Mueller::rotated(theta, &Mueller::linear_polarizer(1.0));
    for theta in [0.0f32, 0.3, 0.7, 1.2, std::f32::consts::FRAC_PI_2] {
        let out = polarizer(theta).apply(Stokes::linear(1.0, 1.0, 0.0));
        assert!(
            (out.intensity() - theta.cos().powi(2)).abs() < 1e-6,
            "theta {theta}"
        );
        let half = polarizer(theta).apply(Stokes::unpolarized(2.0));
        assert!((half.intensity() - 1.0).abs() < 1e-6);
    }
    let crossed = polarizer(std::f32::consts::FRAC_PI_2).after(&polarizer(0.0));
    assert!(crossed.apply(Stokes::unpolarized(1.0)).intensity().abs() < 1e-6);
}

/// A quarter-wave plate at 45 degrees to linear light makes it circular; a half-wave plate
/// at theta turns linear light at 0 to 2 theta.
#[test]
fn wave_plates_turn_linear_into_circular_and_rotate_it() {
    use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};
    let quarter = Mueller::rotated(FRAC_PI_4, &Mueller::linear_retarder(FRAC_PI_2));
    let out = quarter.apply(Stokes::linear(1.0, 1.0, 0.0));
    assert!(
        (out.0.w.abs() - 1.0).abs() < 1e-6 && out.degree_linear() < 1e-6,
        "{out:?}"
    );
    let half = Mueller::rotated(0.3, &Mueller::linear_retarder(PI));
    let out = half.apply(Stokes::linear(1.0, 1.0, 0.0));
    assert!((out.angle_linear() - 0.6).abs() < 1e-5 && (out.degree_linear() - 1.0).abs() < 1e-5);
}

/// Metals turn linear light elliptical: the retardance of gold-like n = 0.18 + 3.42i at
/// 60 degrees is well away from 0 and pi.
#[test]
fn conductors_make_linear_light_elliptical() {
    let f = fresnel_amplitudes(0.5, Complex64::new(0.18, 3.42));
    let out = Mueller::reflection(&f).apply(Stokes::linear(1.0, 1.0, std::f32::consts::FRAC_PI_4));
    assert!(out.0.w.abs() > 0.3, "{out:?}");
    assert!(out.is_physical(1e-5));
}

fn stokes() -> impl Strategy<Value = Stokes> {
    (0.0f32..10.0, -1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0).prop_map(|(s0, a, b, c)| {
        let v = Vec4::new(0.0, a, b, c);
        let len = v.length().max(1.0);
        Stokes(Vec4::new(s0, s0 * a / len, s0 * b / len, s0 * c / len))
    })
}

fn extreme_cosine() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(1.0),
        Just(-1.0),
        Just(1e-12),
        Just(-1e-300),
        Just(f64::NAN),
        -1.0f64..1.0,
    ]
}

fn index() -> impl Strategy<Value = Complex64> {
    prop_oneof![
        (0.01f64..10.0).prop_map(|n| Complex64::new(n, 0.0)),
        (0.01f64..10.0, 0.0f64..20.0).prop_map(|(n, k)| Complex64::new(n, k)),
        Just(Complex64::new(1.0, 0.0)),
        Just(Complex64::new(f64::NAN, 1.0)),
        Just(Complex64::new(0.0, 0.0)),
        Just(Complex64::new(1e300, 1e300)),
    ]
}

proptest! {
    #[test]
    fn interfaces_map_light_to_light(s in stokes(), cos in extreme_cosine(), eta in index()) {
        let f = fresnel_amplitudes(cos, eta);
        for m in [Mueller::reflection(&f), Mueller::transmission(&f)] {
            prop_assert!(m.is_finite());
            let out = m.apply(s);
            prop_assert!(out.is_physical(1e-4), "{out:?} from {s:?}, {m:?}");
            prop_assert!(out.intensity() <= s.intensity() * (1.0 + 1e-5) + 1e-6);
        }
        // Energy: what is reflected and transmitted of unpolarized light never exceeds it.
        let total = f.s.norm_sqr() + f.p.norm_sqr() + f.transmitted_s + f.transmitted_p;
        prop_assert!(total <= 2.0 + 1e-9 && total.is_finite());
    }

    #[test]
    fn linear_elements_map_light_to_light(
        s in stokes(),
        theta in prop_oneof![Just(f32::NAN), Just(0.0f32), -10.0f32..10.0],
        phase in -10.0f32..10.0,
        frame in (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
    ) {
        let w = Vec3::new(frame.0, frame.1, frame.2 + 2.0).normalize();
        let from = w.any_orthonormal_vector();
        let to = w.cross(from).normalize() * frame.0.signum() + from * frame.1;
        for m in [
            Mueller::rotated(theta, &Mueller::linear_polarizer(1.0)),
            Mueller::rotated(theta, &Mueller::linear_retarder(phase)),
            rotate_frame(w, from, to.normalize_or_zero()),
            Mueller::rotator(theta),
        ] {
            let out = m.apply(s);
            if theta.is_finite() {
                // f32 rounding leaves an error of a few ulps of the input's intensity, which
                // near extinction (a polarizer crossed with fully polarized light: 6.5e-5 out
                // of 3.77) is a percent of what comes out: the bound allows for it.
                let slack = 1e-6 * s.intensity();
                prop_assert!(
                    out.0.is_finite() && out.0.yzw().length() <= out.0.x * (1.0 + 1e-4) + slack,
                    "{out:?} from {s:?}"
                );
            }
        }
    }
}

/// The polarized counterpart of a Fresnel BSDF keeps its scalar value as the unpolarized
/// entry, and its frames are the s axis of the plane of incidence, perpendicular to both
/// directions of travel; seen through the frames of a fixed observer the reflected light
/// of a Brewster-angle reflection is polarized perpendicular to the plane of incidence.
#[test]
fn fresnel_interactions_keep_the_scalar_value_and_the_plane_of_incidence() {
    use prism_scene::polarization::Interaction;
    let n = 1.5f32;
    let theta_b = n.atan();
    let wi = Vec3::new(theta_b.sin(), 0.0, theta_b.cos());
    let wo = Vec3::new(-wi.x, 0.0, wi.z);
    let amplitudes = fresnel_amplitudes(f64::from(wi.z), Complex64::new(f64::from(n), 0.0));
    let value = 0.123;
    let it = Interaction::fresnel(wi, wo, Vec3::Z, &amplitudes, value);
    assert!((it.mueller.rows()[0][0] - value).abs() < 1e-7);
    // The plane of incidence is xz: s is +-y, perpendicular to -wi and wo.
    assert!((it.incident_basis.y.abs() - 1.0).abs() < 1e-6);
    assert!(it.incident_basis.dot(wi).abs() < 1e-6 && it.outgoing_basis.dot(wo).abs() < 1e-6);
    // An observer whose frame's x axis is the world's x (turned to be perpendicular to wo)
    // sees the reflection polarized along y: S1 < 0 in that frame, fully.
    let observer_x = (Vec3::X - wo * wo.dot(Vec3::X)).normalize();
    let seen = rotate_frame(wo, it.outgoing_basis, observer_x)
        .after(&it.mueller)
        .apply(Stokes::unpolarized(1.0));
    assert!(
        seen.0.y < 0.0 && (seen.degree_linear() - 1.0).abs() < 1e-4,
        "{seen:?}"
    );
    // Refraction uses the transmission matrix, with the same scaling.
    let wt = Vec3::new(-wi.x / n, 0.0, -(1.0 - (wi.x / n).powi(2)).sqrt());
    let refracted = Interaction::fresnel(wi, wt, Vec3::Z, &amplitudes, 0.5);
    let rows = refracted.mueller.rows();
    assert!(
        (rows[0][0] - 0.5).abs() < 1e-7 && rows[0][1] < 0.0,
        "p is favoured: {rows:?}"
    );
}

/// An iridescent film's amplitudes give its reflectance as the Mueller matrix's
/// unpolarized entry, reduce to the bare interface's at zero thickness, and retard s
/// against p (linear light at 45 degrees comes out with circular content).
#[test]
fn thin_films_polarize_and_retard() {
    use prism_scene::bsdf::ThinFilm;
    use prism_scene::polarization::FresnelAmplitudes;
    let film = ThinFilm {
        ior: 1.3,
        thickness_nm: 400.0,
    };
    let as_mueller = |(s, p): (Complex64, Complex64)| {
        Mueller::reflection(&FresnelAmplitudes {
            s,
            p,
            transmitted_s: 0.0,
            transmitted_p: 0.0,
        })
    };
    for (cos, lambda) in [(0.9f32, 450.0f32), (0.5, 550.0), (0.2, 650.0)] {
        let m = as_mueller(film.amplitudes(cos, lambda, 1.0, 1.5, 0.0));
        let r = film.reflectance(cos, lambda, 1.0, 1.5, 0.0);
        assert!((m.rows()[0][0] - r).abs() < 1e-6);
        let bare = ThinFilm {
            ior: 1.3,
            thickness_nm: 0.0,
        };
        let ours = as_mueller(bare.amplitudes(cos, lambda, 1.0, 1.5, 0.0));
        let interface = Mueller::reflection(&fresnel_amplitudes(
            f64::from(cos),
            Complex64::new(1.5, 0.0),
        ));
        for (a, b) in ours
            .rows()
            .iter()
            .flatten()
            .zip(interface.rows().iter().flatten())
        {
            assert!((a - b).abs() < 1e-6, "{ours:?} vs {interface:?}");
        }
    }
    let m = as_mueller(film.amplitudes(0.5, 550.0, 1.0, 1.5, 0.0));
    let out = m.apply(Stokes::linear(1.0, 1.0, std::f32::consts::FRAC_PI_4));
    assert!(
        out.0.w.abs() > 0.01 * out.intensity() && out.is_physical(1e-5),
        "{out:?}"
    );
}

/// A rough conductor's polarized lobe carries its scalar value per lane as the unpolarized
/// entry, maps light to light, and turns linear light elliptical (gold-like index).
#[test]
fn rough_conductor_lobes_carry_the_scalar_value() {
    use prism_scene::bsdf::{Ggx, RoughConductor};
    use prism_scene::polarization::interactions;
    use prism_scene::world::Bsdf;
    use prism_spectrum::SampledSpectrum;
    let bsdf = RoughConductor::<4> {
        distribution: Ggx::new(0.3, 0.3),
        eta: SampledSpectrum([0.18, 0.4, 1.2, 2.9]),
        k: SampledSpectrum([3.42, 2.5, 7.0, 3.1]),
    };
    let wo = Vec3::new(0.3, 0.2, 0.93).normalize();
    for wi in [
        Vec3::new(-0.5, 0.1, 0.86),
        Vec3::new(0.7, -0.6, 0.38),
        Vec3::new(0.2, 0.1, -0.97),
    ] {
        let wi = wi.normalize();
        let f = bsdf.f(wo, wi);
        let lobes = interactions(&Bsdf::Conductor(bsdf), wo, wi, &f, false);
        for (lane, it) in lobes.iter().enumerate() {
            assert!((it.mueller.rows()[0][0] - f[lane]).abs() <= 1e-6 * f[lane].max(1.0));
            let out = it
                .mueller
                .apply(Stokes::linear(1.0, 1.0, std::f32::consts::FRAC_PI_4));
            assert!(out.is_physical(1e-4), "{out:?}");
            if f[lane] > 0.0 {
                assert!(
                    out.0.w.abs() > 1e-3 * out.intensity(),
                    "lane {lane}: {out:?}"
                );
            }
        }
    }
}

/// A rough dielectric's polarized lobes carry its scalar value per lane for reflection and
/// refraction, from either side, and map light to light; its smooth limit reflects no
/// p-polarized light at Brewster's angle (the sampled delta's matrix).
#[test]
fn dielectric_lobes_carry_the_scalar_value() {
    use prism_scene::bsdf::{Ggx, RoughDielectric, TransportMode};
    use prism_scene::polarization::interactions;
    use prism_scene::world::Bsdf;
    let rough = RoughDielectric::<4> {
        distribution: Ggx::new(0.25, 0.25),
        eta: [1.45, 1.5, 1.55, 1.7],
        mode: TransportMode::Radiance,
    };
    for wo in [Vec3::new(0.3, 0.2, 0.93), Vec3::new(-0.4, 0.5, -0.77)] {
        let wo = wo.normalize();
        for wi in [
            Vec3::new(-0.5, 0.1, 0.86),
            Vec3::new(0.7, -0.6, 0.38),
            Vec3::new(0.2, 0.1, -0.97),
            Vec3::new(-0.5, -0.3, -0.81),
        ] {
            let wi = wi.normalize();
            let f = rough.f(wo, wi);
            let lobes = interactions(&Bsdf::Dielectric(rough), wo, wi, &f, false);
            for (lane, it) in lobes.iter().enumerate() {
                let m00 = it.mueller.rows()[0][0];
                assert!(
                    (m00 - f[lane]).abs() <= 1e-5 * f[lane].max(1.0),
                    "{m00} {}",
                    f[lane]
                );
                for angle in [0.0, 0.4, 1.2] {
                    let out = it.mueller.apply(Stokes::linear(1.0, 1.0, angle));
                    assert!(out.is_physical(1e-4), "{wo} {wi} {out:?}");
                }
            }
        }
    }
    // Smooth glass at Brewster's angle: the sampled reflection passes s light only.
    let eta = 1.5f32;
    let brewster = eta.atan();
    let wo = Vec3::new(brewster.sin(), 0.0, brewster.cos());
    let smooth = RoughDielectric::<1> {
        distribution: Ggx::new(0.0, 0.0),
        eta: [eta],
        mode: TransportMode::Radiance,
    };
    let sample = (0..64)
        .filter_map(|i| smooth.sample(wo, i as f32 / 64.0, glam::Vec2::splat(0.5)))
        .find(|s| s.wi.z > 0.0)
        .expect("a reflection");
    let it = interactions(&Bsdf::Dielectric(smooth), wo, sample.wi, &sample.f, true)[0];
    let out = it.mueller.apply(Stokes::unpolarized(1.0));
    assert!((out.degree_linear() - 1.0).abs() < 1e-3, "{out:?}");
    // Fully polarized along s, the frame's x axis: S1 = +S0.
    assert!((out.0.y - out.0.x).abs() < 1e-3 * out.0.x, "{out:?}");
}

/// A glTF document: one triangle and a spot light on a node turned 90 degrees about +z,
/// its `PRISM_spectral` description `light` (JSON).
#[cfg(feature = "gltf")]
fn spot_light_document(light: &str) -> Vec<u8> {
    let h = std::f32::consts::FRAC_1_SQRT_2;
    format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0,
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {{"KHR_lights_punctual": {{"lights": [{{"name": "lamp", "type": "spot", "intensity": 10, "spot": {{}},
            "extensions": {{"PRISM_spectral": {light}}}}}]}}}},
        "scenes": [{{"nodes": [0, 1]}}],
        "nodes": [{{"mesh": 0}}, {{"rotation": [0, 0, {h}, {h}], "translation": [0, 0, 2],
            "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
            "min": [0, 0, 0], "max": [1, 1, 0]}}],
        "bufferViews": [{{"buffer": 0, "byteLength": 36}}],
        "buffers": [{{"byteLength": 36, "uri": "triangle.bin"}}]}}"#
    )
    .into_bytes()
}

/// A light's `polarization` reaches the scene's light, its angle measured from the
/// light node's x axis (here turned onto +y); bad values are errors naming the light.
#[cfg(feature = "gltf")]
#[test]
fn lights_carry_their_polarization_from_gltf() {
    use prism_scene::load::{LoadOptions, load_scene};
    use prism_scene::world::{Scene, SceneOptions};
    let load = |light: &str| {
        let doc = spot_light_document(light);
        let triangle: Vec<u8> = [0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
            .iter()
            .flat_map(|c| c.to_le_bytes())
            .collect();
        let resolve = move |uri: &str| match uri {
            "triangle.bin" => Ok(triangle.clone()),
            _ => Err(std::io::Error::other("no such file")),
        };
        load_scene(&doc, &resolve, &LoadOptions::default())
            .and_then(|loaded| Scene::from_loaded(loaded, &SceneOptions::default()))
    };
    let scene =
        load(r#"{"spectrum": "illuminant:D65", "polarization": {"degree": 0.75, "angle": 30}}"#)
            .unwrap();
    let index = scene
        .lights()
        .all()
        .iter()
        .position(|l| matches!(l, prism_scene::world::Light::Spot { .. }))
        .unwrap() as u32;
    let p = scene
        .light_polarization(index)
        .expect("the spot light is polarized");
    assert!((p.degree - 0.75).abs() < 1e-6 && (p.angle - 30f32.to_radians()).abs() < 1e-6);
    assert!(p.axis.abs_diff_eq(Vec3::Y, 1e-5), "{}", p.axis);
    // Light shining straight down its axis: Stokes (1, 0.75 cos 60, 0.75 sin 60, 0) in
    // the frame of the light's x axis.
    let (stokes, basis) = p.stokes(-Vec3::Z);
    assert!(basis.abs_diff_eq(Vec3::Y, 1e-5));
    assert!(
        stokes
            .0
            .abs_diff_eq(Vec4::new(1.0, 0.375, 0.75 * 0.866_025_4, 0.0), 1e-5)
    );
    let unpolarized = load(r#"{"spectrum": "illuminant:D65"}"#).unwrap();
    assert!(
        (0..unpolarized.lights().all().len() as u32)
            .all(|i| unpolarized.light_polarization(i).is_none())
    );
    for bad in [
        r#"{"spectrum": 1, "polarization": {"degree": 1.5}}"#,
        r#"{"spectrum": 1, "polarization": {"angle": "up"}}"#,
        r#"{"spectrum": 1, "polarization": {"dgree": 1}}"#,
        r#"{"spectrum": 1, "polarization": 0.5}"#,
    ] {
        let error = load(bad).err().expect(bad).to_string();
        assert!(
            error.contains("lamp") && error.contains("polarization") || error.contains("dgree"),
            "{error}"
        );
    }
}

/// glTF's metallic-roughness material: its polarized lobes sum to the scalar f per lane,
/// map light to light, and polarize where the coating's reflection dominates (a dark
/// glossy dielectric near Brewster's angle reflects mostly s light); a metal turns linear
/// light elliptical.
#[test]
fn metallic_roughness_lobes_split_f_by_fresnel() {
    use prism_scene::bsdf::{CoatingAlbedo, MetallicRoughness};
    use prism_scene::polarization::interactions;
    use prism_scene::world::Bsdf;
    use prism_spectrum::SampledSpectrum;
    let coating = CoatingAlbedo::new(1.5);
    let brewster = 1.5f32.atan();
    let wo = Vec3::new(brewster.sin(), 0.0, brewster.cos());
    let wi = Vec3::new(-wo.x, 0.0, wo.z);
    for (base, metallic, roughness) in [
        ([0.02, 0.03, 0.02, 0.05], 0.0, 0.3),
        ([0.8, 0.5, 0.2, 0.9], 0.0, 0.6),
        ([0.95, 0.7, 0.4, 0.9], 1.0, 0.3),
        ([0.5, 0.5, 0.5, 0.5], 0.5, 0.8),
    ] {
        let bsdf = Bsdf::MetallicRoughness(MetallicRoughness::new(
            SampledSpectrum(base),
            metallic,
            roughness,
            &coating,
        ));
        for (wo, wi) in [
            (wo, wi),
            (Vec3::new(0.3, 0.4, 0.866), Vec3::new(-0.6, 0.1, 0.79)),
        ] {
            let (wo, wi) = (wo.normalize(), wi.normalize());
            let f = bsdf.f(wo, wi);
            let value = f * wi.z;
            let lanes = interactions(&bsdf, wo, wi, &value, false);
            for (lane, it) in lanes.iter().enumerate() {
                let m00 = it.mueller.rows()[0][0];
                assert!(
                    (m00 - value[lane]).abs() <= 1e-5 * value[lane].max(1e-3),
                    "{m00} vs {}",
                    value[lane]
                );
                for angle in [0.0, 0.7, 1.5] {
                    assert!(
                        it.mueller
                            .apply(Stokes::linear(1.0, 1.0, angle))
                            .is_physical(1e-4)
                    );
                }
            }
        }
        let lanes = interactions(&bsdf, wo, wi, &bsdf.f(wo, wi), false);
        let out = lanes[0].mueller.apply(Stokes::unpolarized(1.0));
        if base[0] < 0.1 {
            // A dark glossy dielectric at Brewster's angle: mostly the coating's s light.
            assert!(out.degree_linear() > 0.8, "{out:?}");
        }
        if metallic == 1.0 {
            let diagonal =
                lanes[0]
                    .mueller
                    .apply(Stokes::linear(1.0, 1.0, std::f32::consts::FRAC_PI_4));
            assert!(
                diagonal.0.w.abs() > 0.05 * diagonal.intensity(),
                "{diagonal:?}"
            );
        }
    }
}

/// Under a clear coat and a sheen, the polarized lobes still sum to the scalar f and map
/// light to light, and a black base under a smooth-ish coat reflects mostly s light at
/// Brewster's angle (the coat's Fresnel).
#[test]
fn layered_lobes_split_f_by_layer() {
    use prism_scene::bsdf::{
        Clearcoat, CoatingAlbedo, Layered, MetallicRoughness, Sheen, TransportMode,
    };
    use prism_scene::polarization::interactions;
    use prism_scene::world::Bsdf;
    use prism_spectrum::SampledSpectrum;
    let coating = CoatingAlbedo::new(1.5);
    let brewster = 1.5f32.atan();
    let wo = Vec3::new(brewster.sin(), 0.0, brewster.cos());
    let wi = Vec3::new(-wo.x, 0.0, wo.z);
    for (base, sheen) in [
        ([0.0, 0.0, 0.0, 0.0], None),
        ([0.6, 0.4, 0.3, 0.2], Some(0.5)),
    ] {
        let bsdf = Bsdf::Layered(Box::new(Layered {
            base: MetallicRoughness::new(SampledSpectrum(base), 0.0, 0.5, &coating),
            sheen: sheen.map(|r| Sheen::new(SampledSpectrum([0.3, 0.6, 0.2, 0.9]), r)),
            clearcoat: Some(Clearcoat::new(1.0, 0.05, None)),
            mode: TransportMode::Radiance,
        }));
        for (wo, wi) in [
            (wo, wi),
            (Vec3::new(0.3, 0.4, 0.866), Vec3::new(-0.6, 0.1, 0.79)),
        ] {
            let (wo, wi) = (wo.normalize(), wi.normalize());
            let f = bsdf.f(wo, wi);
            for (lane, it) in interactions(&bsdf, wo, wi, &f, false).iter().enumerate() {
                let m00 = it.mueller.rows()[0][0];
                assert!(
                    (m00 - f[lane]).abs() <= 1e-5 * f[lane].max(1e-3),
                    "{m00} vs {}",
                    f[lane]
                );
                for angle in [0.0, 0.7, 1.5] {
                    assert!(
                        it.mueller
                            .apply(Stokes::linear(1.0, 1.0, angle))
                            .is_physical(1e-4)
                    );
                }
            }
        }
        if sheen.is_none() {
            let out = interactions(&bsdf, wo, wi, &bsdf.f(wo, wi), false)[0]
                .mueller
                .apply(Stokes::unpolarized(1.0));
            assert!(out.degree_linear() > 0.9, "{out:?}");
        }
    }
}
