//! What a loaded scene contains and uses: the report behind `prism info`, and the facts
//! the integrator specializes on.

use super::LoadedGeometry;

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
    /// Whether any material references a base colour texture (not evaluated yet).
    pub uses_textures: bool,
    /// Whether a transmissive material disperses (`KHR_materials_dispersion`).
    pub uses_dispersion: bool,
}

impl LoadedGeometry {
    /// The summary of this scene.
    pub fn summary(&self) -> SceneSummary {
        let emits = |i: &super::MeshInstance| {
            i.material
                .and_then(|m| self.materials.get(m))
                .is_some_and(|m| m.emission.is_some())
        };
        let (lo, hi) = self.bounds();
        SceneSummary {
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
            uses_transmission: self.materials.iter().any(|m| m.transmission > 0.0),
            uses_textures: self.materials.iter().any(|m| m.has_base_color_texture),
            uses_dispersion: self
                .materials
                .iter()
                .any(|m| m.transmission > 0.0 && m.dispersion > 0.0),
        }
    }
}
