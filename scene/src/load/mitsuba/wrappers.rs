//! Mitsuba's BSDF adapters around a shape's BSDF: `mask` as prism's alpha coverage, the
//! rest as what their nested BSDF becomes ([`super::bsdfs::material`]).
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
use super::textures::{Context, float};
use super::tree::{Class, Object};
use crate::LoadError;
use crate::materials::{Alpha, AlphaMode, Material};
use crate::textures::FloatTexture;

/// The material of a shape's BSDF and the alpha coverage of a `mask` around it (None:
/// opaque).
pub(crate) fn surface(bsdf: &Object, cx: &Context) -> Result<(Material, Option<Alpha>), LoadError> {
    match bsdf.kind.as_str() {
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
            let (surface, _) = surface(inner, cx)?;
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
            Ok((surface, alpha))
        }
        // A mask inside twosided: prism's surfaces are two-sided already.
        "twosided" if bsdf.children_of(Class::Bsdf).count() == 1 => {
            let inner = one_nested(bsdf)?;
            if inner.kind == "mask" {
                surface(inner, cx)
            } else {
                Ok((material(bsdf, cx)?, None))
            }
        }
        _ => Ok((material(bsdf, cx)?, None)),
    }
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
