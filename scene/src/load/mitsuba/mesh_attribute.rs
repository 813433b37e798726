//! Mitsuba's `mesh_attribute` texture as a diffuse reflectance (Mitsuba's "Textures"
//! plugin reference, `src/textures/mesh_attribute.cpp`): the shape's attribute `name`
//! (`vertex_color`, `face_color`, or any `vertex_*` / `face_*` the mesh file has) times
//! `scale`, interpolated over each triangle by its barycentrics for a vertex attribute,
//! constant over it for a face one.
//!
//! prism carries such a colour as the scene's per-vertex colours, which multiply a
//! material's base reflectance ([`crate::load::LoadedGeometry::colors`]): the material is
//! a Lambertian surface of reflectance `scale`, and each triangle corner's colour the
//! attribute's RGB there (a one-valued attribute as grey). Mitsuba's spectral variants
//! upsample an RGB attribute only when its name contains "color" and read any other
//! three-valued attribute as sigmoid coefficients; prism refuses the latter rather than
//! guess.

use glam::Vec4;

use super::parse::error;
use super::sensors::number;
use super::shape_mesh::ShapeMesh;
use super::shapes::string;
use super::tree::{Location, Object};
use crate::LoadError;

/// A `mesh_attribute` texture's parameters.
#[derive(Debug, Clone)]
pub(crate) struct MeshAttributeTexture {
    pub(crate) name: String,
    pub(crate) scale: f64,
    pub(crate) at: Location,
}

/// The `mesh_attribute` texture `bsdf` takes its reflectance from, if it is a `diffuse`
/// BSDF (or a `twosided` around one) whose `reflectance` is one.
pub(crate) fn diffuse_reflectance(
    bsdf: &Object,
) -> Result<Option<MeshAttributeTexture>, LoadError> {
    let diffuse = match bsdf.kind.as_str() {
        "diffuse" => bsdf,
        "twosided" => match bsdf
            .children_of(super::tree::Class::Bsdf)
            .map(|c| &c.object)
            .collect::<Vec<_>>()
            .as_slice()
        {
            [one] if one.kind == "diffuse" => one,
            _ => return Ok(None),
        },
        _ => return Ok(None),
    };
    let Some(texture) = diffuse
        .child("reflectance")
        .map(|c| &c.object)
        .filter(|t| t.kind == "mesh_attribute")
    else {
        return Ok(None);
    };
    let name = string(texture, "name")?;
    if !(name.starts_with("vertex_") || name.starts_with("face_")) {
        return Err(error(
            &texture.at,
            format!("mesh_attribute '{name}': a name starts with 'vertex_' or 'face_'"),
        ));
    }
    let scale = number(texture, "scale")?.unwrap_or(1.0);
    if scale < 0.0 {
        return Err(error(
            &texture.at,
            "mesh_attribute: scale must be at least 0",
        ));
    }
    Ok(Some(MeshAttributeTexture {
        name,
        scale,
        at: texture.at.clone(),
    }))
}

/// The colour at each triangle corner of `mesh`, in the mesh's triangle order and
/// corner order, as linear RGB with alpha 1 (each value clamped to [0, 1], as Mitsuba's
/// spectral upsampling clamps it).
pub(crate) fn corner_colors(
    mesh: &ShapeMesh,
    texture: &MeshAttributeTexture,
    warnings: &mut Vec<String>,
) -> Result<Vec<[Vec4; 3]>, LoadError> {
    let name = &texture.name;
    let Some(attribute) = mesh.attribute(name) else {
        let known: Vec<&str> = mesh.attributes.iter().map(|a| a.name.as_str()).collect();
        return Err(error(
            &texture.at,
            format!(
                "mesh_attribute '{name}': the shape has no such attribute (it has: {})",
                if known.is_empty() {
                    "none".into()
                } else {
                    known.join(", ")
                }
            ),
        ));
    };
    let rgb = |values: &[f32]| -> Vec4 {
        let c = |v: f32| {
            if v.is_finite() {
                v.clamp(0.0, 1.0)
            } else {
                0.0
            }
        };
        match values {
            [g] => Vec4::new(c(*g), c(*g), c(*g), 1.0),
            [r, g, b, ..] => Vec4::new(c(*r), c(*g), c(*b), 1.0),
            _ => Vec4::ONE,
        }
    };
    match attribute.dim {
        1 => {}
        3 if name.contains("color") => {}
        3 => {
            return Err(error(
                &texture.at,
                format!(
                    "mesh_attribute '{name}': Mitsuba's spectral variants read a three-valued \
                     attribute without 'color' in its name as sigmoid coefficients, which \
                     prism does not; name it '..._color' to mean RGB"
                ),
            ));
        }
        4 => warnings.push(format!(
            "{}: mesh_attribute '{name}' has four values per item: the first three are read \
             as RGB, the fourth ignored",
            texture.at
        )),
        d => {
            return Err(error(
                &texture.at,
                format!("mesh_attribute '{name}' has {d} values per item (1 or 3 are read)"),
            ));
        }
    }
    let dim = attribute.dim;
    let value = |item: usize| {
        attribute
            .values
            .get(item * dim..(item + 1) * dim)
            .map_or(Vec4::ONE, rgb)
    };
    Ok(mesh
        .triangles
        .iter()
        .enumerate()
        .map(|(k, t)| {
            if attribute.per_vertex() {
                t.map(|i| value(i as usize))
            } else {
                [value(k); 3]
            }
        })
        .collect())
}
