//! Stokes vectors and the rotation of their reference frames.

use glam::{Vec3, Vec4, Vec4Swizzles};

use super::Mueller;

/// A Stokes vector (S0, S1, S2, S3) in some reference frame (see the module
/// documentation): intensity, linear along x or y, linear at 45 degrees, circular.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stokes(pub Vec4);

impl Stokes {
    /// Unpolarized light of intensity `s0`.
    pub fn unpolarized(s0: f32) -> Self {
        Self(Vec4::new(s0, 0.0, 0.0, 0.0))
    }

    /// Partially linearly polarized light of intensity `s0`, degree `degree` in [0, 1] and
    /// angle `angle` (radians, from x towards y); out-of-range degrees are clamped.
    pub fn linear(s0: f32, degree: f32, angle: f32) -> Self {
        let p = if degree.is_finite() {
            degree.clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (s, c) = (2.0 * angle).sin_cos();
        let (s, c) = if s.is_finite() { (s, c) } else { (0.0, 1.0) };
        Self(Vec4::new(s0, s0 * p * c, s0 * p * s, 0.0))
    }

    /// The intensity S0.
    pub fn intensity(self) -> f32 {
        self.0.x
    }

    /// Degree of polarization sqrt(S1^2 + S2^2 + S3^2) / S0 (0 for zero intensity).
    pub fn degree(self) -> f32 {
        ratio(self.0.yzw().length(), self.0.x)
    }

    /// Degree of linear polarization sqrt(S1^2 + S2^2) / S0 (0 for zero intensity).
    pub fn degree_linear(self) -> f32 {
        ratio(self.0.y.hypot(self.0.z), self.0.x)
    }

    /// Angle of linear polarization, radians in (-pi/2, pi/2]: atan2(S2, S1) / 2.
    pub fn angle_linear(self) -> f32 {
        0.5 * self.0.z.atan2(self.0.y)
    }

    /// Whether this can be light: finite, S0 >= |(S1, S2, S3)| (up to `tolerance` S0).
    pub fn is_physical(self, tolerance: f32) -> bool {
        self.0.is_finite() && self.0.yzw().length() <= self.0.x * (1.0 + tolerance) + 1e-30
    }
}

fn ratio(a: f32, b: f32) -> f32 {
    if b > 0.0 && a.is_finite() {
        (a / b).min(1.0)
    } else {
        0.0
    }
}

/// The Mueller matrix that re-expresses a Stokes vector of light travelling along `w`
/// from the frame with basis vector `from` to the frame with basis vector `to` (both
/// perpendicular to `w`, unit): a rotation about `w` by the angle from `from` to `to`.
/// Degenerate input (parallel or zero vectors) gives the identity.
pub fn rotate_frame(w: Vec3, from: Vec3, to: Vec3) -> Mueller {
    let cos = from.dot(to).clamp(-1.0, 1.0);
    let sin = w.dot(from.cross(to));
    let theta = sin.atan2(cos);
    if theta.is_finite() {
        Mueller::rotator(theta)
    } else {
        Mueller::IDENTITY
    }
}
