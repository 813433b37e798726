//! The spectra a scene is described with, behind one type the integrator can sample.

use std::sync::Arc;

use prism_spectrum::Spectrum;
use prism_spectrum::optics::{Cauchy, Sellmeier};
use prism_spectrum::spectra::{Blackbody, DenselySampled, Gaussian, NamedSpectrum};
use prism_spectrum::{SampledSpectrum, SampledWavelengths, saturating_f32};
use prism_upsample::RgbSpectrum;

/// A spectrum of the scene: an upsampled RGB colour, a constant, a tabulated spectrum or a
/// blackbody, times `scale`. One closed enum rather than a trait object so that sampling
/// at a package of wavelengths is a match and a loop, with no dynamic dispatch per lane.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum SceneSpectrum {
    /// The same value at every wavelength.
    Constant(f64),
    /// An RGB colour upsampled by the scene (albedo, unbounded or illuminant kind).
    Rgb(Arc<RgbSpectrum>),
    /// A spectrum tabulated at 1 nm (measured data, CIE illuminants).
    Dense(Arc<DenselySampled>),
    /// Planck's law, normalized to a peak of 1.
    Blackbody(Blackbody),
    /// A piecewise-linear table evaluated as it extrapolates (measured metal indices clamp
    /// to their nearest measurement rather than fall to zero).
    Table(Arc<prism_spectrum::spectra::PiecewiseLinear>),
    /// A Gaussian band (narrow-band sources such as LEDs and lasers).
    Gaussian(Gaussian),
    /// A Cauchy index of refraction (glTF's Abbe-number dispersion).
    Cauchy(Cauchy),
    /// A Sellmeier index of refraction (named and measured glasses).
    Sellmeier(Arc<Sellmeier>),
    /// A spectrum times a factor (light intensities).
    Scaled(Arc<SceneSpectrum>, f64),
    /// A colour texture, upsampled per lookup. Without a texture coordinate (`at`,
    /// `evaluate`) it is its mean colour's spectrum.
    Texture(Arc<super::SpectralTexture>),
    /// A spectrum varying over the surface as Mitsuba's textures do (bitmaps upsampled
    /// texel by texel, checkerboards), read at the first texture coordinate set without
    /// footprint filtering. Without a texture coordinate it is its mean.
    Pattern(Arc<super::Pattern>),
}

impl SceneSpectrum {
    /// The values at the package's wavelengths, as f32 lanes (finite: every variant is).
    pub fn at<const N: usize>(&self, wavelengths: &SampledWavelengths<N>) -> SampledSpectrum<N> {
        match self {
            SceneSpectrum::Constant(v) => SampledSpectrum::splat(saturating_f32(*v)),
            // Every lane at once (the sigmoid vectorizes): RGB colours are most of what
            // paths sample.
            SceneSpectrum::Rgb(rgb) => {
                let values = rgb.evaluate_lanes(wavelengths.lambdas());
                SampledSpectrum::from_fn(|i| values[i])
            }
            SceneSpectrum::Dense(dense) => {
                let values = dense.evaluate_lanes(wavelengths.lambdas());
                SampledSpectrum::from_fn(|i| values[i])
            }
            SceneSpectrum::Blackbody(b) => SampledSpectrum(b.evaluate_lanes(wavelengths.lambdas())),
            SceneSpectrum::Gaussian(g) => SampledSpectrum(g.evaluate_lanes(wavelengths.lambdas())),
            // The inner spectrum at every lane at once (light spectra are scaled tables
            // and blackbodies, evaluated per path), not the scaled sum per lane through
            // this enum twice; the scale multiplies in f64, as `evaluate` does.
            SceneSpectrum::Scaled(inner, k) => {
                let values = inner.at(wavelengths);
                SampledSpectrum::from_fn(|i| saturating_f32(f64::from(values[i]) * k))
            }
            _ => self.sample(wavelengths),
        }
    }

    /// The values at texture coordinates `at` (textures vary with them and are filtered
    /// over their footprint; nothing else varies).
    pub fn at_uv<const N: usize>(
        &self,
        at: impl Into<super::TexCoords>,
        wavelengths: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        match self {
            SceneSpectrum::Texture(t) => t.at(at, wavelengths),
            SceneSpectrum::Pattern(p) => p.at(at.into().uv[0], wavelengths),
            _ => self.at(wavelengths),
        }
    }

    /// The texture coordinate set a texture reads (None: the spectrum is no texture).
    pub fn tex_coord_set(&self) -> Option<usize> {
        match self {
            SceneSpectrum::Texture(t) => Some(t.set()),
            SceneSpectrum::Pattern(_) => Some(0),
            _ => None,
        }
    }

    /// Whether it varies over a surface (a texture or a pattern): a hit's value then
    /// depends on where it is, and cannot be cached per material.
    pub fn varies(&self) -> bool {
        matches!(self, SceneSpectrum::Texture(_) | SceneSpectrum::Pattern(_))
    }

    /// A named spectrum in the form the scene samples fastest: tables become 1 nm dense
    /// tables over their own range (zero outside), the rest stays analytic.
    pub fn from_named(named: NamedSpectrum) -> Result<Self, prism_spectrum::SpectrumError> {
        Ok(match named {
            NamedSpectrum::Blackbody(b) => Self::Blackbody(b),
            NamedSpectrum::Gaussian(g) => Self::Gaussian(g),
            NamedSpectrum::Constant(c) => Self::Constant(c.value()),
            NamedSpectrum::Table(t) => Self::dense(&t)?,
        })
    }

    /// `spectrum` tabulated at every whole nanometre of its table's range.
    pub fn dense(
        table: &prism_spectrum::spectra::PiecewiseLinear,
    ) -> Result<Self, prism_spectrum::SpectrumError> {
        let (first, last) = match (table.lambdas().first(), table.lambdas().last()) {
            (Some(a), Some(b)) => (a.floor() as i32, b.ceil() as i32),
            _ => {
                return Err(prism_spectrum::SpectrumError::InvalidTable(
                    "empty table".into(),
                ));
            }
        };
        Ok(Self::Dense(Arc::new(DenselySampled::from_spectrum(
            table, first, last,
        )?)))
    }

    /// Where the spectrum exceeds `fraction` of its maximum, searched at every nanometre
    /// over 200-2500 nm (None where it never does).
    pub fn extent(&self, fraction: f64) -> Option<(f32, f32)> {
        let threshold = fraction * self.max_value();
        let mut above = (200..=2500).filter(|&nm| self.evaluate(f64::from(nm)) > threshold);
        let first = above.next()?;
        let last = above.next_back().unwrap_or(first);
        Some((first as f32, last as f32))
    }

    /// A short description for reports (`prism info`).
    pub fn describe(&self) -> String {
        match self {
            SceneSpectrum::Constant(v) => format!("constant {v}"),
            SceneSpectrum::Rgb(_) => "upsampled RGB".into(),
            SceneSpectrum::Dense(d) => format!(
                "table {}-{} nm",
                d.first_nm(),
                d.first_nm() + d.values().len() as f64 - 1.0
            ),
            SceneSpectrum::Table(_) => "measured table".into(),
            SceneSpectrum::Blackbody(b) => format!("blackbody {} K", b.kelvin()),
            SceneSpectrum::Gaussian(g) => format!(
                "Gaussian band at {} nm (FWHM {:.1} nm)",
                g.center_nm(),
                g.sigma_nm() * 2.0 * (2.0 * std::f64::consts::LN_2).sqrt()
            ),
            SceneSpectrum::Cauchy(_) => "Cauchy index".into(),
            SceneSpectrum::Sellmeier(_) => "Sellmeier index".into(),
            SceneSpectrum::Scaled(s, _) => s.describe(),
            SceneSpectrum::Texture(t) if t.emits() => "emissive texture (upsampled RGB)".into(),
            SceneSpectrum::Texture(_) => "texture".into(),
            SceneSpectrum::Pattern(_) => "Mitsuba texture".into(),
        }
    }

    /// The mean over 360-830 nm at 5 nm steps: a cheap measure of power for choosing
    /// lights, not a colorimetric quantity.
    pub fn mean_visible(&self) -> f64 {
        self.mean_over(360.0, 830.0)
    }

    /// The mean over `lo`-`hi` nm at (about) 5 nm steps.
    pub fn mean_over(&self, lo: f64, hi: f64) -> f64 {
        let steps = ((hi - lo) / 5.0).round().max(1.0) as u32;
        (0..=steps)
            .map(|i| self.evaluate(lo + (hi - lo) * f64::from(i) / f64::from(steps)))
            .sum::<f64>()
            / f64::from(steps + 1)
    }
}

impl Spectrum for SceneSpectrum {
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        match self {
            SceneSpectrum::Constant(v) => *v,
            SceneSpectrum::Rgb(s) => s.evaluate(lambda_nm),
            SceneSpectrum::Dense(s) => s.evaluate(lambda_nm),
            SceneSpectrum::Blackbody(s) => s.evaluate(lambda_nm),
            SceneSpectrum::Table(s) => s.evaluate(lambda_nm),
            SceneSpectrum::Gaussian(s) => s.evaluate(lambda_nm),
            SceneSpectrum::Cauchy(s) => s.evaluate(lambda_nm),
            SceneSpectrum::Sellmeier(s) => s.evaluate(lambda_nm),
            SceneSpectrum::Scaled(s, k) => s.evaluate(lambda_nm) * k,
            SceneSpectrum::Texture(t) => t.evaluate(lambda_nm),
            SceneSpectrum::Pattern(p) => p.evaluate(lambda_nm),
        }
    }

    fn max_value(&self) -> f64 {
        match self {
            SceneSpectrum::Constant(v) => *v,
            SceneSpectrum::Rgb(s) => s.max_value(),
            SceneSpectrum::Dense(s) => s.max_value(),
            SceneSpectrum::Blackbody(s) => s.max_value(),
            SceneSpectrum::Table(s) => s.max_value(),
            SceneSpectrum::Gaussian(s) => s.max_value(),
            SceneSpectrum::Cauchy(s) => s.max_value(),
            SceneSpectrum::Sellmeier(s) => s.max_value(),
            SceneSpectrum::Scaled(s, k) => s.max_value() * k,
            SceneSpectrum::Texture(t) => t.max_value(),
            SceneSpectrum::Pattern(p) => p.max_value(),
        }
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use prism_spectrum::spectra::{Blackbody, DenselySampled, Gaussian};
    use prism_spectrum::{SampledWavelengths, Spectrum};
    use proptest::prelude::*;

    use super::SceneSpectrum;

    fn inner_spectra() -> Vec<SceneSpectrum> {
        let gaussian = Gaussian::new(365.0, 12.0, 1.0).unwrap();
        vec![
            SceneSpectrum::Blackbody(Blackbody::normalized(2700.0).unwrap()),
            SceneSpectrum::Gaussian(gaussian),
            SceneSpectrum::Dense(Arc::new(
                DenselySampled::from_spectrum(&gaussian, 300, 830).unwrap(),
            )),
            SceneSpectrum::Constant(0.25),
        ]
    }

    proptest! {
        /// A scaled spectrum sampled at a package is its definition (`evaluate`, the inner
        /// spectrum times the scale in f64) within what the inner's lanes promise (1.2e-5
        /// relative, or a subnormal step, scaled) and f32 rounding, saturated at f32::MAX;
        /// and always finite, for scales from 0 to f64::MAX (a constant alike) and
        /// wavelengths in and out of range.
        #[test]
        fn scaled_lanes_are_the_scaled_definition(
            lambdas in proptest::array::uniform4(prop_oneof![200.0f32..900.0, Just(300.0), Just(830.0), Just(1e-30)]),
            scale in prop_oneof![Just(0.0), Just(1.0), Just(1e-30), Just(1e30), Just(1e300), Just(f64::MAX), 1e-3f64..1e3],
        ) {
            let wavelengths = SampledWavelengths::new(lambdas, [0.01; 4]).unwrap();
            let constant = SceneSpectrum::Constant(scale);
            prop_assert!(constant.at(&wavelengths).0.iter().all(|v| v.is_finite()));
            for inner in inner_spectra() {
                let scaled = SceneSpectrum::Scaled(Arc::new(inner), scale);
                let lanes = scaled.at(&wavelengths);
                for (i, &l) in lambdas.iter().enumerate() {
                    let exact = scaled.evaluate(f64::from(l)).min(f64::from(f32::MAX));
                    let got = f64::from(lanes[i]);
                    prop_assert!(got.is_finite(), "{scaled:?} at {l}: {got}");
                    prop_assert!(
                        (got - exact).abs() <= 1.2e-5 * exact.abs() + 1e-37 * (scale + 1.0),
                        "{scaled:?} at {l}: {got} vs {exact}"
                    );
                }
            }
        }
    }
}
