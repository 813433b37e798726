//! Mitsuba's shapes as prism's triangles ("Shapes" plugin reference): the mesh files
//! `obj`, `ply` and `serialized`, and the built-in `rectangle`, `cube`, `disk`,
//! `cylinder` and `sphere` ([`super::primitives`]), placed by their `to_world` with
//! Mitsuba's shading normals and texture coordinates ([`ShapeMesh`]). `shapegroup` and
//! `instance` are [`super::instances`]'.

use glam::{DMat4, DVec3};

use super::files::Files;
use super::parse::error;
use super::primitives;
use super::sensors::number;
use super::shape_mesh::ShapeMesh;
use super::tree::{Object, Value};
use crate::LoadError;
use crate::load::meshes::{TriangleMesh, obj, ply, serialized};

/// The shapes [`shape_mesh`] reads.
pub(crate) const READ: &str =
    "obj, ply, serialized, rectangle, cube, disk, cylinder, sphere, shapegroup and instance";

/// A shape's triangles in world space, shaded as Mitsuba shades it. Warnings (a mesh
/// file's properties read past) go to `warnings`.
pub(crate) fn shape_mesh(
    shape: &Object,
    files: &Files,
    warnings: &mut Vec<String>,
) -> Result<ShapeMesh, LoadError> {
    let to_world = transform(shape, "to_world")?;
    let flip_normals = boolean(shape, "flip_normals", false)?;
    let placed = |result: Result<ShapeMesh, String>| result.map_err(|e| error(&shape.at, e));
    match shape.kind.as_str() {
        "rectangle" => placed(primitives::rectangle(&to_world, flip_normals)),
        "cube" => placed(primitives::cube(&to_world, flip_normals)),
        "disk" => placed(primitives::disk(&to_world, flip_normals)),
        "cylinder" => {
            let p0 = point(shape, "p0", DVec3::ZERO)?;
            let p1 = point(shape, "p1", DVec3::Z)?;
            let radius = number(shape, "radius")?.unwrap_or(1.0);
            placed(primitives::cylinder(
                &to_world,
                p0,
                p1,
                radius,
                flip_normals,
            ))
        }
        "sphere" => {
            let center = point(shape, "center", DVec3::ZERO)?;
            let radius = number(shape, "radius")?.unwrap_or(1.0);
            placed(primitives::sphere(&to_world, center, radius, flip_normals))
        }
        "obj" | "ply" | "serialized" => {
            let mesh = mesh_file(shape, files)?;
            warnings.extend(mesh.warnings.iter().map(|w| format!("{}: {w}", shape.at)));
            let face_normals = boolean(shape, "face_normals", false)?;
            placed(ShapeMesh::from_file(
                mesh,
                &to_world,
                face_normals,
                flip_normals,
            ))
        }
        "sdfgrid" => Err(error(
            &shape.at,
            "shape 'sdfgrid' is not read: prism's surfaces are triangles, and a signed \
             distance grid has none to give",
        )),
        other => Err(error(
            &shape.at,
            format!("shape '{other}' is not read yet ({READ} are)"),
        )),
    }
}

/// What `prism info` lists for a shape of plugin `kind` (the file's features that change
/// how it renders), if anything: the shapes prism tessellates.
pub(crate) fn feature(kind: &str) -> Option<String> {
    let (segments, rings) = (primitives::SEGMENTS, primitives::RINGS);
    Some(match kind {
        "sphere" => format!(
            "sphere tessellated ({segments} x {rings}, {} triangles each)",
            2 * segments * (rings - 1)
        ),
        "disk" => format!("disk tessellated ({segments} triangles each)"),
        "cylinder" => format!("cylinder tessellated ({} triangles each)", 2 * segments),
        "instance" => "instances (each a copy of its shapegroup's triangles)".into(),
        _ => return None,
    })
}

/// The mesh of an `obj`, `ply` or `serialized` shape, its file found as Mitsuba finds
/// it (the `<path>` directories, then next to the file naming it).
fn mesh_file(shape: &Object, files: &Files) -> Result<TriangleMesh, LoadError> {
    let file = string(shape, "filename")?;
    let bytes = files.read(&file, &shape.at)?;
    let read = match shape.kind.as_str() {
        // OBJ files store v downwards; Mitsuba flips it unless told not to.
        "obj" => obj::read(&bytes, boolean(shape, "flip_tex_coords", true)?),
        "ply" => ply::read(&bytes, boolean(shape, "flip_tex_coords", false)?),
        _ => {
            let index = match shape.property("shape_index").map(|p| (&p.value, &p.at)) {
                None => 0,
                Some((Value::Integer(i), at)) => {
                    usize::try_from(*i).map_err(|_| error(at, "shape_index must be at least 0"))?
                }
                Some((_, at)) => return Err(error(at, "shape_index must be an integer")),
            };
            serialized::read(&bytes, index)
        }
    };
    read.map_err(|e| {
        let reason = match e {
            LoadError::Geometry(m) => m,
            other => other.to_string(),
        };
        error(&shape.at, format!("{file}: {reason}"))
    })
}

/// The 4 x 4 transform property `name` (identity where absent).
pub(crate) fn transform(object: &Object, name: &str) -> Result<DMat4, LoadError> {
    match object.property(name).map(|p| (&p.value, &p.at)) {
        None => Ok(DMat4::IDENTITY),
        Some((Value::Transform(rows), _)) => {
            // Rows as the file writes them; glam's matrices are column-major.
            Ok(DMat4::from_cols_array_2d(rows).transpose())
        }
        Some((_, at)) => Err(error(at, format!("'{name}' must be a transform"))),
    }
}

/// The boolean property `name`, `default` where absent.
pub(crate) fn boolean(object: &Object, name: &str, default: bool) -> Result<bool, LoadError> {
    match object.property(name).map(|p| (&p.value, &p.at)) {
        None => Ok(default),
        Some((Value::Boolean(b), _)) => Ok(*b),
        Some((_, at)) => Err(error(at, format!("'{name}' must be a boolean"))),
    }
}

/// The point property `name`, `default` where absent.
fn point(object: &Object, name: &str, default: DVec3) -> Result<DVec3, LoadError> {
    match object.property(name).map(|p| (&p.value, &p.at)) {
        None => Ok(default),
        Some((Value::Point(p) | Value::Vector(p), at)) => {
            let p = DVec3::from(*p);
            if p.is_finite() {
                Ok(p)
            } else {
                Err(error(at, format!("'{name}' must be finite")))
            }
        }
        Some((_, at)) => Err(error(at, format!("'{name}' must be a point"))),
    }
}

/// The string property `name`.
pub(crate) fn string(object: &Object, name: &str) -> Result<String, LoadError> {
    match object.property(name).map(|p| (&p.value, &p.at)) {
        Some((Value::String(s), _)) => Ok(s.clone()),
        Some((_, at)) => Err(error(at, format!("'{name}' must be a string"))),
        None => Err(error(
            &object.at,
            format!("{} '{}' needs '{name}'", object.class.tag(), object.kind),
        )),
    }
}
