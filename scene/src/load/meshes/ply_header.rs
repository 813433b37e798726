//! A PLY file's header, and what Mitsuba 3 makes of each property (mitsuba3,
//! `src/shapes/ply.h` and `ply.cpp`).
//!
//! The header is `ply`, `format ascii|binary_little_endian|binary_big_endian 1.0`, then
//! `element NAME COUNT` lines each followed by its `property TYPE NAME` and `property
//! list COUNT_TYPE ITEM_TYPE NAME` lines, and `end_header`; `comment` and `obj_info`
//! lines anywhere. Types are PLY's (`char`, `uchar`, `short`, `ushort`, `int`, `uint`,
//! `float`, `double`) and the names Mitsuba adds (`int8` ... `float64`, `long`,
//! `ulong`, `half`).
//!
//! Of a `vertex` element Mitsuba reads `x y z`, `nx ny nz`, texture coordinates as `u v`,
//! `texture_u texture_v` or `s t`, and every other property as a named attribute; of a
//! `face` element the `vertex_indices` (or `vertex_index`) list and the other properties
//! as attributes. Attribute names follow its scheme: `r g b [a]` (or `red green blue
//! [alpha]`) are `vertex_color` / `face_color`; consecutive `P_x P_y P_z`, `P_r P_g P_b`,
//! `P_0 P_1 P_2` or `P_1 P_2 P_3` are one three-valued attribute `vertex_P` (`vertex_P_color`
//! for r, g, b), and a lone `P_x` (`P_0`...) a one-valued one; anything else is skipped
//! with a warning.

use crate::LoadError;

/// How the data after the header is stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Format {
    Ascii,
    LittleEndian,
    BigEndian,
}

/// A scalar type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F16,
    F32,
    F64,
}

impl Scalar {
    fn from_name(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "long" | "int64" => Scalar::I64,
            "ulong" | "uint64" => Scalar::U64,
            "half" | "float16" => Scalar::F16,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    /// Bytes in binary files.
    pub(super) fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 | Scalar::F16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::I64 | Scalar::U64 | Scalar::F64 => 8,
        }
    }

    pub(super) fn is_integer(self) -> bool {
        !matches!(self, Scalar::F16 | Scalar::F32 | Scalar::F64)
    }
}

/// A property's type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

/// What a property becomes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Role {
    /// Read past.
    Skip,
    /// Component k of the position.
    Position(usize),
    /// Component k of the normal.
    Normal(usize),
    /// Component k of the texture coordinate.
    Uv(usize),
    /// Component `component` of attribute `attribute` (an index into [`Layout::attributes`]).
    Attribute { attribute: usize, component: usize },
    /// The face's vertex indices.
    Indices,
}

#[derive(Debug, Clone)]
pub(super) struct Property {
    pub(super) name: String,
    pub(super) kind: Kind,
    pub(super) role: Role,
}

#[derive(Debug, Clone)]
pub(super) struct Element {
    pub(super) name: String,
    pub(super) count: u64,
    pub(super) properties: Vec<Property>,
}

impl Element {
    /// The fewest bytes (binary) or whitespace-separated values (ASCII) one item takes:
    /// its scalars, and each list's count with no items.
    pub(super) fn least(&self, format: Format) -> u64 {
        self.properties
            .iter()
            .map(|p| match (format, p.kind) {
                (Format::Ascii, _) => 1,
                (_, Kind::Scalar(s)) => s.size() as u64,
                (_, Kind::List { count, .. }) => count.size() as u64,
            })
            .sum()
    }
}

/// An attribute the properties make: its name (`vertex_color`...) and size.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct AttributeSpec {
    pub(super) name: String,
    pub(super) dim: usize,
}

/// The header, each property's role decided.
#[derive(Debug, Clone)]
pub(super) struct Layout {
    pub(super) format: Format,
    pub(super) elements: Vec<Element>,
    pub(super) attributes: Vec<AttributeSpec>,
    pub(super) has_normals: bool,
    pub(super) has_uvs: bool,
    /// Where the data starts.
    pub(super) body: usize,
    pub(super) warnings: Vec<String>,
}

fn bad(line: usize, reason: impl Into<String>) -> LoadError {
    LoadError::Geometry(format!("PLY header line {line}: {}", reason.into()))
}

/// Reads the header of `bytes` and decides what each property becomes.
pub(super) fn layout(bytes: &[u8]) -> Result<Layout, LoadError> {
    let mut format = None;
    let mut seen_ply = false;
    let mut elements: Vec<Element> = Vec::new();
    let mut at = 0usize;
    let mut number = 0usize;
    loop {
        number += 1;
        let Some(rest) = bytes.get(at..).filter(|r| !r.is_empty()) else {
            return Err(LoadError::Geometry(
                "PLY: the header has no end_header line".into(),
            ));
        };
        let end = rest.iter().position(|&b| b == b'\n');
        let raw = &rest[..end.unwrap_or(rest.len())];
        at += end.map_or(rest.len(), |e| e + 1);
        let line = std::str::from_utf8(raw).map_err(|_| bad(number, "not text"))?;
        let mut tokens = line.split_ascii_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        if !seen_ply && keyword != "ply" && keyword != "comment" {
            return Err(LoadError::Geometry(
                "not a PLY file (it does not start with 'ply')".into(),
            ));
        }
        match keyword {
            "comment" | "obj_info" => continue,
            "ply" if !seen_ply => seen_ply = true,
            "format" if format.is_none() => {
                format = Some(match tokens.next() {
                    Some("ascii") => Format::Ascii,
                    Some("binary_little_endian") => Format::LittleEndian,
                    Some("binary_big_endian") => Format::BigEndian,
                    other => {
                        let other = other.unwrap_or("");
                        return Err(bad(number, format!("unknown format '{other}'")));
                    }
                });
                if tokens.next() != Some("1.0") {
                    return Err(bad(number, "only version 1.0 of the format is read"));
                }
            }
            "element" => {
                let (Some(name), Some(count)) = (tokens.next(), tokens.next()) else {
                    return Err(bad(number, "an element needs a name and a count"));
                };
                let count = count
                    .parse::<u64>()
                    .map_err(|_| bad(number, format!("element count '{count}'")))?;
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    properties: Vec::new(),
                });
            }
            "property" => {
                let element = elements
                    .last_mut()
                    .ok_or_else(|| bad(number, "a property before any element"))?;
                let scalar = |t: Option<&str>| {
                    t.and_then(Scalar::from_name)
                        .ok_or_else(|| bad(number, format!("unknown type '{}'", t.unwrap_or(""))))
                };
                let first = tokens.next();
                let kind = if first == Some("list") {
                    let count = scalar(tokens.next())?;
                    let item = scalar(tokens.next())?;
                    if !count.is_integer() {
                        return Err(bad(number, "a list's count must be an integer type"));
                    }
                    Kind::List { count, item }
                } else {
                    Kind::Scalar(scalar(first)?)
                };
                let name = tokens
                    .next()
                    .ok_or_else(|| bad(number, "a property needs a name"))?;
                element.properties.push(Property {
                    name: name.to_string(),
                    kind,
                    role: Role::Skip,
                });
            }
            "end_header" => break,
            other => return Err(bad(number, format!("unexpected '{other}'"))),
        }
        if tokens.next().is_some() {
            return Err(bad(number, format!("unexpected words after '{keyword}'")));
        }
    }
    let format = format.ok_or_else(|| bad(number, "no format line"))?;
    let mut layout = Layout {
        format,
        elements,
        attributes: Vec::new(),
        has_normals: false,
        has_uvs: false,
        body: at,
        warnings: Vec::new(),
    };
    decide_roles(&mut layout)?;
    Ok(layout)
}

/// Decides what each property of the `vertex` and `face` elements becomes.
fn decide_roles(layout: &mut Layout) -> Result<(), LoadError> {
    let mut vertex_seen = false;
    let mut face_seen = false;
    for e in 0..layout.elements.len() {
        let element = &mut layout.elements[e];
        let find = |element: &Element, name: &str| {
            element
                .properties
                .iter()
                .position(|p| p.name == name && matches!(p.kind, Kind::Scalar(_)))
        };
        let mut taken: Vec<usize> = Vec::new();
        let set = |element: &mut Element, names: &[&str], role: fn(usize) -> Role| {
            let found: Option<Vec<usize>> = names.iter().map(|n| find(element, n)).collect();
            if let Some(found) = &found {
                for (k, &i) in found.iter().enumerate() {
                    element.properties[i].role = role(k);
                }
            }
            found
        };
        let prefix = match element.name.as_str() {
            "vertex" if !vertex_seen => {
                vertex_seen = true;
                let position = set(element, &["x", "y", "z"], Role::Position).ok_or_else(|| {
                    LoadError::Geometry("PLY: vertices without x, y and z".into())
                })?;
                taken.extend(position);
                if let Some(normal) = set(element, &["nx", "ny", "nz"], Role::Normal) {
                    layout.has_normals = true;
                    taken.extend(normal);
                }
                let uv = [["u", "v"], ["texture_u", "texture_v"], ["s", "t"]]
                    .iter()
                    .find_map(|names| set(element, names, Role::Uv));
                if let Some(uv) = uv {
                    layout.has_uvs = true;
                    taken.extend(uv);
                }
                "vertex_"
            }
            "face" if !face_seen => {
                face_seen = true;
                let list = ["vertex_index", "vertex_indices"].iter().find_map(|n| {
                    element
                        .properties
                        .iter()
                        .position(|p| p.name == *n && matches!(p.kind, Kind::List { .. }))
                });
                let Some(list) = list else {
                    return Err(LoadError::Geometry(
                        "PLY: faces without a vertex_indices list".into(),
                    ));
                };
                if let Kind::List { item, .. } = element.properties[list].kind
                    && !item.is_integer()
                {
                    return Err(LoadError::Geometry(
                        "PLY: vertex indices must be integers".into(),
                    ));
                }
                element.properties[list].role = Role::Indices;
                taken.push(list);
                "face_"
            }
            "vertex" | "face" => {
                return Err(LoadError::Geometry(format!(
                    "PLY: a second '{}' element",
                    element.name
                )));
            }
            other => {
                layout
                    .warnings
                    .push(format!("PLY: element '{other}' is read past"));
                continue;
            }
        };
        let element = &mut layout.elements[e];
        for (name, fields) in attributes(prefix, element, &mut taken, &mut layout.warnings) {
            if layout.attributes.iter().any(|a| a.name == name) {
                layout.warnings.push(format!(
                    "PLY: a second attribute '{name}' is read past (the first is read)"
                ));
                continue;
            }
            let attribute = layout.attributes.len();
            layout.attributes.push(AttributeSpec {
                name,
                dim: fields.len(),
            });
            for (component, i) in fields.into_iter().enumerate() {
                element.properties[i].role = Role::Attribute {
                    attribute,
                    component,
                };
            }
        }
    }
    if !vertex_seen || !face_seen {
        return Err(LoadError::Geometry(
            "PLY: a mesh needs a 'vertex' and a 'face' element".into(),
        ));
    }
    Ok(())
}

/// The postfixes of a multi-valued attribute, by position (rows) and scheme (columns):
/// x y z w, r g b a, 0 1 2 3, 1 2 3 4.
const POSTFIXES: [&[u8; 4]; 4] = [b"xr01", b"yg12", b"zb23", b"wa34"];

/// The attributes an element's remaining scalar properties make, named by Mitsuba's
/// scheme (the module's documentation), each with the properties it reads in order.
fn attributes(
    prefix: &str,
    element: &Element,
    taken: &mut Vec<usize>,
    warnings: &mut Vec<String>,
) -> Vec<(String, Vec<usize>)> {
    let mut out = Vec::new();
    let find = |names: &[&str]| -> Option<Vec<usize>> {
        names
            .iter()
            .map(|n| {
                element
                    .properties
                    .iter()
                    .position(|p| p.name == *n && matches!(p.kind, Kind::Scalar(_)))
            })
            .collect()
    };
    // Colours without a prefix.
    let colour = find(&["r", "g", "b"])
        .map(|rgb| (rgb, find(&["a"])))
        .or_else(|| find(&["red", "green", "blue"]).map(|rgb| (rgb, find(&["alpha"]))));
    if let Some((mut fields, alpha)) = colour {
        fields.extend(alpha.into_iter().flatten());
        taken.extend(&fields);
        out.push((format!("{prefix}color"), fields));
    }
    let mut ignored: Vec<&str> = Vec::new();
    let mut seen: Vec<String> = Vec::new();
    // The attribute being read: its prefix, scheme column and properties so far.
    let mut current: Option<(String, usize, Vec<usize>)> = None;
    let flush = |current: &mut Option<(String, usize, Vec<usize>)>,
                 out: &mut Vec<(String, Vec<usize>)>,
                 seen: &mut Vec<String>,
                 warnings: &mut Vec<String>| {
        if let Some((name, column, fields)) = current.take() {
            seen.push(name.clone());
            if fields.len() == 1 || fields.len() == 3 {
                let colour = if column == 1 { "_color" } else { "" };
                out.push((format!("{prefix}{name}{colour}"), fields));
            } else {
                warnings.push(format!(
                    "PLY: attribute '{prefix}{name}' has {} values (1 or 3 are read) and is \
                     read past",
                    fields.len()
                ));
            }
        }
    };
    for (i, property) in element.properties.iter().enumerate() {
        let name = property.name.as_str();
        if taken.contains(&i) || matches!(name, "r" | "g" | "b" | "a") {
            continue;
        }
        if !matches!(property.kind, Kind::Scalar(_)) {
            ignored.push(name);
            continue;
        }
        let split = name
            .rfind('_')
            .map(|at| (&name[..at], &name[at + 1..]))
            .filter(|(_, postfix)| postfix.len() == 1);
        let Some((head, postfix)) = split else {
            ignored.push(name);
            flush(&mut current, &mut out, &mut seen, warnings);
            continue;
        };
        let letter = postfix.as_bytes()[0];
        if current.as_ref().is_some_and(|(p, _, _)| p != head) {
            flush(&mut current, &mut out, &mut seen, warnings);
        }
        match &mut current {
            None => {
                let column = POSTFIXES[0].iter().position(|&c| c == letter);
                match column {
                    Some(column) if !seen.iter().any(|s| s == head) => {
                        current = Some((head.to_string(), column, vec![i]));
                    }
                    _ => ignored.push(name),
                }
            }
            Some((_, column, fields)) => {
                let expected = POSTFIXES.get(fields.len()).map(|row| row[*column]);
                if expected == Some(letter) {
                    fields.push(i);
                } else {
                    // Out of sequence: the whole attribute is read past, as Mitsuba does.
                    warnings.push(format!(
                        "PLY: attribute '{prefix}{head}' has its values out of order and is \
                         read past"
                    ));
                    seen.push(head.to_string());
                    current = None;
                }
            }
        }
    }
    flush(&mut current, &mut out, &mut seen, warnings);
    if !ignored.is_empty() {
        warnings.push(format!(
            "PLY: {} properties read past (not named as Mitsuba names attributes): {}",
            element.name,
            ignored.join(", ")
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(body: &str) -> Result<Layout, LoadError> {
        layout(format!("ply\nformat ascii 1.0\n{body}end_header\n").as_bytes())
    }

    fn names(layout: &Layout) -> Vec<(&str, usize)> {
        layout
            .attributes
            .iter()
            .map(|a| (a.name.as_str(), a.dim))
            .collect()
    }

    const FACES: &str = "element face 1\nproperty list uchar int vertex_indices\n";

    #[test]
    fn roles_of_the_usual_properties() {
        let l = header(&format!(
            "comment made by hand\nelement vertex 3\nproperty float x\nproperty float y\n\
             property float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
             property float texture_u\nproperty float texture_v\n{FACES}"
        ))
        .unwrap();
        assert!(l.has_normals && l.has_uvs);
        let roles: Vec<Role> = l.elements[0].properties.iter().map(|p| p.role).collect();
        assert_eq!(roles[0], Role::Position(0));
        assert_eq!(roles[5], Role::Normal(2));
        assert_eq!(roles[7], Role::Uv(1));
        assert_eq!(l.elements[1].properties[0].role, Role::Indices);
        assert!(l.attributes.is_empty() && l.warnings.is_empty());
    }

    /// The attributes of the file Mitsuba's own mesh_attributes test writes.
    #[test]
    fn attributes_are_named_as_mitsuba_names_them() {
        let l = header(
            "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
             property float color_0\nproperty float color_1\nproperty float color_2\n\
             property uchar red\nproperty uchar green\nproperty uchar blue\n\
             property float n_x\nproperty float m_r\nproperty float m_g\nproperty float m_b\n\
             element face 1\nproperty list uchar int vertex_indices\n\
             property float color_0\nproperty float color_1\nproperty float color_2\n\
             property float weight_0\n",
        )
        .unwrap();
        assert_eq!(
            names(&l),
            vec![
                ("vertex_color", 3),
                ("vertex_n", 1),
                ("vertex_m_color", 3),
                ("face_color", 3),
                ("face_weight", 1),
            ]
        );
        assert!(
            l.warnings
                .iter()
                .any(|w| w.contains("second attribute 'vertex_color'"))
        );
    }

    #[test]
    fn malformed_attributes_are_read_past_with_a_warning() {
        let l = header(&format!(
            "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
             property float p_x\nproperty float p_y\nproperty float q_x\nproperty float q_z\n\
             property float plain\nproperty float long_xy\n{FACES}"
        ))
        .unwrap();
        assert!(l.attributes.is_empty(), "{:?}", l.attributes);
        let all = l.warnings.join(" | ");
        assert!(all.contains("vertex_p' has 2 values"), "{all}");
        assert!(
            all.contains("vertex_q' has its values out of order"),
            "{all}"
        );
        assert!(all.contains("plain, long_xy"), "{all}");
    }

    #[test]
    fn header_errors_are_one_line_with_the_line() {
        let error = |text: &str| layout(text.as_bytes()).unwrap_err().to_string();
        assert!(error("").contains("end_header"));
        assert!(error("solid\n").contains("not a PLY file"));
        assert!(error("ply\nformat binary 1.0\nend_header\n").contains("line 2: unknown format"));
        assert!(error("ply\nformat ascii 2.0\nend_header\n").contains("version 1.0"));
        assert!(
            error("ply\nformat ascii 1.0\nproperty float x\nend_header\n")
                .contains("line 3: a property before any element")
        );
        assert!(
            error("ply\nformat ascii 1.0\nelement vertex -1\nend_header\n")
                .contains("element count '-1'")
        );
        assert!(
            error("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n")
                .contains("unknown type")
        );
        assert!(
            error(&format!(
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n{FACES}end_header\n"
            ))
            .contains("without x, y and z")
        );
        assert!(
            error(
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n\
                 property float z\nend_header\n"
            )
            .contains("needs a 'vertex' and a 'face'")
        );
    }
}
