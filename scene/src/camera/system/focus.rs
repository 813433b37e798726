//! Where a lens system's film goes to focus at a distance: the thick-lens approximation
//! of *PBR* 4th ed. §5.3.3 (pbrt-v4's `ComputeThickLensApproximation` and
//! `FocusThickLens`). A ray parallel to the axis from either side finds the system's
//! principal plane and focal point on the other; Gauss's equation 1/s + 1/s' = 1/f between
//! the principal planes then says how far the film must move for an object at a given
//! distance to image on it.

use glam::DVec3;

use super::{LensRay, LensSystem};

/// A lens system's cardinal points on the axis (z, mm, in the system's space: the film at
/// 0, the object's side at negative z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThickLens {
    /// The front principal plane (object side).
    pub front_principal_z: f64,
    /// The front focal point.
    pub front_focal_z: f64,
    /// The rear principal plane (film side).
    pub rear_principal_z: f64,
    /// The rear focal point.
    pub rear_focal_z: f64,
}

impl ThickLens {
    /// The effective focal length (rear focal point to rear principal plane).
    pub fn focal_length(&self) -> f64 {
        self.rear_focal_z - self.rear_principal_z
    }
}

impl LensSystem {
    /// The thick-lens approximation at `lambda_nm` (None where no near-axis ray passes
    /// or the system does not focus).
    pub fn thick_lens(&self, lambda_nm: f64) -> Option<ThickLens> {
        let smallest = self
            .interfaces()
            .iter()
            .map(|i| i.aperture_radius)
            .fold(f64::INFINITY, f64::min);
        let h = 1e-4 * smallest;
        // From the scene: parallel at height h, out through the rear.
        let entering = LensRay {
            origin: DVec3::new(0.0, h, -self.length() - 1.0),
            direction: DVec3::Z,
        };
        let out = self.trace_from_scene(entering, lambda_nm)?;
        let (rear_focal_z, rear_principal_z) = cardinal(&entering, &out)?;
        // From the film: parallel at height h, out through the front.
        let entering = LensRay {
            origin: DVec3::new(0.0, h, 1.0),
            direction: -DVec3::Z,
        };
        let out = self.trace_from_film(entering, lambda_nm)?;
        let (front_focal_z, front_principal_z) = cardinal(&entering, &out)?;
        Some(ThickLens {
            front_principal_z,
            front_focal_z,
            rear_principal_z,
            rear_focal_z,
        })
    }

    /// How far (mm) to move the film back (positive) or forward from where the
    /// prescription puts it so that an object `distance` mm in front of the film is in
    /// focus at `lambda_nm`; None where there is no thick lens or no real image.
    pub fn focus_shift(&self, distance: f64, lambda_nm: f64) -> Option<f64> {
        let lens = self.thick_lens(lambda_nm)?;
        let f = lens.focal_length();
        // The object at z = -distance, its distance s from the front principal plane; the
        // image s' = s f / (s - f) behind the rear principal plane (Gauss).
        let s = lens.front_principal_z + distance;
        if !(s > f && f > 0.0) {
            return None;
        }
        let image_z = lens.rear_principal_z + s * f / (s - f);
        // The film is at z = 0; it moves to the image.
        let shift = image_z;
        shift.is_finite().then_some(shift)
    }
}

/// Where the ray `out` (leaving the system) crosses the axis, and where it reaches the
/// height the parallel ray `entering` came in at: the focal point and the principal plane.
fn cardinal(entering: &LensRay, out: &LensRay) -> Option<(f64, f64)> {
    if out.direction.y == 0.0 {
        return None;
    }
    let focal = out.origin.z - out.origin.y / out.direction.y * out.direction.z;
    let principal =
        out.origin.z + (entering.origin.y - out.origin.y) / out.direction.y * out.direction.z;
    (focal.is_finite() && principal.is_finite()).then_some((focal, principal))
}
