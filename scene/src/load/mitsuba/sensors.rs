//! Mitsuba's `perspective` sensor and `hdrfilm` as prism's camera and image size
//! (Mitsuba's "Sensors" and "Films" plugin references).
//!
//! Mitsuba's camera looks along its local +z with +x to the image's left; prism's looks
//! along -z with +x to the right, so prism's camera frame is Mitsuba's turned half about
//! y: to_world * diag(-1, 1, -1).

use glam::{DMat4, DVec3};

use super::parse::error;
use super::shapes::transform;
use super::tree::{Class, Object, Value};
use crate::LoadError;
use crate::camera::{Camera, Projection};

/// The image size and samples a scene's sensor asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Film {
    /// Pixels across (Mitsuba's default 768).
    pub width: u32,
    /// Pixels down (default 576).
    pub height: u32,
    /// The sampler's `sample_count` (default 4), if the sensor has a sampler.
    pub spp: Option<u64>,
}

/// The camera and film of `sensor`.
pub(crate) fn camera(sensor: &Object) -> Result<(Camera, Film), LoadError> {
    if sensor.kind != "perspective" {
        return Err(error(
            &sensor.at,
            format!("sensor '{}' is not read yet (perspective is)", sensor.kind),
        ));
    }
    let film = film(sensor)?;
    let aspect = f64::from(film.width) / f64::from(film.height);
    // Without a `fov`, Mitsuba's `parse_fov` takes a `focal_length` (default 50mm) on a
    // 36 x 24 mm frame, along its diagonal.
    let (fov, axis) = match (number(sensor, "fov")?, sensor.property("focal_length")) {
        (Some(_), Some(p)) => {
            return Err(error(
                &p.at,
                "give either 'fov' or 'focal_length', not both",
            ));
        }
        (Some(fov), None) => {
            let axis = match sensor.property("fov_axis").map(|p| &p.value) {
                None => "x".to_string(),
                Some(Value::String(s)) => s.to_lowercase(),
                Some(_) => return Err(error(&sensor.at, "fov_axis must be a string")),
            };
            (fov, axis)
        }
        (None, focal) => {
            let mm = match focal.map(|p| (&p.value, &p.at)) {
                None => 50.0,
                Some((Value::String(f), at)) => f
                    .trim_end_matches("mm")
                    .trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|v| *v > 0.0 && v.is_finite())
                    .ok_or_else(|| error(at, format!("focal_length \"{f}\": expected <x>mm")))?,
                Some((_, at)) => return Err(error(at, "focal_length must be a string (<x>mm)")),
            };
            let diagonal = (36.0f64 * 36.0 + 24.0 * 24.0).sqrt();
            (
                2.0 * (diagonal / (2.0 * mm)).atan().to_degrees(),
                "diagonal".to_string(),
            )
        }
    };
    if !(fov > 0.0 && fov < 180.0) {
        return Err(error(
            &sensor.at,
            format!("fov {fov} must be in (0, 180) degrees"),
        ));
    }
    let tan_half = (fov.to_radians() / 2.0).tan();
    // tan(yfov / 2) from the axis the fov is given along (Mitsuba's `fov_axis`).
    let tan_half_y = match axis.as_str() {
        "x" => tan_half / aspect,
        "y" => tan_half,
        "diagonal" => tan_half / (1.0 + aspect * aspect).sqrt(),
        "smaller" if aspect >= 1.0 => tan_half,
        "smaller" => tan_half / aspect,
        "larger" if aspect >= 1.0 => tan_half / aspect,
        "larger" => tan_half,
        other => {
            return Err(error(
                &sensor.at,
                format!("fov_axis '{other}': expected x, y, diagonal, smaller or larger"),
            ));
        }
    };
    let to_world = transform(sensor, "to_world")? * DMat4::from_scale(DVec3::new(-1.0, 1.0, -1.0));
    let camera = Camera {
        name: sensor.id.clone().unwrap_or_else(|| "sensor".to_string()),
        to_world: to_world.as_mat4(),
        projection: Projection::Perspective {
            yfov: (2.0 * tan_half_y.atan()) as f32,
        },
        aspect_ratio: Some(aspect as f32),
        lens: None,
        system: None,
    };
    Ok((camera, film))
}

/// The sensor's film size and sampler's sample count.
fn film(sensor: &Object) -> Result<Film, LoadError> {
    let mut out = Film {
        width: 768,
        height: 576,
        spp: None,
    };
    if let Some(film) = sensor.children_of(Class::Film).next() {
        let film = &film.object;
        if film.kind != "hdrfilm" {
            return Err(error(
                &film.at,
                format!("film '{}' is not read yet (hdrfilm is)", film.kind),
            ));
        }
        out.width = size(film, "width")?.unwrap_or(768);
        out.height = size(film, "height")?.unwrap_or(576);
    }
    if let Some(sampler) = sensor.children_of(Class::Sampler).next() {
        out.spp = size(&sampler.object, "sample_count")?.map(u64::from);
    }
    Ok(out)
}

/// A positive integer property.
fn size(object: &Object, name: &str) -> Result<Option<u32>, LoadError> {
    match object.property(name) {
        None => Ok(None),
        Some(p) => match p.value {
            Value::Integer(v) if v > 0 && v <= i64::from(u32::MAX) => Ok(Some(v as u32)),
            _ => Err(error(&p.at, format!("'{name}' must be a positive integer"))),
        },
    }
}

/// A number property (float or integer).
pub(crate) fn number(object: &Object, name: &str) -> Result<Option<f64>, LoadError> {
    match object.property(name) {
        None => Ok(None),
        Some(p) => match p.value {
            Value::Float(v) if v.is_finite() => Ok(Some(v)),
            Value::Integer(v) => Ok(Some(v as f64)),
            _ => Err(error(&p.at, format!("'{name}' must be a finite number"))),
        },
    }
}
