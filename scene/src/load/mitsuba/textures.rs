//! Mitsuba's textures (the "Textures" plugin reference): `bitmap` and `checkerboard`,
//! wherever a BSDF takes a spectrum ([`spectrum`]) or one number ([`float`]).
//!
//! A colour bitmap becomes reflectance spectra texel by texel, blended after upsampling
//! as Mitsuba's spectral variants blend them ([`crate::textures::Pattern`]); a grey one,
//! or a `raw` one where a number is asked, gives its value (its luminance for three
//! channels). Lookups use Mitsuba's texel centres, wrap modes, filters and `to_uv`
//! ([`crate::textures::Texels`]). Textures reach a surface through its texture
//! coordinates, which each shape gives as Mitsuba's does.

use std::sync::Arc;

use glam::{Affine2, Vec2};

use super::bitmaps::decode;
use super::files::Files;
use super::parse::error;
use super::shapes::{string, transform};
use super::spectra::{self, Kind};
use super::tree::{Class, Object, Value};
use crate::LoadError;
use crate::load::Upsampler;
use crate::textures::{Filter, FloatTexture, Pattern, SceneSpectrum, Texels, Wrap};

/// What reading textures needs: the upsampler (its coefficient table) and the files.
#[derive(Clone, Copy)]
pub(crate) struct Context<'a> {
    /// Upsamples colours.
    pub upsampler: &'a Upsampler,
    /// Reads the images textures name.
    pub files: Files<'a>,
}

/// The spectrum `name` of `object`: a nested texture, or as [`spectra::spectrum`] reads
/// a value (`default` where there is neither).
pub(crate) fn spectrum(
    object: &Object,
    name: &str,
    kind: Kind,
    default: f64,
    cx: &Context,
) -> Result<SceneSpectrum, LoadError> {
    match object.child(name) {
        Some(c) if c.object.class == Class::Texture => texture_spectrum(&c.object, kind, cx),
        _ => spectra::spectrum(object, name, kind, default, cx.upsampler),
    }
}

fn texture_spectrum(tex: &Object, kind: Kind, cx: &Context) -> Result<SceneSpectrum, LoadError> {
    if kind != Kind::Albedo {
        return Err(error(
            &tex.at,
            format!(
                "texture '{}' as an emitter's radiance is not read yet",
                tex.kind
            ),
        ));
    }
    match tex.kind.as_str() {
        "bitmap" => {
            let (texels, raw) = bitmap(tex, cx)?;
            let pattern = match (texels.channels(), raw) {
                (1, _) => Pattern::Scalar(texels),
                // Mitsuba refuses this too: raw colour data is not a spectrum.
                (_, true) => {
                    return Err(error(
                        &tex.at,
                        "a raw colour bitmap cannot be a spectrum (Mitsuba refuses it too)",
                    ));
                }
                _ => {
                    let table = cx.upsampler.table().map_err(|e| error(&tex.at, e))?;
                    Pattern::reflectances(&texels, &table).map_err(|e| error(&tex.at, e))?
                }
            };
            Ok(SceneSpectrum::Pattern(Arc::new(pattern)))
        }
        "checkerboard" => {
            only(tex, &["color0", "color1", "to_uv"])?;
            Ok(SceneSpectrum::Pattern(Arc::new(Pattern::Checkerboard {
                color0: spectrum(tex, "color0", kind, 0.4, cx)?,
                color1: spectrum(tex, "color1", kind, 0.2, cx)?,
                to_uv: to_uv(tex)?,
            })))
        }
        other => Err(unknown(tex, other)),
    }
}

/// The number `name` of `object` that may vary over the surface (Mitsuba's `eval_1`): a
/// number, a nested texture, or `default`.
pub(crate) fn float(
    object: &Object,
    name: &str,
    default: f32,
    cx: &Context,
) -> Result<FloatTexture, LoadError> {
    if let Some(c) = object.child(name)
        && c.object.class == Class::Texture
    {
        return texture_float(&c.object, cx);
    }
    if let Some(c) = object.child(name) {
        return Err(error(
            &c.object.at,
            format!(
                "{name}: expected a number or a texture, not a {}",
                c.object.class.tag()
            ),
        ));
    }
    match object.property(name).map(|p| (&p.value, &p.at)) {
        None => Ok(FloatTexture::Constant(default)),
        Some((Value::Float(v), at)) => finite(*v, name, at),
        Some((Value::Integer(v), at)) => finite(*v as f64, name, at),
        Some((Value::Spectrum(crate::load::mitsuba::SpectrumValue::Constant(v)), at)) => {
            finite(*v, name, at)
        }
        Some((Value::Rgb([r, g, b]), at)) if r == g && g == b => finite(*r, name, at),
        Some((_, at)) => Err(error(at, format!("{name} must be a number or a texture"))),
    }
}

fn finite(v: f64, name: &str, at: &super::tree::Location) -> Result<FloatTexture, LoadError> {
    if v.is_finite() {
        Ok(FloatTexture::Constant(v as f32))
    } else {
        Err(error(at, format!("{name} {v} is not a finite number")))
    }
}

fn texture_float(tex: &Object, cx: &Context) -> Result<FloatTexture, LoadError> {
    match tex.kind.as_str() {
        "bitmap" => {
            let (texels, raw) = bitmap(tex, cx)?;
            if texels.channels() == 3 && !raw {
                // Mitsuba's spectral variants refuse it (`eval_1` of an upsampled bitmap).
                return Err(error(
                    &tex.at,
                    "a colour bitmap where one number is asked must be raw (Mitsuba refuses \
                     it otherwise); give raw=true or a grey image",
                ));
            }
            Ok(FloatTexture::Texels(texels))
        }
        "checkerboard" => {
            only(tex, &["color0", "color1", "to_uv"])?;
            Ok(FloatTexture::Checkerboard {
                color0: Box::new(float(tex, "color0", 0.4, cx)?),
                color1: Box::new(float(tex, "color1", 0.2, cx)?),
                to_uv: to_uv(tex)?,
            })
        }
        other => Err(unknown(tex, other)),
    }
}

fn unknown(tex: &Object, kind: &str) -> LoadError {
    error(
        &tex.at,
        format!("texture '{kind}' is not read yet (bitmap and checkerboard are)"),
    )
}

/// A `bitmap`'s texels (as Mitsuba stores them: linear, or as stored when `raw`) and
/// whether it is raw.
pub(crate) fn bitmap(tex: &Object, cx: &Context) -> Result<(Texels, bool), LoadError> {
    only(
        tex,
        &[
            "filename",
            "filter_type",
            "wrap_mode",
            "raw",
            "to_uv",
            "format",
            "accel",
        ],
    )?;
    let name = string(tex, "filename")?;
    let filter = match choice(tex, "filter_type", "bilinear")?.as_str() {
        "bilinear" => Filter::Bilinear,
        "nearest" => Filter::Nearest,
        other => return Err(bad_choice(tex, "filter_type", other, "bilinear or nearest")),
    };
    let wrap = match choice(tex, "wrap_mode", "repeat")?.as_str() {
        "repeat" => Wrap::Repeat,
        "mirror" => Wrap::Mirror,
        "clamp" => Wrap::Clamp,
        other => {
            return Err(bad_choice(
                tex,
                "wrap_mode",
                other,
                "repeat, mirror or clamp",
            ));
        }
    };
    // `format` chooses Mitsuba's storage precision; spectral variants keep their own
    // floats under `auto` and `variant`, and prism keeps 32-bit floats for `fp16` too.
    match choice(tex, "format", "auto")?.as_str() {
        "auto" | "variant" | "fp16" => {}
        other => return Err(bad_choice(tex, "format", other, "auto, variant or fp16")),
    }
    let raw = boolean(tex, "raw", false)?;
    boolean(tex, "accel", true)?;
    let bytes = cx.files.read(&name, &tex.at)?;
    let image = decode(&bytes, raw).map_err(|e| error(&tex.at, format!("{name}: {e}")))?;
    let texels = Texels::new(
        image.width,
        image.height,
        image.channels,
        image.data,
        wrap,
        filter,
        to_uv(tex)?,
    )
    .map_err(|e| error(&tex.at, format!("{name}: {e}")))?;
    Ok((texels, raw))
}

/// `to_uv` as the affine map of the plane Mitsuba extracts from a 4 x 4 transform: the
/// upper-left 2 x 2 block and the first two rows' translation.
fn to_uv(tex: &Object) -> Result<Affine2, LoadError> {
    let m = transform(tex, "to_uv")?;
    let affine = Affine2::from_cols(
        Vec2::new(m.x_axis.x as f32, m.x_axis.y as f32),
        Vec2::new(m.y_axis.x as f32, m.y_axis.y as f32),
        Vec2::new(m.w_axis.x as f32, m.w_axis.y as f32),
    );
    if affine.is_finite() {
        Ok(affine)
    } else {
        let at = tex.property("to_uv").map_or(&tex.at, |p| &p.at);
        Err(error(at, "to_uv is not finite"))
    }
}

fn choice(object: &Object, name: &str, default: &str) -> Result<String, LoadError> {
    match object.property(name) {
        None => Ok(default.to_string()),
        Some(_) => string(object, name),
    }
}

fn bad_choice(object: &Object, name: &str, value: &str, valid: &str) -> LoadError {
    let at = object.property(name).map_or(&object.at, |p| &p.at);
    error(at, format!("{name} \"{value}\": expected {valid}"))
}

fn boolean(object: &Object, name: &str, default: bool) -> Result<bool, LoadError> {
    match object.property(name).map(|p| (&p.value, &p.at)) {
        None => Ok(default),
        Some((Value::Boolean(b), _)) => Ok(*b),
        Some((_, at)) => Err(error(at, format!("{name} must be a boolean"))),
    }
}

/// An error for a property or nested object of `tex` outside `known`.
fn only(tex: &Object, known: &[&str]) -> Result<(), LoadError> {
    for p in &tex.properties {
        if !known.contains(&p.name.as_str()) {
            return Err(error(
                &p.at,
                format!("texture {}: parameter '{}' is not read", tex.kind, p.name),
            ));
        }
    }
    for c in &tex.children {
        if !c.name.as_deref().is_some_and(|n| known.contains(&n)) {
            return Err(error(
                &c.object.at,
                format!(
                    "texture {}: nested {} '{}' is not read",
                    tex.kind,
                    c.object.class.tag(),
                    c.object.kind
                ),
            ));
        }
    }
    Ok(())
}
