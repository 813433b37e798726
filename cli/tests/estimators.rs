//! `prism render` resolves its settings into estimators in one place, and says which it
//! used and why: `--stats` carries them, a setting that does not apply warns with the
//! reason, and a refused combination is one line naming both settings.

mod common;

use common::{assert_one_line_errors, prism, prism_ok, temp_dir};

fn scene(file: &str) -> String {
    format!("{}/../scenes/{file}", env!("CARGO_MANIFEST_DIR"))
}

fn stats(out: &std::process::Output) -> serde_json::Value {
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

#[test]
fn stats_say_which_estimators_and_why() {
    let dir = temp_dir("estimators");
    let exr = dir.join("f.exr");
    let furnace = scene("assets/medium-furnace.gltf");
    let common: &[&str] = &[
        "render",
        &furnace,
        "--environment",
        "0.5",
        "--width",
        "16",
        "--height",
        "16",
        "-o",
        exr.to_str().unwrap(),
        "--stats",
        "-q",
    ];
    // The defaults: the volumetric tracer, adaptive sampling on, the pilot's modes.
    let s = stats(&prism_ok(&[common, &["--spp", "16"]]));
    let e = &s["estimators"];
    assert_eq!(e["tracer"], "volume", "{s}");
    assert_eq!(e["adaptive"], true, "{s}");
    assert_eq!(e["light_paths"], false, "{s}");
    assert!(
        e["light_paths_why"]
            .as_str()
            .unwrap()
            .contains("volumetric"),
        "{s}"
    );
    assert!(e["reuse_why"].as_str().unwrap().contains("pilot"), "{s}");
    assert_eq!(e["reuse"], s["reuse"]);
    // A farm's piece samples uniformly, and says so.
    let s = stats(&prism_ok(&[common, &["--sample-range", "0..16"]]));
    assert_eq!(s["estimators"]["adaptive"], false, "{s}");
    assert!(
        s["estimators"]["adaptive_why"]
            .as_str()
            .unwrap()
            .contains("piece"),
        "{s}"
    );
    // Too few samples for the pilot's groups.
    let s = stats(&prism_ok(&[common, &["--spp", "6"]]));
    assert!(
        s["estimators"]["adaptive_why"]
            .as_str()
            .unwrap()
            .contains("16"),
        "{s}"
    );
}

#[test]
fn a_reuse_the_render_cannot_use_warns_with_its_reason() {
    let dir = temp_dir("reuse-warning");
    let exr = dir.join("b.exr");
    let out = prism(&[
        "render",
        &scene("cornell-box.gltf"),
        "--spp",
        "1",
        "--width",
        "8",
        "--height",
        "8",
        "--reuse",
        "4",
        "--polarized",
        "-q",
        "-o",
        exr.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("--reuse 4") && stderr.contains("polarized"),
        "{stderr}"
    );
}

#[test]
fn refused_combinations_are_one_line_naming_both() {
    let cornell = scene("cornell-box.gltf");
    let furnace = scene("assets/medium-furnace.gltf");
    let base = |scene: &str, extra: &[&'static str]| -> Vec<String> {
        let mut args: Vec<String> = [
            "render", scene, "--spp", "1", "--width", "4", "--height", "4",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        args.extend(extra.iter().map(|s| s.to_string()));
        args
    };
    let cases = [
        (base(&cornell, &["--splits", "2", "--reuse", "2"]), "splits"),
        (
            base(&furnace, &["--environment", "0.5", "--splits", "2"]),
            "media",
        ),
    ];
    let owned: Vec<(Vec<&str>, &str)> = cases
        .iter()
        .map(|(args, needle)| (args.iter().map(String::as_str).collect(), *needle))
        .collect();
    let borrowed: Vec<(&[&str], &str)> = owned.iter().map(|(a, n)| (a.as_slice(), *n)).collect();
    assert_one_line_errors(&borrowed);
}

/// `--tracer lanes` asks for the batch tracer, which is not kept: the render warns in one
/// line, says why in `--stats`, and writes the path tracer's image to the byte.
#[test]
fn the_batch_tracer_renders_as_the_path_tracer_and_says_so() {
    let dir = temp_dir("lanes");
    let cornell = scene("cornell-box.gltf");
    let render = |tracer: &str| {
        let exr = dir.join(format!("{tracer}.exr"));
        let out = prism_ok(&[&[
            "render",
            &cornell,
            "--spp",
            "4",
            "--width",
            "8",
            "--height",
            "8",
            "--tracer",
            tracer,
            "--stats",
            "-q",
            "-o",
            exr.to_str().unwrap(),
        ]]);
        (out, std::fs::read(&exr).unwrap())
    };
    let (paths, paths_image) = render("paths");
    let (lanes, lanes_image) = render("lanes:8");
    assert!(String::from_utf8_lossy(&paths.stderr).is_empty());
    let warning = String::from_utf8_lossy(&lanes.stderr);
    assert_eq!(warning.lines().count(), 1, "{warning}");
    assert!(warning.contains("not kept"), "{warning}");
    let e = &stats(&lanes)["estimators"];
    assert_eq!(e["tracer"], "paths");
    assert!(e["tracer_why"].as_str().unwrap().contains("not kept"));
    assert!(lanes_image == paths_image, "lanes changed the image");
}

/// A time budget stops an adaptive render between whole groups of its passes, its image
/// written and finite; a piece of a farm (`--sample-range`) renders uniformly, so that the
/// pieces merge into the whole's samples.
#[test]
fn a_time_budget_stops_between_groups_and_pieces_merge() {
    let dir = temp_dir("estimators-budget");
    let exr = dir.join("t.exr");
    let cornell = scene("cornell-box.gltf");
    let small: &[&str] = &[
        "render", &cornell, "--width", "12", "--height", "8", "-q", "--stats",
    ];
    let s = stats(&prism_ok(&[
        small,
        &[
            "--spp",
            "400000",
            "--time",
            "0.3",
            "-o",
            exr.to_str().unwrap(),
        ],
    ]));
    assert_eq!(s["estimators"]["adaptive"], true, "{s}");
    assert_eq!(s["ending"], "TimeBudget", "{s}");
    let spp = s["spp"].as_u64().unwrap();
    assert!(spp.is_multiple_of(4) && spp < 400_000, "{s}");
    assert!(std::fs::metadata(&exr).unwrap().len() > 0);
    let pieces = ["0..8", "8..16"].map(|range| {
        let path = dir.join(format!("piece-{range}.exr"));
        let s = stats(&prism_ok(&[
            small,
            &["--sample-range", range, "-o", path.to_str().unwrap()],
        ]));
        assert_eq!(s["estimators"]["adaptive"], false, "{s}");
        path
    });
    let merged = dir.join("merged.exr");
    prism_ok(&[&[
        "merge",
        pieces[0].to_str().unwrap(),
        pieces[1].to_str().unwrap(),
        "-o",
        merged.to_str().unwrap(),
    ]]);
    assert!(std::fs::metadata(&merged).unwrap().len() > 0);
}
