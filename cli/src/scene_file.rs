//! Reading scene files: the CLI owns the file system; prism-scene gets bytes and a
//! resolver for the buffers and spectra a file refers to.

use std::path::Path;

use prism_scene::load::{LoadOptions, LoadedGeometry, Upsampling, load_scene};
use prism_scene::spectral::Overlay;

/// Loads `path`: a .gltf or .glb, or a TOML overlay (`.toml`) naming the glTF it applies
/// to. External buffers and `csv:` spectra resolve relative to the glTF file. Errors name
/// the file.
pub fn load(path: &Path, scene: Option<usize>) -> Result<LoadedGeometry, String> {
    load_with(path, scene, Upsampling::Exact)
}

/// [`load`] with a choice of upsampling (`prism trade` measures them).
pub fn load_with(
    path: &Path,
    scene: Option<usize>,
    upsampling: Upsampling,
) -> Result<LoadedGeometry, String> {
    load_edited(path, scene, upsampling, None)
}

/// [`load_with`], with `edits` applied over the file's own descriptions (and over an
/// overlay file's): a material, light or scene key `edits` describes replaces theirs.
pub fn load_edited(
    path: &Path,
    scene: Option<usize>,
    upsampling: Upsampling,
    edits: Option<&Overlay>,
) -> Result<LoadedGeometry, String> {
    let read = |p: &Path| crate::output::read_file(p);
    let is_overlay = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    let (gltf_path, overlay) = if is_overlay {
        let text = String::from_utf8(read(path)?)
            .map_err(|_| format!("'{}': not UTF-8 text", path.display()))?;
        let overlay = Overlay::parse(&text).map_err(|e| format!("'{}': {e}", path.display()))?;
        let gltf = overlay.gltf.clone().ok_or_else(|| {
            format!(
                "'{}': the overlay must name its scene (gltf = \"file.gltf\")",
                path.display()
            )
        })?;
        (
            path.parent().unwrap_or(Path::new(".")).join(gltf),
            Some(overlay),
        )
    } else {
        (path.to_path_buf(), None)
    };
    let overlay = match (overlay, edits) {
        (overlay, None) => overlay,
        (None, Some(edits)) => Some(edits.clone()),
        (Some(mut file), Some(edits)) => {
            let replaced = |entries: &mut Vec<(String, serde_json::Value)>,
                            by: &[(String, serde_json::Value)]| {
                entries.retain(|(name, _)| by.iter().all(|(n, _)| n != name));
                entries.extend(by.iter().cloned());
            };
            replaced(&mut file.materials, &edits.materials);
            replaced(&mut file.lights, &edits.lights);
            file.scene
                .extend(edits.scene.iter().map(|(k, v)| (k.clone(), v.clone())));
            Some(file)
        }
    };
    let bytes = read(&gltf_path)?;
    let dir = gltf_path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let resolve = move |uri: &str| std::fs::read(dir.join(uri));
    let options = LoadOptions::default()
        .scene(scene)
        .overlay(overlay.as_ref())
        .upsampling(upsampling);
    let loaded =
        load_scene(&bytes, &resolve, &options).map_err(|e| format!("'{}': {e}", path.display()))?;
    for warning in &loaded.warnings {
        eprintln!("prism: warning: '{}': {warning}", path.display());
    }
    Ok(loaded)
}
