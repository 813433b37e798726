//! Reading scene files: the CLI owns the file system; prism-scene gets bytes and a
//! resolver for the buffers and spectra a file refers to.

use std::path::Path;

use prism_integrator::Filter;
use prism_scene::load::mitsuba::{self, MitsubaScene, ParseOptions, PixelFilter};
use prism_scene::load::{LoadOptions, LoadedGeometry, Upsampling, load_scene};
use prism_scene::spectral::Overlay;

/// Loads `path`: a .gltf or .glb, a TOML overlay (`.toml`) naming the glTF it applies
/// to, or a Mitsuba 3 scene (`.xml`) at its defaults. External buffers and `csv:` spectra
/// resolve relative to the glTF file. Errors name the file.
pub fn load(path: &Path, scene: Option<usize>) -> Result<LoadedGeometry, String> {
    if is_mitsuba(path) {
        return load_mitsuba(path, &[]).map(|m| m.geometry);
    }
    load_with(path, scene, Upsampling::Exact)
}

/// What a scene file asks of the render where the command line does not say: a Mitsuba
/// scene's film size and filter, sampler's count and integrator's depth.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FileDefaults {
    /// The film's width and height.
    pub size: Option<(u32, u32)>,
    /// Samples per pixel.
    pub spp: Option<u64>,
    /// Bounces.
    pub max_depth: Option<u32>,
    /// The film's pixel filter.
    pub filter: Option<Filter>,
}

impl FileDefaults {
    /// What the Mitsuba scene's film, sampler and integrator ask for.
    pub fn of_mitsuba(scene: &MitsubaScene) -> Self {
        FileDefaults {
            size: Some((scene.film.width, scene.film.height)),
            spp: scene.film.spp,
            max_depth: scene.max_depth,
            filter: Some(pixel_filter(scene.film.filter)),
        }
    }
}

/// prism's filter for a Mitsuba film's: Mitsuba's Gaussian reaches 4 standard deviations.
fn pixel_filter(filter: PixelFilter) -> Filter {
    match filter {
        PixelFilter::Box => Filter::Box,
        PixelFilter::Gaussian { stddev } => Filter::Gaussian {
            radius: 4.0 * stddev,
            sigma: stddev,
        },
        PixelFilter::Tent { radius } => Filter::Tent { radius },
        // A filter this version does not know: Mitsuba's default.
        _ => Filter::Gaussian {
            radius: 2.0,
            sigma: 0.5,
        },
    }
}

/// Whether `path` names a Mitsuba scene (`.xml`).
pub fn is_mitsuba(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"))
}

/// Loads the Mitsuba 3 scene `path` with `defines` (`NAME=VALUE`, as `mitsuba -D`): its
/// includes, `.spd` spectra and meshes resolve relative to it. Warnings go to stderr.
pub fn load_mitsuba(path: &Path, defines: &[String]) -> Result<MitsubaScene, String> {
    let defines = defines
        .iter()
        .map(|d| {
            d.split_once('=')
                .map(|(n, v)| (n.trim().to_string(), v.to_string()))
                .filter(|(n, _)| !n.is_empty())
                .ok_or_else(|| format!("-D '{d}': expected NAME=VALUE"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let text = String::from_utf8(crate::output::read_file(path)?)
        .map_err(|_| format!("'{}': not UTF-8 text", path.display()))?;
    load_mitsuba_text(&text, &path.display().to_string(), &defines)
}

/// Loads the Mitsuba 3 scene `text` as if it were the file `file` (errors name it; the
/// files it names resolve relative to its directory), with `defines`.
pub fn load_mitsuba_text(
    text: &str,
    file: &str,
    defines: &[(String, String)],
) -> Result<MitsubaScene, String> {
    // The loader joins the names a file gives to that file's directory.
    let resolve = |name: &str| std::fs::read(name);
    let options = ParseOptions {
        defines,
        resolve: &resolve,
    };
    let scene =
        mitsuba::load(text, file, &options, &LoadOptions::default()).map_err(|e| e.to_string())?;
    for warning in &scene.geometry.warnings {
        eprintln!("prism: warning: {warning}");
    }
    Ok(scene)
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
