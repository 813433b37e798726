//! Exit-pupil bounds (*PBR* 4th ed. §5.3.4, pbrt-v4's `BoundExitPupil`): of the rays from
//! a point of the film towards the rear element, only those aimed into the exit pupil
//! (the stop's image seen from the film) pass the system. Found once per film radius by
//! tracing a grid of rays, the pupil's bounding box lets camera rays aim where rays pass
//! instead of at the whole rear element.

use glam::DVec3;

use super::{LensRay, LensSystem};

/// Grid points per side of the square searched on the rear element's plane by
/// [`LensSystem::exit_pupil`].
const GRID: usize = 256;

/// An axis-aligned box on the rear element's plane (mm): min x, min y, max x, max y.
pub type PupilBounds = [f64; 4];

impl LensSystem {
    /// The bounds, on the rear element's plane, of the rays from the film point at
    /// distance `film_x` from the axis (on its x axis, the film where the prescription
    /// puts it) that pass the system at `lambda_nm`, grown by one grid cell; None where
    /// none passes.
    pub fn exit_pupil(&self, film_x: f64, lambda_nm: f64) -> Option<PupilBounds> {
        self.exit_pupil_from(DVec3::new(film_x, 0.0, 0.0), lambda_nm, GRID)
    }

    /// [`LensSystem::exit_pupil`] from the film point `film` (on the x axis's half plane
    /// y = 0, at any z behind the rear element), searched on a `grid` x `grid` grid.
    pub fn exit_pupil_from(&self, film: DVec3, lambda_nm: f64, grid: usize) -> Option<PupilBounds> {
        let rear = self.interfaces().last()?;
        let rear_z = -rear.thickness;
        // The rear element's square, half again as wide: the pupil may be off the axis.
        let half = 1.5 * rear.aperture_radius;
        let cell = 2.0 * half / grid as f64;
        let mut bounds: Option<PupilBounds> = None;
        for j in 0..grid {
            for i in 0..grid {
                let p = DVec3::new(
                    -half + (i as f64 + 0.5) * cell,
                    -half + (j as f64 + 0.5) * cell,
                    rear_z,
                );
                let ray = LensRay {
                    origin: film,
                    direction: (p - film).normalize(),
                };
                if self.trace_from_film(ray, lambda_nm).is_some() {
                    let b = bounds.get_or_insert([p.x, p.y, p.x, p.y]);
                    *b = [b[0].min(p.x), b[1].min(p.y), b[2].max(p.x), b[3].max(p.y)];
                }
            }
        }
        bounds.map(|b| [b[0] - cell, b[1] - cell, b[2] + cell, b[3] + cell])
    }
}
