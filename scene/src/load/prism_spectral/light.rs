//! `PRISM_spectral` on `KHR_lights_punctual` lights and on the glTF root.

use serde_json::Value;

use super::value::{Context, Role, only_keys, schedule, spectrum};
use crate::lights::Environment;
use crate::textures::SceneSpectrum;

/// A punctual light's spectrum.
#[derive(Debug, Clone)]
pub struct SpectralLight {
    /// The spectral shape replacing the light's RGB colour.
    pub spectrum: SceneSpectrum,
    /// Whether glTF's intensity is photometric (candela or lux of this spectrum, glTF's
    /// meaning) or radiometric (the spectrum times the intensity is W sr^-1 nm^-1, or
    /// W m^-2 nm^-1 for directional lights). Sources outside the visible (UV LEDs) have
    /// no luminance to normalize by, so they must be radiometric.
    pub radiometric: bool,
    /// Partial linear polarization of its light: degree in [0, 1] and angle (radians,
    /// from the light's x axis towards its y axis), if any.
    pub polarization: Option<(f32, f32)>,
    /// When it shines (None: always).
    pub on: Option<crate::world::Schedule>,
}

/// Parses a light's description: `{"spectrum": S, "units": "photometric" | "radiometric"}`.
pub(crate) fn light(value: &Value, cx: &Context) -> Result<SpectralLight, String> {
    let map = value
        .as_object()
        .ok_or("PRISM_spectral on a light must be an object")?;
    only_keys(map, &["spectrum", "units", "polarization", "on"])?;
    let spectrum = spectrum(
        map.get("spectrum").ok_or("needs 'spectrum'")?,
        Role::Emission,
        cx,
    )
    .map_err(|e| format!("spectrum: {e}"))?;
    let radiometric = match map.get("units").map(|u| u.as_str()) {
        None | Some(Some("photometric")) => false,
        Some(Some("radiometric")) => true,
        Some(_) => return Err("units must be \"photometric\" or \"radiometric\"".into()),
    };
    let polarization = map.get("polarization").map(polarization).transpose()?;
    let on = map
        .get("on")
        .map(|v| schedule(v).map_err(|e| format!("on: {e}")))
        .transpose()?;
    Ok(SpectralLight {
        spectrum,
        radiometric,
        polarization,
        on,
    })
}

/// `{"degree": D, "angle": DEGREES}`: degree in [0, 1] (default 1), angle from the
/// light's x axis towards its y axis (default 0).
fn polarization(value: &Value) -> Result<(f32, f32), String> {
    let map = value
        .as_object()
        .ok_or("polarization must be {\"degree\": D, \"angle\": DEGREES}")?;
    only_keys(map, &["degree", "angle"])?;
    let degree = match map.get("degree") {
        None => 1.0,
        Some(d) => super::value::number(d, "polarization degree")?,
    };
    if !(0.0..=1.0).contains(&degree) {
        return Err(format!("polarization degree {degree} is outside [0, 1]"));
    }
    let angle = match map.get("angle") {
        None => 0.0,
        Some(a) => super::value::number(a, "polarization angle")?,
    };
    if !(angle.is_finite() && angle.abs() <= 360.0) {
        return Err(format!(
            "polarization angle {angle} must be degrees in [-360, 360]"
        ));
    }
    Ok((degree as f32, (angle as f32).to_radians()))
}

/// What the root's `PRISM_spectral` says about the whole scene.
#[derive(Debug, Clone, Default)]
pub struct SpectralScene {
    /// Light arriving from infinity: a spectrum from every direction, or an image.
    pub environment: Option<Environment>,
    /// The camera's response curves (channels shown as R, G, B) instead of the CIE 1931
    /// observer.
    pub camera_response: Option<[SceneSpectrum; 3]>,
    /// When the environment shines (None: always).
    pub environment_on: Option<crate::world::Schedule>,
    /// The medium filling the world outside every boundary (fog), in which the camera
    /// starts.
    pub medium: Option<crate::medium::Medium>,
}

/// Parses the root's description: `{"environment": S, "camera_response": {"r": S, "g":
/// S, "b": S}}`.
pub(crate) fn scene(value: &Value, cx: &Context) -> Result<SpectralScene, String> {
    let map = value
        .as_object()
        .ok_or("PRISM_spectral on the root must be an object")?;
    only_keys(
        map,
        &["environment", "camera_response", "environment_on", "medium"],
    )?;
    let camera_response = match map.get("camera_response") {
        None => None,
        Some(v) => {
            let curves = v
                .as_object()
                .ok_or("camera_response must be {\"r\": S, \"g\": S, \"b\": S}")?;
            only_keys(curves, &["r", "g", "b"])?;
            let curve = |k: &str| {
                let c = curves
                    .get(k)
                    .ok_or_else(|| format!("camera_response needs '{k}'"))?;
                spectrum(c, Role::Plain, cx).map_err(|e| format!("camera_response {k}: {e}"))
            };
            Some([curve("r")?, curve("g")?, curve("b")?])
        }
    };
    let environment_on = map
        .get("environment_on")
        .map(|v| schedule(v).map_err(|e| format!("environment_on: {e}")))
        .transpose()?;
    if environment_on.is_some() && !map.contains_key("environment") {
        return Err("environment_on schedules an environment, and there is none".into());
    }
    Ok(SpectralScene {
        environment_on,
        environment: map
            .get("environment")
            .map(|e| environment(e, cx).map_err(|e| format!("environment: {e}")))
            .transpose()?,
        camera_response,
        medium: map
            .get("medium")
            .map(|m| super::medium::medium(m, cx).map_err(|e| format!("medium: {e}")))
            .transpose()?,
    })
}

/// An environment: a spectrum (any emission form), or an image
/// `{"image": URI, "rotation": DEGREES, "strength": S}` (rotation about +y, default 0;
/// strength default 1), the URI relative to the glTF file or a data URI.
fn environment(value: &Value, cx: &Context) -> Result<Environment, String> {
    let Some(image) = value.as_object().and_then(|m| m.get("image")) else {
        return spectrum(value, Role::Emission, cx).map(Environment::Uniform);
    };
    let map = value.as_object().ok_or("must be an object")?;
    only_keys(map, &["image", "rotation", "strength"])?;
    let uri = image
        .as_str()
        .ok_or("image must be a file name or data URI")?;
    let number = |key: &str, default: f64| -> Result<f64, String> {
        match map.get(key) {
            None => Ok(default),
            Some(v) => v
                .as_f64()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("{key} must be a finite number")),
        }
    };
    let (rotation, strength) = (number("rotation", 0.0)?, number("strength", 1.0)?);
    if strength < 0.0 {
        return Err(format!("strength {strength} must be >= 0"));
    }
    let bytes = crate::load::uri_bytes(uri, cx.resolve)?;
    let image = crate::load::environment::decode_hdr(&bytes)
        .map_err(|e| format!("image '{}': {e}", short(uri)))?;
    let map = cx
        .upsampler
        .environment_map(crate::load::EnvironmentImage {
            image,
            rotation,
            strength,
        })?;
    Ok(Environment::Map(std::sync::Arc::new(map)))
}

/// A URI as an error names it: data URIs by their start.
fn short(uri: &str) -> String {
    if uri.starts_with("data:") {
        format!("{}...", &uri[..uri.len().min(24)])
    } else {
        uri.to_string()
    }
}
