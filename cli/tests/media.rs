//! Scenes with participating media through the command line: they render, their
//! unsupported settings are one-line errors, and what they cannot show is said.

mod common;

use common::{assert_one_line_errors, prism, prism_ok};

fn scene(name: &str) -> String {
    format!("{}/../scenes/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn media_scenes_render() {
    let dir = std::env::temp_dir().join(format!("prism-media-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for file in [
        "cornell-medium.gltf",
        "media.gltf",
        "cornell-milk-bunny.toml",
    ] {
        let out = dir.join(format!("{file}.exr"));
        let run = prism_ok(&[&[
            "render",
            &scene(file),
            "--width",
            "24",
            "--height",
            "16",
            "--spp",
            "2",
            "--stats",
            "-o",
            out.to_str().unwrap(),
        ]]);
        let stats: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
        assert_eq!(stats["nonfinite_samples"], 0, "{file}");
        assert!(out.exists(), "{file}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn unsupported_settings_for_media_are_one_line_errors() {
    let medium = scene("cornell-medium.gltf");
    let common = [
        "render",
        medium.as_str(),
        "--width",
        "8",
        "--height",
        "8",
        "--spp",
        "1",
        "-o",
    ];
    let out = std::env::temp_dir().join("prism-media-refused.png");
    let out = out.to_str().unwrap();
    let with = |extra: &[&'static str]| -> Vec<&str> {
        common
            .iter()
            .copied()
            .chain([out])
            .chain(extra.iter().copied())
            .collect()
    };
    let splits = with(&["--splits", "2"]);
    assert_one_line_errors(&[(&splits, "splitting")]);
    // Polarized renders of media work (Rayleigh particles polarize).
    prism_ok(&[&with(&["--polarized"])]);
}

/// A medium with glass in the scene: the caustics light paths would carry are missing,
/// and the render says so.
#[test]
fn missing_caustics_are_warned_of() {
    let out = std::env::temp_dir().join(format!("prism-milk-{}.png", std::process::id()));
    let run = prism(&[
        "render",
        &scene("cornell-milk-bunny.toml"),
        "--width",
        "8",
        "--height",
        "8",
        "--spp",
        "1",
        "-o",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning") && stderr.contains("caustics"),
        "{stderr}"
    );
    std::fs::remove_file(out).ok();
}

/// `prism info` says what media a scene has, and that a scene without them has none.
#[test]
fn info_lists_the_media() {
    let out = prism_ok(&[&["info", &scene("media.gltf")]]);
    let text = String::from_utf8_lossy(&out.stdout);
    let line = text
        .lines()
        .find(|l| l.starts_with("media "))
        .expect("a media line");
    for word in [
        "dilute milk",
        "Rayleigh",
        "grid 40x40x40",
        "temperature",
        "fluorescent dye",
    ] {
        assert!(line.contains(word), "{line}");
    }
    let out = prism_ok(&[&["info", &scene("cornell-box.gltf")]]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.lines()
            .any(|l| l.starts_with("media ") && l.contains("none")),
        "{text}"
    );
}
