//! A four-wide BVH whose leaves are triangle packets, collapsed from obvhs's binary BVH.
//!
//! Why four-wide and not obvhs's compressed eight-wide tree: on a CPU with SSE, one
//! instruction tests a ray against four boxes, and decoding quantized boxes (what makes
//! the CWBVH small on GPUs) costs more than it saves here. A subtree of at most four
//! triangles becomes a single leaf packet: testing four triangles costs what testing one
//! does, so splitting such a subtree further could only add box tests.
//!
//! The collapse follows Wald, Benthin and Boulos, "Getting rid of packets: efficient SIMD
//! single-ray traversal using multi-branching BVHs", RT 2008, §3: a node's children are
//! its binary children, opened largest surface area first until there are four.

use glam::{Vec3, Vec4};
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;

use super::packet::{LANES, Packet};

/// A child reference: a node index, a leaf packet index with [`LEAF`] set, or [`EMPTY`].
pub(super) type ChildRef = u32;
/// Marks a child that is a leaf packet.
pub(super) const LEAF: ChildRef = 1 << 31;
/// An unused child slot (its bounds are empty, so no ray reaches it).
pub(super) const EMPTY: ChildRef = u32::MAX;

/// Four children's bounds, lane by lane: `bounds[0..3]` the minimum x, y, z and
/// `bounds[3..6]` the maximum.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(16))]
pub(super) struct Node {
    pub(super) bounds: [Vec4; 6],
    pub(super) children: [ChildRef; LANES],
}

impl Node {
    const UNUSED: Self = Self {
        bounds: [
            Vec4::INFINITY,
            Vec4::INFINITY,
            Vec4::INFINITY,
            Vec4::NEG_INFINITY,
            Vec4::NEG_INFINITY,
            Vec4::NEG_INFINITY,
        ],
        children: [EMPTY; LANES],
    };

    fn set(&mut self, lane: usize, bounds: &Aabb, child: ChildRef) {
        for axis in 0..3 {
            self.bounds[axis][lane] = bounds.min[axis];
            self.bounds[axis + 3][lane] = bounds.max[axis];
        }
        self.children[lane] = child;
    }
}

/// The tree: node 0 is the root.
pub(super) struct WideBvh {
    pub(super) nodes: Vec<Node>,
    pub(super) packets: Vec<Packet>,
    /// Levels of nodes on the longest root-to-leaf path.
    pub(super) depth: usize,
}

/// What the collapse reads: the binary tree, the bounds and vertices of the triangles it
/// was built over, and their indices in the caller's slice.
pub(super) struct Source<'a> {
    pub(super) binary: &'a Bvh2,
    pub(super) bounds: &'a [Aabb],
    pub(super) vertices: &'a [[Vec3; 3]],
    pub(super) original: &'a [usize],
}

impl WideBvh {
    pub(super) fn collapse(source: &Source) -> Self {
        let nodes = &source.binary.nodes;
        let counts = subtree_counts(&source.binary.nodes);
        let mut wide = Self {
            nodes: vec![Node::UNUSED],
            packets: Vec::new(),
            depth: 1,
        };
        // (binary node, its wide node, the wide node's depth)
        let mut work = Vec::new();
        if counts[0] as usize <= LANES || nodes[0].prim_count > 0 {
            // A tree too small to branch: the root holds it as its one child.
            let child = wide.child(source, 0, &counts, &mut work, 2);
            wide.nodes[0].set(0, &nodes[0].aabb, child);
        } else {
            work.push((0usize, 0usize, 1usize));
        }
        while let Some((binary, slot, depth)) = work.pop() {
            wide.depth = wide.depth.max(depth);
            let mut children = Vec::with_capacity(LANES);
            let first = nodes[binary].first_index as usize;
            children.extend([first, first + 1]);
            // Open the largest child that is neither a leaf nor small enough to be one.
            while children.len() < LANES {
                let open = children
                    .iter()
                    .enumerate()
                    .filter(|&(_, &c)| nodes[c].prim_count == 0 && counts[c] as usize > LANES)
                    .max_by(|a, b| {
                        let area = |c: usize| nodes[c].aabb.half_area();
                        area(*a.1).total_cmp(&area(*b.1))
                    })
                    .map(|(i, _)| i);
                let Some(i) = open else { break };
                let c = children.swap_remove(i);
                let grandchild = nodes[c].first_index as usize;
                children.extend([grandchild, grandchild + 1]);
            }
            for (lane, &c) in children.iter().enumerate() {
                let child = wide.child(source, c, &counts, &mut work, depth + 1);
                wide.nodes[slot].set(lane, &nodes[c].aabb, child);
            }
        }
        wide
    }

    /// The reference for binary node `c`: a packet if its subtree fits in one, else a new
    /// wide node queued in `work`.
    fn child(
        &mut self,
        source: &Source,
        c: usize,
        counts: &[u32],
        work: &mut Vec<(usize, usize, usize)>,
        depth: usize,
    ) -> ChildRef {
        let node = &source.binary.nodes[c];
        if node.prim_count == 0 && counts[c] as usize > LANES {
            self.nodes.push(Node::UNUSED);
            work.push((c, self.nodes.len() - 1, depth));
            return (self.nodes.len() - 1) as ChildRef;
        }
        let mut members = Vec::new();
        gather(source.binary, c, &mut members);
        self.leaves(source, &members, depth)
    }

    /// A packet of `members` (indices into the triangles the binary tree was built over),
    /// or, for a binary leaf of more than four (which prism's build parameters do not
    /// produce), a node over packets of them.
    fn leaves(&mut self, source: &Source, members: &[u32], depth: usize) -> ChildRef {
        if members.len() <= LANES {
            let lanes: Vec<(u32, [Vec3; 3])> = members
                .iter()
                .map(|&m| {
                    (
                        source.original[m as usize] as u32,
                        source.vertices[m as usize],
                    )
                })
                .collect();
            self.packets.push(Packet::new(&lanes));
            return LEAF | (self.packets.len() - 1) as ChildRef;
        }
        self.depth = self.depth.max(depth);
        self.nodes.push(Node::UNUSED);
        let slot = self.nodes.len() - 1;
        for (lane, chunk) in members.chunks(members.len().div_ceil(LANES)).enumerate() {
            let bounds = chunk
                .iter()
                .fold(Aabb::empty(), |b, &m| b.union(&source.bounds[m as usize]));
            let child = self.leaves(source, chunk, depth + 1);
            self.nodes[slot].set(lane, &bounds, child);
        }
        slot as ChildRef
    }
}

/// The triangle count of every binary node's subtree.
fn subtree_counts(nodes: &[obvhs::bvh2::node::Bvh2Node]) -> Vec<u32> {
    let mut preorder = Vec::with_capacity(nodes.len());
    let mut stack = vec![0usize];
    while let Some(n) = stack.pop() {
        preorder.push(n);
        if nodes[n].prim_count == 0 {
            let first = nodes[n].first_index as usize;
            stack.extend([first, first + 1]);
        }
    }
    let mut counts = vec![0; nodes.len()];
    // Children come after their parent in preorder, so the reverse sees them first.
    for &n in preorder.iter().rev() {
        counts[n] = match nodes[n].prim_count {
            0 => {
                let first = nodes[n].first_index as usize;
                counts[first] + counts[first + 1]
            }
            leaf => leaf,
        };
    }
    counts
}

/// The triangles under binary node `c`, appended to `out`.
fn gather(binary: &Bvh2, c: usize, out: &mut Vec<u32>) {
    let mut stack = vec![c];
    while let Some(n) = stack.pop() {
        let node = &binary.nodes[n];
        let first = node.first_index as usize;
        if node.prim_count == 0 {
            stack.extend([first, first + 1]);
        } else {
            out.extend_from_slice(
                &binary.primitive_indices[first..first + node.prim_count as usize],
            );
        }
    }
}
