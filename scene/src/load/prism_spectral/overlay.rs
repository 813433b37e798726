//! The TOML overlay: a file beside a glTF scene that gives its materials, lights and
//! environment spectral descriptions by name, for scenes whose glTF cannot (or should
//! not) be edited. It is the same description as the `PRISM_spectral` extension, written
//! in TOML and applied to the glTF document before anything is read from it, so both
//! forms share one parser and one set of checks.

use gltf::json::Root;
use serde_json::{Map, Value};

use super::EXTENSION;
use crate::load::LoadError;

/// A parsed overlay.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overlay {
    /// The glTF file the overlay applies to (relative to the overlay), if it names one.
    pub gltf: Option<String>,
    /// Material descriptions by material name.
    pub materials: Vec<(String, Value)>,
    /// Light descriptions by `KHR_lights_punctual` light name.
    pub lights: Vec<(String, Value)>,
    /// The scene-wide description (`environment`), from the overlay's top-level keys.
    pub scene: Map<String, Value>,
}

impl Overlay {
    /// Parses overlay text: top-level `gltf = "file.gltf"` and scene keys, tables
    /// `[materials.NAME]` and `[lights.NAME]`.
    pub fn parse(text: &str) -> Result<Self, LoadError> {
        let bad = |m: String| LoadError::Spectral(format!("overlay: {m}"));
        #[cfg(feature = "toml")]
        let parsed =
            toml::from_str::<Value>(text).map_err(|e| e.to_string().trim().replace('\n', " "));
        #[cfg(not(feature = "toml"))]
        let parsed: Result<Value, String> = {
            let _ = text;
            Err("prism-scene was built without its `toml` feature".into())
        };
        let root = parsed.map_err(bad)?;
        let Value::Object(mut map) = root else {
            return Err(bad("not a table".into()));
        };
        let gltf = match map.remove("gltf") {
            None => None,
            Some(Value::String(s)) => Some(s),
            Some(v) => return Err(bad(format!("gltf = {v} is not a file name"))),
        };
        let mut named = |key: &str| -> Result<Vec<(String, Value)>, LoadError> {
            match map.remove(key) {
                None => Ok(Vec::new()),
                Some(Value::Object(entries)) => Ok(entries.into_iter().collect()),
                Some(_) => Err(bad(format!("[{key}] must be a table of named entries"))),
            }
        };
        let materials = named("materials")?;
        let lights = named("lights")?;
        Ok(Self {
            gltf,
            materials,
            lights,
            scene: map,
        })
    }

    /// Writes the descriptions into the document's `PRISM_spectral` extensions, replacing
    /// what the file had for the same material or light. A name that matches nothing is an
    /// error listing the names there are.
    pub(crate) fn apply(&self, root: &mut Root) -> Result<(), LoadError> {
        for (name, description) in &self.materials {
            let mut found = false;
            for material in &mut root.materials {
                if material.name.as_deref() == Some(name) {
                    let extensions = material.extensions.get_or_insert_with(Default::default);
                    extensions
                        .others
                        .insert(EXTENSION.into(), description.clone());
                    found = true;
                }
            }
            if !found {
                let names = root.materials.iter().filter_map(|m| m.name.as_deref());
                return Err(unknown("material", name, names));
            }
        }
        for (name, description) in &self.lights {
            let lights = root
                .extensions
                .as_mut()
                .and_then(|e| e.khr_lights_punctual.as_mut())
                .map_or(&mut [][..], |l| &mut l.lights[..]);
            let mut found = false;
            for light in lights.iter_mut() {
                if light.name.as_deref() == Some(name) {
                    let mut extensions: Map<String, Value> = match &light.extensions {
                        Some(raw) => serde_json::from_str(raw.get()).unwrap_or_default(),
                        None => Map::new(),
                    };
                    extensions.insert(EXTENSION.into(), description.clone());
                    let text = Value::Object(extensions).to_string();
                    light.extensions = Some(
                        serde_json::value::RawValue::from_string(text)
                            .map_err(|e| LoadError::Spectral(format!("light {name}: {e}")))?,
                    );
                    found = true;
                }
            }
            if !found {
                let names = lights.iter().filter_map(|l| l.name.as_deref());
                return Err(unknown("light", name, names));
            }
        }
        if !self.scene.is_empty() {
            let others = &mut root.extensions.get_or_insert_with(Default::default).others;
            let entry = others
                .entry(EXTENSION)
                .or_insert_with(|| Value::Object(Map::new()));
            match entry {
                Value::Object(existing) => {
                    existing.extend(self.scene.iter().map(|(k, v)| (k.clone(), v.clone())))
                }
                other => *other = Value::Object(self.scene.clone()),
            }
        }
        Ok(())
    }
}

fn unknown<'a>(kind: &str, name: &str, names: impl Iterator<Item = &'a str>) -> LoadError {
    let names: Vec<&str> = names.collect();
    LoadError::Spectral(format!(
        "overlay: no {kind} named '{name}' in the glTF ({kind}s: {})",
        if names.is_empty() {
            "none".into()
        } else {
            names.join(", ")
        }
    ))
}
