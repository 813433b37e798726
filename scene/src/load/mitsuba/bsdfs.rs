//! Mitsuba's BSDFs as prism's materials (Mitsuba's "BSDFs" plugin reference): `diffuse`,
//! `dielectric`, `roughdielectric` and `thindielectric`, `conductor` and `roughconductor`,
//! `plastic` and `roughplastic`, `blendbsdf` of two of them, and `twosided` around any
//! of them. Spectral values enter
//! as spectra; RGB is upsampled as the scene's other colours are
//! (`crate::load::Upsampling`).
//!
//! Mitsuba's microfacet `alpha` is prism's roughness squared (prism's roughness is
//! perceptual, alpha = roughness^2). Isotropic GGX is prism's own rough conductor and
//! dielectric; Mitsuba's default distribution, Beckmann, is its own model
//! ([`crate::bsdf::Beckmann`], [`Material::MicrofacetConductor`] and
//! [`Material::MicrofacetDielectric`]), and `roughplastic` is Mitsuba's model with its
//! energy loss ([`Material::RoughPlastic`]), not prism's `Plastic`.
//! Parameters these plugins do not know, or know but prism does not follow (textures,
//! `specular_reflectance` other than 1, anisotropic alphas), are errors naming them.

use std::sync::Arc;

use super::parse::error;
use super::spectra::{Kind, spectrum};
use super::textures::{self, Context};
use super::tree::{Class, Object, SpectrumValue, Value};
use crate::LoadError;
use crate::bsdf::{Beckmann, Distribution, Ggx};
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
        // Mitsuba's mix of its two nested BSDFs, the second weighed by `weight`.
        "blendbsdf" => {
            for p in &bsdf.properties {
                if p.name != "weight" {
                    return Err(error(
                        &p.at,
                        format!("blendbsdf: parameter '{}' is not read", p.name),
                    ));
                }
            }
            if bsdf.property("weight").is_none() && bsdf.child("weight").is_none() {
                return Err(error(&bsdf.at, "blendbsdf needs a weight"));
            }
            let weight = textures::float(bsdf, "weight", 0.5, cx)?;
            let nested: Vec<&Object> = bsdf.children_of(Class::Bsdf).map(|c| &*c.object).collect();
            let [first, second] = nested.as_slice() else {
                return Err(error(&bsdf.at, "blendbsdf takes two nested BSDFs"));
            };
            Ok(Material::Blend {
                weight: Arc::new(weight),
                first: Box::new(material(first, cx)?),
                second: Box::new(material(second, cx)?),
            })
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
            let ior = SceneSpectrum::Constant(ior);
            if !rough {
                return Ok(Material::Dielectric {
                    ior,
                    roughness: 0.0,
                    absorption: None,
                });
            }
            let model = self::rough(bsdf)?;
            isotropic(bsdf, &model)?;
            Ok(match model.isotropic_ggx() {
                Some(roughness) => Material::Dielectric {
                    ior,
                    roughness,
                    absorption: None,
                },
                None => Material::MicrofacetDielectric {
                    ior,
                    distribution: model.distribution(),
                },
            })
        }
        // Mitsuba's thin sheet: reflectance summed over the slab's inner reflections,
        // R' = R + T^2 R / (1 - R^2), and the rest straight through
        // (`thindielectric.cpp`), which is prism's smooth thin sheet.
        "thindielectric" => {
            only(
                bsdf,
                &[
                    "int_ior",
                    "ext_ior",
                    "specular_reflectance",
                    "specular_transmittance",
                ],
            )?;
            unit(bsdf, "specular_reflectance")?;
            unit(bsdf, "specular_transmittance")?;
            let ior = ior(bsdf, "int_ior", "bk7")? / ior(bsdf, "ext_ior", "air")?;
            Ok(Material::ThinDielectric {
                ior: SceneSpectrum::Constant(ior),
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
            if !rough {
                return Ok(Material::Conductor {
                    eta,
                    k,
                    roughness: 0.0,
                });
            }
            let model = self::rough(bsdf)?;
            isotropic(bsdf, &model)?;
            Ok(match model.isotropic_ggx() {
                Some(roughness) => Material::Conductor { eta, k, roughness },
                None => Material::MicrofacetConductor {
                    eta,
                    k,
                    distribution: model.distribution(),
                },
            })
        }
        // Mitsuba's own model, energy loss and all ([`crate::bsdf::RoughPlastic`]);
        // prism's `Plastic` keeps that light and is what `plastic` reads.
        "roughplastic" => {
            let mut known = vec![
                "diffuse_reflectance",
                "int_ior",
                "ext_ior",
                "nonlinear",
                "specular_reflectance",
            ];
            known.extend(ROUGH);
            only(bsdf, &known)?;
            unit(bsdf, "specular_reflectance")?;
            let eta = ior(bsdf, "int_ior", "polypropylene")? / ior(bsdf, "ext_ior", "air")?;
            if eta == 1.0 {
                return Err(error(
                    &bsdf.at,
                    "roughplastic: the interior and exterior indices must differ",
                ));
            }
            let model = self::rough(bsdf)?;
            if model.alpha_u != model.alpha_v {
                // Mitsuba refuses it too.
                return Err(error(
                    &bsdf.at,
                    "roughplastic does not support anisotropic roughness (nor does Mitsuba)",
                ));
            }
            Ok(Material::RoughPlastic {
                reflectance: textures::spectrum(
                    bsdf,
                    "diffuse_reflectance",
                    Kind::Albedo,
                    0.5,
                    cx,
                )?,
                nonlinear: nonlinear(bsdf)?,
                coating: Arc::new(crate::bsdf::RoughPlasticCoating::new(
                    model.distribution(),
                    eta as f32,
                )),
            })
        }
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
            let nonlinear = nonlinear(bsdf)?;
            let roughness = 0.0f32;
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
                 thindielectric, conductor, roughconductor, plastic, roughplastic, \
                 blendbsdf and twosided are)"
            ),
        )),
    }
}

/// A plastic's `nonlinear` (default false).
fn nonlinear(bsdf: &Object) -> Result<bool, LoadError> {
    match bsdf.property("nonlinear").map(|p| (&p.value, &p.at)) {
        None => Ok(false),
        Some((Value::Boolean(b), _)) => Ok(*b),
        Some((_, at)) => Err(error(at, "nonlinear must be a boolean")),
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

/// A rough plugin's microfacet model as Mitsuba reads it (`MicrofacetDistribution`'s
/// properties constructor): `distribution` beckmann (the default) or ggx, and `alpha`
/// (default 0.1) or `alpha_u` and `alpha_v` both.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rough {
    /// Whether the distribution is GGX (else Beckmann).
    pub ggx: bool,
    /// Roughness along the tangent (dp/du).
    pub alpha_u: f32,
    /// Roughness along the bitangent.
    pub alpha_v: f32,
}

impl Rough {
    /// Whether prism's own isotropic GGX materials (perceptual roughness sqrt(alpha))
    /// say it.
    fn isotropic_ggx(&self) -> Option<f32> {
        (self.ggx && self.alpha_u == self.alpha_v).then(|| self.alpha_u.sqrt())
    }

    /// The distribution.
    pub(crate) fn distribution(&self) -> Distribution {
        if self.ggx {
            Distribution::Ggx(Ggx::new(self.alpha_u, self.alpha_v))
        } else {
            Distribution::Beckmann(Beckmann::new(self.alpha_u, self.alpha_v))
        }
    }
}

/// The microfacet model of a rough plugin.
pub(crate) fn rough(bsdf: &Object) -> Result<Rough, LoadError> {
    let kind = &bsdf.kind;
    let ggx = match bsdf.property("distribution").map(|p| (&p.value, &p.at)) {
        None => false,
        Some((Value::String(d), at)) => match d.to_ascii_lowercase().as_str() {
            "ggx" => true,
            "beckmann" => false,
            _ => return Err(error(at, format!("{kind}: unknown distribution '{d}'"))),
        },
        Some((_, at)) => return Err(error(at, "distribution must be a name")),
    };
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
    let (alpha_u, alpha_v) = match (number("alpha")?, number("alpha_u")?, number("alpha_v")?) {
        (Some(a), None, None) => (a, a),
        (None, None, None) => (0.1, 0.1),
        (None, Some(u), Some(v)) => (u, v),
        _ => {
            return Err(error(
                &bsdf.at,
                format!("{kind}: give alpha, or alpha_u and alpha_v both"),
            ));
        }
    };
    Ok(Rough {
        ggx,
        alpha_u: alpha_u as f32,
        alpha_v: alpha_v as f32,
    })
}

/// An error for anisotropic roughness: Mitsuba orients alpha_u along its shading frame's
/// tangent, which on meshes is its per-vertex tangents interpolated across the triangle
/// (`mesh.cpp`, `finalize_surface_interaction`) and on spheres dp/du; prism's frame at a
/// Mitsuba shape has neither, so the lobe would turn with an arbitrary basis.
fn isotropic(bsdf: &Object, rough: &Rough) -> Result<(), LoadError> {
    if rough.alpha_u == rough.alpha_v {
        Ok(())
    } else {
        Err(error(
            &bsdf.at,
            format!(
                "{} with alpha_u != alpha_v (anisotropic) is not read yet (prism's shading \
                 frame does not follow Mitsuba's surface tangents)",
                bsdf.kind
            ),
        ))
    }
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
pub(super) mod tests {
    use super::*;
    use crate::load::LoadOptions;
    use crate::load::mitsuba::{ParseOptions, parse};

    /// The material of the one `<bsdf>` in `xml`, or its error's text.
    pub(in crate::load::mitsuba) fn read(xml: &str) -> Result<Material, String> {
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
    fn rough_alpha_is_roughness_squared_and_beckmann_its_own_model() {
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
        // Beckmann, Mitsuba's default distribution, is its own model.
        for xml in [
            r#"<bsdf type="roughconductor"/>"#,
            r#"<bsdf type="roughconductor"><string name="distribution" value="Beckmann"/></bsdf>"#,
        ] {
            match read(xml).unwrap() {
                Material::MicrofacetConductor { distribution, .. } => assert_eq!(
                    distribution,
                    Distribution::Beckmann(Beckmann::new(0.1, 0.1))
                ),
                other => panic!("{other:?}"),
            }
        }
        match read(r#"<bsdf type="roughdielectric"><float name="alpha" value="0.3"/></bsdf>"#)
            .unwrap()
        {
            Material::MicrofacetDielectric { distribution, .. } => assert_eq!(
                distribution,
                Distribution::Beckmann(Beckmann::new(0.3, 0.3))
            ),
            other => panic!("{other:?}"),
        }
        let e = read(
            r#"<bsdf type="roughconductor"><string name="distribution" value="phong"/></bsdf>"#,
        )
        .unwrap_err();
        assert!(e.contains("unknown distribution 'phong'"), "{e}");
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
        match read(r#"<bsdf type="roughplastic"><boolean name="nonlinear" value="true"/></bsdf>"#)
            .unwrap()
        {
            Material::RoughPlastic {
                nonlinear, coating, ..
            } => {
                assert!(nonlinear);
                assert_eq!(
                    coating.distribution(),
                    Distribution::Beckmann(Beckmann::new(0.1, 0.1))
                );
                assert!((coating.eta() - (1.49 / 1.000277) as f32).abs() < 1e-6);
            }
            other => panic!("{other:?}"),
        }
        let e = read(r#"<bsdf type="roughplastic"><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.2"/></bsdf>"#)
            .unwrap_err();
        assert!(e.contains("anisotropic"), "{e}");
    }

    #[test]
    fn blendbsdf_mixes_two_by_a_weight() {
        let xml = r#"<bsdf type="blendbsdf"><float name="weight" value="0.3"/><bsdf type="diffuse"/><bsdf type="conductor"/></bsdf>"#;
        match read(xml).unwrap() {
            Material::Blend {
                weight,
                first,
                second,
            } => {
                assert_eq!(weight.constant(), Some(0.3));
                assert!(matches!(*first, Material::Diffuse { .. }));
                assert!(matches!(*second, Material::Conductor { .. }));
            }
            other => panic!("{other:?}"),
        }
        let e = read(r#"<bsdf type="blendbsdf"><float name="weight" value="0.3"/><bsdf type="diffuse"/></bsdf>"#)
            .unwrap_err();
        assert!(e.contains("two nested BSDFs"), "{e}");
        let e =
            read(r#"<bsdf type="blendbsdf"><bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>"#)
                .unwrap_err();
        assert!(e.contains("needs a weight"), "{e}");
    }

    #[test]
    fn thindielectric_is_the_smooth_thin_sheet() {
        match read(r#"<bsdf type="thindielectric"><float name="int_ior" value="1.5"/><float name="ext_ior" value="1"/></bsdf>"#).unwrap() {
            Material::ThinDielectric { ior } => assert_eq!(constant(&ior), 1.5),
            other => panic!("{other:?}"),
        }
        let e = read(r#"<bsdf type="thindielectric"><rgb name="specular_transmittance" value="0.5"/></bsdf>"#)
            .unwrap_err();
        assert!(e.contains("not read yet"), "{e}");
    }
}
