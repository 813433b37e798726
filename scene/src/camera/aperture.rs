//! The shape of a lens's aperture: a disk, or the regular polygon its blades leave. Points
//! on it are drawn uniformly over its area (a thin lens lets light through every point of
//! its opening alike), and the shape is what the blur of an out-of-focus highlight takes
//! (its bokeh).

use std::f32::consts::PI;

use glam::Vec2;
use prism_sampling::warp::{uniform_disk_concentric, uniform_triangle};

/// An aperture's shape, at unit size: a disk of radius 1, or a regular polygon whose
/// corners lie on the unit circle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ApertureShape {
    /// A circular opening.
    Disk,
    /// The opening `blades` straight blades leave (3 or more): a regular polygon, one
    /// corner at angle `rotation` (radians, counter-clockwise from the image's +x).
    Polygon {
        /// How many blades (corners).
        blades: u32,
        /// The first corner's angle, radians.
        rotation: f32,
    },
}

impl ApertureShape {
    /// A point of the shape from `u` in [0, 1)^2, uniform over its area.
    pub fn sample(&self, u: Vec2) -> Vec2 {
        match *self {
            ApertureShape::Disk => uniform_disk_concentric(u),
            ApertureShape::Polygon { blades, rotation } => {
                // A wedge (the triangle centre, corner k, corner k + 1) chosen by u.x,
                // what is left of u.x reused within it: all wedges have the same area.
                let n = blades.max(3) as f32;
                let scaled = u.x * n;
                let k = scaled.floor().min(n - 1.0);
                let reused = Vec2::new((scaled - k).clamp(0.0, 1.0 - f32::EPSILON), u.y);
                let b = uniform_triangle(reused);
                let corner = |i: f32| {
                    let a = rotation + 2.0 * PI * i / n;
                    Vec2::new(a.cos(), a.sin())
                };
                b[1] * corner(k) + b[2] * corner(k + 1.0)
            }
        }
    }

    /// Its area at unit size.
    pub fn area(&self) -> f32 {
        match *self {
            ApertureShape::Disk => PI,
            ApertureShape::Polygon { blades, .. } => {
                let n = blades.max(3) as f32;
                0.5 * n * (2.0 * PI / n).sin()
            }
        }
    }

    /// Whether the point `p` (at unit size) is inside the shape.
    pub fn contains(&self, p: Vec2) -> bool {
        match *self {
            ApertureShape::Disk => p.length_squared() <= 1.0,
            ApertureShape::Polygon { blades, rotation } => {
                let n = blades.max(3) as f32;
                // Inside every edge: the distance along each edge's outward normal is at
                // most the apothem.
                let apothem = (PI / n).cos();
                (0..blades.max(3)).all(|i| {
                    let a = rotation + (2.0 * i as f32 + 1.0) * PI / n;
                    p.dot(Vec2::new(a.cos(), a.sin())) <= apothem + 1e-6
                })
            }
        }
    }
}
