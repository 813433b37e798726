//! A fluorescent medium's dye: a fluorescein or quinine solution glowing under ultraviolet
//! light. What it absorbs at l_i (`absorption`, per unit length, part of the extinction) it
//! re-emits, isotropically, as photons of the `reemission` spectrum's shape with the
//! quantum yield Q, so that per unit length light at l_o gains
//!
//! integral over l_i of K(l_i, l_o) L(l_i) dl_i,  K(l_i, l_o) = sigma_f(l_i) Q e(l_o) l_i / l_o,
//!
//! (e normalized to unit area; l_i / l_o turns photons into energy), the surfaces'
//! re-radiation matrix (`crate::bsdf::fluorescence_matrix`) with an absorption coefficient
//! in place of an absorbed fraction. A camera path at l_o meets it as an in-scattering
//! coefficient sigma_fo(l_o) = integral of K over l_i, and continues at an l_i drawn from
//! K's column (A. Wilkie et al.'s and ART's fluorescent media; neither pbrt-v4 nor Mitsuba
//! 3 has them).

use prism_sampling::distribution::PiecewiseConstant1D;
use prism_sampling::wavelength::{ReradiationSampler, WavelengthRange};
use prism_spectrum::Spectrum;

use crate::textures::SceneSpectrum;

/// The dye of a fluorescent medium.
#[derive(Debug, Clone)]
pub struct Fluorescence {
    /// sigma_f: the dye's absorption coefficient, which the extinction includes.
    absorption: SceneSpectrum,
    /// K / scale, binned (each entry at most 1 per nm, as the matrix's checks want).
    kernel: ReradiationSampler,
    /// The factor that makes `kernel` K (the largest absorption coefficient).
    scale: f64,
    /// Where the scene's lights put their light, times what the dye re-emits of it, per
    /// incident wavelength: the second strategy for incident wavelengths, as at
    /// fluorescent surfaces (None until the scene sets it, or where the lights miss the
    /// dye's absorption).
    guide: Option<PiecewiseConstant1D>,
}

impl Fluorescence {
    /// A dye absorbing `absorption` (per unit length, finite and >= 0), re-emitting the
    /// shape of `reemission` with quantum yield `quantum_yield` in [0, 1], tabulated in
    /// `bins` bins over `range`.
    pub fn new(
        absorption: SceneSpectrum,
        reemission: &dyn Spectrum,
        quantum_yield: f64,
        range: WavelengthRange,
        bins: usize,
    ) -> Result<Self, String> {
        let (lo, hi) = (f64::from(range.min()), f64::from(range.max()));
        let width = (hi - lo) / bins.max(1) as f64;
        let mut scale = 0.0f64;
        for k in 0..bins {
            let a = absorption.evaluate(lo + (k as f64 + 0.5) * width);
            if !(a.is_finite() && a >= 0.0) {
                return Err(format!("absorption {a} must be finite and >= 0"));
            }
            scale = scale.max(a);
        }
        if scale <= 0.0 {
            return Err("absorption is zero over the range: the dye absorbs nothing".into());
        }
        let normalized =
            SceneSpectrum::Scaled(std::sync::Arc::new(absorption.clone()), 1.0 / scale);
        let matrix = crate::bsdf::fluorescence_matrix(
            range,
            bins,
            &prism_spectrum::spectra::Constant::new(0.0).map_err(|e| e.to_string())?,
            &normalized,
            reemission,
            quantum_yield,
        )
        .map_err(|e| e.to_string())?;
        let kernel = ReradiationSampler::new(range, bins, &matrix).map_err(|e| e.to_string())?;
        Ok(Self {
            absorption,
            kernel,
            scale,
            guide: None,
        })
    }

    /// The dye's absorption coefficient.
    pub fn absorption(&self) -> &SceneSpectrum {
        &self.absorption
    }

    /// The wavelengths its kernel covers, nm.
    pub fn range_nm(&self) -> (f32, f32) {
        self.kernel.range_nm()
    }

    /// sigma_fo(`lambda_out`): what light of every wavelength adds to `lambda_out` per unit
    /// length and unit radiance.
    #[inline]
    pub fn in_scattering(&self, lambda_out: f32) -> f32 {
        (self.scale * self.kernel.incident_integral(lambda_out)) as f32
    }

    /// What the dye re-emits, at every wavelength, of light absorbed at `lambda_in`, per
    /// unit of the largest absorption coefficient (a guide's weight).
    pub fn reemitted_fraction(&self, lambda_in: f32) -> f64 {
        self.kernel.outgoing_integral(lambda_in)
    }

    /// Sets where the scene's light is for the dye (see [`Fluorescence::sample_incident`]).
    pub fn set_guide(&mut self, guide: Option<PiecewiseConstant1D>) {
        self.guide = guide;
    }

    /// An incident wavelength for light leaving at `lambda_out`, drawn with `u`, and its
    /// weight K / (pdf sigma_fo(`lambda_out`)): from K's column (weight 1), or where the
    /// lights shine, by one-sample MIS between the column and the guide with the balance
    /// heuristic. None where nothing re-emits at `lambda_out`.
    #[inline]
    pub fn sample_incident(&self, lambda_out: f32, u: f64) -> Option<(f32, f32)> {
        let Some(guide) = &self.guide else {
            return self
                .kernel
                .sample_incident(lambda_out, u)
                .map(|s| (s.lambda, 1.0));
        };
        let lambda = if u < 0.5 {
            self.kernel.sample_incident(lambda_out, 2.0 * u)?.lambda
        } else {
            if self.kernel.incident_integral(lambda_out) <= 0.0 {
                return None;
            }
            guide.sample(2.0 * u - 1.0).value as f32
        };
        let p_column = self.kernel.pdf_incident(lambda, lambda_out);
        let p = 0.5 * p_column + 0.5 * guide.pdf(f64::from(lambda)) as f32;
        Some((lambda, if p > 0.0 { p_column / p } else { 0.0 }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_spectrum::spectra::{Extrapolation, PiecewiseLinear};

    /// A dye of quantum yield 1 whose absorption is C e(l) / l re-emits at each wavelength
    /// what it absorbs there under light of 1 at every wavelength.
    #[test]
    fn balanced_dye_re_emits_what_it_absorbs() {
        let e = |nm: f64| (-0.5 * ((nm - 520.0) / 34.0).powi(2)).exp();
        let nodes: Vec<f64> = (300..=830).step_by(2).map(f64::from).collect();
        let table = |f: &dyn Fn(f64) -> f64| {
            SceneSpectrum::Table(std::sync::Arc::new(
                PiecewiseLinear::new(
                    nodes.clone(),
                    nodes.iter().map(|&x| f(x)).collect(),
                    Extrapolation::Zero,
                )
                .unwrap(),
            ))
        };
        let dye = Fluorescence::new(
            table(&|nm| 1500.0 * e(nm) / nm),
            &table(&e),
            1.0,
            WavelengthRange::new(300.0, 830.0).unwrap(),
            265,
        )
        .unwrap();
        for nm in [455.0f32, 485.0, 520.0, 575.0, 605.0] {
            let absorbed = dye.absorption().evaluate(f64::from(nm));
            let added = f64::from(dye.in_scattering(nm));
            assert!(
                (added - absorbed).abs() < 0.02 * absorbed,
                "{nm} nm: {added} vs {absorbed}"
            );
        }
    }
}
