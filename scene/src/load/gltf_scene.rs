//! A render-ready scene from a loaded glTF file.

use std::sync::Arc;

use prism_spectrum::optics::Cauchy;

use crate::bsdf::CoatingAlbedo;
use crate::lights::{DEFAULT_ENVIRONMENT, Light};
use crate::load::{LightDesc, LoadError, LoadedGeometry, MaterialDesc};
use crate::materials::{Alpha, AlphaMode, Layers, Material, TransmissionDesc};
use crate::textures::SceneSpectrum;
use crate::world::{Scene, SceneOptions, SceneParts};

/// The material a glTF description becomes.
///
/// - transmissive (`KHR_materials_transmission` > 0): clear thick glass (the whole surface,
///   a white base, a volume) is a dielectric of the material's index and roughness;
///   anything else is the metallic-roughness BSDF in part glass ([`TransmissionDesc`]:
///   the share, thin walls, the base colour tinting what crosses);
/// - metallic 0 and roughness 1: Lambertian. This is what exporters write for a matte
///   surface and what the canonical Cornell box means by its walls (Mitsuba's reference
///   scene uses diffuse BSDFs there); glTF's rough coating would add a few percent of
///   white, desaturating reflection that the scene's author did not ask for;
/// - otherwise the glTF metallic-roughness BSDF.
///
/// A `PRISM_spectral` surface replaces all of this.
fn material(desc: &MaterialDesc, coatings: &mut Vec<(f32, Arc<CoatingAlbedo>)>) -> Material {
    if let Some(surface) = desc.spectral.as_ref().and_then(|s| s.surface.clone()) {
        return surface;
    }
    let base = match &desc.base_color_texture {
        Some(texture) => texture.clone(),
        None => SceneSpectrum::Rgb(Arc::new(desc.base_color.clone())),
    };
    let mut layers = desc.layers.clone();
    if desc.transmission > 0.0 {
        // KHR_materials_dispersion: V_d = 20 / dispersion, Cauchy's law through n_d.
        let abbe = 20.0 / f64::from(desc.dispersion);
        let ior = match Cauchy::from_abbe(f64::from(desc.ior), abbe) {
            Ok(cauchy) if desc.dispersion > 0.0 => SceneSpectrum::Cauchy(cauchy),
            _ => SceneSpectrum::Constant(f64::from(desc.ior)),
        };
        if desc.transmission >= 1.0
            && desc.transmission_texture.is_none()
            && !desc.thin_walled
            && desc.base_white
        {
            return Material::Dielectric {
                ior,
                roughness: desc.roughness,
                absorption: desc.absorption.clone(),
            };
        }
        let glass = TransmissionDesc {
            factor: desc.transmission,
            texture: desc.transmission_texture.clone(),
            ior,
            thin: desc.thin_walled,
            absorption: if desc.thin_walled {
                None
            } else {
                desc.absorption.clone()
            },
        };
        // Layers on glass are not rendered (loading warned): only the glass share.
        layers = Some(Layers {
            transmission: Some(glass),
            ..Layers::default()
        });
    }
    let texture = desc.metallic_roughness_texture.clone();
    if desc.metallic == 0.0
        && desc.roughness == 1.0
        && texture.is_none()
        && desc.iridescence.is_none()
        && layers.is_none()
    {
        return Material::Diffuse { reflectance: base };
    }
    Material::MetallicRoughness {
        base,
        metallic: desc.metallic,
        roughness: desc.roughness,
        texture,
        coating: coating_for(desc.ior, coatings),
        iridescence: desc.iridescence.clone().map(Arc::new),
        layers: layers.map(Arc::new),
    }
}

/// One coating table per distinct index (they take milliseconds to build).
fn coating_for(ior: f32, coatings: &mut Vec<(f32, Arc<CoatingAlbedo>)>) -> Arc<CoatingAlbedo> {
    if let Some((_, c)) = coatings.iter().find(|(i, _)| *i == ior) {
        return c.clone();
    }
    let c = Arc::new(CoatingAlbedo::new(ior));
    coatings.push((ior, c.clone()));
    c
}

impl Scene {
    /// The scene of a loaded glTF file. It takes the loaded geometry whole, so that the
    /// triangle and attribute lists move into the scene rather than being copied: a
    /// four-million-triangle scene held them twice at its memory peak.
    pub fn from_loaded(loaded: LoadedGeometry, options: &SceneOptions) -> Result<Self, LoadError> {
        let mut coatings = Vec::new();
        let mut materials: Vec<Material> = loaded
            .materials
            .iter()
            .map(|m| material(m, &mut coatings))
            .collect();
        // glTF's default material: white, fully metallic, fully rough. Only scenes with a
        // mesh that names no material get it (and pay for its coating table, ~40 ms).
        let default_material = materials.len() as u32;
        if loaded.instances.iter().any(|i| i.material.is_none()) {
            materials.push(Material::MetallicRoughness {
                base: SceneSpectrum::Constant(1.0),
                metallic: 1.0,
                roughness: 1.0,
                texture: None,
                coating: coating_for(1.5, &mut coatings),
                iridescence: None,
                layers: None,
            });
        }
        let mut triangle_material = vec![default_material; loaded.triangles.len()];
        for instance in &loaded.instances {
            let m = instance.material.map_or(default_material, |m| m as u32);
            triangle_material[instance.first..instance.first + instance.count].fill(m);
        }
        let SceneLights {
            emission,
            mut lights,
            polarized,
            mut schedules,
        } = SceneLights::of(&loaded);
        let environment = options
            .environment
            .as_ref()
            .or(loaded.spectral.environment.as_ref());
        if let Some(environment) = environment {
            // The file's schedule is its environment's; one given in its place has none.
            if options.environment.is_none()
                && let Some(on) = &loaded.spectral.environment_on
            {
                schedules.push((lights.len(), Arc::new(on.clone())));
            }
            lights.push(environment.light());
        }
        let decays: Vec<_> = loaded
            .materials
            .iter()
            .enumerate()
            .filter_map(|(m, desc)| {
                let decay = desc.spectral.as_ref()?.decay.clone()?;
                Some((m, Arc::new(decay)))
            })
            .collect();
        let lit_by_default = lit_by_default(&loaded, &lights, &triangle_material);
        if lit_by_default {
            lights.push(Light::Environment {
                radiance: crate::lights::grey_environment(DEFAULT_ENVIRONMENT),
            });
        }
        let normal_maps = normal_maps(&loaded, materials.len());
        let perturbations = if loaded.materials.iter().any(|m| m.perturbation.is_some()) {
            let mut list: Vec<_> = loaded
                .materials
                .iter()
                .map(|m| m.perturbation.clone())
                .collect();
            list.resize(materials.len(), None);
            list
        } else {
            Vec::new()
        };
        let alpha = alpha_coverage(&loaded, &triangle_material, materials.len());
        let camera = loaded.camera(options.camera.as_deref())?;
        let media = media_of(&loaded, &materials)?;
        Scene::new(SceneParts {
            triangles: loaded.triangles,
            attributes: crate::world::VertexAttributes {
                normals: loaded.normals,
                uvs: loaded.uvs,
                uvs1: loaded.uvs1,
                tangents: loaded.tangents,
                normal_maps,
                alpha,
                perturbations,
                colors: loaded.colors,
                color_table: loaded.color_table,
                colors_blend_spectra: loaded.colors_blend_spectra,
            },
            triangle_material,
            materials,
            emission,
            lights,
            camera,
            quality: options.quality,
        })
        .and_then(|mut scene| {
            scene.lit_by_default = lit_by_default;
            for (index, polarization) in polarized {
                scene.polarize_light(index, polarization)?;
            }
            let timeline =
                crate::world::Timeline::new(scene.lights().all().len(), schedules, decays);
            if timeline.is_timed() {
                scene.set_timeline(timeline)?;
            }
            if let Some(media) = media {
                scene.set_media(media)?;
            }
            Ok(scene)
        })
    }
}

/// The media of a loaded file: each material's medium inside and the root's fog (None:
/// the file has none). A medium on a material that cannot hold one is an error naming
/// the material.
fn media_of(
    loaded: &LoadedGeometry,
    materials: &[Material],
) -> Result<Option<crate::medium::Media>, crate::LoadError> {
    if let Some(media) = &loaded.media {
        return Ok((!media.is_empty()).then(|| media.clone()));
    }
    let mut media = Vec::new();
    let mut inside = vec![None; loaded.materials.len()];
    for (m, desc) in loaded.materials.iter().enumerate() {
        let medium = desc
            .spectral
            .as_ref()
            .and_then(|s| s.medium.clone())
            .or_else(|| desc.medium.clone());
        if let Some(medium) = medium {
            if !materials.get(m).is_some_and(Material::can_hold_medium) {
                return Err(crate::LoadError::Spectral(format!(
                    "material {}: medium: needs a boundary light crosses (an interface, a dielectric, glTF glass that is not thin-walled, or a diffusely transmitting skin)",
                    desc.name
                )));
            }
            inside[m] = Some(media.len() as u32);
            media.push(medium);
        }
    }
    let world = loaded.spectral.medium.clone().map(|medium| {
        media.push(medium);
        (media.len() - 1) as u32
    });
    if media.is_empty() {
        return Ok(None);
    }
    crate::medium::Media::new(media, inside, world)
        .map(Some)
        .map_err(crate::LoadError::Scene)
}

/// The lights of a loaded file's descriptions (an emissive instance's triangles each a
/// light), with the polarizations and schedules of those that have them, by scene light
/// index.
struct SceneLights {
    /// The emission spectra the triangle lights share, one per emissive material.
    emission: Vec<SceneSpectrum>,
    lights: Vec<Light>,
    polarized: Vec<(usize, crate::polarization::LinearPolarization)>,
    schedules: Vec<(usize, Arc<crate::world::Schedule>)>,
}

impl SceneLights {
    fn of(loaded: &LoadedGeometry) -> Self {
        let mut emission = Vec::new();
        let mut emission_of_material = vec![None; loaded.materials.len()];
        let mut lights = Vec::new();
        // Scene light indices of the descriptions' polarizations and schedules.
        let mut polarized = Vec::new();
        let mut schedules = Vec::new();
        for (d, desc) in loaded.lights.iter().enumerate() {
            if let Some((_, p)) = loaded.light_polarization.iter().find(|(i, _)| *i == d) {
                polarized.push((lights.len(), *p));
            }
            if let Some((_, s)) = loaded.light_schedules.iter().find(|(i, _)| *i == d) {
                schedules.push((lights.len(), Arc::new(s.clone())));
            }
            match desc {
                LightDesc::Area {
                    instance,
                    double_sided,
                } => {
                    let instance = &loaded.instances[*instance];
                    let Some(m) = instance.material else { continue };
                    let desc = &loaded.materials[m];
                    let Some(spectrum) = desc.emission_spectrum() else {
                        continue;
                    };
                    let e = *emission_of_material[m].get_or_insert_with(|| {
                        emission.push(spectrum);
                        emission.len() as u32 - 1
                    });
                    let on = desc
                        .spectral
                        .as_ref()
                        .and_then(|s| s.on.clone())
                        .map(Arc::new);
                    for t in instance.first..instance.first + instance.count {
                        if let Some(on) = &on {
                            schedules.push((lights.len(), on.clone()));
                        }
                        lights.push(Light::Triangle {
                            triangle: t as u32,
                            emission: e,
                            two_sided: *double_sided,
                        });
                    }
                }
                LightDesc::Point {
                    position,
                    spectrum,
                    scale,
                } => lights.push(Light::Point {
                    position: *position,
                    intensity: scaled(spectrum, *scale),
                }),
                LightDesc::Spot {
                    position,
                    direction,
                    inner,
                    outer,
                    spectrum,
                    scale,
                    falloff,
                    texture,
                } => lights.push(Light::Spot {
                    position: *position,
                    direction: *direction,
                    cos_inner: inner.cos(),
                    cos_outer: outer.cos(),
                    intensity: scaled(spectrum, *scale),
                    falloff: *falloff,
                    texture: texture.clone(),
                }),
                LightDesc::Directional {
                    direction,
                    spectrum,
                    scale,
                } => lights.push(Light::Directional {
                    direction: *direction,
                    irradiance: scaled(spectrum, *scale),
                }),
            }
        }
        Self {
            emission,
            lights,
            polarized,
            schedules,
        }
    }
}

/// Whether the scene is to be lit as a glTF viewer lights a model: no light among `lights`
/// is meant to light it.
fn lit_by_default(loaded: &LoadedGeometry, lights: &[Light], triangle_material: &[u32]) -> bool {
    // A file with no light meant to light it (most real assets: viewers light them
    // with an environment) is lit as a glTF viewer would, by a neutral environment:
    // D65 of emissive-colour value 1. Emission no brighter than an emissive colour of
    // 1 (glowing screens and indicators, unlit surfaces) is not such a light; a
    // spectral emission or one scaled by KHR_materials_emissive_strength above 1 is.
    let lamp = |m: &MaterialDesc| {
        m.emission_peak > 1.0 || m.spectral.as_ref().is_some_and(|s| s.emission.is_some())
    };
    lights.iter().all(|l| match l {
        Light::Triangle { triangle, .. } => {
            let m = triangle_material[*triangle as usize] as usize;
            !loaded.materials.get(m).is_some_and(lamp)
        }
        _ => false,
    })
}

/// The normal map of each of `materials` materials (the default material's none).
fn normal_maps(
    loaded: &LoadedGeometry,
    materials: usize,
) -> Vec<Option<Arc<crate::materials::NormalMap>>> {
    // Normal maps per material, the default material's none; no list when no
    // material has one (hits then never look).
    if loaded.materials.iter().any(|m| m.normal_texture.is_some()) {
        let mut maps: Vec<_> = loaded
            .materials
            .iter()
            .map(|m| m.normal_texture.clone())
            .collect();
        maps.resize(materials, None);
        maps
    } else {
        Vec::new()
    }
}

/// Per material, its alpha coverage where it can let rays through: a texture's alpha,
/// vertex alpha below 1 on one of its triangles, or a factor below 1 (under MASK, below
/// the cutoff). A file that marks everything BLEND without any transparency (exporters
/// do) stays on the opaque scenes' path. Empty when no material lets rays through.
fn alpha_coverage(
    loaded: &LoadedGeometry,
    triangle_material: &[u32],
    materials: usize,
) -> Vec<Option<Arc<Alpha>>> {
    let mut vertex_alpha = vec![false; materials];
    for (t, colors) in loaded.colors.iter().enumerate() {
        if colors.iter().any(|c| c.w < 1.0) {
            vertex_alpha[triangle_material[t] as usize] = true;
        }
    }
    let alpha: Vec<Option<Arc<Alpha>>> = (0..materials)
        .map(|m| {
            let a = loaded.materials.get(m)?.alpha.as_ref()?;
            // Without a texture or vertex alpha the factor decides everywhere alike.
            let uniformly_opaque = match a.mode {
                AlphaMode::Mask { cutoff } => a.factor >= cutoff,
                AlphaMode::Blend => a.factor >= 1.0,
            };
            let transparent =
                a.texture.is_some() || a.opacity.is_some() || vertex_alpha[m] || !uniformly_opaque;
            transparent.then(|| Arc::new(a.clone()))
        })
        .collect();
    if alpha.iter().all(Option::is_none) {
        Vec::new()
    } else {
        alpha
    }
}

fn scaled(spectrum: &SceneSpectrum, scale: f64) -> SceneSpectrum {
    SceneSpectrum::Scaled(Arc::new(spectrum.clone()), scale)
}
