//! End-to-end tests of `prism info`.

mod common;

use common::{assert_one_line_errors, assert_success, prism};

#[test]
fn describes_the_canonical_scenes() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes");
    let out = prism(&["info", &format!("{dir}/cornell-bunny.gltf")]);
    assert_success(&out);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("triangles      69463"), "{text}");
    assert!(
        text.contains("area lights    1 instances, 2 triangles"),
        "{text}"
    );
    assert!(text.contains("cameras        camera"), "{text}");
    let out = prism(&["info", &format!("{dir}/cornell-box.gltf")]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("materials      4"));
}

#[test]
fn bad_scenes_are_one_clear_line() {
    let readme = concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md");
    let bunny = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-bunny.gltf");
    assert_one_line_errors(&[
        (&["info", "/no/such/scene.gltf"], "cannot read"),
        (&["info", readme], "invalid glTF"),
        (&["info", bunny, "--scene-index", "7"], "no scene 7"),
        (&["info"], "required"),
    ]);
}

#[test]
fn overlays_are_scenes_and_report_their_spectral_features() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes");
    let out = prism(&["info", &format!("{dir}/cornell-blacklight.toml")]);
    assert_success(&out);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("fluorescence: yes"), "{text}");
    assert!(text.contains("Gaussian band at 365 nm"), "{text}");
    assert!(text.contains("350-830 nm"), "{text}");
    let plain = prism(&["info", &format!("{dir}/cornell-box.gltf")]);
    let text = String::from_utf8_lossy(&plain.stdout);
    assert!(text.contains("fluorescence: no"), "{text}");
    assert!(text.contains("360-830 nm"), "{text}");

    let tmp = common::temp_dir("overlays");
    let write = |name: &str, text: &str| {
        let p = tmp.join(name);
        std::fs::write(&p, text).unwrap();
        p.to_str().unwrap().to_string()
    };
    let gltf = format!("{dir}/cornell-box.gltf");
    let unnamed = write(
        "unnamed.toml",
        "[materials.red]\ntype = \"diffuse\"\nreflectance = 0.5\n",
    );
    let typo = write(
        "typo.toml",
        &format!("gltf = \"{gltf}\"\n[materials.red]\ntype = \"diffuse\"\nreflectence = 0.5\n"),
    );
    let missing = write(
        "missing.toml",
        &format!("gltf = \"{gltf}\"\n[lights.sun]\nspectrum = \"blackbody:5800\"\n"),
    );
    assert_one_line_errors(&[
        (&["info", &unnamed], "must name its scene"),
        (&["info", &typo], "unknown key 'reflectence'"),
        (&["info", &missing], "no light named 'sun'"),
    ]);
}

/// `prism info` says what only a polarized render or an instant shows.
#[test]
fn info_names_polarizing_and_timed_features() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes");
    let text = |scene: &str| {
        let out = prism(&["info", &format!("{dir}/{scene}")]);
        assert_success(&out);
        String::from_utf8_lossy(&out.stdout).to_string()
    };
    let glow = text("glow.gltf");
    assert!(
        glow.contains("1 scheduled sources, 1 phosphorescent materials"),
        "{glow}"
    );
    let window = text("window.gltf");
    assert!(window.contains("polarization   no polarizers"), "{window}");
    assert!(window.contains("time           no schedules"), "{window}");
}
