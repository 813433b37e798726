use glam::{Vec2, Vec3};

use super::clamp_unit2;

/// Barycentric coordinates (b0, b1, b2) uniformly distributed over a triangle, by
/// Heitz's low-distortion mapping ("A low-distortion map between triangle and square",
/// 2019), which preserves the stratification of `u`.
pub fn uniform_triangle(u: Vec2) -> [f32; 3] {
    let u = clamp_unit2(u);
    let (b0, b1) = if u.x < u.y {
        let b0 = u.x / 2.0;
        (b0, u.y - b0)
    } else {
        let b1 = u.y / 2.0;
        (u.x - b1, b1)
    };
    [b0, b1, (1.0 - b0 - b1).max(0.0)]
}

/// The density of [`uniform_triangle`] with respect to area: 1 / area, or 0 for a
/// degenerate triangle (which cannot be sampled).
pub fn uniform_triangle_pdf(p0: Vec3, p1: Vec3, p2: Vec3) -> f32 {
    let area = 0.5 * (p1 - p0).cross(p2 - p0).length();
    if area > 0.0 && area.is_finite() {
        1.0 / area
    } else {
        0.0
    }
}
