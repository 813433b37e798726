//! Mitsuba's volumes (the "Volumes" plugin reference: `constvolume`, `gridvolume`) and
//! the plain values a medium takes in their place, as what prism's media are made of.
//!
//! A volume maps its local unit cube to the world by `to_world`; with `use_grid_bbox` a
//! grid maps its file's bounding box instead, and otherwise the file's box is ignored
//! (Mitsuba's `Volume::update_bbox` and `GridVolume`). prism's grids are axis-aligned
//! boxes, so `to_world` may scale and translate, not rotate, shear or mirror. Grids clamp
//! at their faces and filter `trilinear` or `nearest`; a grid of one channel is a number
//! per voxel, of three an RGB colour upsampled per voxel as Mitsuba's spectral variants
//! do ([`crate::medium::SpectralGrid`]), with prism's coefficient table.
//!
//! What an RGB value means follows Mitsuba 3 (`Properties::get_volume`, the `srgb`
//! spectrum): a medium's `<rgb>` is a reflectance, and Mitsuba refuses one outside [0, 1];
//! a `constvolume`'s `<rgb>` is asked for as unbounded, but Mitsuba's upsampling table
//! clamps it into [0, 1] all the same, so one outside it is refused here rather than
//! rendered as something Mitsuba would not.

use glam::{DMat4, DVec3, Vec3};

use super::files::Files;
use super::parse::error;
use super::shapes::{string, transform};
use super::spectra::{Kind, spectrum};
use super::tree::{Class, Location, Object, Value};
use crate::LoadError;
use crate::load::Upsampler;
use crate::medium::{Filter, Grid, SpectralGrid, parse_vol};
use crate::textures::SceneSpectrum;

/// A volume's values in world space.
#[derive(Debug, Clone)]
pub(crate) enum Volume {
    /// One spectrum over a box (`constvolume`, or a plain value over the unit cube).
    Constant {
        /// The value.
        value: SceneSpectrum,
        /// The box's lower corner.
        min: Vec3,
        /// Its upper corner.
        max: Vec3,
    },
    /// A number per voxel.
    Grid(Grid),
    /// A spectrum per voxel (a grid of colours).
    Spectral(SpectralGrid),
}

/// The volume `name` of `medium`: a number, spectrum or colour (a constant over the unit
/// cube, as Mitsuba wraps one in a `constvolume`), or a nested `<volume>`; `default`
/// where it has neither.
pub(crate) fn volume(
    medium: &Object,
    name: &str,
    default: f64,
    upsampler: &Upsampler,
    files: Files,
    warnings: &mut Vec<String>,
) -> Result<Volume, LoadError> {
    if let Some(child) = medium.child(name) {
        let v = &child.object;
        return match (v.class, v.kind.as_str()) {
            (Class::Volume, "constvolume") => constant_volume(v, upsampler),
            (Class::Volume, "gridvolume" | "grid") => grid_volume(v, upsampler, files, warnings),
            (Class::Volume, other) => Err(error(
                &v.at,
                format!("volume '{other}' is not read yet (constvolume and gridvolume are)"),
            )),
            (class, other) => Err(error(
                &v.at,
                format!(
                    "{} '{other}' as a medium's '{name}' is not read yet (a number, a spectrum, a colour or a volume is)",
                    class.tag()
                ),
            )),
        };
    }
    Ok(Volume::Constant {
        value: value(medium, name, default, upsampler)?,
        min: Vec3::ZERO,
        max: Vec3::ONE,
    })
}

/// The spectrum `name` of `object`: a number, a spectrum, or a colour in [0, 1] as a
/// reflectance.
fn value(
    object: &Object,
    name: &str,
    default: f64,
    upsampler: &Upsampler,
) -> Result<SceneSpectrum, LoadError> {
    if let Some(p) = object.property(name)
        && let Value::Rgb(rgb) = &p.value
        && rgb.iter().any(|c| !(0.0..=1.0).contains(c))
    {
        return Err(error(
            &p.at,
            format!(
                "'{name}' RGB {rgb:?} is outside [0, 1], which Mitsuba 3 refuses (or clamps) here; give a spectrum or a number, or the colour over a 'scale'"
            ),
        ));
    }
    spectrum(object, name, Kind::Albedo, default, upsampler)
}

/// `constvolume`: `value` (default 1) over `to_world`'s unit cube.
fn constant_volume(v: &Object, upsampler: &Upsampler) -> Result<Volume, LoadError> {
    known(v, &["value", "to_world"])?;
    let (min, max) = placed(v, DVec3::ZERO, DVec3::ONE)?;
    Ok(Volume::Constant {
        value: value(v, "value", 1.0, upsampler)?,
        min,
        max,
    })
}

/// `gridvolume`: a `.vol` file's grid.
fn grid_volume(
    v: &Object,
    upsampler: &Upsampler,
    files: Files,
    warnings: &mut Vec<String>,
) -> Result<Volume, LoadError> {
    known(
        v,
        &[
            "filename",
            "use_grid_bbox",
            "filter_type",
            "wrap_mode",
            "raw",
            "to_world",
            "accel",
            "max_value",
        ],
    )?;
    let filter = match v.property("filter_type").map(|p| (&p.value, &p.at)) {
        None => Filter::Trilinear,
        Some((Value::String(s), _)) if s == "trilinear" => Filter::Trilinear,
        Some((Value::String(s), _)) if s == "nearest" => Filter::Nearest,
        Some((_, at)) => {
            return Err(error(
                at,
                "filter_type must be \"trilinear\" or \"nearest\"",
            ));
        }
    };
    match v.property("wrap_mode").map(|p| (&p.value, &p.at)) {
        None => {}
        Some((Value::String(s), _)) if s == "clamp" => {}
        Some((Value::String(s), at)) if s == "repeat" || s == "mirror" => {
            return Err(error(
                at,
                format!("wrap_mode \"{s}\" is not read yet (clamp is)"),
            ));
        }
        Some((_, at)) => {
            return Err(error(
                at,
                "wrap_mode must be \"clamp\", \"repeat\" or \"mirror\"",
            ));
        }
    }
    if let Some(p) = v.property("max_value") {
        warnings.push(format!(
            "{}: max_value is not read: prism bounds the grid by its own values (Mitsuba's majorant; below the grid's largest value it would bias Mitsuba's render)",
            p.at
        ));
    }
    let file = string(v, "filename")?;
    let bytes = files.read(&file, &v.at)?;
    let vol = parse_vol(&bytes).map_err(|e| error(&v.at, format!("{file}: {e}")))?;
    let (lo, hi) = if boolean(v, "use_grid_bbox")? {
        (vol.min.as_dvec3(), vol.max.as_dvec3())
    } else {
        (DVec3::ZERO, DVec3::ONE)
    };
    let (min, max) = placed(v, lo, hi)?;
    let at_file = |e: String| error(&v.at, format!("{file}: {e}"));
    match vol.channels {
        1 => Ok(Volume::Grid(
            Grid::new(vol.resolution, min, max, vol.values)
                .map_err(at_file)?
                .with_filter(filter),
        )),
        3 if boolean(v, "raw")? => Err(error(
            &v.at,
            format!(
                "{file}: a grid of three channels with raw = true is not a spectrum (Mitsuba refuses it as one too)"
            ),
        )),
        3 => {
            let table = upsampler.table().map_err(at_file)?;
            // Mitsuba's spectral grids: each colour over twice its largest channel, a
            // reflectance, fitted, and that scale kept beside it.
            let mut scales = Vec::with_capacity(vol.values.len() / 3);
            let mut coefficients = Vec::with_capacity(vol.values.len() / 3);
            for rgb in vol.values.chunks_exact(3) {
                let scale = 2.0 * rgb[0].max(rgb[1]).max(rgb[2]);
                let normalized = rgb.iter().map(|&c| f64::from(c / scale.max(1e-8)));
                let normalized: Vec<f64> = normalized.collect();
                let shape = table.lookup([normalized[0], normalized[1], normalized[2]]);
                scales.push(scale);
                coefficients.push(shape.coefficients.map(|c| c as f32));
            }
            let scales = Grid::new(vol.resolution, min, max, scales)
                .map_err(at_file)?
                .with_filter(filter);
            Ok(Volume::Spectral(
                SpectralGrid::new(scales, coefficients).map_err(at_file)?,
            ))
        }
        n => Err(error(
            &v.at,
            format!("{file}: a grid of {n} channels is not read (1 and 3 are)"),
        )),
    }
}

/// The box `lo`-`hi` of `v`'s local space placed by its `to_world`, which may scale (by
/// positive factors) and translate.
fn placed(v: &Object, lo: DVec3, hi: DVec3) -> Result<(Vec3, Vec3), LoadError> {
    let m = transform(v, "to_world")?;
    let at = v.property("to_world").map_or(&v.at, |p| &p.at);
    if !axis_aligned(&m) {
        return Err(error(
            at,
            "a volume's to_world that rotates, shears or mirrors is not read yet (scales and translations are)",
        ));
    }
    let (a, b) = (m.transform_point3(lo), m.transform_point3(hi));
    let (min, max) = (a.min(b).as_vec3(), a.max(b).as_vec3());
    if !(min.is_finite() && max.is_finite() && min.cmplt(max).all()) {
        return Err(error(
            at,
            format!("the volume's box {min} - {max} is empty or not finite"),
        ));
    }
    Ok((min, max))
}

/// Whether `m`'s linear part is diagonal with positive entries (to rounding: a rotation
/// by a right angle leaves 1e-8 where 0 is meant) and its last row (0, 0, 0, 1).
fn axis_aligned(m: &DMat4) -> bool {
    let diagonal = [m.x_axis.x, m.y_axis.y, m.z_axis.z];
    let size = diagonal.iter().fold(0.0f64, |a, d| a.max(d.abs()));
    let off = [
        m.x_axis.y, m.x_axis.z, m.y_axis.x, m.y_axis.z, m.z_axis.x, m.z_axis.y,
    ];
    diagonal.iter().all(|&d| d > 0.0 && d.is_finite())
        && off.iter().all(|o| o.abs() <= 1e-6 * size)
        && [m.x_axis.w, m.y_axis.w, m.z_axis.w] == [0.0; 3]
        && m.w_axis.w == 1.0
}

/// The boolean `name` of `v` (false where absent).
fn boolean(v: &Object, name: &str) -> Result<bool, LoadError> {
    match v.property(name).map(|p| (&p.value, &p.at)) {
        None => Ok(false),
        Some((Value::Boolean(b), _)) => Ok(*b),
        Some((_, at)) => Err(error(at, format!("'{name}' must be a boolean"))),
    }
}

/// An error for a property or nested object of `v` outside `names`.
pub(crate) fn known(v: &Object, names: &[&str]) -> Result<(), LoadError> {
    let unknown = |name: &str, at: &Location| {
        error(
            at,
            format!(
                "{} '{}': parameter '{name}' is not read",
                v.class.tag(),
                v.kind
            ),
        )
    };
    if let Some(p) = v
        .properties
        .iter()
        .find(|p| !names.contains(&p.name.as_str()))
    {
        return Err(unknown(&p.name, &p.at));
    }
    match v
        .children
        .iter()
        .find(|c| !names.contains(&c.name.as_deref().unwrap_or("")))
    {
        Some(c) => Err(unknown(
            c.name.as_deref().unwrap_or(c.object.class.tag()),
            &c.object.at,
        )),
        None => Ok(()),
    }
}
