//! `prism.load`, `prism.load_dict` and `prism.Scene`: a glTF scene (or a TOML overlay naming
//! one) or a Mitsuba 3 scene read as the command line reads it, whose cameras, materials and
//! lights can be listed.

use std::path::PathBuf;

use prism_cli::scene_file::FileDefaults;
use prism_scene::load::{LightDesc, LoadedGeometry, Upsampling};
use prism_scene::spectral::Overlay;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use serde_json::{Map, Value};

use crate::SceneError;
use crate::spectrum::{Kind, as_spectrum};

/// A loaded scene: render it with `prism.render(scene, ...)`; replace its materials',
/// lights' and environment's descriptions with `set_material`, `set_light` and
/// `set_environment`.
#[pyclass(module = "prism")]
pub struct Scene {
    pub loaded: LoadedGeometry,
    /// What the file asks of a render (a Mitsuba scene's film, sampler and depth).
    pub defaults: FileDefaults,
    /// Whether the scene is a Mitsuba scene (which edits do not apply to).
    mitsuba: bool,
    pub path: PathBuf,
    pub index: Option<usize>,
    /// What Python replaced, applied over the file as an overlay is.
    edits: Overlay,
}

impl Scene {
    /// Reads the file again with `edits`; on an error the scene stays as it was.
    fn reload(&mut self, py: Python<'_>, edits: Overlay) -> PyResult<()> {
        if self.mitsuba {
            return Err(SceneError::new_err(format!(
                "'{}': set_material, set_light and set_environment edit glTF scenes; edit a Mitsuba scene's file or dict",
                self.path.display()
            )));
        }
        let (path, index) = (self.path.clone(), self.index);
        let loaded = py
            .detach(|| {
                prism_cli::scene_file::load_edited(&path, index, Upsampling::Exact, Some(&edits))
            })
            .map_err(SceneError::new_err)?;
        self.loaded = loaded;
        self.edits = edits;
        Ok(())
    }
}

/// Sets the description of `name` among named `entries` (an overlay's materials or lights).
fn replace(entries: &mut Vec<(String, Value)>, name: &str, description: Value) {
    entries.retain(|(n, _)| n != name);
    entries.push((name.to_string(), description));
}

/// The scene format's JSON for a Python value: dicts, lists, strings, numbers, booleans,
/// and spectra (a named spectrum stays its name; any other is sampled every nanometre from
/// 300 to 1000 nm as [[nm, value], ...]).
fn to_json(value: &Bound<'_, PyAny>) -> PyResult<Value> {
    if value.is_none() {
        return Ok(Value::Null);
    }
    if let Ok(b) = value.cast::<PyBool>() {
        return Ok(Value::Bool(b.is_true()));
    }
    if value.is_instance_of::<PyInt>() {
        return Ok(Value::from(value.extract::<i64>()?));
    }
    if value.is_instance_of::<PyFloat>() {
        let x: f64 = value.extract()?;
        return serde_json::Number::from_f64(x)
            .map(Value::Number)
            .ok_or_else(|| PyValueError::new_err(format!("{x} is not a finite number")));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(Value::String(value.extract()?));
    }
    if let Ok(dict) = value.cast::<PyDict>() {
        let mut map = Map::new();
        for (k, v) in dict.iter() {
            map.insert(k.extract::<String>()?, to_json(&v)?);
        }
        return Ok(Value::Object(map));
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        return value
            .try_iter()?
            .map(|item| to_json(&item?))
            .collect::<PyResult<Vec<_>>>()
            .map(Value::Array);
    }
    let spectrum = as_spectrum(value)?;
    if let Kind::Named(_) = spectrum.kind.as_ref() {
        return Ok(Value::String(spectrum.description().to_string()));
    }
    let samples = (300..=1000)
        .map(|nm| {
            let v = prism_spectrum::Spectrum::evaluate(spectrum.kind.as_ref(), f64::from(nm));
            serde_json::json!([nm, v])
        })
        .collect();
    Ok(Value::Array(samples))
}

/// Loads a .gltf or .glb file, a .toml overlay naming one (`scene`: which of the file's
/// scenes, default its own default), or a Mitsuba 3 scene (.xml), whose parameters
/// (`<default>`s and `$name`s) the keywords set as `mi.load_file` and `mitsuba -D` do. A
/// file that cannot be read or is not a scene raises `prism.SceneError` naming it;
/// unsupported features of a file are warnings on stderr.
#[pyfunction]
#[pyo3(signature = (path, scene = None, **parameters))]
pub fn load(
    py: Python<'_>,
    path: PathBuf,
    scene: Option<usize>,
    parameters: Option<&Bound<'_, PyDict>>,
) -> PyResult<Scene> {
    let defines = defines(parameters)?;
    if !prism_cli::scene_file::is_mitsuba(&path) {
        if let Some((name, _)) = defines.first() {
            return Err(PyTypeError::new_err(format!(
                "prism.load() got the keyword argument '{name}': parameters are a Mitsuba scene's (.xml)"
            )));
        }
        let loaded = py
            .detach(|| prism_cli::scene_file::load(&path, scene))
            .map_err(SceneError::new_err)?;
        return Ok(Scene {
            loaded,
            defaults: FileDefaults::default(),
            mitsuba: false,
            path,
            index: scene,
            edits: Overlay::default(),
        });
    }
    let file = path.display().to_string();
    let text = std::fs::read(&path)
        .map_err(|e| SceneError::new_err(format!("'{file}': {e}")))
        .and_then(|bytes| {
            String::from_utf8(bytes)
                .map_err(|_| SceneError::new_err(format!("'{file}': not UTF-8 text")))
        })?;
    mitsuba_scene(py, &text, &file, &defines, path.clone())
}

/// Loads a Mitsuba 3 scene given as its XML text (`prism.load_dict` writes a dict as
/// XML): files it names resolve relative to `directory`.
#[pyfunction]
#[pyo3(signature = (text, directory, **parameters))]
pub fn load_mitsuba_xml(
    py: Python<'_>,
    text: &str,
    directory: PathBuf,
    parameters: Option<&Bound<'_, PyDict>>,
) -> PyResult<Scene> {
    let defines = defines(parameters)?;
    let path = directory.join("<dict>");
    mitsuba_scene(
        py,
        text,
        &path.display().to_string(),
        &defines,
        path.clone(),
    )
}

fn mitsuba_scene(
    py: Python<'_>,
    text: &str,
    file: &str,
    defines: &[(String, String)],
    path: PathBuf,
) -> PyResult<Scene> {
    let scene = py
        .detach(|| prism_cli::scene_file::load_mitsuba_text(text, file, defines))
        .map_err(SceneError::new_err)?;
    Ok(Scene {
        defaults: FileDefaults::of_mitsuba(&scene),
        loaded: scene.geometry,
        mitsuba: true,
        path,
        index: None,
        edits: Overlay::default(),
    })
}

/// Keyword parameters as `-D` definitions: booleans as Mitsuba writes them (`true`,
/// `false`), anything else its `str()`.
fn defines(parameters: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, String)>> {
    let Some(parameters) = parameters else {
        return Ok(Vec::new());
    };
    parameters
        .iter()
        .map(|(k, v)| {
            let value = match v.cast::<PyBool>() {
                Ok(b) => if b.is_true() { "true" } else { "false" }.to_string(),
                Err(_) => v.str()?.to_string(),
            };
            Ok((k.extract::<String>()?, value))
        })
        .collect()
}

#[pymethods]
impl Scene {
    /// Replaces material `name`'s spectral description (the scene format's
    /// `PRISM_spectral` object, as a dict: `{"type": "diffuse", "reflectance": spectrum}`,
    /// `{"emission": {"spectrum": "illuminant:A", "scale": 20.0}}`...; spectra may be
    /// `prism.Spectrum`s, colour-science distributions, names or numbers). The scene is
    /// read again; an unknown name or key raises `prism.SceneError` and changes nothing.
    fn set_material(
        &mut self,
        py: Python<'_>,
        name: &str,
        description: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let mut edits = self.edits.clone();
        replace(&mut edits.materials, name, to_json(description)?);
        self.reload(py, edits)
    }

    /// Replaces punctual light `name`'s spectral description (`{"spectrum": ...,
    /// "scale": ...}`; see `set_material`). Area lights are materials' `emission`.
    fn set_light(
        &mut self,
        py: Python<'_>,
        name: &str,
        description: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let mut edits = self.edits.clone();
        replace(&mut edits.lights, name, to_json(description)?);
        self.reload(py, edits)
    }

    /// Replaces the environment: a spectrum (uniform light from every direction), a
    /// number, or `{"image": "sky.hdr", "rotation": 90}` (relative to the glTF file).
    fn set_environment(&mut self, py: Python<'_>, environment: &Bound<'_, PyAny>) -> PyResult<()> {
        let mut edits = self.edits.clone();
        edits
            .scene
            .insert("environment".into(), to_json(environment)?);
        self.reload(py, edits)
    }

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
