//! Four triangles of a BVH leaf, stored lane by lane, and the watertight test run on all
//! four at once.
//!
//! The test is the scalar one of `triangle.rs` (Woop, Benthin and Wald 2013) lane by lane:
//! the same operations in the same order, in f32, without fused multiply-adds, so every
//! lane's hit, distance and barycentrics are the scalar test's bit for bit (a property test
//! checks it). The one exception is a lane where an edge function is exactly zero (a ray
//! through an edge or a vertex): the scalar test recomputes those in f64, so such lanes are
//! left to it.

use glam::{Vec3, Vec4};

use crate::geometry::offset::gamma;
use crate::geometry::triangle::{TriangleHit, WatertightRay};

/// Lanes per packet.
pub(super) const LANES: usize = 4;

/// Up to four triangles: `vertices[v][axis]` holds coordinate `axis` of vertex `v` of
/// every lane. Short packets repeat their first triangle in the unused lanes, which costs
/// nothing in correctness: a repeated triangle cannot be strictly closer than itself, and
/// for shadow rays one hit is as good as another.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(16))]
pub(super) struct Packet {
    vertices: [[Vec4; 3]; 3],
    /// Each lane's triangle, as an index into the slice the BVH was built from.
    pub(super) triangles: [u32; LANES],
}

impl Packet {
    /// A packet of 1 to 4 `(input index, vertices)` triangles.
    pub(super) fn new(members: &[(u32, [Vec3; 3])]) -> Self {
        debug_assert!((1..=LANES).contains(&members.len()));
        let lane = |i: usize| members[i.min(members.len() - 1)];
        let coordinate = |v: usize, axis: usize| {
            Vec4::new(
                lane(0).1[v][axis],
                lane(1).1[v][axis],
                lane(2).1[v][axis],
                lane(3).1[v][axis],
            )
        };
        Self {
            vertices: [0, 1, 2].map(|v| [0, 1, 2].map(|axis| coordinate(v, axis))),
            triangles: [0, 1, 2, 3].map(|i| lane(i).0),
        }
    }

    /// The vertices of lane `lane`.
    pub(super) fn triangle(&self, lane: usize) -> [Vec3; 3] {
        self.vertices
            .map(|[x, y, z]| Vec3::new(x[lane], y[lane], z[lane]))
    }
}

/// A ray's watertight-test set-up, splatted across the lanes.
pub(super) struct RayLanes {
    /// The ray's axes in permuted order: the largest |direction| component last.
    axes: [usize; 3],
    origin: [Vec4; 3],
    shear: [Vec4; 3],
}

impl RayLanes {
    pub(super) fn new(ray: &WatertightRay) -> Self {
        // (kz + 1, kz + 2, kz) mod 3, without a division.
        let axes = match ray.kz {
            0 => [1, 2, 0],
            1 => [2, 0, 1],
            _ => [0, 1, 2],
        };
        Self {
            axes,
            origin: axes.map(|a| Vec4::splat(ray.origin[a])),
            shear: ray.shear.to_array().map(Vec4::splat),
        }
    }

    /// The watertight test of every lane of `packet` against hits at 0 < t < `t_max`.
    #[inline(always)]
    pub(super) fn test(&self, packet: &Packet, t_max: f32) -> PacketHits {
        let [kx, ky, kz] = self.axes;
        let [sx, sy, sz] = self.shear;
        // Translated, permuted and sheared vertices, as the scalar test computes them.
        let sheared = |v: &[Vec4; 3]| {
            let z = v[kz] - self.origin[2];
            (
                (v[kx] - self.origin[0]) + sx * z,
                (v[ky] - self.origin[1]) + sy * z,
                z,
            )
        };
        let (x0, y0, z0) = sheared(&packet.vertices[0]);
        let (x1, y1, z1) = sheared(&packet.vertices[1]);
        let (x2, y2, z2) = sheared(&packet.vertices[2]);
        let e = [x1 * y2 - y1 * x2, x2 * y0 - y2 * x0, x0 * y1 - y0 * x1];
        let zero = Vec4::ZERO;
        let any_zero = e[0].cmpeq(zero) | e[1].cmpeq(zero) | e[2].cmpeq(zero);
        let any_negative = e[0].cmplt(zero) | e[1].cmplt(zero) | e[2].cmplt(zero);
        let any_positive = e[0].cmpgt(zero) | e[1].cmpgt(zero) | e[2].cmpgt(zero);
        let exact = any_zero.bitmask();
        let mut inside = !((any_negative & any_positive) | any_zero);
        // Most tests end here: the ray passes outside every triangle.
        if inside.bitmask() == 0 {
            return PacketHits::none(exact);
        }
        let det = e[0] + e[1] + e[2];
        let (z0, z1, z2) = (sz * z0, sz * z1, sz * z2);
        let t_scaled = e[0] * z0 + e[1] * z1 + e[2] * z2;
        let bound = Vec4::splat(t_max) * det;
        let in_front = (det.cmpgt(zero) & t_scaled.cmpgt(zero) & t_scaled.cmple(bound))
            | (det.cmplt(zero) & t_scaled.cmplt(zero) & t_scaled.cmpge(bound));
        inside &= in_front;
        if inside.bitmask() == 0 {
            return PacketHits::none(exact);
        }
        let inverse = Vec4::ONE / det;
        let t = t_scaled * inverse;
        inside &= t.cmpgt(zero) & t.cmplt(Vec4::splat(t_max));
        // t must exceed its own rounding error, bounded as the scalar test bounds it.
        let max3 = |a: Vec4, b: Vec4, c: Vec4| a.abs().max(b.abs()).max(c.abs());
        let max_z = max3(z0, z1, z2);
        let max_x = max3(x0, x1, x2);
        let max_y = max3(y0, y1, y2);
        let g = |n: i32| Vec4::splat(gamma(n));
        let delta_z = g(3) * max_z;
        let delta_x = g(5) * (max_x + max_z);
        let delta_y = g(5) * (max_y + max_z);
        let delta_e = Vec4::splat(2.0) * (g(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
        let max_e = max3(e[0], e[1], e[2]);
        let delta_t = Vec4::splat(3.0)
            * (g(3) * max_e * max_z + delta_e * max_z + delta_z * max_e)
            * inverse.abs();
        inside &= t.cmpgt(delta_t);
        PacketHits {
            hits: inside.bitmask(),
            exact,
            t,
            inverse,
            e,
        }
    }
}

/// The watertight test of the four lanes of a packet.
pub(super) struct PacketHits {
    /// The lanes hit, as a bit mask.
    pub(super) hits: u32,
    /// Lanes with an edge function exactly zero, which only the scalar test decides (it
    /// recomputes them in f64); they are never in `hits`.
    pub(super) exact: u32,
    t: Vec4,
    inverse: Vec4,
    e: [Vec4; 3],
}

impl PacketHits {
    fn none(exact: u32) -> Self {
        Self {
            hits: 0,
            exact,
            t: Vec4::ZERO,
            inverse: Vec4::ZERO,
            e: [Vec4::ZERO; 3],
        }
    }

    /// The nearest lane hit (the lowest lane among equals), if any.
    pub(super) fn nearest(&self) -> Option<usize> {
        let t = self.t.to_array();
        let mut lanes = self.hits;
        let mut best: Option<usize> = None;
        while lanes != 0 {
            let lane = lanes.trailing_zeros() as usize;
            lanes &= lanes - 1;
            if best.is_none_or(|b| t[lane] < t[b]) {
                best = Some(lane);
            }
        }
        best
    }

    /// Lane `lane`'s hit, as the scalar test reports it.
    pub(super) fn hit(&self, lane: usize) -> TriangleHit {
        let inverse = self.inverse[lane];
        TriangleHit {
            t: self.t[lane],
            barycentric: self.e.map(|e| e[lane] * inverse),
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use proptest::prelude::*;

    use super::{Packet, RayLanes};
    use crate::geometry::Ray;
    use crate::geometry::triangle::WatertightRay;

    fn coordinate() -> impl Strategy<Value = f32> {
        prop_oneof![
            Just(0.0f32),
            Just(-0.0f32),
            Just(1.0f32),
            Just(1e30f32),
            Just(-1e-38f32),
            Just(f32::MIN_POSITIVE / 4.0),
            -2.0..2.0f32,
            -2.0..2.0f32,
            -2.0..2.0f32,
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]
        /// Every lane of the packet test is the scalar test bit for bit (distance and
        /// barycentrics), or is handed to the scalar test (an exactly zero edge function).
        #[test]
        fn lanes_are_the_scalar_test(
            v in prop::array::uniform9(prop::array::uniform4(coordinate())),
            o in prop::array::uniform3(-3.0..3.0f32),
            d in prop::array::uniform3(prop_oneof![Just(0.0f32), Just(1e-30f32), -1.0..1.0f32]),
            t_max in prop_oneof![Just(f32::INFINITY), 0.0..10.0f32],
            axis_aligned in any::<bool>(),
            on_surface in prop::option::of((0.0..1.0f32, 0.0..1.0f32)),
        ) {
            let triangle = |lane: usize| {
                let mut t = [0, 1, 2].map(|k| Vec3::new(v[3 * k][lane], v[3 * k + 1][lane], v[3 * k + 2][lane]));
                if axis_aligned {
                    // Walls as in a Cornell box: one coordinate shared by all three.
                    t[1].z = t[0].z;
                    t[2].z = t[0].z;
                }
                (lane as u32, t)
            };
            let members: Vec<(u32, [Vec3; 3])> = (0..4).map(triangle).collect();
            let packet = Packet::new(&members);
            // Rays leaving a point on lane 0's triangle meet it at t ~ 0, where only the
            // distance's own error bound rejects the hit.
            let origin = match on_surface {
                Some((a, b)) => {
                    let (b1, b2) = if a + b > 1.0 { (1.0 - a, 1.0 - b) } else { (a, b) };
                    let t = members[0].1;
                    (1.0 - b1 - b2) * t[0] + b1 * t[1] + b2 * t[2]
                }
                None => Vec3::from(o),
            };
            let ray = Ray::new(origin, Vec3::from(d), t_max);
            let Some(watertight) = WatertightRay::new(&ray) else { return Ok(()) };
            let lanes = RayLanes::new(&watertight).test(&packet, t_max);
            prop_assert_eq!(lanes.hits & lanes.exact, 0);
            for (lane, (_, t)) in members.iter().enumerate() {
                prop_assert_eq!(packet.triangle(lane), *t);
                if lanes.exact & (1 << lane) != 0 {
                    continue;
                }
                let scalar = watertight.intersect(*t, t_max);
                let simd = (lanes.hits & (1 << lane) != 0).then(|| lanes.hit(lane));
                prop_assert_eq!(
                    scalar.map(|h| (h.t.to_bits(), h.barycentric.map(f32::to_bits))),
                    simd.map(|h| (h.t.to_bits(), h.barycentric.map(f32::to_bits))),
                    "lane {}", lane
                );
            }
        }
    }
}
