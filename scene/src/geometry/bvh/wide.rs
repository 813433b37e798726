//! An eight-wide BVH whose leaves are runs of triangle packets, collapsed from obvhs's
//! binary BVH.
//!
//! Why eight children of uncompressed boxes and not obvhs's compressed eight-wide tree: on
//! a CPU with SSE one instruction tests a ray against four boxes, and decoding quantized
//! boxes (what makes the CWBVH small on GPUs) costs more than it saves here. A node holds
//! two such groups of four: their tests are independent, so the second overlaps the first
//! in the pipeline, and the tree is a level shallower than a four-wide one. A leaf is one
//! or two packets of four triangles, tested alike. Measured against a four-wide tree with
//! one packet per leaf (`cargo bench -p prism-benches --bench scene -- rays`), camera,
//! bounce and shadow rays are all faster, most in the bunny box, and so are whole
//! renders, whose images are byte-identical on every repository scene (docs/trade-offs.md,
//! "The BVH and its node test").
//!
//! The collapse is planned, not greedy: a dynamic programme over the binary tree (Ylitie,
//! Karras and Laine, HPG 2017, §4.1) chooses which binary nodes become wide nodes, which
//! become packets and which are opened into their parent, for the least expected cost by
//! the surface area heuristic. Wald, Benthin and Boulos's greedy rule ("Getting rid of
//! packets", RT 2008, §3: open the largest child until there are four) packs any subtree
//! of at most four triangles into one packet, even when its triangles lie far apart.

use glam::{Vec3, Vec4};
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::node::Bvh2Node;

use super::packet::{LANES, Packet};
use super::padded_bounds;

/// Children per node: two groups of four boxes, each tested with one SSE slab test.
pub(super) const WIDTH: usize = 8;
/// Groups of four children per node.
pub(super) const GROUPS: usize = WIDTH / LANES;
/// Packets per leaf at most: a leaf is a run of consecutive packets, all tested.
pub(super) const LEAF_PACKETS: usize = 2;
/// Triangles per leaf at most.
const LEAF_CAPACITY: usize = LANES * LEAF_PACKETS;

/// A child reference: a node index, a leaf (see [`leaf`]) with [`LEAF`] set, or [`EMPTY`].
pub(super) type ChildRef = u32;
/// Marks a child that is a leaf.
pub(super) const LEAF: ChildRef = 1 << 31;
/// An unused child slot (its bounds are empty, so no ray reaches it).
pub(super) const EMPTY: ChildRef = u32::MAX;
/// Where a leaf reference keeps its number of packets, less one: one bit, below [`LEAF`],
/// which leaves 2^30 packets (at least 2^30 triangles) addressable.
const RUN_SHIFT: u32 = 30;
const FIRST_MASK: ChildRef = (1 << RUN_SHIFT) - 1;
const _: () = assert!(LEAF_PACKETS <= 2, "a leaf's run length has one bit");

/// The leaf of packets `first..first + count`.
fn leaf(first: usize, count: usize) -> ChildRef {
    debug_assert!((1..=LEAF_PACKETS).contains(&count));
    // A scene of over 2^30 triangles needs nearly 40 GB for its vertices alone.
    assert!(
        first <= FIRST_MASK as usize,
        "a BVH of more than 2^30 leaf packets cannot be addressed"
    );
    LEAF | ((count as ChildRef - 1) << RUN_SHIFT) | first as ChildRef
}

/// The packets of leaf `child`.
#[inline(always)]
pub(super) fn leaf_packets(child: ChildRef) -> std::ops::Range<usize> {
    let first = (child & FIRST_MASK) as usize;
    first..first + ((child & !LEAF) >> RUN_SHIFT) as usize + 1
}

/// Eight children's bounds, plane by plane: `bounds[0..3]` the minimum x, y, z of the eight
/// children and `bounds[3..6]` the maximum, each plane's eight values in a row (children
/// 4g..4g+4 in `bounds[plane][g]`), so that a node test four lanes wide reads a group and
/// one eight lanes wide reads a whole plane.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(32))]
pub(super) struct Node {
    pub(super) bounds: [[Vec4; GROUPS]; 6],
    pub(super) children: [ChildRef; WIDTH],
}

impl Node {
    const UNUSED: Self = Self {
        bounds: [
            [Vec4::INFINITY; GROUPS],
            [Vec4::INFINITY; GROUPS],
            [Vec4::INFINITY; GROUPS],
            [Vec4::NEG_INFINITY; GROUPS],
            [Vec4::NEG_INFINITY; GROUPS],
            [Vec4::NEG_INFINITY; GROUPS],
        ],
        children: [EMPTY; WIDTH],
    };

    fn set(&mut self, lane: usize, bounds: &Aabb, child: ChildRef) {
        let (group, lane_in_group) = (lane / LANES, lane % LANES);
        for axis in 0..3 {
            self.bounds[axis][group][lane_in_group] = bounds.min[axis];
            self.bounds[axis + 3][group][lane_in_group] = bounds.max[axis];
        }
        self.children[lane] = child;
    }
}

/// The expected cost of a leaf of `count` triangles, per unit of surface area: one
/// packet test, and less for each further one (its test overlaps the first's).
fn leaf_cost(count: usize) -> f32 {
    PACKET_COST * (1.0 + EXTRA_PACKET * (count.div_ceil(LANES).max(1) - 1) as f32)
}

/// The tree: node 0 is the root.
pub(super) struct WideBvh {
    pub(super) nodes: Vec<Node>,
    pub(super) packets: Vec<Packet>,
    /// Levels of nodes on the longest root-to-leaf path.
    pub(super) depth: usize,
}

/// What the collapse reads: the binary tree, the vertices of the triangles it was built
/// over, and their indices in the caller's slice (None: the same indices, nothing was
/// left out). The triangles' bounds are not needed: the caller frees them before the
/// collapse allocates the wide tree.
pub(super) struct Source<'a> {
    pub(super) binary: &'a Bvh2,
    pub(super) vertices: &'a [[Vec3; 3]],
    pub(super) original: Option<&'a [u32]>,
}

impl Source<'_> {
    /// The caller's index of triangle `m`.
    fn original(&self, m: u32) -> u32 {
        self.original.map_or(m, |o| o[m as usize])
    }
}

/// The cost of visiting a wide node (one slab test of four boxes) and a leaf packet (the
/// four-lane watertight test), each per unit of the surface area that makes a ray visit
/// it (the surface area heuristic). A packet test takes about twice a node test's
/// instructions; ratios from 1.5 to 4 gave the same render times (see
/// [`WideBvh::collapse`]), 1 (a packet as cheap as a node) more instructions.
const NODE_COST: f32 = 1.0;
const PACKET_COST: f32 = 2.0;
/// A leaf's further packets, as a share of the first's cost.
const EXTRA_PACKET: f32 = 0.5;

/// The cheapest way to lay a binary node's subtree out as children of a wide node, found
/// bottom-up (the dynamic programme of Ylitie, Karras and Laine, "Efficient incoherent
/// ray traversal on GPUs through compressed wide BVHs", HPG 2017, §4.1, with eight-wide
/// nodes and leaves of up to two four-triangle packets).
#[derive(Debug, Clone, Copy)]
struct Plan {
    /// `cost[i - 1]`: the subtree as at most `i` children.
    cost: [f32; WIDTH],
    /// For `i >= 2`, how many of the `i` children the left binary child's subtree
    /// becomes; 0 when fewer than `i` children are as cheap (see `cost[i - 2]`).
    left: [u8; WIDTH],
    /// As one child: a packet, or (false) a wide node.
    packet: bool,
    /// As a wide node: how many children it has, and how many of them come from the
    /// left binary child.
    wide: u8,
    wide_left: u8,
    /// The triangles in the subtree.
    count: u32,
}

/// Plans every binary node of `binary`, children before parents (the reverse of a
/// preorder), counting each subtree's triangles on the way.
fn plan(binary: &Bvh2) -> Vec<Plan> {
    let nodes = &binary.nodes;
    let mut plans = vec![
        Plan {
            cost: [f32::INFINITY; WIDTH],
            left: [0; WIDTH],
            packet: true,
            wide: 0,
            wide_left: 0,
            count: 0,
        };
        nodes.len()
    ];
    for &n in preorder(nodes).iter().rev() {
        let area = nodes[n].aabb.half_area();
        let first = nodes[n].first_index as usize;
        let mut plan = plans[n];
        plan.count = match nodes[n].prim_count {
            0 => plans[first].count + plans[first + 1].count,
            leaf => leaf,
        };
        let count = plan.count as usize;
        if nodes[n].prim_count > 0 {
            // A binary leaf (of one triangle, as prism builds them) is one packet; a
            // larger one becomes a node over packets (see `WideBvh::leaves`).
            let packets = count.div_ceil(LANES) as f32;
            plan.cost[0] = if count <= LEAF_CAPACITY {
                area * leaf_cost(count)
            } else {
                area * (NODE_COST + packets * PACKET_COST)
            };
            plan.packet = count <= LEAF_CAPACITY;
            plan.cost = [plan.cost[0]; WIDTH];
            plans[n] = plan;
            continue;
        }
        let (l, r) = (&plans[first], &plans[first + 1]);
        // The two subtrees shared out among j children, j = 2..=4.
        // The first share is taken whatever its cost: with triangles near f32's limit the
        // areas, and so every cost, are infinite, and a split must still give each side
        // at least one child.
        let mut split = [(f32::INFINITY, 0u8); WIDTH + 1];
        for (j, best) in split.iter_mut().enumerate().skip(2) {
            for k in 1..j {
                let cost = l.cost[k - 1] + r.cost[j - k - 1];
                if k == 1 || cost < best.0 {
                    *best = (cost, k as u8);
                }
            }
        }
        let (wide, (children, wide_left)) = (2..=WIDTH)
            .map(|j| (j, split[j]))
            .min_by(|a, b| a.1.0.total_cmp(&b.1.0))
            .expect("2..=WIDTH is not empty");
        let as_node = area * NODE_COST + children;
        let as_packet = if count <= LEAF_CAPACITY {
            area * leaf_cost(count)
        } else {
            f32::INFINITY
        };
        plan.packet = as_packet <= as_node;
        plan.wide = wide as u8;
        plan.wide_left = wide_left;
        plan.cost[0] = as_packet.min(as_node);
        for (i, &shared) in split.iter().enumerate().skip(2) {
            let fewer = plan.cost[i - 2];
            (plan.cost[i - 1], plan.left[i - 1]) =
                if shared.0 < fewer { shared } else { (fewer, 0) };
        }
        plans[n] = plan;
    }
    plans
}

impl WideBvh {
    /// Collapses the binary tree by the plan of least expected cost. Against the greedy
    /// collapse of Wald, Benthin and Boulos (RT 2008, §3: open the largest child until
    /// there are four, every subtree of at most four triangles one packet), measured
    /// under callgrind and in wall time: the Cornell box's paths take fewer instructions
    /// for the same time, the bunny box's fewer instructions and less time; images
    /// byte-identical. The plan costs a little more build time.
    pub(super) fn collapse(source: &Source) -> Self {
        let nodes = &source.binary.nodes;
        let plans = plan(source.binary);
        let mut wide = Self {
            nodes: vec![Node::UNUSED],
            packets: Vec::new(),
            depth: 1,
        };
        // (binary node, its wide node, the wide node's depth)
        let mut work = Vec::new();
        if plans[0].count as usize <= LEAF_CAPACITY || nodes[0].prim_count > 0 {
            // A tree too small to branch: the root holds it as its one child.
            let mut members = Vec::new();
            gather(source.binary, 0, &mut members);
            let child = wide.leaves(source, &members, 2);
            wide.nodes[0].set(0, &nodes[0].aabb, child);
        } else {
            work.push((0usize, 0usize, 1usize));
        }
        while let Some((binary, slot, depth)) = work.pop() {
            wide.depth = wide.depth.max(depth);
            let plan = &plans[binary];
            let first = nodes[binary].first_index as usize;
            let mut children = Vec::with_capacity(WIDTH);
            let left = usize::from(plan.wide_left);
            lay_out(&plans, nodes, first, left, &mut children);
            lay_out(
                &plans,
                nodes,
                first + 1,
                usize::from(plan.wide) - left,
                &mut children,
            );
            for (lane, &c) in children.iter().enumerate() {
                let child = if plans[c].packet {
                    let mut members = Vec::new();
                    gather(source.binary, c, &mut members);
                    wide.leaves(source, &members, depth + 1)
                } else {
                    wide.nodes.push(Node::UNUSED);
                    work.push((c, wide.nodes.len() - 1, depth + 1));
                    (wide.nodes.len() - 1) as ChildRef
                };
                wide.nodes[slot].set(lane, &nodes[c].aabb, child);
            }
        }
        // The lists grew by doubling; the tree is kept for the whole render.
        wide.nodes.shrink_to_fit();
        wide.packets.shrink_to_fit();
        wide
    }

    /// A packet of `members` (indices into the triangles the binary tree was built over),
    /// or, for a binary leaf of more than four (which prism's build parameters do not
    /// produce), a node over packets of them.
    fn leaves(&mut self, source: &Source, members: &[u32], depth: usize) -> ChildRef {
        if members.len() <= LEAF_CAPACITY {
            let first = self.packets.len();
            for chunk in members.chunks(LANES) {
                let lanes: Vec<(u32, [Vec3; 3])> = chunk
                    .iter()
                    .map(|&m| (source.original(m), source.vertices[m as usize]))
                    .collect();
                self.packets.push(Packet::new(&lanes));
            }
            return leaf(first, self.packets.len() - first);
        }
        self.depth = self.depth.max(depth);
        self.nodes.push(Node::UNUSED);
        let slot = self.nodes.len() - 1;
        for (lane, chunk) in members.chunks(members.len().div_ceil(WIDTH)).enumerate() {
            let bounds = chunk.iter().fold(Aabb::empty(), |b, &m| {
                b.union(&padded_bounds(&source.vertices[m as usize]))
            });
            let child = self.leaves(source, chunk, depth + 1);
            self.nodes[slot].set(lane, &bounds, child);
        }
        slot as ChildRef
    }
}

/// Appends to `out` the binary nodes that become `i` children (at most) for binary node
/// `n`, as its plan says.
fn lay_out(plans: &[Plan], nodes: &[Bvh2Node], n: usize, i: usize, out: &mut Vec<usize>) {
    let left = usize::from(plans[n].left[i - 1]);
    if i == 1 {
        out.push(n);
    } else if left == 0 {
        lay_out(plans, nodes, n, i - 1, out);
    } else {
        let first = nodes[n].first_index as usize;
        lay_out(plans, nodes, first, left, out);
        lay_out(plans, nodes, first + 1, i - left, out);
    }
}

/// The binary nodes in preorder: every parent before its children.
fn preorder(nodes: &[Bvh2Node]) -> Vec<usize> {
    let mut preorder = Vec::with_capacity(nodes.len());
    let mut stack = vec![0usize];
    while let Some(n) = stack.pop() {
        preorder.push(n);
        if nodes[n].prim_count == 0 {
            let first = nodes[n].first_index as usize;
            stack.extend([first, first + 1]);
        }
    }
    preorder
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

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use glam::{Vec3, Vec3A};
    use obvhs::BvhBuildParams;
    use obvhs::aabb::Aabb;
    use obvhs::bvh2::builder::build_bvh2;

    use super::{EMPTY, LEAF, NODE_COST, Source, WideBvh, leaf_cost, leaf_packets, plan};
    use crate::geometry::bvh::padded_bounds;

    /// Triangles scattered by a fixed linear congruential generator: clusters of small
    /// ones (a mesh) and a few large ones (walls), as in the test scenes.
    fn scene(count: usize) -> Vec<[Vec3; 3]> {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        (0..count)
            .map(|i| {
                let size = if i % 17 == 0 { 2.0 } else { 0.05 };
                let c = Vec3::new(next(), next(), next()) * 4.0 - 2.0;
                [0, 1, 2].map(|_| c + (Vec3::new(next(), next(), next()) - 0.5) * size)
            })
            .collect()
    }

    /// The collapsed tree's expected cost, summed over its nodes and packets from the
    /// bounds the tree stores, is the cost its plan predicted: the tree is the plan.
    #[test]
    fn the_tree_built_is_the_plan_and_holds_every_triangle_once() {
        for count in [1, 3, 4, 5, 9, 36, 200, 1000] {
            let triangles = scene(count);
            let bounds: Vec<Aabb> = triangles.iter().map(padded_bounds).collect();
            let params = BvhBuildParams {
                max_prims_per_leaf: 1,
                ..BvhBuildParams::medium_build()
            };
            let binary = build_bvh2(&bounds, params, &mut Duration::default());
            let tree = WideBvh::collapse(&Source {
                binary: &binary,
                vertices: &triangles,
                original: None,
            });
            let mut seen = vec![0u32; count];
            let mut built = 0.0f64;
            let half_area = |node: &super::Node, lane: usize| {
                let b = |plane: usize| node.bounds[plane][lane / 4][lane % 4];
                let lo = Vec3A::new(b(0), b(1), b(2));
                let hi = Vec3A::new(b(3), b(4), b(5));
                f64::from(Aabb::new(lo, hi).half_area())
            };
            for node in &tree.nodes {
                for (lane, &child) in node.children.iter().enumerate() {
                    if child == EMPTY {
                        continue;
                    }
                    if child & LEAF == 0 {
                        built += half_area(node, lane) * f64::from(NODE_COST);
                        continue;
                    }
                    let mut lanes: Vec<u32> = leaf_packets(child)
                        .flat_map(|p| tree.packets[p].triangles.to_vec())
                        .collect();
                    lanes.dedup();
                    built += half_area(node, lane) * f64::from(leaf_cost(lanes.len()));
                    for t in lanes {
                        seen[t as usize] += 1;
                    }
                }
            }
            assert!(seen.iter().all(|&s| s == 1), "{count} triangles: {seen:?}");
            if count > super::LEAF_CAPACITY {
                // The root is a node; the stored bounds are those of its children down.
                let plans = plan(&binary);
                let root_area = binary.nodes[0].aabb.half_area();
                let predicted = f64::from(plans[0].cost[0] - root_area * NODE_COST);
                assert!(
                    (built - predicted).abs() <= 1e-4 * predicted,
                    "{count} triangles: built {built}, planned {predicted}"
                );
            }
        }
    }
}
