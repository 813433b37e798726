//! Depth of field from the command line: `--f-number`, `--aperture-radius` and
//! `--focus-distance` render, `--stats` reports the distance in focus (by default what the
//! image's centre sees), a pinhole's images do not change, and bad values are one-line
//! errors.

mod common;

use common::{TempDir, assert_one_line_errors, prism_ok, temp_dir};

fn scene(name: &str) -> String {
    format!("{}/../scenes/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn render(dir: &TempDir, name: &str, extra: &[&str]) -> (serde_json::Value, Vec<u8>) {
    let out = dir.join(name);
    let box_scene = scene("cornell-box.gltf");
    let mut args = vec![
        "render",
        box_scene.as_str(),
        "--width",
        "24",
        "--height",
        "24",
        "--spp",
        "4",
        "--stats",
        "-q",
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let run = prism_ok(&[&args]);
    let stats = serde_json::from_slice(&run.stdout).unwrap();
    (stats, std::fs::read(&out).unwrap())
}

#[test]
fn depth_of_field_from_the_command_line() {
    let dir = temp_dir("lens");
    let (pinhole, sharp) = render(&dir, "pinhole.exr", &[]);
    assert!(pinhole["focus_distance"].is_null());
    // The box's camera sits at z = 3.9 looking into the box (open at z = 1, its back wall
    // at z = -1): the image's centre sees something in there.
    let (auto, blurred) = render(&dir, "auto.exr", &["--f-number", "0.7"]);
    let focus = auto["focus_distance"].as_f64().unwrap();
    assert!((2.9..=4.9 + 1e-3).contains(&focus), "{focus}");
    assert_ne!(sharp, blurred);
    let (set, _) = render(
        &dir,
        "set.exr",
        &["--aperture-radius", "0.05", "--focus-distance", "3.2"],
    );
    assert!((set["focus_distance"].as_f64().unwrap() - 3.2).abs() < 1e-6);
    // Focus goes through the boundaries of media, which are not seen: in the volume box
    // the centre's ray crosses the milky block (3.97 away in the plain box) to the back
    // wall.
    let medium = scene("cornell-medium.gltf");
    let run = prism_ok(&[&[
        "render",
        medium.as_str(),
        "--width",
        "8",
        "--height",
        "8",
        "--spp",
        "1",
        "--f-number",
        "2",
        "--stats",
        "-q",
        "-o",
        dir.join("medium.png").to_str().unwrap(),
    ]]);
    let stats: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let through = stats["focus_distance"].as_f64().unwrap();
    assert!((through - 4.9).abs() < 1e-3, "{through}");
    // A radius of 0 is a pinhole: the same image to the byte.
    let (zero, same) = render(&dir, "zero.exr", &["--aperture-radius", "0"]);
    assert!(zero["focus_distance"].is_null());
    assert_eq!(sharp, same);
}

#[test]
fn bad_lenses_are_one_line_errors() {
    let box_scene = scene("cornell-box.gltf");
    let with = |extra: &[&'static str]| {
        let mut args = vec![
            "render",
            box_scene.as_str(),
            "--spp",
            "1",
            "-o",
            "never-written.png",
        ];
        args.extend_from_slice(extra);
        args.into_iter().map(str::to_string).collect::<Vec<_>>()
    };
    let cases: Vec<(Vec<String>, &str)> = vec![
        (with(&["--f-number", "0"]), "f-number 0"),
        (with(&["--aperture-radius", "-1"]), "radius -1"),
        (with(&["--focus-distance", "2"]), "needs an aperture"),
        (
            with(&["--f-number", "2", "--focus-distance", "-1"]),
            "focus distance -1",
        ),
        (
            with(&["--f-number", "2", "--aperture-radius", "0.1"]),
            "cannot be used with",
        ),
    ];
    let owned: Vec<(Vec<&str>, &str)> = cases
        .iter()
        .map(|(a, n)| (a.iter().map(String::as_str).collect(), *n))
        .collect();
    let borrowed: Vec<(&[&str], &str)> = owned.iter().map(|(a, n)| (a.as_slice(), *n)).collect();
    assert_one_line_errors(&borrowed);
}

#[test]
fn info_describes_a_cameras_lens() {
    let out = prism_ok(&[&["info", scene("bokeh.gltf").as_str()]]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains(
            "lens           camera: thin lens, f/1.4, 6 blades, focused at 2.5 m, sensor 36 mm wide"
        ),
        "{text}"
    );
    let out = prism_ok(&[&["info", scene("lens-chart.gltf").as_str()]]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains(
            "lens           camera: lens system lenses/singlet.dat (97.4 mm f/3.25 wide open, stopped to f/5.6, 3 interfaces, dispersive glass), focused at 3 m, sensor 36 mm wide"
        ),
        "{text}"
    );
}

/// `--lens FILE` renders through a prescription: the film moves to focus on what the
/// centre sees (reported), `--f-number` and `--focus-distance` apply to it, `prism info`
/// describes a scene's own, and bad prescriptions and flags are one-line errors.
#[test]
fn lens_systems_from_the_command_line() {
    let dir = temp_dir("lens-system");
    let dgauss = scene("lenses/dgauss.50mm.dat");
    let (pinhole, sharp) = render(&dir, "pinhole.exr", &[]);
    assert!(pinhole["focus_distance"].is_null());
    let (auto, through) = render(&dir, "auto.exr", &["--lens", dgauss.as_str()]);
    let focus = auto["focus_distance"].as_f64().unwrap();
    assert!((2.9..=4.9 + 1e-3).contains(&focus), "{focus}");
    assert_eq!(
        auto["reuse"], 1,
        "reuse does not apply behind a lens system"
    );
    assert_ne!(sharp, through);
    let (set, stopped) = render(
        &dir,
        "set.exr",
        &[
            "--lens",
            dgauss.as_str(),
            "--f-number",
            "8",
            "--focus-distance",
            "3.2",
        ],
    );
    assert!((set["focus_distance"].as_f64().unwrap() - 3.2).abs() < 1e-6);
    assert_ne!(through, stopped);
    // The same render twice is the same image.
    let (_, again) = render(
        &dir,
        "again.exr",
        &[
            "--lens",
            dgauss.as_str(),
            "--f-number",
            "8",
            "--focus-distance",
            "3.2",
        ],
    );
    assert_eq!(stopped, again);

    let broken = dir.join("broken.dat");
    std::fs::write(&broken, "29.4 3.7\n").unwrap();
    let broken = broken.to_str().unwrap().to_string();
    let box_scene = scene("cornell-box.gltf");
    let base = |extra: &[&str]| {
        let mut args = vec![
            "render".to_string(),
            box_scene.clone(),
            "--spp".into(),
            "1".into(),
            "-o".into(),
            "never-written.png".into(),
        ];
        args.extend(extra.iter().map(|s| s.to_string()));
        args
    };
    let cases: Vec<(Vec<String>, &str)> = vec![
        (base(&["--lens", "no-such.dat"]), "--lens 'no-such.dat'"),
        (base(&["--lens", broken.as_str()]), "line 1: 2 columns"),
        (
            base(&["--lens", dgauss.as_str(), "--f-number", "1.2"]),
            "wider than the lens opens (f/2.02)",
        ),
        (
            base(&["--lens", dgauss.as_str(), "--focus-distance", "0.02"]),
            "cannot focus at 0.020 m",
        ),
        (
            base(&["--lens", dgauss.as_str(), "--aperture-radius", "0.1"]),
            "cannot be used with",
        ),
    ];
    let owned: Vec<(Vec<&str>, &str)> = cases
        .iter()
        .map(|(a, n)| (a.iter().map(String::as_str).collect(), *n))
        .collect();
    let borrowed: Vec<(&[&str], &str)> = owned.iter().map(|(a, n)| (a.as_slice(), *n)).collect();
    assert_one_line_errors(&borrowed);
}

/// Behind a lens system a polarized render's sample ranges merge into the render of all
/// of them, and a part rendered through another lens does not merge with them.
#[test]
fn lens_system_renders_merge_and_polarize() {
    let dir = temp_dir("lens-merge");
    let path = |n: &str| dir.join(n).to_str().unwrap().to_string();
    let (window, dgauss, achromat) = (
        scene("window.gltf"),
        scene("lenses/dgauss.50mm.dat"),
        scene("lenses/achromat.dat"),
    );
    let common = [
        window.as_str(),
        "--width",
        "12",
        "--height",
        "8",
        "--seed",
        "3",
        "--polarized",
        "--lens",
        dgauss.as_str(),
    ];
    let run = |extra: &[&str]| prism_ok(&[&["render", "-q"], &common, extra]);
    run(&["--spp", "4", "-o", &path("single.exr")]);
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
    let s0 = &single.channels.iter().find(|c| c.0 == "S0.G").unwrap().1;
    assert!(s0.iter().any(|v| *v > 0.0));
    // A part through the achromat is another render.
    prism_ok(&[&[
        "render",
        "-q",
        window.as_str(),
        "--width",
        "12",
        "--height",
        "8",
        "--seed",
        "3",
        "--polarized",
        "--lens",
        achromat.as_str(),
        "--sample-range",
        "1..4",
        "-o",
        &path("c.exr"),
    ]]);
    let out = common::prism(&[
        "merge",
        &path("a.exr"),
        &path("c.exr"),
        "-o",
        &path("never.exr"),
    ]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("lens="), "{stderr}");
}
