//! OpenVDB grids against OpenVDB itself: the fixtures in `tests/data/vdb` and what OpenVDB
//! 10 reads back from them (`expected.json`: the box of the nonzero voxels, the sum of
//! their values, and `tools::BoxSampler` at points in and around the grid) were written by
//! `tests/data/vdb/make_vdb.cpp`. Blosc, zip and uncompressed values, halves, doubles,
//! tiles at both internal levels, an affine map and an instanced grid are all covered.

#![cfg(feature = "vdb")]

use std::path::PathBuf;

use glam::Vec3;
use prism_scene::medium::{Grid, read_vdb};
use proptest::prelude::*;
use serde_json::Value;

fn data(name: &str) -> Vec<u8> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/vdb")
        .join(name);
    std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn vec3(v: &Value) -> Vec3 {
    let a = v.as_array().expect("3 numbers");
    Vec3::new(
        a[0].as_f64().unwrap() as f32,
        a[1].as_f64().unwrap() as f32,
        a[2].as_f64().unwrap() as f32,
    )
}

fn expected() -> Vec<Value> {
    serde_json::from_slice::<Value>(&data("expected.json"))
        .unwrap()
        .as_array()
        .unwrap()
        .clone()
}

/// The sum of the grid's voxels, looked up at their centres.
fn voxel_sum(grid: &Grid) -> f64 {
    let (min, max) = grid.bounds();
    let r = grid.resolution();
    let size = (max - min) / r.as_vec3();
    let mut sum = 0.0;
    for z in 0..r.z {
        for y in 0..r.y {
            for x in 0..r.x {
                let centre = min + (Vec3::new(x as f32, y as f32, z as f32) + 0.5) * size;
                sum += f64::from(grid.lookup(centre));
            }
        }
    }
    sum
}

#[test]
fn grids_match_what_openvdb_reads() {
    for case in expected() {
        let (file, name) = (
            case["file"].as_str().unwrap(),
            case["grid"].as_str().unwrap(),
        );
        let grid = read_vdb(&data(file), Some(name), "density")
            .unwrap_or_else(|e| panic!("{file} {name}: {e}"));
        let (min, max) = grid.bounds();
        let (want_min, want_max) = (vec3(&case["min"]), vec3(&case["max"]));
        assert!(
            (min - want_min).abs().max_element() < 1e-5
                && (max - want_max).abs().max_element() < 1e-5,
            "{file} {name}: box {min} - {max}, OpenVDB's nonzero voxels and a margin {want_min} - {want_max}"
        );
        let (lo, hi) = (
            case["lo"].as_array().unwrap(),
            case["hi"].as_array().unwrap(),
        );
        for k in 0..3 {
            let span = hi[k].as_i64().unwrap() - lo[k].as_i64().unwrap() + 3;
            assert_eq!(
                i64::from(grid.resolution()[k]),
                span,
                "{file} {name}: axis {k}"
            );
        }
        let peak = grid.max_value();
        for s in case["samples"].as_array().unwrap() {
            let s = s.as_array().unwrap();
            let p = Vec3::new(
                s[0].as_f64().unwrap() as f32,
                s[1].as_f64().unwrap() as f32,
                s[2].as_f64().unwrap() as f32,
            );
            let want = s[3].as_f64().unwrap();
            let got = f64::from(grid.lookup(p));
            assert!(
                (got - want).abs() <= 2e-4 * f64::from(peak),
                "{file} {name}: at {p} prism {got}, OpenVDB's BoxSampler {want}"
            );
        }
        let want_sum = case["sum"].as_f64().unwrap();
        let sum = voxel_sum(&grid);
        assert!(
            (sum - want_sum).abs() <= 1e-5 * want_sum,
            "{file} {name}: voxels sum to {sum}, OpenVDB's to {want_sum}"
        );
    }
}

#[test]
fn the_grid_is_chosen_by_name_by_role_or_as_the_only_one() {
    let smoke = data("smoke.vdb");
    let peak = |g: Result<Grid, String>| g.unwrap().max_value();
    let density = peak(read_vdb(&smoke, None, "density"));
    let temperature = peak(read_vdb(&smoke, None, "temperature"));
    assert!(
        density < 2.0 && temperature > 100.0,
        "{density} {temperature}"
    );
    assert_eq!(
        peak(read_vdb(&smoke, Some("temperature"), "density")),
        temperature
    );
    // One grid in the file: it is the one, whatever its name.
    assert!(read_vdb(&data("smoke-zip.vdb"), None, "temperature").is_ok());
    let e = read_vdb(&smoke, None, "flame").unwrap_err();
    assert!(
        e.contains("'density', 'temperature', 'vel'") && e.contains("\"grid\""),
        "{e}"
    );
    let e = read_vdb(&smoke, Some("heat"), "density").unwrap_err();
    assert!(e.contains("no grid named 'heat'"), "{e}");
}

#[test]
fn grids_prism_cannot_use_are_clear_errors() {
    let cases: [(&str, Option<&str>, &str); 6] = [
        ("smoke.vdb", Some("vel"), "scalar float and double"),
        ("levelset.vdb", None, "level set"),
        ("background.vdb", None, "background value is 0.5"),
        ("rotated.vdb", None, "rotated"),
        ("nan.vdb", None, "voxel (4, 1, 2) is NaN"),
        ("smoke.vol", None, "not an OpenVDB file"),
    ];
    for (file, grid, words) in cases {
        let bytes = if file.ends_with(".vol") {
            b"VOL\x03 not a vdb".to_vec()
        } else {
            data(file)
        };
        let e = read_vdb(&bytes, grid, "density").unwrap_err();
        assert!(e.contains(words), "{file}: {e}");
        assert!(!e.contains('\n'), "{file}: one line: {e}");
    }
}

#[test]
fn every_truncation_is_an_error() {
    let bytes = data("smoke-half.vdb");
    for cut in (0..bytes.len()).step_by(97).chain([bytes.len() - 1]) {
        let e = read_vdb(&bytes[..cut], None, "density").unwrap_err();
        assert!(!e.is_empty());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    /// Corrupted bytes anywhere (header, tree, compressed streams) never panic: the file
    /// reads as an error or as a grid of finite, non-negative values.
    #[test]
    fn corrupted_files_never_panic(
        which in 0usize..3,
        flips in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..6),
    ) {
        let mut bytes = data(["smoke.vdb", "smoke-zip.vdb", "smoke-raw.vdb"][which]);
        for (at, value) in flips {
            let i = at.index(bytes.len());
            bytes[i] = value;
        }
        if let Ok(grid) = read_vdb(&bytes, None, "density") {
            prop_assert!(grid.max_value().is_finite() && grid.max_value() >= 0.0);
        }
    }
}
