use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::clamp_unit2;

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
    let [a, b, c] = v.map(|q| (q - p).normalize_or_zero());
    let numerator = a.dot(b.cross(c)).abs();
    let denominator = 1.0 + a.dot(b) + b.dot(c) + c.dot(a);
    let omega = 2.0 * numerator.atan2(denominator);
    if omega.is_finite() {
        omega.max(0.0)
    } else {
        0.0
    }
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
    let u = clamp_unit2(u);
    let [a, b, c] = v.map(|q| (q - p).normalize_or_zero());
    if a == Vec3::ZERO || b == Vec3::ZERO || c == Vec3::ZERO {
        return None;
    }
    // Normals of the great circles through the edges.
    let n_ab = a.cross(b).try_normalize()?;
    let n_bc = b.cross(c).try_normalize()?;
    let n_ca = c.cross(a).try_normalize()?;
    // Interior angles at the vertices.
    let alpha = angle_between(n_ab, -n_ca);
    let beta = angle_between(n_bc, -n_ab);
    let gamma = angle_between(n_ca, -n_bc);
    let area = alpha + beta + gamma - PI;
    if !(area > 0.0 && area.is_finite()) {
        return None;
    }
    // The sub-triangle of area u.x * area, expressed through its angle at `a`.
    let area_pi = PI + u.x * area;
    let (sin_ap, cos_ap) = area_pi.sin_cos();
    let (sin_alpha, cos_alpha) = alpha.sin_cos();
    let sin_phi = sin_ap * cos_alpha - cos_ap * sin_alpha;
    let cos_phi = cos_ap * cos_alpha + sin_ap * sin_alpha;
    let k1 = cos_phi + cos_alpha;
    let k2 = sin_phi - sin_alpha * a.dot(b);
    let denominator = (k2 * sin_phi + k1 * cos_phi) * sin_alpha;
    let cos_b = if denominator != 0.0 {
        ((k2 + (k2 * cos_phi - k1 * sin_phi) * cos_alpha) / denominator).clamp(-1.0, 1.0)
    } else {
        1.0
    };
    let sin_b = (1.0 - cos_b * cos_b).max(0.0).sqrt();
    // The sub-triangle's third vertex c' on the arc from a to c.
    let c_perp = (c - c.dot(a) * a).try_normalize()?;
    let c_prime = cos_b * a + sin_b * c_perp;
    // A point on the arc from b to c'.
    let cos_theta = 1.0 - u.y * (1.0 - c_prime.dot(b));
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let perp = (c_prime - c_prime.dot(b) * b)
        .try_normalize()
        .unwrap_or(Vec3::ZERO);
    let direction = (cos_theta * b + sin_theta * perp).try_normalize()?;
    Some(SphericalTriangleSample {
        direction,
        pdf: 1.0 / area,
    })
}

/// The angle between unit vectors, accurate for nearly parallel and nearly opposite
/// vectors (asin of half the chord instead of acos of the dot product).
fn angle_between(a: Vec3, b: Vec3) -> f32 {
    if a.dot(b) < 0.0 {
        PI - 2.0 * ((a + b).length() / 2.0).min(1.0).asin()
    } else {
        2.0 * ((b - a).length() / 2.0).min(1.0).asin()
    }
}
