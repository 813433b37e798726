//! Media in the scene format: what loads, and the one-line errors that name the material
//! and the key for everything that cannot (docs/scene-format.md, "Participating media").

use prism_scene::load::{LoadOptions, load_scene};
use prism_scene::world::{Scene, SceneOptions};
use serde_json::{Value, json};

fn scenes_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

/// The Cornell box with `white`'s description replaced by `white` (None: unchanged) and
/// the root's by `root`, loaded into a scene; files resolve in scenes/, `vdb/NAME` in
/// tests/data/vdb, and `bad.vol` is a grid with a NaN voxel.
fn load(white: Option<Value>, root: Option<Value>) -> Result<Scene, String> {
    let mut doc: Value =
        serde_json::from_slice(&std::fs::read(scenes_dir().join("cornell-box.gltf")).unwrap())
            .unwrap();
    if let Some(white) = white {
        for m in doc["materials"].as_array_mut().unwrap() {
            if m["name"] == "white" {
                m["extensions"] = json!({ "PRISM_spectral": white });
            }
        }
    }
    if let Some(root) = root {
        doc["extensions"] = json!({ "PRISM_spectral": root });
    }
    let bytes = serde_json::to_vec(&doc).unwrap();
    let resolve = |uri: &str| -> std::io::Result<Vec<u8>> {
        if uri == "bad.vol" {
            let mut values = vec![0.5f32; 8];
            values[3] = f32::NAN;
            return Ok(prism_scene::medium::write_vol(
                glam::UVec3::splat(2),
                glam::Vec3::ZERO,
                glam::Vec3::ONE,
                &values,
            ));
        }
        if let Some(name) = uri.strip_prefix("vdb/") {
            let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/vdb");
            return std::fs::read(data.join(name));
        }
        std::fs::read(scenes_dir().join(uri))
    };
    let loaded =
        load_scene(&bytes, &resolve, &LoadOptions::default()).map_err(|e| e.to_string())?;
    Scene::from_loaded(loaded, &SceneOptions::default()).map_err(|e| e.to_string())
}

#[test]
fn media_load_into_the_scene() {
    let scene = load(
        Some(json!({"type": "interface", "medium": {"sigma_a": 0.1, "sigma_s": 2.0, "g": 0.5}})),
        None,
    )
    .unwrap();
    assert!(scene.features().media);
    assert_eq!(scene.media().all().len(), 1);
    assert_eq!(scene.media().world(), None);
    let scene = load(
        Some(json!({"type": "dielectric", "ior": 1.33, "medium": {"sigma_s": 1.0, "phase": "rayleigh",
            "density": {"file": "smoke.vol", "scale": 2.0, "bounds": [[-1, -1, -1], [1, 1, 1]]}}})),
        Some(json!({"medium": {"sigma_s": 0.01}})),
    )
    .unwrap();
    let media = scene.media();
    assert_eq!(media.all().len(), 2);
    assert!(media.world().is_some());
    let grid = media.all()[0].density().expect("a grid medium");
    assert_eq!(
        grid.bounds(),
        (glam::Vec3::splat(-1.0), glam::Vec3::splat(1.0))
    );
    assert!(
        (grid.max_value() - 1.2).abs() < 0.01,
        "{}",
        grid.max_value()
    );
    // A fluorescent dye makes the scene fluorescent (paths change wavelength).
    let scene = load(
        Some(
            json!({"type": "interface", "medium": {"sigma_s": 0.5, "fluorescence": {
            "absorption": {"spectrum": "gaussian:365:30", "scale": 20.0},
            "reemission": "gaussian:520:40", "quantum_yield": 0.9}}}),
        ),
        None,
    )
    .unwrap();
    assert!(scene.features().fluorescence && scene.media().all()[0].fluorescence().is_some());
    // OpenVDB grids: density by its usual name, a temperature grid of the same file.
    let scene = load(
        Some(json!({"type": "interface", "medium": {"sigma_a": 1.0,
            "density": {"file": "vdb/smoke.vdb"},
            "temperature": {"file": "vdb/smoke.vdb", "scale": 2.0}}})),
        None,
    )
    .unwrap();
    let medium = &scene.media().all()[0];
    let density = medium.density().expect("a grid medium").max_value();
    let temperature = medium.temperature().expect("a hot medium").max_value();
    assert!(
        density > 0.5 && density < 1.5 && temperature > 2000.0,
        "{density} {temperature}"
    );
    // A scene without media has none and runs the path tracer without them.
    let plain = load(None, None).unwrap();
    assert!(!plain.features().media && plain.media().is_empty());
}

#[test]
fn bad_media_are_one_line_errors_naming_material_and_key() {
    let cases: Vec<(Value, &[&str])> = vec![
        (
            json!({"type": "interface", "medium": {"sigma_a": -1.0}}),
            &["white", "sigma_a"],
        ),
        (
            json!({"type": "interface", "medium": {"sigma_s": 1.0, "g": 1.0}}),
            &["white", "g"],
        ),
        (
            json!({"type": "interface", "medium": {"sigma_s": 1.0, "g": 0.5, "phase": "rayleigh"}}),
            &["white", "g"],
        ),
        (
            json!({"type": "interface", "medium": {"sigma_s": "nonsense:3"}}),
            &["white", "sigma_s"],
        ),
        (
            json!({"type": "interface", "medium": {"g": 0.2}}),
            &["white", "medium"],
        ),
        (
            json!({"type": "interface", "medium": {"sigma_s": 1.0, "colour": 2}}),
            &["white", "colour"],
        ),
        (json!({"type": "interface"}), &["white", "medium"]),
        (
            json!({"type": "diffuse", "reflectance": 0.5, "medium": {"sigma_s": 1.0}}),
            &["white", "medium"],
        ),
        (
            json!({"type": "interface", "medium": {"sigma_s": 1.0, "density": {"file": "missing.vol"}}}),
            &["white", "density", "missing.vol"],
        ),
        (
            json!({"type": "interface", "medium": {"sigma_s": 1.0, "density": {"file": "bad.vol"}}}),
            &["white", "density", "NaN"],
        ),
        (
            json!({"type": "interface", "medium": {"sigma_s": 1.0, "density": {"file": "vdb/smoke.vdb", "grid": "smoke"}}}),
            &["white", "density", "smoke.vdb", "no grid named 'smoke'"],
        ),
        (
            json!({"type": "interface", "medium": {"sigma_s": 1.0, "density": {"file": "vdb/levelset.vdb"}}}),
            &["white", "density", "levelset.vdb", "level set"],
        ),
        (
            json!({"type": "interface", "medium": {"sigma_s": 1.0, "density": {"file": "vdb/smoke.vdb", "grid": 3}}}),
            &["white", "density", "'grid'"],
        ),
        (
            json!({"type": "interface", "medium": {"sigma_s": 1.0, "density": {"file": "smoke.vol", "scale": -1}}}),
            &["white", "density", "scale"],
        ),
        (
            json!({"type": "interface", "medium": {"sigma_s": 1.0, "density": {"file": "smoke.vol",
            "bounds": [[0, 0, 0], [0, 1, 1]]}}}),
            &["white", "density"],
        ),
        (
            json!({"type": "interface", "medium": {"sigma_s": 1.0, "temperature": {"file": "smoke.vol"}}}),
            &["white", "temperature"],
        ),
        (
            json!({"type": "interface", "medium": {"fluorescence": {"matrix": {"rows": [[0.1]]}}}}),
            &["white", "fluorescence", "matrix"],
        ),
        (
            json!({"type": "interface", "medium": {"fluorescence": {"absorption": 1.0,
            "reemission": "gaussian:520:40", "quantum_yield": 1.5}}}),
            &["white", "fluorescence", "quantum"],
        ),
    ];
    for (description, words) in cases {
        let e = load(Some(description.clone()), None)
            .err()
            .unwrap_or_else(|| panic!("loaded: {description}"));
        for w in words {
            assert!(e.contains(w), "{description}: '{e}' lacks '{w}'");
        }
        assert!(!e.contains('\n'), "{e}");
    }
    let e = load(None, Some(json!({"medium": {"sigma_a": -2}})))
        .err()
        .expect("refused");
    assert!(e.contains("medium") && e.contains("sigma_a"), "{e}");
}

/// `KHR_materials_volume_scatter` on glass with a volume becomes a medium: extinction from
/// the attenuation, single-scatter albedo from the multi-scatter colour by the draft's fit.
/// A grey multi-scatter colour gives a flat albedo at every wavelength (no blue halo from
/// an unbounded fit of a grey coefficient), and the extinction is -ln(c) / d.
#[test]
fn volume_scatter_becomes_a_medium() {
    let mut doc: Value =
        serde_json::from_slice(&std::fs::read(scenes_dir().join("cornell-box.gltf")).unwrap())
            .unwrap();
    for m in doc["materials"].as_array_mut().unwrap() {
        if m["name"] == "white" {
            m["extensions"] = json!({
                "KHR_materials_transmission": {"transmissionFactor": 1.0},
                "KHR_materials_volume": {"thicknessFactor": 0.1, "attenuationColor": [0.5, 0.5, 0.5],
                    "attenuationDistance": 0.2},
                "KHR_materials_volume_scatter": {"multiscatterColor": [0.5, 0.5, 0.5], "scatterAnisotropy": 0.3}
            });
        }
    }
    doc["extensionsUsed"] = json!([
        "KHR_materials_transmission",
        "KHR_materials_volume",
        "KHR_materials_volume_scatter",
        "KHR_materials_emissive_strength"
    ]);
    let bytes = serde_json::to_vec(&doc).unwrap();
    let resolve = |uri: &str| std::fs::read(scenes_dir().join(uri));
    let loaded = load_scene(&bytes, &resolve, &LoadOptions::default()).unwrap();
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let scene = Scene::from_loaded(loaded, &SceneOptions::default()).unwrap();
    assert!(scene.features().media);
    let medium = &scene.media().all()[0];
    use prism_spectrum::Spectrum;
    let expected_t = -(0.5f64.ln()) / 0.2;
    // The draft's fit at rho_ms = 0.5.
    let root = (9.59217f64 + 41.6808 * 0.5 + 17.7126 * 0.25).sqrt();
    let rho = 1.0 - (4.09712 + 4.20863 * 0.5 - root).powi(2);
    for nm in (400..=700).step_by(20) {
        let (a, s) = (
            medium.sigma_a().evaluate(f64::from(nm)),
            medium.sigma_s().evaluate(f64::from(nm)),
        );
        assert!(
            ((a + s) - expected_t).abs() < 2e-3 * expected_t,
            "{nm} nm: sigma_t {}",
            a + s
        );
        assert!(
            (s / (a + s) - rho).abs() < 2e-3,
            "{nm} nm: albedo {} vs {rho}",
            s / (a + s)
        );
    }
    assert_eq!(medium.phase().mean_cosine(), 0.3);
}
