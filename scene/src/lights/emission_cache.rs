use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use super::EnvironmentMap;
use super::light_choice::Weights;
use crate::medium::{Medium, MediumPoint};
use crate::textures::{SceneSpectrum, TexCoords};

/// How many of a scene's emission spectra a cache holds (the first ones; the rest are
/// evaluated every time). Scenes have a handful of emitting materials.
const SLOTS: usize = 8;

/// The emission spectra of triangle lights evaluated at one set of wavelengths, each at
/// most once. A path evaluates its lights at the same wavelengths at every vertex (next-event
/// estimation, then the emitter a bounce hits), and an RGB illuminant costs a sigmoid and
/// an illuminant table per lane: measured, these repeats were a noticeable share of the
/// Cornell box's instructions. Values are keyed by the wavelengths themselves, so a cache
/// that outlives a change of wavelengths (fluorescence) refills instead of answering
/// wrongly, and what it returns is bit for bit what evaluating would.
#[derive(Debug, Clone)]
pub struct EmissionCache<const N: usize> {
    lambdas: [f32; N],
    emission: Slots<SampledSpectrum<N>>,
    /// Lambertian materials' constant reflectances at these wavelengths, by material
    /// index (the first `SLOTS` materials): a path meets the same few walls again and
    /// again, and each evaluation is a sigmoid per lane (measured: evaluating reflectances
    /// was a noticeable share of the Cornell box's time).
    reflectances: Slots<SampledSpectrum<N>>,
    /// The lights' choice weights at these wavelengths, once computed (scenes whose
    /// lights differ in spectrum; see `light_choice`).
    pub(crate) choice_weights: Option<Weights>,
    /// Media's coefficients at these wavelengths ([`Medium::at`]), by medium index (the
    /// first `SLOTS` media): a path through a medium evaluates them for every flight and
    /// every shadow ray, two to four spectra each (measured: a noticeable share of the
    /// medium box's instructions).
    media: Slots<MediumPoint<N>>,
    /// The environment image's illuminant at these wavelengths
    /// ([`EnvironmentMap::white`]): every lookup of the image multiplies by it (measured:
    /// evaluating it was a noticeable share of the textured sky scene's instructions).
    ///
    /// [`EnvironmentMap::white`]: super::EnvironmentMap::white
    environment_white: Option<[f32; N]>,
}

impl<const N: usize> Default for EmissionCache<N> {
    fn default() -> Self {
        Self {
            lambdas: [f32::NAN; N],
            emission: Slots::default(),
            reflectances: Slots::default(),
            choice_weights: None,
            media: Slots::default(),
            environment_white: None,
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
            self.emission.filled = 0;
            self.reflectances.filled = 0;
            self.choice_weights = None;
            self.media.filled = 0;
            self.environment_white = None;
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
        self.emission.get(slot, || spectrum.at(wavelengths))
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
        Some(self.reflectances.get(slot, || spectrum.at(wavelengths)))
    }

    /// `map`'s [`EnvironmentMap::white`] at `wavelengths`, evaluated at most once while
    /// the wavelengths stay (a scene has one environment).
    pub(crate) fn environment_white(
        &mut self,
        map: &EnvironmentMap,
        wavelengths: &SampledWavelengths<N>,
    ) -> [f32; N] {
        self.refresh(wavelengths);
        *self
            .environment_white
            .get_or_insert_with(|| map.white(wavelengths))
    }

    /// Medium number `index` (`medium`)'s coefficients at `wavelengths`, evaluated at most
    /// once while the wavelengths stay: bit for bit [`Medium::at`]'s.
    pub fn medium(
        &mut self,
        index: u32,
        medium: &Medium,
        wavelengths: &SampledWavelengths<N>,
    ) -> MediumPoint<N> {
        let slot = index as usize;
        if slot >= SLOTS {
            return medium.at(wavelengths);
        }
        self.refresh(wavelengths);
        self.media.get(slot, || medium.at(wavelengths))
    }
}

/// Values at the cache's wavelengths, by slot, each computed once until the cache refills
/// (`filled`: a bit per slot holding a value).
#[derive(Debug, Clone, Default)]
struct Slots<V> {
    filled: u32,
    values: [V; SLOTS],
}

impl<V: Copy> Slots<V> {
    /// Slot `slot` (below `SLOTS`): `compute`'s value, computed the first time.
    fn get(&mut self, slot: usize, compute: impl FnOnce() -> V) -> V {
        if self.filled & (1 << slot) == 0 {
            self.values[slot] = compute();
            self.filled |= 1 << slot;
        }
        self.values[slot]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `count` Gaussian spectra centred from `first` nm on, `step` apart.
    fn gaussians(count: usize, first: f64, step: f64, width: f64, peak: f64) -> Vec<SceneSpectrum> {
        (0..count)
            .map(|k| {
                SceneSpectrum::Gaussian(
                    prism_spectrum::spectra::Gaussian::new(first + step * k as f64, width, peak)
                        .unwrap(),
                )
            })
            .collect()
    }

    #[test]
    fn answers_what_evaluating_would_and_refills_when_wavelengths_change() {
        let spectra = gaussians(SLOTS + 2, 400.0, 30.0, 20.0, 1.0);
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
        let spectra = gaussians(SLOTS + 1, 420.0, 25.0, 30.0, 0.8);
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

    /// Media's coefficients are bit for bit `Medium::at`'s at the current wavelengths,
    /// past the slots too, and follow a change of wavelengths (a dye's re-emission).
    #[test]
    fn media_are_what_evaluating_gives_at_the_current_wavelengths() {
        use crate::medium::Phase;
        let spectra = gaussians(2 * (SLOTS + 1), 410.0, 20.0, 40.0, 3.0);
        let media: Vec<Medium> = spectra
            .chunks(2)
            .map(|pair| {
                let phase = Phase::henyey_greenstein(0.3).unwrap();
                Medium::new(
                    pair[0].clone(),
                    pair[1].clone(),
                    phase,
                    Some(pair[1].clone()),
                )
                .unwrap()
            })
            .collect();
        let a = SampledWavelengths::new([450.0, 550.0, 650.0, 700.0], [0.01; 4]).unwrap();
        let b = SampledWavelengths::new([450.0, 550.0, 652.0, 700.0], [0.01; 4]).unwrap();
        let mut cache = EmissionCache::new();
        for wavelengths in [&a, &b, &a, &a] {
            for (k, m) in media.iter().enumerate() {
                assert_eq!(
                    cache.medium(k as u32, m, wavelengths),
                    m.at(wavelengths),
                    "medium {k}"
                );
            }
        }
    }
}
