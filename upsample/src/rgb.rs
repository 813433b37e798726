//! RGB colours as spectra: albedo, unbounded and illuminant kinds (Jakob and Hanika 2019,
//! §5; pbrt-v4's RGBAlbedoSpectrum, RGBUnboundedSpectrum, RGBIlluminantSpectrum).
//!
//! Policies for inputs outside a kind's domain, applied before fitting and reported in
//! [`RgbSpectrum::clamped`] so callers can warn:
//! - NaN or infinite components: an error.
//! - Negative components (outside the gamut): clamped to 0.
//! - Albedo components above 1 (no reflectance exceeds 1): clamped to 1.
//! - Exact black: the zero spectrum (no sigmoid reaches 0 everywhere).
//! - r = g = b: an exactly constant spectrum (c0 = c1 = 0), no fit needed.

use std::sync::Arc;

use prism_spectrum::Spectrum;
use prism_spectrum::spectra::DenselySampled;

use crate::error::UpsampleError;
use crate::fit::FitContext;
use crate::model::SigmoidPolynomial;

/// What a fitted colour is used for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RgbKind {
    /// A reflectance or transmittance: values in [0, 1].
    Albedo,
    /// An unbounded positive quantity (components up to half of f64's range, so that the
    /// scale stays finite): scale times a sigmoid, scale = 2 max(r, g, b).
    Unbounded,
    /// An emission: scale times a sigmoid times the space's illuminant (normalized to
    /// luminance 1), so RGB (1, 1, 1) emits exactly the illuminant.
    Illuminant,
}

/// A spectrum standing for an RGB colour.
#[derive(Debug, Clone)]
pub struct RgbSpectrum {
    kind: RgbKind,
    scale: f64,
    /// None for black.
    shape: Option<SigmoidPolynomial>,
    illuminant: Option<Arc<DenselySampled>>,
    clamped: bool,
    residual: f64,
}

impl RgbSpectrum {
    /// Fits `rgb` (linear, in `context`'s space) as `kind`. `illuminant` is required for
    /// [`RgbKind::Illuminant`] and ignored otherwise; pass it normalized to luminance 1
    /// ([`normalized_illuminant`]).
    ///
    /// ```
    /// use prism_spectrum::color::RgbSpaceId;
    /// use prism_spectrum::Spectrum;
    /// use prism_upsample::{normalized_illuminant, FitContext, RgbKind, RgbSpectrum};
    ///
    /// let srgb = RgbSpaceId::Srgb;
    /// let context = FitContext::new(srgb.space(), &srgb.illuminant())?;
    /// // Albedo stays within [0, 1] at every wavelength.
    /// let green = RgbSpectrum::fit(&context, [0.1, 0.7, 0.2], RgbKind::Albedo, None)?;
    /// assert!((360..=830).all(|nm| (0.0..=1.0).contains(&green.evaluate(f64::from(nm)))));
    /// // An emission of RGB (1, 1, 1) is the space's illuminant itself.
    /// let d65 = normalized_illuminant(&srgb.illuminant())?;
    /// let white = RgbSpectrum::fit(&context, [1.0; 3], RgbKind::Illuminant, Some(d65.clone()))?;
    /// assert!((white.evaluate(560.0) / d65.evaluate(560.0) - 1.0).abs() < 1e-3);
    /// // Input that is not a colour is an error, not NaN.
    /// assert!(RgbSpectrum::fit(&context, [f64::NAN, 0.0, 0.0], RgbKind::Albedo, None).is_err());
    /// # Ok::<(), prism_upsample::UpsampleError>(())
    /// ```
    pub fn fit(
        context: &FitContext,
        rgb: [f64; 3],
        kind: RgbKind,
        illuminant: Option<Arc<DenselySampled>>,
    ) -> Result<Self, UpsampleError> {
        Self::build(rgb, kind, illuminant, &|target| {
            let fit = context.fit(target, [0.0; 3]);
            (fit.spectrum, fit.residual)
        })
    }

    /// [`RgbSpectrum::fit`] with the shape looked up in `table` (fitted for `context`'s
    /// space) instead of fitted, then improved by `refine_steps` solver steps (0: the plain
    /// trilinear lookup). Faster, slightly less accurate (docs/upsample-accuracy.md). The
    /// residual is the refined fit's; plain lookups report 0 (their error is not measured
    /// per colour).
    pub fn from_table(
        table: &crate::CoefficientTable,
        context: &FitContext,
        rgb: [f64; 3],
        kind: RgbKind,
        illuminant: Option<Arc<DenselySampled>>,
        refine_steps: u32,
    ) -> Result<Self, UpsampleError> {
        Self::build(rgb, kind, illuminant, &|target| {
            if refine_steps == 0 {
                (table.lookup(target), 0.0)
            } else {
                let fit =
                    context.fit_with_budget(target, table.lookup_normalized(target), refine_steps);
                (fit.spectrum, fit.residual)
            }
        })
    }

    /// The policies of the module doc, with `solve` giving the shape (and its residual)
    /// of a normalized, non-grey, non-black target.
    fn build(
        rgb: [f64; 3],
        kind: RgbKind,
        illuminant: Option<Arc<DenselySampled>>,
        solve: &dyn Fn([f64; 3]) -> (SigmoidPolynomial, f64),
    ) -> Result<Self, UpsampleError> {
        if rgb.iter().any(|c| !c.is_finite()) {
            return Err(UpsampleError::NonFinite(rgb));
        }
        // Unbounded colours are scaled by 2 max(r, g, b): capped at half of f64's range
        // so that the scale stays finite.
        let upper = if kind == RgbKind::Albedo {
            1.0
        } else {
            f64::MAX / 2.0
        };
        let clean = rgb.map(|c| c.clamp(0.0, upper));
        let clamped = clean != rgb;
        let m = clean.iter().copied().fold(0.0, f64::max);
        let scale = if kind == RgbKind::Albedo {
            1.0
        } else {
            2.0 * m
        };
        let (shape, residual) = if m == 0.0 {
            (None, 0.0)
        } else {
            let target = clean.map(|c| c / scale);
            if target[0] == target[1] && target[1] == target[2] {
                (Some(SigmoidPolynomial::constant(target[0])), 0.0)
            } else {
                let (spectrum, residual) = solve(target);
                (Some(spectrum), residual)
            }
        };
        Ok(Self {
            kind,
            scale,
            shape,
            illuminant: if kind == RgbKind::Illuminant {
                illuminant
            } else {
                None
            },
            clamped,
            residual,
        })
    }

    /// The kind.
    pub fn kind(&self) -> RgbKind {
        self.kind
    }

    /// The sigmoid polynomial (None for black).
    pub fn shape(&self) -> Option<SigmoidPolynomial> {
        self.shape
    }

    /// The scale factor (1 for albedo).
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Whether the input was outside the kind's domain and was clamped.
    pub fn clamped(&self) -> bool {
        self.clamped
    }

    /// The fit's remaining CIE76 Lab distance (0 for black and greys).
    pub fn residual(&self) -> f64 {
        self.residual
    }
}

impl RgbSpectrum {
    /// The spectrum at `N` wavelengths (nm) at once, in f32: the sigmoid polynomial as
    /// straight-line lane arithmetic ([`crate::sigmoid::sigmoid_polynomial_lanes`]), times
    /// the scale and, for illuminants, the illuminant. What a renderer samples per path;
    /// within ~1e-5 of [`Spectrum::evaluate`] (the coefficients rounded to f32).
    pub fn evaluate_lanes<const N: usize>(&self, lambda: &[f32; N]) -> [f32; N] {
        let Some(shape) = self.shape else {
            return [0.0; N];
        };
        let c = shape.coefficients.map(|c| c as f32);
        let s = crate::sigmoid::sigmoid_polynomial_lanes(c, lambda);
        let white = match &self.illuminant {
            Some(i) => i.evaluate_lanes(lambda),
            None => [1.0; N],
        };
        let scale = self.scale as f32;
        if scale.is_finite() {
            // Saturated to f32's range: a spectrum never hands out infinity.
            std::array::from_fn(|k| (scale * s[k] * white[k]).min(f32::MAX))
        } else {
            // A scale beyond f32 (emission strengths of 1e38 and more): the product in
            // f64, which holds it, then saturated.
            std::array::from_fn(|k| {
                (self.scale * f64::from(s[k]) * f64::from(white[k])).min(f64::from(f32::MAX)) as f32
            })
        }
    }
}

impl Spectrum for RgbSpectrum {
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        let Some(shape) = self.shape else { return 0.0 };
        let base = self.scale * shape.evaluate(lambda_nm);
        match &self.illuminant {
            Some(i) => base * i.evaluate(lambda_nm),
            None => base,
        }
    }

    fn max_value(&self) -> f64 {
        let Some(shape) = self.shape else { return 0.0 };
        let base = self.scale * shape.max_value();
        match &self.illuminant {
            Some(i) => base * i.max_value(),
            None => base,
        }
    }
}

/// `illuminant` sampled at 1 nm over 300-1000 nm and scaled to luminance Y = 1 (emission
/// XYZ under the CIE 1931 observer), for [`RgbKind::Illuminant`].
pub fn normalized_illuminant<S: Spectrum + ?Sized>(
    illuminant: &S,
) -> Result<Arc<DenselySampled>, UpsampleError> {
    let dense = DenselySampled::from_spectrum(illuminant, 300, 1000)?;
    let y = prism_spectrum::colorimetry::emission_xyz(
        &dense,
        prism_spectrum::colorimetry::Observer::Cie1931,
    )
    .y;
    if !(y > 0.0 && y.is_finite()) {
        return Err(prism_spectrum::SpectrumError::Degenerate(
            "the illuminant has no luminance".into(),
        )
        .into());
    }
    let values = dense.values().iter().map(|v| v / y).collect();
    Ok(Arc::new(DenselySampled::from_values(
        dense.first_nm(),
        values,
    )?))
}
