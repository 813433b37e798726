//! First-order properties of a lens system per wavelength, by tracing rays close to the
//! axis through the same code that renders (`LensSystem::trace_from_scene`): the
//! effective focal length (a ray entering parallel at height h leaves with slope u':
//! f = -h / u'), the back focal distance (where that ray crosses the axis behind the last
//! interface), the entrance pupil (the widest parallel bundle the apertures pass), and the
//! f-number f / D.

use glam::DVec3;

use super::{LensRay, LensSystem};

/// A system's first-order properties at one wavelength, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Paraxial {
    /// The wavelength, nm.
    pub wavelength_nm: f64,
    /// Effective focal length.
    pub efl_mm: f64,
    /// Back focal distance: from the last interface to the paraxial focus.
    pub bfd_mm: f64,
    /// Entrance pupil diameter (for a bundle parallel to the axis).
    pub entrance_pupil_mm: f64,
    /// The f-number, efl / entrance pupil diameter.
    pub f_number: f64,
}

impl LensSystem {
    /// The first-order properties at `lambda_nm`, or an error saying why there are none
    /// (no ray passes near the axis, or the system does not focus).
    pub fn paraxial(&self, lambda_nm: f64) -> Result<Paraxial, String> {
        let smallest = self
            .interfaces()
            .iter()
            .map(|i| i.aperture_radius)
            .fold(f64::INFINITY, f64::min);
        let h = 1e-4 * smallest;
        let start = -self.length() - 1.0;
        let parallel = |height: f64| LensRay {
            origin: DVec3::new(0.0, height, start),
            direction: DVec3::Z,
        };
        let out = self
            .trace_from_scene(parallel(h), lambda_nm)
            .ok_or_else(|| format!("no ray passes near the axis at {lambda_nm} nm"))?;
        let slope = out.direction.y / out.direction.z;
        if !(slope.is_finite() && slope != 0.0) {
            return Err(format!(
                "the system does not focus at {lambda_nm} nm (afocal)"
            ));
        }
        let efl = -h / slope;
        // Behind the last interface (at z = -last thickness) the ray crosses the axis.
        let last_z = -self.interfaces().last().map_or(0.0, |i| i.thickness);
        let crossing_z = out.origin.z - out.origin.y / slope;
        let bfd = crossing_z - last_z;
        // The widest parallel bundle: bisection on the height that still passes.
        let (mut inside, mut outside) = (h, self.interfaces()[0].aperture_radius * 1.0001);
        if self
            .trace_from_scene(parallel(outside), lambda_nm)
            .is_some()
        {
            inside = outside;
        } else {
            for _ in 0..60 {
                let mid = 0.5 * (inside + outside);
                if self.trace_from_scene(parallel(mid), lambda_nm).is_some() {
                    inside = mid;
                } else {
                    outside = mid;
                }
            }
        }
        let pupil = 2.0 * inside;
        Ok(Paraxial {
            wavelength_nm: lambda_nm,
            efl_mm: efl,
            bfd_mm: bfd,
            entrance_pupil_mm: pupil,
            f_number: efl.abs() / pupil,
        })
    }
}
