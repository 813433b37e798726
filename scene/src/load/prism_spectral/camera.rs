//! A camera's `PRISM_spectral` description: a thin lens, `{"aperture": {"f_number": 2.8}}`
//! or `{"aperture": {"radius": 0.01}}` (metres), optionally with `"blades"` and
//! `"rotation"` (degrees) for a polygonal opening, `"focus_distance"` (metres; default:
//! what the image's centre sees) and `"sensor_width"` (metres; default 0.036, full frame).
//! Or a lens system, `{"lens": "file.dat"}`: a prescription in pbrt-v4's lens file format
//! (`camera::system::parse_prescription`), with `"focus_distance"`, `"sensor_width"` and
//! an `"aperture"` of an `"f_number"` that closes its stop.

use serde_json::Value;

use super::value::{number, only_keys};
use crate::camera::system::parse_prescription;
use crate::camera::{
    ApertureImage, ApertureShape, ApertureSize, FULL_FRAME_WIDTH, MountedLens, ThinLens,
};

/// The widest sensor prism takes, metres: wider is surely millimetres written as metres.
const WIDEST_SENSOR: f64 = 1.0;

/// What a camera's description puts before its film: a thin lens, a lens system (read
/// through `resolve`), or neither (a pinhole).
pub(crate) enum Optics {
    Pinhole,
    Thin(ThinLens),
    System(MountedLens),
}

/// Parses a camera's description, reading a lens system's file through `resolve`.
pub(crate) fn optics(value: &Value, resolve: &crate::load::Resolver) -> Result<Optics, String> {
    let map = value
        .as_object()
        .ok_or("must be an object {\"aperture\": .., \"focus_distance\": ..}")?;
    let Some(file) = map.get("lens") else {
        return Ok(match thin_lens(value, resolve)? {
            Some(lens) => Optics::Thin(lens),
            None => Optics::Pinhole,
        });
    };
    only_keys(map, &["lens", "aperture", "focus_distance", "sensor_width"])?;
    let file = file
        .as_str()
        .ok_or("'lens' must be a prescription's file name")?;
    let text = resolve(file).map_err(|e| format!("lens {file}: {e}"))?;
    let text = String::from_utf8(text).map_err(|_| format!("lens {file}: not a text file"))?;
    let system = parse_prescription(&text).map_err(|e| format!("lens {file}: {e}"))?;
    let mut mounted = MountedLens::new(file, system);
    if let Some(aperture) = map.get("aperture") {
        let aperture = aperture
            .as_object()
            .ok_or("aperture must be an object {\"f_number\": N}")?;
        only_keys(aperture, &["f_number"]).map_err(|e| {
            format!("{e} (a lens system's aperture is its stop, closed by 'f_number')")
        })?;
        let n = aperture
            .get("f_number")
            .ok_or("a lens system's aperture needs 'f_number'")?;
        let n = number(n, "aperture f_number")?;
        if !(n.is_finite() && n > 0.0) {
            return Err(format!("f-number {n} must be finite and > 0"));
        }
        mounted.f_number = Some(n as f32);
    }
    if let Some(d) = map.get("focus_distance") {
        let d = number(d, "focus_distance")?;
        if !(d.is_finite() && d > 0.0) {
            return Err(format!("focus_distance {d} must be finite and > 0"));
        }
        mounted.focus_distance = Some(d as f32);
    }
    if let Some(w) = map.get("sensor_width") {
        mounted.sensor_width = sensor_width(w)?;
    }
    Ok(Optics::System(mounted))
}

/// An aperture image from a PNG, JPEG or WebP file: its pixels' luminance (sRGB decoded)
/// as transmission, times its alpha where it has one.
fn aperture_image(bytes: &[u8]) -> Result<ApertureImage, String> {
    let image = crate::load::images::decode(bytes)?;
    let table = crate::textures::Encoding::Srgb.table();
    let transmission: Vec<f32> = image
        .rgb
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let [r, g, b] = p.map(|c| table[usize::from(c)]);
            let alpha = image
                .alpha
                .as_ref()
                .map_or(1.0, |a| f32::from(a[i]) / 255.0);
            ((0.2126 * r + 0.7152 * g + 0.0722 * b) * alpha).clamp(0.0, 1.0)
        })
        .collect();
    ApertureImage::new(image.width as usize, image.height as usize, transmission)
}

/// A sensor's width, metres.
fn sensor_width(w: &Value) -> Result<f32, String> {
    let w = number(w, "sensor_width")?;
    if w > WIDEST_SENSOR {
        return Err(format!(
            "sensor_width {w} is in metres (a full-frame sensor is 0.036)"
        ));
    }
    if !(w.is_finite() && w > 0.0) {
        return Err(format!("sensor_width {w} must be finite and > 0"));
    }
    Ok(w as f32)
}

/// Parses a camera's description into its thin lens (None: no `aperture`, a pinhole),
/// reading an aperture image through `resolve`.
fn thin_lens(value: &Value, resolve: &crate::load::Resolver) -> Result<Option<ThinLens>, String> {
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
    only_keys(
        aperture,
        &["f_number", "radius", "blades", "rotation", "image"],
    )?;
    let size = match (aperture.get("f_number"), aperture.get("radius")) {
        (Some(n), None) => ApertureSize::FNumber(number(n, "aperture f_number")? as f32),
        (None, Some(r)) => ApertureSize::Radius(number(r, "aperture radius")? as f32),
        _ => return Err("aperture needs one of 'f_number' and 'radius'".into()),
    };
    let shape = match (aperture.get("blades"), aperture.get("image")) {
        (Some(_), Some(_)) => return Err("aperture takes 'blades' or 'image', not both".into()),
        (None, Some(file)) => {
            if aperture.contains_key("rotation") {
                return Err("aperture 'rotation' needs 'blades'".into());
            }
            let file = file
                .as_str()
                .ok_or("aperture 'image' must be an image's file name")?;
            let bytes = resolve(file).map_err(|e| format!("aperture image {file}: {e}"))?;
            ApertureShape::Image(std::sync::Arc::new(
                aperture_image(&bytes).map_err(|e| format!("aperture image {file}: {e}"))?,
            ))
        }
        (b, None) => match b {
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
        },
    };
    let focus_distance = match map.get("focus_distance") {
        None => None,
        Some(d) => Some(number(d, "focus_distance")? as f32),
    };
    let sensor_width = match map.get("sensor_width") {
        None => FULL_FRAME_WIDTH,
        Some(w) => sensor_width(w)?,
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
