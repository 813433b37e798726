//! `prism.load` and `prism.Scene`: a glTF scene (or a TOML overlay naming one) read as the
//! command line reads it, whose cameras, materials and lights can be listed.

use std::path::PathBuf;

use prism_scene::load::{LightDesc, LoadedGeometry};
use pyo3::prelude::*;

use crate::SceneError;

/// A loaded scene: render it with `prism.render(scene, ...)`.
#[pyclass(module = "prism", frozen)]
pub struct Scene {
    pub loaded: LoadedGeometry,
    pub path: PathBuf,
    pub index: Option<usize>,
}

/// Loads a .gltf or .glb file, or a .toml overlay naming one (`scene`: which of the file's
/// scenes, default its own default). A file that cannot be read or is not a scene raises
/// `prism.SceneError` naming it; unsupported features of a file are warnings on stderr.
#[pyfunction]
#[pyo3(signature = (path, scene = None))]
pub fn load(py: Python<'_>, path: PathBuf, scene: Option<usize>) -> PyResult<Scene> {
    let loaded = py
        .detach(|| prism_cli::scene_file::load(&path, scene))
        .map_err(SceneError::new_err)?;
    Ok(Scene {
        loaded,
        path,
        index: scene,
    })
}

#[pymethods]
impl Scene {
    /// The names of the scene's cameras, in the file's order (the first renders by default).
    #[getter]
    fn cameras(&self) -> Vec<String> {
        self.loaded.cameras.iter().map(|c| c.name.clone()).collect()
    }

    /// The names of the scene's materials, in the file's order.
    #[getter]
    fn materials(&self) -> Vec<String> {
        self.loaded
            .materials
            .iter()
            .map(|m| m.name.clone())
            .collect()
    }

    /// The scene's lights, one short description each (emissive meshes, then punctual
    /// lights).
    #[getter]
    fn lights(&self) -> Vec<String> {
        self.loaded
            .lights
            .iter()
            .map(|light| match light {
                LightDesc::Area { instance, .. } => {
                    let name = self
                        .loaded
                        .instances
                        .get(*instance)
                        .map(|i| i.node.clone())
                        .unwrap_or_default();
                    format!("area light '{name}'")
                }
                LightDesc::Point { .. } => "point light".into(),
                LightDesc::Spot { .. } => "spot light".into(),
                other => light_kind(other),
            })
            .collect()
    }

    /// The file the scene was read from.
    #[getter]
    fn path(&self) -> PathBuf {
        self.path.clone()
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene('{}': {} triangles, {} materials, {} lights, {} cameras)",
            self.path.display(),
            self.loaded.triangles.len(),
            self.loaded.materials.len(),
            self.loaded.lights.len(),
            self.loaded.cameras.len()
        )
    }
}

/// A light's kind, from its debug name ("Directional { .. }" -> "directional light").
fn light_kind(light: &LightDesc) -> String {
    let debug = format!("{light:?}");
    let name = debug.split([' ', '{', '(']).next().unwrap_or("light");
    format!("{} light", name.to_ascii_lowercase())
}
