//! End-to-end tests of render sessions: time budget, interruption, checkpoints and resume.

mod common;

use std::process::{Command, Stdio};

use common::{assert_one_line_errors, assert_success, prism, temp_dir};

const SIZE: [&str; 4] = ["--width", "24", "--height", "16"];

fn render(extra: &[&str]) -> std::process::Output {
    let mut args = vec!["render", "-q"];
    args.extend(SIZE);
    args.extend(extra);
    prism(&args)
}

/// The `prism` attribute of an EXR: `spp=N;...` (headers are uncompressed text).
fn spp_in_header(path: &std::path::Path) -> u64 {
    let bytes = std::fs::read(path).unwrap();
    let text = String::from_utf8_lossy(&bytes[..bytes.len().min(4096)]).to_string();
    let at = text.find("spp=").expect("spp in the header") + 4;
    text[at..]
        .chars()
        .take_while(char::is_ascii_digit)
        .collect::<String>()
        .parse()
        .unwrap()
}

#[test]
fn checkpoint_and_resume_equal_the_uninterrupted_render() {
    let dir = temp_dir("resume");
    let p = |n: &str| dir.join(n).to_str().unwrap().to_string();
    assert!(
        render(&["--spp", "7", "-o", &p("full.exr")])
            .status
            .success()
    );
    // A render stopped after 3 spp leaves a checkpoint; resuming to 7 gives the same file.
    assert!(
        render(&["--spp", "3", "--checkpoint", "0", "-o", &p("part.exr")])
            .status
            .success()
    );
    let checkpoint = p("part.exr.checkpoint.exr");
    let out = render(&[
        "--spp",
        "7",
        "--resume",
        &checkpoint,
        "-o",
        &p("resumed.exr"),
    ]);
    assert_success(&out);
    assert_eq!(
        std::fs::read(dir.join("full.exr")).unwrap(),
        std::fs::read(dir.join("resumed.exr")).unwrap(),
        "byte-identical"
    );
    assert_eq!(spp_in_header(&dir.join("resumed.exr")), 7);
    // Other settings, or a checkpoint past the requested range, are refused.
    assert_one_line_errors(&[
        (
            &[
                "render",
                "--spp",
                "7",
                "--seed",
                "9",
                "--resume",
                &checkpoint,
                "-o",
                &p("x.exr"),
            ],
            "other settings",
        ),
        (
            &[
                "render",
                "--width",
                "24",
                "--height",
                "16",
                "--spp",
                "2",
                "--resume",
                &checkpoint,
                "-o",
                &p("x.exr"),
            ],
            "not a start",
        ),
        (
            &["render", "--resume", &p("missing.exr"), "-o", &p("x.exr")],
            "missing.exr",
        ),
        (&["render", "--time", "-1", "-o", &p("x.exr")], "--time"),
        (
            &["render", "--checkpoint", "nan", "-o", &p("x.exr")],
            "--checkpoint",
        ),
    ]);
}

#[test]
fn time_budget_stops_at_a_sample_boundary() {
    let dir = temp_dir("time");
    let out_path = dir.join("t.exr");
    let out = render(&[
        "--spp",
        "1000000",
        "--time",
        "0.5",
        "--stats",
        "-o",
        out_path.to_str().unwrap(),
    ]);
    assert_success(&out);
    let stats: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(stats["ending"], "TimeBudget");
    let spp = stats["spp"].as_u64().unwrap();
    assert!(spp < 1_000_000);
    assert_eq!(
        spp_in_header(&out_path),
        spp,
        "the header says how far it got"
    );
    assert_eq!(
        stats["paths"].as_u64().unwrap(),
        spp * 24 * 16,
        "whole samples only"
    );
}

#[cfg(unix)]
#[test]
fn sigint_and_sigterm_write_the_image_so_far_and_say_so() {
    for signal in ["-INT", "-TERM"] {
        stop_with(signal);
    }
}

#[cfg(unix)]
fn stop_with(signal: &str) {
    let dir = temp_dir(&format!("signal{signal}"));
    let out_path = dir.join("i.exr");
    let child = Command::new(env!("CARGO_BIN_EXE_prism"))
        .args([
            "render",
            "-q",
            "--width",
            "24",
            "--height",
            "16",
            "--spp",
            "100000000",
            "-o",
        ])
        .arg(&out_path)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130), "exit code says interrupted");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("interrupted"), "{stderr}");
    let spp = spp_in_header(&out_path);
    assert!(spp < 100_000_000, "{spp}");
}

#[test]
fn spectral_and_energy_checkpoints_resume_to_the_same_file() {
    let dir = temp_dir("resume-spectral");
    let p = |n: &str| dir.join(n).to_str().unwrap().to_string();
    let spectral = [
        "--spectral-bands",
        "5",
        "--spectral-range",
        "400:700",
        "--energy",
    ];
    let run = |extra: &[&str]| {
        let mut args = spectral.to_vec();
        args.extend(extra);
        let out = render(&args);
        assert_success(&out);
    };
    run(&["--spp", "5", "-o", &p("full.exr")]);
    run(&["--spp", "2", "--checkpoint", "0", "-o", &p("part.exr")]);
    let checkpoint = p("part.exr.checkpoint.exr");
    run(&[
        "--spp",
        "5",
        "--resume",
        &checkpoint,
        "-o",
        &p("resumed.exr"),
    ]);
    assert_eq!(
        std::fs::read(dir.join("full.exr")).unwrap(),
        std::fs::read(dir.join("resumed.exr")).unwrap(),
        "byte-identical, spectral and energy channels included"
    );
    // The checkpoint holds bands and energy: resuming it without them, or with other
    // bands, is refused before rendering.
    let elsewhere = p("x.exr");
    // The error names only the settings that differ.
    for (other, difference) in [
        (vec!["--spp", "5"], "energy true vs false"),
        (
            vec!["--spp", "5", "--spectral-bands", "6", "--energy"],
            "bands 5@400:700 vs 6@380:780",
        ),
        (
            vec![
                "--spp",
                "5",
                "--spectral-bands",
                "5",
                "--spectral-range",
                "400:700",
            ],
            "energy true vs false (the file's vs this render's)",
        ),
    ] {
        let mut args = vec!["render", "-q", "--width", "24", "--height", "16"];
        args.extend(other);
        args.extend(["--resume", &checkpoint, "-o", &elsewhere]);
        assert_one_line_errors(&[(&args, difference)]);
    }
}

#[test]
fn aovs_resume_and_merge_as_the_radiance_does() {
    let dir = temp_dir("aov-session");
    let p = |n: &str| dir.join(n).to_str().unwrap().to_string();
    let aovs = ["--aov", "all"];
    assert_success(&render(
        &[&aovs[..], &["--spp", "6", "-o", &p("full.exr")]].concat(),
    ));
    // Resumed from a checkpoint: the same file to the byte.
    assert_success(&render(
        &[
            &aovs[..],
            &["--spp", "2", "--checkpoint", "0", "-o", &p("part.exr")],
        ]
        .concat(),
    ));
    let checkpoint = p("part.exr.checkpoint.exr");
    assert_success(&render(
        &[
            &aovs[..],
            &[
                "--spp",
                "6",
                "--resume",
                &checkpoint,
                "-o",
                &p("resumed.exr"),
            ],
        ]
        .concat(),
    ));
    assert_eq!(
        std::fs::read(dir.join("full.exr")).unwrap(),
        std::fs::read(dir.join("resumed.exr")).unwrap(),
        "byte-identical"
    );
    // A checkpoint without AOVs does not resume a render with them: the AOVs are named.
    assert_one_line_errors(&[(
        &[
            "render",
            "-q",
            "--width",
            "24",
            "--height",
            "16",
            "--spp",
            "6",
            "--resume",
            &checkpoint,
            "-o",
            &p("x.exr"),
        ],
        "aovs",
    )]);
    // Sample ranges merged: every AOV layer as the whole render's, to rounding.
    for (range, name) in [("0..4", "a.exr"), ("4..6", "b.exr")] {
        assert_success(&render(
            &[&aovs[..], &["--sample-range", range, "-o", &p(name)]].concat(),
        ));
    }
    assert_success(&prism(&[
        "merge",
        &p("a.exr"),
        &p("b.exr"),
        "-o",
        &p("merged.exr"),
    ]));
    let read =
        |n: &str| prism_integrator::decode_exr(&std::fs::read(dir.join(n)).unwrap()).unwrap();
    let (merged, full) = (read("merged.exr"), read("full.exr"));
    let layers = [
        "albedo.R",
        "normal.Y",
        "depth.Z",
        "position.X",
        "material_id.ID",
        "variance.G",
    ];
    for layer in layers {
        let find = |image: &prism_integrator::ChannelImage| {
            image
                .channels
                .iter()
                .find(|(n, _)| n == layer)
                .map(|(_, v)| v.clone())
                .unwrap()
        };
        for (a, b) in find(&merged).iter().zip(find(&full)) {
            assert!(
                (a - b).abs() <= 1e-5 * b.abs().max(1.0),
                "{layer}: {a} vs {b}"
            );
        }
    }
}
