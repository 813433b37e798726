//! Spectra and indices of refraction written in scene descriptions (JSON in glTF, TOML in
//! overlays, both read as JSON values).

use std::sync::Arc;

use prism_spectrum::Spectrum;
use prism_spectrum::optics::{
    Cauchy, GLASS_NAMES, METAL_NAMES, Sellmeier, named_glass, named_metal,
};
use prism_spectrum::spectra::{
    Extrapolation, NAMED_SPECTRUM_FORMS, NamedSpectrum, PiecewiseLinear,
};
use prism_upsample::RgbKind;
use serde_json::Value;

use crate::load::Upsampler;
use crate::textures::SceneSpectrum;

/// The forms a spectrum may take, for error messages and the format's documentation.
pub const SPECTRUM_FORMS: &str = "a number (constant), a name (blackbody:T, illuminant:NAME, \
daylight:CCT, gaussian:CENTER_NM:FWHM_NM, constant:V), \"csv:PATH\", a list of [nm, value] pairs, \
{\"rgb\": [r, g, b]}, or {\"spectrum\": S, \"scale\": K}";

/// The forms an index of refraction may take.
pub const IOR_FORMS: &str = "a number >= 1, \"glass:NAME\", {\"sellmeier\": {\"B\": [..], \"C\": [..] (um^2)}}, \
{\"cauchy\": {\"A\": a, \"B\": b (nm^2), \"C\": c (nm^4)}}, {\"abbe\": {\"nd\": n, \"vd\": V}}, or a tabulated spectrum";

/// What a spectrum is for: it decides how RGB is upsampled and which values are allowed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Role {
    /// A fraction of light (reflectance, absorption): values in [0, 1].
    Fraction,
    /// Emitted light: values >= 0; RGB is upsampled as an illuminant.
    Emission,
    /// Any non-negative quantity (emission shapes, eta, k): RGB as an unbounded spectrum.
    Plain,
}

/// What parsing needs besides the value: external files and the upsampler for RGB.
pub(crate) struct Context<'a> {
    /// Reads a file named in the description (relative to the glTF file).
    pub resolve: &'a crate::load::Resolver<'a>,
    /// Fits RGB values (linear sRGB, as glTF colours).
    pub upsampler: &'a Upsampler,
}

/// A spectrum for `role` from its description.
pub(crate) fn spectrum(value: &Value, role: Role, cx: &Context) -> Result<SceneSpectrum, String> {
    let s = match value {
        Value::Number(n) => {
            let v = n
                .as_f64()
                .filter(|v| v.is_finite())
                .ok_or("not a finite number")?;
            SceneSpectrum::Constant(v)
        }
        Value::String(text) => match text.strip_prefix("csv:") {
            Some(path) => csv(path, cx)?,
            None if NamedSpectrum::is_named(text) => {
                SceneSpectrum::from_named(NamedSpectrum::parse(text).map_err(|e| e.to_string())?)
                    .map_err(|e| e.to_string())?
            }
            None => {
                return Err(format!(
                    "'{text}' is not a spectrum (expected {NAMED_SPECTRUM_FORMS}, or csv:PATH)"
                ));
            }
        },
        Value::Array(pairs) => table(pairs)?,
        Value::Object(map) => {
            if let Some(rgb) = map.get("rgb") {
                only_keys(map, &["rgb"])?;
                upsample(rgb, role, cx)?
            } else if let Some(inner) = map.get("spectrum") {
                only_keys(map, &["spectrum", "scale"])?;
                let scale = match map.get("scale") {
                    None => 1.0,
                    Some(k) => number(k, "scale")?,
                };
                SceneSpectrum::Scaled(Arc::new(spectrum(inner, role, cx)?), scale)
            } else {
                return Err(format!("expected {SPECTRUM_FORMS}"));
            }
        }
        _ => return Err(format!("expected {SPECTRUM_FORMS}")),
    };
    check_range(&s, role)?;
    Ok(s)
}

/// Values must be >= 0 everywhere, and <= 1 for fractions; checked at every nanometre
/// from 200 to 2500 nm and at the maximum the spectrum reports.
fn check_range(s: &SceneSpectrum, role: Role) -> Result<(), String> {
    let upper = if role == Role::Fraction {
        1.0 + 1e-6
    } else {
        f64::INFINITY
    };
    for nm in (200..=2500).map(f64::from) {
        let v = s.evaluate(nm);
        if !(v.is_finite() && v >= 0.0 && v <= upper) {
            let expected = if role == Role::Fraction {
                "in [0, 1]"
            } else {
                "finite and >= 0"
            };
            return Err(format!("value {v} at {nm} nm is not {expected}"));
        }
    }
    if role == Role::Fraction && s.max_value() > upper {
        return Err(format!("maximum {} exceeds 1", s.max_value()));
    }
    Ok(())
}

/// A finite number.
pub(crate) fn number(value: &Value, what: &str) -> Result<f64, String> {
    value
        .as_f64()
        .filter(|v| v.is_finite())
        .ok_or_else(|| format!("{what} {value} is not a finite number"))
}

/// Errors on keys other than `allowed`, so that a misspelt key is not silently ignored.
pub(crate) fn only_keys(
    map: &serde_json::Map<String, Value>,
    allowed: &[&str],
) -> Result<(), String> {
    match map.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(k) => Err(format!(
            "unknown key '{k}' (expected {})",
            allowed.join(", ")
        )),
        None => Ok(()),
    }
}

fn csv(path: &str, cx: &Context) -> Result<SceneSpectrum, String> {
    let bytes = (cx.resolve)(path).map_err(|e| format!("csv:{path}: {e}"))?;
    let text = String::from_utf8(bytes).map_err(|_| format!("csv:{path}: not UTF-8 text"))?;
    let table = PiecewiseLinear::from_csv_str(&text, Extrapolation::Zero)
        .map_err(|e| format!("csv:{path}: {e}"))?;
    SceneSpectrum::dense(&table).map_err(|e| format!("csv:{path}: {e}"))
}

fn table(pairs: &[Value]) -> Result<SceneSpectrum, String> {
    let mut lambdas = Vec::with_capacity(pairs.len());
    let mut values = Vec::with_capacity(pairs.len());
    for pair in pairs {
        match pair.as_array().map(Vec::as_slice) {
            Some([l, v]) => {
                lambdas.push(number(l, "wavelength")?);
                values.push(number(v, "value")?);
            }
            _ => return Err(format!("table entry {pair} is not an [nm, value] pair")),
        }
    }
    let table =
        PiecewiseLinear::new(lambdas, values, Extrapolation::Zero).map_err(|e| e.to_string())?;
    SceneSpectrum::dense(&table).map_err(|e| e.to_string())
}

fn upsample(rgb: &Value, role: Role, cx: &Context) -> Result<SceneSpectrum, String> {
    let c = match rgb.as_array().map(Vec::as_slice) {
        Some([r, g, b]) => [number(r, "red")?, number(g, "green")?, number(b, "blue")?],
        _ => return Err(format!("rgb {rgb} is not [r, g, b]")),
    };
    let kind = match role {
        Role::Fraction => RgbKind::Albedo,
        Role::Emission => RgbKind::Illuminant,
        Role::Plain => RgbKind::Unbounded,
    };
    Ok(SceneSpectrum::Rgb(Arc::new(cx.upsampler.fit(c, kind)?)))
}

/// An index of refraction from its description.
pub(crate) fn ior(value: &Value, cx: &Context) -> Result<SceneSpectrum, String> {
    let s = match value {
        Value::Number(_) => {
            let n = number(value, "index")?;
            if n < 1.0 {
                return Err(format!("index {n} is below 1"));
            }
            SceneSpectrum::Constant(n)
        }
        Value::String(text) if text.starts_with("glass:") => {
            let glass = named_glass(&text["glass:".len()..])
                .map_err(|e| format!("{e} (glasses: {GLASS_NAMES})"))?;
            SceneSpectrum::Sellmeier(Arc::new(glass.ior))
        }
        Value::Object(map) if map.contains_key("sellmeier") => {
            only_keys(map, &["sellmeier"])?;
            sellmeier(&map["sellmeier"])?
        }
        Value::Object(map) if map.contains_key("cauchy") => {
            only_keys(map, &["cauchy"])?;
            let c = map["cauchy"]
                .as_object()
                .ok_or("cauchy must be {\"A\", \"B\", \"C\"}")?;
            only_keys(c, &["A", "B", "C"])?;
            let get = |k: &str| c.get(k).map_or(Ok(0.0), |v| number(v, k));
            SceneSpectrum::Cauchy(
                Cauchy::new(get("A")?, get("B")?, get("C")?, Cauchy::ABBE_RANGE_NM)
                    .map_err(|e| e.to_string())?,
            )
        }
        Value::Object(map) if map.contains_key("abbe") => {
            only_keys(map, &["abbe"])?;
            let a = map["abbe"]
                .as_object()
                .ok_or("abbe must be {\"nd\", \"vd\"}")?;
            only_keys(a, &["nd", "vd"])?;
            let nd = number(a.get("nd").ok_or("abbe needs nd")?, "nd")?;
            let vd = number(a.get("vd").ok_or("abbe needs vd")?, "vd")?;
            SceneSpectrum::Cauchy(Cauchy::from_abbe(nd, vd).map_err(|e| e.to_string())?)
        }
        Value::String(_) | Value::Array(_) => spectrum(value, Role::Plain, cx)?,
        _ => return Err(format!("expected {IOR_FORMS}")),
    };
    for nm in (300..=1000).map(f64::from) {
        let n = s.evaluate(nm);
        if !(n.is_finite() && n > 0.0) {
            return Err(format!(
                "index {n} at {nm} nm is not a finite positive number"
            ));
        }
    }
    Ok(s)
}

fn sellmeier(value: &Value) -> Result<SceneSpectrum, String> {
    let map = value
        .as_object()
        .ok_or("sellmeier must be {\"B\": [..], \"C\": [..]}")?;
    only_keys(map, &["B", "C", "range"])?;
    let list = |k: &str| -> Result<Vec<f64>, String> {
        map.get(k)
            .and_then(Value::as_array)
            .ok_or_else(|| format!("sellmeier needs a list {k}"))?
            .iter()
            .map(|v| number(v, k))
            .collect()
    };
    let (b, c) = (list("B")?, list("C")?);
    if b.len() != c.len() {
        return Err(format!(
            "sellmeier B has {} terms but C has {}",
            b.len(),
            c.len()
        ));
    }
    let range = match map.get("range") {
        None => Cauchy::ABBE_RANGE_NM,
        Some(r) => match r.as_array().map(Vec::as_slice) {
            Some([lo, hi]) => (number(lo, "range start")?, number(hi, "range end")?),
            _ => return Err("sellmeier range must be [start_nm, end_nm]".into()),
        },
    };
    let model = Sellmeier::new(b.into_iter().zip(c).collect(), range).map_err(|e| e.to_string())?;
    Ok(SceneSpectrum::Sellmeier(Arc::new(model)))
}

/// eta and k of a named metal (clamped to the nearest measurement outside their range).
pub(crate) fn metal(name: &str) -> Result<(SceneSpectrum, SceneSpectrum), String> {
    let m = named_metal(name).map_err(|e| format!("{e} (metals: {METAL_NAMES})"))?;
    Ok((
        SceneSpectrum::Table(Arc::new(m.eta)),
        SceneSpectrum::Table(Arc::new(m.k)),
    ))
}

/// A schedule: `[[start, end], ...]` in seconds, an end omitted (`[start]`) or null for
/// "until further notice"; in order, not overlapping.
pub(crate) fn schedule(value: &Value) -> Result<crate::world::Schedule, String> {
    let list = value
        .as_array()
        .ok_or("a schedule is [[start, end], ...] in seconds")?;
    let intervals = list
        .iter()
        .map(|entry| match entry.as_array().map(Vec::as_slice) {
            Some([start]) => Ok((number(start, "start")?, f64::INFINITY)),
            Some([start, Value::Null]) => Ok((number(start, "start")?, f64::INFINITY)),
            Some([start, end]) => Ok((number(start, "start")?, number(end, "end")?)),
            _ => Err("a schedule is [[start, end], ...] in seconds".to_string()),
        })
        .collect::<Result<Vec<_>, _>>()?;
    crate::world::Schedule::new(intervals)
}
