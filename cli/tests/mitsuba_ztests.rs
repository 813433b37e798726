//! Mitsuba scenes render as Mitsuba renders them, by Mitsuba's own test: every
//! `scenes/mitsuba/<name>.xml` that has Mitsuba 3's references beside it
//! (`references/<name>-ref.exr`, the mean, and `<name>-var.exr`, the per-sample variance,
//! written by scenes/tools/make_mitsuba_ztest_refs.py with pip Mitsuba's `scalar_spectral`
//! variant) is rendered by prism as the file stands and z-tested per pixel against them,
//! Šidák-corrected, as Mitsuba's render suite tests its own renders
//! ([`prism_integrator::z_test`]).
//!
//! Mitsuba's suite spends 2e6 samples per image; these renders spend
//! `PRISM_ZTEST_SAMPLES` (default 5e5), which keeps the test's level and lowers only its
//! power, so that CI stays fast.

mod common;

use std::path::{Path, PathBuf};

use common::{prism_ok, temp_dir};
use prism_integrator::{ChannelImage, MITSUBA_SIGNIFICANCE, decode_exr, z_test};

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/mitsuba")
}

fn read(path: &Path) -> ChannelImage {
    decode_exr(&std::fs::read(path).unwrap()).unwrap()
}

/// The scenes with both references, by name.
fn scenes_with_references() -> Vec<String> {
    let refs = scenes_dir().join("references");
    let mut names: Vec<String> = std::fs::read_dir(scenes_dir())
        .unwrap()
        .filter_map(|e| {
            let path = e.unwrap().path();
            let name = path.file_stem()?.to_str()?.to_string();
            (path.extension()? == "xml"
                && refs.join(format!("{name}-ref.exr")).exists()
                && refs.join(format!("{name}-var.exr")).exists())
            .then_some(name)
        })
        .collect();
    names.sort();
    names
}

#[test]
fn every_mitsuba_scene_with_references_passes_mitsubas_z_test() {
    let budget: u64 = std::env::var("PRISM_ZTEST_SAMPLES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(500_000);
    let dir = temp_dir("mitsuba-ztests");
    let names = scenes_with_references();
    assert!(!names.is_empty(), "no scene has references");
    let mut failures = Vec::new();
    for name in &names {
        let refs = scenes_dir().join("references");
        let reference = read(&refs.join(format!("{name}-ref.exr")));
        let variance = read(&refs.join(format!("{name}-var.exr")));
        let spp = (budget / (reference.width * reference.height) as u64).max(1);
        let out = dir.join(format!("{name}.exr"));
        let xml = scenes_dir().join(format!("{name}.xml"));
        prism_ok(&[&[
            "render",
            xml.to_str().unwrap(),
            "--spp",
            &spp.to_string(),
            "--seed",
            "0",
            "-q",
            "-o",
            out.to_str().unwrap(),
        ]]);
        let t = z_test(
            &read(&out),
            &reference,
            &variance,
            spp,
            MITSUBA_SIGNIFICANCE,
        )
        .unwrap();
        let line = format!(
            "{name}: {} of {} pixel channels pass at {spp} spp, smallest p {:.2e} at ({}, {}), XYZ mean ratios {:?}",
            t.passed,
            3 * t.pixels,
            t.min_p.0,
            t.min_p.1,
            t.min_p.2,
            t.mean_ratio.map(|r| r.map(|r| (r * 1e4).round() / 1e4)),
        );
        eprintln!("{line}");
        if !t.accepted {
            failures.push(line);
        }
    }
    assert!(failures.is_empty(), "rejected:\n{}", failures.join("\n"));
}
