//! Spectral descriptions: the `PRISM_spectral` extension and the TOML overlay, what they
//! build, and their errors.

use prism_scene::load::{LightDesc, LoadError, LoadOptions, LoadedGeometry, load_scene};
use prism_scene::spectral::Overlay;
use prism_scene::world::{Environment, Material, Scene, SceneOptions, SceneSpectrum};
use prism_spectrum::Spectrum;
use serde_json::{Value, json};

fn scenes_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

fn cornell_json() -> Value {
    serde_json::from_slice(&std::fs::read(scenes_dir().join("cornell-box.gltf")).unwrap()).unwrap()
}

/// Loads `doc` (the Cornell box, edited) with an optional overlay; `files` maps extra
/// file names (CSV spectra) to their text.
fn load(
    doc: &Value,
    overlay: Option<&str>,
    files: &[(&str, &str)],
) -> Result<LoadedGeometry, LoadError> {
    let overlay = overlay.map(Overlay::parse).transpose()?;
    let bytes = serde_json::to_vec(doc).unwrap();
    let files: Vec<(String, String)> = files
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    load_scene(
        &bytes,
        &move |uri| match files.iter().find(|(n, _)| n == uri) {
            Some((_, text)) => Ok(text.clone().into_bytes()),
            None => std::fs::read(scenes_dir().join(uri)),
        },
        &LoadOptions::default().overlay(overlay.as_ref()),
    )
}

fn with_material_extension(name: &str, description: Value) -> Value {
    let mut doc = cornell_json();
    for m in doc["materials"].as_array_mut().unwrap() {
        if m["name"] == name {
            m["extensions"] = json!({ "PRISM_spectral": description });
        }
    }
    doc
}

fn surface(loaded: &LoadedGeometry, name: &str) -> Material {
    loaded
        .materials
        .iter()
        .find(|m| m.name == name)
        .and_then(|m| m.spectral.as_ref()?.surface.clone())
        .unwrap_or_else(|| panic!("{name} has no spectral surface"))
}

fn error(result: Result<LoadedGeometry, LoadError>) -> String {
    match result {
        Ok(_) => panic!("should fail"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn every_spectrum_form_parses_to_its_values() {
    let csv = "nm,value\n400,0.2\n700,0.6\n";
    for (form, at_550) in [
        (json!(0.25), 0.25),
        (json!([[400, 0.2], [700, 0.6]]), 0.4),
        (json!("csv:refl.csv"), 0.4),
        (
            json!({"spectrum": [[400, 0.2], [700, 0.6]], "scale": 0.5}),
            0.2,
        ),
        (json!("constant:0.7"), 0.7),
    ] {
        let doc = with_material_extension("white", json!({"type": "diffuse", "reflectance": form}));
        let loaded = load(&doc, None, &[("refl.csv", csv)]).unwrap();
        let Material::Diffuse { reflectance } = surface(&loaded, "white") else {
            panic!("not diffuse")
        };
        assert!(
            (reflectance.evaluate(550.0) - at_550).abs() < 1e-9,
            "{form}"
        );
    }
    // RGB is upsampled as a reflectance: grey stays grey.
    let doc = with_material_extension(
        "white",
        json!({"type": "diffuse", "reflectance": {"rgb": [0.5, 0.5, 0.5]}}),
    );
    let Material::Diffuse { reflectance } = surface(&load(&doc, None, &[]).unwrap(), "white")
    else {
        panic!()
    };
    for nm in [400.0, 550.0, 700.0] {
        assert!((reflectance.evaluate(nm) - 0.5).abs() < 1e-6);
    }
}

#[test]
fn dielectrics_take_every_ior_form() {
    for (ior, n_d) in [
        (json!(1.33), 1.33),
        (json!("glass:bk7"), 1.5168),
        (json!({"abbe": {"nd": 1.5168, "vd": 64.17}}), 1.5168),
        (
            json!({"cauchy": {"A": 1.5, "B": 4200.0}}),
            1.5 + 4200.0 / 587.5618f64.powi(2),
        ),
        // BK7's published Sellmeier terms.
        (
            json!({"sellmeier": {"B": [1.03961212, 0.231792344, 1.01046945], "C": [0.00600069867, 0.0200179144, 103.560653]}}),
            1.5168,
        ),
    ] {
        let doc = with_material_extension("white", json!({"type": "dielectric", "ior": ior}));
        let Material::Dielectric {
            ior: n, roughness, ..
        } = surface(&load(&doc, None, &[]).unwrap(), "white")
        else {
            panic!("not a dielectric")
        };
        assert_eq!(roughness, 0.0);
        assert!(
            (n.evaluate(587.5618) - n_d).abs() < 2e-4,
            "{ior}: {}",
            n.evaluate(587.5618)
        );
    }
}

#[test]
fn conductors_from_names_or_spectra() {
    let doc = with_material_extension(
        "white",
        json!({"type": "conductor", "metal": "au", "roughness": 0.2}),
    );
    let Material::Conductor { eta, k, roughness } =
        surface(&load(&doc, None, &[]).unwrap(), "white")
    else {
        panic!()
    };
    assert_eq!(roughness, 0.2);
    // Gold: eta ~0.3 and k ~2.9 in the red (Johnson and Christy).
    assert!(eta.evaluate(650.0) < 0.4 && k.evaluate(650.0) > 2.5);
    let doc = with_material_extension(
        "white",
        json!({"type": "conductor", "eta": 1.5, "k": [[400, 3.0], [700, 4.0]]}),
    );
    assert!(matches!(
        surface(&load(&doc, None, &[]).unwrap(), "white"),
        Material::Conductor { .. }
    ));
}

#[test]
fn fluorescent_materials_conserve_energy_and_mark_the_scene() {
    let doc = with_material_extension(
        "white",
        json!({"type": "fluorescent", "reflectance": 0.3, "absorption": {"spectrum": "gaussian:365:40", "scale": 0.7},
               "reemission": "gaussian:520:30", "quantum_yield": 0.6}),
    );
    let loaded = load(&doc, None, &[]).unwrap();
    assert!(surface(&loaded, "white").fluorescent());
    let scene = Scene::from_loaded(loaded, &SceneOptions::default()).unwrap();
    assert!(scene.features().fluorescence);
    let plain = load(&cornell_json(), None, &[]).unwrap();
    assert!(
        !Scene::from_loaded(plain, &SceneOptions::default())
            .unwrap()
            .features()
            .fluorescence
    );

    // Reflectance plus absorption above 1 would create energy.
    let doc = with_material_extension(
        "white",
        json!({"type": "fluorescent", "reflectance": 0.5, "absorption": 0.6,
               "reemission": "gaussian:520:30", "quantum_yield": 0.5}),
    );
    assert!(error(load(&doc, None, &[])).contains("exceeds 1"));
    // So would a matrix whose row integrates above 1 (2 bins of 100 nm, 0.012 per nm: 1.2).
    let doc = with_material_extension(
        "white",
        json!({"type": "fluorescent", "range": [400, 600], "matrix": {"rows": [[0.0, 0.012], [0.0, 0.004]]}}),
    );
    assert!(error(load(&doc, None, &[])).contains("re-radiates"));
    let doc = with_material_extension(
        "white",
        json!({"type": "fluorescent", "range": [400, 600], "matrix": {"rows": [[0.0, 0.004], [0.0, 0.004]]}}),
    );
    assert!(
        load(&doc, None, &[]).unwrap().materials[1]
            .spectral
            .is_some()
    );
}

#[test]
fn spectral_emission_and_environment() {
    let mut doc = with_material_extension(
        "white-emitter",
        json!({"emission": {"spectrum": "blackbody:3000", "scale": 4.0}}),
    );
    doc["extensions"] = json!({"PRISM_spectral": {"environment": "illuminant:D65"}});
    let loaded = load(&doc, None, &[]).unwrap();
    assert!(loaded.spectral.environment.is_some());
    let scene = Scene::from_loaded(loaded, &SceneOptions::default()).unwrap();
    let emitter = scene.emission_spectra().first().unwrap();
    // Peak-normalized 3000 K blackbody times 4: its peak (966 nm) is 4, 560 nm much less.
    assert!((emitter.max_value() - 4.0).abs() < 1e-6);
    assert!(scene.lights().environment().is_some());
}

/// An environment image from the root's description and from a TOML overlay (the file
/// relative to the glTF, rotation and strength), with errors naming what is wrong.
#[test]
fn environment_images_from_the_root_and_overlays() {
    let mut doc = cornell_json();
    doc["extensions"] = json!({"PRISM_spectral": {"environment": {"image": "sky.hdr", "rotation": 30, "strength": 2}}});
    let loaded = load(&doc, None, &[]).unwrap();
    let Some(Environment::Map(map)) = &loaded.spectral.environment else {
        panic!("no environment image")
    };
    assert_eq!(map.size(), (256, 128));
    let overlay =
        "gltf = \"cornell-box.gltf\"\nenvironment = { image = \"sky.hdr\", rotation = 90 }\n";
    let loaded = load(&cornell_json(), Some(overlay), &[]).unwrap();
    assert!(matches!(
        loaded.spectral.environment,
        Some(Environment::Map(_))
    ));
    for (environment, needle) in [
        (json!({"image": "missing.hdr"}), "missing.hdr"),
        (
            json!({"image": "cornell-box.gltf"}),
            "not an OpenEXR or Radiance",
        ),
        (json!({"image": "sky.hdr", "strength": -1}), "strength"),
        (json!({"image": "sky.hdr", "tilt": 3}), "tilt"),
    ] {
        let mut doc = cornell_json();
        doc["extensions"] = json!({"PRISM_spectral": {"environment": environment}});
        let e = load(&doc, None, &[]).unwrap_err().to_string();
        assert!(e.contains("environment") && e.contains(needle), "{e}");
    }
}

#[test]
fn overlays_override_by_name() {
    let overlay = r#"
gltf = "cornell-box.gltf"
environment = 0.1

[materials.red]
type = "conductor"
metal = "cu"

[materials.white-emitter]
emission = "gaussian:365:10"
"#;
    let parsed = Overlay::parse(overlay).unwrap();
    assert_eq!(parsed.gltf.as_deref(), Some("cornell-box.gltf"));
    let loaded = load(&cornell_json(), Some(overlay), &[]).unwrap();
    assert!(matches!(
        surface(&loaded, "red"),
        Material::Conductor { .. }
    ));
    let emitter = loaded
        .materials
        .iter()
        .find(|m| m.name == "white-emitter")
        .unwrap();
    let e = emitter
        .spectral
        .as_ref()
        .unwrap()
        .emission
        .as_ref()
        .unwrap();
    assert!((e.evaluate(365.0) - 1.0).abs() < 1e-9);
    assert!(
        matches!(loaded.spectral.environment, Some(Environment::Uniform(SceneSpectrum::Constant(v))) if v == 0.1)
    );
}

#[test]
fn punctual_lights_take_spectra_in_either_unit() {
    let mut doc = cornell_json();
    doc["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    doc["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"name": "uv", "type": "point", "intensity": 2.0,
         "extensions": {"PRISM_spectral": {"spectrum": "gaussian:365:10", "units": "radiometric"}}},
        {"name": "warm", "type": "point", "intensity": 100.0}
    ]}});
    let nodes = doc["nodes"].as_array_mut().unwrap();
    nodes.push(json!({"name": "uv-node", "translation": [0.0, 0.5, 0.0], "extensions": {"KHR_lights_punctual": {"light": 0}}}));
    nodes.push(json!({"name": "warm-node", "translation": [0.0, 0.4, 0.0], "extensions": {"KHR_lights_punctual": {"light": 1}}}));
    let n = nodes.len();
    doc["scenes"][0]["nodes"]
        .as_array_mut()
        .unwrap()
        .extend([json!(n - 2), json!(n - 1)]);
    let loaded = load(&doc, None, &[]).unwrap();
    let points: Vec<(f64, f64)> = loaded
        .lights
        .iter()
        .filter_map(|l| match l {
            LightDesc::Point {
                spectrum, scale, ..
            } => Some((spectrum.evaluate(365.0), *scale)),
            _ => None,
        })
        .collect();
    assert_eq!(points.len(), 2);
    // The UV light's intensity is radiometric: the Gaussian's peak 1 times 2.
    assert!(
        points
            .iter()
            .any(|&(v, s)| (v - 1.0).abs() < 1e-9 && s == 2.0)
    );
    // A UV source has no luminance: photometric units are an error that says what to do.
    let overlay = "[lights.uv]\nspectrum = \"gaussian:300:5\"\nunits = \"photometric\"\n";
    assert!(error(load(&doc, Some(overlay), &[])).contains("radiometric"));
    let overlay = "[lights.warm]\nspectrum = \"blackbody:2700\"\n";
    assert!(load(&doc, Some(overlay), &[]).is_ok());
}

#[test]
fn bad_descriptions_are_errors_naming_the_problem() {
    let cases = [
        (
            json!({"type": "diffuse", "reflectance": 1.5}),
            "not in [0, 1]",
        ),
        (
            json!({"type": "diffuse", "reflectance": "blackbody:-3"}),
            "temperature",
        ),
        (
            json!({"type": "diffuse", "reflectance": "illuminant:D99"}),
            "D65",
        ),
        (
            json!({"type": "diffuse", "reflectance": "nonsense"}),
            "not a spectrum",
        ),
        (
            json!({"type": "diffuse", "reflectance": "csv:missing.csv"}),
            "missing.csv",
        ),
        (
            json!({"type": "diffuse", "reflectance": [[400, 0.1], [300, 0.2]]}),
            "spectral",
        ),
        (
            json!({"type": "diffuse", "reflectnce": 0.5}),
            "unknown key 'reflectnce'",
        ),
        (json!({"type": "glossy"}), "diffuse, plastic, dielectric"),
        (
            json!({"type": "plastic", "reflectance": 0.5, "ior": "glass:bk7"}),
            "one index for every wavelength",
        ),
        (
            json!({"type": "plastic", "reflectance": 0.5, "ior": 0.8}),
            "ior 0.8 is not in (1, 4]",
        ),
        (
            json!({"type": "plastic", "reflectance": 0.5, "nonlinear": 1}),
            "nonlinear must be true or false",
        ),
        (json!({"type": "plastic"}), "needs 'reflectance'"),
        (json!({"type": "dielectric", "ior": 0.5}), "below 1"),
        (
            json!({"type": "dielectric", "ior": "glass:unobtainium"}),
            "bk7",
        ),
        (json!({"type": "conductor", "metal": "mithril"}), "au"),
        (
            json!({"type": "dielectric", "ior": 1.5, "roughness": 2}),
            "roughness",
        ),
        (
            json!({"type": "fluorescent", "absorption": 0.5, "reemission": "gaussian:520:30", "quantum_yield": 1.5}),
            "quantum yield",
        ),
        (
            json!({"type": "fluorescent", "absorption": 0.5, "reemission": 0.0, "quantum_yield": 0.5}),
            "emission spectrum is zero",
        ),
        (json!({"emission": -1.0}), "emission"),
        (json!([1, 2]), "must be an object"),
    ];
    for (description, expected) in cases {
        let e = error(load(
            &with_material_extension("white", description.clone()),
            None,
            &[],
        ));
        assert!(e.contains("material white"), "{description}: {e}");
        assert!(
            e.contains(expected),
            "{description}: '{e}' lacks '{expected}'"
        );
    }
    // Overlays: TOML syntax, unknown names (listing the valid ones), wrong shapes.
    for (overlay, expected) in [
        (
            "[materials.blue]\ntype = \"diffuse\"\nreflectance = 0.5\n",
            "white-emitter, white, green, red",
        ),
        (
            "[lights.lamp]\nspectrum = \"blackbody:3000\"\n",
            "lights: none",
        ),
        ("materials = 3\n", "table of named entries"),
        ("[materials.red\n", "overlay"),
        ("environment = \"nonsense\"\n", "environment"),
    ] {
        let e = error(load(&cornell_json(), Some(overlay), &[]));
        assert!(e.contains(expected), "{overlay}: '{e}' lacks '{expected}'");
    }
}

#[test]
fn files_that_require_the_extension_still_load() {
    let mut doc = with_material_extension("white", json!({"type": "diffuse", "reflectance": 0.5}));
    doc["extensionsUsed"] = json!(["KHR_materials_emissive_strength", "PRISM_spectral"]);
    doc["extensionsRequired"] = json!(["PRISM_spectral"]);
    assert!(load(&doc, None, &[]).is_ok());
}

#[test]
fn gltf_volumes_absorb_by_beer_lambert() {
    let mut doc = cornell_json();
    doc["extensionsUsed"] = json!(["KHR_materials_transmission", "KHR_materials_volume"]);
    for m in doc["materials"].as_array_mut().unwrap() {
        if m["name"] == "white" {
            m["extensions"] = json!({
                "KHR_materials_transmission": {"transmissionFactor": 1.0},
                "KHR_materials_volume": {"thicknessFactor": 1.0, "attenuationDistance": 2.0,
                                         "attenuationColor": [0.5, 0.5, 0.5]}
            });
        }
    }
    let loaded = load(&doc, None, &[]).unwrap();
    let scene = Scene::from_loaded(loaded, &SceneOptions::default()).unwrap();
    // Tinted by its (grey) base colour, it is glass in the metallic-roughness material; the
    // volume absorbs inside either way.
    let white = &scene.materials()[1];
    assert!(white.transmissive());
    let sigma = white
        .absorption()
        .expect("white should bound an absorbing volume");
    // What is left after 2 units is 0.5: sigma = ln 2 / 2 at every wavelength.
    for nm in [400.0, 550.0, 700.0] {
        assert!((sigma.evaluate(nm) - std::f64::consts::LN_2 / 2.0).abs() < 1e-6);
    }
    // A spectral absorption in PRISM_spectral.
    let doc = with_material_extension(
        "white",
        json!({"type": "dielectric", "ior": 1.33, "absorption": [[400, 0.01], [700, 0.4]]}),
    );
    assert!(matches!(
        surface(&load(&doc, None, &[]).unwrap(), "white"),
        Material::Dielectric {
            absorption: Some(_),
            ..
        }
    ));
}

#[test]
fn scenes_can_describe_a_camera_response() {
    let mut doc = cornell_json();
    doc["extensions"] = json!({"PRISM_spectral": {"camera_response": {
        "r": "gaussian:900:60", "g": "gaussian:850:60", "b": [[700, 0.0], [800, 1.0], [900, 0.0]]}}});
    let loaded = load(&doc, None, &[]).unwrap();
    let curves = loaded.spectral.camera_response.as_ref().unwrap();
    assert!((curves[0].evaluate(900.0) - 1.0).abs() < 1e-9);
    assert!((curves[2].evaluate(800.0) - 1.0).abs() < 1e-9);
    // Where a 60 nm Gaussian exceeds 0.1% of its peak: +-3.72 sigma = +-95 nm.
    let (lo, hi) = curves[1].extent(1e-3).unwrap();
    assert!(
        (lo - 755.0).abs() <= 1.0 && (hi - 945.0).abs() <= 1.0,
        "{lo}-{hi}"
    );
    doc["extensions"] = json!({"PRISM_spectral": {"camera_response": {"r": 1.0, "g": 1.0}}});
    assert!(error(load(&doc, None, &[])).contains("camera_response needs 'b'"));
}

/// Measured spectra for the glTF extensions' colours and index: `sheen_color` replaces
/// KHR_materials_sheen's colour, `specular_color` KHR_materials_specular's (adding the
/// extension at its defaults), `film_ior` the film's index (per wavelength at a hit);
/// asking for a sheen or a film the material lacks is an error naming it; the TOML
/// overlay says the same.
#[test]
fn spectral_colours_and_indices_replace_the_extensions() {
    let with = |khr: Value, spectral: Value| {
        let mut doc = cornell_json();
        for m in doc["materials"].as_array_mut().unwrap() {
            if m["name"] == "white" {
                let mut ext = khr.clone();
                ext["PRISM_spectral"] = spectral.clone();
                m["extensions"] = ext;
            }
        }
        doc
    };
    let white = |loaded: &LoadedGeometry| {
        loaded
            .materials
            .iter()
            .find(|m| m.name == "white")
            .unwrap()
            .clone()
    };
    let sheen = json!({"KHR_materials_sheen": {"sheenColorFactor": [1.0, 1.0, 1.0], "sheenRoughnessFactor": 0.5}});
    let loaded = load(
        &with(
            sheen.clone(),
            json!({"sheen_color": [[400, 0.1], [700, 0.9]]}),
        ),
        None,
        &[],
    )
    .unwrap();
    let layers = white(&loaded).layers.expect("layers");
    let colour = &layers.sheen.as_ref().unwrap().color;
    assert!(
        (colour.evaluate(400.0) - 0.1).abs() < 1e-9 && (colour.evaluate(700.0) - 0.9).abs() < 1e-9
    );
    let loaded = load(
        &with(
            json!({}),
            json!({"specular_color": [[400, 2.0], [700, 0.5]]}),
        ),
        None,
        &[],
    )
    .unwrap();
    let specular = white(&loaded).layers.unwrap().specular.unwrap();
    assert_eq!(specular.factor, 1.0);
    assert!((specular.color.evaluate(400.0) - 2.0).abs() < 1e-9);
    let film = json!({"KHR_materials_iridescence": {"iridescenceFactor": 1.0}});
    let loaded = load(
        &with(film.clone(), json!({"film_ior": "glass:sf11"})),
        None,
        &[],
    )
    .unwrap();
    let desc = white(&loaded).iridescence.unwrap();
    let lambdas = prism_spectrum::SampledWavelengths::new([450.0, 650.0], [1.0; 2]).unwrap();
    let at = prism_scene::world::TexCoords::default();
    let iors = desc.at(&at, &lambdas).iors.expect("a spectral index");
    assert!(iors[0] > iors[1] + 0.01 && iors[1] > 1.7, "{iors:?}");
    for (khr, spectral, missing) in [
        (
            json!({}),
            json!({"sheen_color": 0.5}),
            "KHR_materials_sheen",
        ),
        (
            json!({}),
            json!({"film_ior": 1.4}),
            "KHR_materials_iridescence",
        ),
    ] {
        let e = error(load(&with(khr, spectral), None, &[]));
        assert!(e.contains(missing) && e.contains("white"), "{e}");
    }
    // The overlay, on a file that has the film.
    let loaded = load(
        &with(film, json!({})),
        Some("[materials.white]\nfilm_ior = \"glass:bk7\"\n"),
        &[],
    )
    .unwrap();
    assert!(white(&loaded).iridescence.unwrap().ior_spectrum.is_some());
}
