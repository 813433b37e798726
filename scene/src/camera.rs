//! Cameras: glTF perspective and orthographic projections placed by a node, and a default
//! camera that frames a scene without one.

use glam::{Mat4, Vec2, Vec3};

use crate::geometry::Ray;

/// How a camera maps the film to rays.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// A pinhole with vertical field of view `yfov` (radians); the horizontal one follows
    /// from the output's aspect ratio (glTF's `aspectRatio` is a hint prism ignores: the
    /// output size decides).
    Perspective {
        /// Vertical field of view, radians, in (0, pi).
        yfov: f32,
    },
    /// Parallel rays over a rectangle of half-width `xmag` and half-height `ymag`.
    Orthographic {
        /// Half of the view's width.
        xmag: f32,
        /// Half of the view's height.
        ymag: f32,
    },
}

/// A camera: a projection and its placement (glTF convention: looking down -z, +y up).
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    /// The node's name, or `camera N`, or `default`.
    pub name: String,
    /// Camera to world.
    pub to_world: Mat4,
    /// The projection.
    pub projection: Projection,
}

impl Camera {
    /// The ray through film position `film` in [0, 1]^2 (x right, y down, as images are
    /// stored) for an output of aspect ratio `aspect` = width / height.
    pub fn generate_ray(&self, film: Vec2, aspect: f32) -> Ray {
        let ndc = Vec2::new(2.0 * film.x - 1.0, 1.0 - 2.0 * film.y);
        let (origin, direction) = match self.projection {
            Projection::Perspective { yfov } => {
                let h = (0.5 * yfov).tan();
                (Vec3::ZERO, Vec3::new(ndc.x * h * aspect, ndc.y * h, -1.0))
            }
            Projection::Orthographic { xmag, ymag } => {
                (Vec3::new(ndc.x * xmag, ndc.y * ymag, 0.0), -Vec3::Z)
            }
        };
        let origin = self.to_world.transform_point3(origin);
        let direction = self
            .to_world
            .transform_vector3(direction)
            .normalize_or(-Vec3::Z);
        Ray::new(origin, direction, f32::INFINITY)
    }

    /// A perspective camera (45 degree vertical field of view) looking down -z at the box
    /// `[lo, hi]` from far enough in +z that the whole box is in view at any aspect >= 1:
    /// what a scene without a camera gets.
    pub fn framing(lo: Vec3, hi: Vec3) -> Self {
        let yfov = 45f32.to_radians();
        let center = 0.5 * (lo + hi);
        let radius = (0.5 * (hi - lo)).length().max(1e-3);
        // The bounding sphere fits the vertical field of view.
        let distance = radius / (0.5 * yfov).sin();
        Self {
            name: "default".into(),
            to_world: Mat4::from_translation(center + Vec3::new(0.0, 0.0, distance)),
            projection: Projection::Perspective { yfov },
        }
    }
}
