//! Warps from the unit square to the shapes a renderer samples, each with its density.
//!
//! Directions are unit `glam::Vec3` in a local frame with +z as the normal or axis.
//! Every function clamps its uniform inputs into [0, 1) and returns finite values.

mod hemisphere;
mod spherical_triangle;
mod triangle;

pub use hemisphere::{
    cosine_direction, cosine_hemisphere, cosine_hemisphere_pdf, disk_concentric, uniform_cone,
    uniform_cone_pdf, uniform_disk_concentric, uniform_sphere, uniform_sphere_pdf,
};
pub use spherical_triangle::{
    SphericalTriangleSample, solid_angle, spherical_triangle, spherical_triangle_sample,
    spherical_triangle_solid_angle,
};
pub use triangle::{uniform_triangle, uniform_triangle_pdf};

use glam::Vec2;

use crate::lanes::real::Real;

/// Both components of `u` clamped into [0, 1) (NaN to 0).
pub(crate) fn clamp_unit2(u: Vec2) -> Vec2 {
    let [x, y] = clamp_unit([u.x, u.y]);
    Vec2::new(x, y)
}

/// Each number of one sample or of lanes of them into [0, 1), NaN to 0.
#[inline(always)]
pub(crate) fn clamp_unit<R: Real>(u: [R; 2]) -> [R; 2] {
    let zero = R::splat(0.0);
    u.map(|x| R::select(zero.le(x), x.min(R::splat(1.0 - f32::EPSILON / 2.0)), zero))
}
