use glam::Vec3;

/// gamma(n) = n eps / (1 - n eps), the bound on the relative error of n floating-point
/// operations (*PBR* 4th ed. §6.8.1), eps = f32::EPSILON / 2.
pub(crate) fn gamma(n: i32) -> f32 {
    let e = f32::EPSILON * 0.5 * n as f32;
    e / (1.0 - e)
}

/// The absolute error bound of a point computed from barycentrics as b0 p0 + b1 p1 + b2 p2
/// (*PBR* 4th ed. §6.8.5): gamma(7) (|b0 p0| + |b1 p1| + |b2 p2|).
pub fn triangle_point_error(p: [Vec3; 3], barycentric: [f32; 3]) -> Vec3 {
    let sum = (p[0] * barycentric[0]).abs()
        + (p[1] * barycentric[1]).abs()
        + (p[2] * barycentric[2]).abs();
    gamma(7) * sum
}

/// The origin for a ray leaving surface point `p` (with error bound `error`) towards
/// `direction`: `p` pushed along the geometric normal `n` by the projection of the error
/// box, to the side the ray leaves on, then rounded away from `p` so that it is certainly
/// outside the error box (*PBR* 4th ed. §6.8.6). A spawned ray then cannot re-hit the
/// surface it starts on through rounding.
// Always inlined: two calls per bounce, and out of line (where LLVM placed it without the
// attribute) it cost the Cornell box's paths more instructions.
#[inline(always)]
pub fn offset_ray_origin(p: Vec3, error: Vec3, n: Vec3, direction: Vec3) -> Vec3 {
    offset_ray_origin_to_side(p, error, n, direction.dot(n) < 0.0)
}

/// [`offset_ray_origin`] for every direction on one side of the surface: behind the
/// normal `n` (`behind`, a direction whose dot product with `n` is negative) or in front
/// of it.
#[inline(always)]
pub fn offset_ray_origin_to_side(p: Vec3, error: Vec3, n: Vec3, behind: bool) -> Vec3 {
    let distance = n.abs().dot(error);
    let mut offset = distance * n;
    if behind {
        offset = -offset;
    }
    let mut origin = p + offset;
    for axis in 0..3 {
        if offset[axis] > 0.0 {
            origin[axis] = origin[axis].next_up();
        } else if offset[axis] < 0.0 {
            origin[axis] = origin[axis].next_down();
        }
    }
    origin
}
