//! The local shading frame BSDFs are evaluated in.

use glam::Vec3;
use prism_sampling::lanes::real::{Real, V3};

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
    #[inline(always)]
    pub fn from_normal(z: Vec3) -> Self {
        let frame = Frames::<f32>::from_normal(z.into());
        Self {
            x: frame.x.into(),
            y: frame.y.into(),
            z,
        }
    }

    /// A world direction in the frame.
    #[inline(always)]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.x), v.dot(self.y), v.dot(self.z))
    }

    /// A local direction in the world.
    #[inline(always)]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        v.x * self.x + v.y * self.y + v.z * self.z
    }
}

/// [`Frame`] for one path or for lanes of them (a batch of paths, each lane its own
/// frame), with the same operations in the same order: lane by lane, the scalar frame and
/// its transforms to the bit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frames<R> {
    /// The first tangents.
    pub x: V3<R>,
    /// The second tangents.
    pub y: V3<R>,
    /// The normals.
    pub z: V3<R>,
}

impl<R: Real> Frames<R> {
    /// The frames of unit normals `z`: Duff et al.'s branchless orthonormal basis
    /// ("Building an orthonormal basis, revisited", JCGT 6(1), 2017, listing 3), which is
    /// glam's `any_orthonormal_pair`.
    #[inline(always)]
    pub fn from_normal(z: V3<R>) -> Self {
        let sign = z.z.signum();
        let a = R::splat(-1.0) / (sign + z.z);
        let b = z.x * z.y * a;
        Self {
            x: V3::new(R::splat(1.0) + sign * z.x * z.x * a, sign * b, -sign * z.x),
            y: V3::new(b, sign + z.y * z.y * a, -z.y),
            z,
        }
    }

    /// World directions in the frames.
    #[inline(always)]
    pub fn to_local(&self, v: V3<R>) -> V3<R> {
        V3::new(v.dot(self.x), v.dot(self.y), v.dot(self.z))
    }

    /// Local directions in the world.
    #[inline(always)]
    pub fn to_world(&self, v: V3<R>) -> V3<R> {
        self.x.scale(v.x) + self.y.scale(v.y) + self.z.scale(v.z)
    }
}
