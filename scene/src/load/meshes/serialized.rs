//! Mitsuba's `serialized` meshes: the format its `serialized` shape plugin reads, as that
//! plugin's documentation describes it (mitsuba3, `src/shapes/serialized.cpp`, "Format
//! description", "Multiple shapes", "End-of-file dictionary").
//!
//! Little endian. Each mesh is a `u16` format identifier 0x041C and a `u16` version (3
//! or 4), then a zlib stream holding: `u32` flags (0x0001 vertex normals, 0x0002 texture
//! coordinates, 0x0008 vertex colours, 0x0010 face normals, 0x1000 single precision,
//! 0x2000 double precision), in version 4 the mesh's name as a null-terminated UTF-8
//! string, `u64` vertex and triangle counts, then the positions (x, y, z per vertex), the
//! normals, the texture coordinates and the colours where the flags say so, each in the
//! flags' precision, and the triangles as `u32` vertex indices. Meshes are concatenated;
//! the file ends with each mesh's offset (`u64` in version 4, `u32` in version 3) and a
//! `u32` count of meshes.
//!
//! Nothing is allocated from a count the file declares until the decompressed data is
//! known to hold it, and the decompression itself is bounded by DEFLATE's largest
//! expansion of the compressed bytes (1032:1), so a small file cannot claim gigabytes.

use glam::{Vec2, Vec3};

use super::TriangleMesh;
use crate::LoadError;

const FORMAT: u16 = 0x041C;
const HAS_NORMALS: u32 = 0x0001;
const HAS_TEXCOORDS: u32 = 0x0002;
const HAS_COLORS: u32 = 0x0008;
const FACE_NORMALS: u32 = 0x0010;
const DOUBLE_PRECISION: u32 = 0x2000;

/// The largest ratio of decompressed to compressed bytes a zlib stream reaches (zlib's
/// technical details: "the maximum compression ratio is 1032:1", a 258-byte match
/// repeated in about two bits).
const MAX_RATIO: usize = 1032;

/// Reads mesh `index` (0: the first) of the `serialized` file `bytes`.
///
/// ```
/// # #[cfg(feature = "mitsuba")] {
/// use prism_scene::load::meshes::serialized;
///
/// // Not a serialized file: one clear error, never a panic.
/// assert!(serialized::read(b"not a mesh", 0).is_err());
/// # }
/// ```
pub fn read(bytes: &[u8], index: usize) -> Result<TriangleMesh, LoadError> {
    let version = header(bytes, 0)?;
    let start = if index == 0 {
        0
    } else {
        offset_of(bytes, version, index)?
    };
    if start != 0 {
        let v = header(bytes, start)?;
        if v != version {
            return Err(bad(format!(
                "mesh {index} has version {v}, the file's first {version}"
            )));
        }
    }
    let compressed = bytes.get(start + 4..).unwrap_or_default();
    let limit = compressed.len().saturating_mul(MAX_RATIO);
    let data = miniz_oxide::inflate::decompress_to_vec_zlib_with_limit(compressed, limit)
        .map_err(|e| bad(format!("mesh {index}: its zlib stream is broken ({e:?})")))?;
    decode(&data, version, index)
}

/// The version of the mesh header at `at`.
fn header(bytes: &[u8], at: usize) -> Result<u16, LoadError> {
    let mut r = Reader::new(bytes.get(at..).unwrap_or_default());
    let format = r.u16().map_err(|_| bad("too short for a header".into()))?;
    let version = r.u16().map_err(|_| bad("too short for a header".into()))?;
    if format != FORMAT {
        return Err(bad(format!(
            "not a serialized mesh (identifier 0x{format:04X}, expected 0x041C)"
        )));
    }
    if version != 3 && version != 4 {
        return Err(bad(format!("version {version} (3 and 4 are read)")));
    }
    Ok(version)
}

/// The byte offset of mesh `index`, from the dictionary at the file's end.
fn offset_of(bytes: &[u8], version: u16, index: usize) -> Result<usize, LoadError> {
    let n = bytes.len();
    let count =
        n.checked_sub(4)
            .and_then(|at| Reader::new(&bytes[at..]).u32().ok())
            .ok_or_else(|| bad("too short for its dictionary of meshes".into()))? as usize;
    if index >= count {
        return Err(bad(format!(
            "mesh {index} asked for, the file holds {count}"
        )));
    }
    let width = if version == 4 { 8 } else { 4 };
    let at = (count - index)
        .checked_mul(width)
        .and_then(|b| n.checked_sub(4 + b))
        .ok_or_else(|| {
            bad(format!(
                "its dictionary of {count} meshes runs past its start"
            ))
        })?;
    let mut r = Reader::new(&bytes[at..]);
    let offset = if version == 4 {
        r.u64()
    } else {
        r.u32().map(u64::from)
    }
    .map_err(|_| bad("its dictionary is cut short".into()))?;
    usize::try_from(offset)
        .ok()
        .filter(|&o| o.checked_add(4).is_some_and(|end| end <= at))
        .ok_or_else(|| bad(format!("mesh {index} starts at {offset}, outside the file")))
}

/// The mesh in decompressed `data`.
fn decode(data: &[u8], version: u16, index: usize) -> Result<TriangleMesh, LoadError> {
    let short = |what: &str| bad(format!("mesh {index}: cut short in its {what}"));
    let mut r = Reader::new(data);
    let flags = r.u32().map_err(|_| short("flags"))?;
    let name = if version == 4 {
        r.c_string().map_err(|_| short("name"))?
    } else {
        String::new()
    };
    let vertices = r.u64().map_err(|_| short("vertex count"))?;
    let triangles = r.u64().map_err(|_| short("triangle count"))?;
    let scalar = if flags & DOUBLE_PRECISION != 0 { 8 } else { 4 };
    let per_vertex = 3
        + if flags & HAS_NORMALS != 0 { 3 } else { 0 }
        + if flags & HAS_TEXCOORDS != 0 { 2 } else { 0 }
        + if flags & HAS_COLORS != 0 { 3 } else { 0 };
    // What the counts claim, checked against what the stream holds before any allocation.
    let needed = vertices
        .checked_mul(per_vertex * scalar)
        .and_then(|v| triangles.checked_mul(12).and_then(|t| v.checked_add(t)));
    if needed.is_none_or(|n| n > r.remaining() as u64) {
        return Err(bad(format!(
            "mesh {index} declares {vertices} vertices and {triangles} triangles, more than its \
             {} bytes of data hold",
            r.remaining()
        )));
    }
    let (vertices, triangles) = (vertices as usize, triangles as usize);
    let mut read_vec = |dim: usize| -> Result<Vec<f32>, LoadError> {
        (0..vertices * dim)
            .map(|_| {
                let v = if scalar == 8 {
                    r.f64().map(|v| v as f32)
                } else {
                    r.f32()
                }
                .map_err(|_| short("vertex data"))?;
                if v.is_finite() {
                    Ok(v)
                } else {
                    Err(bad(format!("mesh {index}: a vertex value is not finite")))
                }
            })
            .collect()
    };
    let positions = read_vec(3)?;
    let normals = if flags & HAS_NORMALS != 0 {
        read_vec(3)?
    } else {
        Vec::new()
    };
    let uvs = if flags & HAS_TEXCOORDS != 0 {
        read_vec(2)?
    } else {
        Vec::new()
    };
    if flags & HAS_COLORS != 0 {
        // Vertex colours are read past: prism's Mitsuba scenes take colour from textures.
        read_vec(3)?;
    }
    let mut faces = Vec::with_capacity(triangles);
    for _ in 0..triangles {
        let mut t = [0u32; 3];
        for i in &mut t {
            *i = r.u32().map_err(|_| short("triangles"))?;
            if *i as usize >= vertices {
                return Err(bad(format!(
                    "mesh {index}: a triangle names vertex {i} of {vertices}"
                )));
            }
        }
        faces.push(t);
    }
    Ok(TriangleMesh {
        name,
        positions: positions
            .chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect(),
        normals: normals
            .chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect(),
        uvs: uvs.chunks_exact(2).map(|c| Vec2::new(c[0], c[1])).collect(),
        triangles: faces,
        face_normals: flags & FACE_NORMALS != 0,
        ..TriangleMesh::default()
    })
}

fn bad(reason: String) -> LoadError {
    LoadError::Geometry(format!("serialized mesh: {reason}"))
}

/// Little-endian reads that fail, rather than panic, past the end.
struct Reader<'a> {
    bytes: &'a [u8],
}

impl<'a> Reader<'a> {
    fn new(bytes: &'a [u8]) -> Self {
        Self { bytes }
    }

    fn remaining(&self) -> usize {
        self.bytes.len()
    }

    fn take<const K: usize>(&mut self) -> Result<[u8; K], ()> {
        let (head, rest) = self.bytes.split_first_chunk::<K>().ok_or(())?;
        self.bytes = rest;
        Ok(*head)
    }

    fn u16(&mut self) -> Result<u16, ()> {
        self.take().map(u16::from_le_bytes)
    }

    fn u32(&mut self) -> Result<u32, ()> {
        self.take().map(u32::from_le_bytes)
    }

    fn u64(&mut self) -> Result<u64, ()> {
        self.take().map(u64::from_le_bytes)
    }

    fn f32(&mut self) -> Result<f32, ()> {
        self.take().map(f32::from_le_bytes)
    }

    fn f64(&mut self) -> Result<f64, ()> {
        self.take().map(f64::from_le_bytes)
    }

    fn c_string(&mut self) -> Result<String, ()> {
        let end = self.bytes.iter().position(|&b| b == 0).ok_or(())?;
        let text = String::from_utf8_lossy(&self.bytes[..end]).into_owned();
        self.bytes = &self.bytes[end + 1..];
        Ok(text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// One mesh as the format lays it out, before compression.
    struct Plain<'a> {
        flags: u32,
        name: &'a str,
        positions: &'a [f64],
        normals: &'a [f64],
        uvs: &'a [f64],
        colors: &'a [f64],
        triangles: &'a [u32],
    }

    /// A file of `meshes` in `version`, written by the format's description (not by the
    /// reader's code): header, zlib stream, and for several meshes the dictionary.
    fn file(version: u16, meshes: &[Plain]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut offsets = Vec::new();
        for m in meshes {
            offsets.push(out.len() as u64);
            out.extend(FORMAT.to_le_bytes());
            out.extend(version.to_le_bytes());
            let mut plain = Vec::new();
            plain.extend(m.flags.to_le_bytes());
            if version == 4 {
                plain.extend(m.name.as_bytes());
                plain.push(0);
            }
            plain.extend(((m.positions.len() / 3) as u64).to_le_bytes());
            plain.extend(((m.triangles.len() / 3) as u64).to_le_bytes());
            for values in [m.positions, m.normals, m.uvs, m.colors] {
                for &v in values {
                    if m.flags & DOUBLE_PRECISION != 0 {
                        plain.extend(v.to_le_bytes());
                    } else {
                        plain.extend((v as f32).to_le_bytes());
                    }
                }
            }
            for &i in m.triangles {
                plain.extend(i.to_le_bytes());
            }
            out.extend(miniz_oxide::deflate::compress_to_vec_zlib(&plain, 6));
        }
        for o in &offsets {
            if version == 4 {
                out.extend(o.to_le_bytes());
            } else {
                out.extend((*o as u32).to_le_bytes());
            }
        }
        out.extend((meshes.len() as u32).to_le_bytes());
        out
    }

    const QUAD: [f64; 12] = [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.];
    const QUAD_TRIANGLES: [u32; 6] = [0, 1, 2, 0, 2, 3];

    fn quad(flags: u32, name: &str) -> Plain<'_> {
        Plain {
            flags,
            name,
            positions: &QUAD,
            normals: &[],
            uvs: &[],
            colors: &[],
            triangles: &QUAD_TRIANGLES,
        }
    }

    #[test]
    fn a_mesh_reads_back_in_either_precision() {
        for flags in [0x1000, DOUBLE_PRECISION] {
            let mesh = read(&file(4, &[quad(flags, "quad")]), 0).unwrap();
            assert_eq!(mesh.name, "quad");
            assert_eq!(mesh.positions[2], Vec3::new(1.0, 1.0, 0.0));
            assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
            assert!(mesh.normals.is_empty() && mesh.uvs.is_empty() && !mesh.face_normals);
        }
    }

    #[test]
    fn normals_and_texture_coordinates_are_read_and_colours_read_past() {
        let normals = [0., 0., 1., 0., 0., 1., 0., 0., 1., 0., 0., 1.];
        let uvs = [0., 0., 1., 0., 1., 1., 0., 1.];
        let colors = [0.5; 12];
        let plain = Plain {
            normals: &normals,
            uvs: &uvs,
            colors: &colors,
            ..quad(
                HAS_NORMALS | HAS_TEXCOORDS | HAS_COLORS | FACE_NORMALS,
                "lit",
            )
        };
        let mesh = read(&file(4, &[plain]), 0).unwrap();
        assert_eq!(mesh.normals, vec![Vec3::Z; 4]);
        assert_eq!(mesh.uvs[2], Vec2::new(1.0, 1.0));
        assert_eq!(mesh.triangles.len(), 2);
        assert!(mesh.face_normals);
    }

    #[test]
    fn the_dictionary_finds_each_mesh_in_both_versions() {
        let shifted: Vec<f64> = QUAD.iter().map(|v| v + 10.0).collect();
        let second = Plain {
            positions: &shifted,
            ..quad(0, "second")
        };
        for version in [3, 4] {
            let bytes = file(version, &[quad(0, "first"), second.clone_plain()]);
            let a = read(&bytes, 0).unwrap();
            let b = read(&bytes, 1).unwrap();
            assert_eq!(a.positions[0], Vec3::ZERO, "version {version}");
            assert_eq!(b.positions[0], Vec3::splat(10.0), "version {version}");
            assert!(read(&bytes, 2).unwrap_err().to_string().contains("holds 2"));
        }
    }

    impl Plain<'_> {
        fn clone_plain(&self) -> Plain<'_> {
            Plain { ..*self }
        }
    }

    #[test]
    fn bad_files_are_one_line_errors() {
        let good = file(4, &[quad(0, "q")]);
        let error = |bytes: &[u8]| read(bytes, 0).unwrap_err().to_string();
        assert!(error(b"").contains("header"));
        assert!(error(&[0x1C, 0x05, 4, 0]).contains("identifier"));
        assert!(error(&[0x1C, 0x04, 9, 0]).contains("version 9"));
        assert!(error(&good[..good.len() / 2]).contains("mesh 0"));
        let bad_index = Plain {
            triangles: &[0, 1, 7],
            ..quad(0, "q")
        };
        assert!(error(&file(4, &[bad_index])).contains("vertex 7"));
        let not_finite = [f64::NAN; 12];
        let nan = Plain {
            positions: &not_finite,
            ..quad(0, "q")
        };
        assert!(error(&file(4, &[nan])).contains("not finite"));
        for e in [error(b""), error(&good[..good.len() / 2])] {
            assert!(!e.contains('\n'), "{e}");
        }
    }

    /// A 60-byte file that claims 2^40 vertices is refused before anything is allocated.
    #[test]
    fn declared_counts_beyond_the_data_are_refused() {
        let mut plain = Vec::new();
        plain.extend(0u32.to_le_bytes());
        plain.push(0);
        plain.extend((1u64 << 40).to_le_bytes());
        plain.extend(1u64.to_le_bytes());
        let mut bytes = vec![0x1C, 0x04, 4, 0];
        bytes.extend(miniz_oxide::deflate::compress_to_vec_zlib(&plain, 6));
        let e = read(&bytes, 0).unwrap_err().to_string();
        assert!(e.contains("1099511627776 vertices"), "{e}");
        // The counts at u64's end overflow the arithmetic, and are refused the same way.
        let mut plain = Vec::new();
        plain.extend(DOUBLE_PRECISION.to_le_bytes());
        plain.push(0);
        plain.extend(u64::MAX.to_le_bytes());
        plain.extend(u64::MAX.to_le_bytes());
        let mut bytes = vec![0x1C, 0x04, 4, 0];
        bytes.extend(miniz_oxide::deflate::compress_to_vec_zlib(&plain, 6));
        assert!(read(&bytes, 0).is_err());
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        /// Random bytes, and a valid file with bytes flipped or cut, never panic.
        #[test]
        fn no_input_panics(
            noise in proptest::collection::vec(any::<u8>(), 0..256),
            flips in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 0..8),
            cut in any::<prop::sample::Index>(),
            index in 0usize..3,
        ) {
            let _ = read(&noise, index);
            let mut bytes = file(4, &[quad(HAS_NORMALS, "q"), quad(0, "r")]);
            for (at, value) in &flips {
                let i = at.index(bytes.len());
                bytes[i] ^= value;
            }
            let _ = read(&bytes, index);
            let _ = read(&bytes[..cut.index(bytes.len())], index);
        }
    }
}
