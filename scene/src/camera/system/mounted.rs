//! A lens system as a scene mounts it on a camera: the prescription, and the film, stop
//! and focus it is used with. [`MountedLens::focus`] makes it ready for an output's size.

use super::{FocusedSystem, LensSystem};
use crate::camera::FULL_FRAME_WIDTH;

/// A lens system on a camera.
#[derive(Debug, Clone, PartialEq)]
pub struct MountedLens {
    /// Where the prescription came from (a file name), for messages.
    pub source: String,
    /// The prescription.
    pub system: LensSystem,
    /// The f-number to close the stop to (None: as the prescription opens it).
    pub f_number: Option<f32>,
    /// The distance in focus from the film, metres (None: what the image's centre sees).
    pub focus_distance: Option<f32>,
    /// The film's width, metres.
    pub sensor_width: f32,
}

impl MountedLens {
    /// The prescription `system` read from `source`, wide open, before a full-frame film,
    /// focused on what the image's centre sees.
    pub fn new(source: impl Into<String>, system: LensSystem) -> Self {
        Self {
            source: source.into(),
            system,
            f_number: None,
            focus_distance: None,
            sensor_width: FULL_FRAME_WIDTH,
        }
    }

    /// The lens focused for an output of aspect ratio `aspect`: at its focus distance, or
    /// at `auto_focus`'s (metres; None: infinity). The error names the lens's source.
    pub fn focus(
        &self,
        aspect: f32,
        auto_focus: impl FnOnce() -> Option<f32>,
    ) -> Result<FocusedSystem, String> {
        let distance = self
            .focus_distance
            .or_else(auto_focus)
            .filter(|d| d.is_finite() && *d > 0.0)
            .map_or(f64::INFINITY, |d| 1000.0 * f64::from(d));
        FocusedSystem::new(
            &self.system,
            1000.0 * f64::from(self.sensor_width),
            f64::from(aspect),
            self.f_number.map(f64::from),
            distance,
        )
        .map_err(|e| format!("lens {}: {e}", self.source))
    }
}
