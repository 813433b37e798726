//! A fluorescent vertex: the wavelength each lane's light arrived at.

use prism_sampling::stream::{SampleStream, SobolStream};
use prism_sampling::wavelength::ReradiationSampler;
use prism_scene::bsdf::Diffuse;
use prism_scene::bsdf::TransportMode;
use prism_scene::world::{Bsdf, EmissionCache, Hit, Material, SceneSpectrum};
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use super::walk::Walk;
use crate::transport::context::Integrator;
use crate::transport::throughput::Throughput;

impl<'a> Integrator<'a> {
    /// The BSDF a camera path meets at `hit`: at a fluorescent surface (in scenes with
    /// re-radiation, `FLUORESCENCE`) each lane first picks the wavelength its light arrived
    /// at ([`Integrator::fluoresce`], drawing from `here`); any other surface is the scene's
    /// BSDF at the path's wavelengths. None where no wavelength is left.
    #[inline(always)]
    pub(crate) fn vertex_bsdf<const N: usize, const FLUORESCENCE: bool, T: Throughput<N>>(
        &self,
        hit: &Hit,
        here: &mut SobolStream,
        walk: &mut Walk<N, T>,
        emission: &mut EmissionCache<N>,
    ) -> Option<Bsdf<'a, N>> {
        match self.scene.material(hit) {
            Material::Fluorescent {
                reflectance,
                reradiation,
            } if FLUORESCENCE => self.fluoresce(hit, reflectance, reradiation, here, walk),
            _ => Some(self.scene.bsdf_cached(
                hit,
                &walk.transport,
                TransportMode::Radiance,
                emission,
            )),
        }
    }

    /// A fluorescent vertex of reflectance `reflectance` and re-radiation `reradiation`
    /// at `hit`: each lane of `walk` picks the wavelength its light arrived at
    /// ([`Integrator::reradiated`], drawn from `here`), a phosphor's lanes also when
    /// ([`Integrator::delay`]), and the walk carries on with those wavelengths and weights. The
    /// surface is Lambertian either way: its BSDF, or None where no wavelength is left.
    #[inline]
    pub(crate) fn fluoresce<const N: usize, T: Throughput<N>>(
        &self,
        hit: &Hit,
        reflectance: &SceneSpectrum,
        reradiation: &ReradiationSampler,
        here: &mut SobolStream,
        walk: &mut Walk<N, T>,
    ) -> Option<Bsdf<'static, N>> {
        let u_wavelength = here.next_1d();
        let (incident, mut weights, reemitted) =
            self.reradiated(hit, reflectance, reradiation, &walk.transport, u_wavelength);
        if let (Some(times), Some(decay)) = (&mut walk.times, self.scene.decay_at(hit)) {
            self.delay(decay, here.next_1d(), &reemitted, times, &mut weights);
        }
        walk.beta.scale(weights);
        walk.transport = SampledWavelengths::new(incident, *walk.transport.pdfs()).ok()?;
        Some(Bsdf::Diffuse(Diffuse::new(SampledSpectrum::splat(1.0))))
    }

    /// At a fluorescent vertex of reflectance `reflectance` and re-radiation `reradiation`,
    /// the wavelength each lane's light arrived at, the lane's weight, and whether it was
    /// re-emitted (drawn with `u_wavelength`): unchanged with probability R / (R + F)
    /// (weight R + F), else from the re-radiation column F or the lights' spectra, one-sample
    /// MIS with the balance heuristic (weight (R + F) / F * M / p_mix).
    #[inline]
    fn reradiated<const N: usize>(
        &self,
        hit: &Hit,
        reflectance: &SceneSpectrum,
        reradiation: &ReradiationSampler,
        transport: &SampledWavelengths<N>,
        u_wavelength: f32,
    ) -> ([f32; N], SampledSpectrum<N>, [bool; N]) {
        let guide = self.scene.light_wavelengths(hit);
        let r = reflectance.at_uv(hit.tex, transport);
        let mut incident = *transport.lambdas();
        let mut weights = SampledSpectrum::splat(1.0);
        let mut reemitted = [false; N];
        for j in 0..N {
            let out = transport.lambda(j);
            let f = reradiation.incident_integral(out) as f32;
            let total = r[j] + f;
            let mut weight = total;
            if total > 0.0 && f > 0.0 && u_wavelength * total >= r[j] {
                let u = ((u_wavelength * total - r[j]) / f).min(0.999_999_9);
                let lambda = match guide {
                    None => reradiation
                        .sample_incident(out, f64::from(u))
                        .map(|s| s.lambda),
                    Some(_) if u < 0.5 => reradiation
                        .sample_incident(out, f64::from(2.0 * u))
                        .map(|s| s.lambda),
                    Some(g) => Some(g.sample(f64::from(2.0 * u - 1.0)).value as f32),
                };
                weight = match lambda {
                    Some(l) => {
                        let p_column = reradiation.pdf_incident(l, out);
                        let p = match guide {
                            None => p_column,
                            Some(g) => 0.5 * p_column + 0.5 * g.pdf(f64::from(l)) as f32,
                        };
                        incident[j] = l;
                        reemitted[j] = true;
                        if p > 0.0 {
                            total / f * reradiation.value(l, out) as f32 / p
                        } else {
                            0.0
                        }
                    }
                    None => 0.0,
                };
            }
            weights[j] = weight;
        }
        (incident, weights, reemitted)
    }
}
