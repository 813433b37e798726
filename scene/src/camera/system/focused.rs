//! A lens system in front of a film, ready to make camera rays (*PBR* 4th ed. §5.3,
//! pbrt-v4's `RealisticCamera`): the film moved to focus at a distance by the thick-lens
//! approximation, the stop closed to an f-number, exit-pupil bounds per film radius, and
//! the weight of each ray.
//!
//! A film point (the image is inverted by the lens: the film's right sees the scene's
//! left) aims at a point drawn uniformly in the exit pupil's bounds, rotated to the point's
//! polar angle (the system is rotationally symmetric), and the ray is traced through the
//! elements at one wavelength. What reaches the film from there is radiance times
//! cos^4(theta) / z^2 per unit of the rear plane's area (z: the film's distance from that
//! plane; *PBR* 4th ed. eq. 5.3), so a ray weighs cos^4 A / z^2 with A the bounds' area.
//! Weights are divided by their mean at the film's centre, so a uniformly bright scene is
//! as bright at the centre as through a pinhole: darker towards the corners by the natural
//! cos^4 fall-off and by the rays the elements' rims stop (vignetting), as on a camera set
//! to expose the centre right.

use glam::{DVec3, Vec2};

use super::{LensRay, LensSystem, PupilBounds};

/// The d line (helium, 587.56 nm): where focus, the stop and the centre's exposure are set.
pub const D_LINE_NM: f64 = 587.5618;

/// Wavelengths whose exit pupils together bound every wavelength's: the ends of the
/// visible range and the d line (a pupil moves little and smoothly with wavelength).
const PUPIL_WAVELENGTHS: [f64; 3] = [380.0, D_LINE_NM, 780.0];

/// Film radii the pupil is bounded at (segments between them).
const PUPIL_SEGMENTS: usize = 32;

/// Grid points per side searched for each pupil.
const PUPIL_GRID: usize = 96;

/// Grid points per side of the quadrature of the centre's exposure.
const EXPOSURE_GRID: usize = 256;

/// A lens system focused in front of a film of a given size.
#[derive(Debug, Clone, PartialEq)]
pub struct FocusedSystem {
    system: LensSystem,
    /// The film's z (lens space, mm).
    film_z: f64,
    /// The rear element's plane z.
    rear_z: f64,
    /// Half the film's width and height, mm.
    half_film: [f64; 2],
    /// Exit-pupil bounds per segment of film radius (from the axis, on +x).
    pupils: Vec<Option<PupilBounds>>,
    /// Film radius per segment, mm.
    segment: f64,
    /// One over the mean weight at the film's centre.
    exposure: f64,
    /// The distance in focus from the film, mm (infinite: focused at infinity).
    focus_distance_mm: f64,
    /// The effective focal length at the d line, mm.
    efl_mm: f64,
}

impl FocusedSystem {
    /// `system` before a film `film_width_mm` wide of aspect ratio `aspect` (width /
    /// height), closed to `f_number` if given, focused at `focus_distance_mm` from the film
    /// (infinite: at infinity). An error says why it cannot be (no image, an f-number
    /// wider than the system opens, a distance nearer than it focuses, a film no ray
    /// reaches).
    pub fn new(
        system: &LensSystem,
        film_width_mm: f64,
        aspect: f64,
        f_number: Option<f64>,
        focus_distance_mm: f64,
    ) -> Result<Self, String> {
        if !(film_width_mm.is_finite() && film_width_mm > 0.0 && aspect.is_finite() && aspect > 0.0)
        {
            return Err(format!(
                "a film {film_width_mm} mm wide at aspect {aspect} cannot be"
            ));
        }
        let mut system = system.clone();
        if let Some(n) = f_number {
            system = system.stopped_to(n)?;
        }
        let paraxial = system.paraxial(D_LINE_NM)?;
        let efl_mm = paraxial.efl_mm;
        if efl_mm <= 0.0 {
            return Err(format!(
                "the lens diverges light (focal length {efl_mm:.2} mm): it forms no image on a film"
            ));
        }
        let film_z = if focus_distance_mm.is_infinite() {
            let thick = system
                .thick_lens(D_LINE_NM)
                .ok_or("no ray passes near the lens's axis")?;
            thick.rear_focal_z
        } else {
            system.focus_shift(focus_distance_mm, D_LINE_NM).ok_or_else(|| {
                format!(
                    "the lens cannot focus at {:.3} m (too near for its {efl_mm:.1} mm focal length)",
                    focus_distance_mm / 1000.0
                )
            })?
        };
        let rear_z = -system.interfaces().last().map_or(0.0, |i| i.thickness);
        if !(film_z.is_finite() && film_z > rear_z) {
            return Err("the lens's image falls in front of its last element".into());
        }
        let half_film = [0.5 * film_width_mm, 0.5 * film_width_mm / aspect];
        let diagonal = half_film[0].hypot(half_film[1]);
        let segment = diagonal / PUPIL_SEGMENTS as f64;
        // Bounds at each segment's two ends, united over the wavelengths; a segment's
        // bounds are its ends' union.
        let at_radius: Vec<Option<PupilBounds>> = (0..=PUPIL_SEGMENTS)
            .map(|k| {
                let film = DVec3::new(k as f64 * segment, 0.0, film_z);
                PUPIL_WAVELENGTHS
                    .iter()
                    .filter_map(|&l| system.exit_pupil_from(film, l, PUPIL_GRID))
                    .reduce(union)
            })
            .collect();
        let pupils: Vec<Option<PupilBounds>> = at_radius
            .windows(2)
            .map(|w| match (w[0], w[1]) {
                (Some(a), Some(b)) => Some(union(a, b)),
                (a, b) => a.or(b),
            })
            .collect();
        let mut focused = Self {
            system,
            film_z,
            rear_z,
            half_film,
            pupils,
            segment,
            exposure: 1.0,
            focus_distance_mm,
            efl_mm,
        };
        let centre = focused.centre_weight();
        if !(centre > 0.0 && centre.is_finite()) {
            return Err("no ray from the film's centre passes the lens".into());
        }
        focused.exposure = 1.0 / centre;
        Ok(focused)
    }

    /// The mean weight of rays from the film's centre at the d line, by quadrature over
    /// its pupil's bounds.
    fn centre_weight(&self) -> f64 {
        let Some(Some(bounds)) = self.pupils.first() else {
            return 0.0;
        };
        let film = DVec3::new(0.0, 0.0, self.film_z);
        let mut sum = 0.0;
        for j in 0..EXPOSURE_GRID {
            for i in 0..EXPOSURE_GRID {
                let u = Vec2::new(
                    ((i as f64 + 0.5) / EXPOSURE_GRID as f64) as f32,
                    ((j as f64 + 0.5) / EXPOSURE_GRID as f64) as f32,
                );
                if let Some((_, w)) = self.trace(film, bounds, u, D_LINE_NM) {
                    sum += w;
                }
            }
        }
        sum / (EXPOSURE_GRID * EXPOSURE_GRID) as f64
    }

    /// The camera ray (lens space, mm, towards -z) through film position `film` in
    /// [0, 1]^2 (x right, y down, as images are stored) for `u` in [0, 1)^2 and the
    /// wavelength `lambda_nm`, with its weight; None where the elements stop it
    /// (vignetting) or reflect it totally.
    pub fn ray(&self, film: Vec2, u: Vec2, lambda_nm: f64) -> Option<(LensRay, f64)> {
        // The lens inverts the image: the film's right sees the scene's left.
        let x = (1.0 - 2.0 * f64::from(film.x)) * self.half_film[0];
        let y = (2.0 * f64::from(film.y) - 1.0) * self.half_film[1];
        let r = x.hypot(y);
        let k = ((r / self.segment) as usize).min(self.pupils.len() - 1);
        let bounds = self.pupils[k]?;
        let (sin, cos) = if r > 0.0 { (y / r, x / r) } else { (0.0, 1.0) };
        // The bounds hold for the film point (r, 0); turn the drawn point to (x, y).
        let point = DVec3::new(x, y, self.film_z);
        let (ray, weight) = self.trace_turned(point, &bounds, u, lambda_nm, (sin, cos))?;
        Some((ray, weight * self.exposure))
    }

    fn trace(
        &self,
        film: DVec3,
        bounds: &PupilBounds,
        u: Vec2,
        lambda_nm: f64,
    ) -> Option<(LensRay, f64)> {
        self.trace_turned(film, bounds, u, lambda_nm, (0.0, 1.0))
    }

    /// Traces from `film` towards the point of `bounds` that `u` picks, turned by the
    /// angle of (`sin`, `cos`): the ray leaving the front element and cos^4 A / z^2.
    fn trace_turned(
        &self,
        film: DVec3,
        bounds: &PupilBounds,
        u: Vec2,
        lambda_nm: f64,
        (sin, cos): (f64, f64),
    ) -> Option<(LensRay, f64)> {
        let px = bounds[0] + f64::from(u.x) * (bounds[2] - bounds[0]);
        let py = bounds[1] + f64::from(u.y) * (bounds[3] - bounds[1]);
        let target = DVec3::new(px * cos - py * sin, px * sin + py * cos, self.rear_z);
        let direction = (target - film).normalize();
        if !direction.is_finite() {
            return None;
        }
        let out = self.system.trace_from_film(
            LensRay {
                origin: film,
                direction,
            },
            lambda_nm,
        )?;
        let area = (bounds[2] - bounds[0]) * (bounds[3] - bounds[1]);
        let z = self.film_z - self.rear_z;
        let cos2 = direction.z * direction.z;
        let weight = cos2 * cos2 * area / (z * z);
        (weight.is_finite() && out.direction.is_finite()).then_some((out, weight))
    }

    /// The film's position behind the prescription's (mm; positive: further back).
    pub fn film_z(&self) -> f64 {
        self.film_z
    }

    /// The distance in focus from the film, mm (infinite: at infinity).
    pub fn focus_distance_mm(&self) -> f64 {
        self.focus_distance_mm
    }

    /// The effective focal length at the d line, mm.
    pub fn efl_mm(&self) -> f64 {
        self.efl_mm
    }

    /// The vertical field of view the film sees through the lens (radians), by its
    /// focal length: what filters textures and what `prism info` reports.
    pub fn yfov(&self) -> f64 {
        2.0 * (self.half_film[1] / self.efl_mm).atan()
    }

    /// Whether the lens's glass disperses light: rays of different wavelengths through
    /// one film point part ways.
    pub fn dispersive(&self) -> bool {
        self.system.dispersive()
    }

    /// The system as focused (the stop closed to the f-number asked for).
    pub fn system(&self) -> &LensSystem {
        &self.system
    }

    /// The exit-pupil bounds used for film radius `r` mm (None: no ray passes there).
    pub fn pupil_bounds(&self, r: f64) -> Option<PupilBounds> {
        let k = ((r / self.segment) as usize).min(self.pupils.len() - 1);
        self.pupils[k]
    }
}

fn union(a: PupilBounds, b: PupilBounds) -> PupilBounds {
    [
        a[0].min(b[0]),
        a[1].min(b[1]),
        a[2].max(b[2]),
        a[3].max(b[3]),
    ]
}

impl LensSystem {
    /// The system with its stop closed so that its f-number at the d line is `n`; an
    /// error where it opens no wider than that, or has no stop.
    pub fn stopped_to(&self, n: f64) -> Result<LensSystem, String> {
        if !(n.is_finite() && n > 0.0) {
            return Err(format!("f-number {n} must be finite and > 0"));
        }
        let Some(stop) = self.interfaces().iter().position(|i| i.radius == 0.0) else {
            return Err("the lens has no aperture stop (an interface of radius 0) to close".into());
        };
        let widest = self.paraxial(D_LINE_NM)?.f_number;
        if n < widest * (1.0 - 1e-9) {
            return Err(format!(
                "f/{n} is wider than the lens opens (f/{widest:.2})"
            ));
        }
        let open = self.interfaces()[stop].aperture_radius;
        let with_stop = |radius: f64| {
            let mut interfaces = self.interfaces().to_vec();
            interfaces[stop].aperture_radius = radius;
            LensSystem::new(interfaces)
        };
        // The f-number falls as the stop opens: bisection on its radius.
        let (mut small, mut large) = (0.0, open);
        for _ in 0..60 {
            let mid = 0.5 * (small + large);
            match with_stop(mid)?.paraxial(D_LINE_NM) {
                Ok(p) if p.f_number <= n => large = mid,
                _ => small = mid,
            }
        }
        with_stop(large)
    }
}
