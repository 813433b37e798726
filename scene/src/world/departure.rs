//! Where the shadow rays of one vertex leave it: a vertex that many rays leave (a first
//! vertex of path reuse connects to every second vertex of its tile) offsets its origin
//! once per side of its surface instead of once per ray.

use glam::Vec3;

use super::Hit;
use crate::geometry::{Ray, offset_ray_origin_to_side};

/// The two origins [`Hit::spawn_to`] chooses between, and how far each lies from the hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Departure {
    normal: Vec3,
    front: Vec3,
    front_offset: f32,
    back: Vec3,
    back_offset: f32,
}

impl Hit {
    /// The origins of the rays leaving this hit.
    #[inline]
    pub fn departure(&self) -> Departure {
        let front = offset_ray_origin_to_side(self.p, self.error, self.normal, false);
        let back = offset_ray_origin_to_side(self.p, self.error, self.normal, true);
        Departure {
            normal: self.normal,
            front,
            front_offset: (front - self.p).length(),
            back,
            back_offset: (back - self.p).length(),
        }
    }
}

impl Departure {
    /// [`Hit::spawn_to`] of the hit, to the bit: a shadow ray towards a point `distance`
    /// away along the unit `direction`, stopping just short of it.
    #[inline]
    pub fn ray_to(&self, direction: Vec3, distance: f32) -> Ray {
        let (origin, offset) = if direction.dot(self.normal) < 0.0 {
            (self.back, self.back_offset)
        } else {
            (self.front, self.front_offset)
        };
        let t_max = if distance.is_finite() {
            (distance - offset) * (1.0 - 1e-4)
        } else {
            f32::INFINITY
        };
        Ray::new(origin, direction, t_max.max(0.0))
    }
}
