//! Mitsuba's spectral values as prism's spectra: `<spectrum>` values and `.spd` files as
//! tables, a single value as a constant, `<rgb>` upsampled by the scene's upsampler (as a
//! reflectance, or for emitters as an illuminant under D65, as Mitsuba's spectral
//! variants read an emitter's RGB), and `<spectrum type="blackbody">` as Planck's law.

use std::sync::Arc;

use prism_spectrum::spectra::{Extrapolation, PiecewiseLinear};

use super::parse::error;
use super::tree::{Class, Object, SpectrumValue, Value};
use crate::LoadError;
use crate::load::Upsampler;
use crate::textures::SceneSpectrum;

/// Mitsuba's film divides by the CIE 1931 y-bar integral (`MI_CIE_Y_NORMALIZATION` in
/// `include/mitsuba/core/spectrum.h`), so that a unit spectrum of radiance has luminance 1;
/// prism's film integrates radiance against y-bar as it is. An emitter's spectrum given
/// as numbers is scaled by this to mean in prism what it means in Mitsuba. (An emitter's
/// colour is upsampled to a spectrum under D65 whose luminance is the colour's already.)
pub(crate) const MITSUBA_Y_NORMALIZATION: f64 = 1.0 / 106.750_259_399_414_06;

/// What an RGB value means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// A reflectance in [0, 1].
    Albedo,
    /// Emitted radiance: the colour under the D65 white.
    Illuminant,
}

/// The spectrum `name` of `object`: its property or nested spectrum, or `default` where
/// it has neither.
pub(crate) fn spectrum(
    object: &Object,
    name: &str,
    kind: Kind,
    default: f64,
    upsampler: &Upsampler,
) -> Result<SceneSpectrum, LoadError> {
    if let Some(p) = object.property(name) {
        let number = match p.value {
            Value::Float(v) => Some(v),
            Value::Integer(v) => Some(v as f64),
            _ => None,
        };
        // An emitter's number is a grey under D65, as Mitsuba's `d65` texture makes it.
        if let (Kind::Illuminant, Some(v)) = (kind, number) {
            if !v.is_finite() {
                return Err(error(&p.at, format!("{v} is not a finite number")));
            }
            let fitted = upsampler
                .emission([f64::from(v as f32); 3])
                .map_err(|e| error(&p.at, format!("{name}: {e}")))?;
            return Ok(SceneSpectrum::Rgb(Arc::new(fitted)));
        }
        return match &p.value {
            Value::Float(v) => constant(*v, &p.at),
            Value::Integer(v) => constant(*v as f64, &p.at),
            Value::Spectrum(SpectrumValue::Constant(v)) => constant(*v * scale(kind), &p.at),
            Value::Spectrum(SpectrumValue::Samples(samples)) => {
                let scaled: Vec<(f64, f64)> =
                    samples.iter().map(|&(l, v)| (l, v * scale(kind))).collect();
                table(&scaled, &p.at)
            }
            Value::Rgb(rgb) => {
                // Mitsuba keeps colours as 32-bit floats.
                let rgb = &rgb.map(|c| f64::from(c as f32));
                let fitted = match kind {
                    Kind::Albedo => upsampler
                        .fit(*rgb, prism_upsample::RgbKind::Albedo)
                        .map_err(|e| error(&p.at, format!("{name}: {e}"))),
                    Kind::Illuminant => upsampler
                        .emission(*rgb)
                        .map_err(|e| error(&p.at, format!("{name}: {e}"))),
                }?;
                Ok(SceneSpectrum::Rgb(Arc::new(fitted)))
            }
            _ => Err(error(
                &p.at,
                format!("'{name}' must be a spectrum, a colour or a number"),
            )),
        };
    }
    if let Some(child) = object.child(name) {
        let nested = &child.object;
        return match (nested.class, nested.kind.as_str()) {
            (Class::Texture, other) => Err(error(
                &nested.at,
                format!("texture '{other}' for '{name}' is not read yet"),
            )),
            (_, other) => Err(error(
                &nested.at,
                format!("'{other}' for '{name}' is not read yet"),
            )),
        };
    }
    Ok(SceneSpectrum::Constant(default))
}

/// How a spectrum given as numbers scales: emitted radiance by Mitsuba's normalization.
fn scale(kind: Kind) -> f64 {
    match kind {
        Kind::Albedo => 1.0,
        Kind::Illuminant => MITSUBA_Y_NORMALIZATION,
    }
}

fn constant(v: f64, at: &super::tree::Location) -> Result<SceneSpectrum, LoadError> {
    if v.is_finite() {
        Ok(SceneSpectrum::Constant(v))
    } else {
        Err(error(at, format!("{v} is not a finite number")))
    }
}

/// Samples (nm, value) as a piecewise-linear spectrum, zero beyond its ends (Mitsuba's
/// irregular spectra are zero outside their range).
fn table(samples: &[(f64, f64)], at: &super::tree::Location) -> Result<SceneSpectrum, LoadError> {
    let (lambdas, values): (Vec<f64>, Vec<f64>) = samples.iter().copied().unzip();
    PiecewiseLinear::new(lambdas, values, Extrapolation::Zero)
        .map(|t| SceneSpectrum::Table(Arc::new(t)))
        .map_err(|e| error(at, format!("spectrum: {e}")))
}
