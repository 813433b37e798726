//! What one sample adds to the film: its colour, and its spectral and energy sums when the
//! film keeps them. Camera samples and light-path splats are recorded alike, and added to
//! the film only once known to be finite.

use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use crate::SpectralBands;
use crate::film::camera_response::CameraResponse;
use crate::film::radiance::Radiance;

/// What turns a sample's spectrum into the film's colour: the CIE observer, or a camera's
/// response curves (raw channels) where the render has one.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sensor<'a> {
    pub observer: prism_spectrum::colorimetry::Observer,
    pub camera: Option<&'a CameraResponse>,
}

/// Photons per joule at 1 nm: a photon of wavelength l nm carries hc / (l 1e-9) J.
pub(crate) const PHOTONS_PER_JOULE_NM: f64 =
    1e-9 / (prism_spectrum::constants::PLANCK * prism_spectrum::constants::SPEED_OF_LIGHT);

/// The film's outputs besides colour.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Outputs {
    pub bands: Option<SpectralBands>,
    pub energy: bool,
    /// Whether the bands are kept per Stokes component.
    pub polarized: bool,
}

impl Outputs {
    /// Spectral sums per pixel.
    pub(crate) fn spectral_width(&self) -> usize {
        let components = if self.polarized { 4 } else { 1 };
        self.bands.map_or(0, |b| b.count() * components)
    }
}

/// One sample's value, accumulated over the radiance estimates its path reports.
#[derive(Debug, Clone, Default)]
pub(crate) struct SampleValue {
    /// Colour (XYZ, or a camera's raw channels).
    pub xyz: [f64; 3],
    /// Radiance integrated over wavelength, and photon radiance.
    pub energy: [f64; 2],
    /// (band, spectral radiance) pairs.
    pub binned: Vec<(usize, f64)>,
    /// The colour of the Stokes components S1, S2, S3 (polarized renders; `xyz` is S0's).
    pub stokes: [[f64; 3]; 3],
}

impl SampleValue {
    pub(crate) fn clear(&mut self) {
        self.xyz = [0.0; 3];
        self.energy = [0.0; 2];
        self.binned.clear();
        self.stokes = [[0.0; 3]; 3];
    }

    /// Adds the estimate `radiance` made with `lambdas` (a spectrum, or Stokes vectors
    /// whose intensity is the spectrum every other output reads).
    pub(crate) fn add<const N: usize>(
        &mut self,
        sensor: Sensor,
        outputs: Outputs,
        radiance: &impl Radiance<N>,
        lambdas: &SampledWavelengths<N>,
    ) {
        let colour = |spectrum: &SampledSpectrum<N>| match sensor.camera {
            Some(camera) => camera.channels(spectrum, lambdas),
            None => spectrum.to_xyz(lambdas, sensor.observer).to_array(),
        };
        let polarization = radiance.polarization();
        if let Some(polarization) = polarization {
            for (sum, component) in self.stokes.iter_mut().zip(polarization) {
                for (acc, v) in sum.iter_mut().zip(colour(component)) {
                    *acc += v;
                }
            }
        }
        let radiance = radiance.intensity();
        for (acc, v) in self.xyz.iter_mut().zip(colour(radiance)) {
            *acc += v;
        }
        if outputs.energy {
            // (1/C) sum_j L_j / pdf_j estimates the radiance integral; each lane's photons
            // are its energy times lambda / hc.
            for j in 0..N {
                let pdf = f64::from(lambdas.pdf(j));
                if pdf > 0.0 {
                    let e = f64::from(radiance[j]) / pdf / N as f64;
                    self.energy[0] += e;
                    self.energy[1] += e * f64::from(lambdas.lambda(j)) * PHOTONS_PER_JOULE_NM;
                }
            }
        }
        if let Some(bands) = outputs.bands {
            // Each lane estimates (1/C) L / pdf of its band's integral; per nm, divided by
            // the band's width.
            let scale = 1.0 / (N as f64 * bands.width());
            for j in 0..N {
                let pdf = f64::from(lambdas.pdf(j));
                if let (true, Some(band)) = (pdf > 0.0, bands.band_of(lambdas.lambda(j))) {
                    self.binned
                        .push((band, f64::from(radiance[j]) / pdf * scale));
                    // S1..S3's bands follow S0's in the pixel's spectral sums.
                    for (k, component) in polarization.into_iter().flatten().enumerate() {
                        self.binned.push((
                            band + (k + 1) * bands.count(),
                            f64::from(component[j]) / pdf * scale,
                        ));
                    }
                }
            }
        }
    }

    /// Whether every sum is finite (a sample that is not is rejected whole).
    pub(crate) fn finite(&self) -> bool {
        self.xyz.iter().all(|v| v.is_finite())
            && self.stokes.iter().flatten().all(|v| v.is_finite())
            && self.energy.iter().all(|v| v.is_finite())
            && self.binned.iter().all(|b| b.1.is_finite())
    }

    /// The factor the optional firefly clamp scales this sample by.
    pub(crate) fn clamp_scale(&self, clamp: Option<f64>) -> f64 {
        match clamp {
            Some(c) if self.xyz[1] > c => c / self.xyz[1],
            _ => 1.0,
        }
    }

    /// Adds `weight` times the value to one pixel's sums (`spectral`, `energy` and
    /// `stokes` empty when the film does not keep them).
    pub(crate) fn add_to(
        &self,
        weight: f64,
        xyz: &mut [f64; 3],
        spectral: &mut [f64],
        energy: Option<&mut [f64; 2]>,
        stokes: Option<&mut [[f64; 3]; 3]>,
    ) {
        for (acc, v) in xyz.iter_mut().zip(self.xyz) {
            *acc += v * weight;
        }
        if let Some(stokes) = stokes {
            for (acc, v) in stokes
                .iter_mut()
                .flatten()
                .zip(self.stokes.iter().flatten())
            {
                *acc += v * weight;
            }
        }
        for &(band, v) in &self.binned {
            spectral[band] += v * weight;
        }
        if let Some(e) = energy {
            e[0] += self.energy[0] * weight;
            e[1] += self.energy[1] * weight;
        }
    }
}
