//! How next-event estimation chooses a light when the scene's lights differ in spectrum:
//! in proportion to each light's power at the path's own wavelengths.
//!
//! Choosing by power over the visible range (pbrt-v4's `PowerLightSampler`, *PBR* 4th ed.
//! §12.6.2; Mitsuba 3 likewise) suits an average path, but a spectral path carries a few
//! wavelengths, and a light whose spectrum is zero there brings that path nothing: the
//! effects stage's 365 nm tube drew a share of the shadow rays of paths that carry only
//! visible light, and past a fluorescent surface (whose path carries the ultraviolet
//! wavelengths it absorbs) the visible lamps drew theirs. Here each light is weighted by
//! its extent (area, solid angle) times the sum of its spectrum over the path's
//! wavelengths.
//!
//! Why this stays unbiased and keeps hero-wavelength MIS: the choice depends on the set of
//! wavelengths the path carries, the same for every lane and for every lane as the hero
//! (rotation maps the set onto itself), and a light that emits nothing at any of them
//! contributes nothing to the path. `Scene::light_pdf` reports the same probability, from
//! the same cached weights, for MIS with BSDF sampling.
//!
//! Lights whose spectra differ only by a factor (the triangles of one emissive material,
//! lamps of one colour at different intensities) form one group, chosen among by extent
//! in units of the group's spectrum (an alias table), so the work per set of wavelengths
//! is one lookup per group and lane, cached with the emission spectra. A scene whose
//! lights all share one spectral shape has one group, and then nothing changes: lights
//! are chosen by power as before. Scenes with more than [`MAX_GROUPS`] shapes also keep
//! the choice by power, bounding the per-path work.
//!
//! Each group's spectrum is read through a 1 nm proxy table (its largest value within
//! each bin), one load per lane instead of a blackbody or table evaluation, because the
//! weights are recomputed whenever a fluorescent vertex changes the path's wavelengths.
//! Any positive weight keeps the choice unbiased; a floor of [`DEFENSIVE`] times each
//! spectrum's mean keeps every emitting light possible whatever the proxy says.
//!
//! When the choice follows the wavelengths: only when some group's sum over a package
//! changes from package to package ([`lane_sum_variation`] above [`SPECTRAL_VARIATION`]):
//! bands narrower than a package's spacing, or light only outside the visible. A
//! package's wavelengths are spread across the range, so a broad spectrum's sum over them
//! is nearly its mean, and choosing by it only adds the other lights' spectral noise to
//! each light's estimate: measured (docs/trade-offs.md, "When the choice follows the
//! wavelengths"), the choice by power is the more efficient with a warm lamp and daylight
//! or 40 nm LED bands, while the spectral choice gains a little with 30 nm bands and on
//! the effects stage (its 365 nm tube), and much with 20 nm bands.

use std::collections::HashMap;

use prism_sampling::distribution::AliasTable;
use prism_sampling::wavelength::WavelengthRange;
use prism_spectrum::{SampledWavelengths, Spectrum};

use super::EmissionCache;
use super::light::{Light, light_spectrum, unit_f32};
use crate::textures::SceneSpectrum;

/// The most groups (distinct light spectra) chosen among by wavelength.
pub const MAX_GROUPS: usize = 8;

/// The proxy tables' range, nm, at 1 nm: every sampler's default range and the
/// ultraviolet that fluorescent materials absorb, and the near infrared of camera
/// responses. A wavelength outside it is looked up in the spectrum itself.
const TABLE_MIN: f32 = 200.0;
const TABLE_LEN: usize = 1001;

/// The least [`lane_sum_variation`] of some group for which the choice follows the
/// path's wavelengths.
const SPECTRAL_VARIATION: f64 = 0.4;

/// Each group's weight includes this fraction of its spectrum's mean (per lane), so that
/// every light with any emission keeps a nonzero probability whatever the proxy says:
/// light sampling stays unbiased even for point lights (which BSDF sampling cannot hit),
/// at the cost of one choice in about a thousand going to a light that adds nothing.
const DEFENSIVE: f32 = 1e-3;

/// Lights sharing one spectrum.
#[derive(Debug, Clone)]
struct Group {
    spectrum: SceneSpectrum,
    /// The spectrum's largest value within each 1 nm bin centred on TABLE_MIN + k: a
    /// proxy that catches bands narrower than a bin and costs one load per lane.
    proxy: Vec<f32>,
    /// DEFENSIVE times the proxy's mean.
    floor: f32,
    /// The members' summed extent.
    extent: f64,
    /// Chooses a member by extent.
    members: AliasTable,
    /// The members' light indices, in the alias table's order.
    lights: Vec<u32>,
}

impl Group {
    /// The proxy of the spectrum at `lambda`, whose bin is `bin` (None outside the
    /// table: the spectrum itself). Bin k holds [TABLE_MIN + k - 0.5, TABLE_MIN + k +
    /// 0.5), so the bin of l is the truncating cast of l - TABLE_MIN + 0.5 where that is
    /// in range, without a libm round.
    fn proxy(&self, bin: Option<usize>, lambda: f32) -> f32 {
        match bin.and_then(|k| self.proxy.get(k)) {
            Some(&p) => p,
            None => (self.spectrum.evaluate(f64::from(lambda)) as f32).max(0.0),
        }
    }
}

/// The proxy table of `spectrum` (see [`Group::proxy`]): each bin's maximum over 21
/// points 0.05 nm apart.
fn proxy_table(spectrum: &SceneSpectrum) -> Vec<f32> {
    (0..TABLE_LEN)
        .map(|k| {
            let centre = f64::from(TABLE_MIN) + k as f64;
            (-10..=10)
                .map(|i| spectrum.evaluate(centre + 0.05 * f64::from(i)))
                .fold(0.0f64, f64::max) as f32
        })
        .collect()
}

/// A spectrum's values at the proxy table's bin centres and their mean: what tells
/// spectra that differ only by a factor (lamps of one colour at different intensities,
/// emissive materials of one colour at different strengths), which share a group.
struct Shape {
    values: Vec<f64>,
    mean: f64,
}

impl Shape {
    fn of(spectrum: &SceneSpectrum) -> Self {
        let values: Vec<f64> = (0..TABLE_LEN)
            .map(|k| spectrum.evaluate(f64::from(TABLE_MIN) + k as f64))
            .collect();
        let mean = values.iter().sum::<f64>() / TABLE_LEN as f64;
        Self { values, mean }
    }

    /// Whether the two are one spectrum times a positive factor, to within rounding: 1e-6
    /// relative at every bin, or 1e-9 of the mean, where far tails lose their precision
    /// to subnormals. Spectra dark over the whole table are never merged: nothing here
    /// tells their shapes apart.
    fn proportional(&self, other: &Shape) -> bool {
        let usable = |m: f64| m > 0.0 && m.is_finite();
        usable(self.mean)
            && usable(other.mean)
            && self.values.iter().zip(&other.values).all(|(&a, &b)| {
                let (a, b) = (a / self.mean, b / other.mean);
                (a - b).abs() <= 1e-6 * a.abs().max(b.abs()) + 1e-9
            })
    }
}

/// How much a spectrum's sum over a path's wavelengths varies from path to path, as the
/// coefficient of variation of the sum over eight wavelengths spaced evenly across
/// 360-830 nm (the default package over the visible range) at 64 offsets. A spectrum
/// dark at every such wavelength gives infinity: it matters only at wavelengths outside
/// the visible (the ultraviolet that fluorescent materials absorb, a camera's infrared),
/// so a path carries either none of its light or much of it, which one power cannot
/// weigh.
fn lane_sum_variation(proxy: &[f32]) -> f64 {
    const LANES: usize = 8;
    const OFFSETS: usize = 64;
    let visible = WavelengthRange::VISIBLE;
    let (lo, width) = (f64::from(visible.min()), f64::from(visible.width()));
    let sums: Vec<f64> = (0..OFFSETS)
        .map(|k| {
            let offset = (k as f64 + 0.5) / OFFSETS as f64;
            (0..LANES)
                .map(|j| {
                    let lambda = lo + (offset + j as f64) * width / LANES as f64;
                    let bin = (lambda - f64::from(TABLE_MIN)).round() as usize;
                    f64::from(proxy.get(bin).copied().unwrap_or(0.0))
                })
                .sum()
        })
        .collect();
    let mean = sums.iter().sum::<f64>() / OFFSETS as f64;
    if mean.is_nan() || mean <= 0.0 {
        return f64::INFINITY;
    }
    let variance = sums.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / OFFSETS as f64;
    variance.sqrt() / mean
}

/// Lights grouped by spectrum, for the choice at a path's wavelengths.
#[derive(Debug, Clone)]
pub(crate) struct SpectralChoice {
    groups: Vec<Group>,
    /// Per light: its group, and its probability within it.
    group_of: Vec<(u32, f32)>,
}

/// The groups' weights at one set of wavelengths (zeros past the scene's groups), and
/// their sum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Weights {
    group: [f32; MAX_GROUPS],
    total: f32,
}

impl SpectralChoice {
    /// Groups `lights` by spectrum; `extent` is each light's flux per unit of its
    /// spectrum, `emission` the emissive triangles' spectra. None when there is only one
    /// group (the choice by power is then the same) or more than [`MAX_GROUPS`], or no
    /// light has extent.
    pub(crate) fn new(
        lights: &[Light],
        extent: &[f64],
        emission: &[SceneSpectrum],
    ) -> Option<Self> {
        // A light's spectrum is its triangle's emission (shared by every triangle of an
        // emissive material) or its own.
        let source_of = |i: usize| match &lights[i] {
            Light::Triangle { emission, .. } => (0u8, *emission),
            _ => (1u8, i as u32),
        };
        let mut shapes: Vec<Shape> = Vec::new();
        let mut shape_of: HashMap<(u8, u32), usize> = HashMap::new();
        // Per group: its representative shape, and its members with their extents in
        // units of the representative's spectrum.
        let mut representatives: Vec<usize> = Vec::new();
        let mut members: Vec<Vec<(u32, f64)>> = Vec::new();
        for (i, &weight) in extent.iter().enumerate().take(lights.len()) {
            if !(weight > 0.0 && weight.is_finite()) {
                continue;
            }
            let s = *shape_of.entry(source_of(i)).or_insert_with(|| {
                shapes.push(Shape::of(light_spectrum(&lights[i], emission)));
                shapes.len() - 1
            });
            let group = representatives
                .iter()
                .position(|&r| shapes[r].proportional(&shapes[s]));
            let g = match group {
                Some(g) => g,
                None => {
                    if representatives.len() == MAX_GROUPS {
                        return None;
                    }
                    representatives.push(s);
                    members.push(Vec::new());
                    representatives.len() - 1
                }
            };
            let ratio = shapes[s].mean / shapes[representatives[g]].mean;
            // A shape without mean is its own group's representative (ratio 1).
            let ratio = if ratio.is_finite() { ratio } else { 1.0 };
            members[g].push((i as u32, weight * ratio));
        }
        if representatives.len() < 2 {
            return None;
        }
        let mut group_of = vec![(u32::MAX, 0.0f32); lights.len()];
        let mut groups = Vec::with_capacity(representatives.len());
        for (g, members) in members.into_iter().enumerate() {
            let weights: Vec<f64> = members.iter().map(|&(_, w)| w).collect();
            let table = AliasTable::new(&weights).ok()?;
            for (m, &(i, _)) in members.iter().enumerate() {
                group_of[i as usize] = (g as u32, table.pmf(m) as f32);
            }
            let spectrum = light_spectrum(&lights[members[0].0 as usize], emission).clone();
            let proxy = proxy_table(&spectrum);
            let mean = proxy.iter().map(|&v| f64::from(v)).sum::<f64>() / TABLE_LEN as f64;
            groups.push(Group {
                spectrum,
                proxy,
                floor: DEFENSIVE * mean as f32,
                extent: weights.iter().sum(),
                members: table,
                lights: members.iter().map(|&(i, _)| i).collect(),
            });
        }
        let varies = groups
            .iter()
            .any(|g| lane_sum_variation(&g.proxy) > SPECTRAL_VARIATION);
        varies.then_some(Self { groups, group_of })
    }

    /// Each group's weight at `wavelengths`: its extent times its proxy spectrum summed
    /// over the lanes, plus the defensive floor. Computed once per set of wavelengths and
    /// kept in `cache` beside the emission spectra.
    pub(crate) fn weights<const N: usize>(
        &self,
        wavelengths: &SampledWavelengths<N>,
        cache: &mut EmissionCache<N>,
    ) -> Weights {
        cache.refresh(wavelengths);
        if let Some(weights) = cache.choice_weights {
            return weights;
        }
        // Lane by lane, each lane's bin found once for every group.
        let mut lanes = [0.0f32; MAX_GROUPS];
        for &l in wavelengths.lambdas() {
            let x = l - (TABLE_MIN - 0.5);
            let bin = (x >= 0.0 && x < TABLE_LEN as f32).then_some(x as i32 as usize);
            for (sum, g) in lanes.iter_mut().zip(&self.groups) {
                *sum += g.proxy(bin, l);
            }
        }
        let mut group = [0.0f32; MAX_GROUPS];
        for ((w, g), sum) in group.iter_mut().zip(&self.groups).zip(lanes) {
            let weight = (g.extent * f64::from(sum + N as f32 * g.floor)) as f32;
            *w = if weight.is_finite() { weight } else { 0.0 };
        }
        let total = group.iter().sum::<f32>();
        let weights = Weights {
            group,
            total: if total.is_finite() { total } else { 0.0 },
        };
        cache.choice_weights = Some(weights);
        weights
    }

    /// A light chosen with `u` in proportion to `weights` (from [`Self::weights`]), its
    /// probability, and what is left of `u` (uniform in [0, 1) again); None when no light
    /// has weight.
    pub(crate) fn choose(&self, u: f32, weights: &Weights) -> Option<(usize, f32, f32)> {
        if weights.total <= 0.0 {
            return None;
        }
        let target = u * weights.total;
        let mut below = 0.0f32;
        // The last group with weight takes what rounding leaves past the sum.
        let mut chosen = None;
        for (g, &w) in weights.group.iter().enumerate().take(self.groups.len()) {
            if w <= 0.0 {
                continue;
            }
            chosen = Some((g, below));
            if target < below + w {
                break;
            }
            below += w;
        }
        let (g, below) = chosen?;
        // The part of u within the group's interval, reused to choose a member.
        let u_member = (f64::from(target - below) / f64::from(weights.group[g]))
            .clamp(0.0, 1.0 - f64::EPSILON);
        let group = &self.groups[g];
        // A group of one light (a punctual light, the environment) needs no second choice.
        let (light, rest) = match group.lights.as_slice() {
            [only] => (*only as usize, u_member),
            members => {
                let (m, _, rest) = group.members.sample_remapped(u_member);
                (members[m] as usize, rest)
            }
        };
        let pmf = self.pmf(light, weights);
        (pmf > 0.0).then_some((light, pmf, unit_f32(rest)))
    }

    /// The probability that [`Self::choose`] picks light `i` given `weights`.
    pub(crate) fn pmf(&self, i: usize, weights: &Weights) -> f32 {
        match self.group_of.get(i) {
            Some(&(g, within)) if g != u32::MAX && weights.total > 0.0 => {
                weights.group[g as usize] / weights.total * within
            }
            _ => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::Vec3;
    use prism_sampling::stats::chi_square_test;
    use prism_spectrum::spectra::Gaussian;
    use prism_spectrum::{SampledWavelengths, Spectrum};
    use proptest::prelude::*;

    use super::{
        DEFENSIVE, MAX_GROUPS, SPECTRAL_VARIATION, SpectralChoice, TABLE_LEN, TABLE_MIN,
        lane_sum_variation, proxy_table,
    };
    use crate::lights::{EmissionCache, Light};
    use crate::textures::SceneSpectrum;

    fn band(centre: f64, fwhm: f64) -> SceneSpectrum {
        SceneSpectrum::Gaussian(Gaussian::new(centre, fwhm, 1.0).unwrap())
    }

    /// Three emissive triangles, two of a blue band (extents 1 and 3) and one of a red
    /// band (extent 2), and a point light of the red band (extent 4 pi), a group of its
    /// own.
    fn lights() -> (Vec<Light>, Vec<f64>, Vec<SceneSpectrum>) {
        let triangle = |triangle, emission| Light::Triangle {
            triangle,
            emission,
            two_sided: false,
        };
        let lights = vec![
            triangle(0, 0),
            triangle(1, 1),
            triangle(2, 0),
            Light::Point {
                position: Vec3::ZERO,
                intensity: band(650.0, 15.0),
            },
        ];
        let extent = vec![1.0, 2.0, 3.0, 4.0 * std::f64::consts::PI];
        (lights, extent, vec![band(450.0, 15.0), band(650.0, 15.0)])
    }

    fn wavelengths(lambda: [f32; 4]) -> SampledWavelengths<4> {
        SampledWavelengths::new(lambda, [0.01; 4]).unwrap()
    }

    /// The weight the choice should give a light of spectrum `s` and extent `x` at `w`:
    /// x times the sum over lanes of the spectrum's largest value within 0.5 nm, plus the
    /// defensive floor (computed here from the definition, not the table).
    fn expected_weight(s: &SceneSpectrum, x: f64, w: &SampledWavelengths<4>) -> f64 {
        let bin_max = |l: f64| {
            let c = l.round();
            (-10..=10)
                .map(|i| s.evaluate(c + 0.05 * f64::from(i)))
                .fold(0.0, f64::max)
        };
        let mean = (0..TABLE_LEN)
            .map(|k| bin_max(f64::from(TABLE_MIN) + k as f64))
            .sum::<f64>()
            / TABLE_LEN as f64;
        let lanes: f64 = w.lambdas().iter().map(|&l| bin_max(f64::from(l))).sum();
        x * (lanes + 4.0 * f64::from(DEFENSIVE) * mean)
    }

    #[test]
    fn chooses_in_proportion_to_power_at_the_path_wavelengths() {
        let (lights, extent, emission) = lights();
        let choice = SpectralChoice::new(&lights, &extent, &emission).expect("two spectra");
        for lambda in [
            [450.0, 460.0, 470.0, 480.0],
            [440.5, 560.25, 650.0, 700.0],
            [640.0, 650.0, 660.0, 700.0],
            [548.0, 550.0, 552.0, 551.0],
        ] {
            let w = wavelengths(lambda);
            let mut cache = EmissionCache::new();
            let weights = choice.weights(&w, &mut cache);
            let power = [
                expected_weight(&emission[0], extent[0], &w),
                expected_weight(&emission[1], extent[1], &w),
                expected_weight(&emission[0], extent[2], &w),
                expected_weight(&emission[1], extent[3], &w),
            ];
            let total: f64 = power.iter().sum();
            let pmf: Vec<f64> = (0..4).map(|i| f64::from(choice.pmf(i, &weights))).collect();
            for i in 0..4 {
                assert!(
                    (pmf[i] - power[i] / total).abs() <= 1e-5 * (power[i] / total).max(1e-3),
                    "{lambda:?}: light {i} pmf {} vs {}",
                    pmf[i],
                    power[i] / total
                );
            }
            let n = 200_000u64;
            let mut counts = [0u64; 4];
            for k in 0..n {
                let u = (k as f32 + 0.5) / n as f32;
                let (i, p, _) = choice.choose(u, &weights).expect("every light has a floor");
                assert_eq!(p, choice.pmf(i, &weights));
                counts[i] += 1;
            }
            // Stratified u: the counts are the probabilities to within rounding.
            let expected: Vec<f64> = pmf.iter().map(|p| p * n as f64).collect();
            for i in 0..4 {
                assert!(
                    (counts[i] as f64 - expected[i]).abs() <= 2.0 + 1e-4 * n as f64,
                    "{lambda:?}: light {i} chosen {} times, expected {}",
                    counts[i],
                    expected[i]
                );
            }
            assert!(chi_square_test(&counts, &expected).p_value > 1e-3);
            // The weights were cached for these wavelengths.
            assert_eq!(cache.choice_weights, Some(weights));
        }
    }

    /// Twelve point lamps in three colours at four intensities each: more lights than
    /// groups, but three spectral shapes, so the choice stays spectral, each lamp chosen
    /// by its own power at the path's wavelengths; with one colour it is the choice by
    /// power.
    #[test]
    fn lamps_of_one_colour_at_different_intensities_share_a_group() {
        let lamp = |centre: f64, scale: f64| Light::Point {
            position: Vec3::ZERO,
            intensity: SceneSpectrum::Scaled(Arc::new(band(centre, 15.0)), scale),
        };
        let lights: Vec<Light> = [450.0, 550.0, 650.0]
            .iter()
            .flat_map(|&c| [0.5, 1.0, 3.0, 40.0].map(|k| lamp(c, k)))
            .collect();
        assert!(lights.len() > MAX_GROUPS);
        let extent = vec![4.0 * std::f64::consts::PI; lights.len()];
        let choice = SpectralChoice::new(&lights, &extent, &[]).expect("three shapes");
        assert_eq!(choice.groups.len(), 3);
        let spectrum = |l: &Light| match l {
            Light::Point { intensity, .. } => intensity.clone(),
            _ => unreachable!(),
        };
        for lambda in [[450.0, 470.0, 600.0, 640.0], [500.0, 550.0, 551.0, 700.0]] {
            let w = wavelengths(lambda);
            let weights = choice.weights(&w, &mut EmissionCache::new());
            let power: Vec<f64> = lights
                .iter()
                .zip(&extent)
                .map(|(l, &x)| expected_weight(&spectrum(l), x, &w))
                .collect();
            let total: f64 = power.iter().sum();
            for (i, p) in power.iter().enumerate() {
                let pmf = f64::from(choice.pmf(i, &weights));
                assert!(
                    (pmf - p / total).abs() <= 1e-5 * (p / total).max(1e-3),
                    "{lambda:?}: lamp {i} pmf {pmf} vs {}",
                    p / total
                );
            }
        }
        let one_colour: Vec<Light> = [0.5, 1.0, 3.0].map(|k| lamp(550.0, k)).into();
        assert!(SpectralChoice::new(&one_colour, &extent[..3], &[]).is_none());
    }

    /// Broad spectra that differ in shape (a warm and a cool lamp) keep the choice by
    /// power: their sums over a package barely change from path to path, and choosing by
    /// them was measured to add noise (docs/trade-offs.md, "When the choice follows the
    /// wavelengths"). Bands narrower
    /// than the package's spacing, or dark over the visible, make the choice spectral.
    #[test]
    fn only_spectra_that_vary_across_packages_make_the_choice_spectral() {
        let point = |s: SceneSpectrum| Light::Point {
            position: Vec3::ZERO,
            intensity: s,
        };
        let extent = [1.0; 2];
        let broad = [band(500.0, 120.0), band(600.0, 120.0)].map(point);
        assert!(SpectralChoice::new(&broad, &extent, &[]).is_none());
        let narrow = [band(500.0, 120.0), band(600.0, 20.0)].map(point);
        assert!(SpectralChoice::new(&narrow, &extent, &[]).is_some());
        let ultraviolet = [band(500.0, 120.0), band(300.0, 20.0)].map(point);
        assert!(SpectralChoice::new(&ultraviolet, &extent, &[]).is_some());

        let variation = |s: &SceneSpectrum| lane_sum_variation(&proxy_table(s));
        assert!(variation(&SceneSpectrum::Constant(2.0)) < 1e-6);
        assert!(variation(&band(550.0, 120.0)) < 0.01);
        assert!(variation(&band(550.0, 20.0)) > 2.0 * SPECTRAL_VARIATION);
        assert_eq!(variation(&band(250.0, 10.0)), f64::INFINITY);
    }

    #[test]
    fn lights_dark_at_the_path_wavelengths_keep_only_the_defensive_share() {
        let (lights, extent, emission) = lights();
        let choice = SpectralChoice::new(&lights, &extent, &emission).unwrap();
        // Bands of 15 nm full width at 450 and 650 nm are below f32's range 98 nm away;
        // at 450 nm the red one is.
        let dark = wavelengths([548.0, 550.0, 552.0, 551.0]);
        let blue = wavelengths([450.0, 450.0, 450.0, 450.0]);
        let mut cache = EmissionCache::new();
        let at_dark = choice.weights(&dark, &mut cache);
        let at_blue = choice.weights(&blue, &mut cache);
        for g in 0..2 {
            assert!(at_dark.group[g] > 0.0, "group {g} keeps its floor");
        }
        let red = choice.pmf(1, &at_blue) + choice.pmf(3, &at_blue);
        assert!(red > 0.0 && red < 1e-2, "red lights at 450 nm: {red}");
    }

    #[test]
    fn the_proxy_catches_narrow_bands_and_bounds_the_spectrum() {
        // A laser line 0.05 nm wide between two whole nanometres.
        let laser = band(532.3, 0.05);
        let table = proxy_table(&laser);
        let k = (532.0 - TABLE_MIN) as usize;
        assert!(table[k] > 0.5, "the bin holding the line: {}", table[k]);
        // A smooth band: every bin's proxy lies between the spectrum at the bin's centre
        // and its maximum over the bin.
        let smooth = band(500.0, 30.0);
        let table = proxy_table(&smooth);
        for (k, &p) in table.iter().enumerate() {
            let c = f64::from(TABLE_MIN) + k as f64;
            let lo = smooth.evaluate(c) as f32;
            let hi = [c - 0.5, c, c + 0.5]
                .map(|l| smooth.evaluate(l))
                .into_iter()
                .fold(0.0, f64::max) as f32;
            assert!(
                p >= lo * (1.0 - 1e-6) && p <= hi * (1.0 + 1e-6),
                "bin {k}: {p} not in [{lo}, {hi}]"
            );
        }
    }

    fn wavelength() -> impl Strategy<Value = f32> {
        prop_oneof![
            Just(f32::MIN_POSITIVE),
            Just(1e-45f32),
            Just(199.4f32),
            Just(199.5f32),
            Just(1200.49f32),
            Just(1200.5f32),
            Just(f32::MAX),
            1.0..2000.0f32,
            350.0..800.0f32,
        ]
    }

    proptest! {
        /// For any wavelengths a package can carry (positive and finite: subnormal, at
        /// the proxy table's ends, huge), the weights and probabilities are finite, the
        /// probabilities sum to 1, and every u in [0, 1) chooses a light with exactly the
        /// probability `pmf` reports.
        #[test]
        fn any_wavelengths_give_a_distribution(
            lambda in prop::array::uniform4(wavelength()),
            u in prop_oneof![Just(0.0f32), Just(1.0 - f32::EPSILON / 2.0), 0.0..1.0f32],
        ) {
            let (lights, extent, emission) = lights();
            let choice = SpectralChoice::new(&lights, &extent, &emission).unwrap();
            let w = wavelengths(lambda);
            let weights = choice.weights(&w, &mut EmissionCache::new());
            prop_assert!(weights.total.is_finite() && weights.total > 0.0);
            let pmf: Vec<f32> = (0..4).map(|i| choice.pmf(i, &weights)).collect();
            prop_assert!(pmf.iter().all(|p| p.is_finite() && *p >= 0.0));
            prop_assert!((pmf.iter().sum::<f32>() - 1.0).abs() < 1e-5, "{pmf:?}");
            let (i, p, rest) = choice.choose(u, &weights).expect("every light has a floor");
            prop_assert!((0.0..1.0).contains(&rest));
            prop_assert_eq!(p, pmf[i]);
            prop_assert!(p > 0.0);
        }
    }

    proptest! {
        /// Lamps of any intensity (subnormal to near f64's limit, zero) and any extent:
        /// grouping never panics, and a spectral choice it makes gives finite
        /// probabilities that sum to 1 (or chooses nothing when no weight is left).
        #[test]
        fn any_intensities_give_a_distribution_or_none(
            scales in prop::array::uniform3(prop_oneof![
                Just(0.0f64), Just(1e-310f64), Just(1e-30f64), Just(1.0f64), Just(1e30f64),
                Just(1e300f64), 1e-3..1e3f64,
            ]),
            extent in prop::array::uniform3(prop_oneof![Just(0.0f64), Just(1e-300f64), Just(1e300f64), 1e-3..1e3f64]),
            lambda in prop::array::uniform4(350.0..850.0f32),
        ) {
            let lamp = |centre: f64, scale: f64| Light::Point {
                position: Vec3::ZERO,
                intensity: SceneSpectrum::Scaled(Arc::new(band(centre, 15.0)), scale),
            };
            let lights = [lamp(450.0, scales[0]), lamp(450.0, scales[1]), lamp(650.0, scales[2])];
            if let Some(choice) = SpectralChoice::new(&lights, &extent, &[]) {
                let weights = choice.weights(&wavelengths(lambda), &mut EmissionCache::new());
                prop_assert!(weights.total.is_finite() && weights.total >= 0.0);
                let pmf: Vec<f32> = (0..3).map(|i| choice.pmf(i, &weights)).collect();
                prop_assert!(pmf.iter().all(|p| p.is_finite() && *p >= 0.0));
                if weights.total > 0.0 {
                    prop_assert!((pmf.iter().sum::<f32>() - 1.0).abs() < 1e-4, "{pmf:?}");
                } else {
                    prop_assert!(choice.choose(0.5, &weights).is_none());
                }
            }
        }
    }

    #[test]
    fn one_spectrum_or_too_many_keep_the_choice_by_power() {
        let emission: Vec<SceneSpectrum> = (0..=MAX_GROUPS)
            .map(|k| band(400.0 + 20.0 * k as f64, 10.0))
            .collect();
        let one: Vec<Light> = (0..5)
            .map(|t| Light::Triangle {
                triangle: t,
                emission: 0,
                two_sided: false,
            })
            .collect();
        assert!(SpectralChoice::new(&one, &[1.0; 5], &emission).is_none());
        let many: Vec<Light> = (0..=MAX_GROUPS as u32)
            .map(|t| Light::Triangle {
                triangle: t,
                emission: t,
                two_sided: false,
            })
            .collect();
        assert!(SpectralChoice::new(&many, &[1.0; MAX_GROUPS + 1], &emission).is_none());
        assert!(SpectralChoice::new(&many[..MAX_GROUPS], &[1.0; MAX_GROUPS], &emission).is_some());
        // Lights without extent are never chosen and make no group.
        let mut extent = vec![0.0; MAX_GROUPS + 1];
        extent[0] = 1.0;
        extent[1] = 1.0;
        assert!(SpectralChoice::new(&many, &extent, &emission).is_some());
    }
}
