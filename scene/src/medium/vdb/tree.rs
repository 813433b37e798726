//! A grid's tree as OpenVDB writes it (`tree/RootNode.h`, `InternalNode.h`, `LeafNode.h`:
//! `readTopology`, then `readBuffers`), for the standard 5-4-3 configuration: a root
//! table of tiles and of 4096^3-voxel internal nodes, each holding 32^3 tiles or 128^3
//! nodes, each of those 16^3 tiles or 8^3 leaves. Nodes' children are stored depth first
//! in the order of their offsets, and the leaves' values after all the topology, in the
//! same order.

use super::bytes::{Bytes, bit};
use super::values::{Encoding, read_values};

/// log2 of a leaf's, a lower internal node's and an upper internal node's edge in child
/// units (`Tree_float_5_4_3`).
const LEAF_LOG2: u32 = 3;
const LOWER_LOG2: u32 = 4;
const UPPER_LOG2: u32 = 5;

/// What a tree holds: constant boxes and leaves of 8^3 voxels, all in index space.
#[derive(Debug, Default)]
pub(super) struct Tree {
    /// Cubes of one value other than the background: their first voxel, their edge in
    /// voxels, their value.
    pub tiles: Vec<([i32; 3], i32, f64)>,
    /// Leaves: their first voxel and their 512 values, z fastest, then y, then x.
    pub leaves: Vec<([i32; 3], Vec<f64>)>,
}

/// The voxel offset of child `n` in a node with `log2` children per edge, each
/// `child_edge_log2` voxels wide (x slowest, z fastest, as `offsetToLocalCoord`).
fn child_origin(origin: [i32; 3], n: usize, log2: u32, child_edge_log2: u32) -> [i32; 3] {
    let n = n as i32;
    let edge = (1 << log2) - 1;
    let local = [n >> (2 * log2), (n >> log2) & edge, n & edge];
    [
        origin[0].wrapping_add(local[0] << child_edge_log2),
        origin[1].wrapping_add(local[1] << child_edge_log2),
        origin[2].wrapping_add(local[2] << child_edge_log2),
    ]
}

/// Reads the topology and then the leaf values of a tree whose stream starts at the
/// root's background.
pub(super) fn read_tree(bytes: &mut Bytes, encoding: &mut Encoding) -> Result<Tree, String> {
    let buffers = bytes.i32("the tree's buffer count")?;
    if buffers != 1 {
        return Err(format!(
            "a tree with {buffers} buffers per leaf (OpenVDB writes 1)"
        ));
    }
    encoding.background = encoding.value(bytes, "the grid's background value")?;
    let tiles = bytes.u32("the root's tile count")?;
    let children = bytes.u32("the root's child count")?;
    let mut tree = Tree::default();
    for _ in 0..tiles {
        let origin = bytes.coord("a root tile")?;
        let value = encoding.value(bytes, "a root tile")?;
        let _active = bytes.u8("a root tile")?;
        if value != encoding.background {
            tree.tiles
                .push((origin, 1 << (UPPER_LOG2 + LOWER_LOG2 + LEAF_LOG2), value));
        }
    }
    let mut leaf_origins = Vec::new();
    for _ in 0..children {
        let origin = bytes.coord("a root child")?;
        internal(
            bytes,
            encoding,
            origin,
            UPPER_LOG2,
            &mut tree,
            &mut leaf_origins,
        )?;
    }
    for origin in leaf_origins {
        let words = 1usize << (3 * LEAF_LOG2 - 6);
        let active = bytes.mask(words, "a leaf's value mask")?;
        let values = read_values(bytes, 1 << (3 * LEAF_LOG2), &active, encoding)?;
        tree.leaves.push((origin, values));
    }
    Ok(tree)
}

/// Reads the topology of the internal node at `origin` with `log2` children per edge
/// (5 or 4) and of its children, noting its tiles and where its leaves are.
fn internal(
    bytes: &mut Bytes,
    encoding: &Encoding,
    origin: [i32; 3],
    log2: u32,
    tree: &mut Tree,
    leaf_origins: &mut Vec<[i32; 3]>,
) -> Result<(), String> {
    let count = 1usize << (3 * log2);
    let child_edge_log2 = if log2 == UPPER_LOG2 {
        LOWER_LOG2 + LEAF_LOG2
    } else {
        LEAF_LOG2
    };
    let children = bytes.mask(count / 64, "a node's child mask")?;
    let active = bytes.mask(count / 64, "a node's value mask")?;
    let values = read_values(bytes, count, &active, encoding)?;
    for (n, value) in values.iter().enumerate() {
        if !bit(&children, n) && *value != encoding.background {
            let tile = child_origin(origin, n, log2, child_edge_log2);
            tree.tiles.push((tile, 1 << child_edge_log2, *value));
        }
    }
    for n in (0..count).filter(|&n| bit(&children, n)) {
        let child = child_origin(origin, n, log2, child_edge_log2);
        if log2 == UPPER_LOG2 {
            internal(bytes, encoding, child, LOWER_LOG2, tree, leaf_origins)?;
        } else {
            // A leaf's topology is its value mask, read again with its values.
            bytes.mask(1 << (3 * LEAF_LOG2 - 6), "a leaf's value mask")?;
            leaf_origins.push(child);
        }
    }
    Ok(())
}
