//! Stanford PLY meshes as Mitsuba 3's `ply` shape reads them (mitsuba3,
//! `src/shapes/ply.cpp`): ASCII, binary little endian and binary big endian; positions,
//! normals, texture coordinates and the other vertex and face properties as named
//! attributes (`vertex_color`, `face_weight`..., see `ply_header`). Faces of
//! more than three corners are cut into a fan from their first corner (Mitsuba reads
//! only triangles), each triangle keeping its face's attributes. Elements other than
//! `vertex` and `face` are read past.
//!
//! Integer properties are read as Mitsuba's header declares them (`Normalized | Gamma`):
//! divided by the type's largest value and decoded from sRGB to linear, so an 8-bit
//! colour 128 is 0.2158. (Mitsuba 3.9 itself leaves `uchar` values unscaled, 128 stays
//! 128, though its own warning says colours are expected in [0, 1]: prism follows the
//! declaration, and says so.)
//!
//! Before anything is allocated, the counts the header declares are checked against the
//! bytes after it: each element's items need at least their scalars' bytes (binary) or
//! one number each (ASCII). Data left after the last element is an error, as in Mitsuba.

use glam::{Vec2, Vec3};

use super::ply_header::{Element, Format, Kind, Layout, Role, Scalar, layout};
use super::{MeshAttribute, TriangleMesh};
use crate::LoadError;

/// Reads the PLY file `bytes`; `flip_tex_coords` turns each texture coordinate's v into
/// 1 - v (Mitsuba's `flip_tex_coords`, false by default for PLY).
///
/// ```
/// # #[cfg(feature = "mitsuba")] {
/// use prism_scene::load::meshes::ply;
///
/// let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n\
///             property float y\nproperty float z\nelement face 1\n\
///             property list uchar int vertex_indices\nend_header\n\
///             0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
/// let mesh = ply::read(text.as_bytes(), false).unwrap();
/// assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
/// # }
/// ```
pub fn read(bytes: &[u8], flip_tex_coords: bool) -> Result<TriangleMesh, LoadError> {
    let layout = layout(bytes)?;
    let body = &bytes[layout.body..];
    check_counts(&layout, body.len())?;
    let vertices = layout
        .elements
        .iter()
        .find(|e| e.name == "vertex")
        .map_or(0, |e| e.count);
    let vertices = u32::try_from(vertices)
        .map_err(|_| LoadError::Geometry(format!("PLY: {vertices} vertices (at most 2^32)")))?;
    let mut source = match layout.format {
        Format::Ascii => Source::Ascii(Ascii { text: body, at: 0 }),
        Format::LittleEndian => Source::Binary(Binary {
            bytes: body,
            at: 0,
            big: false,
        }),
        Format::BigEndian => Source::Binary(Binary {
            bytes: body,
            at: 0,
            big: true,
        }),
    };
    let mut mesh = Builder::new(&layout, vertices, flip_tex_coords);
    for element in &layout.elements {
        for item in 0..element.count {
            if let Err(reason) = read_item(&mut source, element, &mut mesh) {
                return Err(source_error(
                    &source,
                    &element.name,
                    item,
                    element.count,
                    &reason,
                ));
            }
        }
    }
    if !source.at_end() {
        return Err(LoadError::Geometry(
            "PLY: data is left after the last element".into(),
        ));
    }
    Ok(mesh.finish(layout))
}

/// Reads one item of `element` into `mesh`.
fn read_item(source: &mut Source, element: &Element, mesh: &mut Builder) -> Result<(), String> {
    for property in &element.properties {
        match property.kind {
            Kind::Scalar(scalar) => {
                let value = source.scalar(scalar)?;
                mesh.scalar(property.role, value, scalar);
            }
            Kind::List { count, item } => {
                let n = source.scalar(count)?.as_index()?;
                if property.role == Role::Indices {
                    mesh.face.clear();
                }
                for _ in 0..n {
                    let v = source.scalar(item)?;
                    if property.role == Role::Indices {
                        mesh.corner(v.as_index()?)?;
                    }
                }
            }
        }
    }
    mesh.end_item(&element.name)
}

/// Refuses a header that declares more items than the data can hold.
fn check_counts(layout: &Layout, available: usize) -> Result<(), LoadError> {
    let mut needed = 0u64;
    for e in &layout.elements {
        needed = e
            .count
            .checked_mul(e.least(layout.format))
            .and_then(|n| needed.checked_add(n))
            .unwrap_or(u64::MAX);
    }
    // ASCII numbers take a byte each and one of whitespace between them.
    let bytes = match layout.format {
        Format::Ascii => needed.saturating_mul(2).saturating_sub(1),
        _ => needed,
    };
    if bytes > available as u64 {
        let declared: Vec<String> = layout
            .elements
            .iter()
            .map(|e| format!("{} '{}'", e.count, e.name))
            .collect();
        return Err(LoadError::Geometry(format!(
            "PLY: the header declares {}, more than the {available} bytes after it hold",
            declared.join(" and ")
        )));
    }
    Ok(())
}

fn source_error(source: &Source, element: &str, item: u64, count: u64, reason: &str) -> LoadError {
    let line = match source {
        Source::Ascii(a) => format!(" (data line {})", a.line()),
        Source::Binary(_) => String::new(),
    };
    LoadError::Geometry(format!("PLY: {element} {item} of {count}{line}: {reason}"))
}

/// A number as the file stores it.
#[derive(Debug, Clone, Copy)]
enum Number {
    Int(i64),
    UInt(u64),
    Float(f64),
}

impl Number {
    /// A list count or vertex index.
    fn as_index(self) -> Result<u32, String> {
        let value = match self {
            Number::Int(i) => u32::try_from(i).ok(),
            Number::UInt(u) => u32::try_from(u).ok(),
            Number::Float(_) => None,
        };
        value.ok_or_else(|| format!("{self:?} is not a count or index"))
    }

    /// The value Mitsuba reads: floats as they are; integers divided by their type's
    /// largest value and decoded from sRGB (its header's `Normalized | Gamma`).
    fn value(self, scalar: Scalar) -> f32 {
        let normalized = match self {
            Number::Float(f) => return f as f32,
            Number::Int(i) => i as f64 / largest(scalar),
            Number::UInt(u) => u as f64 / largest(scalar),
        };
        srgb_to_linear(normalized) as f32
    }
}

fn largest(scalar: Scalar) -> f64 {
    match scalar {
        Scalar::I8 => i8::MAX as f64,
        Scalar::U8 => u8::MAX as f64,
        Scalar::I16 => i16::MAX as f64,
        Scalar::U16 => u16::MAX as f64,
        Scalar::I32 => i32::MAX as f64,
        Scalar::U32 => u32::MAX as f64,
        Scalar::I64 => i64::MAX as f64,
        Scalar::U64 => u64::MAX as f64,
        Scalar::F16 | Scalar::F32 | Scalar::F64 => 1.0,
    }
}

/// The sRGB transfer function's inverse (IEC 61966-2-1), odd below its linear segment's
/// end as Mitsuba applies it to negative values.
fn srgb_to_linear(v: f64) -> f64 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

enum Source<'a> {
    Ascii(Ascii<'a>),
    Binary(Binary<'a>),
}

impl Source<'_> {
    fn scalar(&mut self, scalar: Scalar) -> Result<Number, String> {
        match self {
            Source::Ascii(a) => a.scalar(scalar),
            Source::Binary(b) => b.scalar(scalar),
        }
    }

    fn at_end(&self) -> bool {
        match self {
            Source::Ascii(a) => a.text[a.at..].iter().all(u8::is_ascii_whitespace),
            Source::Binary(b) => b.at == b.bytes.len(),
        }
    }
}

/// Whitespace-separated numbers.
struct Ascii<'a> {
    text: &'a [u8],
    at: usize,
}

impl Ascii<'_> {
    /// The 1-based line of the data (after the header) being read.
    fn line(&self) -> usize {
        1 + self.text[..self.at.min(self.text.len())]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
    }

    fn scalar(&mut self, scalar: Scalar) -> Result<Number, String> {
        let rest = &self.text[self.at..];
        let start = rest
            .iter()
            .position(|b| !b.is_ascii_whitespace())
            .ok_or_else(|| "the file ends".to_string())?;
        let len = rest[start..]
            .iter()
            .position(u8::is_ascii_whitespace)
            .unwrap_or(rest.len() - start);
        let token = &rest[start..start + len];
        self.at += start + len;
        let text = std::str::from_utf8(token).map_err(|_| "a value is not text".to_string())?;
        let bad = || format!("'{text}' is not a {scalar:?} value");
        // Integer types take integers in their range, as Mitsuba's ASCII reader does.
        Ok(match scalar {
            Scalar::F16 | Scalar::F32 | Scalar::F64 => {
                Number::Float(text.parse::<f64>().map_err(|_| bad())?)
            }
            Scalar::U8 | Scalar::U16 | Scalar::U32 | Scalar::U64 => {
                let v = text.parse::<u64>().map_err(|_| bad())?;
                if v as f64 > largest(scalar) {
                    return Err(bad());
                }
                Number::UInt(v)
            }
            _ => {
                let v = text.parse::<i64>().map_err(|_| bad())?;
                let max = largest(scalar);
                if v as f64 > max || (v as f64) < -max - 1.0 {
                    return Err(bad());
                }
                Number::Int(v)
            }
        })
    }
}

/// Binary numbers of either byte order.
struct Binary<'a> {
    bytes: &'a [u8],
    at: usize,
    big: bool,
}

impl Binary<'_> {
    fn take<const K: usize>(&mut self) -> Result<[u8; K], String> {
        let chunk = self
            .bytes
            .get(self.at..)
            .and_then(|r| r.first_chunk::<K>())
            .ok_or_else(|| "the file ends".to_string())?;
        self.at += K;
        let mut out = *chunk;
        if self.big {
            out.reverse();
        }
        Ok(out)
    }

    fn scalar(&mut self, scalar: Scalar) -> Result<Number, String> {
        Ok(match scalar {
            Scalar::I8 => Number::Int(i8::from_le_bytes(self.take()?).into()),
            Scalar::U8 => Number::UInt(u8::from_le_bytes(self.take()?).into()),
            Scalar::I16 => Number::Int(i16::from_le_bytes(self.take()?).into()),
            Scalar::U16 => Number::UInt(u16::from_le_bytes(self.take()?).into()),
            Scalar::I32 => Number::Int(i32::from_le_bytes(self.take()?).into()),
            Scalar::U32 => Number::UInt(u32::from_le_bytes(self.take()?).into()),
            Scalar::I64 => Number::Int(i64::from_le_bytes(self.take()?)),
            Scalar::U64 => Number::UInt(u64::from_le_bytes(self.take()?)),
            Scalar::F16 => Number::Float(half_to_f64(u16::from_le_bytes(self.take()?))),
            Scalar::F32 => Number::Float(f32::from_le_bytes(self.take()?).into()),
            Scalar::F64 => Number::Float(f64::from_le_bytes(self.take()?)),
        })
    }
}

/// An IEEE 754 half-precision number's value.
fn half_to_f64(bits: u16) -> f64 {
    let sign = if bits & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exponent = i32::from((bits >> 10) & 0x1f);
    let fraction = f64::from(bits & 0x3ff);
    sign * match exponent {
        0 => fraction * 2f64.powi(-24),
        31 if fraction == 0.0 => f64::INFINITY,
        31 => f64::NAN,
        e => (1.0 + fraction / 1024.0) * 2f64.powi(e - 15),
    }
}

/// The mesh as the items are read.
struct Builder {
    vertices: u32,
    flip_tex_coords: bool,
    has_normals: bool,
    has_uvs: bool,
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
    triangles: Vec<[u32; 3]>,
    /// Per attribute: where its values sit in `item`, how many, whether per vertex, and
    /// its values so far.
    attributes: Vec<(usize, usize, bool, Vec<f32>)>,
    /// The item being read: position, normal, texture coordinate, attribute values and
    /// a face's corners.
    position: Vec3,
    normal: Vec3,
    uv: Vec2,
    item: Vec<f32>,
    face: Vec<u32>,
    uchar_warned: bool,
    warnings: Vec<String>,
}

impl Builder {
    fn new(layout: &Layout, vertices: u32, flip_tex_coords: bool) -> Self {
        // The counts are checked against the data by now: these allocations are bounded
        // by the file's size.
        let faces = layout
            .elements
            .iter()
            .find(|e| e.name == "face")
            .map_or(0, |e| usize::try_from(e.count).unwrap_or(0));
        let v = vertices as usize;
        let mut offset = 0;
        let attributes = layout
            .attributes
            .iter()
            .map(|a| {
                let per_vertex = a.name.starts_with("vertex_");
                let items = if per_vertex { v } else { faces };
                let entry = (offset, a.dim, per_vertex, Vec::with_capacity(a.dim * items));
                offset += a.dim;
                entry
            })
            .collect();
        Builder {
            vertices,
            flip_tex_coords,
            has_normals: layout.has_normals,
            has_uvs: layout.has_uvs,
            positions: Vec::with_capacity(v),
            normals: Vec::with_capacity(if layout.has_normals { v } else { 0 }),
            uvs: Vec::with_capacity(if layout.has_uvs { v } else { 0 }),
            triangles: Vec::with_capacity(faces),
            attributes,
            position: Vec3::ZERO,
            normal: Vec3::ZERO,
            uv: Vec2::ZERO,
            item: vec![0.0; offset],
            face: Vec::new(),
            uchar_warned: false,
            warnings: Vec::new(),
        }
    }

    fn scalar(&mut self, role: Role, value: Number, scalar: Scalar) {
        if scalar == Scalar::U8 && role != Role::Skip && !self.uchar_warned {
            self.uchar_warned = true;
            self.warnings.push(
                "PLY: 8-bit values are read as fractions of 255 decoded from sRGB, as \
                 Mitsuba's reader declares them (Mitsuba 3.9 itself leaves them unscaled)"
                    .into(),
            );
        }
        let v = value.value(scalar);
        match role {
            Role::Skip | Role::Indices => {}
            Role::Position(k) => self.position[k] = v,
            Role::Normal(k) => self.normal[k] = v,
            Role::Uv(k) => self.uv[k] = v,
            Role::Attribute {
                attribute,
                component,
            } => self.item[self.attributes[attribute].0 + component] = v,
        }
    }

    fn corner(&mut self, index: u32) -> Result<(), String> {
        if index >= self.vertices {
            return Err(format!(
                "vertex index {index}, the file has {} vertices",
                self.vertices
            ));
        }
        self.face.push(index);
        Ok(())
    }

    /// Keeps the item just read: a vertex, or a face's triangles (a fan from its first
    /// corner, each with the face's attributes).
    fn end_item(&mut self, element: &str) -> Result<(), String> {
        let (per_vertex, copies) = match element {
            "vertex" => {
                if !self.position.is_finite() {
                    return Err("a position is not finite".into());
                }
                self.positions.push(self.position);
                if self.has_normals {
                    self.normals.push(self.normal);
                }
                if self.has_uvs {
                    let mut uv = self.uv;
                    if self.flip_tex_coords {
                        uv.y = 1.0 - uv.y;
                    }
                    self.uvs.push(uv);
                }
                (true, 1)
            }
            "face" => {
                if self.face.len() < 3 {
                    return Err(format!("a face of {} corners", self.face.len()));
                }
                let fan = self.face.len() - 2;
                for k in 0..fan {
                    self.triangles
                        .push([self.face[0], self.face[k + 1], self.face[k + 2]]);
                }
                (false, fan)
            }
            _ => return Ok(()),
        };
        for (offset, dim, vertex, values) in &mut self.attributes {
            if *vertex == per_vertex {
                for _ in 0..copies {
                    values.extend_from_slice(&self.item[*offset..*offset + *dim]);
                }
            }
        }
        Ok(())
    }

    fn finish(self, layout: Layout) -> TriangleMesh {
        let mut warnings = layout.warnings;
        warnings.extend(self.warnings);
        TriangleMesh {
            name: String::new(),
            positions: self.positions,
            normals: self.normals,
            uvs: self.uvs,
            triangles: self.triangles,
            face_normals: false,
            attributes: layout
                .attributes
                .into_iter()
                .zip(self.attributes)
                .map(|(spec, (_, dim, _, values))| MeshAttribute {
                    name: spec.name,
                    dim,
                    values,
                })
                .collect(),
            warnings,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const TRIANGLE_HEADER: &str = "element vertex 3\nproperty float x\nproperty float y\n\
                                   property float z\nelement face 1\n\
                                   property list uchar int vertex_indices\n";

    fn ascii(body: &str) -> Vec<u8> {
        format!("ply\nformat ascii 1.0\n{body}").into_bytes()
    }

    fn error(bytes: &[u8]) -> String {
        read(bytes, false).unwrap_err().to_string()
    }

    #[test]
    fn ascii_with_normals_texture_coordinates_and_attributes() {
        let text = ascii(
            "comment a lit triangle\nelement vertex 3\nproperty float x\nproperty float y\n\
             property float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
             property float s\nproperty float t\nproperty float r\nproperty float g\n\
             property float b\nelement face 1\nproperty list uchar uint vertex_indices\n\
             property float weight_0\nend_header\n\
             0 0 0 0 0 1 0 0 1 0 0\n1 0 0 0 0 1 1 0 0 1 0\n\
             0 1 0 0 0 1 0 1 0 0 1\n3 0 1 2 0.25\n",
        );
        let mesh = read(&text, true).unwrap();
        assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
        assert_eq!(mesh.normals, vec![Vec3::Z; 3]);
        // t flipped: 1 - t.
        assert_eq!(mesh.uvs[2], Vec2::new(0.0, 0.0));
        assert_eq!(mesh.uvs[1], Vec2::new(1.0, 1.0));
        let colour = &mesh.attributes[0];
        assert_eq!((colour.name.as_str(), colour.dim), ("vertex_color", 3));
        assert_eq!(&colour.values[3..6], &[0.0, 1.0, 0.0]);
        assert!(colour.per_vertex());
        let weight = &mesh.attributes[1];
        assert_eq!(
            (weight.name.as_str(), weight.values.clone()),
            ("face_weight", vec![0.25])
        );
        assert!(mesh.warnings.is_empty(), "{:?}", mesh.warnings);
    }

    /// A binary file of a quad face (cut into two triangles that keep its colour) with
    /// 8-bit colours and half-precision texture coordinates, in either byte order.
    fn binary(big: bool) -> Vec<u8> {
        let order = if big { "big" } else { "little" };
        let mut bytes = format!(
            "ply\nformat binary_{order}_endian 1.0\nelement vertex 4\nproperty double x\n\
             property double y\nproperty double z\nproperty half u\nproperty half v\n\
             property uchar red\nproperty uchar green\nproperty uchar blue\n\
             element face 1\nproperty list uchar int vertex_indices\nproperty ushort c_r\n\
             property ushort c_g\nproperty ushort c_b\nend_header\n"
        )
        .into_bytes();
        let e = |b: &[u8]| -> Vec<u8> {
            let mut b = b.to_vec();
            if big {
                b.reverse();
            }
            b
        };
        // Half 0.5 is 0x3800, 1.0 is 0x3C00.
        for (p, uv, c) in [
            ([0.0f64, 0.0, 0.0], [0u16, 0], [0u8, 128, 255]),
            ([1.0, 0.0, 0.0], [0x3C00, 0], [0, 0, 0]),
            ([1.0, 1.0, 0.0], [0x3C00, 0x3C00], [0, 0, 0]),
            ([0.0, 1.0, 0.0], [0, 0x3800], [0, 0, 0]),
        ] {
            for v in p {
                bytes.extend(e(&v.to_le_bytes()));
            }
            for v in uv {
                bytes.extend(e(&v.to_le_bytes()));
            }
            bytes.extend(c);
        }
        bytes.push(4);
        for i in [0i32, 1, 2, 3] {
            bytes.extend(e(&i.to_le_bytes()));
        }
        for c in [0u16, 32768, 65535] {
            bytes.extend(e(&c.to_le_bytes()));
        }
        bytes
    }

    #[test]
    fn binary_in_both_byte_orders() {
        for big in [false, true] {
            let mesh = read(&binary(big), false).unwrap();
            assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]], "big {big}");
            assert_eq!(mesh.positions[2], Vec3::new(1.0, 1.0, 0.0));
            assert_eq!(mesh.uvs[3], Vec2::new(0.0, 0.5));
            let colour = &mesh.attributes[0];
            // 128 / 255 decoded from sRGB; 255 is 1.
            assert!(
                (colour.values[1] - 0.215_861).abs() < 1e-5,
                "{:?}",
                colour.values
            );
            assert_eq!(colour.values[2], 1.0);
            let face = &mesh.attributes[1];
            assert_eq!(face.name, "face_c_color");
            // The face's colour on both of its triangles.
            assert_eq!(face.values.len(), 6);
            assert_eq!(face.values[..3], face.values[3..]);
            assert!(
                (face.values[1] - 0.214_04).abs() < 1e-4,
                "{:?}",
                face.values
            );
            assert!(mesh.warnings.iter().any(|w| w.contains("8-bit")));
        }
    }

    #[test]
    fn bad_files_are_one_line_errors() {
        let good = binary(false);
        // Cut anywhere in the data: the element and item are named.
        let cut = error(&good[..good.len() - 3]);
        assert!(cut.contains("face 0 of 1: the file ends"), "{cut}");
        let mut trailing = good.clone();
        trailing.push(0);
        assert!(error(&trailing).contains("left after the last element"));
        let bad_index = ascii(&format!(
            "{TRIANGLE_HEADER}end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"
        ));
        assert!(error(&bad_index).contains("vertex index 3, the file has 3 vertices"));
        let short_face = ascii(&format!(
            "{TRIANGLE_HEADER}end_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"
        ));
        assert!(error(&short_face).contains("a face of 2 corners"));
        let nan = ascii(&format!(
            "{TRIANGLE_HEADER}end_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"
        ));
        assert!(error(&nan).contains("vertex 1 of 3 (data line 2): a position is not finite"));
        let word = ascii(&format!(
            "{TRIANGLE_HEADER}end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 x\n"
        ));
        assert!(
            error(&word).contains("(data line 4): 'x' is not a I32 value"),
            "{}",
            error(&word)
        );
        let big_uchar = ascii(&format!(
            "{TRIANGLE_HEADER}end_header\n0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n"
        ));
        assert!(error(&big_uchar).contains("'300' is not a U8"));
        for e in [cut, error(&word)] {
            assert!(!e.contains('\n'), "{e}");
        }
    }

    /// A few hundred bytes that declare four billion vertices are refused before anything
    /// is allocated for them, in either format.
    #[test]
    fn declared_counts_beyond_the_data_are_refused() {
        for format in ["ascii", "binary_little_endian"] {
            let text = format!(
                "ply\nformat {format} 1.0\nelement vertex 4000000000\nproperty float x\n\
                 property float y\nproperty float z\nelement face 18446744073709551615\n\
                 property list uchar int vertex_indices\nend_header\n0 0 0\n"
            );
            let e = error(text.as_bytes());
            assert!(e.contains("more than the"), "{format}: {e}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        /// Random bytes, and valid files with bytes flipped or cut, never panic.
        #[test]
        fn no_input_panics(
            noise in proptest::collection::vec(any::<u8>(), 0..256),
            flips in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 0..8),
            cut in any::<prop::sample::Index>(),
            big in any::<bool>(),
        ) {
            let _ = read(&noise, false);
            let mut header = b"ply\nformat ascii 1.0\n".to_vec();
            header.extend(&noise);
            let _ = read(&header, false);
            for mut bytes in [binary(big), ascii(&format!("{TRIANGLE_HEADER}end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"))] {
                for (at, value) in &flips {
                    let i = at.index(bytes.len());
                    bytes[i] ^= value;
                }
                let _ = read(&bytes, true);
                let _ = read(&bytes[..cut.index(bytes.len())], false);
            }
        }
    }
}
