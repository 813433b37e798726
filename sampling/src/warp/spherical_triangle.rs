use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use crate::lanes::real::{Real, V3};

/// A direction sampled uniformly in the solid angle a triangle subtends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphericalTriangleSample {
    /// Unit direction from the reference point towards the triangle.
    pub direction: Vec3,
    /// Density with respect to solid angle: 1 / (subtended solid angle).
    pub pdf: f32,
}

/// The solid angle the triangle `v` subtends from `p` (Van Oosterom and Strackee, IEEE
/// Trans. Biomed. Eng. 30(2), 1983): 2 atan(|a . (b x c)| / (1 + a.b + b.c + c.a)) with
/// a, b, c the unit directions to the vertices. 0 for degenerate input.
pub fn spherical_triangle_solid_angle(p: Vec3, v: [Vec3; 3]) -> f32 {
    solid_angle(p.into(), v.map(V3::from))
}

/// [`spherical_triangle_solid_angle`] of one point or of lanes of them.
#[inline(always)]
pub fn solid_angle<R: Real>(p: V3<R>, v: [V3<R>; 3]) -> R {
    let [a, b, c] = v.map(|q| (q - p).normalize_or_zero());
    let numerator = a.dot(b.cross(c)).abs();
    let denominator = R::splat(1.0) + a.dot(b) + b.dot(c) + c.dot(a);
    let omega = R::splat(2.0) * numerator.atan2(denominator);
    R::select(omega.is_finite(), omega.max(R::splat(0.0)), R::splat(0.0))
}

/// Uniform sampling of the solid angle subtended by triangle `v` as seen from `p`, by
/// Arvo's method ("Stratified sampling of spherical triangles", SIGGRAPH 1995), in the
/// numerically careful arrangement of *PBR* 4th ed. §6.5.4. `u.x` chooses the sub-area,
/// `u.y` the point along the arc.
///
/// Returns `None` when the triangle is degenerate as seen from `p` (collinear directions,
/// `p` in its plane, zero solid angle), where solid-angle sampling is undefined and the
/// caller should sample by area. In `f32` the method loses accuracy for solid angles
/// below about 1e-4 sr; callers switch to area sampling there (as pbrt does).
pub fn spherical_triangle(p: Vec3, v: [Vec3; 3], u: Vec2) -> Option<SphericalTriangleSample> {
    let (direction, pdf, valid) = spherical_triangle_sample(p.into(), v.map(V3::from), [u.x, u.y]);
    valid.then(|| SphericalTriangleSample {
        direction: direction.into(),
        pdf,
    })
}

/// [`spherical_triangle`] of one point or of lanes of them: the direction, its density
/// and where it is valid (elsewhere both are meaningless).
#[inline(always)]
pub fn spherical_triangle_sample<R: Real>(
    p: V3<R>,
    v: [V3<R>; 3],
    u: [R; 2],
) -> (V3<R>, R, R::Mask) {
    let [zero, one] = [R::splat(0.0), R::splat(1.0)];
    let [ux, uy] = super::clamp_unit(u);
    let [a, b, c] = v.map(|q| (q - p).normalize_or_zero());
    let mut valid = !(a.is_zero() | b.is_zero() | c.is_zero());
    // Normals of the great circles through the edges.
    let (n_ab, ok_ab) = a.cross(b).try_normalize();
    let (n_bc, ok_bc) = b.cross(c).try_normalize();
    let (n_ca, ok_ca) = c.cross(a).try_normalize();
    valid = valid & ok_ab & ok_bc & ok_ca;
    // Interior angles at the vertices.
    let alpha = angle_between(n_ab, -n_ca);
    let beta = angle_between(n_bc, -n_ab);
    let gamma = angle_between(n_ca, -n_bc);
    let area = alpha + beta + gamma - R::splat(PI);
    valid = valid & area.gt(zero) & area.is_finite();
    // The sub-triangle of area u.x * area, expressed through its angle at `a`.
    let area_pi = R::splat(PI) + ux * area;
    let (sin_ap, cos_ap) = area_pi.sin_cos();
    let (sin_alpha, cos_alpha) = alpha.sin_cos();
    let sin_phi = sin_ap * cos_alpha - cos_ap * sin_alpha;
    let cos_phi = cos_ap * cos_alpha + sin_ap * sin_alpha;
    let k1 = cos_phi + cos_alpha;
    let k2 = sin_phi - sin_alpha * a.dot(b);
    let denominator = (k2 * sin_phi + k1 * cos_phi) * sin_alpha;
    let ratio = (k2 + (k2 * cos_phi - k1 * sin_phi) * cos_alpha) / denominator;
    let cos_b = R::select(denominator.ne(zero), clamp_signed_unit(ratio), one);
    let sin_b = (one - cos_b * cos_b).max(zero).sqrt();
    // The sub-triangle's third vertex c' on the arc from a to c.
    let (c_perp, ok_perp) = (c - a.scale(c.dot(a))).try_normalize();
    valid = valid & ok_perp;
    let c_prime = a.scale(cos_b) + c_perp.scale(sin_b);
    // A point on the arc from b to c'.
    let cos_theta = one - uy * (one - c_prime.dot(b));
    let sin_theta = (one - cos_theta * cos_theta).max(zero).sqrt();
    let (perp, ok_arc) = (c_prime - b.scale(c_prime.dot(b))).try_normalize();
    let perp = V3::select(ok_arc, perp, V3::zero());
    let (direction, ok_direction) = (b.scale(cos_theta) + perp.scale(sin_theta)).try_normalize();
    (direction, one / area, valid & ok_direction)
}

/// `x` clamped to [-1, 1] as `f32::clamp` clamps (NaN stays NaN).
#[inline(always)]
fn clamp_signed_unit<R: Real>(x: R) -> R {
    let (low, high) = (R::splat(-1.0), R::splat(1.0));
    R::select(x.lt(low), low, R::select(x.gt(high), high, x))
}

/// The angle between unit vectors, accurate for nearly parallel and nearly opposite
/// vectors (asin of half the chord instead of acos of the dot product).
#[inline(always)]
fn angle_between<R: Real>(a: V3<R>, b: V3<R>) -> R {
    let opposite = a.dot(b).lt(R::splat(0.0));
    let chord = V3::select(opposite, a + b, b - a);
    let half = R::splat(2.0) * (chord.length() / R::splat(2.0)).asin_min1();
    R::select(opposite, R::splat(PI) - half, half)
}
