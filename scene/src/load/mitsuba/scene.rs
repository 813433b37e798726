//! A Mitsuba scene as prism's loaded geometry: the tree's shapes, BSDFs, emitters and
//! sensor turned into triangles, materials, lights and a camera, which
//! [`crate::world::Scene::from_loaded`] makes a render-ready scene as it does glTF's.
//!
//! Each shape is one instance; shapes that share a BSDF (by reference) share a material,
//! and a shape with an area emitter gets a material of its own that emits. Plugins and
//! parameters not read yet are errors naming them (file:line), never a silent default.

use std::collections::HashMap;
use std::sync::Arc;

use super::bsdfs::key;
use super::emitters::{emission, emitter, only};
use super::files::Files;
use super::instances::{Groups, check_group};
use super::media::{MediaBuilder, Reading, nested, null_boundary};
use super::mesh_attribute::{corner_colors, diffuse_reflectance};
use super::parse::error;
use super::sensors::{Film, camera, number};
use super::shape_mesh::ShapeMesh;
use super::shapes::{feature, shape_mesh};
use super::spectra::Kind;
use super::textures::Context;
use super::tree::{Class, Object, Value};
use super::unread::unread_parameters;
use super::{ParseOptions, parse};
use crate::LoadError;
use crate::load::{LightDesc, LoadOptions, LoadedGeometry, MaterialDesc, MeshInstance, Upsampler};

/// A Mitsuba scene read for prism.
#[derive(Debug, Clone)]
pub struct MitsubaScene {
    /// The geometry, materials, lights and camera ([`crate::world::Scene::from_loaded`]).
    pub geometry: LoadedGeometry,
    /// The image size and samples the sensor's film and sampler ask for.
    pub film: Film,
    /// The integrator's `max_depth` as prism's bounces (None: unbounded).
    pub max_depth: Option<u32>,
}

/// Reads the Mitsuba scene `text` (named `file`) with `parse`'s definitions and resolver,
/// upsampling RGB as `load` says.
pub fn load(
    text: &str,
    file: &str,
    options: &ParseOptions,
    load: &LoadOptions,
) -> Result<MitsubaScene, LoadError> {
    let parsed = parse(text, file, options)?;
    let upsampler = Upsampler::new(load.upsampling, load.table.clone())?;
    let cx = Context {
        upsampler: &upsampler,
        files: Files {
            resolve: options.resolve,
            search: &parsed.search,
        },
    };
    let mut geometry = LoadedGeometry {
        warnings: parsed.warnings,
        ..LoadedGeometry::default()
    };
    let mut shared: HashMap<usize, usize> = HashMap::new();
    let mut groups = Groups::default();
    let mut film = None;
    let mut max_depth = None;
    let mut media = MediaBuilder::default();
    let mut integrator_object = None;
    for child in &parsed.scene.children {
        let object = &child.object;
        match object.class {
            Class::Shape => match object.kind.as_str() {
                // A group is read where an instance places it.
                "shapegroup" => check_group(object)?,
                "instance" => {
                    note(&mut geometry.gltf_features, "instance");
                    let placed = groups.place(
                        object,
                        geometry.triangles.len(),
                        &cx.files,
                        &mut geometry.warnings,
                    )?;
                    for (member, mesh) in placed {
                        note(&mut geometry.gltf_features, &member.kind);
                        shape(&member, &mesh, &cx, &mut shared, &mut media, &mut geometry)?;
                    }
                }
                kind => {
                    note(&mut geometry.gltf_features, kind);
                    let mesh = shape_mesh(object, &cx.files, &mut geometry.warnings)?;
                    shape(object, &mesh, &cx, &mut shared, &mut media, &mut geometry)?;
                }
            },
            Class::Emitter => emitter(object, &cx, &mut geometry)?,
            Class::Sensor => {
                if geometry.cameras.is_empty() {
                    let (c, f) = camera(object, &mut geometry.warnings)?;
                    geometry.cameras.push(c);
                    film = Some(f);
                    let mut reading = Reading {
                        upsampler: &upsampler,
                        files: cx.files,
                        warnings: &mut geometry.warnings,
                    };
                    media.sensor(object, &mut reading)?;
                } else {
                    geometry.warnings.push(format!(
                        "{}: a second sensor is not read (the first is)",
                        object.at
                    ));
                }
            }
            Class::Integrator => {
                max_depth = integrator(object, &mut geometry.warnings)?;
                integrator_object = Some(object);
            }
            // Objects defined at the top for reference (BSDFs, textures, media) are read
            // where they are used.
            Class::Bsdf
            | Class::Texture
            | Class::Spectrum
            | Class::Rgb
            | Class::Medium
            | Class::Phase
            | Class::Volume => {}
            other => {
                return Err(error(
                    &object.at,
                    format!("{} '{}' is not read yet", other.tag(), object.kind),
                ));
            }
        }
    }
    if !geometry.colors.is_empty() {
        geometry.color_table = Some(upsampler.table().map_err(LoadError::Scene)?);
        // Mitsuba upsamples each vertex's colour and interpolates the spectra.
        geometry.colors_blend_spectra = true;
        geometry
            .gltf_features
            .push("mesh attributes as vertex colours (blended as spectra)".into());
    }
    let film = film.ok_or_else(|| error(&parsed.scene.at, "the scene has no sensor"))?;
    geometry.media = media.finish(
        integrator_object.map(|o| o.as_ref()),
        &mut geometry.warnings,
    )?;
    geometry.warnings.extend(unread_parameters(&parsed.scene));
    Ok(MitsubaScene {
        geometry,
        film,
        max_depth,
    })
}

/// Adds `shape`'s triangles (`mesh`), its material and, with an area emitter, its light.
fn shape(
    shape: &Object,
    mesh: &ShapeMesh,
    cx: &Context,
    shared: &mut HashMap<usize, usize>,
    media: &mut MediaBuilder,
    out: &mut LoadedGeometry,
) -> Result<(), LoadError> {
    let upsampler = cx.upsampler;
    let sides = media.shape_sides(
        shape,
        &mut Reading {
            upsampler,
            files: cx.files,
            warnings: &mut out.warnings,
        },
    )?;
    let mut bsdfs = shape.children_of(Class::Bsdf);
    let bsdf = bsdfs.next();
    if bsdfs.next().is_some() {
        return Err(error(&shape.at, "a shape has one BSDF"));
    }
    let mut emitters = shape.children_of(Class::Emitter);
    let emitter = emitters.next();
    if emitters.next().is_some() {
        return Err(error(&shape.at, "a shape has one emitter"));
    }
    let emission = match emitter {
        None => None,
        Some(e) if e.object.kind == "area" => Some(area_radiance(&e.object, cx)?),
        Some(e) => {
            return Err(error(
                &e.object.at,
                format!("emitter '{}' on a shape: only 'area' is", e.object.kind),
            ));
        }
    };
    // A diffuse reflectance from a mesh attribute is the mesh's vertex colours over a
    // reflectance of the texture's scale.
    let attribute = match bsdf {
        Some(b) => diffuse_reflectance(&b.object)?,
        None => None,
    };
    let colors = match &attribute {
        Some(a) => Some(corner_colors(mesh, a, &mut out.warnings)?),
        None => None,
    };
    // Mitsuba's default BSDF is a diffuse one of reflectance 0.5.
    let super::wrappers::Surface {
        material: surface,
        alpha,
        perturbation,
    } = match (bsdf, &attribute) {
        (Some(b), None) if b.object.kind == "null" => super::wrappers::Surface {
            material: null_boundary(&b.object)?,
            alpha: None,
            perturbation: None,
        },
        (_, Some(a)) => super::wrappers::Surface {
            material: crate::materials::Material::Diffuse {
                reflectance: crate::textures::SceneSpectrum::Constant(a.scale),
            },
            alpha: None,
            perturbation: None,
        },
        (Some(b), None) => super::wrappers::surface(&b.object, cx)?,
        (None, None) => super::wrappers::Surface {
            material: crate::materials::Material::Diffuse {
                reflectance: crate::textures::SceneSpectrum::Constant(0.5),
            },
            alpha: None,
            perturbation: None,
        },
    };
    let name = shape
        .id
        .clone()
        .unwrap_or_else(|| format!("shape {}", out.instances.len()));
    // Shapes share their BSDF's material unless they emit or bound media of their own.
    let material = match (bsdf, &emission) {
        (Some(b), None) if sides.is_none() && shared.contains_key(&key(&b.object)) => {
            shared[&key(&b.object)]
        }
        _ => {
            let mut desc = MaterialDesc::surface(
                b_name(bsdf.map(|b| &b.object), &name),
                surface,
                emission.clone(),
                upsampler,
            )?;
            desc.alpha = alpha;
            desc.perturbation = perturbation.map(Arc::new);
            out.materials.push(desc);
            let index = out.materials.len() - 1;
            if let (Some(b), None, None) = (bsdf, &emission, sides) {
                shared.insert(key(&b.object), index);
            }
            media.set_sides(index, sides);
            index
        }
    };
    let first = out.triangles.len();
    let count = mesh.append(colors.as_deref(), out);
    out.instances.push(MeshInstance {
        node: name,
        material: Some(material),
        first,
        count,
    });
    if emission.is_some() {
        out.lights.push(LightDesc::Area {
            instance: out.instances.len() - 1,
            double_sided: false,
        });
    }
    Ok(())
}

/// An `area` emitter's `radiance`. A nested texture is read as Mitsuba reads any texture:
/// Mitsuba's textures do not know they emit, so a colour bitmap's texels upsample as
/// reflectances (clamped to [0, 1], no D65: `upsample_spectral` in
/// src/textures/bitmap.cpp) and that spectrum is the radiance.
fn area_radiance(area: &Object, cx: &Context) -> Result<crate::textures::SceneSpectrum, LoadError> {
    only(area, &["radiance"])?;
    match area.child("radiance") {
        Some(c) if c.object.class == Class::Texture => {
            super::textures::spectrum(area, "radiance", Kind::Albedo, 1.0, cx)
        }
        _ => emission(area, "radiance", cx.upsampler),
    }
}

/// Lists what shapes of plugin `kind` change about the render once ([`feature`]).
fn note(features: &mut Vec<String>, kind: &str) {
    if let Some(f) = feature(kind)
        && !features.contains(&f)
    {
        features.push(f);
    }
}

fn b_name(bsdf: Option<&Arc<Object>>, shape: &str) -> String {
    bsdf.and_then(|b| b.id.clone())
        .unwrap_or_else(|| format!("{shape} material"))
}

/// The integrator's `max_depth` as prism's bounces, warning where prism's path tracer
/// differs from the one asked for. Every integrator prism maps here estimates the same
/// image with its own path tracer: `direct` is a path of one bounce, and `ptracer`'s
/// light paths reach the same expectation as camera paths.
fn integrator(integrator: &Object, warnings: &mut Vec<String>) -> Result<Option<u32>, LoadError> {
    // The integrator a `moment` or `aov` wrapper runs is the one that renders.
    let integrator = nested(integrator);
    if let Some(p) = integrator.property("hide_emitters")
        && p.value != Value::Boolean(false)
    {
        return Err(error(
            &p.at,
            "hide_emitters is not read yet (prism's camera sees emitters)",
        ));
    }
    // Mitsuba's own sampling choices: prism's estimator reaches the same image.
    for name in [
        "rr_depth",
        "emitter_samples",
        "bsdf_samples",
        "samples_per_pass",
    ] {
        let _ = integrator.property(name);
    }
    match integrator.kind.as_str() {
        "path" | "volpath" | "volpathmis" | "ptracer" => {}
        // Mitsuba's `direct` (src/integrators/direct.cpp) sees emitters and lights the
        // first hit, by MIS of emitter and BSDF samples: the expectation of a path of one
        // bounce.
        "direct" => return Ok(Some(1)),
        other => warnings.push(format!(
            "{}: integrator '{other}' renders with prism's path tracer",
            integrator.at
        )),
    }
    // Mitsuba's max_depth counts path vertices from the camera: 1 sees emitters only,
    // 2 adds direct light; prism's counts bounces, so it is one less. -1: unbounded.
    match number(integrator, "max_depth")? {
        None => Ok(None),
        Some(d) if d < 0.0 => Ok(None),
        Some(d) if d >= 1.0 && d.fract() == 0.0 && d <= f64::from(u32::MAX) => {
            Ok(Some(d as u32 - 1))
        }
        Some(d) => Err(error(
            &integrator.at,
            format!("max_depth {d}: expected -1 or a whole number of at least 1"),
        )),
    }
}
