//! Shared by the integrator's tests.

#![allow(dead_code)]

use prism_scene::world::Scene;

/// The repository's Cornell box as a render-ready scene.
pub fn cornell() -> Scene {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let bytes = std::fs::read(dir.join("cornell-box.gltf")).unwrap();
    let loaded = prism_scene::load::load_geometry(
        &bytes,
        &|uri| std::fs::read(dir.join(uri)).map_err(|e| e.to_string()),
        None,
    )
    .unwrap();
    Scene::from_loaded(&loaded, &Default::default()).unwrap()
}
