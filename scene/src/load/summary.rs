//! What a loaded scene contains and uses: the report behind `prism info`, and the facts
//! the integrator specializes on.

use super::{LightDesc, LoadedGeometry};
use crate::materials::Material;
use crate::textures::SceneSpectrum;

/// A summary of a loaded scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneSummary {
    /// Triangles.
    pub triangles: usize,
    /// Mesh primitive instances.
    pub instances: usize,
    /// Materials in the file.
    pub materials: usize,
    /// Instances whose material emits (area lights).
    pub emissive_instances: usize,
    /// Triangles of emissive instances.
    pub emissive_triangles: usize,
    /// Camera names.
    pub cameras: Vec<String>,
    /// Bounding box of the geometry.
    pub bounds: ([f32; 3], [f32; 3]),
    /// Whether any material transmits (glass).
    pub uses_transmission: bool,
    /// Whether any material has a base colour, metallic-roughness, normal or emissive
    /// texture.
    pub uses_textures: bool,
    /// Whether a transmissive material disperses (`KHR_materials_dispersion`, or a
    /// spectral IOR from `PRISM_spectral`).
    pub uses_dispersion: bool,
    /// Whether a material re-radiates (fluorescence).
    pub uses_fluorescence: bool,
    /// Materials that are polarizing elements (polarizers, retarders), and lights whose
    /// emission is polarized: what only a polarized render shows.
    pub polarizing: (usize, usize),
    /// Sources with schedules (materials' emission, punctual lights, the environment)
    /// and phosphorescent materials: what `--at` changes.
    pub timed: (usize, usize),
    /// The glTF features and extensions the file uses that change how it renders.
    pub gltf_features: Vec<String>,
    /// What the lights' spectra are, one line each, distinct.
    pub light_spectra: Vec<String>,
    /// The participating media, one line each (`material: what it is`, `world: ...` for
    /// fog): empty in a vacuum.
    pub media: Vec<String>,
    /// The wavelengths (nm) the scene needs: the visible 360-830 nm, widened to where its
    /// lights emit (above 1% of their peak) within the range of a fluorescent material
    /// that can turn that light into visible light.
    pub wavelength_range: (f32, f32),
}

impl LoadedGeometry {
    /// The summary of this scene.
    pub fn summary(&self) -> SceneSummary {
        let emits = |i: &super::MeshInstance| {
            i.material
                .and_then(|m| self.materials.get(m))
                .is_some_and(|m| m.emits())
        };
        let surface = |m: &super::MaterialDesc| m.spectral.as_ref().and_then(|s| s.surface.clone());
        // Light spectra: spectral emissions, RGB emissions, punctual lights, environment.
        let mut spectra: Vec<SceneSpectrum> = Vec::new();
        for i in self.instances.iter().filter(|i| emits(i)) {
            let m = &self.materials[i.material.unwrap_or_default()];
            spectra.extend(m.emission_spectrum());
        }
        for light in &self.lights {
            if let LightDesc::Point { spectrum, .. }
            | LightDesc::Spot { spectrum, .. }
            | LightDesc::Directional { spectrum, .. } = light
            {
                spectra.push(spectrum.clone());
            }
        }
        spectra.extend(
            self.spectral
                .environment
                .as_ref()
                .map(|e| e.spectrum().clone()),
        );
        let mut light_spectra: Vec<String> = spectra.iter().map(SceneSpectrum::describe).collect();
        light_spectra.sort();
        light_spectra.dedup();
        // The camera sees 360-830 nm; light outside it matters only where a fluorescent
        // material can turn it into visible light.
        let mut range = (360.0f32, 830.0f32);
        for m in &self.materials {
            if let Some(Material::Fluorescent { reradiation, .. }) = surface(m) {
                let (lo, hi) = reradiation.range_nm();
                for (a, b) in spectra.iter().filter_map(|s| s.extent(0.01)) {
                    if a < hi && b > lo {
                        range = (range.0.min(a.max(lo)), range.1.max(b.min(hi)));
                    }
                }
            }
        }
        let mut media: Vec<String> = self
            .materials
            .iter()
            .filter_map(|m| {
                let medium = m
                    .spectral
                    .as_ref()
                    .and_then(|s| s.medium.as_ref())
                    .or(m.medium.as_ref())?;
                Some(format!("{}: {}", m.name, medium.describe()))
            })
            .collect();
        media.extend(
            self.spectral
                .medium
                .as_ref()
                .map(|m| format!("world (fog): {}", m.describe())),
        );
        // Media the file places by surface (Mitsuba's), listed by their index.
        if let Some(placed) = &self.media {
            media.extend(
                placed
                    .all()
                    .iter()
                    .enumerate()
                    .map(|(i, m)| format!("medium {i}: {}", m.describe())),
            );
        }
        let dyed = self
            .materials
            .iter()
            .filter_map(|m| m.spectral.as_ref().and_then(|s| s.medium.as_ref()))
            .chain(self.spectral.medium.as_ref())
            .any(|m| m.fluorescence().is_some());
        let (lo, hi) = self.bounds();
        SceneSummary {
            media,
            triangles: self.triangles.len(),
            instances: self.instances.len(),
            materials: self.materials.len(),
            emissive_instances: self.instances.iter().filter(|i| emits(i)).count(),
            emissive_triangles: self
                .instances
                .iter()
                .filter(|i| emits(i))
                .map(|i| i.count)
                .sum(),
            cameras: self.cameras.iter().map(|c| c.name.clone()).collect(),
            bounds: (lo.to_array(), hi.to_array()),
            uses_transmission: self.materials.iter().any(|m| match surface(m) {
                Some(s) => matches!(
                    s,
                    Material::Dielectric { .. }
                        | Material::MicrofacetDielectric { .. }
                        | Material::ThinDielectric { .. }
                ),
                None => m.transmission > 0.0,
            }),
            uses_textures: self.materials.iter().any(|m| {
                m.has_base_color_texture
                    || m.metallic_roughness_texture.is_some()
                    || m.normal_texture.is_some()
            }),
            uses_dispersion: self.materials.iter().any(|m| match surface(m) {
                Some(s) => s.dispersive(),
                None => m.transmission > 0.0 && m.dispersion > 0.0,
            }),
            uses_fluorescence: dyed
                || self
                    .materials
                    .iter()
                    .any(|m| surface(m).is_some_and(|s| s.fluorescent())),
            polarizing: (
                self.materials
                    .iter()
                    .filter(|m| surface(m).is_some_and(|s| s.polarizing_element()))
                    .count(),
                self.light_polarization.len(),
            ),
            timed: (
                self.materials
                    .iter()
                    .filter(|m| m.spectral.as_ref().is_some_and(|s| s.on.is_some()))
                    .count()
                    + self.light_schedules.len()
                    + usize::from(self.spectral.environment_on.is_some()),
                self.materials
                    .iter()
                    .filter(|m| m.spectral.as_ref().is_some_and(|s| s.decay.is_some()))
                    .count(),
            ),
            gltf_features: self.gltf_features.clone(),
            light_spectra,
            wavelength_range: range,
        }
    }
}
