//! End-to-end tests of `prism upsample` and `prism table`.

use std::io::Write;
mod common;

use common::{assert_one_line_errors, assert_success, prism};
use std::process::{Command, Output, Stdio};

fn prism_stdin(args: &[&str], input: &str) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("prism runs");
    child
        .stdin
        .take()
        .unwrap()
        .write_all(input.as_bytes())
        .unwrap();
    child.wait_with_output().unwrap()
}

fn temp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("prism-cli-{}-{name}", std::process::id()))
}

#[test]
fn exact_upsampling_round_trips() {
    let out = prism(&["upsample", "0.8", "0.2", "0.1", "--json"]);
    assert_success(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v["delta_e_2000"].as_f64().unwrap() < 1e-3);
    assert_eq!(v["coefficients"].as_array().unwrap().len(), 3);
    for space in [
        "srgb",
        "display-p3",
        "rec2020",
        "acescg",
        "aces2065-1",
        "prophoto",
        "adobe-rgb",
        "dci-p3",
    ] {
        let out = prism(&["upsample", "--space", space, "0.3", "0.5", "0.2", "--json"]);
        assert!(
            out.status.success(),
            "{space}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert!(v["delta_e_2000"].as_f64().unwrap() < 1e-3, "{space}: {v}");
    }
    let black: serde_json::Value =
        serde_json::from_slice(&prism(&["upsample", "0", "0", "0", "--json"]).stdout).unwrap();
    assert_eq!(black["black"], true);
    assert_eq!(black["coefficients"][2], "-inf");
    // White's constant 1 is c2 = +inf, which JSON numbers cannot hold (it was null).
    let white: serde_json::Value =
        serde_json::from_slice(&prism(&["upsample", "1", "1", "1", "--json"]).stdout).unwrap();
    assert_eq!(white["black"], false);
    assert_eq!(white["coefficients"], serde_json::json!([0.0, 0.0, "inf"]));
}

#[test]
fn stdin_mode_writes_one_line_per_colour_and_nothing_else() {
    let out = prism_stdin(
        &["upsample", "--stdin"],
        "0.8 0.2 0.1\n0 0 0\n0.5 0.5 0.5\n1 1 1\n",
    );
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 4, "{text}");
    for line in &lines {
        assert_eq!(line.split_whitespace().count(), 3, "{line}");
    }
    assert!(lines[1].ends_with("-inf"), "black: {}", lines[1]);
    let bad = prism_stdin(&["upsample", "--stdin"], "0.1 0.2 0.3\n0.5 nope 0.1\n");
    assert_eq!(bad.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("line 2"));
}

#[test]
fn tables_fit_describe_and_look_up() {
    let path = temp("srgb-8.bin");
    let p = path.to_str().unwrap();
    let out = prism(&["table", "fit", "--space", "srgb", "--res", "8", "-o", p]);
    assert_success(&out);
    assert!(String::from_utf8_lossy(&out.stdout).contains("reachable nodes: 100.0000%"));
    let info = prism(&["table", "info", p]);
    assert!(String::from_utf8_lossy(&info.stdout).contains("resolution    8"));
    let lookup = prism(&["upsample", "--table", p, "0.8", "0.2", "0.1", "--json"]);
    assert!(lookup.status.success());
    let refined = prism(&[
        "upsample", "--table", p, "--refine", "0.8", "0.2", "0.1", "--json",
    ]);
    let de = |o: &Output| {
        serde_json::from_slice::<serde_json::Value>(&o.stdout).unwrap()["delta_e_2000"]
            .as_f64()
            .unwrap()
    };
    assert!(
        de(&refined) < de(&lookup),
        "refinement improves on the 8^3 lookup"
    );
    // A table for another space is refused.
    let wrong = prism(&[
        "upsample", "--table", p, "--space", "rec2020", "0.5", "0.5", "0.4",
    ]);
    assert_eq!(wrong.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&wrong.stderr).contains("not for --space rec2020"));
    // A corrupted table is refused with a reason.
    let mut bytes = std::fs::read(&path).unwrap();
    let mid = bytes.len() / 2;
    bytes[mid] ^= 1;
    let broken = temp("broken.bin");
    std::fs::write(&broken, &bytes).unwrap();
    let out = prism(&["table", "info", broken.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("checksum"));
    let _ = std::fs::remove_file(path);
    let _ = std::fs::remove_file(broken);
}

#[test]
fn bad_input_is_one_clear_line() {
    let cases: &[(&[&str], &str)] = &[
        (&["upsample", "0.5", "0.5"], "three components"),
        (&["upsample", "nan", "0.5", "0.5"], "not finite"),
        (
            &["upsample", "--space", "cmyk", "0.5", "0.5", "0.5"],
            "colour space",
        ),
        (
            &[
                "upsample",
                "--table",
                "/no/such/table.bin",
                "0.1",
                "0.2",
                "0.3",
            ],
            "cannot read",
        ),
        (&["upsample", "--refine", "0.1", "0.2", "0.3"], "--table"),
        (
            &["table", "fit", "--res", "1", "-o", "/tmp/x.bin"],
            "resolution",
        ),
        (
            &["table", "fit", "--res", "4", "-o", "/no/such/dir/x.bin"],
            "cannot write",
        ),
        (&["table", "info", "/no/such/file"], "cannot read"),
        (
            &["upsample", "--space", "0.7,0.3,0.2", "0.5", "0.5", "0.5"],
            "six numbers",
        ),
        (
            &[
                "upsample",
                "--space",
                "0.7,0.3,0.7,0.3,0.1,0.05",
                "0.5",
                "0.5",
                "0.5",
            ],
            "collinear",
        ),
        (
            &[
                "upsample",
                "--space",
                "0.7,0.3,0.2,0.75,0.12,0.05@sunlight",
                "0.5",
                "0.5",
                "0.5",
            ],
            "illuminant",
        ),
        (
            &[
                "upsample",
                "--space",
                "0.7,0.3,0.2,0.75,0.12,0.05",
                "--table",
                "auto",
                "0.5",
                "0.5",
                "0.5",
            ],
            "named spaces only",
        ),
    ];
    assert_one_line_errors(cases);
}

/// A space given by its primaries and illuminant: sRGB's own primaries under D65 fit
/// exactly as `--space srgb` does, and a space of other primaries under D50 fits, makes
/// a table that records its primaries, and only accepts that table for itself.
#[test]
fn user_defined_spaces_fit_and_make_tables() {
    let coefficients = |space: &str| -> serde_json::Value {
        let out = prism(&["upsample", "--space", space, "0.8", "0.2", "0.1", "--json"]);
        assert_success(&out);
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert!(v["delta_e_2000"].as_f64().unwrap() < 1e-3, "{space}: {v}");
        v["coefficients"].clone()
    };
    assert_eq!(
        coefficients("0.64,0.33,0.30,0.60,0.15,0.06@illuminant:D65"),
        coefficients("srgb")
    );
    let wide = "0.7,0.3,0.2,0.75,0.12,0.05@illuminant:D50";
    let dir = common::temp_dir("custom-space");
    let file = dir.join("wide.bin");
    let file = file.to_str().unwrap();
    assert_success(&prism(&[
        "table", "fit", "--space", wide, "--res", "8", "-o", file,
    ]));
    let info = prism(&["table", "info", file]);
    assert_success(&info);
    assert!(String::from_utf8_lossy(&info.stdout).contains("r (0.7, 0.3)"));
    let looked_up = prism(&[
        "upsample", "--space", wide, "--table", file, "0.5", "0.3", "0.2", "--json",
    ]);
    assert_success(&looked_up);
    let other = prism(&[
        "upsample", "--space", "srgb", "--table", file, "0.5", "0.3", "0.2",
    ]);
    assert!(!other.status.success());
    assert!(String::from_utf8_lossy(&other.stderr).contains("is a table for"));
}

/// `--table auto` fits the default table on first use, caches it, reuses it, and replaces
/// a damaged cache file.
#[test]
fn default_tables_are_cached() {
    let cache = temp("cache");
    let _ = std::fs::remove_dir_all(&cache);
    let run = || {
        Command::new(env!("CARGO_BIN_EXE_prism"))
            .args(["upsample", "--table", "auto", "--json", "0.8", "0.2", "0.1"])
            .env("PRISM_CACHE_DIR", &cache)
            .output()
            .unwrap()
    };
    let first = run();
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let file = cache
        .join("tables")
        .join(format!("srgb-64-v{}.bin", prism_upsample::FORMAT_VERSION));
    let written = std::fs::metadata(&file)
        .expect("the table was cached")
        .modified()
        .unwrap();
    let second = run();
    assert_eq!(
        first.stdout, second.stdout,
        "the cached table gives the same answer"
    );
    assert_eq!(
        std::fs::metadata(&file).unwrap().modified().unwrap(),
        written,
        "not refitted"
    );
    std::fs::write(&file, b"garbage").unwrap();
    let third = run();
    assert!(third.status.success());
    assert!(String::from_utf8_lossy(&third.stderr).contains("refitting"));
    assert_eq!(first.stdout, third.stdout);
    let _ = std::fs::remove_dir_all(&cache);
}

/// `prism upsample --stdin ... | head -1`: a reader that closes the pipe ends the stream
/// quietly, without an error.
#[test]
fn stdin_stream_ends_quietly_at_a_closed_pipe() {
    let (reader, writer) = std::io::pipe().expect("a pipe");
    drop(reader);
    let mut child = Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(["upsample", "--stdin"])
        .stdin(Stdio::piped())
        .stdout(writer)
        .stderr(Stdio::piped())
        .spawn()
        .expect("prism runs");
    let mut input = child.stdin.take().expect("stdin");
    // The child may stop reading once its output is refused: a failed write here is fine.
    let _ = input.write_all(b"0.8 0.2 0.1\n0.5 0.5 0.5\n");
    drop(input);
    let out = child.wait_with_output().expect("prism ends");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.is_empty(), "{stderr}");
}
