//! The render-ready world: geometry in a BVH, a material per triangle, lights with the
//! distribution that chooses among them, a camera, and the features the scene uses. This
//! is what the integrator sees: spectra to sample at its wavelengths and BSDFs to
//! evaluate, never RGB.
//!
//! What the scene is made of has folders of its own below this one: textures and spectra
//! ([`crate::textures`]), materials ([`crate::materials`]), lights ([`crate::lights`]) and
//! the BSDF at a hit ([`crate::bsdf::Bsdf`]); their types are re-exported here, so that
//! `world::{Material, Light, SceneSpectrum, ...}` name them too. A scene from a loaded
//! glTF file is made in `load` (`Scene::from_loaded`).

mod builder;
mod corner_colors;
mod departure;
mod guide;
#[cfg(feature = "gltf")]
mod options;
mod perturbed;
mod time;

pub use crate::bsdf::Bsdf;
#[allow(deprecated)]
pub use crate::lights::Aim;
pub use crate::lights::{
    CausticTarget, DEFAULT_ENVIRONMENT, EmissionCache, EmissionSample, Environment, EnvironmentMap,
    Light, LightSample, Lights, MAX_GROUPS, SpotFalloff, SpotTexture, grey_environment, unit_d65,
};
pub use crate::materials::{
    Alpha, AlphaMode, AnisotropyDesc, ClearcoatDesc, DiffuseTransmissionDesc, IridescenceDesc,
    Layers, Material, NormalMap, SheenDesc, SpecularDesc, SurfaceFrame, TransmissionDesc,
};
pub use crate::textures::{
    Encoding, RgbTexture, SceneSpectrum, SpectralTexture, TEX_COORD_SETS, TexCoords, UvTransform,
    Wrap,
};
pub use builder::SceneBuilder;
pub use departure::Departure;
#[cfg(feature = "gltf")]
pub use options::SceneOptions;
pub use time::{Schedule, Timeline};

use std::sync::Arc;

use glam::{Vec2, Vec3};
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use crate::camera::Camera;
use crate::geometry::{
    Bvh, BvhQuality, Ray, offset_ray_origin, triangle_normal, triangle_point_error, unit_or_zero,
};

/// What a scene uses, so that the integrator pays only for what is there.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Features {
    /// A material whose index depends on wavelength: refraction splits the package.
    pub dispersion: bool,
    /// A re-radiating (fluorescent) material: wavelengths change along paths.
    pub fluorescence: bool,
    /// A transmissive material.
    pub transmission: bool,
    /// A material with a delta lobe (smooth glass or metal): caustics, which the
    /// integrator traces from the lights.
    pub specular: bool,
    /// A participating medium (fog, or one inside a boundary) or an interface boundary:
    /// paths are traced by the volumetric path tracer.
    pub media: bool,
}

/// Everything a [`Scene`] is made of, for building scenes in code (tests, procedural
/// content) as well as from files.
#[derive(Debug, Clone)]
pub struct SceneParts {
    /// World-space triangles.
    pub triangles: Vec<[Vec3; 3]>,
    /// Per-vertex shading normals and texture coordinates.
    pub attributes: VertexAttributes,
    /// The material of each triangle (index into `materials`).
    pub triangle_material: Vec<u32>,
    /// Materials.
    pub materials: Vec<Material>,
    /// Emission spectra (radiance) that [`Light::Triangle`] refers to.
    pub emission: Vec<SceneSpectrum>,
    /// Lights.
    pub lights: Vec<Light>,
    /// The camera.
    pub camera: Camera,
    /// BVH build effort.
    pub quality: BvhQuality,
}

/// Per-vertex attributes of the triangles, each list parallel to the triangles or empty
/// (empty normals: flat shading; empty UVs: texture coordinates 0), and the normal maps
/// that read them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct VertexAttributes {
    /// Unit shading normals at the vertices.
    pub normals: Vec<[Vec3; 3]>,
    /// Texture coordinates at the vertices (the first set).
    pub uvs: Vec<[glam::Vec2; 3]>,
    /// The second set's, for textures that read it (empty: such textures read the first
    /// set's; see [`TexCoords`]).
    pub uvs1: Vec<[glam::Vec2; 3]>,
    /// Unit tangents at the vertices, with glTF's handedness sign in w (bitangent =
    /// normal x tangent times w): only normal maps read them.
    pub tangents: Vec<[glam::Vec4; 3]>,
    /// Per material (parallel to the materials, or empty: no normal maps), its normal
    /// map. A material with one needs `tangents`.
    pub normal_maps: Vec<Option<Arc<NormalMap>>>,
    /// Vertex colours (linear RGBA): their RGB multiplies the base colour's reflectance
    /// (as the reflectance spectrum of the colour, through `color_table`).
    pub colors: Vec<[glam::Vec4; 3]>,
    /// The coefficient table that turns vertex colours into spectra (needed with them).
    pub color_table: Option<Arc<prism_upsample::CoefficientTable>>,
    /// Whether vertex colours blend as spectra (each corner's upsampled, then
    /// interpolated: Mitsuba's mesh attributes) rather than as RGB (glTF's `COLOR_0`).
    pub colors_blend_spectra: bool,
    /// Per material (parallel to the materials, or empty: every surface opaque), its
    /// alpha coverage, None where opaque. Rays pass through where it says so.
    pub alpha: Vec<Option<Arc<Alpha>>>,
    /// Per material (parallel to the materials, or empty: none), Mitsuba's normal or bump
    /// map around its BSDF ([`crate::materials::Perturbation`]).
    pub perturbations: Vec<Option<Arc<crate::materials::Perturbation>>>,
}

impl VertexAttributes {
    /// The texture coordinates of texture coordinate set `set` at the vertices: the second
    /// set's where the scene keeps one, the first's otherwise.
    pub fn uvs_of_set(&self, set: usize) -> &[[glam::Vec2; 3]] {
        if set >= 1 && !self.uvs1.is_empty() {
            &self.uvs1
        } else {
            &self.uvs
        }
    }
}

/// Where a ray meets the scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// The point.
    pub p: Vec3,
    /// Its floating-point error bound.
    pub error: Vec3,
    /// Unit geometric normal, on the side the triangle's counter-clockwise winding faces.
    pub normal: Vec3,
    /// Unit shading normal (interpolated vertex normals), on the geometric normal's side.
    pub shading_normal: Vec3,
    /// Texture coordinates in each set, and the hit's footprint in each (textures are
    /// filtered over it: see [`Scene::set_footprint`]; intersections return `-inf`, which
    /// reads texels unfiltered).
    pub tex: TexCoords,
    /// The vertex colour (linear RGBA; white without vertex colours).
    pub color: glam::Vec4,
    /// The ray parameter.
    pub t: f32,
    /// The triangle.
    pub triangle: u32,
}

impl Hit {
    /// A ray leaving the hit along `direction`, offset so it cannot hit its own surface.
    #[inline]
    pub fn spawn(&self, direction: Vec3) -> Ray {
        let origin = offset_ray_origin(self.p, self.error, self.normal, direction);
        Ray::new(origin, direction, f32::INFINITY)
    }

    /// A shadow ray towards a point `distance` away along the unit `direction` (infinity
    /// for distant lights), stopping just short of it.
    #[inline]
    pub fn spawn_to(&self, direction: Vec3, distance: f32) -> Ray {
        let origin = offset_ray_origin(self.p, self.error, self.normal, direction);
        let t_max = if distance.is_finite() {
            (distance - (origin - self.p).length()) * (1.0 - 1e-4)
        } else {
            f32::INFINITY
        };
        Ray::new(origin, direction, t_max.max(0.0))
    }
}

/// The most cut-out or transparent surfaces a ray passes through before the next one
/// counts as a hit (dense foliage seen edge-on has dozens of layers).
pub const MAX_ALPHA_CROSSINGS: usize = 256;

/// A scene ready to render.
pub struct Scene {
    bvh: Bvh,
    triangles: Vec<[Vec3; 3]>,
    /// Each triangle's unit normal (`triangle_normal`), computed once rather than at
    /// every hit (a square root and a division in a hit's dependency chain).
    normals: Vec<Vec3>,
    attributes: VertexAttributes,
    triangle_material: Vec<u32>,
    materials: Vec<Material>,
    emission: Vec<SceneSpectrum>,
    lights: Lights,
    camera: Camera,
    features: Features,
    centre: Vec3,
    radius: f32,
    /// Per material: where its re-radiated light comes from (fluorescent materials only).
    light_wavelengths: Vec<Option<prism_sampling::distribution::PiecewiseConstant1D>>,
    /// Whether the scene is lit by the default environment (see `lit_by_default()`).
    pub(crate) lit_by_default: bool,
    /// Whether a material has a base colour or metallic-roughness texture.
    filters_textures: bool,
    /// Whether any material reads the surface's tangent frame (anisotropy, a coat's
    /// normal texture): only then does [`Scene::bsdf`] look.
    oriented_materials: bool,
    /// Per light, its emission's linear polarization; empty when no light is polarized.
    light_polarization: Vec<Option<crate::polarization::LinearPolarization>>,
    /// When its lights shine and how long its phosphors glow (empty: steady light).
    timeline: Timeline,
    /// Its participating media and where they are (empty: a vacuum).
    media: crate::medium::Media,
}

impl Scene {
    /// Builds the BVH and the light distribution. Triangle material indices past the
    /// material list, and light references past the triangle or emission lists, are
    /// errors ([`LoadError::Scene`](crate::LoadError::Scene) naming the mismatch).
    pub fn new(parts: SceneParts) -> Result<Self, crate::LoadError> {
        Self::assemble(parts).map_err(crate::LoadError::Scene)
    }

    fn assemble(parts: SceneParts) -> Result<Self, String> {
        let SceneParts {
            triangles,
            attributes,
            triangle_material,
            materials,
            emission,
            lights,
            camera,
            quality,
        } = parts;
        if triangle_material.len() != triangles.len() {
            return Err(format!(
                "{} triangle materials for {} triangles",
                triangle_material.len(),
                triangles.len()
            ));
        }
        for (what, n) in [
            ("shading normals", attributes.normals.len()),
            ("texture coordinates", attributes.uvs.len()),
            ("second texture coordinates", attributes.uvs1.len()),
            ("tangents", attributes.tangents.len()),
            ("vertex colours", attributes.colors.len()),
        ] {
            if n != 0 && n != triangles.len() {
                return Err(format!(
                    "{n} triangles' {what} for {} triangles",
                    triangles.len()
                ));
            }
        }
        if !attributes.alpha.is_empty() && attributes.alpha.len() != materials.len() {
            return Err(format!(
                "{} materials' alpha for {} materials",
                attributes.alpha.len(),
                materials.len()
            ));
        }
        let perturbations = attributes.perturbations.len();
        if perturbations != 0 && perturbations != materials.len() {
            return Err(format!(
                "{perturbations} materials' normal or bump maps for {} materials",
                materials.len()
            ));
        }
        let normal_maps = attributes.normal_maps.len();
        if normal_maps != 0 && normal_maps != materials.len() {
            return Err(format!(
                "{normal_maps} materials' normal maps for {} materials",
                materials.len()
            ));
        }
        if attributes.normal_maps.iter().any(Option::is_some) && attributes.tangents.is_empty() {
            return Err("normal maps without tangents".into());
        }
        if !attributes.colors.is_empty() && attributes.color_table.is_none() {
            return Err("vertex colours without a coefficient table".into());
        }
        if let Some(m) = triangle_material
            .iter()
            .find(|&&m| m as usize >= materials.len())
        {
            return Err(format!(
                "material {m} does not exist ({} materials)",
                materials.len()
            ));
        }
        for light in &lights {
            if let Light::Triangle {
                triangle,
                emission: e,
                ..
            } = light
                && (*triangle as usize >= triangles.len() || *e as usize >= emission.len())
            {
                return Err(format!(
                    "area light on triangle {triangle} with emission {e} does not exist"
                ));
            }
        }
        let filters_textures =
            !attributes.uvs.is_empty() && materials.iter().any(Material::textured);
        let oriented_materials = materials.iter().any(Material::oriented);
        let bvh = Bvh::build(&triangles, quality);
        let (centre, radius) = bounding_sphere(triangles.iter()).unwrap_or((Vec3::ZERO, 1.0));
        let features = Features {
            dispersion: materials.iter().any(Material::dispersive),
            fluorescence: materials.iter().any(Material::fluorescent),
            transmission: materials.iter().any(Material::transmissive),
            specular: materials.iter().any(Material::specular),
            media: materials.iter().any(Material::interface),
        };
        // Lights are chosen by their power where the scene can see it: the visible
        // range, widened to the fluorescent materials' range (ultraviolet light shows
        // only through them).
        let fluorescent_ranges = materials.iter().filter_map(|m| match m {
            Material::Fluorescent { reradiation, .. } => Some(reradiation.range_nm()),
            _ => None,
        });
        let light_wavelengths = guide::light_wavelengths(
            &materials,
            &lights,
            &{
                lights
                    .iter()
                    .map(|l| light_extent_of(l, &triangles, &attributes, &emission, radius))
                    .collect::<Vec<_>>()
            },
            &emission,
        );
        let lights = choose_lights(
            lights,
            fluorescent_ranges,
            &triangles,
            &attributes,
            &emission,
            radius,
        );
        Ok(Self {
            bvh,
            normals: triangles.iter().map(|&t| triangle_normal(t)).collect(),
            triangles,
            attributes,
            triangle_material,
            materials,
            emission,
            lights,
            camera,
            features,
            centre,
            radius,
            light_wavelengths,
            lit_by_default: false,
            filters_textures,
            oriented_materials,
            light_polarization: Vec::new(),
            timeline: Timeline::default(),
            media: crate::medium::Media::default(),
        })
    }

    /// Fills the scene's volumes: `media` says which material holds which medium inside
    /// and which fills the world. A medium inside a material that cannot hold one (an
    /// opaque surface light cannot enter) is an error naming the material.
    pub fn set_media(&mut self, mut media: crate::medium::Media) -> Result<(), crate::LoadError> {
        for (m, material) in self.materials.iter().enumerate() {
            if media.bounds_medium(m as u32) && !material.can_hold_medium() {
                return Err(crate::LoadError::Scene(format!(
                    "material {m}: a medium needs a boundary light crosses (an interface or a dielectric)"
                )));
            }
        }
        self.features.media = !media.is_empty() || self.materials.iter().any(Material::interface);
        // A dye changes wavelengths as a fluorescent surface does, and the lights are
        // chosen by their power over its range too (a UV lamp lights it).
        let dyes: Vec<(f32, f32)> = media
            .all()
            .iter()
            .filter_map(|m| m.fluorescence().map(crate::medium::Fluorescence::range_nm))
            .collect();
        if !dyes.is_empty() {
            self.features.fluorescence = true;
            let ranges = self
                .materials
                .iter()
                .filter_map(|m| match m {
                    Material::Fluorescent { reradiation, .. } => Some(reradiation.range_nm()),
                    _ => None,
                })
                .chain(dyes);
            self.lights = choose_lights(
                self.lights.all().to_vec(),
                ranges,
                &self.triangles,
                &self.attributes,
                &self.emission,
                self.radius,
            );
            let lights = self.lights.all();
            let extents: Vec<f64> = lights
                .iter()
                .map(|l| {
                    light_extent_of(
                        l,
                        &self.triangles,
                        &self.attributes,
                        &self.emission,
                        self.radius,
                    )
                })
                .collect();
            for medium in media.all_mut() {
                if let Some(dye) = medium.fluorescence_mut() {
                    let g = guide::guide(dye.range_nm(), lights, &extents, &self.emission, |nm| {
                        dye.reemitted_fraction(nm)
                    });
                    dye.set_guide(g);
                }
            }
        }
        self.media = media;
        Ok(())
    }

    /// The scene's participating media.
    pub fn media(&self) -> &crate::medium::Media {
        &self.media
    }

    /// The medium inside the boundary `hit` is on, if it holds one.
    pub fn medium_inside(&self, hit: &Hit) -> Option<u32> {
        self.media
            .inside(self.triangle_material[hit.triangle as usize])
    }

    /// Whether `hit` is on a boundary of a volume, one that paths crossing it enter or
    /// leave (an interface, a dielectric, a glTF transmission that is not thin-walled):
    /// the medium within is [`Scene::medium_inside`], vacuum if none. Where crossing
    /// sets the medium ([`crate::medium::Media::with_sides`]), the surfaces with media on
    /// their sides, whatever their material.
    pub fn bounds_volume(&self, hit: &Hit) -> bool {
        if self.media.crossing_sets() {
            return self.media.sides(self.material_index(hit)).is_some();
        }
        self.material(hit).can_hold_medium()
    }

    /// Where crossing sets the medium ([`crate::medium::Media::with_sides`]), the medium a
    /// path is in after crossing the surface at `hit` towards `direction`: the inside's
    /// against the geometric normal, the outside's along it (Mitsuba's
    /// `SurfaceInteraction::target_medium`); None where volumes nest instead or the
    /// surface has no media on its sides.
    pub fn medium_beyond(&self, hit: &Hit, direction: glam::Vec3) -> Option<Option<u32>> {
        let sides = self.media.sides(self.material_index(hit))?;
        Some(if direction.dot(hit.normal) > 0.0 {
            sides.outside
        } else {
            sides.inside
        })
    }

    /// Whether `hit` is on an interface: a boundary of a medium that light crosses
    /// unchanged (rays pass through it as if it were not there).
    pub fn is_interface(&self, hit: &Hit) -> bool {
        matches!(self.material(hit), Material::Interface)
    }

    /// Gives the scene its timing: schedules by light index, decay laws by material
    /// index (a decay on a material that is not fluorescent is an error).
    pub fn set_timeline(&mut self, timeline: Timeline) -> Result<(), crate::LoadError> {
        for (m, material) in self.materials.iter().enumerate() {
            if timeline.decay(m as u32).is_some() && !material.fluorescent() {
                return Err(crate::LoadError::Scene(format!(
                    "material {m}: a lifetime needs a fluorescent material (what it absorbs and re-emits)"
                )));
            }
        }
        self.timeline = timeline;
        Ok(())
    }

    /// When the lights shine and how long the phosphors glow.
    pub fn timeline(&self) -> &Timeline {
        &self.timeline
    }

    /// The light a hit emitter is (an emissive triangle's), if any.
    pub fn light_of(&self, hit: &Hit) -> Option<u32> {
        self.lights.of_triangle(hit.triangle)
    }

    /// The light from infinity, if any.
    pub fn environment_light(&self) -> Option<u32> {
        self.lights.environment()
    }

    /// The decay law of the material at `hit`, if it is phosphorescent.
    pub fn decay_at(&self, hit: &Hit) -> Option<&prism_sampling::decay::Decay> {
        let m = *self.triangle_material.get(hit.triangle as usize)?;
        self.timeline.decay(m)
    }

    /// Makes light `index`'s emission (a point, spot or directional light's) partly
    /// linearly polarized, as polarized renders see it; unpolarized renders see its
    /// intensity only. An index past the lights is an error.
    pub fn polarize_light(
        &mut self,
        index: usize,
        polarization: crate::polarization::LinearPolarization,
    ) -> Result<(), crate::LoadError> {
        let lights = self.lights.all();
        match lights.get(index) {
            Some(Light::Point { .. } | Light::Spot { .. } | Light::Directional { .. }) => {}
            Some(_) => {
                return Err(crate::LoadError::Scene(format!(
                    "light {index}: only point, spot and directional lights can be polarized"
                )));
            }
            None => {
                return Err(crate::LoadError::Scene(format!(
                    "light {index} does not exist (the scene has {})",
                    lights.len()
                )));
            }
        }
        let count = lights.len();
        self.light_polarization.resize(count, None);
        self.light_polarization[index] = Some(polarization);
        Ok(())
    }

    /// The linear polarization of light `index`'s emission, if it has one.
    pub fn light_polarization(
        &self,
        index: u32,
    ) -> Option<&crate::polarization::LinearPolarization> {
        self.light_polarization.get(index as usize)?.as_ref()
    }

    /// Whether the scene's file had no light of its own (no punctual light, no
    /// environment, no emission brighter than an emissive colour of 1) and the scene is
    /// lit by the default environment ([`DEFAULT_ENVIRONMENT`]) instead.
    pub fn lit_by_default(&self) -> bool {
        self.lit_by_default
    }

    /// The features the scene uses.
    pub fn features(&self) -> Features {
        self.features
    }

    /// For the fluorescent material of `hit`: the wavelengths its re-radiated light is
    /// absorbed at, weighted by the lights' spectral flux there (None for other
    /// materials, or where no light reaches the absorption band): see `guide.rs`.
    pub fn light_wavelengths(
        &self,
        hit: &Hit,
    ) -> Option<&prism_sampling::distribution::PiecewiseConstant1D> {
        let m = self.triangle_material[hit.triangle as usize] as usize;
        self.light_wavelengths.get(m)?.as_ref()
    }

    /// The materials, indexed as triangles refer to them.
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    /// The camera.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The lights.
    pub fn lights(&self) -> &Lights {
        &self.lights
    }

    /// Bytes held by geometry and BVH.
    pub fn memory_bytes(&self) -> usize {
        self.bvh.memory_bytes()
            + std::mem::size_of_val(self.triangles.as_slice())
            + std::mem::size_of_val(self.triangle_material.as_slice())
    }

    /// The emission spectra of the emissive triangles.
    pub fn emission_spectra(&self) -> &[SceneSpectrum] {
        &self.emission
    }

    /// The radius of the scene's bounding sphere.
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// The closest hit along `ray` on a surface the ray does not pass through (alpha
    /// coverage: see [`Alpha`]).
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        if self.attributes.alpha.is_empty() {
            self.closest(ray)
        } else {
            self.intersect_through_alpha(ray)
        }
    }

    /// [`Scene::intersect`] in a scene with cut-out or transparent surfaces: the closest
    /// hit, then the next beyond it wherever the ray passes through, up to
    /// [`MAX_ALPHA_CROSSINGS`] surfaces (a ray through more is taken as blocked). Opaque
    /// scenes never come here.
    #[inline(never)]
    fn intersect_through_alpha(&self, ray: &Ray) -> Option<Hit> {
        let mut current = *ray;
        let mut travelled = 0.0f32;
        for _ in 0..MAX_ALPHA_CROSSINGS {
            let mut hit = self.closest(&current)?;
            let material = self.triangle_material[hit.triangle as usize] as usize;
            let passes = match self.attributes.alpha.get(material) {
                Some(Some(alpha)) => {
                    let u = crate::materials::blend_number(
                        current.origin,
                        current.direction,
                        hit.triangle,
                    );
                    !alpha.opaque(&hit.tex, hit.color.w, u)
                }
                _ => false,
            };
            if !passes {
                hit.t += travelled;
                return Some(hit);
            }
            travelled += hit.t;
            let next = hit.spawn(current.direction);
            current = Ray::new(next.origin, current.direction, current.t_max - hit.t);
            if current.t_max <= 0.0 {
                return None;
            }
        }
        let mut hit = self.closest(&current)?;
        hit.t += travelled;
        Some(hit)
    }

    /// The closest hit along `ray`, whatever its alpha.
    fn closest(&self, ray: &Ray) -> Option<Hit> {
        let hit = self.bvh.intersect(ray)?;
        // The BVH's copy of the vertices: the same values, already in cache.
        let v = hit.vertices;
        let b = hit.hit.barycentric;
        let p = b[0] * v[0] + b[1] * v[1] + b[2] * v[2];
        let normal = self.normals[hit.triangle];
        let shading_normal = match self.attributes.normals.get(hit.triangle) {
            Some(n) => {
                let s = unit_or_zero(b[0] * n[0] + b[1] * n[1] + b[2] * n[2]);
                // Vertex normals that cancel, or face away from the surface, are not a
                // shading frame prism can use: the face's own normal is.
                let d = s.dot(normal);
                if d > 0.0 {
                    s
                } else if d < 0.0 {
                    -s
                } else {
                    normal
                }
            }
            None => normal,
        };
        let tex = match self.attributes.uvs.get(hit.triangle) {
            Some(&first) => {
                let second = self.attributes.uvs1.get(hit.triangle).copied();
                TexCoords::interpolate([first, second.unwrap_or(first)], b)
            }
            None => TexCoords::default(),
        };
        let shading_normal = if self.attributes.normal_maps.is_empty() {
            shading_normal
        } else {
            self.normal_mapped(hit.triangle, b, shading_normal, normal, &tex)
        };
        let shading_normal = if self.attributes.perturbations.is_empty() {
            shading_normal
        } else {
            self.perturbed_normal(hit.triangle, shading_normal, normal, &tex, ray.direction)
        };
        let color = self
            .attributes
            .colors
            .get(hit.triangle)
            .map_or(glam::Vec4::ONE, |c| b[0] * c[0] + b[1] * c[1] + b[2] * c[2]);
        Some(Hit {
            p,
            error: triangle_point_error(v, b),
            normal,
            shading_normal,
            tex,
            color,
            t: hit.hit.t,
            triangle: hit.triangle as u32,
        })
    }

    /// The shading normal `n` of triangle `triangle` at barycentrics `b` tilted by its
    /// material's normal map, if it has one; `n` where the map would tilt it to or past the
    /// surface (behind the geometric normal `geometric`), or has no frame. Out of line:
    /// inlined, it made every path of a scene without normal maps take more instructions.
    #[inline(never)]
    fn normal_mapped(
        &self,
        triangle: usize,
        b: [f32; 3],
        n: Vec3,
        geometric: Vec3,
        tex: &TexCoords,
    ) -> Vec3 {
        let material = self.triangle_material[triangle] as usize;
        let (Some(Some(map)), Some(t)) = (
            self.attributes.normal_maps.get(material),
            self.attributes.tangents.get(triangle),
        ) else {
            return n;
        };
        let tangent = b[0] * t[0] + b[1] * t[1] + b[2] * t[2];
        map.perturb(n, tangent, *tex)
            .filter(|p| p.dot(geometric) > 0.0)
            .unwrap_or(n)
    }

    /// Whether anything blocks `ray` (cut-out and transparent surfaces as
    /// [`Scene::intersect`] sees them).
    pub fn occluded(&self, ray: &Ray) -> bool {
        if self.attributes.alpha.is_empty() {
            self.bvh.occluded(ray)
        } else {
            self.intersect_through_alpha(ray).is_some()
        }
    }

    /// The index of the material of a hit (as `SceneParts::materials` and the media's
    /// `inside` list count them).
    pub fn material_index(&self, hit: &Hit) -> u32 {
        self.triangle_material[hit.triangle as usize]
    }

    /// The material of a hit.
    pub fn material(&self, hit: &Hit) -> &Material {
        &self.materials[self.triangle_material[hit.triangle as usize] as usize]
    }

    /// The BSDF at `hit` for paths carrying `mode`: its material's, with the base colour
    /// multiplied by the hit's vertex colour where the scene has vertex colours.
    pub fn bsdf<const N: usize>(
        &self,
        hit: &Hit,
        wavelengths: &SampledWavelengths<N>,
        mode: crate::bsdf::TransportMode,
    ) -> Bsdf<'_, N> {
        let tint = self.tint_table(hit).map(|table| {
            let t = hit.triangle as usize;
            match (
                self.attributes.colors_blend_spectra,
                self.attributes.colors.get(t),
            ) {
                (true, Some(corners)) => corner_colors::blended_tint(
                    &self.triangles[t],
                    corners,
                    hit.p,
                    table,
                    wavelengths,
                ),
                _ => crate::textures::reflectance_lanes(
                    hit.color.truncate().to_array(),
                    table,
                    wavelengths,
                ),
            }
        });
        let material = self.material(hit);
        if !self.attributes.perturbations.is_empty() && self.perturbation(hit).is_some() {
            return self.bsdf_perturbed(hit, material.bsdf_at(&hit.tex, wavelengths, mode, tint));
        }
        if self.oriented_materials && material.oriented() {
            return self.bsdf_in_tangent_frame(hit, material, wavelengths, mode, tint);
        }
        material.bsdf_at(&hit.tex, wavelengths, mode, tint)
    }

    /// The table that upsamples `hit`'s vertex colour, where it tints the base colour (a
    /// scene with vertex colours, a colour other than white).
    fn tint_table(&self, hit: &Hit) -> Option<&prism_upsample::CoefficientTable> {
        self.attributes
            .color_table
            .as_deref()
            .filter(|_| hit.color.truncate() != Vec3::ONE)
    }

    /// [`Scene::bsdf`], with a path's cache: a Lambertian material of constant reflectance
    /// (no texture, no vertex colour) is evaluated once per set of wavelengths. The same
    /// BSDF, bit for bit.
    pub fn bsdf_cached<const N: usize>(
        &self,
        hit: &Hit,
        wavelengths: &SampledWavelengths<N>,
        mode: crate::bsdf::TransportMode,
        cache: &mut EmissionCache<N>,
    ) -> Bsdf<'_, N> {
        let index = self.triangle_material[hit.triangle as usize];
        if let Material::Diffuse { reflectance } = &self.materials[index as usize]
            && !reflectance.varies()
            && self.tint_table(hit).is_none()
            && (self.attributes.perturbations.is_empty() || self.perturbation(hit).is_none())
            && let Some(r) = cache.reflectance(index, reflectance, wavelengths)
        {
            return Bsdf::Diffuse(crate::bsdf::Diffuse::new(r));
        }
        self.bsdf(hit, wavelengths, mode)
    }

    /// [`Scene::bsdf`] for a material read in the surface's tangent frame. Out of line,
    /// so that scenes without such materials keep their code as it was.
    #[inline(never)]
    fn bsdf_in_tangent_frame<'s, const N: usize>(
        &self,
        hit: &Hit,
        material: &'s Material,
        wavelengths: &SampledWavelengths<N>,
        mode: crate::bsdf::TransportMode,
        tint: Option<SampledSpectrum<N>>,
    ) -> Bsdf<'s, N> {
        let mut tangent = self.tangent_at(hit);
        // Mitsuba's principled BSDFs lie along Mitsuba's shading frame, whose tangent is
        // dp/du (`SurfaceInteraction::initialize_sh_frame`), where the mesh gives none.
        if tangent == glam::Vec4::ZERO
            && matches!(
                material,
                Material::Principled(_) | Material::PrincipledThin(_)
            )
        {
            let (dp_du, _) = self.surface_derivatives(hit.triangle as usize, hit.normal);
            tangent = dp_du.extend(1.0);
        }
        let frame = SurfaceFrame::new(hit.shading_normal, tangent);
        material.bsdf_oriented(&hit.tex, wavelengths, mode, tint, Some(&frame))
    }

    /// The interpolated tangent (xyz, glTF's bitangent sign in w) at a hit; zero where
    /// the mesh has none.
    fn tangent_at(&self, hit: &Hit) -> glam::Vec4 {
        let t = hit.triangle as usize;
        let (Some(tangents), Some(v)) = (self.attributes.tangents.get(t), self.triangles.get(t))
        else {
            return glam::Vec4::ZERO;
        };
        // Barycentrics of the hit point from the sub-triangles' areas.
        let area = |a: Vec3, b: Vec3, c: Vec3| (b - a).cross(c - a).length();
        let total = area(v[0], v[1], v[2]);
        if total.is_nan() || total <= 0.0 {
            return tangents[0];
        }
        let b1 = area(v[0], hit.p, v[2]) / total;
        let b2 = area(v[0], v[1], hit.p) / total;
        let b0 = (1.0 - b1 - b2).max(0.0);
        b0 * tangents[0] + b1 * tangents[1] + b2 * tangents[2]
    }

    /// Whether the surface at `hit` reflects the light it receives alike towards every
    /// direction on a side, whichever ray found it: a Lambertian material whose reflectance
    /// is one spectrum (a texture's filtered lookup depends on the ray's footprint). What a
    /// path estimates beyond such a point serves every other point that sees it (path reuse).
    pub fn reflects_alike(&self, hit: &Hit) -> bool {
        matches!(
            self.material(hit),
            Material::Diffuse { reflectance } if !reflectance.varies()
                && (self.attributes.perturbations.is_empty() || self.perturbation(hit).is_none())
        )
    }

    /// Whether some surface is cut out or transparent (alpha coverage): a ray then passes
    /// through it by chance, and a point behind it is not simply seen or hidden.
    pub fn has_cutouts(&self) -> bool {
        !self.attributes.alpha.is_empty()
    }

    /// Whether any material reads a texture that footprints filter (base colour or
    /// metallic-roughness): only then do paths compute footprints.
    pub fn filters_textures(&self) -> bool {
        self.filters_textures
    }

    /// Sets the footprints of `hit.tex` for a footprint `width` wide (world units, across
    /// the ray `direction` at the hit): the width over the surface's cosine (a glancing
    /// footprint spreads), in each set's texture coordinates by the triangle's ratio of
    /// texture to world area (*Ray Tracing Gems* ch. 20, ray cones). Triangles without
    /// texture coordinates keep `-inf`.
    pub fn set_footprint(&self, hit: &mut Hit, direction: Vec3, width: f32) {
        let t = hit.triangle as usize;
        let (Some(&first), Some(v)) = (self.attributes.uvs.get(t), self.triangles.get(t)) else {
            return;
        };
        let world_area = (v[1] - v[0]).cross(v[2] - v[0]).length();
        let across = width / hit.normal.dot(direction).abs().max(0.05);
        let lod = |uv: [Vec2; 3]| {
            let uv_area = (uv[1] - uv[0]).perp_dot(uv[2] - uv[0]).abs();
            let lod = (across * (uv_area / world_area).sqrt()).log2();
            if lod.is_nan() { f32::NEG_INFINITY } else { lod }
        };
        let first = lod(first);
        let second = self.attributes.uvs1.get(t).map_or(first, |&uv| lod(uv));
        hit.tex.lod = [first, second];
    }

    /// Radiance emitted by the hit surface towards `wo` (unit, pointing away from it).
    /// Emission spectra come from `cache`, which holds them at the path's current
    /// wavelengths (one cache per path; see [`EmissionCache`]).
    pub fn emitted<const N: usize>(
        &self,
        hit: &Hit,
        wo: Vec3,
        wavelengths: &SampledWavelengths<N>,
        cache: &mut EmissionCache<N>,
    ) -> SampledSpectrum<N> {
        let Some(l) = self.lights.of_triangle(hit.triangle) else {
            return SampledSpectrum::splat(0.0);
        };
        match &self.lights.lights[l as usize] {
            Light::Triangle {
                emission,
                two_sided,
                ..
            } if *two_sided || hit.normal.dot(wo) > 0.0 => {
                cache.get(&self.emission, *emission, wavelengths, &hit.tex)
            }
            _ => SampledSpectrum::splat(0.0),
        }
    }

    /// The density (solid angle, times the choice probability) with which light sampling
    /// from `from`, with the path at `wavelengths`, would have produced the direction to
    /// `hit`, an emitter. `cache` is the path's, as in [`Scene::sample_light`].
    pub fn light_pdf<const N: usize>(
        &self,
        from: Vec3,
        hit: &Hit,
        wavelengths: &SampledWavelengths<N>,
        cache: &mut EmissionCache<N>,
    ) -> f32 {
        let Some(l) = self.lights.of_triangle(hit.triangle) else {
            return 0.0;
        };
        let pmf = self.lights.pmf_at(l, wavelengths, cache);
        let shape = self.lights.shape(l);
        let pdf = match crate::lights::solid_angle_sampled(from, shape) {
            Some(omega) => pmf / omega,
            None => {
                let to = hit.p - from;
                let d2 = to.length_squared();
                let cos = hit.normal.dot(to).abs() / d2.sqrt();
                pmf * d2 / (cos * shape.area)
            }
        };
        if pdf.is_finite() { pdf } else { 0.0 }
    }

    /// Radiance arriving along unit direction `direction` from a ray that leaves the
    /// scene, and the density with which light sampling would have chosen that direction
    /// (`cache` as in [`Scene::light_pdf`]).
    pub fn escaped<const N: usize>(
        &self,
        direction: Vec3,
        wavelengths: &SampledWavelengths<N>,
        cache: &mut EmissionCache<N>,
    ) -> Option<(SampledSpectrum<N>, f32)> {
        let l = self.lights.environment()?;
        match &self.lights.lights[l as usize] {
            Light::Environment { radiance } => Some((
                radiance.at(wavelengths),
                self.lights.pmf_at(l, wavelengths, cache) / (4.0 * std::f32::consts::PI),
            )),
            Light::EnvironmentMap { map } => {
                let white = cache.environment_white(map, wavelengths);
                let (radiance, pdf) = map.radiance_and_pdf(direction, wavelengths, &white);
                Some((radiance, self.lights.pmf_at(l, wavelengths, cache) * pdf))
            }
            _ => None,
        }
    }

    /// Chooses a light with `u_choice` in proportion to its power and samples a ray
    /// leaving it (the start of a light path): a point with `u_position` and a direction
    /// with `u_direction`, cosine-weighted from an emitting triangle, uniform from a point
    /// light, within the cone of a spot; for light from infinity (directional and
    /// environment lights, the environment's direction sampled as next-event estimation
    /// samples it) a parallel ray through a disk covering the scene, from outside it. With
    /// an `aim` ([`Scene::aim`]), the disk covers the aim's sphere only, and lights are
    /// chosen by the power that reaches it.
    pub fn sample_emission<const N: usize>(
        &self,
        u_choice: f32,
        u_position: Vec2,
        u_direction: Vec2,
        wavelengths: &SampledWavelengths<N>,
        aim: Option<&CausticTarget>,
    ) -> Option<EmissionSample<N>> {
        self.lights.sample_emission(
            u_choice,
            u_position,
            u_direction,
            wavelengths,
            &self.emission,
            (self.centre, self.radius),
            aim,
        )
    }

    /// Light paths that count only light reaching the triangles whose material `keep`s
    /// first aimed at them: their bounding sphere ([`Scene::bounding_sphere_where`]), and
    /// the lights' choice by the power that can reach it. None when `keep` keeps nothing.
    pub fn aim(&self, keep: impl Fn(&Material) -> bool) -> Option<CausticTarget> {
        let sphere = self.bounding_sphere_where(keep)?;
        Some(self.lights.aimed(sphere, self.radius))
    }

    /// A bounding sphere (centre, radius) of the triangles whose material `keep`s (None
    /// when it keeps none): centred on their bounding box, as small as that centre allows
    /// (a sphere's own, where the box's corners would give sqrt(3) times its radius).
    pub fn bounding_sphere_where(&self, keep: impl Fn(&Material) -> bool) -> Option<(Vec3, f32)> {
        let kept: Vec<bool> = self.materials.iter().map(keep).collect();
        let triangles = || {
            self.triangles
                .iter()
                .zip(&self.triangle_material)
                .filter(|(_, m)| kept.get(**m as usize).copied().unwrap_or(false))
                .map(|(t, _)| t)
        };
        let (centre, _) = bounding_sphere(triangles())?;
        let radius = triangles()
            .flatten()
            .filter(|v| v.is_finite())
            .map(|v| v.distance(centre))
            .fold(1e-3f32, f32::max);
        // A hair more, so that rounding never leaves a vertex outside.
        Some((centre, radius * (1.0 + 1e-5)))
    }

    /// Chooses a light and samples a direction to it from `hit`, both with `u` (`u.x`
    /// chooses, and what is left of it places the point). The light's emission comes
    /// from `cache`, as in [`Scene::emitted`].
    pub fn sample_light<const N: usize>(
        &self,
        hit: &Hit,
        u: Vec2,
        wavelengths: &SampledWavelengths<N>,
        cache: &mut EmissionCache<N>,
    ) -> Option<LightSample<N>> {
        self.lights
            .sample(hit.p, u, wavelengths, &self.emission, cache)
    }

    /// [`Scene::sample_light`] from a point `p` that is on no surface (in a medium).
    pub fn sample_light_at<const N: usize>(
        &self,
        p: Vec3,
        u: Vec2,
        wavelengths: &SampledWavelengths<N>,
        cache: &mut EmissionCache<N>,
    ) -> Option<LightSample<N>> {
        self.lights.sample(p, u, wavelengths, &self.emission, cache)
    }
}

/// A light's extent (the solid angle or area that scales its power) times how much of it
/// its texture covers.
fn light_extent_of(
    light: &Light,
    triangles: &[[Vec3; 3]],
    attributes: &VertexAttributes,
    emission: &[SceneSpectrum],
    radius: f32,
) -> f64 {
    crate::lights::light_extent(light, triangles, radius)
        * crate::lights::texture_coverage(light, |set| attributes.uvs_of_set(set), emission)
}

/// The lights, chosen by their power over the visible range widened to every range in
/// `fluorescent` (the fluorescent materials' and dyes': ultraviolet light shows only
/// through them).
fn choose_lights(
    lights: Vec<Light>,
    fluorescent: impl Iterator<Item = (f32, f32)>,
    triangles: &[[Vec3; 3]],
    attributes: &VertexAttributes,
    emission: &[SceneSpectrum],
    radius: f32,
) -> Lights {
    let power_range = fluorescent.fold((360.0f64, 830.0f64), |(lo, hi), (a, b)| {
        (lo.min(f64::from(a)), hi.max(f64::from(b)))
    });
    let extent: Vec<f64> = lights
        .iter()
        .map(|l| light_extent_of(l, triangles, attributes, emission, radius))
        .collect();
    let power: Vec<f64> = lights
        .iter()
        .zip(&extent)
        .map(|(l, x)| {
            x * crate::lights::light_spectrum(l, emission).mean_over(power_range.0, power_range.1)
        })
        .collect();
    Lights::new(lights, &power, &extent, emission, triangles, |set| {
        attributes.uvs_of_set(set)
    })
}

/// The sphere around the bounding box of `triangles`' finite vertices (its radius at least
/// 1e-3), None when there are none.
fn bounding_sphere<'t>(triangles: impl Iterator<Item = &'t [Vec3; 3]>) -> Option<(Vec3, f32)> {
    let (lo, hi) = triangles
        .flatten()
        .filter(|v| v.is_finite())
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(*v), hi.max(*v))
        });
    (lo.x <= hi.x).then(|| (0.5 * (lo + hi), (0.5 * (hi - lo)).length().max(1e-3)))
}
