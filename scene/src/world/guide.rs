//! Where re-radiating vertices look for the wavelengths light arrives at.

use prism_sampling::distribution::PiecewiseConstant1D;
use prism_spectrum::Spectrum;

use crate::lights::{Light, light_spectrum};
use crate::materials::Material;
use crate::textures::SceneSpectrum;

/// Per material, for the fluorescent ones: the density, at 1 nm over the material's
/// range, of the product of what the material re-radiates from each incident wavelength
/// (its row integral: absorption times quantum yield) and the lights' summed spectral
/// flux there. A camera path at a fluorescent vertex samples its incident wavelength from
/// this and from the material's re-radiation column (one-sample MIS): the column alone
/// rarely finds a narrow source, such as a UV LED, inside a broad absorption band, and
/// the lights' spectra alone waste samples where the material absorbs nothing. Empty
/// without fluorescent materials; None for a material no light excites.
pub(crate) fn light_wavelengths(
    materials: &[Material],
    lights: &[Light],
    extents: &[f64],
    emission: &[SceneSpectrum],
) -> Vec<Option<PiecewiseConstant1D>> {
    if !materials.iter().any(Material::fluorescent) {
        return Vec::new();
    }
    materials
        .iter()
        .map(|m| {
            let Material::Fluorescent { reradiation, .. } = m else {
                return None;
            };
            guide(reradiation.range_nm(), lights, extents, emission, |nm| {
                reradiation.outgoing_integral(nm)
            })
        })
        .collect()
}

/// The density, at 1 nm over `range`, of the lights' spectral flux (each light's spectrum
/// times its extent) times `reradiated`: what a re-radiating surface or dye re-emits of
/// each incident wavelength. None where the product is zero everywhere.
pub(crate) fn guide(
    range: (f32, f32),
    lights: &[Light],
    extents: &[f64],
    emission: &[SceneSpectrum],
    reradiated: impl Fn(f32) -> f64,
) -> Option<PiecewiseConstant1D> {
    let (lo, hi) = (f64::from(range.0).floor(), f64::from(range.1).ceil());
    let bins = (hi - lo).max(1.0) as usize;
    let values: Vec<f64> = (0..bins)
        .map(|k| {
            let nm = lo + k as f64 + 0.5;
            let flux: f64 = lights
                .iter()
                .zip(extents)
                .map(|(l, &e)| e * light_spectrum(l, emission).evaluate(nm).max(0.0))
                .filter(|f| f.is_finite())
                .sum();
            flux * reradiated(nm as f32)
        })
        .collect();
    PiecewiseConstant1D::new(&values, lo, hi).ok()
}
