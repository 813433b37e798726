//! A glTF 2.0 file loaded and described: what it holds, which extensions prism read, what
//! it warned about, and what the render-ready scene needs from an integrator.
//!
//! `cargo run -p prism-scene --example load_gltf -- path/to/model.gltf` (or `.glb`;
//! inside the repository, without a path: `scenes/cornell-box.gltf`).

use std::path::PathBuf;

use prism_scene::load::{LoadOptions, load_scene};
use prism_scene::world::{Scene, SceneOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = match std::env::args_os().nth(1) {
        Some(path) => PathBuf::from(path),
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes/cornell-box.gltf"),
    };
    let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    // Buffers, images and spectra the file names are read relative to it.
    let dir = path.parent().map(PathBuf::from).unwrap_or_default();
    let resolve = move |uri: &str| std::fs::read(dir.join(uri));
    let loaded = load_scene(&bytes, &resolve, &LoadOptions::default())
        .map_err(|e| format!("{}: {e}", path.display()))?;

    println!("{}", path.display());
    println!(
        "  {} triangles, {} materials, {} punctual lights, {} cameras",
        loaded.triangles.len(),
        loaded.materials.len(),
        loaded.lights.len(),
        loaded.cameras.len()
    );
    for material in &loaded.materials {
        println!("  material '{}'", material.name);
    }
    println!("  extensions read: {}", loaded.gltf_features.join(", "));
    for warning in &loaded.warnings {
        println!("  warning: {warning}");
    }

    let scene = Scene::from_loaded(loaded, &SceneOptions::default())?;
    let features = scene.features();
    println!(
        "  scene: radius {:.2}, {} light sources, dispersion {}, fluorescence {}, caustics {}",
        scene.radius(),
        scene.emission_spectra().len(),
        features.dispersion,
        features.fluorescence,
        features.specular
    );
    Ok(())
}
