//! Mitsuba's `perspective`, `thinlens` and `orthographic` sensors and `hdrfilm` with its
//! reconstruction filter as prism's camera, image size and pixel filter (Mitsuba's
//! "Sensors", "Films" and "Reconstruction filters" plugin references).
//!
//! Mitsuba's camera looks along its local +z with +x to the image's left; prism's looks
//! along -z with +x to the right, so prism's camera frame is Mitsuba's turned half about
//! y: to_world * diag(-1, 1, -1).

use glam::{DMat4, DVec3};

use super::parse::error;
use super::shapes::transform;
use super::tree::{Class, Object, Value};
use crate::LoadError;
use crate::camera::{ApertureSize, Camera, Projection, ThinLens};

/// The pixel filter a film's `rfilter` asks for; Mitsuba's default is its Gaussian.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum PixelFilter {
    /// `box`: the pixel's square.
    Box,
    /// `gaussian`: exp(-x^2 / (2 stddev^2)) minus its value at 4 stddev, clamped at 0
    /// (Mitsuba's `gaussian.cpp`), over a radius of 4 `stddev` pixels.
    Gaussian {
        /// Standard deviation, pixels (Mitsuba's default 0.5).
        stddev: f32,
    },
    /// `tent`: 1 - |x| / radius.
    Tent {
        /// Half-width, pixels (Mitsuba's default 1).
        radius: f32,
    },
}

/// Mitsuba's default reconstruction filter: `gaussian` with `stddev` 0.5.
const DEFAULT_FILTER: PixelFilter = PixelFilter::Gaussian { stddev: 0.5 };

/// The image size and samples a scene's sensor asks for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Film {
    /// Pixels across (Mitsuba's default 768).
    pub width: u32,
    /// Pixels down (default 576).
    pub height: u32,
    /// The sampler's `sample_count` (default 4), if the sensor has a sampler.
    pub spp: Option<u64>,
    /// The film's reconstruction filter.
    pub filter: PixelFilter,
}

/// The camera and film of `sensor`.
pub(crate) fn camera(
    sensor: &Object,
    warnings: &mut Vec<String>,
) -> Result<(Camera, Film), LoadError> {
    let film = film(sensor, warnings)?;
    // Clip planes cut only what lies within `near_clip` of the camera or beyond
    // `far_clip`; prism's camera rays start at the camera and end nowhere. A pinhole has
    // no focus.
    for name in ["near_clip", "far_clip", "focus_distance"] {
        let _ = number(sensor, name)?;
    }
    let aspect = f64::from(film.width) / f64::from(film.height);
    let to_world = transform(sensor, "to_world")? * DMat4::from_scale(DVec3::new(-1.0, 1.0, -1.0));
    let (to_world, projection, lens) = match sensor.kind.as_str() {
        "perspective" => (to_world, perspective(sensor, aspect)?, None),
        "thinlens" => (
            to_world,
            perspective(sensor, aspect)?,
            Some(thin_lens(sensor)?),
        ),
        "orthographic" => orthographic(sensor, to_world, aspect)?,
        other => {
            return Err(error(
                &sensor.at,
                format!(
                    "sensor '{other}' is not read yet (perspective, thinlens and orthographic are)"
                ),
            ));
        }
    };
    let camera = Camera {
        name: sensor.id.clone().unwrap_or_else(|| "sensor".to_string()),
        to_world: to_world.as_mat4(),
        projection,
        aspect_ratio: Some(aspect as f32),
        lens,
        system: None,
    };
    Ok((camera, film))
}

/// A pinhole's projection from `fov` along `fov_axis`, or from `focal_length` (default
/// "50mm") on a 36 x 24 mm frame's diagonal (Mitsuba's `parse_fov` in `sensor.cpp`).
pub(crate) fn perspective(sensor: &Object, aspect: f64) -> Result<Projection, LoadError> {
    let (fov, axis) = match (number(sensor, "fov")?, sensor.property("focal_length")) {
        (Some(_), Some(p)) => {
            return Err(error(
                &p.at,
                "give either a focal length ('focal_length') or a field of view ('fov')",
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
            let text = match focal.map(|p| &p.value) {
                None => "50mm".to_string(),
                Some(Value::String(s)) => s.clone(),
                Some(Value::Float(v)) => v.to_string(),
                Some(Value::Integer(v)) => v.to_string(),
                Some(_) => return Err(error(&sensor.at, "focal_length must be like \"50mm\"")),
            };
            let mm: f64 = text
                .trim()
                .trim_end_matches("mm")
                .parse()
                .ok()
                .filter(|v: &f64| v.is_finite() && *v > 0.0)
                .ok_or_else(|| {
                    error(
                        &sensor.at,
                        format!(
                            "focal_length \"{text}\": expected a positive length in mm (\"50mm\")"
                        ),
                    )
                })?;
            let diagonal = (36.0f64 * 36.0 + 24.0 * 24.0).sqrt();
            (
                (diagonal / (2.0 * mm)).atan().to_degrees() * 2.0,
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
    Ok(Projection::Perspective {
        yfov: (2.0 * tan_half_y.atan()) as f32,
    })
}

/// `thinlens`'s `aperture_radius` (required) and `focus_distance` (Mitsuba's default is
/// the far clip, 10^4).
fn thin_lens(sensor: &Object) -> Result<ThinLens, LoadError> {
    let radius = number(sensor, "aperture_radius")?
        .ok_or_else(|| error(&sensor.at, "thinlens needs an 'aperture_radius'"))?;
    if radius < 0.0 {
        return Err(error(
            &sensor.at,
            format!("aperture_radius {radius} must be >= 0"),
        ));
    }
    let far = number(sensor, "far_clip")?.unwrap_or(1e4);
    let focus = number(sensor, "focus_distance")?.unwrap_or(far);
    if !(focus.is_finite() && focus > 0.0) {
        return Err(error(
            &sensor.at,
            format!("focus_distance {focus} must be finite and > 0"),
        ));
    }
    let mut lens = ThinLens::new(ApertureSize::Radius(radius as f32));
    lens.focus_distance = Some(focus as f32);
    Ok(lens)
}

/// `orthographic`: Mitsuba's view is x in [-1, 1] and y in [-1/aspect, 1/aspect] of the
/// sensor's local frame (`orthographic_projection` in `sensor.h`), scaled by `to_world`;
/// prism's camera frame stays rigid, so the scale moves into the view's half-sizes.
fn orthographic(
    sensor: &Object,
    to_world: DMat4,
    aspect: f64,
) -> Result<(DMat4, Projection, Option<ThinLens>), LoadError> {
    let (x, y, z) = (
        to_world.x_axis.truncate(),
        to_world.y_axis.truncate(),
        to_world.z_axis.truncate(),
    );
    let orthogonal = |a: DVec3, b: DVec3| a.dot(b).abs() <= 1e-6 * a.length() * b.length();
    if !(orthogonal(x, y) && orthogonal(y, z) && orthogonal(x, z))
        || [x, y, z]
            .iter()
            .any(|v| !(v.length() > 0.0 && v.is_finite()))
    {
        return Err(error(
            &sensor.at,
            "orthographic: to_world must be a rotation with a scale along its axes",
        ));
    }
    let rigid = DMat4::from_cols(
        x.normalize().extend(0.0),
        y.normalize().extend(0.0),
        z.normalize().extend(0.0),
        to_world.w_axis,
    );
    let projection = Projection::Orthographic {
        xmag: x.length() as f32,
        ymag: (y.length() / aspect) as f32,
    };
    Ok((rigid, projection, None))
}

/// The sensor's film size and filter, and its sampler's sample count.
fn film(sensor: &Object, warnings: &mut Vec<String>) -> Result<Film, LoadError> {
    let mut out = Film {
        width: 768,
        height: 576,
        spp: None,
        filter: DEFAULT_FILTER,
    };
    if let Some(film) = sensor.children_of(Class::Film).next() {
        let film = &film.object;
        if film.kind != "hdrfilm" {
            return Err(error(
                &film.at,
                format!("film '{}' is not read yet (hdrfilm is)", film.kind),
            ));
        }
        // How Mitsuba would write its file: prism's outputs are what `-o` names.
        for name in ["pixel_format", "component_format", "file_format"] {
            let _ = film.property(name);
        }
        out.width = size(film, "width")?.unwrap_or(768);
        out.height = size(film, "height")?.unwrap_or(576);
        for crop in [
            "crop_offset_x",
            "crop_offset_y",
            "crop_width",
            "crop_height",
        ] {
            if let Some(p) = film.property(crop) {
                return Err(error(
                    &p.at,
                    format!("hdrfilm: '{crop}' is not read yet (prism renders the whole film)"),
                ));
            }
        }
        if let Some(rfilter) = film.children_of(Class::Rfilter).next() {
            out.filter = pixel_filter(&rfilter.object, warnings)?;
        }
    }
    if let Some(sampler) = sensor.children_of(Class::Sampler).next() {
        out.spp = size(&sampler.object, "sample_count")?.map(u64::from);
    }
    Ok(out)
}

/// The filter an `rfilter` names. prism draws film positions from the filter (filter
/// importance sampling), which needs a filter without negative lobes: `mitchell`,
/// `catmullrom` and `lanczos` become Mitsuba's default Gaussian, with a warning.
fn pixel_filter(rfilter: &Object, warnings: &mut Vec<String>) -> Result<PixelFilter, LoadError> {
    let positive = |name: &str, default: f64| -> Result<f32, LoadError> {
        let v = number(rfilter, name)?.unwrap_or(default);
        if v > 0.0 && v <= 4.0 {
            Ok(v as f32)
        } else {
            Err(error(
                &rfilter.at,
                format!("{}: '{name}' {v} must be in (0, 4] pixels", rfilter.kind),
            ))
        }
    };
    Ok(match rfilter.kind.as_str() {
        "box" => PixelFilter::Box,
        "gaussian" => PixelFilter::Gaussian {
            stddev: positive("stddev", 0.5)?,
        },
        "tent" => PixelFilter::Tent {
            radius: positive("radius", 1.0)?,
        },
        other @ ("mitchell" | "catmullrom" | "lanczos") => {
            warnings.push(format!(
                "{}: rfilter '{other}' has negative lobes, which prism's filter sampling cannot draw: the film uses Mitsuba's gaussian (stddev 0.5)",
                rfilter.at
            ));
            DEFAULT_FILTER
        }
        other => {
            return Err(error(
                &rfilter.at,
                format!(
                    "rfilter '{other}' is not read (box, gaussian, tent, mitchell, catmullrom and lanczos are)"
                ),
            ));
        }
    })
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
