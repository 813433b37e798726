//! Texture coordinates of Mitsuba's shapes, as Mitsuba gives them (textures reach a
//! surface only through them): `rectangle` maps [-1, 1]^2 to [0, 1]^2, (x + 1) / 2 and
//! (y + 1) / 2 (src/shapes/rectangle.cpp); `cube` maps each face to [0, 1]^2 as its
//! vertex table does (src/shapes/cube.cpp); a mesh without texture coordinates is
//! parameterized by its barycentrics, each triangle's vertices at (0, 0), (1, 0) and
//! (0, 1) (src/render/mesh.cpp).

use glam::{Vec2, Vec3};

use super::shapes::{cube, rectangle, transform};
use super::tree::Object;
use crate::LoadError;
use crate::load::LoadedGeometry;

/// Records the texture coordinates of `shape`, whose triangles were just added to `out`
/// from index `first`: its own where Mitsuba gives the shape some, barycentric ones
/// otherwise, and for earlier triangles where this is the first shape with any.
pub(crate) fn add(shape: &Object, first: usize, out: &mut LoadedGeometry) -> Result<(), LoadError> {
    let own = local_uvs(shape)?;
    if own.is_none() && out.uvs.is_empty() {
        return Ok(());
    }
    let barycentric = [Vec2::ZERO, Vec2::X, Vec2::Y];
    if out.uvs.len() < first {
        out.uvs.resize(first, barycentric);
    }
    match own {
        Some(uvs) => out.uvs.extend(uvs),
        None => out.uvs.resize(out.triangles.len(), barycentric),
    }
    Ok(())
}

/// The texture coordinates of a rectangle's or a cube's triangles, in the order (and
/// with the winding) `shapes::triangles` gives them; None for other shapes.
fn local_uvs(shape: &Object) -> Result<Option<Vec<[Vec2; 3]>>, LoadError> {
    let (local, uv): (Vec<[Vec3; 3]>, fn([Vec3; 3]) -> [Vec2; 3]) = match shape.kind.as_str() {
        "rectangle" => (rectangle(), |t| {
            t.map(|p| Vec2::new(p.x + 1.0, p.y + 1.0) * 0.5)
        }),
        "cube" => (cube(), cube_uvs),
        _ => return Ok(None),
    };
    // A mirroring transform turns the winding back by swapping two vertices.
    let mirrored = transform(shape, "to_world")?.determinant() < 0.0;
    Ok(Some(
        local
            .into_iter()
            .map(|t| {
                let c = uv(t);
                if mirrored { [c[0], c[2], c[1]] } else { c }
            })
            .collect(),
    ))
}

/// A cube triangle's coordinates: its face (by its outward normal) maps the two axes
/// across it to u and v as Mitsuba's vertex table does, face by face.
fn cube_uvs(t: [Vec3; 3]) -> [Vec2; 3] {
    let n = (t[1] - t[0]).cross(t[2] - t[0]);
    let up = |a: f32| (a + 1.0) * 0.5;
    let down = |a: f32| (1.0 - a) * 0.5;
    let face: fn(Vec3, &dyn Fn(f32) -> f32, &dyn Fn(f32) -> f32) -> Vec2 = if n.x > 0.5 {
        |p, up, down| Vec2::new(up(p.y), down(p.z))
    } else if n.x < -0.5 {
        |p, up, _| Vec2::new(up(p.y), up(p.z))
    } else if n.y > 0.5 {
        |p, _, down| Vec2::new(down(p.x), down(p.z))
    } else if n.y < -0.5 {
        |p, up, _| Vec2::new(up(p.z), up(p.x))
    } else if n.z > 0.5 {
        |p, up, _| Vec2::new(up(p.y), up(p.x))
    } else {
        |p, up, down| Vec2::new(down(p.y), up(p.x))
    };
    t.map(|p| face(p, &up, &down))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each face of the cube covers [0, 1]^2 with its corners where Mitsuba's table puts
    /// them: the -y face's corner (1, -1, -1) at (0, 1), the +z face's (-1, 1, 1) at
    /// (1, 0).
    #[test]
    fn cube_faces_follow_mitsubas_table() {
        let tris = cube();
        let find = |corner: Vec3, normal: Vec3| -> Vec2 {
            for t in &tris {
                let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
                if (n - normal).length() < 1e-6
                    && let Some(i) = t.iter().position(|p| (*p - corner).length() < 1e-6)
                {
                    return cube_uvs(*t)[i];
                }
            }
            panic!("no corner {corner} on face {normal}");
        };
        assert_eq!(
            find(Vec3::new(1.0, -1.0, -1.0), Vec3::NEG_Y),
            Vec2::new(0.0, 1.0)
        );
        assert_eq!(
            find(Vec3::new(-1.0, -1.0, 1.0), Vec3::NEG_Y),
            Vec2::new(1.0, 0.0)
        );
        assert_eq!(
            find(Vec3::new(-1.0, 1.0, 1.0), Vec3::Z),
            Vec2::new(1.0, 0.0)
        );
        assert_eq!(
            find(Vec3::new(1.0, 1.0, -1.0), Vec3::Y),
            Vec2::new(0.0, 1.0)
        );
        assert_eq!(
            find(Vec3::new(1.0, 1.0, -1.0), Vec3::X),
            Vec2::new(1.0, 1.0)
        );
        assert_eq!(
            find(Vec3::new(-1.0, 1.0, -1.0), Vec3::NEG_X),
            Vec2::new(1.0, 0.0)
        );
        assert_eq!(
            find(Vec3::new(1.0, -1.0, -1.0), Vec3::NEG_Z),
            Vec2::new(1.0, 1.0)
        );
    }
}
