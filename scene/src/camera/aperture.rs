//! The shape of a lens's aperture: a disk, the regular polygon its blades leave, or an
//! image (pbrt-v4's `apertureImage`: how much light each point of the opening lets
//! through). Points on a disk or polygon are drawn uniformly over its area (a thin lens
//! lets light through every point of its opening alike), on an image in proportion to its
//! transmission; the shape is what the blur of an out-of-focus highlight takes (its
//! bokeh).

use std::f32::consts::PI;
use std::sync::Arc;

use glam::Vec2;
use prism_sampling::distribution::PiecewiseConstant2D;
use prism_sampling::warp::{uniform_disk_concentric, uniform_triangle};

/// An aperture's shape, at unit size: a disk of radius 1, or a regular polygon whose
/// corners lie on the unit circle.
#[derive(Debug, Clone, PartialEq)]
pub enum ApertureShape {
    /// A circular opening.
    Disk,
    /// The opening `blades` straight blades leave (3 or more): a regular polygon, one
    /// corner at angle `rotation` (radians, counter-clockwise from the image's +x).
    Polygon {
        /// How many blades (corners).
        blades: u32,
        /// The first corner's angle, radians.
        rotation: f32,
    },
    /// An image's transmission over the square [-1, 1]^2 (its top row at +y).
    Image(Arc<ApertureImage>),
}

/// An aperture image: transmission per pixel over the square [-1, 1]^2, rows from the top
/// (+y) down, and the distribution lens points are drawn from.
#[derive(Debug, Clone, PartialEq)]
pub struct ApertureImage {
    width: usize,
    height: usize,
    transmission: Vec<f32>,
    distribution: PiecewiseConstant2D,
    /// The mean transmission over the square relative to its largest.
    fill: f32,
}

impl ApertureImage {
    /// An aperture of `width` x `height` transmissions (each in [0, 1], rows from the top);
    /// an error where none lets light through, or one is not a number in [0, 1].
    pub fn new(width: usize, height: usize, transmission: Vec<f32>) -> Result<Self, String> {
        if width == 0 || height == 0 || width.checked_mul(height) != Some(transmission.len()) {
            return Err(format!(
                "{} values do not form a {width} x {height} aperture image",
                transmission.len()
            ));
        }
        if let Some(t) = transmission.iter().find(|t| !(0.0..=1.0).contains(*t)) {
            return Err(format!("aperture transmission {t} is not in [0, 1]"));
        }
        let values: Vec<f64> = transmission.iter().map(|&t| f64::from(t)).collect();
        let distribution =
            PiecewiseConstant2D::new(&values, width, height, [[-1.0, 1.0], [-1.0, 1.0]]).map_err(
                |_| "the aperture image lets no light through (it is black)".to_string(),
            )?;
        let largest = transmission.iter().copied().fold(0.0f32, f32::max);
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        Ok(Self {
            width,
            height,
            fill: (mean / f64::from(largest)) as f32,
            transmission,
            distribution,
        })
    }

    /// The transmission at `p` in [-1, 1]^2 (0 outside).
    pub fn transmission(&self, p: Vec2) -> f32 {
        if !(p.x >= -1.0 && p.x < 1.0 && p.y > -1.0 && p.y <= 1.0) {
            return 0.0;
        }
        let i = (((p.x + 1.0) * 0.5 * self.width as f32) as usize).min(self.width - 1);
        let j = (((1.0 - p.y) * 0.5 * self.height as f32) as usize).min(self.height - 1);
        self.transmission[j * self.width + i]
    }

    /// The density of [`ApertureShape::sample`]'s points at `p`, per unit area.
    pub fn pdf(&self, p: Vec2) -> f32 {
        if self.transmission(p) == 0.0 {
            return 0.0;
        }
        self.distribution.pdf([f64::from(p.x), f64::from(-p.y)]) as f32
    }
}

impl ApertureShape {
    /// A point of the shape from `u` in [0, 1)^2, uniform over its area.
    pub fn sample(&self, u: Vec2) -> Vec2 {
        match self {
            ApertureShape::Disk => uniform_disk_concentric(u),
            ApertureShape::Image(image) => {
                let s = image.distribution.sample([f64::from(u.x), f64::from(u.y)]);
                // Rows run from the top down: the distribution's y grows downwards.
                Vec2::new(s.point[0] as f32, -(s.point[1] as f32))
            }
            &ApertureShape::Polygon { blades, rotation } => {
                // A wedge (the triangle centre, corner k, corner k + 1) chosen by u.x,
                // what is left of u.x reused within it: all wedges have the same area.
                let n = blades.max(3) as f32;
                let scaled = u.x * n;
                let k = scaled.floor().min(n - 1.0);
                let reused = Vec2::new((scaled - k).clamp(0.0, 1.0 - f32::EPSILON), u.y);
                let b = uniform_triangle(reused);
                let corner = |i: f32| {
                    let a = rotation + 2.0 * PI * i / n;
                    Vec2::new(a.cos(), a.sin())
                };
                b[1] * corner(k) + b[2] * corner(k + 1.0)
            }
        }
    }

    /// Its area at unit size (an image's: the square's, times its mean transmission
    /// relative to its largest).
    pub fn area(&self) -> f32 {
        match self {
            ApertureShape::Disk => PI,
            ApertureShape::Image(image) => 4.0 * image.fill,
            &ApertureShape::Polygon { blades, .. } => {
                let n = blades.max(3) as f32;
                0.5 * n * (2.0 * PI / n).sin()
            }
        }
    }

    /// Whether the point `p` (at unit size) is inside the shape.
    pub fn contains(&self, p: Vec2) -> bool {
        match self {
            ApertureShape::Disk => p.length_squared() <= 1.0,
            ApertureShape::Image(image) => image.transmission(p) > 0.0,
            &ApertureShape::Polygon { blades, rotation } => {
                let n = blades.max(3) as f32;
                // Inside every edge: the distance along each edge's outward normal is at
                // most the apothem.
                let apothem = (PI / n).cos();
                (0..blades.max(3)).all(|i| {
                    let a = rotation + (2.0 * i as f32 + 1.0) * PI / n;
                    p.dot(Vec2::new(a.cos(), a.sin())) <= apothem + 1e-6
                })
            }
        }
    }
}
