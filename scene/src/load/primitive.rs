//! One glTF triangle primitive into the loaded geometry: its attributes read, morphed and
//! checked against each other (`Attributes::read`), then placed in the world (`place`):
//! positions by the node's matrix, normals by its inverse transpose, tangents (the file's,
//! else MikkTSpace's, else each triangle's) where a material needs them, and the winding
//! kept under mirroring.

use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};

use super::geometry::{LoadedGeometry, MeshInstance, node_name, note, warn_once};
use super::tex_coord_sets::TexCoordSets;
use super::{LoadError, accessor};
use crate::geometry::triangle_normal;
use crate::materials::triangle_tangent;

/// A primitive's vertex attributes as read: morphed to the default weights, every list as
/// long as `positions` and every index within it.
struct Attributes {
    positions: Vec<Vec3>,
    indices: Vec<u32>,
    normals: Option<Vec<Vec3>>,
    /// The texture coordinate sets the material's textures read: its first, and a second.
    uvs: Option<Vec<Vec2>>,
    uvs1: Option<Vec<Vec2>>,
    tangents: Option<Vec<Vec4>>,
    colors: Option<Vec<Vec4>>,
}

/// Adds the triangles of `primitive`, placed by `node` with its world matrix `world`, to
/// `out`: an error where the primitive cannot be read as glTF 2.0 says it must be.
pub(super) fn add_primitive(
    out: &mut LoadedGeometry,
    node: &gltf::Node,
    primitive: &gltf::Primitive,
    world: Mat4,
    buffers: &[Vec<u8>],
    weights: &[f32],
) -> Result<(), LoadError> {
    let name = node_name(node);
    if primitive.mode() != gltf::mesh::Mode::Triangles {
        return Err(LoadError::Geometry(format!(
            "{name}: primitive mode {:?} is not supported (only TRIANGLES)",
            primitive.mode()
        )));
    }
    let material = primitive.material();
    let sets = TexCoordSets::of(&material);
    if let Some(w) = sets.warning(material.name().unwrap_or("(unnamed)")) {
        warn_once(&mut out.warnings, &format!("{name}: {w}"));
    }
    let attributes = Attributes::read(out, &name, primitive, &sets, buffers, weights)?;
    let first = out.triangles.len();
    place(out, &material, &sets, &attributes, world);
    out.instances.push(MeshInstance {
        node: name,
        material: primitive.material().index(),
        first,
        count: out.triangles.len() - first,
    });
    Ok(())
}

impl Attributes {
    /// The attributes of `primitive` (node `name`), each checked before the glTF reader
    /// reads it (it trusts the document, and would panic where a file lies), the features
    /// they use noted in `out`.
    fn read(
        out: &mut LoadedGeometry,
        name: &str,
        primitive: &gltf::Primitive,
        sets: &TexCoordSets,
        buffers: &[Vec<u8>],
        weights: &[f32],
    ) -> Result<Self, LoadError> {
        check_accessors(primitive, sets, name, buffers)?;
        let morph_targets = primitive.morph_targets().next().is_some();
        // Morphed to the default weights where the primitive has targets.
        let morphed = |normals: bool, values: Vec<Vec3>| {
            if morph_targets {
                morph(primitive, weights, normals, values, buffers)
            } else {
                values
            }
        };
        let positions = read_positions(primitive, name, buffers)?;
        if morph_targets {
            note(&mut out.gltf_features, "morph targets (default weights)");
            warn_once(
                &mut out.warnings,
                "morph targets are rendered at their default weights",
            );
        }
        let positions = morphed(false, positions);
        if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
            return Err(LoadError::Geometry(format!(
                "{name}: position {i} is not finite"
            )));
        }
        let indices = read_indices(primitive, name, buffers, positions.len())?;
        let per_vertex = PerVertex {
            primitive,
            buffers,
            name,
            count: positions.len(),
        };
        let normals = per_vertex
            .accessor(gltf::Semantic::Normals)
            .and_then(|a| accessor::read_f32::<3>(&a, buffers))
            .map(|n| morphed(true, n.into_iter().map(Vec3::from).collect()));
        let normals = per_vertex.counted(normals, "NORMAL")?;
        let uvs = per_vertex.uvs(sets.first())?;
        let uvs1 = match sets.second() {
            Some(set) => {
                let second = per_vertex.uvs(set)?;
                if second.is_none() {
                    warn_once(
                        &mut out.warnings,
                        &format!(
                            "{name}: a texture reads TEXCOORD_{set}, which the primitive does not have; it reads TEXCOORD_{} instead",
                            sets.first()
                        ),
                    );
                }
                second
            }
            None => None,
        };
        let tangents = per_vertex
            .accessor(gltf::Semantic::Tangents)
            .and_then(|a| accessor::read_f32::<4>(&a, buffers))
            .map(|t| t.into_iter().map(Vec4::from).collect());
        let tangents = per_vertex.counted(tangents, "TANGENT")?;
        let colors = vertex_colors(primitive, buffers);
        note_features(out, primitive, sets, colors.is_some());
        let colors = per_vertex.counted(colors, "COLOR_0")?;
        Ok(Self {
            positions,
            indices,
            normals,
            uvs,
            uvs1,
            tangents,
            colors,
        })
    }
}

/// Checks the accessors of the attributes prism reads, and the indices', before the glTF
/// reader reads them: it trusts the document, and what it would panic on is an error here.
fn check_accessors(
    primitive: &gltf::Primitive,
    sets: &TexCoordSets,
    name: &str,
    buffers: &[Vec<u8>],
) -> Result<(), LoadError> {
    for (semantic, expected) in [
        (gltf::Semantic::Positions, &accessor::POSITION),
        (gltf::Semantic::Normals, &accessor::NORMAL),
        (gltf::Semantic::Tangents, &accessor::TANGENT),
        (gltf::Semantic::TexCoords(sets.first()), &accessor::TEXCOORD),
        (
            gltf::Semantic::TexCoords(sets.second().unwrap_or(sets.first())),
            &accessor::TEXCOORD,
        ),
        (gltf::Semantic::Colors(0), &accessor::COLOR),
    ] {
        if let Some(a) = primitive.get(&semantic) {
            accessor::check(&a, expected, name, buffers)?;
        }
    }
    if let Some(a) = primitive.indices() {
        accessor::check(&a, &accessor::INDICES, name, buffers)?;
    }
    Ok(())
}

/// The primitive's positions, before morphing (quantized ones, KHR_mesh_quantization,
/// read as floats like any other).
fn read_positions(
    primitive: &gltf::Primitive,
    name: &str,
    buffers: &[Vec<u8>],
) -> Result<Vec<Vec3>, LoadError> {
    let Some(a) = primitive.get(&gltf::Semantic::Positions) else {
        return Err(LoadError::Geometry(format!(
            "{name}: a primitive has no POSITION attribute"
        )));
    };
    let positions = accessor::read_f32::<3>(&a, buffers).ok_or_else(|| {
        LoadError::Geometry(format!(
            "{name}: POSITION accessor {} cannot be read (it runs past its buffer view or buffer)",
            a.index()
        ))
    })?;
    Ok(positions.into_iter().map(Vec3::from).collect())
}

/// The primitive's triangle indices into its `count` vertices (0, 1, 2, ... where it has
/// none), each checked to be within them.
fn read_indices(
    primitive: &gltf::Primitive,
    name: &str,
    buffers: &[Vec<u8>],
    count: usize,
) -> Result<Vec<u32>, LoadError> {
    let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
    let indices: Vec<u32> = match (reader.read_indices(), primitive.indices()) {
        (Some(i), _) => i.into_u32().collect(),
        (None, None) => (0..count as u32).collect(),
        // Declared but unreadable: not a non-indexed primitive.
        (None, Some(accessor)) => {
            return Err(LoadError::Geometry(format!(
                "{name}: index accessor {} cannot be read (it runs past its buffer view or buffer)",
                accessor.index()
            )));
        }
    };
    if !indices.len().is_multiple_of(3) {
        return Err(LoadError::Geometry(format!(
            "{name}: {} indices do not form triangles",
            indices.len()
        )));
    }
    if let Some(bad) = indices.iter().find(|&&i| i as usize >= count) {
        return Err(LoadError::Geometry(format!(
            "{name}: index {bad} is past the {count} vertices"
        )));
    }
    Ok(indices)
}

/// Reads a primitive's optional per-vertex attributes, each of which must have one entry
/// per vertex.
struct PerVertex<'p, 'b> {
    primitive: &'p gltf::Primitive<'p>,
    buffers: &'b [Vec<u8>],
    name: &'p str,
    /// Vertices (positions).
    count: usize,
}

impl PerVertex<'_, '_> {
    /// The accessor of attribute `semantic`, if the primitive has it.
    fn accessor(&self, semantic: gltf::Semantic) -> Option<gltf::Accessor<'_>> {
        self.primitive.get(&semantic)
    }

    /// `values` of attribute `what`, if read, provided there is one per vertex.
    fn counted<T>(&self, values: Option<Vec<T>>, what: &str) -> Result<Option<Vec<T>>, LoadError> {
        match values {
            Some(v) if v.len() != self.count => Err(self.miscounted(what, v.len())),
            values => Ok(values),
        }
    }

    /// Texture coordinate set `set`, if present.
    fn uvs(&self, set: u32) -> Result<Option<Vec<Vec2>>, LoadError> {
        let uvs = self
            .accessor(gltf::Semantic::TexCoords(set))
            .and_then(|a| accessor::read_f32::<2>(&a, self.buffers));
        let uvs = self.counted(uvs, &format!("TEXCOORD_{set}"))?;
        Ok(uvs.map(|t| t.into_iter().map(Vec2::from).collect()))
    }

    /// The error for an attribute `what` of `n` entries.
    fn miscounted(&self, what: &str, n: usize) -> LoadError {
        LoadError::Geometry(format!(
            "{}: {what} has {n} entries for {} vertices",
            self.name, self.count
        ))
    }
}

/// Notes the glTF features a primitive's attributes use (vertex colours, texture sets
/// past the first, no indices, sparse accessors).
fn note_features(
    out: &mut LoadedGeometry,
    primitive: &gltf::Primitive,
    sets: &TexCoordSets,
    colors: bool,
) {
    if colors {
        note(&mut out.gltf_features, "COLOR_0");
    }
    for set in [Some(sets.first()), sets.second()].into_iter().flatten() {
        if set > 0 {
            note(&mut out.gltf_features, &format!("TEXCOORD_{set}"));
        }
    }
    if primitive.indices().is_none() {
        note(&mut out.gltf_features, "non-indexed primitives");
    }
    if primitive.attributes().any(|(_, a)| a.sparse().is_some()) {
        note(&mut out.gltf_features, "sparse accessors");
    }
}

/// Appends the primitive's triangles to `out`, placed by `world`, with the attributes the
/// scene keeps (an attribute list stays empty until some primitive has it).
fn place(
    out: &mut LoadedGeometry,
    material: &gltf::Material,
    sets: &TexCoordSets,
    attributes: &Attributes,
    world: Mat4,
) {
    let Attributes {
        positions,
        indices,
        normals,
        uvs,
        uvs1,
        tangents,
        colors,
    } = attributes;
    // Normals transform by the inverse transpose (correct under non-uniform scale and
    // mirroring), tangents (directions in the surface) by the matrix itself.
    let linear = Mat3::from_mat4(world);
    let normal_matrix = linear.inverse().transpose();
    // A mirroring transform flips the winding; swapping two vertices restores it so that
    // front faces stay front faces.
    let mirrored = world.determinant() < 0.0;
    let order = |t: [usize; 3]| if mirrored { [t[0], t[2], t[1]] } else { t };
    let first = out.triangles.len();
    // Attribute lists stay empty until a primitive has the attribute; the triangles before
    // it then get the defaults. Most scenes have no texture coordinates and many no
    // normals: 60 bytes a triangle that would be kept and interpolated at every hit.
    let keep_normals = normals.is_some() || !out.normals.is_empty();
    if keep_normals {
        let from = out.normals.len();
        let flat = |t: &[Vec3; 3]| [triangle_normal(*t); 3];
        out.normals.extend(out.triangles[from..].iter().map(flat));
    }
    let keep_uvs = uvs.is_some() || uvs1.is_some() || !out.uvs.is_empty();
    if keep_uvs {
        out.uvs.resize(first, [Vec2::ZERO; 3]);
    }
    // The second set stays empty until a primitive reads one; the triangles before it
    // then get their first set's.
    let keep_uvs1 = uvs1.is_some() || !out.uvs1.is_empty();
    if keep_uvs1 && out.uvs1.len() < first {
        let from = out.uvs1.len();
        let copied: Vec<[Vec2; 3]> = out.uvs[from..first].to_vec();
        out.uvs1.extend(copied);
    }
    let keep_colors = colors.is_some() || !out.colors.is_empty();
    if keep_colors {
        out.colors.resize(first, [Vec4::ONE; 3]);
    }
    // Tangents serve normal maps, anisotropy and a coat's normal texture.
    let normal_mapped = material.normal_texture().is_some() || oriented(material);
    let keep_tangents = normal_mapped || !out.tangents.is_empty();
    if keep_tangents {
        out.tangents.resize(first, [Vec4::ZERO; 3]);
    }
    // Under mirroring the normal x tangent flips relative to the mirrored bitangent.
    let handedness = if mirrored { -1.0 } else { 1.0 };
    let triangles = indices.len() / 3;
    out.triangles.reserve(triangles);
    out.normals
        .reserve(if keep_normals { triangles } else { 0 });
    out.uvs.reserve(if keep_uvs { triangles } else { 0 });
    out.tangents
        .reserve(if keep_tangents { triangles } else { 0 });
    // Without TANGENT, a normal-mapped primitive gets MikkTSpace's (per corner, in the
    // primitive's own space), as glTF asks.
    // Tangents follow the u direction of the set the normal texture reads.
    let normal_set = material
        .normal_texture()
        .map_or(0, |n| sets.slot(super::tex_coord_sets::normal_set(&n)));
    let normal_uvs = if normal_set == 1 && uvs1.is_some() {
        uvs1
    } else {
        uvs
    };
    let mikktspace = match (tangents, normal_uvs) {
        (None, Some(uvs)) if normal_mapped => {
            super::tangents::mikktspace(positions, normals.as_deref(), uvs, indices)
        }
        _ => None,
    };
    let corners = if mirrored { [0, 2, 1] } else { [0, 1, 2] };
    for (face, tri) in indices.chunks_exact(3).enumerate() {
        let t = order([tri[0] as usize, tri[1] as usize, tri[2] as usize]);
        let v = t.map(|i| world.transform_point3(positions[i]));
        out.triangles.push(v);
        if keep_normals {
            let geometric = triangle_normal(v);
            out.normals.push(match normals {
                // Unusable normals (zero, non-finite) fall back to the face's own.
                Some(n) => t.map(|i| {
                    let w = (normal_matrix * n[i]).normalize_or_zero();
                    if w == Vec3::ZERO { geometric } else { w }
                }),
                None => [geometric; 3],
            });
        }
        let corner_uvs = |uvs: &Option<Vec<Vec2>>| {
            uvs.as_ref()
                .map(|uv| t.map(|i| if uv[i].is_finite() { uv[i] } else { Vec2::ZERO }))
        };
        let uv = corner_uvs(uvs).unwrap_or([Vec2::ZERO; 3]);
        let uv1 = corner_uvs(uvs1).unwrap_or(uv);
        if keep_uvs {
            out.uvs.push(uv);
        }
        if keep_uvs1 {
            out.uvs1.push(uv1);
        }
        let tangent_uv = if normal_set == 1 { uv1 } else { uv };
        if keep_colors {
            out.colors.push(match colors {
                // Colours are linear factors in [0, 1]; anything else is clamped.
                Some(c) => t.map(|i| {
                    let v = c[i];
                    if v.is_finite() {
                        v.clamp(Vec4::ZERO, Vec4::ONE)
                    } else {
                        Vec4::ONE
                    }
                }),
                None => [Vec4::ONE; 3],
            });
        }
        if keep_tangents {
            out.tangents.push(if normal_mapped {
                let derived = triangle_tangent(v, tangent_uv, triangle_normal(v));
                // A tangent of the primitive's space in world space; unusable ones (zero,
                // non-finite) fall back to the triangle's derived tangent.
                let placed = |tangent: Vec4| {
                    let d = (linear * tangent.truncate()).normalize_or_zero();
                    let sign = if tangent.w < 0.0 { -1.0 } else { 1.0 };
                    if d == Vec3::ZERO {
                        derived
                    } else {
                        d.extend(sign * handedness)
                    }
                };
                match (tangents, &mikktspace) {
                    (Some(tangent), _) => t.map(|i| placed(tangent[i])),
                    (None, Some(mikk)) => corners.map(|c| mikk[face][c].map_or(derived, placed)),
                    (None, None) => [derived; 3],
                }
            } else {
                [Vec4::ZERO; 3]
            });
        }
    }
}

/// `COLOR_0` as linear RGBA (alpha 1 for RGB colours), if the primitive has it.
fn vertex_colors(primitive: &gltf::Primitive, buffers: &[Vec<u8>]) -> Option<Vec<Vec4>> {
    let a = primitive.get(&gltf::Semantic::Colors(0))?;
    match a.dimensions() {
        gltf::accessor::Dimensions::Vec3 => accessor::read_f32::<3>(&a, buffers)
            .map(|c| c.into_iter().map(|c| Vec3::from(c).extend(1.0)).collect()),
        _ => accessor::read_f32::<4>(&a, buffers).map(|c| c.into_iter().map(Vec4::from).collect()),
    }
}

/// `values` displaced by the primitive's morph targets of `semantic` (POSITION or NORMAL)
/// at `weights` (the node's, else the mesh's default weights): the shape a viewer shows
/// before any animation plays.
fn morph(
    primitive: &gltf::Primitive,
    weights: &[f32],
    normals: bool,
    mut values: Vec<Vec3>,
    buffers: &[Vec<u8>],
) -> Vec<Vec3> {
    for (target, &w) in primitive.morph_targets().zip(weights) {
        let accessor = if normals {
            target.normals()
        } else {
            target.positions()
        };
        let deltas = accessor
            .filter(|a| accessor::check(a, &accessor::MORPH_TARGET, "", buffers).is_ok())
            .and_then(|a| accessor::read_f32::<3>(&a, buffers));
        if w == 0.0 || !w.is_finite() {
            continue;
        }
        if let Some(deltas) = deltas.filter(|d| d.len() == values.len()) {
            for (v, d) in values.iter_mut().zip(deltas) {
                *v += w * Vec3::from(d);
            }
        }
    }
    values
}

/// Whether a material's extensions need the surface's tangents (anisotropy's direction, a
/// coat's normal texture).
fn oriented(material: &gltf::Material) -> bool {
    material
        .extension_value("KHR_materials_anisotropy")
        .is_some()
        || material
            .extension_value("KHR_materials_clearcoat")
            .is_some_and(|c| c.get("clearcoatNormalTexture").is_some())
}
