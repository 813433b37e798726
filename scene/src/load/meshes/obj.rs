//! Wavefront OBJ meshes as Mitsuba 3's `obj` shape reads them (mitsuba3,
//! `src/shapes/obj.cpp`): `v` positions, `vt` texture coordinates (the second flipped to
//! 1 - v unless told otherwise, Mitsuba's default for the format), `vn` normals and `f`
//! faces of `v`, `v/vt`, `v//vn` or `v/vt/vn` corners, polygons cut into a fan of
//! triangles from their first corner. Every other statement (`o`, `g`, `s`, `usemtl`,
//! comments) is read past: one file is one mesh.
//!
//! Each distinct corner (position, texture coordinate, normal) becomes one vertex, as in
//! Mitsuba, so that a seam in the texture coordinates or normals splits the vertices
//! along it (and normals Mitsuba computes for a file without them are not smoothed across
//! such a seam). Indices may be negative, counted back from the last one defined, as the
//! format's specification allows (Mitsuba itself refuses them).
//!
//! OBJ declares no counts: what is allocated grows with the lines read. An index is
//! checked against what the file defines; every error names the line.

use std::collections::HashMap;

use glam::{Vec2, Vec3};

use super::TriangleMesh;
use crate::LoadError;

/// Reads the OBJ file `bytes`; `flip_tex_coords` turns each texture coordinate's v into
/// 1 - v (Mitsuba's `flip_tex_coords`, true by default for OBJ).
///
/// ```
/// # #[cfg(feature = "mitsuba")] {
/// use prism_scene::load::meshes::obj;
///
/// let quad = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
/// let mesh = obj::read(quad, true).unwrap();
/// assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
/// assert!(obj::read(b"f 1 2 3\n", true).unwrap_err().to_string().contains("line 1"));
/// # }
/// ```
pub fn read(bytes: &[u8], flip_tex_coords: bool) -> Result<TriangleMesh, LoadError> {
    let totals = count(bytes);
    let mut pools = Pools::default();
    // Corner keys (position, texture coordinate + 1, normal + 1; 0: none) to vertex ids.
    let mut vertex_of: HashMap<[u32; 3], u32> = HashMap::new();
    let mut keys: Vec<[u32; 3]> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut warnings = Vec::new();
    for (number, line) in lines(bytes) {
        let fail = |reason: String| LoadError::Geometry(format!("OBJ line {number}: {reason}"));
        let Some((keyword, rest)) = statement(line) else {
            continue;
        };
        match keyword {
            b"v" => pools
                .positions
                .push(finite(floats::<3>(rest).map_err(&fail)?, "a position").map_err(&fail)?),
            b"vn" => pools
                .normals
                .push(finite(floats::<3>(rest).map_err(&fail)?, "a normal").map_err(&fail)?),
            b"vt" => {
                let [u, v] = finite(floats::<2>(rest).map_err(&fail)?, "a texture coordinate")
                    .map_err(&fail)?;
                pools
                    .uvs
                    .push(Vec2::new(u, if flip_tex_coords { 1.0 - v } else { v }));
            }
            b"f" => {
                let mut corners = 0usize;
                let mut fan = [0u32; 3];
                for token in rest.split(|b| b.is_ascii_whitespace()) {
                    if token.is_empty() {
                        continue;
                    }
                    let key = corner(token, &pools, &totals).map_err(&fail)?;
                    let id = match vertex_of.get(&key) {
                        Some(&id) => id,
                        None => {
                            let id = u32::try_from(keys.len())
                                .map_err(|_| fail("more than 2^32 vertices".into()))?;
                            vertex_of.insert(key, id);
                            keys.push(key);
                            id
                        }
                    };
                    // A fan from the first corner, as Mitsuba cuts polygons.
                    match corners {
                        0..=2 => fan[corners] = id,
                        _ => fan = [fan[0], fan[2], id],
                    }
                    corners += 1;
                    if corners >= 3 {
                        triangles.push(fan);
                    }
                }
                if corners < 3 {
                    warnings.push(format!(
                        "OBJ line {number}: a face of {corners} corners is not a surface and \
                         is skipped"
                    ));
                }
            }
            _ => {}
        }
    }
    if triangles.is_empty() {
        return Err(LoadError::Geometry("OBJ: the file has no faces".into()));
    }
    Ok(pools.mesh(&keys, triangles, warnings))
}

/// What the file defines, counted before reading so that a face may name any of it.
#[derive(Default)]
struct Totals {
    positions: usize,
    uvs: usize,
    normals: usize,
}

fn count(bytes: &[u8]) -> Totals {
    let mut totals = Totals::default();
    for (_, line) in lines(bytes) {
        match statement(line).map(|(k, _)| k) {
            Some(b"v") => totals.positions += 1,
            Some(b"vt") => totals.uvs += 1,
            Some(b"vn") => totals.normals += 1,
            _ => {}
        }
    }
    totals
}

/// The values the file defines, in file order.
#[derive(Default)]
struct Pools {
    positions: Vec<Vec3>,
    uvs: Vec<Vec2>,
    normals: Vec<Vec3>,
}

impl Pools {
    /// The mesh of the distinct corners `keys`: texture coordinates and normals where any
    /// corner has them (zero for the corners that do not).
    fn mesh(
        &self,
        keys: &[[u32; 3]],
        triangles: Vec<[u32; 3]>,
        warnings: Vec<String>,
    ) -> TriangleMesh {
        let has_uvs = keys.iter().any(|k| k[1] != 0);
        let has_normals = keys.iter().any(|k| k[2] != 0);
        let pick = |pool_index: u32| pool_index.checked_sub(1).map(|i| i as usize);
        TriangleMesh {
            positions: keys.iter().map(|k| self.positions[k[0] as usize]).collect(),
            uvs: if has_uvs {
                keys.iter()
                    .map(|k| pick(k[1]).map_or(Vec2::ZERO, |i| self.uvs[i]))
                    .collect()
            } else {
                Vec::new()
            },
            normals: if has_normals {
                keys.iter()
                    .map(|k| pick(k[2]).map_or(Vec3::ZERO, |i| self.normals[i]))
                    .collect()
            } else {
                Vec::new()
            },
            triangles,
            warnings,
            ..TriangleMesh::default()
        }
    }
}

/// A face corner `v`, `v/vt`, `v//vn` or `v/vt/vn` as its key: the position's index, and
/// the texture coordinate's and normal's plus one (0 where absent).
fn corner(token: &[u8], pools: &Pools, totals: &Totals) -> Result<[u32; 3], String> {
    let text = std::str::from_utf8(token).map_err(|_| "a face corner is not text".to_string())?;
    if text.split('/').count() > 3 {
        return Err(format!("face corner '{text}' has more than three indices"));
    }
    let mut parts = text.split('/');
    let mut key = [0u32; 3];
    // Relative (negative) indices count back from what is defined so far, positive ones
    // may name anything the file defines.
    let pools_so_far = [pools.positions.len(), pools.uvs.len(), pools.normals.len()];
    let pools_total = [totals.positions, totals.uvs, totals.normals];
    for (slot, what) in ["position", "texture coordinate", "normal"]
        .into_iter()
        .enumerate()
    {
        let part = match parts.next() {
            Some(p) => p,
            None => break,
        };
        if part.is_empty() {
            if slot == 0 {
                return Err(format!("face corner '{text}' has no position"));
            }
            continue;
        }
        let index: i64 = part
            .parse()
            .map_err(|_| format!("face corner '{text}': '{part}' is not an index"))?;
        let resolved = match index {
            0 => return Err(format!("face corner '{text}': indices count from 1")),
            i if i > 0 => i - 1,
            i => pools_so_far[slot] as i64 + i,
        };
        if resolved < 0 || resolved as u64 >= pools_total[slot] as u64 {
            return Err(format!(
                "face corner '{text}' names {what} {index}, the file defines {}",
                pools_total[slot]
            ));
        }
        let resolved = u32::try_from(resolved)
            .map_err(|_| format!("face corner '{text}': index {index} is too large"))?;
        key[slot] = if slot == 0 { resolved } else { resolved + 1 };
    }
    Ok(key)
}

/// The first `K` numbers of a statement (more may follow, and are read past as Mitsuba
/// does: a `v` with a weight, a `vt` with a w).
fn floats<const K: usize>(rest: &[u8]) -> Result<[f32; K], String> {
    let mut out = [0.0f32; K];
    let mut tokens = rest
        .split(|b| b.is_ascii_whitespace())
        .filter(|t| !t.is_empty());
    for (i, v) in out.iter_mut().enumerate() {
        let token = tokens
            .next()
            .ok_or_else(|| format!("expected {K} numbers, found {i}"))?;
        *v = std::str::from_utf8(token)
            .ok()
            .and_then(|t| t.parse().ok())
            .ok_or_else(|| format!("'{}' is not a number", String::from_utf8_lossy(token)))?;
    }
    Ok(out)
}

fn finite<const K: usize, T: From<[f32; K]>>(values: [f32; K], what: &str) -> Result<T, String> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(T::from(values))
    } else {
        Err(format!("{what} is not finite"))
    }
}

/// The keyword of a line and what follows it; None for a blank line.
fn statement(line: &[u8]) -> Option<(&[u8], &[u8])> {
    let start = line.iter().position(|b| !b.is_ascii_whitespace())?;
    let line = &line[start..];
    let end = line
        .iter()
        .position(|b| b.is_ascii_whitespace())
        .unwrap_or(line.len());
    Some((&line[..end], &line[end..]))
}

/// The file's lines with their 1-based numbers.
fn lines(bytes: &[u8]) -> impl Iterator<Item = (usize, &[u8])> {
    bytes
        .split(|&b| b == b'\n')
        .enumerate()
        .map(|(i, l)| (i + 1, l))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn error(text: &str) -> String {
        read(text.as_bytes(), true).unwrap_err().to_string()
    }

    #[test]
    fn corners_with_texture_coordinates_and_normals() {
        let text = "# a quad\no quad\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n\
                    vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n\
                    f 1/1/1 2/2/1 3/3/1 4/4/1\n";
        let mesh = read(text.as_bytes(), true).unwrap();
        assert_eq!(mesh.positions.len(), 4);
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(mesh.normals, vec![Vec3::Z; 4]);
        // Flipped as Mitsuba flips OBJ's texture coordinates by default.
        assert_eq!(mesh.uvs[0], Vec2::new(0.0, 1.0));
        assert_eq!(mesh.uvs[2], Vec2::new(1.0, 0.0));
        let unflipped = read(text.as_bytes(), false).unwrap();
        assert_eq!(unflipped.uvs[2], Vec2::new(1.0, 1.0));
    }

    #[test]
    fn each_distinct_corner_is_a_vertex() {
        // Position 1 with two texture coordinates: two vertices, as in Mitsuba.
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 1\n\
                    f 1/1 2/1 3/1\nf 1/2 3/1 2/1\n";
        let mesh = read(text.as_bytes(), true).unwrap();
        assert_eq!(mesh.positions.len(), 4);
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [3, 2, 1]]);
        assert!(mesh.normals.is_empty());
    }

    #[test]
    fn slashes_and_relative_indices() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0.5 0.5\n\
                    f 1//1 2//1 3//1\nf -3/-1/ -2/-1/ -1/-1/\n";
        let mesh = read(text.as_bytes(), true).unwrap();
        assert_eq!(mesh.triangles.len(), 2);
        assert_eq!(mesh.positions.len(), 6);
        // The second face's corners have texture coordinates but no normals.
        assert_eq!(mesh.normals[3], Vec3::ZERO);
        assert_eq!(mesh.uvs[3], Vec2::new(0.5, 0.5));
    }

    #[test]
    fn a_face_may_name_what_later_lines_define() {
        let mesh = read(b"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", true).unwrap();
        assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn errors_name_the_line() {
        assert!(error("v 0 0 0\nv 1 0\n").contains("line 2: expected 3 numbers, found 2"));
        assert!(error("v 0 0 x\n").contains("'x' is not a number"));
        assert!(error("v 0 0 nan\n").contains("line 1: a position is not finite"));
        assert!(error("v 0 0 0\nf 1 2 3\n").contains("line 2: face corner '2' names position 2"));
        assert!(error("v 0 0 0\nf 0 1 1\n").contains("indices count from 1"));
        assert!(error("v 0 0 0\nf 1/5 1 1\n").contains("texture coordinate 5"));
        assert!(error("v 0 0 0\nf 1/1/1/1 1 1\n").contains("more than three"));
        assert!(error("v 0 0 0\nf 1 -4 1\n").contains("position -4"));
        assert!(error("v 0 0 0\nf 1 99999999999 1\n").contains("position 99999999999"));
        assert!(error("v 0 0 0\n").contains("no faces"));
        for e in [error("v 0 0 0\nf 1 2 3\n"), error("")] {
            assert!(!e.contains('\n'), "{e}");
        }
    }

    #[test]
    fn short_faces_are_skipped_with_a_warning() {
        let mesh = read(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\nf 1 2 3\n", true).unwrap();
        assert_eq!(mesh.triangles.len(), 1);
        assert!(mesh.warnings[0].contains("line 4"), "{:?}", mesh.warnings);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        /// Random bytes, and a valid file cut or with bytes replaced, never panic.
        #[test]
        fn no_input_panics(
            noise in proptest::collection::vec(any::<u8>(), 0..256),
            flips in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 0..8),
            cut in any::<prop::sample::Index>(),
        ) {
            let _ = read(&noise, true);
            let mut bytes = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\nf -1 -2 -3\n".to_vec();
            for (at, value) in &flips {
                let i = at.index(bytes.len());
                bytes[i] = *value;
            }
            let _ = read(&bytes, true);
            let _ = read(&bytes[..cut.index(bytes.len())], false);
        }
    }
}
