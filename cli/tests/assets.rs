//! Real-world-shaped glTF files (scenes/assets, from scenes/tools/make_assets.py): every
//! one renders lit, framed and with an alpha channel; the features they carry show.

mod common;

use std::path::{Path, PathBuf};

use common::{assert_one_line_errors, assert_success, prism, temp_dir};
use prism_integrator::decode_exr;

fn assets() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/assets")
}

fn asset(name: &str) -> String {
    assets().join(name).to_str().unwrap().to_string()
}

/// Channel `name` of an EXR file.
fn channel(exr: &Path, name: &str) -> Vec<f32> {
    let image = decode_exr(&std::fs::read(exr).unwrap()).unwrap();
    image
        .channels
        .into_iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no channel {name}"))
        .1
}

/// Renders `scene` (with `extra` arguments) to a 32 x 32 EXR at 4 spp; returns the EXR's
/// path and the run's stderr.
fn render(dir: &Path, scene: &str, extra: &[&str]) -> (PathBuf, String) {
    let exr = dir.join(format!(
        "{}.exr",
        Path::new(scene).file_stem().unwrap().to_str().unwrap()
    ));
    let mut args = vec![
        "render", scene, "--spp", "4", "--width", "32", "--height", "32", "-q", "-o",
    ];
    args.push(exr.to_str().unwrap());
    args.extend_from_slice(extra);
    let out = prism(&args);
    assert_success(&out);
    (exr, String::from_utf8_lossy(&out.stderr).to_string())
}

/// Every asset that prism can read renders lit (its covered pixels are not black),
/// framed (what it covers spans most of the image one way, and not all of it both
/// ways, unless its own camera fills the view) and with an alpha channel.
#[test]
fn every_asset_renders_lit_framed_and_with_alpha() {
    let dir = temp_dir("assets");
    let mut names: Vec<String> = std::fs::read_dir(assets())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_str().unwrap().to_string())
        .filter(|n| (n.ends_with(".gltf") || n.ends_with(".glb")) && !n.starts_with("requires-"))
        .collect();
    names.sort();
    assert!(names.len() >= 5, "{names:?}");
    for name in names {
        let (exr, _) = render(&dir, &asset(&name), &[]);
        let alpha = channel(&exr, "A");
        let (r, g) = (channel(&exr, "R"), channel(&exr, "G"));
        let covered: Vec<usize> = (0..alpha.len()).filter(|&i| alpha[i] > 0.5).collect();
        assert!(!covered.is_empty(), "{name}: nothing in view");
        let lit = covered.iter().map(|&i| r[i] + g[i]).sum::<f32>() / covered.len() as f32;
        assert!(lit > 0.02, "{name}: covered pixels are dark ({lit})");
        let (xs, ys): (Vec<usize>, Vec<usize>) = covered.iter().map(|&i| (i % 32, i / 32)).unzip();
        let span = |v: &[usize]| v.iter().max().unwrap() - v.iter().min().unwrap() + 1;
        assert!(
            span(&xs).max(span(&ys)) >= 20,
            "{name}: the model spans {}x{} of 32x32 pixels",
            span(&xs),
            span(&ys)
        );
    }
}

#[test]
fn a_file_without_lights_is_lit_by_default_and_says_so() {
    let dir = temp_dir("asset-notice");
    let (_, stderr) = render(&dir, &asset("box.gltf"), &[]);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("no light source") && stderr.contains("--environment"));
    // Glowing surfaces (an unlit quad emits its base colour, at most 1) do not light a
    // scene as lamps do: it still gets the environment, and the notice.
    let (_, stderr) = render(&dir, &asset("unlit.gltf"), &[]);
    assert!(stderr.contains("no light source"), "{stderr}");
    // Stating an environment, even a black one, is the scene's own light: no notice.
    let (_, stderr) = render(&dir, &asset("unlit.gltf"), &["--environment", "0"]);
    assert!(stderr.is_empty(), "{stderr}");
    // A file with a lamp (an emissive strength of 6, and a point light) gets none.
    let textured = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/textured.gltf");
    let (_, stderr) = render(&dir, textured.to_str().unwrap(), &[]);
    assert!(stderr.is_empty(), "{stderr}");
}

/// An unlit material is seen with exactly its base colour (0.2, 0.5, 0.8).
#[test]
fn an_unlit_quad_shows_its_base_colour() {
    let dir = temp_dir("asset-unlit");
    let (exr, _) = render(&dir, &asset("unlit.gltf"), &[]);
    for (name, expected) in [("R", 0.2f32), ("G", 0.5), ("B", 0.8)] {
        let values = channel(&exr, name);
        let mean = values.iter().sum::<f32>() / values.len() as f32;
        assert!(
            (mean - expected).abs() < 0.01 * expected + 2e-3,
            "{name}: {mean} vs {expected}"
        );
    }
    assert!(channel(&exr, "A").iter().all(|&a| a == 1.0));
}

/// One convention for environment radiance: `--environment 0.5`, an image whose texels
/// are all 0.5, and the same image at strength 2 with value 0.25... all light a white
/// Lambertian plane to RGB 0.5.
#[test]
fn environment_numbers_and_images_mean_emissive_colours() {
    let dir = temp_dir("asset-environment");
    let plane = asset("white-plane.gltf");
    let hdr = asset("grey-0.5.hdr");
    let cases: [&[&str]; 4] = [
        &["--environment", "0.5"],
        &["--environment", "0.25", "--environment-strength", "2"],
        &["--environment", &hdr],
        &["--environment", &hdr, "--environment-rotation", "77"],
    ];
    for extra in cases {
        let (exr, stderr) = render(&dir, &plane, extra);
        assert!(stderr.is_empty(), "{extra:?}: {stderr}");
        for name in ["R", "G", "B"] {
            let values = channel(&exr, name);
            let mean = values.iter().sum::<f32>() / values.len() as f32;
            assert!((mean - 0.5).abs() < 0.01, "{extra:?} {name}: {mean}");
        }
    }
}

#[test]
fn extensions_prism_cannot_read_are_errors_when_required_and_warnings_when_used() {
    let dir = temp_dir("asset-warnings");
    let out = dir.join("x.png");
    assert_one_line_errors(&[(
        &[
            "render",
            &asset("requires-draco.gltf"),
            "-o",
            out.to_str().unwrap(),
        ],
        "requires glTF extension KHR_draco_mesh_compression",
    )]);
    let (_, stderr) = render(&dir, &asset("uses-unknown.gltf"), &[]);
    for extension in ["KHR_materials_sss", "VENDOR_made_up"] {
        let lines = stderr.lines().filter(|l| l.contains(extension)).count();
        assert_eq!(lines, 1, "{extension}: {stderr}");
    }
}

/// `--transparent`: pixels that miss the model are transparent black in the EXR and have
/// alpha 0 in an RGBA PNG.
#[test]
fn transparent_renders_leave_the_background_empty() {
    let dir = temp_dir("asset-transparent");
    let png = dir.join("box.png");
    let (exr, _) = render(
        &dir,
        &asset("box.gltf"),
        &["--transparent", "-o", png.to_str().unwrap()],
    );
    let (alpha, r) = (channel(&exr, "A"), channel(&exr, "R"));
    assert_eq!(alpha[0], 0.0);
    assert_eq!(r[0], 0.0);
    assert!(alpha.contains(&1.0));
    let bytes = std::fs::read(&png).unwrap();
    // IHDR colour type 6: RGBA.
    assert_eq!(bytes[25], 6);
}

/// The mean of channel `name` over the columns `columns` of a 32 x 32 EXR.
fn column_mean(exr: &Path, name: &str, columns: std::ops::Range<usize>) -> f32 {
    region_mean(exr, name, 0..32, columns)
}

/// The mean of channel `name` over rows `rows` (from the top) and columns `columns` of a
/// 32 x 32 EXR.
fn region_mean(
    exr: &Path,
    name: &str,
    rows: std::ops::Range<usize>,
    columns: std::ops::Range<usize>,
) -> f32 {
    let values = channel(exr, name);
    let picked: Vec<f32> = (0..values.len())
        .filter(|i| rows.contains(&(i / 32)) && columns.contains(&(i % 32)))
        .map(|i| values[i])
        .collect();
    picked.iter().sum::<f32>() / picked.len() as f32
}

/// Textures read the texture coordinate set they name: each quad's TEXCOORD_0 points
/// into the red half of a texture and its TEXCOORD_1 spans red and green, so the right
/// half of the view is green only when set 1 is read: above, by an emissive texture beside
/// a grey base colour texture on set 0 (a material reading both sets); below, by an unlit
/// quad whose set 0 KHR_texture_transform overrides to 1. Emission is read on camera
/// paths and by light sampling alike.
#[test]
fn textures_read_the_texture_coordinate_set_they_name() {
    let dir = temp_dir("asset-multi-uv");
    let (exr, stderr) = render(&dir, &asset("multi-uv.gltf"), &["--environment", "1"]);
    assert!(stderr.is_empty(), "{stderr}");
    // sRGB 204, 128 and 25: 0.604, 0.216 and 0.0097.
    let (hi, lo, grey) = (0.604, 0.0097, 0.216);
    for (half, rows, base) in [("top", 2..14, grey), ("bottom", 18..30, 0.0)] {
        for (side, columns, (r, g)) in [("left", 2..14, (hi, lo)), ("right", 18..30, (lo, hi))] {
            let red = region_mean(&exr, "R", rows.clone(), columns.clone());
            let green = region_mean(&exr, "G", rows.clone(), columns);
            let (r, g) = (r + base, g + base);
            assert!(
                (red - r).abs() < 0.03 && (green - g).abs() < 0.03,
                "{half} {side}: R {red}, G {green}, expected {r}, {g}"
            );
        }
    }
}

/// COLOR_0 multiplies the base colour: a white Lambertian plane under a grey environment
/// of 1 shows its vertex colours, normalized bytes on the left, floats on the right.
#[test]
fn vertex_colours_multiply_the_base_colour() {
    let dir = temp_dir("asset-colours");
    let (exr, _) = render(&dir, &asset("vertex-colors.gltf"), &["--environment", "1"]);
    let expected = [
        (0..14, [1.0f32, 64.0 / 255.0, 0.0]),
        (18..32, [0.2, 0.6, 0.9]),
    ];
    for (columns, colour) in expected {
        for (name, c) in ["R", "G", "B"].iter().zip(colour) {
            let mean = column_mean(&exr, name, columns.clone());
            assert!(
                (mean - c).abs() < 0.02,
                "columns {columns:?} {name}: {mean} vs {c}"
            );
        }
    }
}

/// KHR_mesh_quantization: SHORT positions scaled by the node, BYTE normals and
/// normalized UNSIGNED_SHORT texture coordinates make the same white plane as floats do.
#[test]
fn quantized_meshes_read_as_floats() {
    let dir = temp_dir("asset-quantized");
    let (exr, stderr) = render(&dir, &asset("quantized.gltf"), &["--environment", "1"]);
    assert!(stderr.is_empty(), "{stderr}");
    assert!(channel(&exr, "A").iter().all(|&a| a == 1.0));
    for name in ["R", "G", "B"] {
        let mean = column_mean(&exr, name, 0..32);
        assert!((mean - 1.0).abs() < 0.01, "{name}: {mean}");
    }
}

/// alphaMode MASK: the red floor shows through the leaf's cut-out left half; the right
/// half is the white leaf.
#[test]
fn masked_cutouts_show_what_is_behind() {
    let dir = temp_dir("asset-mask");
    let (exr, _) = render(&dir, &asset("alpha-mask.gltf"), &["--environment", "1"]);
    let (left_r, left_g) = (column_mean(&exr, "R", 2..14), column_mean(&exr, "G", 2..14));
    assert!(
        left_r > 0.3 && left_g < 0.5 * left_r,
        "cut-out half: R {left_r}, G {left_g}"
    );
    let right_g = column_mean(&exr, "G", 18..30);
    assert!(right_g > 0.8, "opaque half: G {right_g}");
}

/// alphaMode BLEND: a white square of alpha 0.25 over a black floor shows a quarter of
/// its radiance (1 under a grey environment of 1), on average over samples.
#[test]
fn blended_surfaces_are_stochastically_transparent() {
    let dir = temp_dir("asset-blend");
    let exr = dir.join("blend.exr");
    let out = prism(&[
        "render",
        &asset("alpha-blend.gltf"),
        "--environment",
        "1",
        "--spp",
        "64",
        "--width",
        "16",
        "--height",
        "16",
        "-q",
        "-o",
        exr.to_str().unwrap(),
    ]);
    assert_success(&out);
    for name in ["R", "G", "B"] {
        let values = channel(&exr, name);
        let mean = values.iter().sum::<f32>() / values.len() as f32;
        // 16 x 16 x 64 Bernoulli(0.25) choices: a standard error of 0.0027.
        assert!((mean - 0.25).abs() < 0.015, "{name}: {mean}");
    }
}

/// EXT_texture_webp, required, no fallback: the WebP base colour (red left, blue right)
/// shows on the white plane.
#[test]
fn webp_textures_decode() {
    let dir = temp_dir("asset-webp");
    let (exr, stderr) = render(&dir, &asset("webp-texture.gltf"), &["--environment", "1"]);
    assert!(stderr.is_empty(), "{stderr}");
    let (left_r, left_b) = (column_mean(&exr, "R", 2..14), column_mean(&exr, "B", 2..14));
    let (right_r, right_b) = (
        column_mean(&exr, "R", 18..30),
        column_mean(&exr, "B", 18..30),
    );
    assert!(left_r > 0.8 && left_b < 0.1, "left: R {left_r} B {left_b}");
    assert!(
        right_b > 0.8 && right_r < 0.1,
        "right: R {right_r} B {right_b}"
    );
}

/// `prism info` names the glTF features each asset carries.
#[test]
fn info_names_the_gltf_features_a_file_uses() {
    for (file, feature) in [
        ("alpha-mask.gltf", "alphaMode MASK"),
        ("alpha-blend.gltf", "alphaMode BLEND"),
        ("quantized.gltf", "KHR_mesh_quantization"),
        ("vertex-colors.gltf", "COLOR_0"),
        ("unlit.gltf", "KHR_materials_unlit"),
        ("webp-texture.gltf", "EXT_texture_webp"),
        ("multi-uv.gltf", "TEXCOORD_1"),
    ] {
        let out = prism(&["info", &asset(file)]);
        assert_success(&out);
        let text = String::from_utf8_lossy(&out.stdout);
        let line = text.lines().find(|l| l.starts_with("glTF")).unwrap_or("");
        assert!(line.contains(feature), "{file}: {text}");
    }
}

/// Every pixel's value of channel `name` of a 32 x 32 render of `scene` at 1 spp under a
/// grey environment `environment`.
fn pixels(dir: &Path, scene: &str, environment: &str, name: &str) -> Vec<f32> {
    let exr = dir.join("pixels.exr");
    let out = prism(&[
        "render",
        scene,
        "--spp",
        "1",
        "--width",
        "32",
        "--height",
        "32",
        "--environment",
        environment,
        "-q",
        "-o",
        exr.to_str().unwrap(),
    ]);
    assert_success(&out);
    channel(&exr, name)
}

fn mean_and_spread(v: &[f32]) -> (f32, f32) {
    let n = v.len() as f32;
    let mean = v.iter().sum::<f32>() / n;
    (
        mean,
        (v.iter().map(|x| (x - mean).powi(2)).sum::<f32>() / n).sqrt(),
    )
}

/// Texture filtering by footprint (mipmaps): a checkerboard so fine that each pixel
/// covers 32 x 32 texels renders at 1 spp as its squares' mean (linear 0.5), its pixels
/// spreading no more than a uniform surface of the same radiance does (path noise), not
/// as aliased black and white pixels (a spread of 0.5); magnified, the squares stay
/// sharp.
#[test]
fn minified_textures_do_not_alias_at_one_sample_per_pixel() {
    let dir = temp_dir("asset-checker");
    let fine = pixels(&dir, &asset("checker-minified.gltf"), "1", "G");
    let (mean, spread) = mean_and_spread(&fine);
    assert!((mean - 0.5).abs() < 0.03, "mean {mean}");
    let uniform = pixels(&dir, &asset("white-plane.gltf"), "0.5", "G");
    let (uniform_mean, noise) = mean_and_spread(&uniform);
    assert!(
        (uniform_mean - 0.5).abs() < 0.03,
        "uniform mean {uniform_mean}"
    );
    assert!(
        spread < 1.3 * noise + 0.01,
        "checker pixels spread by {spread}, a uniform surface's by {noise}: aliasing"
    );
    let coarse = pixels(&dir, &asset("checker-magnified.gltf"), "1", "G");
    let (_, spread) = mean_and_spread(&coarse);
    assert!(spread > 0.4, "magnified squares blurred: spread {spread}");
}

/// A non-indexed primitive with interleaved POSITION and NORMAL and a sparse POSITION
/// accessor (whose substitution moves two far-off corners back) is the white plane that
/// fills the view: white everywhere under a grey environment of 1.
#[test]
fn sparse_interleaved_non_indexed_primitives_read_right() {
    let dir = temp_dir("asset-sparse");
    let (exr, _) = render(
        &dir,
        &asset("sparse-interleaved.gltf"),
        &["--environment", "1"],
    );
    assert!(channel(&exr, "A").iter().all(|&a| a == 1.0));
    let (mean, _) = mean_and_spread(&channel(&exr, "G"));
    assert!((mean - 1.0).abs() < 0.02, "G {mean}");
}

/// KHR_materials_pbrSpecularGlossiness: the diffuse colour is the base colour (a matte
/// dielectric at glossiness 0), with the approximation said once.
#[test]
fn specular_glossiness_materials_take_their_diffuse_colour() {
    let dir = temp_dir("asset-spec-gloss");
    let (exr, stderr) = render(&dir, &asset("spec-gloss.gltf"), &["--environment", "1"]);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("approximated"), "{stderr}");
    for (name, c) in [("R", 0.2f32), ("G", 0.6), ("B", 0.9)] {
        let mean = column_mean(&exr, name, 0..32);
        assert!((mean - c).abs() < 0.02, "{name}: {mean} vs {c}");
    }
}
