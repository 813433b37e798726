//! Polarized renders of the repository's scenes, each feature on: dispersion (the prism),
//! fluorescence (the blacklight box), light paths (the rainbow), glTF materials (the
//! effects stage), textures: every pixel's Stokes vector is light (S0 >= |S1, S2, S3|),
//! and the intensity is the unpolarized render's within noise.

mod common;

use prism_integrator::{Film, RenderSettings, render};

fn luminance_mean(film: &Film) -> f64 {
    let n = f64::from(film.width() * film.height());
    (0..film.height())
        .flat_map(|y| (0..film.width()).map(move |x| (x, y)))
        .map(|(x, y)| film.xyz(x, y).y)
        .sum::<f64>()
        / n
}

#[test]
fn repository_scenes_render_polarized() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    for file in [
        "prism.gltf",
        "rainbow.gltf",
        "effects.gltf",
        "textured.gltf",
        "window.gltf",
        "cornell-blacklight.toml",
    ] {
        let scene = if file.ends_with(".toml") {
            let overlay = prism_scene::spectral::Overlay::parse(
                &std::fs::read_to_string(dir.join(file)).unwrap(),
            )
            .unwrap();
            let gltf = std::fs::read(dir.join(overlay.gltf.clone().unwrap())).unwrap();
            let loaded = prism_scene::load::load_scene(
                &gltf,
                &|uri| std::fs::read(dir.join(uri)),
                &prism_scene::load::LoadOptions::default().overlay(Some(&overlay)),
            )
            .unwrap();
            prism_scene::world::Scene::from_loaded(loaded, &Default::default()).unwrap()
        } else {
            common::repository_scene(file, |_| {})
        };
        let settings = RenderSettings::default()
            .width(24)
            .height(16)
            .samples(0..32)
            .polarized(true);
        let (polarized, stats) = render(&scene, &settings).unwrap();
        assert_eq!(stats.nonfinite, 0, "{file}");
        for y in 0..16 {
            for x in 0..24 {
                let s = polarized.stokes(x, y).unwrap();
                for c in 0..3 {
                    let p = (s[1][c].powi(2) + s[2][c].powi(2) + s[3][c].powi(2)).sqrt();
                    assert!(
                        p <= s[0][c] * (1.0 + 1e-4) + 1e-9,
                        "{file} ({x}, {y}) channel {c}: {s:?}"
                    );
                }
            }
        }
        let (plain, _) = render(&scene, &settings.clone().polarized(false)).unwrap();
        let (a, b) = (luminance_mean(&polarized), luminance_mean(&plain));
        assert!(
            (a / b - 1.0).abs() < 0.1,
            "{file}: polarized {a}, unpolarized {b}"
        );
    }
}
