//! The local shading frame BSDFs are evaluated in.

use glam::Vec3;

/// An orthonormal frame whose z is a given unit normal; its x and y are a fixed function
/// of the normal, so that the integrator and the scene (orienting anisotropy and a coat's
/// own normal at a hit) build the same frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// The first tangent.
    pub x: Vec3,
    /// The second tangent.
    pub y: Vec3,
    /// The normal.
    pub z: Vec3,
}

impl Frame {
    /// The frame of unit normal `z`.
    pub fn from_normal(z: Vec3) -> Self {
        let (x, y) = z.any_orthonormal_pair();
        Self { x, y, z }
    }

    /// A world direction in the frame.
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.x), v.dot(self.y), v.dot(self.z))
    }

    /// A local direction in the world.
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        v.x * self.x + v.y * self.y + v.z * self.z
    }
}
