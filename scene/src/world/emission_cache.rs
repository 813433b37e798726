use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use super::light_choice::Weights;
use super::{SceneSpectrum, TexCoords};

/// How many of a scene's emission spectra a cache holds (the first ones; the rest are
/// evaluated every time). Scenes have a handful of emitting materials.
const SLOTS: usize = 8;

/// The emission spectra of triangle lights evaluated at one set of wavelengths, each at
/// most once. A path evaluates its lights at the same wavelengths at every vertex (next-event
/// estimation, then the emitter a bounce hits), and an RGB illuminant costs a sigmoid and
/// an illuminant table per lane: measured, these repeats were 6% of the Cornell box's
/// instructions. Values are keyed by the wavelengths themselves, so a cache that outlives
/// a change of wavelengths (fluorescence) refills instead of answering wrongly, and what
/// it returns is bit for bit what evaluating would.
#[derive(Debug, Clone)]
pub struct EmissionCache<const N: usize> {
    lambdas: [f32; N],
    filled: u32,
    values: [SampledSpectrum<N>; SLOTS],
    /// Lambertian materials' constant reflectances at these wavelengths, by material
    /// index (the first `SLOTS` materials): a path meets the same few walls again and
    /// again, and each evaluation is a sigmoid per lane (measured: 7% of the Cornell
    /// box's time went to evaluating reflectances).
    reflectance_filled: u32,
    reflectances: [SampledSpectrum<N>; SLOTS],
    /// The lights' choice weights at these wavelengths, once computed (scenes whose
    /// lights differ in spectrum; see `light_choice`).
    pub(crate) choice_weights: Option<Weights>,
}

impl<const N: usize> Default for EmissionCache<N> {
    fn default() -> Self {
        Self {
            lambdas: [f32::NAN; N],
            filled: 0,
            values: [SampledSpectrum::splat(0.0); SLOTS],
            reflectance_filled: 0,
            reflectances: [SampledSpectrum::splat(0.0); SLOTS],
            choice_weights: None,
        }
    }
}

impl<const N: usize> EmissionCache<N> {
    /// An empty cache.
    pub fn new() -> Self {
        Self::default()
    }

    /// Empties the cache if `wavelengths` are not the ones its values were computed at.
    pub(crate) fn refresh(&mut self, wavelengths: &SampledWavelengths<N>) {
        // Bitwise: the NaN the cache starts with never equals a wavelength.
        if self.lambdas.map(f32::to_bits) != wavelengths.lambdas().map(f32::to_bits) {
            self.lambdas = *wavelengths.lambdas();
            self.filled = 0;
            self.reflectance_filled = 0;
            self.choice_weights = None;
        }
    }

    /// Emission spectrum number `index` of the scene's `spectra`, at `wavelengths`, at
    /// texture coordinates `at` of the emitter (an emissive texture varies with them, and
    /// is looked up every time).
    pub(crate) fn get(
        &mut self,
        spectra: &[SceneSpectrum],
        index: u32,
        wavelengths: &SampledWavelengths<N>,
        at: &TexCoords,
    ) -> SampledSpectrum<N> {
        let slot = index as usize;
        let spectrum = &spectra[slot];
        if let SceneSpectrum::Texture(texture) = spectrum {
            return texture.at(*at, wavelengths);
        }
        if slot >= SLOTS {
            return spectrum.at(wavelengths);
        }
        self.refresh(wavelengths);
        if self.filled & (1 << slot) == 0 {
            self.values[slot] = spectrum.at(wavelengths);
            self.filled |= 1 << slot;
        }
        self.values[slot]
    }

    /// Material number `material`'s reflectance `spectrum` (not a texture) at
    /// `wavelengths`, evaluated at most once while the wavelengths stay (None for materials
    /// past the cache's slots: the caller evaluates).
    pub(crate) fn reflectance(
        &mut self,
        material: u32,
        spectrum: &SceneSpectrum,
        wavelengths: &SampledWavelengths<N>,
    ) -> Option<SampledSpectrum<N>> {
        let slot = material as usize;
        if slot >= SLOTS {
            return None;
        }
        self.refresh(wavelengths);
        if self.reflectance_filled & (1 << slot) == 0 {
            self.reflectances[slot] = spectrum.at(wavelengths);
            self.reflectance_filled |= 1 << slot;
        }
        Some(self.reflectances[slot])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn answers_what_evaluating_would_and_refills_when_wavelengths_change() {
        let spectra: Vec<SceneSpectrum> = (0..SLOTS + 2)
            .map(|k| {
                SceneSpectrum::Gaussian(
                    prism_spectrum::spectra::Gaussian::new(400.0 + 30.0 * k as f64, 20.0, 1.0)
                        .unwrap(),
                )
            })
            .collect();
        let a = SampledWavelengths::new([450.0, 550.0, 650.0, 700.0], [0.01; 4]).unwrap();
        let b = SampledWavelengths::new([451.0, 550.0, 650.0, 700.0], [0.01; 4]).unwrap();
        let mut cache = EmissionCache::new();
        for _ in 0..2 {
            for wavelengths in [&a, &b, &a] {
                for (k, s) in spectra.iter().enumerate() {
                    let cached = cache.get(&spectra, k as u32, wavelengths, &TexCoords::default());
                    assert_eq!(cached, s.at(wavelengths), "spectrum {k}");
                }
            }
        }
    }

    #[test]
    fn reflectances_are_what_evaluating_gives_at_the_current_wavelengths() {
        let spectra: Vec<SceneSpectrum> = (0..SLOTS + 1)
            .map(|k| {
                SceneSpectrum::Gaussian(
                    prism_spectrum::spectra::Gaussian::new(420.0 + 25.0 * k as f64, 30.0, 0.8)
                        .unwrap(),
                )
            })
            .collect();
        let a = SampledWavelengths::new([450.0, 550.0, 650.0, 700.0], [0.01; 4]).unwrap();
        let b = SampledWavelengths::new([450.0, 551.0, 650.0, 700.0], [0.01; 4]).unwrap();
        let mut cache = EmissionCache::new();
        for wavelengths in [&a, &b, &a, &a] {
            for (k, s) in spectra.iter().enumerate() {
                match cache.reflectance(k as u32, s, wavelengths) {
                    Some(r) => assert_eq!(r, s.at(wavelengths), "material {k}"),
                    None => assert!(k >= SLOTS, "material {k} has a slot"),
                }
            }
        }
    }
}
