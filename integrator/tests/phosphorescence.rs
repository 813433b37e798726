//! Phosphorescence against its closed forms: a phosphor of lifetime tau under a light
//! switched on at 0 and off at T glows, at time t, with the steady state's radiance times
//! 1 - exp(-t / tau) while the light is on, (1 - exp(-T / tau)) exp(-(t - T) / tau)
//! after, nothing before; a multi-exponential phosphor by the weighted sum; a phosphor
//! whose light has no schedule at its steady state at any time. The scene is read from
//! glTF, so `lifetime(s)` and `on` are exercised as files give them.

use prism_integrator::{Film, RenderSettings, render};
use prism_scene::load::{LoadOptions, load_scene};
use prism_scene::world::{Scene, SceneOptions};

/// A square of phosphor (UV in, green out, nothing reflected) facing +z, seen by an
/// orthographic camera, lit by a UV directional light described by `light` (its
/// PRISM_spectral entries besides the spectrum) and glowing with `decay` (its material's
/// entries besides the fluorescence).
fn scene(decay: &str, light: &str) -> Scene {
    scene_lit_by(decay, r#""type": "directional""#, light)
}

/// [`scene`] with the light of kind `kind` (its glTF type and parameters), 2 units above
/// the square pointing down at it.
fn scene_lit_by(decay: &str, kind: &str, light: &str) -> Scene {
    try_scene(decay, kind, light).unwrap()
}

/// [`scene_lit_by`], or the loader's error.
fn try_scene(decay: &str, kind: &str, light: &str) -> Result<Scene, prism_scene::LoadError> {
    let doc = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0,
        "extensionsUsed": ["KHR_lights_punctual", "PRISM_spectral"],
        "extensions": {{"KHR_lights_punctual": {{"lights": [{{"name": "uv", {kind}, "intensity": 1,
            "extensions": {{"PRISM_spectral": {{"spectrum": "gaussian:365:10", "units": "radiometric"{light}}}}}}}]}}}},
        "scenes": [{{"nodes": [0, 1, 2]}}],
        "nodes": [{{"mesh": 0}}, {{"translation": [0, 0, 2], "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}},
            {{"camera": 0, "translation": [0, 0, 1]}}],
        "cameras": [{{"type": "orthographic", "orthographic": {{"xmag": 0.5, "ymag": 0.5, "znear": 0.01, "zfar": 10}}}}],
        "materials": [{{"name": "phosphor", "extensions": {{"PRISM_spectral": {{"type": "fluorescent", "reflectance": 0,
            "absorption": {{"spectrum": "gaussian:365:30", "scale": 0.9}}, "reemission": "gaussian:520:30",
            "quantum_yield": 0.9{decay}}}}}}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "material": 0}}]}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3",
            "min": [-2, -2, 0], "max": [2, 2, 0]}}],
        "bufferViews": [{{"buffer": 0, "byteLength": 72}}],
        "buffers": [{{"byteLength": 72, "uri": "square.bin"}}]}}"#
    );
    let square: Vec<u8> = [
        -2f32, -2.0, 0.0, 2.0, -2.0, 0.0, 2.0, 2.0, 0.0, -2.0, -2.0, 0.0, 2.0, 2.0, 0.0, -2.0, 2.0,
        0.0,
    ]
    .iter()
    .flat_map(|c| c.to_le_bytes())
    .collect();
    let resolve = move |uri: &str| match uri {
        "square.bin" => Ok(square.clone()),
        _ => Err(std::io::Error::other("no such file")),
    };
    let loaded = load_scene(doc.as_bytes(), &resolve, &LoadOptions::default())?;
    Scene::from_loaded(loaded, &SceneOptions::default())
}

fn glow(scene: &Scene, at: Option<f64>) -> f64 {
    let settings = RenderSettings::default()
        .width(4)
        .height(4)
        .samples(0..16)
        .at(at);
    let (film, _): (Film, _) = render(scene, &settings).unwrap();
    let mut sum = 0.0;
    for y in 0..4 {
        for x in 0..4 {
            sum += film.xyz(x, y).y;
        }
    }
    sum / 16.0
}

fn assert_ratio(scene: &Scene, steady: f64, at: f64, expected: f64) {
    let ratio = glow(scene, Some(at)) / steady;
    assert!(
        (ratio - expected).abs() <= 1e-5 * expected.max(1e-3),
        "at {at} s: {ratio}, expected {expected}"
    );
}

#[test]
fn a_phosphor_charges_and_decays_exponentially() {
    let (tau, off) = (2.0f64, 5.0f64);
    let scene = scene(r#", "lifetime": 2.0"#, r#", "on": [[0, 5]]"#);
    let steady = glow(&scene, None);
    assert!(steady > 0.0);
    // Before the light ever shone: black.
    assert_eq!(glow(&scene, Some(-1.0)), 0.0);
    // Charging while it shines.
    for t in [0.5, 2.0, 4.9] {
        assert_ratio(&scene, steady, t, 1.0 - (-t / tau).exp());
    }
    // Decaying after it went off.
    for t in [5.5, 7.0, 12.0] {
        assert_ratio(
            &scene,
            steady,
            t,
            (1.0 - (-off / tau).exp()) * (-(t - off) / tau).exp(),
        );
    }
}

#[test]
fn multi_exponential_phosphors_follow_their_sum() {
    let weights = [(0.5f64, 0.6f64), (8.0, 0.4)];
    let scene = scene(
        r#", "lifetimes": [[0.5, 0.6], [8.0, 0.4]]"#,
        r#", "on": [[0, 3]]"#,
    );
    let steady = glow(&scene, None);
    for t in [1.0, 4.0, 10.0] {
        // The mass of delays d with t - d in [0, 3]: d in [max(0, t - 3), t].
        let (a, b) = ((t - 3.0f64).max(0.0), t);
        let expected: f64 = weights
            .iter()
            .map(|&(tau, w)| w * ((-a / tau).exp() - (-b / tau).exp()))
            .sum();
        assert_ratio(&scene, steady, t, expected);
    }
}

#[test]
fn a_phosphor_under_an_unscheduled_light_is_steady() {
    let scene = scene(r#", "lifetime": 3.0"#, "");
    let steady = glow(&scene, None);
    for t in [-100.0, 0.0, 42.0] {
        assert_ratio(&scene, steady, t, 1.0);
    }
    // And without a lifetime, a schedule still switches the light.
    let fluorescent = scene_without_lifetime();
    assert!(glow(&fluorescent, Some(1.0)) > 0.0);
    assert_eq!(glow(&fluorescent, Some(6.0)), 0.0);
}

fn scene_without_lifetime() -> Scene {
    scene("", r#", "on": [[0, 5]]"#)
}

/// An exposure averages the glow over the time the shutter is open (the closed form's
/// mean over [4, 8] s, a light on during [0, 5] s, lifetime 2 s), within the Monte Carlo
/// error of the times drawn.
#[test]
fn an_exposure_is_the_mean_over_the_shutter() {
    let (tau, off) = (2.0f64, 5.0f64);
    let scene = scene(r#", "lifetime": 2.0"#, r#", "on": [[0, 5]]"#);
    let settings = RenderSettings::default()
        .width(4)
        .height(4)
        .samples(0..64)
        .shutter(Some((4.0, 8.0)));
    let mean_of = |settings: &RenderSettings| {
        let (film, _) = render(&scene, settings).unwrap();
        (0..16).map(|i| film.xyz(i % 4, i / 4).y).sum::<f64>() / 16.0
    };
    // The steady state with the same samples, so that only the times differ.
    let steady = mean_of(&settings.clone().shutter(None));
    let mean = mean_of(&settings);
    // (1/4) [ int_4^5 (1 - e^{-t/tau}) dt + (1 - e^{-off/tau}) int_5^8 e^{-(t-off)/tau} dt ]
    let charging = 1.0 + tau * ((-5.0 / tau).exp() - (-4.0 / tau).exp());
    let decaying = (1.0 - (-off / tau).exp()) * tau * (1.0 - (-3.0 / tau).exp());
    let expected = (charging + decaying) / 4.0;
    let ratio = mean / steady;
    assert!(
        (ratio / expected - 1.0).abs() < 0.02,
        "{ratio} vs {expected}"
    );
    // An instant and an exposure at once is an error.
    assert!(render(&scene, &settings.clone().at(Some(1.0))).is_err());
}

/// The independent check's setting: a UV spot light switched on at 0 and off at 5 s.
#[test]
fn a_scheduled_spot_light_charges_and_leaves_a_decaying_glow() {
    let tau = 1.5f64;
    let scene = scene_lit_by(
        r#", "lifetime": 1.5"#,
        r#""type": "spot", "spot": {"innerConeAngle": 0.6, "outerConeAngle": 0.9}"#,
        r#", "on": [[0, 5]]"#,
    );
    let steady = glow(&scene, None);
    assert!(steady > 0.0);
    assert_eq!(glow(&scene, Some(-0.5)), 0.0);
    assert_ratio(&scene, steady, 3.0, 1.0 - (-3.0 / tau).exp());
    for t in [6.0, 9.0] {
        assert_ratio(
            &scene,
            steady,
            t,
            (1.0 - (-5.0 / tau).exp()) * (-(t - 5.0) / tau).exp(),
        );
    }
}

/// Bad schedules on a light are one-line errors naming it.
#[test]
fn bad_light_schedules_name_the_light() {
    let directional = r#""type": "directional""#;
    for (light, needle) in [
        (r#", "on": [[5, 1]]"#, "reversed"),
        (r#", "on": [[0, 5], [3, 8]]"#, "overlap"),
        (r#", "on": [["dawn", 5]]"#, "start"),
        (r#", "on": 3"#, "schedule"),
    ] {
        let error = try_scene("", directional, light)
            .err()
            .expect(needle)
            .to_string();
        assert!(error.contains("uv") && error.contains(needle), "{error}");
        assert_eq!(error.lines().count(), 1);
    }
}
