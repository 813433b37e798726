//! Where re-radiating vertices look for the wavelengths light arrives at.

use prism_sampling::distribution::PiecewiseConstant1D;
use prism_spectrum::Spectrum;

use super::{Light, Material, SceneSpectrum};

/// The lights' spectral power over the range of the scene's fluorescent materials, at
/// 1 nm: each light's spectrum normalized to unit area over the range, weighted by its
/// power. A camera path at a fluorescent vertex samples its incident wavelength from this
/// and from the material's re-radiation column (one-sample MIS): the column alone rarely
/// finds a narrow source, such as a UV LED, inside a broad absorption band. None without
/// fluorescent materials or light in their range.
pub(crate) fn light_wavelengths(
    materials: &[Material],
    lights: &[Light],
    power: &[f64],
    emission: &[SceneSpectrum],
) -> Option<PiecewiseConstant1D> {
    let (lo, hi) = materials
        .iter()
        .filter_map(|m| match m {
            Material::Fluorescent { reradiation, .. } => Some(reradiation.range_nm()),
            _ => None,
        })
        .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))?;
    let (lo, hi) = (f64::from(lo).floor(), f64::from(hi).ceil());
    let bins = (hi - lo).max(1.0) as usize;
    let centre = |k: usize| lo + k as f64 + 0.5;
    let mut values = vec![0.0; bins];
    for (light, &p) in lights.iter().zip(power) {
        let spectrum = match light {
            Light::Triangle { emission: e, .. } => &emission[*e as usize],
            Light::Point { intensity: s, .. }
            | Light::Spot { intensity: s, .. }
            | Light::Directional { irradiance: s, .. }
            | Light::Environment { radiance: s } => s,
        };
        let samples: Vec<f64> = (0..bins)
            .map(|k| spectrum.evaluate(centre(k)).max(0.0))
            .collect();
        let area: f64 = samples.iter().sum();
        if area > 0.0 && area.is_finite() && p > 0.0 && p.is_finite() {
            for (v, s) in values.iter_mut().zip(samples) {
                *v += p * s / area;
            }
        }
    }
    PiecewiseConstant1D::new(&values, lo, hi).ok()
}
