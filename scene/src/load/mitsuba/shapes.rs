//! Mitsuba's shapes as triangles: `rectangle`, `cube` and `serialized` meshes, placed by
//! their `to_world` (Mitsuba's "Shapes" plugin reference). A shape's front faces are the
//! side its normals point to, as Mitsuba's: an area emitter on it emits from that side.

use glam::{DMat4, Vec3};

use super::parse::error;
use super::tree::{Object, Value};
use crate::LoadError;
use crate::load::meshes::TriangleMesh;

/// A shape's triangles in world space, counter-clockwise seen from their front.
pub(crate) fn triangles(
    shape: &Object,
    resolve: &dyn Fn(&str) -> std::io::Result<Vec<u8>>,
) -> Result<Vec<[Vec3; 3]>, LoadError> {
    let local = match shape.kind.as_str() {
        "rectangle" => rectangle(),
        "cube" => cube(),
        "serialized" => serialized(shape, resolve)?,
        other => {
            return Err(error(
                &shape.at,
                format!("shape '{other}' is not read yet (rectangle, cube and serialized are)"),
            ));
        }
    };
    let to_world = transform(shape, "to_world")?;
    // A mirroring transform turns the winding over; Mitsuba's normals (transformed by the
    // inverse transpose) do not turn, so the winding is turned back.
    let mirrored = to_world.determinant() < 0.0;
    Ok(local
        .into_iter()
        .map(|t| {
            let p = t.map(|v| to_world.transform_point3(v.as_dvec3()).as_vec3());
            if mirrored { [p[0], p[2], p[1]] } else { p }
        })
        .collect())
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

/// Mitsuba's `rectangle`: [-1, 1]^2 in the z = 0 plane, facing +z.
pub(crate) fn rectangle() -> Vec<[Vec3; 3]> {
    let c = |x: f32, y: f32| Vec3::new(x, y, 0.0);
    vec![
        [c(-1.0, -1.0), c(1.0, -1.0), c(1.0, 1.0)],
        [c(-1.0, -1.0), c(1.0, 1.0), c(-1.0, 1.0)],
    ]
}

/// Mitsuba's `cube`: [-1, 1]^3, facing outwards.
pub(crate) fn cube() -> Vec<[Vec3; 3]> {
    let mut out = Vec::with_capacity(12);
    // Each face: its outward axis and two axes spanning it (u x v = the normal).
    for (n, u, v) in [
        (Vec3::X, Vec3::Y, Vec3::Z),
        (Vec3::NEG_X, Vec3::Z, Vec3::Y),
        (Vec3::Y, Vec3::Z, Vec3::X),
        (Vec3::NEG_Y, Vec3::X, Vec3::Z),
        (Vec3::Z, Vec3::X, Vec3::Y),
        (Vec3::NEG_Z, Vec3::Y, Vec3::X),
    ] {
        let p = |a: f32, b: f32| n + a * u + b * v;
        out.push([p(-1.0, -1.0), p(1.0, -1.0), p(1.0, 1.0)]);
        out.push([p(-1.0, -1.0), p(1.0, 1.0), p(-1.0, 1.0)]);
    }
    out
}

/// A `serialized` shape's mesh (`filename`, `shape_index`).
fn serialized(
    shape: &Object,
    resolve: &dyn Fn(&str) -> std::io::Result<Vec<u8>>,
) -> Result<Vec<[Vec3; 3]>, LoadError> {
    let file = string(shape, "filename")?;
    let index = match shape.property("shape_index").map(|p| (&p.value, &p.at)) {
        None => 0,
        Some((Value::Integer(i), at)) => {
            usize::try_from(*i).map_err(|_| error(at, "shape_index must be at least 0"))?
        }
        Some((_, at)) => return Err(error(at, "shape_index must be an integer")),
    };
    // Relative to the file that names it, as Mitsuba resolves it.
    let path = super::paths::join(super::paths::directory(&shape.at.file), &file);
    let bytes = resolve(&path).map_err(|e| error(&shape.at, format!("{file}: {e}")))?;
    let mesh = crate::load::meshes::serialized::read(&bytes, index)
        .map_err(|e| error(&shape.at, format!("{file}: {e}")))?;
    Ok(mesh_triangles(&mesh))
}

fn mesh_triangles(mesh: &TriangleMesh) -> Vec<[Vec3; 3]> {
    mesh.triangles
        .iter()
        .map(|t| t.map(|i| mesh.positions[i as usize]))
        .collect()
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
