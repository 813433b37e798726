//! Every example in docs/scene-format.md loads: material descriptions on the Cornell box's
//! "white" material (glTF material extensions too), light descriptions as an added
//! punctual light, camera descriptions on its camera, root descriptions on the root, and
//! overlays against the Cornell box.

use prism_scene::load::{LoadError, LoadOptions, LoadedGeometry, load_scene};
use prism_scene::spectral::Overlay;
use prism_scene::world::{Scene, SceneOptions};
use serde_json::{Value, json};

fn scenes_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

/// The fenced code blocks of `lang` in the document.
fn blocks(doc: &str, lang: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut current: Option<String> = None;
    for line in doc.lines() {
        match (&mut current, line.trim_start()) {
            (None, l) if l == format!("```{lang}") => current = Some(String::new()),
            (Some(_), "```") => out.push(current.take().unwrap()),
            (Some(text), l) => {
                text.push_str(l);
                text.push('\n');
            }
            _ => {}
        }
    }
    out
}

fn load(doc: &Value, overlay: Option<&Overlay>) -> Result<LoadedGeometry, LoadError> {
    let bytes = serde_json::to_vec(doc).unwrap();
    let dir = scenes_dir();
    load_scene(
        &bytes,
        &move |uri| std::fs::read(dir.join(uri)),
        &LoadOptions::default().overlay(overlay),
    )
}

#[test]
fn every_documented_example_loads() {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/scene-format.md"),
    )
    .unwrap();
    let cornell: Value =
        serde_json::from_slice(&std::fs::read(scenes_dir().join("cornell-box.gltf")).unwrap())
            .unwrap();
    let examples = blocks(&text, "json");
    assert!(
        examples.len() >= 12,
        "found {} JSON examples",
        examples.len()
    );
    for example in &examples {
        let value: Value = serde_json::from_str(example)
            .unwrap_or_else(|e| panic!("example is not JSON ({e}):\n{example}"));
        let mut doc = cornell.clone();
        if value.get("name").is_some() {
            doc["extensionsUsed"] = json!(["KHR_lights_punctual"]);
            doc["extensions"] = json!({"KHR_lights_punctual": {"lights": [value]}});
            let nodes = doc["nodes"].as_array_mut().unwrap();
            nodes
                .push(json!({"name": "lamp", "extensions": {"KHR_lights_punctual": {"light": 0}}}));
            let n = nodes.len() - 1;
            doc["scenes"][0]["nodes"]
                .as_array_mut()
                .unwrap()
                .push(json!(n));
        } else if value.get("aperture").is_some() || value.get("lens").is_some() {
            // A camera's thin lens or lens system: on the box's camera (its files in the
            // scenes folder).
            doc["extensionsUsed"] = json!(["PRISM_spectral"]);
            doc["cameras"][0]["extensions"] = json!({ "PRISM_spectral": value });
            let loaded = load(&doc, None).unwrap_or_else(|e| panic!("{e}:\n{example}"));
            let camera = &loaded.cameras[0];
            assert!(
                camera.lens.is_some() != camera.system.is_some(),
                "{example}"
            );
        } else if let Some(extensions) = value["extensions"].as_object().filter(|e| {
            e.keys().any(|k| k.starts_with("KHR_materials_"))
                && e.keys()
                    .all(|k| k.starts_with("KHR_materials_") || k == "PRISM_spectral")
        }) {
            // A glTF material extension (with a PRISM_spectral description beside it): on
            // the white material, declared as used.
            doc["extensionsUsed"] = json!(extensions.keys().collect::<Vec<_>>());
            for m in doc["materials"].as_array_mut().unwrap() {
                if m["name"] == "white" {
                    m["extensions"] = value["extensions"].clone();
                }
            }
        } else if value.get("extensions").is_some() {
            doc["extensions"] = value["extensions"].clone();
        } else {
            for m in doc["materials"].as_array_mut().unwrap() {
                if m["name"] == "white" {
                    m["extensions"] = json!({ "PRISM_spectral": value });
                }
            }
        }
        let loaded = load(&doc, None).unwrap_or_else(|e| panic!("{e}:\n{example}"));
        Scene::from_loaded(loaded, &SceneOptions::default())
            .unwrap_or_else(|e| panic!("{e}:\n{example}"));
    }
    let overlays = blocks(&text, "toml");
    assert!(!overlays.is_empty());
    for example in &overlays {
        let overlay = Overlay::parse(example).unwrap_or_else(|e| panic!("{e}:\n{example}"));
        let loaded = load(&cornell, Some(&overlay)).unwrap_or_else(|e| panic!("{e}:\n{example}"));
        Scene::from_loaded(loaded, &SceneOptions::default()).unwrap();
    }
}

#[test]
fn the_repository_overlays_load() {
    for entry in std::fs::read_dir(scenes_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let overlay = Overlay::parse(&std::fs::read_to_string(&path).unwrap()).unwrap();
            let gltf = overlay
                .gltf
                .clone()
                .expect("overlays in scenes/ name their glTF");
            let bytes = std::fs::read(scenes_dir().join(gltf)).unwrap();
            let dir = scenes_dir();
            let loaded = load_scene(
                &bytes,
                &move |uri| std::fs::read(dir.join(uri)),
                &LoadOptions::default().overlay(Some(&overlay)),
            )
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            Scene::from_loaded(loaded, &SceneOptions::default()).unwrap();
        }
    }
}

/// Bad time entries are one-line errors naming the material or light, and good ones reach
/// the scene's timeline (the Cornell box's light switched on at 0 and off at 5, its green
/// wall a phosphor).
#[test]
fn time_entries_reach_the_timeline_and_bad_ones_are_errors() {
    let cornell: Value =
        serde_json::from_slice(&std::fs::read(scenes_dir().join("cornell-box.gltf")).unwrap())
            .unwrap();
    let with = |emitter: Value, green: Value| {
        let mut doc = cornell.clone();
        for m in doc["materials"].as_array_mut().unwrap() {
            match m["name"].as_str() {
                Some("white-emitter") => {
                    m["extensions"] = json!({"PRISM_spectral": emitter.clone()})
                }
                Some("green") => m["extensions"] = json!({"PRISM_spectral": green.clone()}),
                _ => {}
            }
        }
        load(&doc, None).and_then(|l| Scene::from_loaded(l, &SceneOptions::default()))
    };
    let phosphor = |extra: Value| {
        let mut p = json!({"type": "fluorescent", "absorption": 0.5, "reemission": "gaussian:520:30", "quantum_yield": 0.9});
        for (k, v) in extra.as_object().unwrap() {
            p[k] = v.clone();
        }
        p
    };
    let scene = with(
        json!({"emission": {"spectrum": "gaussian:365:12", "scale": 4}, "on": [[0, 5]]}),
        phosphor(json!({"lifetime": 2.0})),
    )
    .unwrap();
    let timeline = scene.timeline();
    assert!(timeline.is_timed());
    assert_eq!(timeline.any_on(), &[(0.0, 5.0)]);
    let lamp = (0..scene.lights().all().len() as u32)
        .find(|&i| timeline.schedule(i).is_some())
        .expect("the lamp's triangles are scheduled");
    assert!(timeline.on(lamp, 1.0) && !timeline.on(lamp, 5.0));
    for (emitter, green, needle) in [
        (
            json!({"emission": 1.0, "on": [[5, 1]]}),
            phosphor(json!({})),
            "reversed",
        ),
        (
            json!({"emission": 1.0, "on": [[0, 5], [4, 6]]}),
            phosphor(json!({})),
            "overlap",
        ),
        (
            json!({"emission": 1.0, "on": "always"}),
            phosphor(json!({})),
            "schedule",
        ),
        (
            json!({"type": "diffuse", "reflectance": 0.5, "on": [[0]]}),
            phosphor(json!({})),
            "emission",
        ),
        (
            json!({"emission": 1.0}),
            phosphor(json!({"lifetime": -1.0})),
            "lifetime",
        ),
        (
            json!({"emission": 1.0}),
            phosphor(json!({"lifetimes": [[1.0, 0.5], [2.0, 0.4]]})),
            "sum",
        ),
        (
            json!({"emission": 1.0}),
            json!({"type": "diffuse", "reflectance": 0.5, "lifetime": 1.0}),
            "fluorescent",
        ),
    ] {
        let error = with(emitter, green).err().expect(needle).to_string();
        assert!(error.contains(needle), "'{error}' lacks '{needle}'");
        assert!(
            error.contains("white-emitter") || error.contains("green"),
            "'{error}' names no material"
        );
        assert_eq!(error.lines().count(), 1, "{error}");
    }
}
