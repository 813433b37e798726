use glam::{DVec3, Vec3};
use prism_sampling::distribution::positive_finite;

use super::Ray;
use super::offset::gamma;

/// The area of a triangle.
pub fn triangle_area(p: [Vec3; 3]) -> f32 {
    0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length()
}

/// The unit normal of a triangle, on the side its counter-clockwise winding faces (zero
/// for a degenerate triangle: zero area even in f64, or non-finite vertices).
#[inline]
pub fn triangle_normal(p: [Vec3; 3]) -> Vec3 {
    // `unit_or_zero` inlined rather than called and its zero tested: the test cost a
    // measurable share of the Cornell box's instructions (this runs for every hit).
    let cross = (p[1] - p[0]).cross(p[2] - p[0]);
    let rcp = 1.0 / cross.length();
    if positive_finite(rcp) {
        cross * rcp
    } else {
        triangle_normal_f64(p)
    }
}

/// [`triangle_normal`] where f32 cannot: its cross product overflows for edges beyond
/// ~1e19 (the length squared is infinite, or inf - inf is NaN) and underflows for edges
/// below ~1e-19, though such triangles have a normal and can be hit. f64 has the range
/// for every f32 triangle. Out of line, so that the common path stays small.
#[cold]
#[inline(never)]
fn triangle_normal_f64(p: [Vec3; 3]) -> Vec3 {
    let [a, b, c] = p.map(|v| v.as_dvec3());
    let cross = (b - a).cross(c - a);
    let length = cross.length();
    if length > 0.0 && length.is_finite() {
        (cross / length).as_vec3()
    } else {
        Vec3::ZERO
    }
}

/// `v` scaled to unit length, or zero where that is not finite (zero, subnormal or
/// non-finite `v`): glam's `normalize_or_zero`, the same operations, with the check on the
/// reciprocal's bits (see `positive_finite`), which is run for every hit.
pub(crate) fn unit_or_zero(v: Vec3) -> Vec3 {
    let rcp = 1.0 / v.length();
    if positive_finite(rcp) {
        v * rcp
    } else {
        Vec3::ZERO
    }
}

/// Where a ray meets a triangle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriangleHit {
    /// Ray parameter of the hit.
    pub t: f32,
    /// Barycentric coordinates (b0, b1, b2) of the hit point, summing to 1.
    pub barycentric: [f32; 3],
}

/// The watertight ray-triangle test of Woop, Benthin and Wald, "Watertight ray/triangle
/// intersection", JCGT 2(1), 2013 (as arranged in *PBR* 4th ed. §6.5.3): the vertices are
/// translated to the ray origin, permuted so the ray's largest direction component is z,
/// and sheared so the ray is +z; the edge functions are then evaluated in 2D and, where
/// one is exactly 0 in f32 (a ray through an edge or a vertex), recomputed in f64, so a
/// ray through a shared edge is never lost between the two triangles. Degenerate
/// triangles are never hit. Hits with t <= 0 or t >= `ray.t_max` are ignored.
pub fn intersect_triangle(ray: &Ray, p: [Vec3; 3]) -> Option<TriangleHit> {
    WatertightRay::new(ray)?.intersect(p, ray.t_max)
}

/// The per-ray part of the watertight test (the axis permutation and the shear), computed
/// once per ray and reused for every triangle it is tested against: the same arithmetic as
/// computing it per triangle, so the same results bit for bit.
#[derive(Debug, Clone, Copy)]
pub(crate) struct WatertightRay {
    pub(crate) origin: Vec3,
    /// The axis of the largest |direction| component, which becomes z.
    pub(crate) kz: u8,
    pub(crate) shear: Vec3,
}

/// The permutation (kx, ky, kz) = (kz + 1, kz + 2, kz) mod 3 as fixed swizzles: indexing a
/// vector by a run-time axis forces it through memory, and this runs per triangle tested.
fn permute(v: Vec3, kz: u8) -> Vec3 {
    match kz {
        0 => Vec3::new(v.y, v.z, v.x),
        1 => Vec3::new(v.z, v.x, v.y),
        _ => v,
    }
}

impl WatertightRay {
    /// None for a ray that can hit nothing (non-finite, or a zero direction).
    pub(crate) fn new(ray: &Ray) -> Option<Self> {
        let d = ray.direction;
        if !(d.is_finite() && d != Vec3::ZERO && ray.origin.is_finite()) {
            return None;
        }
        // Permute so that the largest |direction| component is z.
        let kz = d.abs().max_position() as u8;
        let d = permute(d, kz);
        Some(Self {
            origin: ray.origin,
            kz,
            shear: Vec3::new(-d.x / d.z, -d.y / d.z, 1.0 / d.z),
        })
    }

    /// The hit with triangle `p` at 0 < t < `t_max`, if any.
    pub(crate) fn intersect(&self, p: [Vec3; 3], t_max: f32) -> Option<TriangleHit> {
        let [mut p0, mut p1, mut p2] = p.map(|v| permute(v - self.origin, self.kz));
        // Shear so the ray direction is +z.
        let (sx, sy, sz) = (self.shear.x, self.shear.y, self.shear.z);
        for q in [&mut p0, &mut p1, &mut p2] {
            q.x += sx * q.z;
            q.y += sy * q.z;
        }
        // Edge functions; fall back to f64 where one is exactly zero.
        let mut e0 = p1.x * p2.y - p1.y * p2.x;
        let mut e1 = p2.x * p0.y - p2.y * p0.x;
        let mut e2 = p0.x * p1.y - p0.y * p1.x;
        if e0 == 0.0 || e1 == 0.0 || e2 == 0.0 {
            let (a, b, c) = (p0.as_dvec3(), p1.as_dvec3(), p2.as_dvec3());
            let edge = |u: DVec3, v: DVec3| (u.x * v.y - u.y * v.x) as f32;
            (e0, e1, e2) = (edge(b, c), edge(c, a), edge(a, b));
        }
        if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
            return None;
        }
        let det = e0 + e1 + e2;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        // Scaled distance, compared against the range without dividing first.
        let (z0, z1, z2) = (sz * p0.z, sz * p1.z, sz * p2.z);
        let t_scaled = e0 * z0 + e1 * z1 + e2 * z2;
        if det < 0.0 && (t_scaled >= 0.0 || t_scaled < t_max * det) {
            return None;
        }
        if det > 0.0 && (t_scaled <= 0.0 || t_scaled > t_max * det) {
            return None;
        }
        let inverse = 1.0 / det;
        let t = t_scaled * inverse;
        if !(t > 0.0 && t < t_max) {
            return None;
        }
        // t must exceed its own rounding error (*PBR* 4th ed. §6.5.3): a ray spawned on a
        // surface whose error bound is zero along its normal (a plane through the origin,
        // where the offset is nothing) otherwise re-hits it at t ~ 1e-7.
        let max_z = z0.abs().max(z1.abs()).max(z2.abs());
        let max_x = p0.x.abs().max(p1.x.abs()).max(p2.x.abs());
        let max_y = p0.y.abs().max(p1.y.abs()).max(p2.y.abs());
        let delta_z = gamma(3) * max_z;
        let delta_x = gamma(5) * (max_x + max_z);
        let delta_y = gamma(5) * (max_y + max_z);
        let delta_e = 2.0 * (gamma(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
        let max_e = e0.abs().max(e1.abs()).max(e2.abs());
        let delta_t =
            3.0 * (gamma(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * inverse.abs();
        if t <= delta_t {
            return None;
        }
        Some(TriangleHit {
            t,
            barycentric: [e0 * inverse, e1 * inverse, e2 * inverse],
        })
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use proptest::prelude::*;

    use super::{triangle_normal, unit_or_zero};

    fn component() -> impl Strategy<Value = f32> {
        prop_oneof![
            Just(0.0f32),
            Just(-0.0f32),
            Just(1e-45f32),
            Just(f32::MIN_POSITIVE),
            Just(f32::MAX),
            Just(f32::INFINITY),
            Just(f32::NAN),
            any::<f32>(),
            -2.0..2.0f32,
        ]
    }

    proptest! {
        /// Bit for bit glam's `normalize_or_zero`, whatever the components (zero,
        /// subnormal, huge, infinite, NaN).
        #[test]
        fn unit_or_zero_is_glams_normalize_or_zero(v in prop::array::uniform3(component())) {
            let v = Vec3::from(v);
            prop_assert_eq!(
                unit_or_zero(v).to_array().map(f32::to_bits),
                v.normalize_or_zero().to_array().map(f32::to_bits)
            );
        }

        /// Any triangle of finite vertices has a unit normal unless its area is zero in
        /// f64, including triangles whose f32 cross product overflows (edges of 1e20 and
        /// more) or underflows; non-finite vertices give zero.
        #[test]
        fn normals_exist_wherever_the_area_does(
            v in prop::array::uniform9(prop_oneof![
                component(),
                Just(3e38f32),
                Just(-3e38f32),
                Just(1e20f32),
                Just(1e-30f32),
            ]),
        ) {
            let p = [0, 1, 2].map(|k| Vec3::new(v[3 * k], v[3 * k + 1], v[3 * k + 2]));
            let n = triangle_normal(p);
            prop_assert!(n.is_finite());
            let [a, b, c] = p.map(|x| x.as_dvec3());
            let cross = (b - a).cross(c - a);
            if p.iter().all(|x| x.is_finite()) && cross.length() > 0.0 {
                // (Its direction is f32's: slivers mixing scales of 1e38 and 1e-30 cancel
                // in f32 as in any f32 renderer; the huge triangle below is checked against
                // f64.)
                prop_assert!((n.length() - 1.0).abs() < 1e-6, "{:?} -> {:?}", p, n);
            } else {
                prop_assert_eq!(n, Vec3::ZERO);
            }
        }
    }

    #[test]
    fn huge_and_tiny_triangles_have_normals() {
        let huge = [
            Vec3::new(0.0, -3e38, 0.0),
            Vec3::new(-1.84, 0.0, 1.5e-39),
            Vec3::new(-1.61, 1e30, 1.5e-39),
        ];
        let n = triangle_normal(huge);
        let [a, b, c] = huge.map(|x| x.as_dvec3());
        let exact = (b - a).cross(c - a).normalize();
        assert!(n.as_dvec3().dot(exact) > 1.0 - 1e-6, "{n} against {exact}");
        let tiny = [
            Vec3::ZERO,
            Vec3::new(1e-25, 0.0, 0.0),
            Vec3::new(0.0, 1e-25, 0.0),
        ];
        assert_eq!(triangle_normal(tiny), Vec3::Z);
        assert_eq!(triangle_normal([Vec3::ONE; 3]), Vec3::ZERO);
    }
}
