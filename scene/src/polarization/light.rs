//! Polarized emission: lights whose light is partly linearly polarized (a lamp behind a
//! polarizing filter, a laser, skylight seen through an open window).

use glam::Vec3;

use super::Stokes;

/// Partial linear polarization of a light's emission: `degree` in [0, 1] at `angle`
/// radians from the light's x axis `axis` (world space) towards its y axis, for light
/// travelling along the light's -z; for other directions (a point light's) the axis is
/// projected across the direction of travel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearPolarization {
    /// Degree of linear polarization in [0, 1].
    pub degree: f32,
    /// Angle of the polarization, radians from `axis`.
    pub angle: f32,
    /// The light's x axis in world space.
    pub axis: Vec3,
}

impl LinearPolarization {
    /// The Stokes vector of unit intensity of light travelling along `travel` (unit), in
    /// the frame whose basis vector is returned with it.
    pub fn stokes(&self, travel: Vec3) -> (Stokes, Vec3) {
        let basis = (self.axis - travel * self.axis.dot(travel))
            .try_normalize()
            .unwrap_or_else(|| travel.any_orthonormal_vector());
        (Stokes::linear(1.0, self.degree, self.angle), basis)
    }
}
