use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};

use glam::{Vec2, Vec3};

use super::{clamp_unit, clamp_unit2};
use crate::lanes::real::{Real, V3};

/// A point on the unit disk with uniform density 1/pi, by Shirley and Chiu's concentric
/// mapping ("A low distortion map between disk and square", JGT 2(3), 1997), which keeps
/// strata compact.
pub fn uniform_disk_concentric(u: Vec2) -> Vec2 {
    let [x, y] = disk_concentric([u.x, u.y]);
    Vec2::new(x, y)
}

/// A direction on the +z hemisphere with density cos(theta) / pi (Malley's method: a
/// uniform disk point projected up).
///
/// ```
/// use prism_sampling::glam::Vec2;
/// use prism_sampling::warp::{cosine_hemisphere, cosine_hemisphere_pdf};
///
/// let w = cosine_hemisphere(Vec2::new(0.3, 0.8));
/// assert!((w.length() - 1.0).abs() < 1e-6 && w.z >= 0.0);
/// assert!((cosine_hemisphere_pdf(w) - w.z / std::f32::consts::PI).abs() < 1e-7);
/// ```
pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    cosine_direction([u.x, u.y]).into()
}

/// [`uniform_disk_concentric`] of one sample or of lanes of them.
#[inline(always)]
pub fn disk_concentric<R: Real>(u: [R; 2]) -> [R; 2] {
    let [zero, one] = [R::splat(0.0), R::splat(1.0)];
    let [x, y] = clamp_unit(u).map(|v| R::splat(2.0) * v - one);
    let centre = !(x.ne(zero) | y.ne(zero));
    // The square's concentric rings to the disk's circles: the larger coordinate is the
    // radius, the other's ratio to it the angle within that quarter.
    let x_major = x.abs().gt(y.abs());
    let r = R::select(x_major, x, y);
    let ratio = R::select(x_major, y, x) / R::select(x_major, x, y);
    let theta = R::select(
        x_major,
        R::splat(FRAC_PI_4) * ratio,
        R::splat(FRAC_PI_2) - R::splat(FRAC_PI_4) * ratio,
    );
    let (sin, cos) = theta.sin_cos();
    [
        R::select(centre, zero, r * cos),
        R::select(centre, zero, r * sin),
    ]
}

/// [`cosine_hemisphere`] of one sample or of lanes of them.
#[inline(always)]
pub fn cosine_direction<R: Real>(u: [R; 2]) -> V3<R> {
    let [x, y] = disk_concentric(u);
    let z = (R::splat(1.0) - (x * x + y * y)).max(R::splat(0.0)).sqrt();
    V3::new(x, y, z)
}

/// The density of [`cosine_hemisphere`] for direction `w` (0 below the horizon).
pub fn cosine_hemisphere_pdf(w: Vec3) -> f32 {
    w.z.max(0.0) / PI
}

/// A direction with uniform density 1 / (4 pi) on the unit sphere.
pub fn uniform_sphere(u: Vec2) -> Vec3 {
    let u = clamp_unit2(u);
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// The density of [`uniform_sphere`]: 1 / (4 pi).
pub fn uniform_sphere_pdf() -> f32 {
    1.0 / (4.0 * PI)
}

/// A direction with uniform density in the cone around +z of half-angle
/// acos(`cos_theta_max`) (clamped into [-1, 1]; -1 is the whole sphere).
pub fn uniform_cone(u: Vec2, cos_theta_max: f32) -> Vec3 {
    let u = clamp_unit2(u);
    let cos_max = sanitize_cos(cos_theta_max);
    let cos_theta = (1.0 - u.x) + u.x * cos_max;
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta)
}

/// The density of [`uniform_cone`]: 1 / (2 pi (1 - cos_theta_max)); for a degenerate cone
/// (cos_theta_max = 1, a single direction) it is +inf, a delta distribution.
pub fn uniform_cone_pdf(cos_theta_max: f32) -> f32 {
    1.0 / (2.0 * PI * (1.0 - sanitize_cos(cos_theta_max)))
}

fn sanitize_cos(c: f32) -> f32 {
    if c.is_nan() { 1.0 } else { c.clamp(-1.0, 1.0) }
}
