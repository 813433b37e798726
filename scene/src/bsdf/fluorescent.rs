use glam::{Vec2, Vec3};
use prism_sampling::warp::{cosine_hemisphere, cosine_hemisphere_pdf};
use prism_sampling::wavelength::{ReradiationSampler, WavelengthRange};
use prism_spectrum::{SampledSpectrum, Spectrum};

use super::BsdfSample;

/// The re-radiation matrix of a fluorescent material on `bins` bins over `range`, row i
/// the incident bin, column o the outgoing one, each entry a density per nm of incident
/// wavelength (what [`ReradiationSampler`] samples):
///
/// M(l_i, l_o) = R(l_o) delta(l_i - l_o) + a(l_i) Q e(l_o) l_i / l_o,
///
/// with R the ordinary reflectance (the diagonal, spread over its bin as R / width), a the
/// absorbed fraction, e the emission spectrum normalized to unit area (a photon
/// distribution per nm), and Q the quantum yield (photons out per photon absorbed); the
/// factor l_i / l_o converts photons to energy (E = hc / l). Per unit incident energy at
/// l_i the re-emitted energy is a Q l_i E[1 / l_o], so energy is conserved when
/// R + a <= 1, which is required (an error otherwise) along with 0 <= Q <= 1.
pub fn reradiation_matrix(
    range: WavelengthRange,
    bins: usize,
    reflectance: &dyn Spectrum,
    absorption: &dyn Spectrum,
    emission: &dyn Spectrum,
    quantum_yield: f64,
) -> Result<Vec<f64>, crate::LoadError> {
    let mut m = fluorescence_matrix(
        range,
        bins,
        reflectance,
        absorption,
        emission,
        quantum_yield,
    )?;
    let (lo, hi) = (f64::from(range.min()), f64::from(range.max()));
    let width = (hi - lo) / bins as f64;
    for i in 0..bins {
        m[i * bins + i] += reflectance.evaluate(lo + (i as f64 + 0.5) * width) / width;
    }
    Ok(m)
}

/// The inelastic part of [`reradiation_matrix`] alone, a(l_i) Q e(l_o) l_i / l_o, with the
/// same checks (including R + a <= 1). Renderers that keep the elastic diagonal exact (a
/// delta in wavelength rather than a bin's width of blur) use this with R kept apart.
pub fn fluorescence_matrix(
    range: WavelengthRange,
    bins: usize,
    reflectance: &dyn Spectrum,
    absorption: &dyn Spectrum,
    emission: &dyn Spectrum,
    quantum_yield: f64,
) -> Result<Vec<f64>, crate::LoadError> {
    if bins == 0 {
        return Err(crate::LoadError::Fluorescence(
            "the matrix needs at least one bin".into(),
        ));
    }
    if !(0.0..=1.0).contains(&quantum_yield) {
        return Err(crate::LoadError::Fluorescence(format!(
            "quantum yield {quantum_yield} is outside [0, 1]"
        )));
    }
    let (lo, hi) = (f64::from(range.min()), f64::from(range.max()));
    let width = (hi - lo) / bins as f64;
    let centre = |k: usize| lo + (k as f64 + 0.5) * width;
    let e: Vec<f64> = (0..bins)
        .map(|k| emission.evaluate(centre(k)).max(0.0))
        .collect();
    let e_area: f64 = e.iter().sum::<f64>() * width;
    if quantum_yield > 0.0 && !(e_area > 0.0 && e_area.is_finite()) {
        return Err(crate::LoadError::Fluorescence(
            "the emission spectrum is zero over the range".into(),
        ));
    }
    let mut m = vec![0.0; bins * bins];
    for i in 0..bins {
        let (r, a) = (
            reflectance.evaluate(centre(i)),
            absorption.evaluate(centre(i)),
        );
        if !(r.is_finite() && a.is_finite() && (0.0..=1.0).contains(&r) && (0.0..=1.0).contains(&a))
        {
            return Err(crate::LoadError::Fluorescence(format!(
                "reflectance {r} or absorption {a} at {:.1} nm is outside [0, 1]",
                centre(i)
            )));
        }
        if r + a > 1.0 + 1e-9 {
            return Err(crate::LoadError::Fluorescence(format!(
                "reflectance {r} plus absorption {a} exceeds 1 at {:.1} nm (energy would be created)",
                centre(i)
            )));
        }
        if quantum_yield > 0.0 {
            for o in 0..bins {
                m[i * bins + o] += a * quantum_yield * (e[o] / e_area) * centre(i) / centre(o);
            }
        }
    }
    Ok(m)
}

/// A sampled direction and, per lane, the incident wavelength the light came in at.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FluorescentSample<const N: usize> {
    /// The direction (Lambertian), with f = M(l_i, l_o) / pi per lane and the direction's
    /// density.
    pub bsdf: BsdfSample<N>,
    /// The incident wavelength per lane (the path continues at these).
    pub lambda_in: [f32; N],
    /// The density of each lane's incident wavelength, per nm.
    pub lambda_pdf: [f32; N],
}

/// A Lambertian surface that re-radiates: light arriving at l_i leaves at l_o with the
/// re-radiation matrix's density. Camera paths know l_o (their lanes' wavelengths) and
/// sample l_i from the matrix's column (fluorescent sampling).
#[derive(Debug, Clone, Copy)]
pub struct FluorescentDiffuse<'a> {
    /// The matrix's sampler.
    pub sampler: &'a ReradiationSampler,
}

impl FluorescentDiffuse<'_> {
    /// f(l_i, l_o) / pi-weighted value of the BSDF for one wavelength pair.
    pub fn value(&self, lambda_in: f32, lambda_out: f32) -> f32 {
        (self.sampler.value(lambda_in, lambda_out) / std::f64::consts::PI) as f32
    }

    /// A cosine direction and, for each lane, an incident wavelength given the lane's
    /// outgoing one. A lane whose wavelength nothing re-radiates into gets f = 0 and
    /// density 0. The estimator weight f cos / (pdf_dir pdf_lambda) of a live lane is the
    /// matrix column's integral.
    pub fn sample<const N: usize>(
        &self,
        wo: Vec3,
        u: Vec2,
        u_lambda: f64,
        lambda_out: &[f32; N],
    ) -> Option<FluorescentSample<N>> {
        if wo.z == 0.0 || !wo.is_finite() {
            return None;
        }
        let mut wi = cosine_hemisphere(u);
        if wo.z < 0.0 {
            wi.z = -wi.z;
        }
        let pdf_dir = cosine_hemisphere_pdf(Vec3::new(wi.x, wi.y, wi.z.abs()));
        if pdf_dir == 0.0 {
            return None;
        }
        let mut lambda_in = *lambda_out;
        let mut lambda_pdf = [0.0f32; N];
        let mut f = SampledSpectrum::splat(0.0);
        let mut pdf = [0.0f32; N];
        for lane in 0..N {
            if let Some(s) = self.sampler.sample_incident(lambda_out[lane], u_lambda) {
                lambda_in[lane] = s.lambda;
                lambda_pdf[lane] = s.pdf;
                f[lane] = self.value(s.lambda, lambda_out[lane]);
                pdf[lane] = pdf_dir;
            }
        }
        Some(FluorescentSample {
            bsdf: BsdfSample::smooth(wi, f, pdf),
            lambda_in,
            lambda_pdf,
        })
    }
}
