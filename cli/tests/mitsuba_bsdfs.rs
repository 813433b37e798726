//! Mitsuba's BSDFs as prism reads them render as Mitsuba renders them: Mitsuba's Cornell
//! box with its two cubes given the BSDF under test (scenes/mitsuba/bsdfs-<name>.xml),
//! against Mitsuba 3's own `scalar_spectral` render of the same file
//! (scenes/mitsuba/references/bsdfs-<name>-32.exr, 16384 spp, written by
//! scenes/tools/make_mitsuba_bsdfs.py). `roughplastic` is not read: prism's rough
//! coating keeps the energy Mitsuba's loses, and the box with two roughplastic cubes
//! (alpha 0.1 and 0.3) rendered 3.5% brighter than Mitsuba's (t = 21 to 29).

mod common;

use common::{prism_ok, temp_dir};
use prism_integrator::decode_exr;

fn scene(file: &str) -> String {
    format!("{}/../scenes/{file}", env!("CARGO_MANIFEST_DIR"))
}

/// An EXR's R, G and B image means.
fn means(bytes: &[u8]) -> [f64; 3] {
    let image = decode_exr(bytes).unwrap();
    ["R", "G", "B"].map(|name| {
        let (_, values) = image.channels.iter().find(|(n, _)| n == name).unwrap();
        values.iter().map(|&v| f64::from(v)).sum::<f64>() / values.len() as f64
    })
}

/// Per channel, the image mean of 8 seeds at `spp` against Mitsuba's, by Student's t with
/// 7 degrees of freedom: |t| > 7 has probability 2.1e-4 for a right render, 6.3e-4 over
/// the three channels. The reference's own noise is allowed for as 0.1% of its value, in
/// quadrature (as cli/tests/mitsuba.rs compares the plain box).
fn renders_as_mitsuba(name: &str, spp: u32) {
    let dir = temp_dir(&format!("mitsuba-bsdfs-{name}"));
    let reference =
        means(&std::fs::read(scene(&format!("mitsuba/references/bsdfs-{name}-32.exr"))).unwrap());
    let xml = scene(&format!("mitsuba/bsdfs-{name}.xml"));
    let renders: Vec<[f64; 3]> = (0..8)
        .map(|seed| {
            let out = dir.join(format!("{seed}.exr"));
            prism_ok(&[&[
                "render",
                &xml,
                "--width",
                "32",
                "--height",
                "32",
                "--spp",
                &spp.to_string(),
                "--seed",
                &seed.to_string(),
                "-q",
                "-o",
                out.to_str().unwrap(),
            ]]);
            means(&std::fs::read(&out).unwrap())
        })
        .collect();
    let mut failures = Vec::new();
    for k in 0..3 {
        let values: Vec<f64> = renders.iter().map(|m| m[k]).collect();
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
        let error = (variance / n + (1e-3 * reference[k]).powi(2)).sqrt();
        let t = (mean - reference[k]) / error;
        eprintln!(
            "{name} channel {k}: prism {mean:.5}, Mitsuba {:.5} (t = {t:.1})",
            reference[k]
        );
        if t.abs() >= 7.0 {
            failures.push(format!(
                "{name} channel {k}: prism {mean:.5}, Mitsuba {:.5} (t = {t:.1})",
                reference[k]
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("; "));
}

/// Smooth glass: bk7 in air (Mitsuba's defaults) and water by name.
#[test]
fn dielectric() {
    renders_as_mitsuba("dielectric", 128);
}

/// Smooth conductors by Mitsuba's names: gold, and "none", a perfect mirror.
#[test]
fn conductor() {
    renders_as_mitsuba("conductor", 128);
}

/// Smooth conductors with eta and k given.
#[test]
fn conductor_eta_k() {
    renders_as_mitsuba("conductor-eta-k", 128);
}

/// GGX conductors at alpha 0.1 and 0.4.
#[test]
fn roughconductor() {
    renders_as_mitsuba("roughconductor", 128);
}

/// GGX glass at alpha 0.1 (bk7) and 0.3 (index 1.33).
#[test]
fn roughdielectric() {
    renders_as_mitsuba("roughdielectric", 128);
}

/// Smooth plastic: a blue substrate, and a grey one under bk7 with `nonlinear`.
#[test]
fn plastic() {
    renders_as_mitsuba("plastic", 128);
}
