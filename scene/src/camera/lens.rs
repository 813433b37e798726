//! A thin lens in front of a perspective camera: depth of field (*PBR* 4th ed. §5.2.3;
//! Kolb, Mitchell and Hanrahan, "A realistic camera model for computer graphics",
//! SIGGRAPH 1995, §2). A ray leaves a point of the aperture towards the point of the
//! plane in focus that the pinhole's ray through the same film point meets: points on that
//! plane are sharp, others blur into the aperture's shape, by the circle of confusion.
//!
//! How large the aperture is may be given as a radius in scene units (metres) or as an
//! f-number N, radius = f / (2 N), where the focal length f follows from the camera's
//! field of view and its sensor's width (36 mm, full frame, unless the scene says
//! otherwise), so that f-numbers mean what they mean on a camera.

use glam::Vec2;

use super::aperture::ApertureShape;

/// The full-frame sensor's width, metres: what a camera has unless it says otherwise.
pub const FULL_FRAME_WIDTH: f32 = 0.036;

/// How large the aperture is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ApertureSize {
    /// Its radius in scene units (metres in a glTF scene).
    Radius(f32),
    /// The f-number: focal length over the aperture's diameter.
    FNumber(f32),
}

/// A thin lens as a scene describes it.
#[derive(Debug, Clone, PartialEq)]
pub struct ThinLens {
    /// How large the aperture is.
    pub size: ApertureSize,
    /// Its shape.
    pub shape: ApertureShape,
    /// The distance in focus, along the view (None: what the image's centre sees).
    pub focus_distance: Option<f32>,
    /// The sensor's width, metres (what an f-number is relative to).
    pub sensor_width: f32,
}

impl ThinLens {
    /// A lens of this aperture size with a round aperture, focused on what the image's
    /// centre sees, in front of a full-frame sensor.
    pub fn new(size: ApertureSize) -> Self {
        Self {
            size,
            shape: ApertureShape::Disk,
            focus_distance: None,
            sensor_width: FULL_FRAME_WIDTH,
        }
    }

    /// The focal length, metres, of a camera of vertical field of view `yfov` rendering
    /// an image of aspect ratio `aspect` (width / height) on this sensor.
    pub fn focal_length(&self, yfov: f32, aspect: f32) -> f32 {
        0.5 * self.sensor_width / (aspect * (0.5 * yfov).tan())
    }

    /// The aperture's radius in scene units for such a camera.
    pub fn radius(&self, yfov: f32, aspect: f32) -> f32 {
        match self.size {
            ApertureSize::Radius(r) => r,
            ApertureSize::FNumber(n) => self.focal_length(yfov, aspect) / (2.0 * n),
        }
    }

    /// Checks that every number is usable: one line naming what is not.
    pub fn validate(&self) -> Result<(), String> {
        match self.size {
            ApertureSize::Radius(r) if !(r.is_finite() && r >= 0.0) => {
                return Err(format!("aperture radius {r} must be finite and >= 0"));
            }
            ApertureSize::FNumber(n) if !(n.is_finite() && n > 0.0) => {
                return Err(format!("f-number {n} must be finite and > 0"));
            }
            _ => {}
        }
        if let &ApertureShape::Polygon { blades, rotation } = &self.shape {
            if !(3..=64).contains(&blades) {
                return Err(format!("{blades} aperture blades (3 to 64)"));
            }
            if !rotation.is_finite() {
                return Err(format!("aperture rotation {rotation} must be finite"));
            }
        }
        if let Some(d) = self.focus_distance
            && !(d.is_finite() && d > 0.0)
        {
            return Err(format!("focus distance {d} must be finite and > 0"));
        }
        if !(self.sensor_width.is_finite() && self.sensor_width > 0.0) {
            return Err(format!(
                "sensor width {} must be finite and > 0",
                self.sensor_width
            ));
        }
        Ok(())
    }
}

/// A thin lens ready to render with: its aperture's radius (scene units) and shape, and
/// the distance in focus along the view.
#[derive(Debug, Clone, PartialEq)]
pub struct Focus {
    /// The aperture's radius (its shape's corners lie on it), scene units.
    pub radius: f32,
    /// The aperture's shape.
    pub shape: ApertureShape,
    /// The distance of the plane in focus along the view, scene units (infinite: focused
    /// at infinity).
    pub distance: f32,
}

impl Focus {
    /// The point of the aperture (camera space, the lens plane z = 0) for `u` in [0, 1)^2.
    pub fn lens_point(&self, u: Vec2) -> Vec2 {
        self.radius * self.shape.sample(u)
    }
}
