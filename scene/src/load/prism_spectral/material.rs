//! `PRISM_spectral` on materials: a spectral surface replacing glTF's, and spectral
//! emission.

use std::sync::Arc;

use prism_sampling::wavelength::{ReradiationSampler, WavelengthRange};
use serde_json::{Map, Value};

use super::value::{Context, Role, ior, metal, number, only_keys, schedule, spectrum};
use crate::bsdf::fluorescence_matrix;
use crate::materials::Material;
use crate::textures::SceneSpectrum;

/// The material types a description may give.
pub const MATERIAL_TYPES: &str =
    "diffuse, plastic, dielectric, conductor, fluorescent, polarizer, retarder, interface";

/// A plastic coating's index when the description gives none: polypropylene's, as in
/// Mitsuba.
pub const PLASTIC_IOR: f64 = 1.49;

/// The default range and bin width of fluorescence matrices: from the near UV that
/// blacklights emit to the end of the visible.
pub const FLUORESCENCE_RANGE_NM: (f32, f32) = (300.0, 830.0);
const FLUORESCENCE_BIN_NM: f32 = 2.0;

/// A material's `PRISM_spectral` description.
#[derive(Debug, Clone, Default)]
pub struct SpectralMaterial {
    /// The surface replacing glTF's (None: keep glTF's surface).
    pub surface: Option<Material>,
    /// Emitted radiance, W m^-2 sr^-1 nm^-1, replacing glTF's emissive colour.
    pub emission: Option<SceneSpectrum>,
    /// A measured spectrum replacing `KHR_materials_sheen`'s sheen colour.
    pub sheen_color: Option<SceneSpectrum>,
    /// A measured spectrum replacing `KHR_materials_specular`'s specular colour.
    pub specular_color: Option<SceneSpectrum>,
    /// A spectral index (a named glass, a table, Cauchy or Sellmeier coefficients)
    /// replacing `KHR_materials_iridescence`'s film index.
    pub film_ior: Option<SceneSpectrum>,
    /// When its emission shines (None: always).
    pub on: Option<crate::world::Schedule>,
    /// A fluorescent material's decay law, making it phosphorescent (None: its
    /// re-emission is instantaneous).
    pub decay: Option<prism_sampling::decay::Decay>,
    /// The participating medium inside the material's closed surface (an interface, a
    /// dielectric, or glTF glass), if any.
    pub medium: Option<crate::medium::Medium>,
}

/// Parses a material's description.
pub(crate) fn material(value: &Value, cx: &Context) -> Result<SpectralMaterial, String> {
    let mut map = value
        .as_object()
        .ok_or("PRISM_spectral on a material must be an object")?
        .clone();
    // Time, which any type may have: a schedule for its emission, a lifetime for a
    // fluorescent one.
    let on = map
        .remove("on")
        .map(|v| schedule(&v).map_err(|e| format!("on: {e}")))
        .transpose()?;
    let decay = decay(map.remove("lifetime"), map.remove("lifetimes"))?;
    let medium = map
        .remove("medium")
        .map(|v| super::medium::medium(&v, cx).map_err(|e| format!("medium: {e}")))
        .transpose()?;
    let interface = map.get("type").and_then(Value::as_str) == Some("interface");
    if interface && medium.is_none() {
        return Err("an interface needs 'medium' (what is inside it)".into());
    }
    if let Some(kind) = map.get("type").and_then(Value::as_str)
        && medium.is_some()
        && !matches!(kind, "interface" | "dielectric")
    {
        return Err(format!(
            "a medium needs a boundary light crosses: type {kind} cannot hold one (use \"interface\" or \"dielectric\")"
        ));
    }
    let mut description = surface_and_emission(&map, cx)?;
    description.medium = medium;
    if on.is_some() && description.emission.is_none() {
        return Err("'on' schedules an emission, and the material has none".into());
    }
    if decay.is_some() && !matches!(description.surface, Some(Material::Fluorescent { .. })) {
        return Err(
            "a lifetime needs \"type\": \"fluorescent\" (what it absorbs and re-emits)".into(),
        );
    }
    description.on = on;
    description.decay = decay;
    Ok(description)
}

/// The material's surface and emission (every key but the time ones).
fn surface_and_emission(
    map: &Map<String, Value>,
    cx: &Context,
) -> Result<SpectralMaterial, String> {
    let emission = map
        .get("emission")
        .map(|e| spectrum(e, Role::Emission, cx).map_err(|e| format!("emission: {e}")))
        .transpose()?;
    let Some(kind) = map.get("type") else {
        only_keys(
            map,
            &["emission", "sheen_color", "specular_color", "film_ior"],
        )?;
        let optional = |key: &str, role: Role| {
            map.get(key)
                .map(|v| spectrum(v, role, cx).map_err(|e| format!("{key}: {e}")))
                .transpose()
        };
        return Ok(SpectralMaterial {
            surface: None,
            emission,
            sheen_color: optional("sheen_color", Role::Fraction)?,
            specular_color: optional("specular_color", Role::Plain)?,
            film_ior: map
                .get("film_ior")
                .map(|v| ior(v, cx).map_err(|e| format!("film_ior: {e}")))
                .transpose()?,
            ..SpectralMaterial::default()
        });
    };
    let field = |key: &str, role: Role| -> Result<SceneSpectrum, String> {
        let v = map.get(key).ok_or_else(|| format!("needs '{key}'"))?;
        spectrum(v, role, cx).map_err(|e| format!("{key}: {e}"))
    };
    let roughness = || -> Result<f32, String> {
        match map.get("roughness") {
            None => Ok(0.0),
            Some(r) => {
                let r = number(r, "roughness")?;
                if (0.0..=1.0).contains(&r) {
                    Ok(r as f32)
                } else {
                    Err(format!("roughness {r} is outside [0, 1]"))
                }
            }
        }
    };
    let surface = match kind.as_str() {
        Some("diffuse") => {
            only_keys(map, &["type", "emission", "reflectance"])?;
            Material::Diffuse {
                reflectance: field("reflectance", Role::Fraction)?,
            }
        }
        Some("plastic") => {
            only_keys(
                map,
                &[
                    "type",
                    "emission",
                    "reflectance",
                    "ior",
                    "roughness",
                    "nonlinear",
                ],
            )?;
            let eta = match map.get("ior") {
                None => PLASTIC_IOR,
                Some(n) => {
                    let n = number(n, "ior").map_err(|e| {
                        format!("{e} (a plastic's coating has one index for every wavelength)")
                    })?;
                    if !(n > 1.0 && n <= 4.0) {
                        return Err(format!("ior {n} is not in (1, 4]"));
                    }
                    n
                }
            };
            let nonlinear = match map.get("nonlinear") {
                None => false,
                Some(v) => v.as_bool().ok_or("nonlinear must be true or false")?,
            };
            let roughness = roughness()?;
            Material::Plastic {
                reflectance: field("reflectance", Role::Fraction)?,
                nonlinear,
                coating: Arc::new(crate::bsdf::PlasticCoating::new(
                    eta as f32,
                    roughness * roughness,
                )),
            }
        }
        Some("dielectric") => {
            only_keys(map, &["type", "emission", "ior", "roughness", "absorption"])?;
            let n = map.get("ior").ok_or("needs 'ior'")?;
            Material::Dielectric {
                ior: ior(n, cx).map_err(|e| format!("ior: {e}"))?,
                roughness: roughness()?,
                absorption: map
                    .get("absorption")
                    .map(|a| spectrum(a, Role::Plain, cx).map_err(|e| format!("absorption: {e}")))
                    .transpose()?,
            }
        }
        Some("conductor") => {
            only_keys(map, &["type", "emission", "metal", "eta", "k", "roughness"])?;
            let (eta, k) = match map.get("metal") {
                Some(name) => metal(name.as_str().ok_or("metal must be a name")?)?,
                None => (field("eta", Role::Plain)?, field("k", Role::Plain)?),
            };
            Material::Conductor {
                eta,
                k,
                roughness: roughness()?,
            }
        }
        Some("fluorescent") => fluorescent(map, cx)?,
        Some("interface") => {
            only_keys(map, &["type"])?;
            Material::Interface
        }
        Some("polarizer") => {
            only_keys(map, &["type", "emission", "axis", "transmittance"])?;
            Material::Polarizer {
                axis: axis(map)?,
                transmittance: match map.get("transmittance") {
                    Some(_) => field("transmittance", Role::Fraction)?,
                    None => SceneSpectrum::Constant(1.0),
                },
            }
        }
        Some("retarder") => {
            only_keys(
                map,
                &["type", "emission", "axis", "retardance", "path_difference"],
            )?;
            let retardance = match (map.get("retardance"), map.get("path_difference")) {
                (Some(_), None) => field("retardance", Role::Plain)?,
                (None, Some(d)) => path_difference(number(d, "path_difference")?)?,
                _ => {
                    return Err(
                        "needs one of 'retardance' (waves) or 'path_difference' (nm)".into(),
                    );
                }
            };
            Material::Retarder {
                axis: axis(map)?,
                retardance,
            }
        }
        _ => return Err(format!("type {kind} is not one of {MATERIAL_TYPES}")),
    };
    Ok(SpectralMaterial {
        surface: Some(surface),
        emission,
        ..SpectralMaterial::default()
    })
}

/// A polarizing sheet's axis: a direction [x, y, z] in world space, not zero.
fn axis(map: &Map<String, Value>) -> Result<glam::Vec3, String> {
    let v = map
        .get("axis")
        .ok_or("needs 'axis' (a direction [x, y, z])")?;
    let components = v
        .as_array()
        .filter(|a| a.len() == 3)
        .ok_or("axis must be a direction [x, y, z]")?;
    let mut out = [0.0f32; 3];
    for (o, c) in out.iter_mut().zip(components) {
        let x = number(c, "axis")?;
        if !x.is_finite() || x.abs() > 1e30 {
            return Err(format!("axis component {x} is not a usable number"));
        }
        *o = x as f32;
    }
    glam::Vec3::from(out)
        .try_normalize()
        .ok_or_else(|| "axis must not be zero".into())
}

/// The retardance in waves of a plate whose optical path difference is `nm` at every
/// wavelength (a zero-order plate without dispersion of its birefringence): `nm / lambda`,
/// tabulated at 1 nm over 200-2500 nm.
fn path_difference(nm: f64) -> Result<SceneSpectrum, String> {
    if !(0.0..=1e6).contains(&nm) {
        return Err(format!("path_difference {nm} must be in [0, 1e6] nm"));
    }
    let values: Vec<f64> = (200..=2500).map(|l| nm / f64::from(l)).collect();
    let table = prism_spectrum::spectra::PiecewiseLinear::from_regular(
        200.0,
        1.0,
        &values,
        prism_spectrum::spectra::Extrapolation::Clamp,
    )
    .map_err(|e| format!("path_difference: {e}"))?;
    Ok(SceneSpectrum::Table(Arc::new(table)))
}

/// `lifetime`: seconds (exponential decay), or `lifetimes`: [[seconds, weight], ...]
/// (multi-exponential, weights summing to 1).
fn decay(
    lifetime: Option<Value>,
    lifetimes: Option<Value>,
) -> Result<Option<prism_sampling::decay::Decay>, String> {
    use prism_sampling::decay::Decay;
    match (lifetime, lifetimes) {
        (None, None) => Ok(None),
        (Some(_), Some(_)) => Err("give 'lifetime' or 'lifetimes', not both".into()),
        (Some(t), None) => {
            let t = number(&t, "lifetime")?;
            Decay::exponential(t)
                .map(Some)
                .map_err(|e| format!("lifetime {t} s: {e}"))
        }
        (None, Some(list)) => {
            let pairs = list
                .as_array()
                .ok_or("lifetimes must be [[seconds, weight], ...]")?
                .iter()
                .map(|pair| match pair.as_array().map(Vec::as_slice) {
                    Some([t, w]) => Ok((number(t, "lifetime")?, number(w, "lifetime weight")?)),
                    _ => Err("lifetimes must be [[seconds, weight], ...]".to_string()),
                })
                .collect::<Result<Vec<_>, _>>()?;
            Decay::multi(&pairs)
                .map(Some)
                .map_err(|e| format!("lifetimes: {e}"))
        }
    }
}

/// A fluorescent material from absorption, re-emission and quantum yield, or from a full
/// re-radiation matrix.
fn fluorescent(map: &Map<String, Value>, cx: &Context) -> Result<Material, String> {
    only_keys(
        map,
        &[
            "type",
            "emission",
            "reflectance",
            "absorption",
            "reemission",
            "quantum_yield",
            "range",
            "bins",
            "matrix",
        ],
    )?;
    let reflectance = match map.get("reflectance") {
        Some(v) => spectrum(v, Role::Fraction, cx).map_err(|e| format!("reflectance: {e}"))?,
        None => SceneSpectrum::Constant(0.0),
    };
    let range = kernel_range(map)?;
    let (lo, hi) = (range.min(), range.max());
    let (bins, matrix) = if let Some(m) = map.get("matrix") {
        for key in ["absorption", "reemission", "quantum_yield", "bins"] {
            if map.contains_key(key) {
                return Err(format!("'{key}' cannot be combined with 'matrix'"));
            }
        }
        let (bins, m) = full_matrix(m)?;
        // Energy: what leaves per unit energy arriving at l_i is the row's integral over l_o.
        let width = f64::from(hi - lo) / bins as f64;
        for i in 0..bins {
            let out: f64 = m[i * bins..(i + 1) * bins].iter().sum::<f64>() * width;
            if out > 1.0 + 1e-6 {
                return Err(format!(
                    "matrix row {i} re-radiates {out} of the light it receives (must be <= 1)"
                ));
            }
        }
        (bins, m)
    } else {
        let bins = kernel_bins(map, range)?;
        let Dye {
            absorption,
            reemission,
            quantum_yield: q,
        } = dye(map, Role::Fraction, cx)?;
        let m = fluorescence_matrix(range, bins, &reflectance, &absorption, &reemission, q)
            .map_err(|e| e.to_string())?;
        (bins, m)
    };
    let sampler = ReradiationSampler::new(range, bins, &matrix).map_err(|e| e.to_string())?;
    Ok(Material::Fluorescent {
        reflectance,
        reradiation: Arc::new(sampler),
    })
}

/// What a dye absorbs, the shape of what it re-emits, and its quantum yield.
pub(crate) struct Dye {
    pub absorption: SceneSpectrum,
    pub reemission: SceneSpectrum,
    pub quantum_yield: f64,
}

/// A dye's `absorption` (a fraction on surfaces, a coefficient in media: `absorption`'s
/// role), `reemission` and `quantum_yield`, each required.
pub(crate) fn dye(map: &Map<String, Value>, absorption: Role, cx: &Context) -> Result<Dye, String> {
    let required = |key: &str, role: Role| {
        let value = map.get(key).ok_or_else(|| format!("needs '{key}'"))?;
        spectrum(value, role, cx).map_err(|e| format!("{key}: {e}"))
    };
    Ok(Dye {
        absorption: required("absorption", absorption)?,
        reemission: required("reemission", Role::Plain)?,
        quantum_yield: number(
            map.get("quantum_yield").ok_or("needs 'quantum_yield'")?,
            "quantum_yield",
        )?,
    })
}

/// A re-radiation kernel's `range` ([start_nm, end_nm], default 300-830 nm), for
/// fluorescent materials and dyes alike.
pub(crate) fn kernel_range(map: &Map<String, Value>) -> Result<WavelengthRange, String> {
    let (lo, hi) = match map.get("range") {
        None => FLUORESCENCE_RANGE_NM,
        Some(r) => match r.as_array().map(Vec::as_slice) {
            Some([a, b]) => (
                number(a, "range start")? as f32,
                number(b, "range end")? as f32,
            ),
            _ => return Err("range must be [start_nm, end_nm]".into()),
        },
    };
    WavelengthRange::new(lo, hi).map_err(|e| format!("range: {e}"))
}

/// A re-radiation kernel's `bins` over `range` (default one per 2 nm).
pub(crate) fn kernel_bins(
    map: &Map<String, Value>,
    range: WavelengthRange,
) -> Result<usize, String> {
    match map.get("bins") {
        None => Ok(((range.max() - range.min()) / FLUORESCENCE_BIN_NM)
            .ceil()
            .max(1.0) as usize),
        Some(b) => match b.as_u64() {
            Some(n @ 1..=4096) => Ok(n as usize),
            _ => Err(format!("bins {b} must be a whole number in 1..=4096")),
        },
    }
}

/// `matrix`: `rows`, one per incident bin, each with one density (per nm of incident
/// wavelength) per outgoing bin; square, finite, >= 0.
fn full_matrix(value: &Value) -> Result<(usize, Vec<f64>), String> {
    let rows = value
        .as_object()
        .and_then(|m| {
            only_keys(m, &["rows"]).ok()?;
            m.get("rows")?.as_array()
        })
        .ok_or("matrix must be {\"rows\": [[..], ..]}")?;
    let bins = rows.len();
    let mut out = Vec::with_capacity(bins * bins);
    for (i, row) in rows.iter().enumerate() {
        let row = row.as_array().filter(|r| r.len() == bins).ok_or_else(|| {
            format!("matrix row {i} must have {bins} entries (the matrix is square)")
        })?;
        for v in row {
            let x = number(v, "matrix entry")?;
            if x < 0.0 {
                return Err(format!("matrix entry {x} in row {i} is negative"));
            }
            out.push(x);
        }
    }
    if bins == 0 {
        return Err("matrix has no rows".into());
    }
    Ok((bins, out))
}
