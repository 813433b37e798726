use glam::Vec3;

/// A ray: origin, direction (not necessarily normalized) and the largest parameter of
/// interest. Directions are canonicalized on construction: -0.0 components become +0.0,
/// because obvhs 0.4 picks the traversal octant from the sign test `d < 0` while inverting
/// -0.0 to a negative number, and so misses rays with a -0.0 component.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Origin.
    pub origin: Vec3,
    /// Direction.
    pub direction: Vec3,
    /// Hits beyond this parameter are ignored.
    pub t_max: f32,
}

impl Ray {
    /// A ray from `origin` along `direction` up to `t_max`.
    pub fn new(origin: Vec3, direction: Vec3, t_max: f32) -> Self {
        // Adding +0.0 turns -0.0 into +0.0 and leaves every other value unchanged.
        Self {
            origin,
            direction: direction + Vec3::ZERO,
            t_max,
        }
    }

    /// The point at parameter `t`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.direction
    }
}
