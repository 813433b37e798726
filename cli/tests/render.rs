//! End-to-end tests of `prism render`: the binary as a user runs it.

mod common;

use common::{assert_one_line_errors, prism};

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("prism-render-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn renders_the_default_scene_to_exr_and_png_with_stats() {
    let dir = temp_dir("default");
    let (exr, png) = (dir.join("a.exr"), dir.join("a.png"));
    let out = prism(&[
        "render",
        "--spp",
        "2",
        "--width",
        "24",
        "--height",
        "16",
        "-o",
        exr.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
        "--stats",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stats: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
    for key in [
        "spp",
        "seconds",
        "paths_per_second",
        "rays_per_second",
        "nonfinite_samples",
        "peak_memory_bytes",
    ] {
        assert!(!stats[key].is_null(), "{key} missing: {stats}");
    }
    assert_eq!(stats["spp"], 2);
    assert_eq!(stats["paths"], 24 * 16 * 2);
    let png_bytes = std::fs::read(&png).unwrap();
    assert_eq!(&png_bytes[..8], b"\x89PNG\r\n\x1a\n");
    // IHDR width and height.
    assert_eq!(&png_bytes[16..24], &[0, 0, 0, 24, 0, 0, 0, 16]);
    let exr_bytes = std::fs::read(&exr).unwrap();
    assert_eq!(&exr_bytes[..4], &[0x76, 0x2f, 0x31, 0x01], "EXR magic");
    let header = String::from_utf8_lossy(&exr_bytes[..exr_bytes.len().min(2000)]);
    assert!(
        header.contains("chromaticities"),
        "chromaticities attribute"
    );
    assert!(header.contains("spp=2;seed=0"), "prism attribute");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn thread_count_does_not_change_the_file() {
    let dir = temp_dir("threads");
    let files: Vec<_> = ["1", "2"]
        .iter()
        .map(|t| {
            let path = dir.join(format!("t{t}.exr"));
            let out = prism(&[
                "render",
                "--spp",
                "2",
                "--width",
                "16",
                "--height",
                "16",
                "--threads",
                t,
                "-o",
                path.to_str().unwrap(),
            ]);
            assert!(out.status.success());
            std::fs::read(&path).unwrap()
        })
        .collect();
    assert_eq!(files[0], files[1]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_input_is_one_clear_line() {
    let dir = temp_dir("bad");
    let out = dir.join("x.png");
    let out = out.to_str().unwrap();
    let broken = dir.join("broken.gltf");
    std::fs::write(&broken, b"{ not json").unwrap();
    let broken = broken.to_str().unwrap();
    assert_one_line_errors(&[
        (&["render", "--spp", "0", "-o", out], "sample range"),
        (&["render", "--wavelengths", "3", "-o", out], "wavelengths"),
        (&["render", "--width", "0", "-o", out], "empty"),
        (
            &[
                "render", "--width", "100000", "--height", "100000", "-o", out,
            ],
            "too large",
        ),
        (&["render", "-o", "image.jpg"], ".exr or .png"),
        (&["render", "--lambda-sampler", "magic", "-o", out], "magic"),
        (&["render", "--space", "nope", "-o", out], "nope"),
        (&["render", "--filter", "lanczos", "-o", out], "lanczos"),
        (&["render", "--clamp", "0", "-o", out], "clamp"),
        (&["render", "--environment", "-1", "-o", out], "environment"),
        (&["render", "missing.gltf", "-o", out], "missing.gltf"),
        (&["render", broken, "-o", out], "broken.gltf"),
        (&["render", "--camera", "nobody", "-o", out], "nobody"),
        (&["render", "--spp", "many"], "--spp"),
    ]);
    std::fs::remove_dir_all(&dir).unwrap();
}
