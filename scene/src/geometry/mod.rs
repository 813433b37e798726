//! Rays, the watertight ray-triangle test, robust spawn offsets and the BVH.

mod bvh;
mod frame;
mod offset;
mod ray;
mod triangle;

pub use bvh::{Bvh, BvhQuality, NodeLanes, SurfaceHit};
pub use frame::{Frame, Frames};
pub use offset::{offset_ray_origin, offset_ray_origin_to_side, triangle_point_error};
pub use ray::Ray;
pub(crate) use triangle::unit_or_zero;
pub use triangle::{TriangleHit, intersect_triangle, triangle_area, triangle_normal};
