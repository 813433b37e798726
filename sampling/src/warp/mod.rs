//! Warps from the unit square to the shapes a renderer samples, each with its density.
//!
//! Directions are unit `glam::Vec3` in a local frame with +z as the normal or axis.
//! Every function clamps its uniform inputs into [0, 1) and returns finite values.

mod hemisphere;
mod spherical_triangle;
mod triangle;

pub use hemisphere::{
    cosine_hemisphere, cosine_hemisphere_pdf, uniform_cone, uniform_cone_pdf,
    uniform_disk_concentric, uniform_sphere, uniform_sphere_pdf,
};
pub use spherical_triangle::{
    SphericalTriangleSample, spherical_triangle, spherical_triangle_solid_angle,
};
pub use triangle::{uniform_triangle, uniform_triangle_pdf};

use glam::Vec2;

/// Both components of `u` clamped into [0, 1) (NaN to 0).
pub(crate) fn clamp_unit2(u: Vec2) -> Vec2 {
    let c = |v: f32| {
        if v.is_nan() || v < 0.0 {
            0.0
        } else {
            v.min(1.0 - f32::EPSILON / 2.0)
        }
    };
    Vec2::new(c(u.x), c(u.y))
}
