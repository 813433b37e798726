//! A camera's `PRISM_spectral` description: a thin lens, `{"aperture": {"f_number": 2.8}}`
//! or `{"aperture": {"radius": 0.01}}` (metres), optionally with `"blades"` and
//! `"rotation"` (degrees) for a polygonal opening, `"focus_distance"` (metres; default:
//! what the image's centre sees) and `"sensor_width"` (metres; default 0.036, full frame).

use serde_json::Value;

use super::value::{number, only_keys};
use crate::camera::{ApertureShape, ApertureSize, FULL_FRAME_WIDTH, ThinLens};

/// The widest sensor prism takes, metres: wider is surely millimetres written as metres.
const WIDEST_SENSOR: f64 = 1.0;

/// Parses a camera's description into its thin lens (None: no `aperture`, a pinhole).
pub(crate) fn thin_lens(value: &Value) -> Result<Option<ThinLens>, String> {
    let map = value
        .as_object()
        .ok_or("must be an object {\"aperture\": .., \"focus_distance\": ..}")?;
    only_keys(map, &["aperture", "focus_distance", "sensor_width"])?;
    let Some(aperture) = map.get("aperture") else {
        if map.contains_key("focus_distance") || map.contains_key("sensor_width") {
            return Err("'focus_distance' and 'sensor_width' need an 'aperture'".into());
        }
        return Ok(None);
    };
    let aperture = aperture
        .as_object()
        .ok_or("aperture must be an object {\"f_number\": N} or {\"radius\": R}")?;
    only_keys(aperture, &["f_number", "radius", "blades", "rotation"])?;
    let size = match (aperture.get("f_number"), aperture.get("radius")) {
        (Some(n), None) => ApertureSize::FNumber(number(n, "aperture f_number")? as f32),
        (None, Some(r)) => ApertureSize::Radius(number(r, "aperture radius")? as f32),
        _ => return Err("aperture needs one of 'f_number' and 'radius'".into()),
    };
    let shape = match aperture.get("blades") {
        None => {
            if aperture.contains_key("rotation") {
                return Err("aperture 'rotation' needs 'blades'".into());
            }
            ApertureShape::Disk
        }
        Some(b) => {
            let blades = b.as_u64().filter(|b| (3..=64).contains(b)).ok_or_else(|| {
                format!("aperture blades {b} must be a whole number from 3 to 64")
            })?;
            let rotation = match aperture.get("rotation") {
                None => 0.0,
                Some(r) => number(r, "aperture rotation")?.to_radians() as f32,
            };
            ApertureShape::Polygon {
                blades: blades as u32,
                rotation,
            }
        }
    };
    let focus_distance = match map.get("focus_distance") {
        None => None,
        Some(d) => Some(number(d, "focus_distance")? as f32),
    };
    let sensor_width = match map.get("sensor_width") {
        None => FULL_FRAME_WIDTH,
        Some(w) => {
            let w = number(w, "sensor_width")?;
            if w > WIDEST_SENSOR {
                return Err(format!(
                    "sensor_width {w} is in metres (a full-frame sensor is 0.036)"
                ));
            }
            w as f32
        }
    };
    let lens = ThinLens {
        size,
        shape,
        focus_distance,
        sensor_width,
    };
    lens.validate()?;
    Ok(Some(lens))
}
