//! End-to-end tests of `prism render`: the binary as a user runs it.

mod common;

use common::{assert_one_line_errors, assert_success, prism, prism_ok, temp_dir};

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
    assert_success(&out);
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
}

/// The camera's aspect ratio (the default stage's is 4:3) fills in whichever of width and
/// height is not given; the default is 512 pixels high.
#[test]
fn output_size_follows_the_camera_aspect_ratio() {
    let dir = temp_dir("aspect");
    let exr = dir.join("a.exr");
    for (args, expected) in [
        (vec!["--height", "30"], (40, 30)),
        (vec!["--width", "40"], (40, 30)),
        (vec!["--width", "20", "--height", "20"], (20, 20)),
    ] {
        let mut all = vec![
            "render",
            "--spp",
            "1",
            "-q",
            "--stats",
            "-o",
            exr.to_str().unwrap(),
        ];
        all.extend(args);
        let out = prism(&all);
        assert_success(&out);
        let stats: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(
            (stats["width"].as_u64(), stats["height"].as_u64()),
            (Some(expected.0), Some(expected.1)),
            "{all:?}"
        );
    }
    // The default stage shows every effect: the scene reports them.
    let info = prism(&[
        "info",
        concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/effects.gltf"),
    ]);
    let text = String::from_utf8_lossy(&info.stdout);
    assert!(
        text.contains("dispersion: yes") && text.contains("fluorescence: yes"),
        "{text}"
    );
}

/// The EXR of a small render of `scene` (None: the default stage) on `threads` threads.
fn render_on_threads(dir: &std::path::Path, scene: Option<&str>, threads: &str) -> Vec<u8> {
    let path = dir.join(format!("t{threads}.exr"));
    let mut args = vec!["render"];
    args.extend(scene);
    args.extend([
        "--spp",
        "2",
        "--width",
        "16",
        "--height",
        "12",
        "--threads",
        threads,
    ]);
    args.extend(["-o", path.to_str().unwrap()]);
    assert_success(&prism(&args));
    std::fs::read(&path).unwrap()
}

#[test]
fn thread_count_does_not_change_the_file() {
    let dir = temp_dir("threads");
    assert_eq!(
        render_on_threads(&dir, None, "1"),
        render_on_threads(&dir, None, "2")
    );
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
        (&["render", "--tracer", "lanes:5", "-o", out], "lanes:16"),
        (&["render", "--width", "0", "-o", out], "empty"),
        (
            &["render", "--width", "40000", "--height", "40000", "-o", out],
            "GiB available",
        ),
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
        (
            &["render", "--threads", "100000", "-o", out],
            "at most 1024",
        ),
        (&["render", "--time", "1e300", "-o", out], "--time 1e300"),
        (
            &["render", "--checkpoint", "1e300", "-o", out],
            "--checkpoint",
        ),
        (&["render", "--time", "nan", "-o", out], "--time NaN"),
        (&["render", "--environment", "-1", "-o", out], "environment"),
        (&["render", "--environment", "1e300", "-o", out], "3.4e38"),
        (&["render", "missing.gltf", "-o", out], "missing.gltf"),
        (&["render", broken, "-o", out], "broken.gltf"),
        (&["render", "--camera", "nobody", "-o", out], "nobody"),
        (&["render", "--spp", "many"], "--spp"),
    ]);
}

#[test]
fn sample_ranges_merge_into_the_single_render() {
    let dir = temp_dir("merge");
    let path = |n: &str| dir.join(n).to_str().unwrap().to_string();
    let common = ["--width", "12", "--height", "8", "--seed", "3"];
    let run = |extra: &[&str]| prism_ok(&[&["render"], &common, extra]);
    run(&["--sample-range", "0..5", "-o", &path("whole.exr")]);
    run(&["--sample-range", "2..5", "-o", &path("b.exr")]);
    run(&["--sample-range", "0..2", "-o", &path("a.exr")]);
    let (a, b) = (path("a.exr"), path("b.exr"));
    let merge = |extra: &[&str]| prism_ok(&[&["merge", b.as_str(), a.as_str()], extra]);
    merge(&["--accumulation", "-o", &path("merged.exr")]);
    merge(&["-o", &path("image.exr"), "-o", &path("image.png")]);
    let decode = |name: &str| {
        prism_integrator::decode_accumulation(&std::fs::read(dir.join(name)).unwrap()).unwrap()
    };
    let (whole, merged) = (decode("whole.exr"), decode("merged.exr"));
    assert_eq!(merged.samples, 0..5);
    assert_eq!(merged.film.samples(), whole.film.samples());
    for (a, b) in merged.film.sums().iter().zip(whole.film.sums()) {
        for k in 0..3 {
            // The same samples summed in another grouping: equal to f64 rounding.
            assert!(
                (a[k] - b[k]).abs() <= 1e-12 * b[k].abs().max(1e-30),
                "{a:?} {b:?}"
            );
        }
    }
    assert!(
        std::fs::read(dir.join("image.png"))
            .unwrap()
            .starts_with(b"\x89PNG")
    );
    assert_one_line_errors(&[
        (
            &[
                "merge",
                &path("a.exr"),
                &path("a.exr"),
                "-o",
                &path("x.exr"),
            ],
            "overlap",
        ),
        (
            &["merge", &path("image.exr"), "-o", &path("x.exr")],
            "accumulation",
        ),
        (
            &["merge", &path("missing.exr"), "-o", &path("x.exr")],
            "missing.exr",
        ),
        (
            &["render", "--sample-range", "5..2", "-o", &path("x.exr")],
            "sample-range",
        ),
        (
            &["render", "--sample-range", "0..2", "-o", &path("x.png")],
            "accumulation",
        ),
    ]);
}

#[test]
fn compare_measures_and_thresholds() {
    let dir = temp_dir("compare");
    let path = |n: &str| dir.join(n).to_str().unwrap().to_string();
    for (name, spp, seed) in [
        ("a.exr", "8", "1"),
        ("a.png", "8", "1"),
        ("b.exr", "8", "2"),
        ("c.exr", "128", "3"),
    ] {
        // 32x32 at 8 spp: the image mean's spread between seeds is about 3% (16x16 at 4
        // spp spreads 8%, too close to the 20% bound below for every seed to pass).
        let out = prism(&[
            "render",
            "--width",
            "32",
            "--height",
            "32",
            "--spp",
            spp,
            "--seed",
            seed,
            "-o",
            &path(name),
        ]);
        assert!(out.status.success());
    }
    let json = |a: &str, b: &str| -> serde_json::Value {
        let out = prism(&["compare", &path(a), &path(b), "--json"]);
        assert_success(&out);
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let same = json("a.exr", "a.exr");
    assert_eq!(same["rmse"], 0.0);
    assert!(same["psnr"].is_null(), "infinite PSNR is null");
    // Two 8-spp renders differ more from each other than an 8-spp render from a 128-spp one.
    let noisy = json("a.exr", "b.exr")["relmse"].as_f64().unwrap();
    let better = json("a.exr", "c.exr")["relmse"].as_f64().unwrap();
    assert!(
        noisy > 0.0 && better > 0.0 && better < noisy,
        "{better} vs {noisy}"
    );
    let ratio = json("a.exr", "c.exr")["mean_ratio"][1].as_f64().unwrap();
    assert!((ratio - 1.0).abs() < 0.2, "{ratio}");
    // The threshold decides the exit code.
    let passing = format!("{}", noisy * 2.0);
    assert!(
        prism(&[
            "compare",
            &path("a.exr"),
            &path("b.exr"),
            "--max-relmse",
            &passing
        ])
        .status
        .success()
    );
    let failing = format!("{}", noisy / 2.0);
    let out = prism(&[
        "compare",
        &path("a.exr"),
        &path("b.exr"),
        "--max-relmse",
        &failing,
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("exceeds"));
    let out = prism(&[
        "render",
        "--width",
        "8",
        "--height",
        "8",
        "--spp",
        "1",
        "-o",
        &path("small.exr"),
    ]);
    assert!(out.status.success());
    let out = prism(&[
        "render",
        "--width",
        "8",
        "--height",
        "8",
        "--sample-range",
        "0..1",
        "-o",
        &path("acc.exr"),
    ]);
    assert!(out.status.success());
    assert_one_line_errors(&[
        (
            &["compare", &path("a.exr"), &path("small.exr")],
            "cannot compare: sizes differ",
        ),
        (
            &["compare", &path("acc.exr"), &path("small.exr")],
            "prism merge",
        ),
        (&["compare", &path("a.exr"), &path("none.exr")], "none.exr"),
        (
            &["compare", &path("a.png"), &path("a.exr")],
            "a.png': cannot read: not an OpenEXR file",
        ),
        (
            &["merge", &path("a.png"), "-o", &path("merged.exr")],
            "cannot read: not a prism accumulation file: not an OpenEXR file",
        ),
        (
            &[
                "compare",
                &path("a.exr"),
                &path("a.exr"),
                "--max-relmse",
                "nan",
            ],
            "max-relmse",
        ),
    ]);
}

#[test]
fn spectral_and_energy_sample_ranges_merge_into_the_single_render() {
    let dir = temp_dir("merge-spectral");
    let path = |n: &str| dir.join(n).to_str().unwrap().to_string();
    let common = [
        "--width",
        "10",
        "--height",
        "6",
        "--seed",
        "5",
        "--spectral-bands",
        "6",
        "--energy",
    ];
    let run = |extra: &[&str]| prism_ok(&[&["render", "-q"], &common, extra]);
    run(&["--spp", "4", "-o", &path("single.exr")]);
    run(&["--sample-range", "1..4", "-o", &path("b.exr")]);
    run(&["--sample-range", "0..1", "-o", &path("a.exr")]);
    let out = prism(&[
        "merge",
        &path("a.exr"),
        &path("b.exr"),
        "-o",
        &path("merged.exr"),
    ]);
    assert_success(&out);
    let read =
        |name: &str| prism_integrator::decode_exr(&std::fs::read(dir.join(name)).unwrap()).unwrap();
    let (single, merged) = (read("single.exr"), read("merged.exr"));
    let names = |image: &prism_integrator::ChannelImage| -> Vec<String> {
        image.channels.iter().map(|c| c.0.clone()).collect()
    };
    assert_eq!(names(&merged), names(&single), "the same channels");
    assert!(names(&merged).iter().any(|n| n.starts_with("S0.")));
    assert!(names(&merged).iter().any(|n| n.starts_with("energy.")));
    for ((name, a), (_, b)) in merged.channels.iter().zip(&single.channels) {
        for (x, y) in a.iter().zip(b) {
            // f32 channels of sums added in another grouping.
            assert!(
                (x - y).abs() <= 1e-6 * y.abs().max(1e-30),
                "{name}: {x} vs {y}"
            );
        }
    }
}

#[test]
fn spectral_output_has_the_layout_channels() {
    let dir = temp_dir("spectral");
    let exr = dir.join("s.exr");
    let out = prism(&[
        "render",
        "--width",
        "8",
        "--height",
        "8",
        "--spp",
        "2",
        "--spectral-bands",
        "4",
        "--spectral-range",
        "400:800",
        "-o",
        exr.to_str().unwrap(),
    ]);
    assert_success(&out);
    let bytes = std::fs::read(&exr).unwrap();
    let image = prism_integrator::decode_exr(&bytes).unwrap();
    let names: Vec<&str> = image.channels.iter().map(|c| c.0.as_str()).collect();
    for band in [
        "S0.450,000000nm",
        "S0.550,000000nm",
        "S0.650,000000nm",
        "S0.750,000000nm",
    ] {
        assert!(names.contains(&band), "{names:?}");
    }
    let o = exr.to_str().unwrap();
    assert_one_line_errors(&[
        (
            &["render", "--spectral-bands", "0", "-o", o],
            "spectral bands",
        ),
        (
            &[
                "render",
                "--spectral-bands",
                "4",
                "--spectral-range",
                "800:400",
                "-o",
                o,
            ],
            "--spectral-range '800:400'",
        ),
        (
            &[
                "render",
                "--spectral-bands",
                "4",
                "--spectral-range",
                "x",
                "-o",
                o,
            ],
            "A:B",
        ),
        // Without bands the range is unused, and a mistyped one is still an error.
        (
            &["render", "--spectral-range", "1e300:1e301", "-o", o],
            "--spectral-range '1e300:1e301'",
        ),
    ]);
}

#[test]
fn renders_a_fluorescent_overlay() {
    let dir = temp_dir("blacklight");
    let png = dir.join("b.png");
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenes/cornell-blacklight.toml"
    );
    let out = prism(&[
        "render",
        scene,
        "--spp",
        "2",
        "--width",
        "16",
        "--height",
        "16",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert_success(&out);
    assert!(std::fs::metadata(&png).unwrap().len() > 0);
}

/// Mean R / B of an EXR.
fn red_over_blue(path: &std::path::Path) -> f64 {
    let image = prism_integrator::decode_exr(&std::fs::read(path).unwrap()).unwrap();
    let mean = |name: &str| {
        let (_, v) = image.channels.iter().find(|(n, _)| n == name).unwrap();
        v.iter().map(|&x| f64::from(x)).sum::<f64>() / v.len() as f64
    };
    mean("R") / mean("B")
}

#[test]
fn white_balance_energy_and_wavelength_range() {
    let dir = temp_dir("balance");
    let gltf = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.gltf");
    let lit_by = |name: &str, illuminant: &str| {
        let overlay = dir.join(format!("{name}.toml"));
        std::fs::write(
            &overlay,
            format!("gltf = \"{gltf}\"\n[materials.white-emitter]\nemission = {{ spectrum = \"{illuminant}\", scale = 0.2 }}\n"),
        )
        .unwrap();
        overlay.to_str().unwrap().to_string()
    };
    let (tungsten, d65) = (
        lit_by("tungsten", "illuminant:A"),
        lit_by("d65", "illuminant:D65"),
    );
    let render_scene = |scene: &str, extra: &[&str], out: &std::path::Path| {
        let mut args = vec![
            "render",
            scene,
            "--spp",
            "4",
            "--width",
            "16",
            "--height",
            "16",
            "-o",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let result = prism(&args);
        assert!(
            result.status.success(),
            "{}",
            String::from_utf8_lossy(&result.stderr)
        );
        result
    };
    let (plain, balanced, daylight) = (
        dir.join("plain.exr"),
        dir.join("balanced.exr"),
        dir.join("d65.exr"),
    );
    let render = |extra: &[&str], out: &std::path::Path| render_scene(&tungsten, extra, out);
    render(&[], &plain);
    render(&["--white-balance", "illuminant:A"], &balanced);
    // The same box under D65, sRGB's white, for what balanced colours look like.
    render_scene(&d65, &[], &daylight);
    let (before, after, reference) = (
        red_over_blue(&plain),
        red_over_blue(&balanced),
        red_over_blue(&daylight),
    );
    assert!(
        before > 1.5 * reference,
        "tungsten light is orange: R/B {before} vs {reference}"
    );
    assert!(
        (after - reference).abs() < 0.15 * reference,
        "balanced to A the box looks as under daylight: R/B {after} vs {reference}"
    );

    let energy = dir.join("energy.exr");
    let out = render(
        &["--energy", "--stats", "-q", "--wavelength-range", "300:900"],
        &energy,
    );
    let stats: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        stats["energy"]["range_nm"],
        serde_json::json!([300.0, 900.0])
    );
    assert!(stats["energy"]["mean_radiance_w_m2_sr"].as_f64().unwrap() > 0.0);
    let image = prism_integrator::decode_exr(&std::fs::read(&energy).unwrap()).unwrap();
    for name in ["energy.radiance", "energy.eV", "energy.photons"] {
        assert!(
            image.channels.iter().any(|(n, _)| n == name),
            "{name} missing"
        );
    }
    assert_one_line_errors(&[
        (
            &["render", "--white-balance", "illuminant:Q9", "-o", "x.png"],
            "illuminant",
        ),
        (
            &["render", "--wavelength-range", "830:360", "-o", "x.png"],
            "--wavelength-range",
        ),
    ]);
}

#[test]
fn camera_response_files_render_false_colour() {
    let dir = temp_dir("nir");
    let png = dir.join("nir.png");
    let csv = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/nir-camera.csv");
    let out = prism(&[
        "render",
        "--camera-response",
        csv,
        "--spp",
        "2",
        "--width",
        "16",
        "--height",
        "16",
        "--lambda-sampler",
        "response",
        "-o",
        png.to_str().unwrap(),
        "--stats",
        "-q",
    ]);
    assert_success(&out);
    assert!(std::fs::metadata(&png).unwrap().len() > 0);
    let bad = dir.join("bad.csv");
    std::fs::write(&bad, "700,1,1\n").unwrap();
    let bad = bad.to_str().unwrap();
    assert_one_line_errors(&[
        (
            &["render", "--camera-response", bad, "-o", "x.png"],
            "four numbers",
        ),
        (
            &["render", "--camera-response", "/no/such.csv", "-o", "x.png"],
            "cannot read",
        ),
        (
            &[
                "render",
                "--camera-response",
                csv,
                "--white-balance",
                "illuminant:A",
                "-o",
                "x.png",
            ],
            "--white-balance",
        ),
    ]);
}

/// `prism trade` on the Cornell box into a fresh directory named `name`, at `size` x
/// `size` pixels with the spp ladder and reference spp given, plus `extra` arguments.
fn trade_box(
    name: &str,
    size: &str,
    spp: &str,
    reference_spp: &str,
    extra: &[&str],
) -> std::path::PathBuf {
    let out_dir = temp_dir(name).join("box");
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.gltf");
    let dir = out_dir.to_str().unwrap();
    let mut args = vec![
        "trade",
        scene,
        "-o",
        dir,
        "--spp",
        spp,
        "--reference-spp",
        reference_spp,
        "--width",
        size,
        "--height",
        size,
    ];
    args.extend(extra);
    assert_success(&prism(&args));
    out_dir
}

/// The budget cuts repeats too: a billion repeats of the first run end with the budget,
/// and the CSV records how many were made.
#[test]
fn trade_budget_cuts_repeats() {
    let out_dir = trade_box(
        "trade-budget",
        "4",
        "1",
        "2",
        &["--repeat", "1000000000", "--budget", "0.5"],
    );
    let csv = std::fs::read_to_string(out_dir.join("runs.csv")).unwrap();
    let first = csv.lines().nth(1).unwrap();
    let repeats: u64 = first.rsplit(',').next().unwrap().parse().unwrap();
    assert!((1..1_000_000_000).contains(&repeats), "{first}");
}

#[test]
fn trade_measures_every_sweep_and_redraws_reports() {
    let out_dir = trade_box("trade", "8", "2,1", "8", &[]);
    let csv = std::fs::read_to_string(out_dir.join("runs.csv")).unwrap();
    // 5 package sizes + 4 samplers + 5 upsampling modes, at 2 sample counts.
    assert_eq!(csv.lines().count(), 1 + 14 * 2, "{csv}");
    assert!(csv.lines().all(|l| l.split(',').count() == 8));
    for sweep in ["wavelengths", "sampler", "upsampling"] {
        let svg = std::fs::read_to_string(out_dir.join(format!("{sweep}.svg"))).unwrap();
        assert!(
            svg.starts_with("<svg") && svg.contains("<polyline"),
            "{sweep}"
        );
    }
    assert!(out_dir.join("reference.exr").exists());
    // A peer's rows join the plots and tables on --report.
    std::fs::write(
        out_dir.join("peer.csv"),
        "scene,sweep,setting,spp,seconds,setup_seconds,relmse\ncornell-box,peer,mitsuba scalar_spectral,2,0.5,0.1,0.2\n",
    )
    .unwrap();
    let out = prism(&["trade", "--report", "-o", out_dir.to_str().unwrap()]);
    assert_success(&out);
    let summary = std::fs::read_to_string(out_dir.join("summary.md")).unwrap();
    assert!(
        summary.contains("mitsuba scalar_spectral") && summary.contains("Most efficient"),
        "{summary}"
    );
    let o = out_dir.to_str().unwrap();
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.gltf");
    assert_one_line_errors(&[
        (&["trade", "-o", o], "needs a SCENE"),
        (&["trade", scene, "-o", o, "--spp", "0"], "--spp"),
        (&["trade", scene, "-o", o, "--budget", "-1"], "--budget"),
        (&["trade", "--report", "-o", "/no/such/dir"], "cannot read"),
    ]);
}

#[test]
fn the_complete_spectral_example_renders_and_scene_options_work() {
    let dir = temp_dir("spectral-example");
    let png = dir.join("s.png");
    let scenes = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes");
    let scene = format!("{scenes}/cornell-spectral.gltf");
    let out = prism(&[
        "render",
        &scene,
        "--spp",
        "2",
        "--width",
        "16",
        "--height",
        "16",
        "--bvh",
        "slow",
        "--scene-index",
        "0",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert_success(&out);
    // A scene that describes its own (near-infrared) camera renders through it.
    let overlay = dir.join("nir.toml");
    std::fs::write(
        &overlay,
        format!("gltf = \"{scenes}/cornell-box.gltf\"\n[camera_response]\nr = \"gaussian:900:60\"\ng = \"gaussian:850:60\"\nb = \"gaussian:800:60\"\n[materials.white-emitter]\nemission = \"blackbody:3000\"\n"),
    )
    .unwrap();
    let out = prism(&[
        "render",
        overlay.to_str().unwrap(),
        "--spp",
        "2",
        "--width",
        "16",
        "--height",
        "16",
        "-o",
        png.to_str().unwrap(),
        "--stats",
        "-q",
    ]);
    assert_success(&out);
    assert_one_line_errors(&[
        (&["render", &scene, "--bvh", "fast", "-o", "x.png"], "--bvh"),
        (
            &["render", &scene, "--scene-index", "3", "-o", "x.png"],
            "no scene 3",
        ),
    ]);
}

/// The textured example (base colour, metallic-roughness, normal and emissive textures)
/// reports its textures and renders the same file on one thread and on two.
#[test]
fn the_textured_example_renders_deterministically() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/textured.gltf");
    let info = prism(&["info", scene]);
    assert_success(&info);
    let text = String::from_utf8_lossy(&info.stdout);
    assert!(
        text.contains("textures: yes") && text.contains("emissive texture"),
        "{text}"
    );
    let dir = temp_dir("textured");
    assert_eq!(
        render_on_threads(&dir, Some(scene), "1"),
        render_on_threads(&dir, Some(scene), "2")
    );
}
