//! Reading scene files: the CLI owns the file system; prism-scene gets bytes and a
//! resolver for the buffers a file refers to.

use std::path::Path;

use prism_scene::load::{LoadedGeometry, load_geometry};

/// Loads `path` (a .gltf or .glb), resolving external buffers relative to it. Errors name
/// the file.
pub fn load(path: &Path, scene: Option<usize>) -> Result<LoadedGeometry, String> {
    let bytes =
        std::fs::read(path).map_err(|e| format!("cannot read '{}': {e}", path.display()))?;
    let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let resolve = move |uri: &str| {
        let file = dir.join(uri);
        std::fs::read(&file).map_err(|e| format!("cannot read '{}': {e}", file.display()))
    };
    load_geometry(&bytes, &resolve, scene).map_err(|e| format!("'{}': {e}", path.display()))
}
