//! Real lens systems: spherical interfaces and an aperture stop on one axis, each medium
//! with its own dispersion, traced per wavelength (Kolb, Mitchell and Hanrahan, "A
//! realistic camera model for computer graphics", SIGGRAPH 1995; *PBR* 4th ed. §5.3).
//! Lengths are millimetres, as prescriptions give them; the axis is z, the object's side
//! at negative z, the film at z = 0 behind the last interface. Tracing is in f64: a
//! paraxial ray's slopes are small differences of large numbers.

mod focus;
mod focused;
mod mounted;
mod paraxial;
mod prescription;
mod pupil;

pub use focus::ThickLens;
pub use focused::{D_LINE_NM, FocusedSystem};
pub use mounted::MountedLens;
pub use paraxial::Paraxial;
pub use prescription::parse_prescription;
pub use pupil::PupilBounds;

use glam::DVec3;
use prism_spectrum::Spectrum;
use prism_spectrum::optics::{Cauchy, Sellmeier};

/// What fills the space behind an interface (towards the film).
#[derive(Debug, Clone, PartialEq)]
pub enum Medium {
    /// Air (index 1).
    Air,
    /// A glass of one index at every wavelength.
    Index(f64),
    /// A glass by its Sellmeier terms.
    Sellmeier(Sellmeier),
    /// A glass by the Abbe model (n_d, V_d).
    Cauchy(Cauchy),
}

impl Medium {
    /// The index of refraction at `lambda_nm`.
    pub fn index(&self, lambda_nm: f64) -> f64 {
        match self {
            Medium::Air => 1.0,
            Medium::Index(n) => *n,
            Medium::Sellmeier(s) => s.evaluate(lambda_nm),
            Medium::Cauchy(c) => c.evaluate(lambda_nm),
        }
    }

    /// Whether its index depends on the wavelength.
    pub fn dispersive(&self) -> bool {
        matches!(self, Medium::Sellmeier(_) | Medium::Cauchy(_))
    }
}

/// One interface of a lens system.
#[derive(Debug, Clone, PartialEq)]
pub struct Interface {
    /// Radius of curvature, mm (positive: the centre towards the film; 0: the stop).
    pub radius: f64,
    /// Distance along the axis to the next interface (or, for the last, to the film), mm.
    pub thickness: f64,
    /// The medium behind it, towards the film.
    pub medium: Medium,
    /// Half its clear aperture, mm.
    pub aperture_radius: f64,
}

/// A lens system: its interfaces from the object's side to the film's.
#[derive(Debug, Clone, PartialEq)]
pub struct LensSystem {
    interfaces: Vec<Interface>,
}

/// A ray in the lens system's space (mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LensRay {
    /// Where it is.
    pub origin: DVec3,
    /// Where it goes (unit length).
    pub direction: DVec3,
}

impl LensSystem {
    /// A system of these interfaces: at least one, the last one in air.
    pub fn new(interfaces: Vec<Interface>) -> Result<Self, String> {
        let Some(last) = interfaces.last() else {
            return Err("a lens prescription with no interfaces".into());
        };
        if !matches!(last.medium, Medium::Air) {
            return Err("the last interface must leave the light in air, towards the film".into());
        }
        Ok(Self { interfaces })
    }

    /// The interfaces, from the object's side.
    pub fn interfaces(&self) -> &[Interface] {
        &self.interfaces
    }

    /// Whether any medium disperses light.
    pub fn dispersive(&self) -> bool {
        self.interfaces.iter().any(|i| i.medium.dispersive())
    }

    /// The distance from the first interface to the film, mm.
    pub fn length(&self) -> f64 {
        self.interfaces.iter().map(|i| i.thickness).sum()
    }

    /// Traces a ray from the object's side (starting in front of the first interface)
    /// through every interface at `lambda_nm`: the ray leaving the last one, or None
    /// where an interface's aperture stops it (vignetting) or it is totally reflected.
    pub fn trace_from_scene(&self, ray: LensRay, lambda_nm: f64) -> Option<LensRay> {
        let mut ray = ray;
        let mut z = -self.length();
        let mut eta_before = 1.0;
        for interface in &self.interfaces {
            let eta_after = interface.medium.index(lambda_nm);
            ray = cross(ray, interface, z, eta_before / eta_after)?;
            eta_before = eta_after;
            z += interface.thickness;
        }
        Some(ray)
    }

    /// Traces a ray from the film's side (starting behind the last interface, towards
    /// -z) through every interface back to front at `lambda_nm`: the ray leaving the
    /// first, or None where an aperture stops it or it is totally reflected.
    pub fn trace_from_film(&self, ray: LensRay, lambda_nm: f64) -> Option<LensRay> {
        let mut ray = ray;
        let mut z = 0.0;
        for (i, interface) in self.interfaces.iter().enumerate().rev() {
            z -= interface.thickness;
            let eta_before = interface.medium.index(lambda_nm);
            let eta_after = match i {
                0 => 1.0,
                _ => self.interfaces[i - 1].medium.index(lambda_nm),
            };
            ray = cross(ray, interface, z, eta_before / eta_after)?;
        }
        Some(ray)
    }
}

/// `ray` across `interface`, whose vertex is at `z`, from index ratio `eta` = n_before /
/// n_after (either direction): where it meets the surface (the stop's plane, or the
/// spherical cap), refracted there; None where it misses, the aperture stops it, or it is
/// totally reflected. The stop does not bend it.
fn cross(ray: LensRay, interface: &Interface, z: f64, eta: f64) -> Option<LensRay> {
    let (t, normal) = if interface.radius == 0.0 {
        if ray.direction.z == 0.0 {
            return None;
        }
        ((z - ray.origin.z) / ray.direction.z, DVec3::Z)
    } else {
        intersect_sphere(&ray, z + interface.radius, interface.radius)?
    };
    if !(t.is_finite() && t >= 0.0) {
        return None;
    }
    let hit = ray.origin + t * ray.direction;
    if hit.x * hit.x + hit.y * hit.y > interface.aperture_radius * interface.aperture_radius {
        return None;
    }
    let direction = if interface.radius == 0.0 {
        ray.direction
    } else {
        refract(ray.direction, normal, eta)?
    };
    Some(LensRay {
        origin: hit,
        direction,
    })
}

/// Where a ray meets the sphere of `radius` (signed) centred on the axis at `centre_z`,
/// on the cap a lens uses (the hemisphere facing the side the radius's sign says), and
/// the unit normal there facing against the ray.
fn intersect_sphere(ray: &LensRay, centre_z: f64, radius: f64) -> Option<(f64, DVec3)> {
    let o = ray.origin - DVec3::new(0.0, 0.0, centre_z);
    let (a, b, c) = (
        ray.direction.length_squared(),
        2.0 * ray.direction.dot(o),
        o.length_squared() - radius * radius,
    );
    let discriminant = b * b - 4.0 * a * c;
    if discriminant.is_nan() || discriminant < 0.0 {
        return None;
    }
    let root = discriminant.sqrt();
    let (t0, t1) = ((-b - root) / (2.0 * a), (-b + root) / (2.0 * a));
    // A convex surface (centre towards the film, the ray travelling towards +z) is met
    // first; a concave one second.
    let use_closer = (ray.direction.z > 0.0) ^ (radius < 0.0);
    let t = if use_closer { t0.min(t1) } else { t0.max(t1) };
    let p = o + t * ray.direction;
    let mut normal = p.normalize_or_zero();
    if normal.dot(ray.direction) > 0.0 {
        normal = -normal;
    }
    Some((t, normal))
}

/// Snell's law: `d` (unit) refracted at a surface of unit normal `n` facing against it,
/// from index ratio `eta` = n_before / n_after; None beyond the critical angle.
fn refract(d: DVec3, n: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = -d.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((eta * d + (eta * cos_i - cos_t) * n).normalize())
}
