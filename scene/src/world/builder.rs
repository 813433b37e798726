//! Scenes built in code: materials, triangles, emitters and lights added one call at a
//! time, the bookkeeping of [`SceneParts`] (parallel lists, one light per emissive
//! triangle) done for the caller.

use glam::Vec3;

use super::{Scene, SceneParts, VertexAttributes};
use crate::camera::Camera;
use crate::geometry::BvhQuality;
use crate::lights::Light;
use crate::materials::Material;
use crate::textures::SceneSpectrum;

/// Builds a [`Scene`] from triangles, materials and lights.
///
/// ```
/// use prism_scene::camera::Camera;
/// use prism_scene::glam::Vec3;
/// use prism_scene::world::{Material, SceneBuilder, SceneSpectrum};
///
/// let mut builder = SceneBuilder::new(Camera::look_at(Vec3::new(0.0, 1.0, 4.0), Vec3::new(0.0, 1.0, 0.0), Vec3::Y, 0.8));
/// let white = builder.material(Material::Diffuse { reflectance: SceneSpectrum::Constant(0.8) });
/// // A floor, two triangles.
/// let (a, b, c, d) = (Vec3::new(-2.0, 0.0, -2.0), Vec3::new(2.0, 0.0, -2.0), Vec3::new(2.0, 0.0, 2.0), Vec3::new(-2.0, 0.0, 2.0));
/// builder.triangles(&[[a, c, b], [a, d, c]], white);
/// // A square lamp facing down, emitting a flat spectrum of 1 (W m^-2 sr^-1 nm^-1).
/// let y = 2.0;
/// let (p, q, r, s) = (Vec3::new(-0.5, y, -0.5), Vec3::new(0.5, y, -0.5), Vec3::new(0.5, y, 0.5), Vec3::new(-0.5, y, 0.5));
/// builder.emitter(&[[p, q, r], [p, r, s]], SceneSpectrum::Constant(1.0), false);
/// let scene = builder.build().unwrap();
/// assert_eq!(scene.materials().len(), 2); // white, and the emitters' black
/// // Straight down from under the lamp: the floor.
/// let ray = prism_scene::geometry::Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::NEG_Y, f32::INFINITY);
/// let hit = scene.intersect(&ray).unwrap();
/// assert!(hit.p.y.abs() < 1e-5);
/// ```
#[derive(Debug, Clone)]
pub struct SceneBuilder {
    parts: SceneParts,
    /// The black material emitters get, once one is added.
    emitter_material: Option<u32>,
}

impl SceneBuilder {
    /// An empty scene seen by `camera`.
    pub fn new(camera: Camera) -> Self {
        Self {
            parts: SceneParts {
                triangles: Vec::new(),
                attributes: VertexAttributes::default(),
                triangle_material: Vec::new(),
                materials: Vec::new(),
                emission: Vec::new(),
                lights: Vec::new(),
                camera,
                quality: BvhQuality::Medium,
            },
            emitter_material: None,
        }
    }

    /// Adds a material; its index for [`SceneBuilder::triangles`].
    pub fn material(&mut self, material: Material) -> u32 {
        self.parts.materials.push(material);
        (self.parts.materials.len() - 1) as u32
    }

    /// Adds flat-shaded triangles (counter-clockwise seen from their front) of material
    /// `material`.
    pub fn triangles(&mut self, triangles: &[[Vec3; 3]], material: u32) -> &mut Self {
        self.parts.triangles.extend_from_slice(triangles);
        self.parts
            .triangle_material
            .extend(std::iter::repeat_n(material, triangles.len()));
        self
    }

    /// Adds emissive triangles of radiance `emission` (from their front faces, or both
    /// sides when `two_sided`), each a light; they reflect nothing.
    pub fn emitter(
        &mut self,
        triangles: &[[Vec3; 3]],
        emission: SceneSpectrum,
        two_sided: bool,
    ) -> &mut Self {
        let black = match self.emitter_material {
            Some(m) => m,
            None => {
                let m = self.material(Material::Diffuse {
                    reflectance: SceneSpectrum::Constant(0.0),
                });
                self.emitter_material = Some(m);
                m
            }
        };
        self.parts.emission.push(emission);
        let emission = (self.parts.emission.len() - 1) as u32;
        let first = self.parts.triangles.len() as u32;
        self.triangles(triangles, black);
        self.parts
            .lights
            .extend((0..triangles.len() as u32).map(|k| Light::Triangle {
                triangle: first + k,
                emission,
                two_sided,
            }));
        self
    }

    /// Adds a light that is not a triangle (point, spot, directional, environment).
    pub fn light(&mut self, light: Light) -> &mut Self {
        self.parts.lights.push(light);
        self
    }

    /// The BVH's build effort (default medium).
    pub fn quality(&mut self, quality: BvhQuality) -> &mut Self {
        self.parts.quality = quality;
        self
    }

    /// The scene, or why the parts do not make one (a material index out of range...).
    pub fn build(self) -> Result<Scene, crate::LoadError> {
        Scene::new(self.parts)
    }
}
