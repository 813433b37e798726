//! Mitsuba's BSDFs as prism's materials (Mitsuba's "BSDFs" plugin reference): `diffuse`,
//! `dielectric` and `roughdielectric`, `conductor` and `roughconductor`, `plastic` (not
//! `roughplastic`), and `twosided` around any of them. Spectral values enter as spectra;
//! RGB is upsampled as the scene's other colours are (`crate::load::Upsampling`).
//!
//! Mitsuba's microfacet `alpha` is prism's roughness squared (prism's roughness is
//! perceptual, alpha = roughness^2). Only the GGX distribution is read: Mitsuba's default,
//! Beckmann, has no counterpart in prism and is an error rather than a look-alike.
//! Parameters these plugins do not know, or know but prism does not follow (textures,
//! `specular_reflectance` other than 1, anisotropic alphas), are errors naming them.

use std::sync::Arc;

use super::parse::error;
use super::spectra::{Kind, spectrum};
use super::textures::{self, Context};
use super::tree::{Class, Object, SpectrumValue, Value};
use crate::LoadError;
use crate::load::Upsampler;
use crate::materials::Material;
use crate::textures::SceneSpectrum;

/// Mitsuba's named indices of refraction (`include/mitsuba/render/ior.h`, `ior_data`:
/// Hecht, *Optics*, 4th ed., at ~589 nm), looked up case-insensitively as Mitsuba does.
pub(crate) const NAMED_IORS: [(&str, f64); 23] = [
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
];

/// The material of `bsdf`.
pub(crate) fn material(bsdf: &Object, cx: &Context) -> Result<Material, LoadError> {
    let upsampler = cx.upsampler;
    match bsdf.kind.as_str() {
        "diffuse" => {
            only(bsdf, &["reflectance"])?;
            Ok(Material::Diffuse {
                reflectance: textures::spectrum(bsdf, "reflectance", Kind::Albedo, 0.5, cx)?,
            })
        }
        // prism's surfaces reflect on both sides, so `twosided` is its one BSDF.
        "twosided" => {
            let mut inner = bsdf
                .children
                .iter()
                .filter(|c| c.object.class == Class::Bsdf);
            match (inner.next(), inner.next()) {
                (Some(one), None) => material(&one.object, cx),
                (Some(_), Some(_)) => Err(error(
                    &bsdf.at,
                    "twosided with a different BSDF on each side is not read yet",
                )),
                (None, _) => Err(error(&bsdf.at, "twosided needs a nested BSDF")),
            }
        }
        "dielectric" | "roughdielectric" => {
            let rough = bsdf.kind == "roughdielectric";
            let mut known = vec![
                "int_ior",
                "ext_ior",
                "specular_reflectance",
                "specular_transmittance",
            ];
            if rough {
                known.extend(ROUGH);
            }
            only(bsdf, &known)?;
            unit(bsdf, "specular_reflectance")?;
            unit(bsdf, "specular_transmittance")?;
            let ior = ior(bsdf, "int_ior", "bk7")? / ior(bsdf, "ext_ior", "air")?;
            Ok(Material::Dielectric {
                ior: SceneSpectrum::Constant(ior),
                roughness: if rough { roughness(bsdf)? } else { 0.0 },
                absorption: None,
            })
        }
        "conductor" | "roughconductor" => {
            let rough = bsdf.kind == "roughconductor";
            let mut known = vec!["material", "eta", "k", "specular_reflectance"];
            if rough {
                known.extend(ROUGH);
            }
            only(bsdf, &known)?;
            unit(bsdf, "specular_reflectance")?;
            let (eta, k) = conductor_index(bsdf, upsampler)?;
            Ok(Material::Conductor {
                eta,
                k,
                roughness: if rough { roughness(bsdf)? } else { 0.0 },
            })
        }
        // prism's rough coating keeps the light Mitsuba's loses (its inner reflectance by
        // reciprocity, plastic.rs; Mitsuba's `roughplastic` loses 9% in a white furnace
        // at alpha 0.1, mitsuba3 issue #1155): the box with roughplastic cubes renders
        // 3.5% brighter than Mitsuba's, so it is refused rather than read as something
        // else.
        "roughplastic" => Err(error(
            &bsdf.at,
            "roughplastic is not read yet (prism's rough plastic keeps the energy \
             Mitsuba's loses and renders brighter; plastic is read)",
        )),
        "plastic" => {
            let rough = false;
            let mut known = vec![
                "diffuse_reflectance",
                "int_ior",
                "ext_ior",
                "nonlinear",
                "specular_reflectance",
            ];
            if rough {
                known.extend(ROUGH);
            }
            only(bsdf, &known)?;
            unit(bsdf, "specular_reflectance")?;
            let eta = ior(bsdf, "int_ior", "polypropylene")? / ior(bsdf, "ext_ior", "air")?;
            if !(eta > 1.0 && eta <= 4.0) {
                return Err(error(
                    &bsdf.at,
                    format!(
                        "{}: int_ior / ext_ior = {eta} is not in (1, 4] (prism's plastic \
                         coating is denser than the outside)",
                        bsdf.kind
                    ),
                ));
            }
            let nonlinear = match bsdf.property("nonlinear").map(|p| (&p.value, &p.at)) {
                None => false,
                Some((Value::Boolean(b), _)) => *b,
                Some((_, at)) => return Err(error(at, "nonlinear must be a boolean")),
            };
            let roughness = if rough { roughness(bsdf)? } else { 0.0 };
            Ok(Material::Plastic {
                reflectance: textures::spectrum(
                    bsdf,
                    "diffuse_reflectance",
                    Kind::Albedo,
                    0.5,
                    cx,
                )?,
                nonlinear,
                coating: Arc::new(crate::bsdf::PlasticCoating::new(
                    eta as f32,
                    roughness * roughness,
                )),
            })
        }
        "principled" => super::principled::principled(bsdf, cx),
        "principledthin" => super::principled::principled_thin(bsdf, cx),
        other => Err(error(
            &bsdf.at,
            format!(
                "bsdf '{other}' is not read yet (diffuse, dielectric, roughdielectric, \
                 conductor, roughconductor, plastic and twosided are)"
            ),
        )),
    }
}

/// The parameters the rough plugins add.
const ROUGH: [&str; 5] = [
    "distribution",
    "alpha",
    "alpha_u",
    "alpha_v",
    "sample_visible",
];

/// An error for a property or nested object of `bsdf` outside `known`.
fn only(bsdf: &Object, known: &[&str]) -> Result<(), LoadError> {
    for p in &bsdf.properties {
        if !known.contains(&p.name.as_str()) {
            return Err(error(
                &p.at,
                format!("{}: parameter '{}' is not read", bsdf.kind, p.name),
            ));
        }
    }
    for c in &bsdf.children {
        match c.name.as_deref() {
            Some(name) if known.contains(&name) => {}
            name => {
                return Err(error(
                    &c.object.at,
                    format!(
                        "{}: nested {} '{}' ({}) is not read",
                        bsdf.kind,
                        c.object.class.tag(),
                        c.object.kind,
                        name.unwrap_or("unnamed")
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// An error unless `name` is absent or 1 (Mitsuba's physically meaningful default).
fn unit(bsdf: &Object, name: &str) -> Result<(), LoadError> {
    let one = |v: f64| v == 1.0;
    let at = match bsdf.property(name) {
        None => match bsdf.child(name) {
            None => return Ok(()),
            Some(c) => &c.object.at,
        },
        Some(p) => match &p.value {
            Value::Float(v) | Value::Spectrum(SpectrumValue::Constant(v)) if one(*v) => {
                return Ok(());
            }
            Value::Integer(1) => return Ok(()),
            Value::Rgb(c) if c.iter().all(|&v| one(v)) => return Ok(()),
            _ => &p.at,
        },
    };
    Err(error(
        at,
        format!("{}: {name} other than 1 is not read yet", bsdf.kind),
    ))
}

/// Mitsuba's index `name` of `bsdf`: a number or one of [`NAMED_IORS`], `default` (a
/// name) where absent.
fn ior(bsdf: &Object, name: &str, default: &str) -> Result<f64, LoadError> {
    let (value, at) = match bsdf.property(name) {
        None => return Ok(named_ior(default).expect("a default is a named index")),
        Some(p) => (&p.value, &p.at),
    };
    let n = match value {
        Value::Float(v) => *v,
        Value::Integer(v) => *v as f64,
        Value::String(s) => named_ior(s).ok_or_else(|| {
            let names: Vec<&str> = NAMED_IORS.iter().map(|(n, _)| *n).collect();
            error(
                at,
                format!(
                    "{name}: no index named '{s}' (Mitsuba's are {})",
                    names.join(", ")
                ),
            )
        })?,
        _ => return Err(error(at, format!("{name} must be a number or a name"))),
    };
    if n.is_finite() && n >= 1.0 {
        Ok(n)
    } else {
        Err(error(
            at,
            format!("{name} {n} is not an index of at least 1"),
        ))
    }
}

/// The index Mitsuba names `name` (case-insensitively).
pub(crate) fn named_ior(name: &str) -> Option<f64> {
    let lower = name.to_ascii_lowercase();
    NAMED_IORS
        .iter()
        .find(|(n, _)| *n == lower)
        .map(|(_, v)| *v)
}

/// eta and k of a conductor: a named `material` (Mitsuba's data, `conductors.rs`),
/// Mitsuba's default "none" (eta 0, k 1: a mirror reflecting everything), or `eta` and
/// `k` given.
fn conductor_index(
    bsdf: &Object,
    upsampler: &Upsampler,
) -> Result<(SceneSpectrum, SceneSpectrum), LoadError> {
    let material = match bsdf.property("material") {
        None => "none",
        Some(p) => match &p.value {
            Value::String(s) => s.as_str(),
            _ => return Err(error(&p.at, "material must be a name")),
        },
    };
    let given = bsdf.property("eta").is_some() || bsdf.property("k").is_some();
    if material == "none" {
        for name in ["eta", "k"] {
            // Mitsuba's eta and k are unbounded: an RGB colour would need the unbounded
            // upsampling, which prism's Mitsuba reader does not do yet.
            if let Some(p) = bsdf.property(name)
                && matches!(p.value, Value::Rgb(_))
            {
                return Err(error(
                    &p.at,
                    format!("{}: {name} as an RGB colour is not read yet", bsdf.kind),
                ));
            }
        }
        let eta = spectrum(bsdf, "eta", Kind::Albedo, 0.0, upsampler)?;
        let k = spectrum(bsdf, "k", Kind::Albedo, 1.0, upsampler)?;
        return Ok((eta, k));
    }
    if given {
        return Err(error(
            &bsdf.at,
            format!("{}: give either eta and k or material, not both", bsdf.kind),
        ));
    }
    super::conductors::preset(material).ok_or_else(|| {
        error(
            &bsdf.at,
            format!(
                "{}: no material preset '{material}' (Mitsuba's are {} and 'none'; or \
                 give eta and k)",
                bsdf.kind,
                super::conductors::names().join(", ")
            ),
        )
    })
}

/// prism's roughness, sqrt(alpha), of a rough plugin: GGX only, isotropic.
fn roughness(bsdf: &Object) -> Result<f32, LoadError> {
    let kind = &bsdf.kind;
    match bsdf.property("distribution").map(|p| (&p.value, &p.at)) {
        Some((Value::String(d), _)) if d == "ggx" => {}
        Some((Value::String(d), at)) if d != "beckmann" => {
            return Err(error(at, format!("{kind}: unknown distribution '{d}'")));
        }
        Some((Value::String(_), _)) | None => {
            let at = bsdf.property("distribution").map_or(&bsdf.at, |p| &p.at);
            return Err(error(
                at,
                format!(
                    "{kind} with the beckmann distribution is not read yet (distribution ggx is)"
                ),
            ));
        }
        Some((_, at)) => return Err(error(at, "distribution must be a name")),
    }
    if let Some(s) = bsdf.property("sample_visible")
        && !matches!(s.value, Value::Boolean(_))
    {
        return Err(error(&s.at, "sample_visible must be a boolean"));
    }
    let number = |name: &str| -> Result<Option<f64>, LoadError> {
        if let Some(c) = bsdf.child(name) {
            return Err(error(
                &c.object.at,
                format!("{kind}: {name} as a texture is not read yet"),
            ));
        }
        match bsdf.property(name).map(|p| (&p.value, &p.at)) {
            None => Ok(None),
            Some((Value::Float(v), at)) => check_alpha(*v, name, at).map(Some),
            Some((Value::Integer(v), at)) => check_alpha(*v as f64, name, at).map(Some),
            Some((_, at)) => Err(error(at, format!("{name} must be a number"))),
        }
    };
    let alpha = match (number("alpha")?, number("alpha_u")?, number("alpha_v")?) {
        (Some(a), None, None) => a,
        (None, None, None) => 0.1,
        (None, Some(u), Some(v)) if u == v => u,
        (None, Some(_), Some(_)) => {
            return Err(error(
                &bsdf.at,
                format!("{kind} with alpha_u != alpha_v (anisotropic) is not read yet"),
            ));
        }
        _ => {
            return Err(error(
                &bsdf.at,
                format!("{kind}: give alpha, or alpha_u and alpha_v both"),
            ));
        }
    };
    Ok(alpha.sqrt() as f32)
}

fn check_alpha(v: f64, name: &str, at: &super::tree::Location) -> Result<f64, LoadError> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(error(
            at,
            format!("{name} {v} is not a roughness of at least 0"),
        ))
    }
}

/// What an object shared by reference is keyed by: the same `Arc` is the same object.
pub(crate) fn key(object: &Arc<Object>) -> usize {
    Arc::as_ptr(object) as usize
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::LoadOptions;
    use crate::load::mitsuba::{ParseOptions, parse};

    /// The material of the one `<bsdf>` in `xml`, or its error's text.
    fn read(xml: &str) -> Result<Material, String> {
        let none = |name: &str| -> std::io::Result<Vec<u8>> {
            Err(std::io::Error::other(format!("no file {name}")))
        };
        let options = ParseOptions {
            defines: &[],
            resolve: &none,
        };
        let text = format!("<scene version=\"3.0.0\">\n{xml}\n</scene>\n");
        let parsed = parse(&text, "t.xml", &options).unwrap();
        let load = LoadOptions::default();
        let upsampler = Upsampler::new(load.upsampling, load.table.clone()).unwrap();
        let bsdf = &parsed.scene.children[0].object;
        let cx = Context {
            upsampler: &upsampler,
            files: crate::load::mitsuba::files::Files {
                resolve: &none,
                search: &[],
            },
        };
        material(bsdf, &cx).map_err(|e| e.to_string())
    }

    fn constant(s: &SceneSpectrum) -> f64 {
        match s {
            SceneSpectrum::Constant(v) => *v,
            other => panic!("not a constant: {other:?}"),
        }
    }

    #[test]
    fn dielectric_indices_are_mitsubas_named_or_numbers_inside_over_outside() {
        let ior = |xml: &str| match read(xml).unwrap() {
            Material::Dielectric { ior, roughness, .. } => (constant(&ior), roughness),
            other => panic!("{other:?}"),
        };
        // Mitsuba's defaults: bk7 in air.
        let (n, r) = ior(r#"<bsdf type="dielectric"/>"#);
        assert!((n - 1.5046 / 1.000277).abs() < 1e-12 && r == 0.0);
        let (n, _) = ior(
            r#"<bsdf type="dielectric"><string name="int_ior" value="Diamond"/><string name="ext_ior" value="water"/></bsdf>"#,
        );
        assert!((n - 2.419 / 1.3330).abs() < 1e-12);
        let (n, _) = ior(
            r#"<bsdf type="dielectric"><float name="int_ior" value="1.7"/><float name="ext_ior" value="1"/></bsdf>"#,
        );
        assert!((n - 1.7).abs() < 1e-12);
        assert_eq!(named_ior("fused quartz"), Some(1.458));
        assert_eq!(named_ior("PET"), Some(1.575));
        assert_eq!(named_ior("vacuum"), Some(1.0));
        let e = read(r#"<bsdf type="dielectric"><string name="int_ior" value="glass"/></bsdf>"#)
            .unwrap_err();
        assert!(
            e.contains("no index named 'glass'") && e.contains("bk7"),
            "{e}"
        );
        let e = read(
            r#"<bsdf type="dielectric"><rgb name="specular_transmittance" value="0.5"/></bsdf>"#,
        )
        .unwrap_err();
        assert!(e.contains("not read yet"), "{e}");
    }

    #[test]
    fn rough_alpha_is_roughness_squared_and_beckmann_is_an_error() {
        let xml = r#"<bsdf type="roughdielectric"><string name="distribution" value="ggx"/><float name="alpha" value="0.25"/></bsdf>"#;
        match read(xml).unwrap() {
            Material::Dielectric { roughness, .. } => assert_eq!(roughness, 0.5),
            other => panic!("{other:?}"),
        }
        // alpha's default, 0.1.
        let xml = r#"<bsdf type="roughconductor"><string name="distribution" value="ggx"/></bsdf>"#;
        match read(xml).unwrap() {
            Material::Conductor { roughness, .. } => {
                assert!((roughness - 0.1f32.sqrt()).abs() < 1e-7)
            }
            other => panic!("{other:?}"),
        }
        // Beckmann, Mitsuba's default distribution, is not taken for GGX.
        for xml in [
            r#"<bsdf type="roughconductor"/>"#,
            r#"<bsdf type="roughconductor"><string name="distribution" value="beckmann"/></bsdf>"#,
        ] {
            let e = read(xml).unwrap_err();
            assert!(
                e.contains(
                    "roughconductor with the beckmann distribution is not read yet (distribution ggx is)"
                ),
                "{e}"
            );
        }
        let e = read(r#"<bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.2"/></bsdf>"#).unwrap_err();
        assert!(e.contains("alpha_u != alpha_v"), "{e}");
    }

    #[test]
    fn conductors_are_named_none_or_given() {
        match read(r#"<bsdf type="conductor"/>"#).unwrap() {
            Material::Conductor { eta, k, roughness } => {
                assert_eq!((constant(&eta), constant(&k), roughness), (0.0, 1.0, 0.0));
                // eta 0, k 1 reflects everything, as Mitsuba's "none" mirror.
                for c in [1.0, 0.5, 0.1] {
                    let f = crate::bsdf::fresnel_conductor(c, 0.0, 1.0);
                    assert!((f - 1.0).abs() < 1e-6, "{c}: {f}");
                }
            }
            other => panic!("{other:?}"),
        }
        match read(r#"<bsdf type="conductor"><string name="material" value="Au"/></bsdf>"#).unwrap()
        {
            Material::Conductor { eta, k, .. } => {
                assert!(matches!(eta, SceneSpectrum::Table(_)));
                assert!(matches!(k, SceneSpectrum::Table(_)));
            }
            other => panic!("{other:?}"),
        }
        // Every preset Mitsuba ships, a-C and Cr among them; names are Mitsuba's files'.
        for name in ["Cr", "a-C", "Ni_palik"] {
            let xml = format!(
                r#"<bsdf type="roughconductor"><string name="distribution" value="ggx"/><string name="material" value="{name}"/></bsdf>"#
            );
            assert!(
                matches!(read(&xml), Ok(Material::Conductor { .. })),
                "{name}"
            );
        }
        let e = read(r#"<bsdf type="conductor"><string name="material" value="gold"/></bsdf>"#)
            .unwrap_err();
        assert!(
            e.contains("no material preset 'gold'") && e.contains("a-C"),
            "{e}"
        );
        let e = read(r#"<bsdf type="conductor"><rgb name="eta" value="0.2, 0.9, 1.1"/><rgb name="k" value="3, 2, 2"/></bsdf>"#).unwrap_err();
        assert!(e.contains("RGB colour is not read yet"), "{e}");
        let e = read(r#"<bsdf type="conductor"><float name="roughness" value="0.2"/></bsdf>"#)
            .unwrap_err();
        assert!(e.contains("parameter 'roughness' is not read"), "{e}");
    }

    #[test]
    fn plastic_defaults_are_polypropylene_in_air() {
        match read(r#"<bsdf type="plastic"/>"#).unwrap() {
            Material::Plastic {
                reflectance,
                nonlinear,
                coating,
            } => {
                assert_eq!(constant(&reflectance), 0.5);
                assert!(!nonlinear);
                assert!((coating.eta() - (1.49 / 1.000277) as f32).abs() < 1e-6);
                assert!(coating.distribution().effectively_smooth());
            }
            other => panic!("{other:?}"),
        }
        let xml = r#"<bsdf type="plastic"><string name="int_ior" value="bk7"/><boolean name="nonlinear" value="true"/></bsdf>"#;
        match read(xml).unwrap() {
            Material::Plastic {
                nonlinear, coating, ..
            } => {
                assert!(nonlinear);
                assert!((coating.eta() - (1.5046 / 1.000277) as f32).abs() < 1e-6);
            }
            other => panic!("{other:?}"),
        }
        let xml = r#"<bsdf type="roughplastic"><string name="distribution" value="ggx"/></bsdf>"#;
        assert!(
            read(xml)
                .unwrap_err()
                .contains("roughplastic is not read yet")
        );
    }
}
