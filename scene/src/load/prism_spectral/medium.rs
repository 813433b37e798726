//! `"medium"` in a description: a participating medium, on an `interface` or `dielectric`
//! material (the medium inside it), on a glTF glass material (`PRISM_spectral` without a
//! `type`), or on the root (fog filling the world).

use serde_json::Value;

use super::value::{Context, Role, number, only_keys, spectrum};
use crate::medium::{Fluorescence, Grid, Medium, Phase, read_vol};

/// The keys a medium may have.
const KEYS: &[&str] = &[
    "sigma_a",
    "sigma_s",
    "g",
    "phase",
    "emission",
    "density",
    "temperature",
    "fluorescence",
];

/// Parses `{"sigma_a": S, "sigma_s": S, "g": G | "phase": "rayleigh" |
/// "henyey-greenstein", "emission": S}`: coefficients per unit of scene length (m^-1 in a
/// scene in metres), each defaulting to 0, and the emission coefficient in W m^-2 sr^-1
/// nm^-1 per unit length.
pub(crate) fn medium(value: &Value, cx: &Context) -> Result<Medium, String> {
    let map = value
        .as_object()
        .ok_or("a medium must be an object {\"sigma_a\": .., \"sigma_s\": .., \"g\": ..}")?;
    only_keys(map, KEYS)?;
    let coefficient = |key: &str| match map.get(key) {
        None => Ok(crate::textures::SceneSpectrum::Constant(0.0)),
        Some(v) => spectrum(v, Role::Plain, cx).map_err(|e| format!("{key}: {e}")),
    };
    let sigma_a = coefficient("sigma_a")?;
    let sigma_s = coefficient("sigma_s")?;
    if !["sigma_a", "sigma_s", "emission", "fluorescence"]
        .iter()
        .any(|k| map.contains_key(*k))
    {
        return Err("a medium needs 'sigma_a', 'sigma_s', 'emission' or 'fluorescence'".into());
    }
    let phase = match (map.get("phase"), map.get("g")) {
        (Some(_), Some(_)) if map.get("phase").and_then(Value::as_str) == Some("rayleigh") => {
            return Err("'g' is Henyey-Greenstein's; the Rayleigh phase function has none".into());
        }
        (Some(p), g) => match p.as_str() {
            Some("rayleigh") => Phase::Rayleigh,
            Some("henyey-greenstein") => hg(g)?,
            _ => {
                return Err(format!(
                    "phase {p} is not one of \"henyey-greenstein\", \"rayleigh\""
                ));
            }
        },
        (None, g) => hg(g)?,
    };
    let emission = map
        .get("emission")
        .map(|e| spectrum(e, Role::Emission, cx).map_err(|e| format!("emission: {e}")))
        .transpose()?;
    let mut medium = Medium::new(sigma_a, sigma_s, phase, emission)?;
    if let Some(d) = map.get("density") {
        medium = medium.with_density(grid(d, "density", cx).map_err(|e| format!("density: {e}"))?);
    }
    if let Some(t) = map.get("temperature") {
        if !map.contains_key("sigma_a") {
            return Err("temperature: a medium glows by its temperature where it absorbs: it needs 'sigma_a'".into());
        }
        medium = medium
            .with_temperature(grid(t, "temperature", cx).map_err(|e| format!("temperature: {e}"))?);
    }
    if let Some(f) = map.get("fluorescence") {
        medium = medium.with_fluorescence(dye(f, cx).map_err(|e| format!("fluorescence: {e}"))?);
    }
    Ok(medium)
}

/// Parses a dye, `{"absorption": S, "reemission": S, "quantum_yield": Q, "range": [A, B],
/// "bins": N}`: the fluorescent material's keys, with `absorption` a coefficient per unit
/// length (any value >= 0) rather than a fraction.
fn dye(value: &Value, cx: &Context) -> Result<Fluorescence, String> {
    let map = value.as_object().ok_or(
        "must be an object {\"absorption\": .., \"reemission\": .., \"quantum_yield\": ..}",
    )?;
    if map.contains_key("matrix") {
        return Err("a medium's dye is 'absorption', 'reemission' and 'quantum_yield' ('matrix' is a surface's)".into());
    }
    only_keys(
        map,
        &["absorption", "reemission", "quantum_yield", "range", "bins"],
    )?;
    let dye = super::material::dye(map, Role::Plain, cx)?;
    let range = super::material::kernel_range(map)?;
    let bins = super::material::kernel_bins(map, range)?;
    Fluorescence::new(
        dye.absorption,
        &dye.reemission,
        dye.quantum_yield,
        range,
        bins,
    )
}

/// Parses `{"file": "smoke.vdb", "grid": NAME, "scale": S, "bounds": [[x, y, z],
/// [x, y, z]]}`: the grid in the file (OpenVDB's `.vdb`, where `grid` names one of the
/// file's grids, by default the one called `usual` or the only one; or Mitsuba's `.vol`,
/// which holds one), times `scale` (default 1), on the file's own box unless `bounds`
/// gives another (in world units).
fn grid(value: &Value, usual: &str, cx: &Context) -> Result<Grid, String> {
    let map = value
        .as_object()
        .ok_or("must be an object {\"file\": .., \"scale\": ..}")?;
    only_keys(map, &["file", "grid", "scale", "bounds"])?;
    let file = map
        .get("file")
        .and_then(Value::as_str)
        .ok_or("needs 'file', the grid's file name")?;
    let extension = file.rsplit('.').next().unwrap_or("").to_ascii_lowercase();
    let read = || (cx.resolve)(file).map_err(|e| format!("{file}: {e}"));
    let mut grid = match extension.as_str() {
        // A .vol file holds one unnamed grid, whatever 'grid' calls it.
        "vol" => read_vol(&read()?).map_err(|e| format!("{file}: {e}"))?,
        #[cfg(feature = "vdb")]
        "vdb" => {
            let name = match map.get("grid") {
                None => None,
                Some(g) => Some(g.as_str().ok_or("'grid' must be a grid's name")?),
            };
            crate::medium::read_vdb(&read()?, name, usual).map_err(|e| format!("{file}: {e}"))?
        }
        #[cfg(not(feature = "vdb"))]
        "vdb" => {
            return Err(format!(
                "{file}: this build of prism-scene reads no OpenVDB files (feature 'vdb')"
            ));
        }
        _ => return Err(format!("{file}: not a grid file prism reads (.vdb, .vol)")),
    };
    if let Some(scale) = map.get("scale") {
        grid = grid.scaled(number(scale, "scale")? as f32)?;
    }
    if let Some(bounds) = map.get("bounds") {
        let corner = |v: Option<&Value>| -> Result<glam::Vec3, String> {
            let a = v
                .and_then(Value::as_array)
                .filter(|a| a.len() == 3)
                .ok_or("bounds must be [[min x, y, z], [max x, y, z]]")?;
            let mut c = [0.0f32; 3];
            for (k, x) in a.iter().enumerate() {
                c[k] = number(x, "bounds")? as f32;
            }
            Ok(glam::Vec3::from(c))
        };
        let b = bounds
            .as_array()
            .filter(|b| b.len() == 2)
            .ok_or("bounds must be [[min x, y, z], [max x, y, z]]")?;
        grid = grid.placed(corner(b.first())?, corner(b.get(1))?)?;
    }
    Ok(grid)
}

/// Henyey-Greenstein with `g` (default 0, isotropic).
fn hg(g: Option<&Value>) -> Result<Phase, String> {
    let g = match g {
        None => 0.0,
        Some(v) => number(v, "g")?,
    };
    Phase::henyey_greenstein(g)
}
