//! `--polarized`, `--camera-polarizer` and `--polarization-png` end to end: the Stokes
//! channels in EXR outputs, `--stats`, sample ranges merging into the single render, and
//! one-line errors.

mod common;

use common::{assert_one_line_errors, prism, prism_ok, temp_dir};

fn scene(name: &str) -> String {
    format!("{}/../scenes/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn polarized_renders_write_stokes_and_merge() {
    let dir = temp_dir("polarized");
    let path = |n: &str| dir.join(n).to_str().unwrap().to_string();
    let window = scene("window.gltf");
    let common = [
        window.as_str(),
        "--width",
        "12",
        "--height",
        "8",
        "--seed",
        "3",
        "--polarized",
    ];
    let run = |extra: &[&str]| prism_ok(&[&["render", "-q"], &common, extra]);
    let out = run(&[
        "--spp",
        "4",
        "-o",
        &path("single.exr"),
        "--polarization-png",
        &path("polarization.png"),
        "--stats",
    ]);
    let stats: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(stats["polarized"], true);
    assert!(
        std::fs::read(path("polarization.png"))
            .unwrap()
            .starts_with(b"\x89PNG")
    );
    run(&["--sample-range", "0..1", "-o", &path("a.exr")]);
    run(&["--sample-range", "1..4", "-o", &path("b.exr")]);
    prism_ok(&[&[
        "merge",
        &path("a.exr"),
        &path("b.exr"),
        "-o",
        &path("merged.exr"),
    ]]);
    let read =
        |name: &str| prism_integrator::decode_exr(&std::fs::read(dir.join(name)).unwrap()).unwrap();
    let (single, merged) = (read("single.exr"), read("merged.exr"));
    let names: Vec<&str> = single.channels.iter().map(|c| c.0.as_str()).collect();
    for c in ["R", "S0.R", "S1.R", "S1.G", "S2.B", "S3.B"] {
        assert!(names.contains(&c), "{c} missing from {names:?}");
    }
    for (a, b) in single.channels.iter().zip(&merged.channels) {
        assert_eq!(a.0, b.0);
        for (x, y) in a.1.iter().zip(&b.1) {
            assert!(
                (x - y).abs() <= 1e-5 * x.abs().max(1e-3),
                "{}: {x} vs {y}",
                a.0
            );
        }
    }
    // The window reflects the street polarized: S1 is not zero everywhere.
    let s1 = &single.channels.iter().find(|c| c.0 == "S1.G").unwrap().1;
    assert!(s1.iter().any(|v| v.abs() > 1e-3));
    // An unpolarized part does not merge with polarized ones.
    prism_ok(&[&[
        "render",
        "-q",
        &window,
        "--width",
        "12",
        "--height",
        "8",
        "--seed",
        "3",
        "--sample-range",
        "4..5",
        "-o",
        &path("c.exr"),
    ]]);
    let out = prism(&[
        "merge",
        &path("a.exr"),
        &path("c.exr"),
        "-o",
        &path("bad.exr"),
    ]);
    assert!(!out.status.success());
}

#[test]
fn polarization_errors_are_one_line() {
    let dir = temp_dir("polarized-errors");
    let png = dir.join("p.png").to_str().unwrap().to_string();
    assert_one_line_errors(&[
        (
            &[
                "render",
                "--width",
                "4",
                "--height",
                "4",
                "--spp",
                "1",
                "--polarization-png",
                &png,
            ],
            "--polarized",
        ),
        (
            &[
                "render",
                "--width",
                "4",
                "--height",
                "4",
                "--spp",
                "1",
                "--camera-polarizer",
                "nan",
                "-o",
                &png,
            ],
            "polarizer",
        ),
        (
            &[
                "render",
                "--width",
                "4",
                "--height",
                "4",
                "--spp",
                "1",
                "--camera-polarizer",
                "inf",
                "-o",
                &png,
            ],
            "polarizer",
        ),
    ]);
}
