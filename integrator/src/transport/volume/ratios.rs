//! The ratios that weigh a volumetric path's light by spectral and light-sampling MIS.
//!
//! A path through media is sampled by its hero wavelength's majorant and collision
//! probabilities. Its density had another lane been the hero differs wherever the medium's
//! coefficients differ across the package, so each lane k keeps `r_u[k]` = q_k / q_0, the
//! density of the path sampled unidirectionally with lane k as hero over its density with
//! the actual hero, and `r_l[k]`, the same for the path's end sampled by next-event
//! estimation (light sampling, then ratio tracking), over q_0 as well. These are the r_u /
//! r_l of pbrt-v4's `VolPathIntegrator` (*PBR* 4th ed. §14.2.3, after Miller, Georgiev and
//! Jarosz 2019, §5). The balance heuristic over every lane as hero and both strategies then
//! divides a lane's contribution f_j / q_0 by the package's balance density of those ratios
//! ([`WavelengthPackage::balance_pdf`], which folds in how the package's wavelengths were
//! drawn).

use prism_sampling::wavelength::WavelengthPackage;
use prism_spectrum::SampledSpectrum;

/// r_u and r_l of a path so far (both one at the camera).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ratios<const N: usize> {
    /// Unidirectional sampling's density per lane as hero, over the hero's.
    pub r_u: SampledSpectrum<N>,
    /// Light sampling's density per lane as hero, over the hero's unidirectional one,
    /// without the light's own density (multiplied in where a light is met).
    pub r_l: SampledSpectrum<N>,
}

impl<const N: usize> Ratios<N> {
    pub(crate) fn one() -> Self {
        Self {
            r_u: SampledSpectrum::splat(1.0),
            r_l: SampledSpectrum::splat(1.0),
        }
    }

    /// Multiplies both ratios by `factor` (a stretch of medium both strategies cross alike).
    #[inline]
    pub(crate) fn scale(&mut self, factor: &SampledSpectrum<N>) {
        self.r_u *= *factor;
        self.r_l *= *factor;
    }
}

/// The factor per lane that turns a contribution carried with the hero's density into the
/// balance-heuristic estimate: pdf_j / balance_pdf(r)_j, with `pdf` the package's own
/// densities (by which the film divides), `r` the sum of the competing strategies' ratios.
/// Zero where the balance density is zero or not finite (no strategy could have made the
/// lane's path).
#[inline]
pub(crate) fn spectral_weight<const N: usize>(
    package: &WavelengthPackage<N>,
    r: &SampledSpectrum<N>,
) -> SampledSpectrum<N> {
    let balance = package.balance_pdf(&r.0);
    SampledSpectrum::from_fn(|j| {
        let b = balance[j];
        let w = package.pdf[j] / b;
        if b > 0.0 && w.is_finite() { w } else { 0.0 }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_sampling::wavelength::{PackageScheme, WavelengthDistribution, WavelengthRange};

    /// Where every lane's density is the hero's (r = 1: no chromatic medium on the path),
    /// the weight is 1 per lane: the surface path tracer's estimate.
    #[test]
    fn equal_ratios_weigh_one() {
        let d = WavelengthDistribution::visible(WavelengthRange::VISIBLE);
        for scheme in [PackageScheme::HeroRotation, PackageScheme::Stratified] {
            let p = WavelengthPackage::<4>::sample(&d, 0.37, scheme);
            let w = spectral_weight(&p, &SampledSpectrum::splat(1.0));
            for j in 0..4 {
                assert!((w[j] - 1.0).abs() < 1e-5, "{scheme:?} lane {j}: {}", w[j]);
            }
        }
    }

    /// The weights are the balance heuristic: with rotation they are p_j / sum_k p_k r_k
    /// times C, so a lane whose strategy is twice as likely weighs everyone down alike.
    #[test]
    fn weights_are_the_balance_heuristic() {
        let d = WavelengthDistribution::visible(WavelengthRange::VISIBLE);
        let p = WavelengthPackage::<2>::sample(&d, 0.2, PackageScheme::HeroRotation);
        let r = SampledSpectrum([1.0, 3.0]);
        let w = spectral_weight(&p, &r);
        let sum = f64::from(p.hero_pdf[0]) + 3.0 * f64::from(p.hero_pdf[1]);
        for j in 0..2 {
            let expected = f64::from(p.pdf[j]) * 2.0 / sum;
            assert!((f64::from(w[j]) - expected).abs() < 1e-5 * expected);
        }
        // No strategy at all: no weight, and no NaN.
        let w = spectral_weight(&p, &SampledSpectrum::splat(0.0));
        assert_eq!(w.0, [0.0, 0.0]);
        let w = spectral_weight(&p, &SampledSpectrum::splat(f32::NAN));
        assert_eq!(w.0, [0.0, 0.0]);
    }
}
