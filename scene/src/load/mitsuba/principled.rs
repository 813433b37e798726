//! Mitsuba's `principled` and `principledthin` BSDFs (Mitsuba 3's "BSDFs" plugin
//! reference; `src/bsdfs/principled.cpp`, `principledthin.cpp`) as prism's materials of
//! the same models ([`crate::bsdf::Principled`], [`crate::bsdf::PrincipledThin`]).
//!
//! Every parameter Mitsuba takes as a texture may be a number or a texture here
//! (`bitmap`, `checkerboard`), the base colour a spectrum, a colour or a texture.
//! Defaults, `specular`'s map to `eta` and the nudges away from an index of 1 where
//! light is transmitted are Mitsuba's.

use std::sync::Arc;

use super::parse::error;
use super::spectra::Kind;
use super::textures::{self, Context};
use super::tree::{Object, Value};
use crate::LoadError;
use crate::bsdf::{PrincipledRates, PrincipledThinRates};
use crate::materials::{Material, PrincipledDesc, PrincipledThinDesc};

/// The parameters both plugins read as textures.
const SHARED: [&str; 8] = [
    "base_color",
    "roughness",
    "anisotropic",
    "spec_trans",
    "spec_tint",
    "sheen",
    "sheen_tint",
    "flatness",
];

/// `principled`.
pub(crate) fn principled(bsdf: &Object, cx: &Context) -> Result<Material, LoadError> {
    let mut known = SHARED.to_vec();
    known.extend([
        "metallic",
        "clearcoat",
        "clearcoat_gloss",
        "eta",
        "specular",
        "diffuse_reflectance_sampling_rate",
        "main_specular_sampling_rate",
        "clearcoat_sampling_rate",
    ]);
    only(bsdf, &known)?;
    let transmits = flag(bsdf, "spec_trans");
    let eta = match (number(bsdf, "eta")?, number(bsdf, "specular")?) {
        (Some(_), Some(_)) => {
            return Err(error(
                &bsdf.at,
                "principled: give eta or specular, not both (Mitsuba refuses both)",
            ));
        }
        // An index of 1 transmits nothing (Mitsuba nudges it to 1.001).
        (Some(eta), None) if transmits && eta == 1.0 => 1.001,
        (Some(eta), None) => eta,
        (None, specular) => {
            let mut s = specular.unwrap_or(0.5);
            if transmits && s == 0.0 {
                s = 1e-3;
            }
            // Burley's specular is F0 / 0.08 (2012 notes §5.6): eta of that F0.
            2.0 / (1.0 - (0.08 * s).sqrt()) - 1.0
        }
    };
    if !(eta.is_finite() && eta > 0.0) {
        return Err(error(
            &bsdf.at,
            format!("principled: eta {eta} is not a positive index (specular must be in [0, 1])"),
        ));
    }
    let desc = PrincipledDesc {
        base_color: textures::spectrum(bsdf, "base_color", Kind::Albedo, 0.5, cx)?,
        roughness: textures::float(bsdf, "roughness", 0.5, cx)?,
        anisotropic: textures::float(bsdf, "anisotropic", 0.0, cx)?,
        metallic: textures::float(bsdf, "metallic", 0.0, cx)?,
        spec_trans: textures::float(bsdf, "spec_trans", 0.0, cx)?,
        spec_tint: textures::float(bsdf, "spec_tint", 0.0, cx)?,
        sheen: textures::float(bsdf, "sheen", 0.0, cx)?,
        sheen_tint: textures::float(bsdf, "sheen_tint", 0.0, cx)?,
        flatness: textures::float(bsdf, "flatness", 0.0, cx)?,
        clearcoat: textures::float(bsdf, "clearcoat", 0.0, cx)?,
        clearcoat_gloss: textures::float(bsdf, "clearcoat_gloss", 0.0, cx)?,
        eta: eta as f32,
        rates: PrincipledRates {
            diffuse: rate(bsdf, "diffuse_reflectance_sampling_rate")?,
            specular: rate(bsdf, "main_specular_sampling_rate")?,
            clearcoat: rate(bsdf, "clearcoat_sampling_rate")?,
        },
    };
    if desc.rates.diffuse + desc.rates.specular + desc.rates.clearcoat <= 0.0 {
        return Err(error(&bsdf.at, "principled: every sampling rate is 0"));
    }
    Ok(Material::Principled(Arc::new(desc)))
}

/// `principledthin`.
pub(crate) fn principled_thin(bsdf: &Object, cx: &Context) -> Result<Material, LoadError> {
    let mut known = SHARED.to_vec();
    known.extend([
        "eta",
        "diff_trans",
        "specular_reflectance_sampling_rate",
        "specular_transmittance_sampling_rate",
        "diffuse_reflectance_sampling_rate",
        "diffuse_transmittance_sampling_rate",
    ]);
    only(bsdf, &known)?;
    let eta = textures::float(bsdf, "eta", 1.5, cx)?;
    if let Some(e) = eta.constant()
        && (e.is_nan() || e <= 0.0)
    {
        return Err(error(
            &bsdf.at,
            format!("principledthin: eta {e} is not a positive index"),
        ));
    }
    let desc = PrincipledThinDesc {
        base_color: textures::spectrum(bsdf, "base_color", Kind::Albedo, 0.5, cx)?,
        roughness: textures::float(bsdf, "roughness", 0.5, cx)?,
        anisotropic: textures::float(bsdf, "anisotropic", 0.0, cx)?,
        spec_trans: textures::float(bsdf, "spec_trans", 0.0, cx)?,
        spec_tint: textures::float(bsdf, "spec_tint", 0.0, cx)?,
        sheen: textures::float(bsdf, "sheen", 0.0, cx)?,
        sheen_tint: textures::float(bsdf, "sheen_tint", 0.0, cx)?,
        flatness: textures::float(bsdf, "flatness", 0.0, cx)?,
        diff_trans: textures::float(bsdf, "diff_trans", 0.0, cx)?,
        eta,
        rates: PrincipledThinRates {
            specular_reflection: rate(bsdf, "specular_reflectance_sampling_rate")?,
            specular_transmission: rate(bsdf, "specular_transmittance_sampling_rate")?,
            diffuse_reflection: rate(bsdf, "diffuse_reflectance_sampling_rate")?,
            diffuse_transmission: rate(bsdf, "diffuse_transmittance_sampling_rate")?,
        },
    };
    Ok(Material::PrincipledThin(Arc::new(desc)))
}

/// Mitsuba's `get_flag`: whether a lobe's parameter is given other than as the number 0.
fn flag(bsdf: &Object, name: &str) -> bool {
    match bsdf.property(name).map(|p| &p.value) {
        Some(Value::Float(v)) => *v != 0.0,
        Some(Value::Integer(v)) => *v != 0,
        Some(_) => true,
        None => bsdf.child(name).is_some(),
    }
}

/// The plain number `name`, if given (Mitsuba reads `eta` and `specular` as numbers).
fn number(bsdf: &Object, name: &str) -> Result<Option<f64>, LoadError> {
    if let Some(c) = bsdf.child(name) {
        return Err(error(
            &c.object.at,
            format!("{}: {name} must be a number", bsdf.kind),
        ));
    }
    match bsdf.property(name).map(|p| (&p.value, &p.at)) {
        None => Ok(None),
        Some((Value::Float(v), _)) if v.is_finite() => Ok(Some(*v)),
        Some((Value::Integer(v), _)) => Ok(Some(*v as f64)),
        Some((_, at)) => Err(error(at, format!("{}: {name} must be a number", bsdf.kind))),
    }
}

/// A sampling rate (default 1), a number of at least 0.
fn rate(bsdf: &Object, name: &str) -> Result<f32, LoadError> {
    let r = number(bsdf, name)?.unwrap_or(1.0);
    if r >= 0.0 {
        Ok(r as f32)
    } else {
        let at = bsdf.property(name).map_or(&bsdf.at, |p| &p.at);
        Err(error(
            at,
            format!("{}: {name} {r} is not a rate of at least 0", bsdf.kind),
        ))
    }
}

/// An error for a property or nested object of `bsdf` outside `known`.
fn only(bsdf: &Object, known: &[&str]) -> Result<(), LoadError> {
    let unknown = |name: Option<&str>| name.is_none_or(|n| !known.contains(&n));
    if let Some(p) = bsdf.properties.iter().find(|p| unknown(Some(&p.name))) {
        return Err(error(
            &p.at,
            format!("{}: parameter '{}' is not read", bsdf.kind, p.name),
        ));
    }
    if let Some(c) = bsdf.children.iter().find(|c| unknown(c.name.as_deref())) {
        return Err(error(
            &c.object.at,
            format!(
                "{}: nested {} '{}' ({}) is not read",
                bsdf.kind,
                c.object.class.tag(),
                c.object.kind,
                c.name.as_deref().unwrap_or("unnamed")
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::bsdfs::tests::read;
    use super::*;
    use crate::textures::FloatTexture;

    /// Whether a number that varies over a surface is the constant `v`.
    fn is(t: &FloatTexture, v: f32) -> bool {
        t.constant() == Some(v)
    }

    #[test]
    fn defaults_and_specular_are_mitsubas() {
        let Material::Principled(d) = read(r#"<bsdf type="principled"/>"#).unwrap() else {
            panic!()
        };
        // specular 0.5: eta = 2 / (1 - sqrt(0.04)) - 1 = 1.5.
        assert!((d.eta - 1.5).abs() < 1e-6, "{}", d.eta);
        assert!(is(&d.roughness, 0.5) && is(&d.metallic, 0.0) && is(&d.clearcoat, 0.0));
        assert!(!d.transmissive());
        let xml = r#"<bsdf type="principled"><float name="eta" value="1"/><float name="spec_trans" value="0.5"/></bsdf>"#;
        let Material::Principled(d) = read(xml).unwrap() else {
            panic!()
        };
        assert_eq!(d.eta, 1.001);
        assert!(d.transmissive());
        let xml = r#"<bsdf type="principled"><float name="eta" value="1.4"/><float name="specular" value="0.3"/></bsdf>"#;
        assert!(read(xml).unwrap_err().contains("not both"));
    }

    #[test]
    fn parameters_may_be_textures_and_unknown_ones_are_errors() {
        let xml = r#"<bsdf type="principled">
            <rgb name="base_color" value="0.2, 0.8, 0.1"/>
            <texture name="metallic" type="checkerboard">
                <float name="color0" value="0.7"/><float name="color1" value="0.1"/>
            </texture>
        </bsdf>"#;
        let Material::Principled(d) = read(xml).unwrap() else {
            panic!()
        };
        assert!(d.metallic.constant().is_none() && d.textured());
        let xml = r#"<bsdf type="principled"><float name="subsurface" value="0.3"/></bsdf>"#;
        assert!(
            read(xml)
                .unwrap_err()
                .contains("parameter 'subsurface' is not read")
        );
        let xml = r#"<bsdf type="principledthin"><float name="metallic" value="0.3"/></bsdf>"#;
        assert!(
            read(xml)
                .unwrap_err()
                .contains("parameter 'metallic' is not read")
        );
        let xml = r#"<bsdf type="principledthin"><float name="diff_trans" value="1.4"/><float name="eta" value="1.33"/></bsdf>"#;
        let Material::PrincipledThin(d) = read(xml).unwrap() else {
            panic!()
        };
        assert!(is(&d.diff_trans, 1.4) && is(&d.eta, 1.33) && d.transmissive());
    }
}
