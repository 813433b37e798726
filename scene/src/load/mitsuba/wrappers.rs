//! Mitsuba's BSDF adapters around a shape's BSDF: `mask` as prism's alpha coverage,
//! `normalmap` and `bumpmap` as a tilt of the shading normal
//! ([`crate::materials::Perturbation`], Mitsuba's model), the rest as what their nested
//! BSDF becomes ([`super::bsdfs::material`]).
//!
//! Mitsuba's `mask` lets light through with probability 1 - opacity, unbent, and
//! scatters with the nested BSDF otherwise ("Opacity mask", BSDF plugin reference):
//! prism's stochastic alpha (`AlphaMode::Blend`) does the same for the rays that meet the
//! surface. Two things differ, both of Mitsuba's `path` integrator rather than of the
//! mask: a ray through the mask counts as a bounce toward `max_depth` there, and shadow
//! rays do not pass masked surfaces at all (`Scene::ray_test` sees geometry only); in
//! prism light passes a cut-out surface alike for every ray.

use std::sync::Arc;

use super::bsdfs::material;
use super::parse::error;
use super::textures::{Context, bitmap, float};
use super::tree::{Class, Object, Value};
use crate::LoadError;
use crate::materials::{Alpha, AlphaMode, Material, Perturbation};
use crate::textures::FloatTexture;

/// What a shape's BSDF becomes: a material, the alpha coverage of a `mask` around it
/// (None: opaque), and the normal or bump map around it.
pub(crate) struct Surface {
    pub material: Material,
    pub alpha: Option<Alpha>,
    pub perturbation: Option<Perturbation>,
}

/// The surface a shape's BSDF makes.
pub(crate) fn surface(bsdf: &Object, cx: &Context) -> Result<Surface, LoadError> {
    match bsdf.kind.as_str() {
        "normalmap" | "bumpmap" => {
            for p in &bsdf.properties {
                let known: &[&str] = if bsdf.kind == "bumpmap" {
                    &["scale"]
                } else {
                    &[]
                };
                match p.name.as_str() {
                    "flip_invalid_normals" | "use_shadowing_function"
                        if matches!(p.value, Value::Boolean(true)) => {}
                    name if known.contains(&name) => {}
                    name => {
                        return Err(error(
                            &p.at,
                            format!("{}: parameter '{name}' is not read", bsdf.kind),
                        ));
                    }
                }
            }
            let inner = one_nested(bsdf)?;
            if matches!(inner.kind.as_str(), "mask" | "normalmap" | "bumpmap") {
                return Err(error(
                    &inner.at,
                    format!("{} inside {} is not read", inner.kind, bsdf.kind),
                ));
            }
            let perturbation = if bsdf.kind == "normalmap" {
                normal_map(bsdf, cx)?
            } else {
                bump_map(bsdf, cx)?
            };
            Ok(Surface {
                material: material(inner, cx)?,
                alpha: None,
                perturbation: Some(perturbation),
            })
        }
        "mask" => {
            for p in &bsdf.properties {
                if p.name != "opacity" {
                    return Err(error(
                        &p.at,
                        format!("mask: parameter '{}' is not read", p.name),
                    ));
                }
            }
            let inner = one_nested(bsdf)?;
            if inner.kind == "mask" {
                return Err(error(&inner.at, "a mask inside a mask is not read"));
            }
            // Mitsuba's default opacity is 0.5.
            let opacity = float(bsdf, "opacity", 0.5, cx)?;
            let inner = surface(inner, cx)?;
            let alpha = match opacity {
                FloatTexture::Constant(v) if v >= 1.0 => None,
                FloatTexture::Constant(v) => Some(Alpha {
                    mode: AlphaMode::Blend,
                    factor: v.max(0.0),
                    texture: None,
                    opacity: None,
                }),
                varying => Some(Alpha {
                    mode: AlphaMode::Blend,
                    factor: 1.0,
                    texture: None,
                    opacity: Some(Arc::new(varying)),
                }),
            };
            Ok(Surface { alpha, ..inner })
        }
        // A mask inside twosided: prism's surfaces are two-sided already.
        "twosided" if bsdf.children_of(Class::Bsdf).count() == 1 => {
            let inner = one_nested(bsdf)?;
            if matches!(inner.kind.as_str(), "mask" | "normalmap" | "bumpmap") {
                surface(inner, cx)
            } else {
                plain(bsdf, cx)
            }
        }
        _ => plain(bsdf, cx),
    }
}

fn plain(bsdf: &Object, cx: &Context) -> Result<Surface, LoadError> {
    Ok(Surface {
        material: material(bsdf, cx)?,
        alpha: None,
        perturbation: None,
    })
}

/// A `normalmap`'s texture: a raw three-channel bitmap, or a `rawconstant` normal.
fn normal_map(bsdf: &Object, cx: &Context) -> Result<Perturbation, LoadError> {
    let tex = bsdf
        .child("normalmap")
        .map(|c| &c.object)
        .filter(|o| o.class == Class::Texture)
        .ok_or_else(|| error(&bsdf.at, "normalmap needs a texture named 'normalmap'"))?;
    match tex.kind.as_str() {
        "bitmap" => {
            let (texels, raw) = bitmap(tex, cx)?;
            if texels.channels() != 3 || !raw {
                return Err(error(
                    &tex.at,
                    "a normal map must be a raw colour bitmap (Mitsuba reads its colour \
                     as the normal 2c - 1)",
                ));
            }
            Ok(Perturbation::NormalMap(texels))
        }
        "rawconstant" => match tex.property("value").map(|p| (&p.value, &p.at)) {
            Some((Value::Vector(v) | Value::Point(v) | Value::Rgb(v), _))
                if v.iter().all(|c| c.is_finite()) =>
            {
                let [x, y, z] = v.map(|c| 2.0 * c as f32 - 1.0);
                Ok(Perturbation::ConstantNormal(glam::Vec3::new(x, y, z)))
            }
            Some((_, at)) => Err(error(at, "rawconstant: value must be three finite numbers")),
            None => Err(error(&tex.at, "rawconstant needs a value")),
        },
        other => Err(error(
            &tex.at,
            format!("a normal map from texture '{other}' is not read (bitmap and rawconstant are)"),
        )),
    }
}

/// A `bumpmap`'s height texture (its one nested texture) and scale.
fn bump_map(bsdf: &Object, cx: &Context) -> Result<Perturbation, LoadError> {
    let mut textures = bsdf.children_of(Class::Texture);
    let tex = match (textures.next(), textures.next()) {
        (Some(one), None) => &one.object,
        _ => return Err(error(&bsdf.at, "bumpmap takes one nested texture")),
    };
    if tex.kind != "bitmap" {
        return Err(error(
            &tex.at,
            format!(
                "bumpmap heights from texture '{}' are not read (bitmap is)",
                tex.kind
            ),
        ));
    }
    let (texels, raw) = bitmap(tex, cx)?;
    if texels.channels() == 3 && !raw {
        return Err(error(
            &tex.at,
            "bumpmap heights from a colour bitmap must be raw (Mitsuba refuses it otherwise)",
        ));
    }
    let scale = match bsdf.property("scale").map(|p| (&p.value, &p.at)) {
        None => 1.0,
        Some((Value::Float(v), _)) if v.is_finite() => *v as f32,
        Some((Value::Integer(v), _)) => *v as f32,
        Some((_, at)) => return Err(error(at, "bumpmap: scale must be a finite number")),
    };
    Ok(Perturbation::Bump {
        height: FloatTexture::Texels(texels),
        scale,
    })
}

/// The one BSDF nested in `bsdf`.
fn one_nested(bsdf: &Object) -> Result<&Object, LoadError> {
    let mut nested = bsdf.children_of(Class::Bsdf);
    match (nested.next(), nested.next()) {
        (Some(one), None) => Ok(&one.object),
        (None, _) => Err(error(
            &bsdf.at,
            format!("{} needs a nested BSDF", bsdf.kind),
        )),
        (Some(_), Some(_)) => Err(error(
            &bsdf.at,
            format!("{} takes one nested BSDF", bsdf.kind),
        )),
    }
}
