//! `--denoise` and `prism denoise` with Intel Open Image Denoise: the error it removes on
//! the Cornell box, the light it must not move, and the one line where the library is
//! missing. The library comes from `PRISM_OIDN` (CI installs pyoidn and sets it, with
//! `PRISM_REQUIRE_OIDN=1` so that these tests fail rather than skip without it).

mod common;

use std::path::Path;
use std::process::Command;

use common::{assert_one_line_errors, assert_success, temp_dir};
use prism_integrator::{ChannelImage, decode_exr};

const SCENE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.gltf");
/// `prism render scenes/cornell-box.gltf --width 128 --height 128 --spp 4096 --seed 1`.
const REFERENCE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/cornell-box-128-4096spp.exr"
);

/// Whether the denoiser can run here; panics where CI requires it and it cannot.
fn oidn_available() -> bool {
    let found = std::env::var_os("PRISM_OIDN").is_some_and(|p| Path::new(&p).exists());
    if !found && std::env::var_os("PRISM_REQUIRE_OIDN").is_some() {
        panic!("PRISM_REQUIRE_OIDN is set but PRISM_OIDN names no library");
    }
    if !found {
        eprintln!("skipped: set PRISM_OIDN to libOpenImageDenoise (pip install pyoidn)");
    }
    found
}

fn prism(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(args)
        .output()
        .expect("the prism binary runs")
}

fn read(path: &Path) -> ChannelImage {
    decode_exr(&std::fs::read(path).unwrap()).unwrap()
}

fn rgb(image: &ChannelImage, prefix: &str) -> Vec<[f64; 3]> {
    let c = |n: &str| {
        let name = format!("{prefix}{n}");
        &image.channels.iter().find(|(k, _)| *k == name).unwrap().1
    };
    let (r, g, b) = (c("R"), c("G"), c("B"));
    (0..r.len())
        .map(|i| [r[i], g[i], b[i]].map(f64::from))
        .collect()
}

fn relmse(a: &[[f64; 3]], reference: &[[f64; 3]]) -> f64 {
    let sum: f64 = a
        .iter()
        .zip(reference)
        .flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).powi(2) / (q[k] * q[k] + 0.01)))
        .sum();
    sum / (3 * a.len()) as f64
}

/// The mean of each `grid` x `grid` region of a `size` x `size` image, per channel.
fn regions(image: &[[f64; 3]], size: usize, grid: usize) -> Vec<[f64; 3]> {
    let cell = size / grid;
    let mut out = vec![[0.0; 3]; grid * grid];
    for (i, p) in image.iter().enumerate() {
        let (x, y) = (i % size, i / size);
        let r = &mut out[(y / cell) * grid + x / cell];
        for k in 0..3 {
            r[k] += p[k] / (cell * cell) as f64;
        }
    }
    out
}

#[test]
fn denoising_the_cornell_box_cuts_its_error_fivefold_and_moves_no_region() {
    if !oidn_available() {
        return;
    }
    let dir = temp_dir("denoise");
    let reference = rgb(&read(Path::new(REFERENCE)), "");
    let mut mean_denoised = vec![[0.0; 3]; reference.len()];
    let mut last = None;
    for seed in ["1", "2"] {
        let out = dir.join(format!("box-{seed}.exr"));
        let run = prism(&[
            "render",
            SCENE,
            "--width",
            "128",
            "--height",
            "128",
            "--spp",
            "16",
            "--seed",
            seed,
            "--denoise",
            "-q",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_success(&run);
        assert!(
            run.stderr.is_empty(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let image = read(&out);
        let (denoised, noisy) = (rgb(&image, ""), rgb(&image, "noisy."));
        let (before, after) = (relmse(&noisy, &reference), relmse(&denoised, &reference));
        assert!(
            before > 5.0 * after,
            "seed {seed}: relMSE {before} noisy, {after} denoised"
        );
        for (m, p) in mean_denoised.iter_mut().zip(&denoised) {
            for k in 0..3 {
                m[k] += p[k] / 2.0;
            }
        }
        // The AOVs the denoiser read are in the file.
        for c in ["albedo.R", "normal.X"] {
            assert!(image.channels.iter().any(|(n, _)| n == c), "{c}");
        }
        last = Some((denoised, noisy));
    }
    // The denoiser moves no light between regions: over two seeds, each 16 x 16 region's
    // mean is the converged one's within 2%, per channel (where a channel has light).
    let (a, b) = (regions(&mean_denoised, 128, 8), regions(&reference, 128, 8));
    let brightest = b.iter().flatten().fold(0.0f64, |m, v| m.max(*v));
    for (r, (p, q)) in a.iter().zip(&b).enumerate() {
        for k in 0..3 {
            if q[k] > 0.05 * brightest {
                let shift = (p[k] - q[k]).abs() / q[k];
                assert!(shift < 0.02, "region {r} channel {k}: {} vs {}", p[k], q[k]);
            }
        }
    }
    // prism denoise on a render with the same AOVs makes the same image.
    let (denoised, noisy) = last.unwrap();
    let aovs = dir.join("aovs.exr");
    assert_success(&prism(&[
        "render",
        SCENE,
        "--width",
        "128",
        "--height",
        "128",
        "--spp",
        "16",
        "--seed",
        "2",
        "--aov",
        "albedo,normal",
        "--reuse",
        "1",
        "-q",
        "-o",
        aovs.to_str().unwrap(),
    ]));
    let again = dir.join("again.exr");
    let png = dir.join("again.png");
    assert_success(&prism(&[
        "denoise",
        aovs.to_str().unwrap(),
        "-o",
        again.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
    ]));
    assert_eq!(rgb(&read(&again), ""), denoised);
    assert_eq!(rgb(&read(&again), "noisy."), noisy);
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
}

#[test]
fn a_missing_library_or_aov_is_one_line() {
    let dir = temp_dir("denoise-missing");
    let out = dir.join("x.exr");
    let out = out.to_str().unwrap();
    let run = |envs: &[(&str, &str)], args: &[&str]| {
        let mut command = Command::new(env!("CARGO_BIN_EXE_prism"));
        command
            .args(args)
            .env_remove("PRISM_OIDN")
            .env_remove("OIDN_DIR");
        for (k, v) in envs {
            command.env(k, v);
        }
        command.output().unwrap()
    };
    let render = [
        "render",
        "--spp",
        "1",
        "--width",
        "8",
        "--height",
        "8",
        "--denoise",
        "-o",
        out,
    ];
    let no_library = run(
        &[("PRISM_OIDN", "/nonexistent/libOpenImageDenoise.so.2")],
        &render,
    );
    let text = String::from_utf8_lossy(&no_library.stderr);
    assert!(!no_library.status.success());
    assert_eq!(text.trim_end().lines().count(), 1, "{text}");
    assert!(
        text.contains("pip install pyoidn") && text.contains("/nonexistent"),
        "{text}"
    );
    assert!(
        !Path::new(out).exists(),
        "nothing is rendered without the library"
    );
    // Neither PRISM_OIDN, the system's library path nor a Python with pyoidn.
    let none = run(
        &[("PRISM_PYTHON", "/bin/false"), ("LD_LIBRARY_PATH", "")],
        &render,
    );
    let text = String::from_utf8_lossy(&none.stderr);
    if !none.status.success() {
        assert_eq!(text.trim_end().lines().count(), 1, "{text}");
        assert!(text.contains("pip install pyoidn"), "{text}");
    }
    // A render without the albedo and normal AOVs cannot be denoised afterwards.
    let plain = dir.join("plain.exr");
    assert_success(&prism(&[
        "render",
        "--spp",
        "1",
        "--width",
        "8",
        "--height",
        "8",
        "-q",
        "-o",
        plain.to_str().unwrap(),
    ]));
    assert_one_line_errors(&[
        (
            &["denoise", plain.to_str().unwrap(), "-o", out],
            "render it with --aov albedo,normal",
        ),
        (
            &["denoise", "/nonexistent.exr", "-o", out],
            "/nonexistent.exr",
        ),
        (
            &["denoise", plain.to_str().unwrap(), "-o", "x.jpg"],
            "extension",
        ),
    ]);
}
