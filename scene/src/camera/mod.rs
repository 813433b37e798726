//! Cameras: glTF perspective and orthographic projections placed by a node, and a default
//! camera that frames a scene without one. A perspective camera is a pinhole unless it
//! has a thin lens (`lens`: depth of field, the aperture's shape in its bokeh).

mod aperture;
mod lens;
pub mod system;

pub use aperture::{ApertureImage, ApertureShape};
pub use lens::{ApertureSize, FULL_FRAME_WIDTH, Focus, ThinLens};
pub use system::{FocusedSystem, MountedLens};

use glam::{Mat4, Vec2, Vec3};

use crate::geometry::Ray;

/// How a camera maps the film to rays.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// A pinhole with vertical field of view `yfov` (radians); the horizontal one follows
    /// from the output's aspect ratio (glTF's `aspectRatio` only suggests the output's
    /// default size, [`Camera::aspect_ratio`]: the output size decides).
    Perspective {
        /// Vertical field of view, radians, in (0, pi).
        yfov: f32,
    },
    /// Parallel rays over a rectangle of half-width `xmag` and half-height `ymag`.
    Orthographic {
        /// Half of the view's width.
        xmag: f32,
        /// Half of the view's height.
        ymag: f32,
    },
}

/// A point seen by the camera: where on the film, and how to connect to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilmPoint {
    /// Film position in [0, 1)^2 (x right, y down).
    pub film: Vec2,
    /// Unit direction from the camera to the point.
    pub direction: Vec3,
    /// Distance from the camera to the point.
    pub distance: f32,
    /// The camera's importance towards the point, per unit film area and solid angle:
    /// radiance `L` arriving from it adds `L * importance * cos_at_point / distance^2` per
    /// unit of the point's area to the film's mean.
    pub importance: f32,
}

impl FilmPoint {
    /// `point` seen at `film` from `origin` (on the camera's lens or pinhole), the ray
    /// making cosine `cos(direction)` with the view's axis, by a perspective camera whose image plane
    /// at distance 1 is 2 `h` high and `aspect` times as wide. The importance is a
    /// pinhole's per unit film area, normalized so that the film's unit square integrates
    /// to one: 1 / (A cos^3) per unit solid angle with the cosine at the camera already
    /// folded in (Veach 1997, §10.2; *PBR* 4th ed. §5.1.6), A = the image plane's area.
    fn seen(
        film: Vec2,
        origin: Vec3,
        point: Vec3,
        cos: impl FnOnce(Vec3) -> f32,
        h: f32,
        aspect: f32,
    ) -> Option<Self> {
        let to = point - origin;
        let distance = to.length();
        let direction = to / distance;
        let cos = cos(direction);
        let area = 4.0 * h * h * aspect;
        let importance = 1.0 / (area * cos * cos * cos);
        (distance > 0.0 && importance.is_finite()).then_some(FilmPoint {
            film,
            direction,
            distance,
            importance,
        })
    }
}

/// A camera: a projection and its placement (glTF convention: looking down -z, +y up).
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    /// The node's name, or `camera N`, or `default`.
    pub name: String,
    /// Camera to world.
    pub to_world: Mat4,
    /// The projection.
    pub projection: Projection,
    /// The width / height the scene was framed for, if it says (glTF's `aspectRatio`, or
    /// `xmag / ymag`): what an output whose size is not given takes.
    pub aspect_ratio: Option<f32>,
    /// A thin lens in front of a perspective camera (None: a pinhole, everything sharp).
    pub lens: Option<ThinLens>,
    /// A lens system in front of a perspective camera's film, which then replaces both the
    /// pinhole and the thin lens: its focal length and the film's size set the field of
    /// view.
    pub system: Option<MountedLens>,
}

impl Camera {
    /// The ray through film position `film` in [0, 1]^2 (x right, y down, as images are
    /// stored) for an output of aspect ratio `aspect` = width / height.
    pub fn generate_ray(&self, film: Vec2, aspect: f32) -> Ray {
        let ndc = Vec2::new(2.0 * film.x - 1.0, 1.0 - 2.0 * film.y);
        let (origin, direction) = match self.projection {
            Projection::Perspective { yfov } => {
                let h = (0.5 * yfov).tan();
                (Vec3::ZERO, Vec3::new(ndc.x * h * aspect, ndc.y * h, -1.0))
            }
            Projection::Orthographic { xmag, ymag } => {
                (Vec3::new(ndc.x * xmag, ndc.y * ymag, 0.0), -Vec3::Z)
            }
        };
        let origin = self.to_world.transform_point3(origin);
        let direction = self
            .to_world
            .transform_vector3(direction)
            .normalize_or(-Vec3::Z);
        Ray::new(origin, direction, f32::INFINITY)
    }

    /// The camera's thin lens made ready for an output of aspect ratio `aspect`: its
    /// radius and the distance in focus, `auto_focus` giving the distance to what the
    /// image's centre sees when the lens does not say (None there: focused at infinity).
    /// None for a pinhole, an orthographic camera or an aperture of radius 0.
    pub fn focus(&self, aspect: f32, auto_focus: impl FnOnce() -> Option<f32>) -> Option<Focus> {
        let (Projection::Perspective { yfov }, Some(lens)) = (self.projection, &self.lens) else {
            return None;
        };
        let radius = lens.radius(yfov, aspect);
        if !(radius > 0.0 && radius.is_finite()) {
            return None;
        }
        let distance = lens
            .focus_distance
            .or_else(auto_focus)
            .filter(|d| d.is_finite() && *d > 0.0)
            .unwrap_or(f32::INFINITY);
        Some(Focus {
            radius,
            shape: lens.shape.clone(),
            distance,
        })
    }

    /// The ray through film position `film` (as in [`Camera::generate_ray`]) leaving the
    /// thin lens `focus` (from [`Camera::focus`]) at its point for `u_lens` in [0, 1)^2,
    /// towards where the pinhole's ray meets the plane in focus. Without a lens, the
    /// pinhole's ray.
    pub fn generate_ray_through(
        &self,
        film: Vec2,
        aspect: f32,
        focus: Option<&Focus>,
        u_lens: Vec2,
    ) -> Ray {
        let (Some(focus), Projection::Perspective { yfov }) = (focus, self.projection) else {
            return self.generate_ray(film, aspect);
        };
        let ndc = Vec2::new(2.0 * film.x - 1.0, 1.0 - 2.0 * film.y);
        let h = (0.5 * yfov).tan();
        let pinhole = Vec3::new(ndc.x * h * aspect, ndc.y * h, -1.0);
        let lens = focus.lens_point(u_lens).extend(0.0);
        let direction = if focus.distance.is_finite() {
            pinhole * focus.distance - lens
        } else {
            pinhole
        };
        let origin = self.to_world.transform_point3(lens);
        let direction = self
            .to_world
            .transform_vector3(direction)
            .normalize_or(-Vec3::Z);
        Ray::new(origin, direction, f32::INFINITY)
    }

    /// The ray through film position `film` (as in [`Camera::generate_ray`]) leaving the
    /// lens system `system` (from [`MountedLens::focus`]) at wavelength `lambda_nm`, its
    /// path through the elements chosen by `u_lens` in [0, 1)^2, and its weight (the
    /// light the film gathers along it relative to a pinhole's); None where the
    /// elements stop it.
    pub fn generate_ray_system(
        &self,
        film: Vec2,
        system: &FocusedSystem,
        u_lens: Vec2,
        lambda_nm: f32,
    ) -> Option<(Ray, f32)> {
        let (ray, weight) = system.ray(film, u_lens, f64::from(lambda_nm))?;
        // Lens space is camera space in millimetres (the film at the camera's origin where
        // the prescription puts it, the scene towards -z).
        let origin = self
            .to_world
            .transform_point3((ray.origin * 1e-3).as_vec3());
        let direction = self
            .to_world
            .transform_vector3(ray.direction.as_vec3())
            .try_normalize()?;
        let weight = weight as f32;
        (origin.is_finite() && weight.is_finite())
            .then(|| (Ray::new(origin, direction, f32::INFINITY), weight))
    }

    /// [`Camera::project`] through the thin lens `focus`: the point is connected to the
    /// aperture's point for `u_lens` (drawn uniformly over the aperture, as camera rays
    /// leave it), and seen where the ray from there through the point meets the film.
    /// Without a lens, [`Camera::project`].
    pub fn project_through(
        &self,
        point: Vec3,
        aspect: f32,
        focus: Option<&Focus>,
        u_lens: Vec2,
    ) -> Option<FilmPoint> {
        let (Some(focus), Projection::Perspective { yfov }) = (focus, self.projection) else {
            return self.project(point, aspect);
        };
        let local = self.to_world.inverse().transform_point3(point);
        let lens = focus.lens_point(u_lens).extend(0.0);
        let v = local - lens;
        if v.z.is_nan() || v.z >= 0.0 {
            return None;
        }
        // The pinhole direction of the film point this ray comes from: where it meets
        // the plane in focus, seen from the lens's centre.
        let pinhole = if focus.distance.is_finite() {
            lens + v * (focus.distance / -v.z)
        } else {
            v
        };
        let h = (0.5 * yfov).tan();
        let ndc = Vec2::new(
            pinhole.x / (-pinhole.z * h * aspect),
            pinhole.y / (-pinhole.z * h),
        );
        let film = Vec2::new(0.5 * (ndc.x + 1.0), 0.5 * (1.0 - ndc.y));
        if !(film.x >= 0.0 && film.x < 1.0 && film.y >= 0.0 && film.y < 1.0) {
            return None;
        }
        // As for the pinhole, with the cosine of this ray (*PBR* 4th ed. §5.4.1: the
        // thin lens's importance 1 / (A A_lens cos^4) times the lens's cosine and area,
        // its sampling density being uniform over the aperture).
        let cos = -v.z / v.length();
        let origin = self.to_world.transform_point3(lens);
        FilmPoint::seen(film, origin, point, |_| cos, h, aspect)
    }

    /// Where a light path's vertex `point` is seen on the film of an output of aspect ratio
    /// `aspect`, for connecting it to the camera (light tracing): None when the camera
    /// cannot see it (behind it, off the film, or an orthographic camera, which no point
    /// can be connected to since its rays are a delta in direction).
    pub fn project(&self, point: Vec3, aspect: f32) -> Option<FilmPoint> {
        let Projection::Perspective { yfov } = self.projection else {
            return None;
        };
        let local = self.to_world.inverse().transform_point3(point);
        if local.z.is_nan() || local.z >= 0.0 {
            return None;
        }
        let h = (0.5 * yfov).tan();
        let ndc = Vec2::new(local.x / (-local.z * h * aspect), local.y / (-local.z * h));
        let film = Vec2::new(0.5 * (ndc.x + 1.0), 0.5 * (1.0 - ndc.y));
        if !(film.x >= 0.0 && film.x < 1.0 && film.y >= 0.0 && film.y < 1.0) {
            return None;
        }
        let origin = self.to_world.transform_point3(Vec3::ZERO);
        let axis = self
            .to_world
            .transform_vector3(-Vec3::Z)
            .normalize_or(-Vec3::Z);
        FilmPoint::seen(
            film,
            origin,
            point,
            |direction| direction.dot(axis),
            h,
            aspect,
        )
    }

    /// A perspective camera at `eye` looking at `target`, `up` giving the view's vertical
    /// (glTF's convention: the camera looks down its -z with +y up), with vertical field of
    /// view `yfov` in radians. glam dropped `Mat4::look_at_rh` in 0.34; this builds the
    /// camera-to-world matrix from the three directions. Degenerate inputs (`eye` at
    /// `target`, `up` along the view, non-finite values) fall back to looking down -z from
    /// `eye` with +y up.
    ///
    /// ```
    /// use prism_scene::camera::{Camera, Projection};
    /// use glam::Vec3;
    ///
    /// let camera = Camera::look_at(Vec3::new(0.0, 1.0, 5.0), Vec3::new(0.0, 1.0, 0.0), Vec3::Y, 0.7);
    /// // The centre of the film looks from the eye at the target.
    /// let ray = camera.generate_ray(glam::Vec2::splat(0.5), 1.0);
    /// assert!((ray.origin - Vec3::new(0.0, 1.0, 5.0)).length() < 1e-6);
    /// assert!((ray.direction.normalize() - Vec3::NEG_Z).length() < 1e-6);
    /// assert!(matches!(camera.projection, Projection::Perspective { .. }));
    /// ```
    pub fn look_at(eye: Vec3, target: Vec3, up: Vec3, yfov: f32) -> Self {
        let fallback = Mat4::from_translation(if eye.is_finite() { eye } else { Vec3::ZERO });
        let to_world = (target - eye)
            .try_normalize()
            .and_then(|forward| {
                let right = forward.cross(up).try_normalize()?;
                let true_up = right.cross(forward);
                Some(Mat4::from_cols(
                    right.extend(0.0),
                    true_up.extend(0.0),
                    (-forward).extend(0.0),
                    eye.extend(1.0),
                ))
            })
            .filter(|m| m.is_finite())
            .unwrap_or(fallback);
        let yfov = if yfov.is_finite() && yfov > 0.0 && yfov < std::f32::consts::PI {
            yfov
        } else {
            45f32.to_radians()
        };
        Self {
            name: "look_at".into(),
            to_world,
            projection: Projection::Perspective { yfov },
            aspect_ratio: None,
            lens: None,
            system: None,
        }
    }

    /// A perspective camera (45 degree vertical field of view) looking down -z at the box
    /// `[lo, hi]`, as the glTF Sample Viewer frames a model (`fitDistanceToExtents`): the
    /// larger of the box's x and y extents fills the view (at any aspect >= 1) with a 5%
    /// margin, measured at the box's front face so that nothing nearer is cut off. What a
    /// scene without a camera gets.
    pub fn framing(lo: Vec3, hi: Vec3) -> Self {
        let yfov = 45f32.to_radians();
        let (center, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
        let fit = 1.05 * half.x.max(half.y) / (0.5 * yfov).tan();
        // A flat or point-like model still gets a camera in front of it.
        let distance = half.z + fit.max(1e-3 * half.length()).max(1e-3);
        Self {
            name: "default".into(),
            to_world: Mat4::from_translation(center + Vec3::new(0.0, 0.0, distance)),
            projection: Projection::Perspective { yfov },
            aspect_ratio: None,
            lens: None,
            system: None,
        }
    }
}
