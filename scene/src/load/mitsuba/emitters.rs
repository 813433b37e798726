//! Mitsuba's emitters that stand on their own (not on a shape), as prism's lights: the
//! plugins of Mitsuba 3's "Emitters" reference (src/emitters/*.cpp).
//!
//! - `constant` (`radiance`): the uniform environment.
//! - `envmap` (`filename`, `scale`, `to_world`): an environment image read with Mitsuba's
//!   direction mapping, texel grid and spectra ([`EnvironmentMap::mitsuba`]).
//!   `mis_compensation` is a sampling choice: prism always compensates next-event
//!   estimation's samples, which leaves the image's expectation as it is.
//! - `point` (`intensity` in W sr^-1, `position` or `to_world`'s translation).
//! - `directional` (`irradiance` in W m^-2 facing the light, travelling along
//!   `direction` or `to_world`'s +z).
//! - `spot` (`intensity` on the axis, `cutoff_angle` and `beam_width` in degrees, at
//!   `to_world`'s translation along its +z), with Mitsuba's falloff, linear in angle
//!   ([`SpotFalloff::LinearAngle`]), and its projected `texture` ([`SpotTexture`]).
//! - `projector` (`irradiance`, `scale`, `fov`, `to_world`): a spot light projecting its
//!   image through a frustum ([`SpotTexture::frustum`], [`SpotFalloff::InverseCosCubed`]).
//!
//! An emitter's colour is an illuminant, as `get_emissive_texture` makes it in spectral
//! variants: RGB and plain numbers times D65 (a number v is the colour (v, v, v), and an
//! absent one 1), spectra as given in Mitsuba's units (luminance relative to a spectrum
//! of 1, see [`CIE_Y_NORMALIZATION`]).

use std::sync::Arc;

use glam::{DMat4, DVec3, Mat3, Vec3};

use super::bitmaps::decode;
use super::parse::error;
use super::shapes::{string, transform};
use super::spectra::{Kind, spectrum};
use super::textures::Context;
use super::tree::{Class, Object, Value};
use crate::LoadError;
use crate::lights::{Environment, EnvironmentMap, SpotFalloff, SpotTexture};
use crate::load::{LightDesc, LoadedGeometry, Upsampler};
use crate::textures::SceneSpectrum;

/// Adds a top-level emitter to `out`.
pub(crate) fn emitter(
    emitter: &Object,
    cx: &Context,
    out: &mut LoadedGeometry,
) -> Result<(), LoadError> {
    let upsampler = cx.upsampler;
    match emitter.kind.as_str() {
        "constant" => {
            only(emitter, &["radiance"])?;
            let radiance = emission(emitter, "radiance", upsampler)?;
            set_environment(emitter, Environment::Uniform(radiance), out)
        }
        "envmap" => {
            only(
                emitter,
                &["filename", "scale", "to_world", "mis_compensation"],
            )?;
            let map = envmap(emitter, cx)?;
            set_environment(emitter, Environment::Map(Arc::new(map)), out)
        }
        "point" => {
            only(emitter, &["intensity", "position", "to_world"])?;
            let position = match emitter.property("position") {
                Some(p) => {
                    exclusive(emitter, "position")?;
                    match p.value {
                        Value::Point(v) | Value::Vector(v) => DVec3::from(v),
                        _ => return Err(error(&p.at, "'position' must be a point")),
                    }
                }
                None => transform(emitter, "to_world")?.w_axis.truncate(),
            };
            out.lights.push(LightDesc::Point {
                position: finite_vec(emitter, position, "position")?,
                spectrum: emission(emitter, "intensity", upsampler)?,
                scale: 1.0,
            });
            Ok(())
        }
        "directional" => {
            only(emitter, &["irradiance", "direction", "to_world"])?;
            let direction = match emitter.property("direction") {
                Some(p) => {
                    exclusive(emitter, "direction")?;
                    match p.value {
                        Value::Point(v) | Value::Vector(v) => DVec3::from(v),
                        _ => return Err(error(&p.at, "'direction' must be a vector")),
                    }
                }
                None => axis(&transform(emitter, "to_world")?),
            };
            out.lights.push(LightDesc::Directional {
                direction: unit(emitter, direction, "direction")?,
                spectrum: emission(emitter, "irradiance", upsampler)?,
                scale: 1.0,
            });
            Ok(())
        }
        "spot" => {
            only(
                emitter,
                &[
                    "intensity",
                    "cutoff_angle",
                    "beam_width",
                    "to_world",
                    "texture",
                ],
            )?;
            let to_world = transform(emitter, "to_world")?;
            let cutoff = angle(emitter, "cutoff_angle")?.unwrap_or(20.0);
            let beam = angle(emitter, "beam_width")?.unwrap_or(cutoff * 0.75);
            if !(0.0 < beam && beam <= cutoff && cutoff <= 180.0) {
                return Err(error(
                    &emitter.at,
                    format!(
                        "spot: beam_width {beam} and cutoff_angle {cutoff} must satisfy \
                         0 < beam_width <= cutoff_angle <= 180"
                    ),
                ));
            }
            // Mitsuba reads the texture as any texture (a bitmap's colours as
            // reflectance spectra), and it multiplies the intensity.
            if let Some(p) = emitter.property("texture") {
                return Err(error(
                    &p.at,
                    "spot: 'texture' must be a texture (Mitsuba asks for a spatially varying one)",
                ));
            }
            let texture = match emitter.child("texture") {
                None => None,
                Some(c) if c.object.class == Class::Texture => {
                    let texture =
                        super::textures::spectrum(emitter, "texture", Kind::Albedo, 1.0, cx)?;
                    let projected =
                        SpotTexture::new(linear(&to_world), cutoff.to_radians() as f32, texture)
                            .map_err(|e| error(&c.object.at, format!("spot: {e}")))?;
                    Some(Arc::new(projected))
                }
                Some(c) => {
                    return Err(error(
                        &c.object.at,
                        "spot: 'texture' must be a texture (Mitsuba asks for a spatially varying one)",
                    ));
                }
            };
            out.lights.push(LightDesc::Spot {
                position: finite_vec(emitter, to_world.w_axis.truncate(), "to_world")?,
                direction: unit(emitter, axis(&to_world), "to_world's +z")?,
                inner: beam.to_radians() as f32,
                outer: cutoff.to_radians() as f32,
                spectrum: emission(emitter, "intensity", upsampler)?,
                scale: 1.0,
                falloff: SpotFalloff::LinearAngle,
                texture,
            });
            Ok(())
        }
        "projector" => projector(emitter, cx, out),
        other => Err(error(
            &emitter.at,
            format!(
                "emitter '{other}' is not read yet (area, constant, envmap, point, \
                 directional, spot and projector are)"
            ),
        )),
    }
}

/// Mitsuba 3's `projector` (src/emitters/projector.cpp) as a spot light at `to_world`'s
/// translation whose [`SpotTexture::frustum`] projects `irradiance` through the
/// perspective camera's frustum (`fov`, `fov_axis` or `focal_length` as the
/// `perspective` sensor reads them, the aspect the texture's resolution, 1 for a constant)
/// and whose intensity in direction w at angle theta from the axis is
/// pi scale E(uv(w)) / cos^3 theta ([`SpotFalloff::InverseCosCubed`]); Mitsuba's
/// `sample_direction` returns it over dist^2 as pi scale E / (z_local^2 cos theta).
/// A constant `irradiance` is an illuminant (D65 for an RGB colour); a texture is read as
/// `bitmap` reads any texture in spectral variants (its colours as reflectance spectra,
/// with no illuminant), so its spectrum is 1 in Mitsuba's units (over the y-bar
/// integral, `MITSUBA_Y_NORMALIZATION`).
fn projector(emitter: &Object, cx: &Context, out: &mut LoadedGeometry) -> Result<(), LoadError> {
    only(
        emitter,
        &[
            "irradiance",
            "scale",
            "to_world",
            "fov",
            "fov_axis",
            "focal_length",
        ],
    )?;
    let to_world = transform(emitter, "to_world")?;
    let scale = match emitter.property("scale").map(|p| &p.value) {
        None => 1.0,
        Some(Value::Float(v)) => *v,
        Some(Value::Integer(v)) => *v as f64,
        Some(_) => return Err(error(&emitter.at, "projector: 'scale' must be a number")),
    };
    let textured = emitter
        .child("irradiance")
        .filter(|c| c.object.class == Class::Texture);
    // Mitsuba's `Texture::resolution`: a bitmap's size, (1, 1) for any other texture.
    let (width, height) = match textured {
        Some(c) if c.object.kind == "bitmap" => super::textures::bitmap(&c.object, cx)?.0.size(),
        _ => (1, 1),
    };
    let aspect = f64::from(width) / f64::from(height);
    let tan_y = match super::sensors::perspective(emitter, aspect)? {
        crate::camera::Projection::Perspective { yfov } => (f64::from(yfov) / 2.0).tan(),
        _ => {
            return Err(error(
                &emitter.at,
                "projector: expected a perspective field of view",
            ));
        }
    };
    let tan_half = glam::Vec2::new((tan_y * aspect) as f32, tan_y as f32);
    let (spectrum, image) = match textured {
        // Mitsuba's films divide every spectrum by the y-bar integral, a texel's too.
        Some(_) => (
            SceneSpectrum::Constant(super::spectra::MITSUBA_Y_NORMALIZATION),
            super::textures::spectrum(emitter, "irradiance", Kind::Albedo, 1.0, cx)?,
        ),
        None => (
            emission(emitter, "irradiance", cx.upsampler)?,
            SceneSpectrum::Constant(1.0),
        ),
    };
    let projected = SpotTexture::frustum(linear(&to_world), tan_half, image)
        .map_err(|e| error(&emitter.at, format!("projector: {e}")))?;
    // The cone holding the frustum, a little wider so that its corners stay lit; the
    // frustum itself clips.
    let outer = (projected.tan_extent().atan() * (1.0 + 1e-4)).min(std::f32::consts::FRAC_PI_2);
    out.lights.push(LightDesc::Spot {
        position: finite_vec(emitter, to_world.w_axis.truncate(), "to_world")?,
        direction: unit(emitter, axis(&to_world), "to_world's +z")?,
        inner: outer,
        outer,
        spectrum,
        scale: std::f64::consts::PI * scale,
        falloff: SpotFalloff::InverseCosCubed,
        texture: Some(Arc::new(projected)),
    });
    Ok(())
}

/// The emitted spectrum `name` of `emitter` as Mitsuba's spectral variants read it
/// (`Properties::get_texture_impl`): its absence is D65, and the rest as
/// [`spectrum`] reads an illuminant (a number a grey under D65, a spectrum given as
/// numbers scaled by Mitsuba's luminance normalization).
pub(crate) fn emission(
    emitter: &Object,
    name: &str,
    upsampler: &Upsampler,
) -> Result<SceneSpectrum, LoadError> {
    if emitter.property(name).is_none() && emitter.child(name).is_none() {
        let fitted = upsampler
            .emission([1.0; 3])
            .map_err(|e| error(&emitter.at, format!("{name}: {e}")))?;
        return Ok(SceneSpectrum::Rgb(Arc::new(fitted)));
    }
    spectrum(emitter, name, Kind::Illuminant, 1.0, upsampler)
}

/// Mitsuba's `envmap`: its image, scale and frame.
fn envmap(emitter: &Object, cx: &Context) -> Result<EnvironmentMap, LoadError> {
    let name = string(emitter, "filename")?;
    let scale = match emitter.property("scale") {
        None => 1.0,
        Some(p) => match p.value {
            Value::Float(v) if v.is_finite() && v >= 0.0 => v,
            Value::Integer(v) if v >= 0 => v as f64,
            _ => return Err(error(&p.at, "'scale' must be a number >= 0")),
        },
    };
    match emitter
        .property("mis_compensation")
        .map(|p| (&p.value, &p.at))
    {
        None | Some((Value::Boolean(_), _)) => {}
        Some((_, at)) => return Err(error(at, "'mis_compensation' must be a boolean")),
    }
    let frame = linear(&transform(emitter, "to_world")?);
    let bytes = cx.files.read(&name, &emitter.at)?;
    // PNG and JPEG are sRGB-encoded: Mitsuba converts them to linear values first.
    let image = decode(&bytes, false).map_err(|e| error(&emitter.at, format!("{name}: {e}")))?;
    let texels: Vec<[f32; 3]> = match image.channels {
        1 => image.data.iter().map(|&v| [v; 3]).collect(),
        _ => image
            .data
            .chunks_exact(image.channels)
            .map(|c| [c[0], c[1], c[2]])
            .collect(),
    };
    let table = cx
        .upsampler
        .table()
        .map_err(|e| error(&emitter.at, format!("{name}: {e}")))?;
    EnvironmentMap::mitsuba(
        image.width,
        image.height,
        texels,
        frame,
        scale,
        (
            table,
            cx.upsampler.context.clone(),
            cx.upsampler.illuminant.clone(),
        ),
    )
    .map_err(|e| error(&emitter.at, format!("{name}: {e}")))
}

fn set_environment(
    emitter: &Object,
    environment: Environment,
    out: &mut LoadedGeometry,
) -> Result<(), LoadError> {
    if out.spectral.environment.is_some() {
        return Err(error(&emitter.at, "a second environment emitter"));
    }
    out.spectral.environment = Some(environment);
    Ok(())
}

/// Mitsuba refuses `name` beside `to_world`.
fn exclusive(emitter: &Object, name: &str) -> Result<(), LoadError> {
    match emitter.property("to_world") {
        Some(p) => Err(error(
            &p.at,
            format!("only one of '{name}' and 'to_world' can be given"),
        )),
        None => Ok(()),
    }
}

/// The linear part of a transform.
fn linear(to_world: &DMat4) -> Mat3 {
    Mat3::from_cols(
        to_world.x_axis.truncate().as_vec3(),
        to_world.y_axis.truncate().as_vec3(),
        to_world.z_axis.truncate().as_vec3(),
    )
}

/// The direction `to_world` turns +z into.
fn axis(to_world: &DMat4) -> DVec3 {
    to_world.transform_vector3(DVec3::Z)
}

fn finite_vec(emitter: &Object, v: DVec3, name: &str) -> Result<Vec3, LoadError> {
    let v = v.as_vec3();
    if v.is_finite() {
        Ok(v)
    } else {
        Err(error(&emitter.at, format!("{name} is not finite")))
    }
}

fn unit(emitter: &Object, v: DVec3, name: &str) -> Result<Vec3, LoadError> {
    match v.try_normalize() {
        Some(u) => Ok(u.as_vec3()),
        None => Err(error(
            &emitter.at,
            format!("{name} is not a direction (zero or not finite)"),
        )),
    }
}

/// An angle in degrees.
fn angle(emitter: &Object, name: &str) -> Result<Option<f64>, LoadError> {
    super::sensors::number(emitter, name)
}

/// An error for a property or nested object of `emitter` outside `known`.
pub(crate) fn only(emitter: &Object, known: &[&str]) -> Result<(), LoadError> {
    for p in &emitter.properties {
        if !known.contains(&p.name.as_str()) {
            return Err(error(
                &p.at,
                format!(
                    "emitter {}: parameter '{}' is not read",
                    emitter.kind, p.name
                ),
            ));
        }
    }
    for c in &emitter.children {
        if !c.name.as_deref().is_some_and(|n| known.contains(&n)) {
            return Err(error(
                &c.object.at,
                format!(
                    "emitter {}: nested {} '{}' is not read",
                    emitter.kind,
                    c.object.class.tag(),
                    c.object.kind
                ),
            ));
        }
    }
    Ok(())
}
