//! The spectra a scene is described with, behind one type the integrator can sample.

use std::sync::Arc;

use prism_spectrum::Spectrum;
use prism_spectrum::optics::Cauchy;
use prism_spectrum::spectra::{Blackbody, DenselySampled};
use prism_spectrum::{SampledSpectrum, SampledWavelengths};
use prism_upsample::RgbSpectrum;

/// A spectrum of the scene: an upsampled RGB colour, a constant, a tabulated spectrum or a
/// blackbody, times `scale`. One closed enum rather than a trait object so that sampling
/// at a package of wavelengths is a match and a loop, with no dynamic dispatch per lane.
#[derive(Debug, Clone)]
pub enum SceneSpectrum {
    /// The same value at every wavelength.
    Constant(f64),
    /// An RGB colour upsampled by the scene (albedo, unbounded or illuminant kind).
    Rgb(Arc<RgbSpectrum>),
    /// A spectrum tabulated at 1 nm (measured data, CIE illuminants).
    Dense(Arc<DenselySampled>),
    /// Planck's law, normalized to a peak of 1.
    Blackbody(Blackbody),
    /// A Cauchy index of refraction (glTF's Abbe-number dispersion).
    Cauchy(Cauchy),
    /// A spectrum times a factor (light intensities).
    Scaled(Arc<SceneSpectrum>, f64),
}

impl SceneSpectrum {
    /// The values at the package's wavelengths, as f32 lanes (finite: every variant is).
    pub fn at<const N: usize>(&self, wavelengths: &SampledWavelengths<N>) -> SampledSpectrum<N> {
        match self {
            SceneSpectrum::Constant(v) => SampledSpectrum::splat(*v as f32),
            _ => self.sample(wavelengths),
        }
    }

    /// The mean over 360-830 nm at 5 nm steps: a cheap measure of power for choosing
    /// lights, not a colorimetric quantity.
    pub fn mean_visible(&self) -> f64 {
        (0..=94)
            .map(|i| self.evaluate(360.0 + 5.0 * f64::from(i)))
            .sum::<f64>()
            / 95.0
    }
}

impl Spectrum for SceneSpectrum {
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        match self {
            SceneSpectrum::Constant(v) => *v,
            SceneSpectrum::Rgb(s) => s.evaluate(lambda_nm),
            SceneSpectrum::Dense(s) => s.evaluate(lambda_nm),
            SceneSpectrum::Blackbody(s) => s.evaluate(lambda_nm),
            SceneSpectrum::Cauchy(s) => s.evaluate(lambda_nm),
            SceneSpectrum::Scaled(s, k) => s.evaluate(lambda_nm) * k,
        }
    }

    fn max_value(&self) -> f64 {
        match self {
            SceneSpectrum::Constant(v) => *v,
            SceneSpectrum::Rgb(s) => s.max_value(),
            SceneSpectrum::Dense(s) => s.max_value(),
            SceneSpectrum::Blackbody(s) => s.max_value(),
            SceneSpectrum::Cauchy(s) => s.max_value(),
            SceneSpectrum::Scaled(s, k) => s.max_value() * k,
        }
    }
}
