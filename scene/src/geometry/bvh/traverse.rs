//! Single-ray traversal of the eight-wide BVH: one SSE slab test per group of four
//! children, children visited nearest first for closest hits (Wald, Benthin and Boulos,
//! RT 2008, §4), and leaves tested four triangles at a time.

use glam::{Vec3, Vec4};

use super::packet::{Packet, RayLanes};
use super::wide::{ChildRef, GROUPS, LEAF, Node, WIDTH, WideBvh, leaf_packets};
use crate::geometry::Ray;
use crate::geometry::offset::gamma;
use crate::geometry::triangle::{TriangleHit, WatertightRay};

/// A node waiting on the stack, with the distance at which the ray enters its bounds.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Pending {
    child: ChildRef,
    t_enter: f32,
}

/// Entries a traversal of a tree `depth` nodes deep can hold at once: each level leaves at
/// most all but one of a node's children behind.
pub(super) fn stack_size(depth: usize) -> usize {
    (WIDTH - 1) * depth + 1
}

/// A ray's test against a node's eight boxes: which children it enters before `t_max`,
/// as a bit mask, and where it enters each. Implemented four lanes wide ([`BoxRay`], any
/// x86-64 or other CPU) and eight wide ([`super::avx::BoxRay8`], with AVX); both perform
/// the same IEEE operations per child in the same order, so their answers are equal to
/// the bit and the choice between them never changes an image.
pub(super) trait NodeTest {
    fn new(ray: &Ray) -> Self;
    fn enter(&self, node: &Node, t_max: f32) -> (u32, [f32; WIDTH]);
}

/// A ray direction's reciprocal, with a zero component made a tiny one of the same sign,
/// so that 1/d is finite and (bound - origin) / d is never 0 * inf: the ray is then
/// treated as parallel to within 1e-30, far inside the padding of every box.
#[inline(always)]
pub(super) fn slab_inverse(ray: &Ray) -> [f32; 3] {
    ray.direction.to_array().map(|d| {
        let d = if d.abs() < 1e-30 {
            1e-30f32.copysign(d)
        } else {
            d
        };
        1.0 / d
    })
}

/// Per axis, the index in `Node::bounds` of the plane a ray with reciprocal direction
/// `inverse` meets first, and of the one it meets last.
#[inline(always)]
pub(super) fn slab_planes(inverse: [f32; 3]) -> ([usize; 3], [usize; 3]) {
    let positive = inverse.map(|i| i >= 0.0);
    (
        [0, 1, 2].map(|a| if positive[a] { a } else { a + 3 }),
        [0, 1, 2].map(|a| if positive[a] { a + 3 } else { a }),
    )
}

/// The factor that widens a slab test's exit distance: 1 + 2 gamma(3), the bound on the
/// test's rounding (*PBR* 4th ed. §6.8.2), so rounding never culls a box the ray touches.
#[inline(always)]
pub(super) fn exit_widening() -> f32 {
    1.0 + 2.0 * gamma(3)
}

/// The slab test four lanes wide (SSE): the ray's set-up.
pub(super) struct BoxRay {
    origin: [Vec4; 3],
    inverse: [Vec4; 3],
    near: [usize; 3],
    far: [usize; 3],
}

impl NodeTest for BoxRay {
    #[inline(always)]
    fn new(ray: &Ray) -> Self {
        let inverse = slab_inverse(ray);
        let (near, far) = slab_planes(inverse);
        Self {
            origin: ray.origin.to_array().map(Vec4::splat),
            inverse: inverse.map(Vec4::splat),
            near,
            far,
        }
    }

    /// Every group of four children in turn (the groups' tests are independent, so they
    /// overlap in the pipeline).
    #[inline(always)]
    fn enter(&self, node: &Node, t_max: f32) -> (u32, [f32; WIDTH]) {
        let mut mask = 0;
        let mut t_enter = [0.0; WIDTH];
        for group in 0..GROUPS {
            let (m, t) = self.enter_group(node, group, t_max);
            mask |= m << (4 * group);
            t_enter[4 * group..4 * group + 4].copy_from_slice(&t.to_array());
        }
        (mask, t_enter)
    }
}

impl BoxRay {
    /// [`NodeTest::enter`] for the four children of `group`.
    #[inline(always)]
    fn enter_group(&self, node: &Node, group: usize, t_max: f32) -> (u32, Vec4) {
        let slab = |plane: usize, axis: usize| {
            (node.bounds[plane][group] - self.origin[axis]) * self.inverse[axis]
        };
        let t_enter = slab(self.near[0], 0)
            .max(slab(self.near[1], 1))
            .max(slab(self.near[2], 2).max(Vec4::ZERO));
        let t_exit = slab(self.far[0], 0)
            .min(slab(self.far[1], 1))
            .min(slab(self.far[2], 2).min(Vec4::splat(t_max)));
        let widened = t_exit * Vec4::splat(exit_widening());
        (t_enter.cmple(widened).bitmask(), t_enter)
    }
}

impl WideBvh {
    /// The closest hit along `ray` with 0 < t < `ray.t_max`: the input index of its
    /// triangle, the scalar watertight test's hit, and the triangle's vertices (read from
    /// its packet, already in cache, so that callers need not fetch them again).
    /// `stack` holds at least [`stack_size`] entries.
    #[inline(always)]
    pub(super) fn closest<B: NodeTest>(
        &self,
        ray: &Ray,
        watertight: &WatertightRay,
        stack: &mut [Pending],
    ) -> Option<(u32, TriangleHit, [Vec3; 3])> {
        let boxes = B::new(ray);
        let lanes = RayLanes::new(watertight);
        // The packet and lane of the closest hit so far.
        let mut best: Option<(&Packet, usize, TriangleHit)> = None;
        let mut t_max = ray.t_max;
        let mut top = 0;
        let mut current: ChildRef = 0;
        loop {
            if current & LEAF != 0 {
                for packet in &self.packets[leaf_packets(current)] {
                    let lanes = lanes.test(packet, t_max);
                    if let Some(lane) = lanes.nearest() {
                        let hit = lanes.hit(lane);
                        t_max = hit.t;
                        best = Some((packet, lane, hit));
                    }
                    let mut exact = lanes.exact;
                    while exact != 0 {
                        let lane = exact.trailing_zeros() as usize;
                        exact &= exact - 1;
                        if let Some(hit) = watertight.intersect(packet.triangle(lane), t_max) {
                            t_max = hit.t;
                            best = Some((packet, lane, hit));
                        }
                    }
                }
            } else {
                let node = &self.nodes[current as usize];
                let (mut mask, t_enter) = boxes.enter(node, t_max);
                if mask != 0 {
                    let first = mask.trailing_zeros() as usize;
                    let rest = mask & (mask - 1);
                    if rest == 0 {
                        current = node.children[first];
                        continue;
                    }
                    // Two children: the nearer next and the other pushed, as the sorted
                    // push below would order them (ties to the second), without its loop.
                    if rest & (rest - 1) == 0 {
                        let second = rest.trailing_zeros() as usize;
                        let (near, far) = if t_enter[first] < t_enter[second] {
                            (first, second)
                        } else {
                            (second, first)
                        };
                        stack[top] = Pending {
                            child: node.children[far],
                            t_enter: t_enter[far],
                        };
                        top += 1;
                        current = node.children[near];
                        continue;
                    }
                    // Push the children hit, keeping the pushed run sorted nearest on top.
                    let base = top;
                    while mask != 0 {
                        let lane = mask.trailing_zeros() as usize;
                        mask &= mask - 1;
                        stack[top] = Pending {
                            child: node.children[lane],
                            t_enter: t_enter[lane],
                        };
                        let mut i = top;
                        while i > base && stack[i - 1].t_enter < stack[i].t_enter {
                            stack.swap(i - 1, i);
                            i -= 1;
                        }
                        top += 1;
                    }
                    top -= 1;
                    current = stack[top].child;
                    continue;
                }
            }
            // Resume with the nearest pending node the ray can still reach before t_max.
            loop {
                if top == 0 {
                    return best.map(|(packet, lane, hit)| {
                        (packet.triangles[lane], hit, packet.triangle(lane))
                    });
                }
                top -= 1;
                if stack[top].t_enter <= t_max {
                    current = stack[top].child;
                    break;
                }
            }
        }
    }

    /// Whether any triangle lies along `ray` with 0 < t < `ray.t_max`; the first hit found
    /// ends the search.
    #[inline(always)]
    pub(super) fn any<B: NodeTest>(
        &self,
        ray: &Ray,
        watertight: &WatertightRay,
        stack: &mut [Pending],
    ) -> bool {
        let boxes = B::new(ray);
        let lanes = RayLanes::new(watertight);
        let t_max = ray.t_max;
        stack[0].child = 0;
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let current = stack[top].child;
            if current & LEAF != 0 {
                for packet in &self.packets[leaf_packets(current)] {
                    let lanes = lanes.test(packet, t_max);
                    if lanes.hits != 0 {
                        return true;
                    }
                    let mut exact = lanes.exact;
                    while exact != 0 {
                        let lane = exact.trailing_zeros() as usize;
                        exact &= exact - 1;
                        if watertight.intersect(packet.triangle(lane), t_max).is_some() {
                            return true;
                        }
                    }
                }
            } else {
                let node = &self.nodes[current as usize];
                let (mut mask, _) = boxes.enter(node, t_max);
                while mask != 0 {
                    let lane = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    stack[top].child = node.children[lane];
                    top += 1;
                }
            }
        }
        false
    }
}
