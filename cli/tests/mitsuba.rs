//! `prism render scene.xml`: Mitsuba 3 scenes, rendered as Mitsuba renders them, with the
//! film, sampler and integrator the file gives unless the command line says otherwise,
//! `-D` parameters as `mitsuba -D`, and bad files refused in one line naming file:line.

mod common;

use common::{assert_one_line_errors, prism_ok, temp_dir};
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

/// Mitsuba's `mi.cornell_box()` as XML (scenes/mitsuba/cornell-box.xml) renders, by
/// prism at 32 x 32, the image Mitsuba 3's `scalar_spectral` variant renders of the same
/// file (scenes/mitsuba/references/cornell-box-32.exr, 16384 spp, written by
/// scenes/tools/make_mitsuba_scenes.py). Per channel, the image mean of 8 seeds at 128
/// spp against the reference, by Student's t with 7 degrees of freedom: |t| > 7 has
/// probability 2.1e-4 for a right render, 6.3e-4 over the three channels. The
/// reference's own noise is allowed for as 0.1% of its value, in quadrature. (The glTF
/// box, whose glTF BRDF adds a specular layer to the walls, is 2% redder.)
#[test]
fn a_mitsuba_scene_renders_as_mitsuba_renders_it() {
    let dir = temp_dir("mitsuba-box");
    let reference = means(&std::fs::read(scene("mitsuba/references/cornell-box-32.exr")).unwrap());
    let xml = scene("mitsuba/cornell-box.xml");
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
                "128",
                "--seed",
                &seed.to_string(),
                "-q",
                "-o",
                out.to_str().unwrap(),
            ]]);
            means(&std::fs::read(&out).unwrap())
        })
        .collect();
    for k in 0..3 {
        let values: Vec<f64> = renders.iter().map(|m| m[k]).collect();
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
        let error = (variance / n + (1e-3 * reference[k]).powi(2)).sqrt();
        let t = (mean - reference[k]) / error;
        assert!(
            t.abs() < 7.0,
            "channel {k}: prism {mean:.5}, Mitsuba {:.5} (t = {t:.1})",
            reference[k]
        );
    }
}

/// Without --width, --height, --spp or --max-depth the file's film, sampler and
/// integrator decide; `-D` sets a `<default>` parameter as `mitsuba -D` does.
#[test]
fn the_file_gives_size_samples_and_parameters() {
    let dir = temp_dir("mitsuba-defaults");
    let file = dir.join("small.xml");
    std::fs::write(
        &file,
        r#"<scene version="3.0.0">
    <default name="spp" value="2"/>
    <integrator type="path"><integer name="max_depth" value="3"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm"><integer name="width" value="12"/><integer name="height" value="6"/></film>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
    <shape type="cube"><bsdf type="diffuse"/></shape>
</scene>
"#,
    )
    .unwrap();
    let out = dir.join("small.exr");
    let render = |extra: &[&str]| -> serde_json::Value {
        let mut args = vec![
            "render",
            file.to_str().unwrap(),
            "--stats",
            "-q",
            "-o",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        serde_json::from_slice(&prism_ok(&[&args]).stdout).unwrap()
    };
    let s = render(&[]);
    assert_eq!(
        (s["width"].as_u64(), s["height"].as_u64()),
        (Some(12), Some(6))
    );
    assert_eq!(s["spp"], 2);
    let s = render(&["-D", "spp=3"]);
    assert_eq!(s["spp"], 3);
    let s = render(&["--spp", "5", "--width", "8"]);
    assert_eq!((s["spp"].as_u64(), s["width"].as_u64()), (Some(5), Some(8)));
}

/// Malformed XML, a plugin prism does not read yet, an undefined parameter, a missing
/// include and `-D` on a glTF scene are each one line with a non-zero exit; those in
/// the file name it and the line.
#[test]
fn bad_mitsuba_files_are_one_line_naming_file_and_line() {
    let dir = temp_dir("mitsuba-bad");
    let write = |name: &str, text: &str| -> String {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let truncated = write(
        "truncated.xml",
        "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n",
    );
    let unread = write(
        "unread.xml",
        "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n    <bsdf type=\"hair\"/>\n  </shape>\n</scene>\n",
    );
    let undefined = write(
        "undefined.xml",
        "<scene version=\"3.0.0\">\n  <shape type=\"$kind\"/>\n</scene>\n",
    );
    let include = write(
        "include.xml",
        "<scene version=\"3.0.0\">\n  <include filename=\"missing.xml\"/>\n</scene>\n",
    );
    let out = dir.join("x.png");
    let out = out.to_str().unwrap();
    let gltf = scene("cornell-box.gltf");
    assert_one_line_errors(&[
        (&["render", &truncated, "-o", out], "truncated.xml:"),
        (&["render", &unread, "-o", out], "unread.xml:3"),
        (&["render", &undefined, "-o", out], "undefined.xml:2"),
        (&["render", &include, "-o", out], "include.xml:2"),
        (&["render", &gltf, "-D", "a=1", "-o", out], "-D"),
    ]);
}
