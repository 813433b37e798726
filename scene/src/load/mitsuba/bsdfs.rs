//! Mitsuba's BSDFs as prism's materials (Mitsuba's "BSDFs" plugin reference): `diffuse`,
//! and `twosided` around it. Spectral values enter as spectra; RGB is upsampled as the
//! scene's other colours are (`crate::load::Upsampling`).

use std::sync::Arc;

use super::parse::error;
use super::spectra::{Kind, spectrum};
use super::tree::Object;
use crate::LoadError;
use crate::load::Upsampler;
use crate::materials::Material;

/// The material of `bsdf`.
pub(crate) fn material(bsdf: &Object, upsampler: &Upsampler) -> Result<Material, LoadError> {
    match bsdf.kind.as_str() {
        "diffuse" => Ok(Material::Diffuse {
            reflectance: spectrum(bsdf, "reflectance", Kind::Albedo, 0.5, upsampler)?,
        }),
        // prism's surfaces reflect on both sides, so `twosided` is its one BSDF.
        "twosided" => {
            let mut inner = bsdf
                .children
                .iter()
                .filter(|c| c.object.class == super::tree::Class::Bsdf);
            match (inner.next(), inner.next()) {
                (Some(one), None) => material(&one.object, upsampler),
                (Some(_), Some(_)) => Err(error(
                    &bsdf.at,
                    "twosided with a different BSDF on each side is not read yet",
                )),
                (None, _) => Err(error(&bsdf.at, "twosided needs a nested BSDF")),
            }
        }
        other => Err(error(
            &bsdf.at,
            format!("bsdf '{other}' is not read yet (diffuse and twosided are)"),
        )),
    }
}

/// What an object shared by reference is keyed by: the same `Arc` is the same object.
pub(crate) fn key(object: &Arc<Object>) -> usize {
    Arc::as_ptr(object) as usize
}
