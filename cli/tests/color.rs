//! End-to-end tests of `prism color`: the binary as a user runs it.

mod common;

use common::{assert_one_line_errors, prism};

fn json(args: &[&str]) -> serde_json::Value {
    let out = prism(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("stdout is one JSON object")
}

fn f(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap()
}

#[test]
fn json_has_the_documented_keys_and_values() {
    let v = json(&["color", "illuminant:D65", "--json"]);
    let xyz = v["XYZ"].as_array().unwrap();
    assert_eq!(f(&xyz[1]), 1.0, "normalized to Y = 1");
    // CIE 015 Table 3: D65 is (0.31272, 0.32903) under the 1931 observer.
    assert!((f(&v["xy"][0]) - 0.31272).abs() < 5e-5);
    assert!((f(&v["xy"][1]) - 0.32903).abs() < 5e-5);
    // The white of sRGB is D65: RGB close to (1, 1, 1) (the tabulated D65 differs from the
    // rounded xy of the sRGB white in the 4th decimal).
    for c in v["rgb"].as_array().unwrap() {
        assert!((f(c) - 1.0).abs() < 2e-3, "{v}");
    }
    assert!((f(&v["cct_kelvin"]) - 6504.0).abs() < 2.0, "{v}");
}

#[test]
fn blackbody_cct_is_its_temperature() {
    for t in ["1500", "2856", "6500", "9000"] {
        let v = json(&["color", &format!("blackbody:{t}"), "--json"]);
        let expected: f64 = t.parse().unwrap();
        assert!((f(&v["cct_kelvin"]) - expected).abs() < 0.01, "{t}: {v}");
    }
}

#[test]
fn every_spec_form_and_option_works() {
    let csv = std::env::temp_dir().join(format!("prism-color-test-{}.csv", std::process::id()));
    std::fs::write(
        &csv,
        "wavelength_nm,value\n400,0.5\n500,1.0\n600,1.0\n700,0.5\n",
    )
    .unwrap();
    let csv = csv.to_str().unwrap().to_string();
    for spec in [
        "blackbody:3000",
        "illuminant:A",
        "illuminant:F11",
        "illuminant:FL11",
        "illuminant:d50",
        "daylight:5000",
        "gaussian:550:40",
        "constant:1",
        csv.as_str(),
    ] {
        for observer in ["cie1931", "cie1964"] {
            for space in [
                "srgb",
                "rec2020",
                "display-p3",
                "dci-p3",
                "acescg",
                "aces2065-1",
                "prophoto",
                "adobe-rgb",
            ] {
                let v = json(&[
                    "color",
                    spec,
                    "--observer",
                    observer,
                    "--space",
                    space,
                    "--json",
                ]);
                assert_eq!(v["space"], space);
                assert!(
                    v["rgb"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .all(|c| f(c).is_finite())
                );
            }
        }
        let text = prism(&["color", spec]);
        assert!(text.status.success());
        assert!(String::from_utf8_lossy(&text.stdout).contains("xy"));
    }
    // A monochromatic green is far from the locus: CCT is null, not a number.
    let v = json(&["color", "gaussian:520:5", "--json"]);
    assert!(v["cct_kelvin"].is_null());
}

/// Bad input: one line on stderr, a non-zero exit code, never a panic.
#[test]
fn bad_input_is_one_clear_line() {
    let cases: &[(&[&str], &str)] = &[
        (&["color", "blackbody:-5"], "temperature"),
        (&["color", "blackbody:0"], "temperature"),
        (&["color", "blackbody:abc"], "not a number"),
        (&["color", "illuminant:D66"], "valid: A, D50"),
        (&["color", "illuminant:F13"], "unknown illuminant"),
        (&["color", "daylight:3000"], "4000"),
        (&["color", "gaussian:550"], "gaussian:CENTER_NM:FWHM_NM"),
        (&["color", "gaussian:550:-1"], "FWHM"),
        (&["color", "constant:0"], "luminance"),
        (&["color", "constant:inf"], "finite"),
        (&["color", "gaussian:100:5"], "luminance"),
        (&["color", "/no/such/file.csv"], "neither"),
        (
            &["color", "blackbody:6500", "--observer", "cie2000"],
            "observer",
        ),
        (
            &["color", "blackbody:6500", "--space", "xyz"],
            "colour space",
        ),
        (&["color"], "required"),
        (&["color", "blackbody:6500", "--bogus"], "--bogus"),
        (&["frobnicate"], "frobnicate"),
    ];
    assert_one_line_errors(cases);
}

#[test]
fn malformed_csv_files_are_errors() {
    let dir = std::env::temp_dir();
    for (name, content, needle) in [
        ("unsorted", "500,1\n400,1\n", "increase"),
        ("three-columns", "400,1,2\n500,1,2\n", "two numbers"),
        ("one-row", "400,1\n", "at least 2"),
        ("text", "400,abc\n500,1\n", "two numbers"),
        ("empty", "", "at least 2"),
        ("nan", "400,nan\n500,1\n", "not finite"),
    ] {
        let path = dir.join(format!("prism-bad-{name}-{}.csv", std::process::id()));
        std::fs::write(&path, content).unwrap();
        let out = prism(&["color", path.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{name}: {stderr}");
        assert!(stderr.contains(needle), "{name}: {stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1);
    }
}

#[test]
fn help_has_examples() {
    let out = prism(&["color", "--help"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("prism color blackbody:6500"));
}

/// `prism color ... | head -1`: a reader that stops reading is not an error, and above all
/// not a panic (`println!` panicked on the closed pipe).
#[test]
fn a_closed_pipe_on_stdout_ends_quietly() {
    let (reader, writer) = std::io::pipe().expect("a pipe");
    drop(reader);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(["color", "blackbody:6500"])
        .stdout(writer)
        .output()
        .expect("prism runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.is_empty(), "{stderr}");
}

/// Output lost to a full disk is one line on stderr and a failed exit.
#[cfg(target_os = "linux")]
#[test]
fn a_full_disk_on_stdout_fails_with_one_line() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .expect("/dev/full");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(["color", "blackbody:6500"])
        .stdout(full)
        .output()
        .expect("prism runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("prism: error: cannot write to standard output"),
        "{stderr}"
    );
}
