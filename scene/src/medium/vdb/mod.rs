//! OpenVDB files (`.vdb`), the format smoke and fire simulations are exchanged in
//! (Houdini, Blender, EmberGen; K. Museth, "VDB: High-resolution sparse volumes with
//! dynamic topology", ACM TOG 32(3), 2013).
//!
//! A file is a header (the magic number, the format version, the library version, a
//! UUID), file metadata, and one descriptor per grid giving where its data is. A grid's
//! data is its compression flags, metadata, index-to-world transform, and its sparse tree
//! ([`tree`]). prism reads scalar grids (`float` or `double`, halves included) of the
//! standard 5-4-3 tree in files of format version 222 or later (OpenVDB 3.0 on), with
//! zlib or Blosc compression, and axis-aligned transforms. The layout follows OpenVDB's
//! own reader (`io/Archive.cc`, `io/GridDescriptor.cc`, `math/Maps.h`).
//!
//! The sparse tree becomes a dense [`Grid`] over its nonzero voxels plus one voxel of
//! background on each side, so that the trilinear lookup fades to 0 past the outermost
//! voxel centres as OpenVDB's `BoxSampler` does.

mod blosc;
mod bytes;
mod tree;
mod values;

use glam::{DVec3, UVec3};

use super::grid::Grid;
use bytes::Bytes;
use values::Encoding;

/// "VDB " and four zero bytes, little-endian (`OPENVDB_MAGIC`).
const MAGIC: i64 = 0x5644_4220;
/// The first file version that stores node values with a layout byte and compression
/// per grid (`OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION`, OpenVDB 3.0).
const NODE_MASK_COMPRESSION: u32 = 222;
/// The most voxels a dense copy of a grid may have (1 GiB of floats).
const MAX_VOXELS: u64 = 1 << 28;
/// The separator OpenVDB puts between a grid's name and the counter that makes it unique
/// (`GridDescriptor::SEP`).
const NAME_SEPARATOR: char = '\u{1e}';

/// Where a grid is in the file.
struct Descriptor {
    name: String,
    kind: String,
    instance_of: String,
    grid_at: u64,
}

/// Reads the scalar grid `name` of an OpenVDB file; without a name, the grid named
/// `usual` (say "density") or the file's only grid. Every malformation, and every grid
/// prism cannot use as a density (vectors, level sets, a nonzero background), is an error
/// that says what is wrong.
pub fn read_vdb(data: &[u8], name: Option<&str>, usual: &str) -> Result<Grid, String> {
    let mut bytes = Bytes::new(data);
    if data.len() < 8 || bytes.i64("the header")? != MAGIC {
        return Err("not an OpenVDB file (it must start with \"VDB \")".into());
    }
    let version = bytes.u32("the header")?;
    if version < NODE_MASK_COMPRESSION {
        return Err(format!(
            "OpenVDB file format {version} (prism reads 222 and later, written by OpenVDB 3.0 \
             on: save the file again with a newer OpenVDB)"
        ));
    }
    let _library = (bytes.u32("the header")?, bytes.u32("the header")?);
    let has_offsets = bytes.u8("the header")? != 0;
    bytes.take(36, "the file's UUID")?;
    metadata(&mut bytes)?;
    if !has_offsets {
        return Err("an OpenVDB stream without grid offsets (save it as a file)".into());
    }
    let count = bytes.u32("the grid count")?;
    let mut descriptors = Vec::new();
    for _ in 0..count {
        let name = bytes.string("a grid's name")?;
        let kind = bytes.string("a grid's type")?;
        let instance_of = bytes.string("a grid's instance parent")?;
        let grid_at = bytes.u64("a grid's offset")?;
        let _blocks_at = bytes.u64("a grid's offset")?;
        let end = bytes.u64("a grid's offset")?;
        let plain = |n: &str| {
            n.split(NAME_SEPARATOR)
                .next()
                .unwrap_or_default()
                .to_string()
        };
        descriptors.push(Descriptor {
            name: plain(&name),
            kind,
            instance_of: plain(&instance_of),
            grid_at,
        });
        bytes.seek(end)?;
    }
    let chosen = choose(&descriptors, name, usual)?;
    let what = |e: String| format!("grid '{}': {e}", chosen.name);
    let (size, half_by_type) = value_type(&chosen.kind).map_err(what)?;

    bytes.seek(chosen.grid_at).map_err(what)?;
    let compression = bytes.u32("a grid's compression").map_err(what)?;
    let meta = metadata(&mut bytes).map_err(what)?;
    if meta.class.as_deref() == Some("level set") {
        return Err(what(
            "a level set (a signed distance to a surface), not a density: convert it to a \
             fog volume first (OpenVDB's sdfToFogVolume, Houdini's Convert VDB)"
                .into(),
        ));
    }
    let map = transform(&mut bytes).map_err(what)?;
    if !chosen.instance_of.is_empty() {
        // An instance shares its parent's tree: read the parent's from its own data.
        let parent = descriptors
            .iter()
            .find(|d| d.name == chosen.instance_of && d.instance_of.is_empty())
            .ok_or_else(|| {
                what(format!(
                    "its tree is grid '{}', which the file lacks",
                    chosen.instance_of
                ))
            })?;
        bytes.seek(parent.grid_at).map_err(what)?;
        bytes.u32("a grid's compression").map_err(what)?;
        metadata(&mut bytes).map_err(what)?;
        transform(&mut bytes).map_err(what)?;
    }
    let mut encoding = Encoding {
        compression,
        size,
        half: half_by_type || meta.half,
        background: 0.0,
    };
    let tree = tree::read_tree(&mut bytes, &mut encoding).map_err(what)?;
    if encoding.background != 0.0 {
        return Err(what(format!(
            "its background value is {} (a density is 0 outside its voxels)",
            encoding.background
        )));
    }
    densify(&tree, map).map_err(what)
}

/// The grid to read: `name`, else `usual`, else the only grid.
fn choose<'a>(
    grids: &'a [Descriptor],
    name: Option<&str>,
    usual: &str,
) -> Result<&'a Descriptor, String> {
    let names = || {
        grids
            .iter()
            .map(|d| format!("'{}'", d.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    if grids.is_empty() {
        return Err("the file holds no grids".into());
    }
    match name {
        Some(n) => grids
            .iter()
            .find(|d| d.name == n)
            .ok_or_else(|| format!("no grid named '{n}' (the file holds {})", names())),
        None => grids
            .iter()
            .find(|d| d.name == usual)
            .or(if grids.len() == 1 {
                grids.first()
            } else {
                None
            })
            .ok_or_else(|| format!("the file holds grids {}: name one with \"grid\"", names())),
    }
}

/// Bytes per value, and whether values are halves, from a grid type such as
/// `Tree_float_5_4_3` (`_HalfFloat` marks halves in files before format 215).
fn value_type(kind: &str) -> Result<(usize, bool), String> {
    let (base, half) = match kind.strip_suffix("_HalfFloat") {
        Some(base) => (base, true),
        None => (kind, false),
    };
    match base {
        "Tree_float_5_4_3" => Ok((4, half)),
        "Tree_double_5_4_3" => Ok((8, half)),
        other if other.ends_with("_5_4_3") => Err(format!(
            "a grid of type {other} (prism reads scalar float and double grids)"
        )),
        other => Err(format!(
            "a tree of type {other} (prism reads the standard 5-4-3 tree)"
        )),
    }
}

/// What prism needs of a grid's metadata.
#[derive(Default)]
struct Meta {
    class: Option<String>,
    half: bool,
}

/// Reads a metadata table (`MetaMap::readMeta`): a count, then per entry its name, its
/// type name, its size in bytes and its bytes.
fn metadata(bytes: &mut Bytes) -> Result<Meta, String> {
    let mut meta = Meta::default();
    let count = bytes.u32("metadata")?;
    for _ in 0..count {
        let name = bytes.string("metadata")?;
        let kind = bytes.string("metadata")?;
        let size = bytes.u32("metadata")?;
        let value = bytes.take(u64::from(size), "metadata")?;
        match (name.as_str(), kind.as_str()) {
            ("class", "string") => meta.class = Some(String::from_utf8_lossy(value).into_owned()),
            ("is_saved_as_half_float", "bool") => {
                meta.half = value.first().is_some_and(|&b| b != 0)
            }
            _ => {}
        }
    }
    Ok(meta)
}

/// An axis-aligned index-to-world map: world = index * scale + translation.
#[derive(Debug, Clone, Copy)]
struct Map {
    scale: DVec3,
    translation: DVec3,
}

/// Reads a transform (`Transform::read`, the maps' `read`). Scales and translations are
/// read; an affine or unitary map must be a scale and a translation (no rotation, no
/// shear, no mirror), and a frustum is an error.
fn transform(bytes: &mut Bytes) -> Result<Map, String> {
    let kind = bytes.string("the grid's transform")?;
    let what = "the grid's transform";
    let scales = |bytes: &mut Bytes| -> Result<DVec3, String> {
        // The scale, then the voxel size, its inverse, its inverse squared and half its
        // inverse, which follow from it.
        let scale = DVec3::from(bytes.vec3(what)?);
        for _ in 0..4 {
            bytes.vec3(what)?;
        }
        Ok(scale)
    };
    let map = match kind.as_str() {
        "ScaleMap" | "UniformScaleMap" => Map {
            scale: scales(bytes)?,
            translation: DVec3::ZERO,
        },
        "ScaleTranslateMap" | "UniformScaleTranslateMap" => {
            let translation = DVec3::from(bytes.vec3(what)?);
            Map {
                scale: scales(bytes)?,
                translation,
            }
        }
        "TranslationMap" => Map {
            scale: DVec3::ONE,
            translation: DVec3::from(bytes.vec3(what)?),
        },
        "AffineMap" | "UnitaryMap" => {
            // A 4x4 matrix of doubles, row by row, acting on row vectors: the translation
            // is its last row.
            let mut m = [0.0f64; 16];
            for v in &mut m {
                *v = bytes.f64(what)?;
            }
            let scale = DVec3::new(m[0], m[5], m[10]);
            let off_diagonal = [m[1], m[2], m[4], m[6], m[8], m[9]];
            let tolerance = 1e-9 * scale.abs().max_element();
            if off_diagonal.iter().any(|v| v.abs() > tolerance) {
                return Err(
                    "a rotated or sheared transform (prism's grids are axis-aligned boxes: \
                     give \"bounds\" or resample the grid)"
                        .into(),
                );
            }
            Map {
                scale,
                translation: DVec3::new(m[12], m[13], m[14]),
            }
        }
        other => {
            return Err(format!(
                "a {other} transform (prism reads scales and translations)"
            ));
        }
    };
    if !(map.scale.is_finite() && map.translation.is_finite()) || map.scale.min_element() <= 0.0 {
        return Err(format!(
            "voxels of size {} (they must be finite and positive: mirrored grids are not read)",
            map.scale
        ));
    }
    Ok(map)
}

/// A dense grid over the tree's nonzero voxels with a margin of one voxel of 0.
fn densify(tree: &tree::Tree, map: Map) -> Result<Grid, String> {
    let mut lo = [i64::MAX; 3];
    let mut hi = [i64::MIN; 3];
    let mut include = |p: [i64; 3], edge: i64| {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k] + edge - 1);
        }
    };
    for (origin, edge, _) in &tree.tiles {
        include(origin.map(i64::from), i64::from(*edge));
    }
    for (origin, values) in &tree.leaves {
        for (n, _) in values.iter().enumerate().filter(|(_, v)| **v != 0.0) {
            include(leaf_voxel(*origin, n), 1);
        }
    }
    if lo[0] > hi[0] {
        return Err("it holds no nonzero voxels".into());
    }
    let (lo, hi) = (lo.map(|v| v - 1), hi.map(|v| v + 1));
    let size: [u64; 3] = std::array::from_fn(|k| (hi[k] - lo[k] + 1) as u64);
    let count = size
        .iter()
        .try_fold(1u64, |n, s| n.checked_mul(*s))
        .unwrap_or(u64::MAX);
    if count > MAX_VOXELS {
        return Err(format!(
            "its nonzero voxels span {} x {} x {}, more than the {MAX_VOXELS} voxels prism \
             holds densely",
            size[0], size[1], size[2]
        ));
    }
    let mut values = vec![0.0f32; count as usize];
    let mut set = |p: [i64; 3], v: f64| -> Result<(), String> {
        if !(v.is_finite() && v >= 0.0) {
            return Err(format!(
                "voxel ({}, {}, {}) is {v} (a density must be finite and >= 0)",
                p[0], p[1], p[2]
            ));
        }
        let [x, y, z] = std::array::from_fn(|k| (p[k] - lo[k]) as u64);
        values[((z * size[1] + y) * size[0] + x) as usize] = v as f32;
        Ok(())
    };
    for (origin, edge, value) in &tree.tiles {
        let o = origin.map(i64::from);
        let edge = i64::from(*edge);
        for x in 0..edge {
            for y in 0..edge {
                for z in 0..edge {
                    set([o[0] + x, o[1] + y, o[2] + z], *value)?;
                }
            }
        }
    }
    for (origin, leaf) in &tree.leaves {
        // Zeros are already there, and every other voxel is inside the box.
        for (n, v) in leaf.iter().enumerate().filter(|(_, v)| **v != 0.0) {
            set(leaf_voxel(*origin, n), *v)?;
        }
    }
    // Voxel centres sit at integer index coordinates, so the box runs half a voxel past
    // the first and last.
    let corner = |i: [i64; 3], half: f64| {
        (DVec3::new(i[0] as f64, i[1] as f64, i[2] as f64) + half) * map.scale + map.translation
    };
    let (min, max) = (corner(lo, -0.5).as_vec3(), corner(hi, 0.5).as_vec3());
    Grid::new(
        UVec3::new(size[0] as u32, size[1] as u32, size[2] as u32),
        min,
        max,
        values,
    )
}

/// Voxel `n` of the leaf at `origin` (x slowest, z fastest).
fn leaf_voxel(origin: [i32; 3], n: usize) -> [i64; 3] {
    let n = n as i64;
    [
        i64::from(origin[0]) + (n >> 6),
        i64::from(origin[1]) + ((n >> 3) & 7),
        i64::from(origin[2]) + (n & 7),
    ]
}
