//! The `Spectrum` trait: a function of wavelength.

use crate::sampled::{SampledSpectrum, SampledWavelengths};

/// A quantity that varies with wavelength: a reflectance, an emission, an index of
/// refraction, a camera response.
///
/// Wavelengths are in nanometres. Implementations evaluate in `f64` so that colorimetry
/// is exact to the precision of its tables; the renderer's hot path takes `f32` lanes
/// through [`Spectrum::sample`], which implementations may specialise.
///
/// Contract: [`Spectrum::evaluate`] returns a finite value for every input, including
/// NaN and infinite wavelengths (for which it returns what the implementation documents,
/// usually 0).
pub trait Spectrum {
    /// The value at `lambda_nm`.
    fn evaluate(&self, lambda_nm: f64) -> f64;

    /// An upper bound of [`Spectrum::evaluate`] over all wavelengths (the exact maximum
    /// where that is cheap to know).
    fn max_value(&self) -> f64;

    /// The values at a package of sampled wavelengths, one per lane.
    fn sample<const N: usize>(&self, wavelengths: &SampledWavelengths<N>) -> SampledSpectrum<N>
    where
        Self: Sized,
    {
        SampledSpectrum::from_fn(|i| {
            crate::sampled::saturating_f32(self.evaluate(f64::from(wavelengths.lambda(i))))
        })
    }
}

impl<S: Spectrum + ?Sized> Spectrum for &S {
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        (**self).evaluate(lambda_nm)
    }
    fn max_value(&self) -> f64 {
        (**self).max_value()
    }
}

impl<S: Spectrum + ?Sized> Spectrum for Box<S> {
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        (**self).evaluate(lambda_nm)
    }
    fn max_value(&self) -> f64 {
        (**self).max_value()
    }
}
