//! What adaptive sampling's pilot measures in a pixel: its error in every output the
//! render writes, not only in colour.
//!
//! A spectral render's user reads its bands; a render with `--energy` its radiance
//! integral; a polarized render its Stokes images. Their errors are not its colour's:
//! where the sky is seen directly, every sample's colour is nearly the same (the hero
//! package's wavelengths, spread evenly, integrate a flat spectrum almost exactly), while
//! each band is hit or missed by a sample's few wavelengths. A pilot that judged colour
//! alone gave such pixels the fewest samples and left their bands several times as noisy
//! as a uniform render's (docs/trade-offs.md, "Adaptive sampling"). So each output the film
//! keeps enters the pilot's error with the same weight as colour: its channels' errors,
//! each weighted as the relative MSE weighs it (`channel_error`), in that output's units,
//! averaged over its channels and scaled to colour's three.

use prism_spectrum::colorimetry::Observer;

use crate::film::sample_value::{Outputs, PHOTONS_PER_JOULE_NM, SampleValue};

/// Half the squared difference of two estimates `a` and `b` of a channel whose value is
/// about `mean`, weighted as the relative MSE weighs errors.
pub(crate) fn channel_error(a: f64, b: f64, mean: f64) -> f64 {
    let weight = 1.0 / (mean * mean + 0.01);
    0.5 * (a - b).powi(2) * weight
}

/// The error measure of one render's pilot: the outputs it writes and the scale of each.
#[derive(Debug, Clone)]
pub(crate) struct PilotMeasure {
    outputs: Outputs,
    /// Band values per unit of colour (Y) for a flat spectrum: the relative MSE's floor in
    /// the dark, 0.01 in colour's units, is the same light in every output.
    band_unit: f64,
    /// The same for the radiance integral and the photon radiance.
    energy_units: [f64; 2],
}

impl PilotMeasure {
    /// The measure for a render writing `outputs` over wavelengths `range` (nm), its
    /// colour by `observer`.
    pub(crate) fn new(outputs: Outputs, range: (f32, f32), observer: Observer) -> Self {
        let (lo, hi) = (f64::from(range.0), f64::from(range.1));
        // Y of a flat spectrum of 1 over the range, at 1 nm steps (a scale, not a result).
        let first = lo.ceil() as i64;
        let last = hi.floor() as i64;
        let y: f64 = (first..=last).map(|l| observer.cmf(l as f64)[1]).sum();
        let y = if y.is_finite() && y > 0.0 { y } else { 1.0 };
        let width = (hi - lo).max(1.0);
        Self {
            outputs,
            band_unit: 1.0 / y,
            energy_units: [
                width / y,
                0.5 * (hi * hi - lo * lo).max(1.0) * PHOTONS_PER_JOULE_NM / y,
            ],
        }
    }

    /// Channels per sample: colour, the spectral sums, energy, the Stokes colours.
    pub(crate) fn len(&self) -> usize {
        3 + self.outputs.spectral_width()
            + if self.outputs.energy { 2 } else { 0 }
            + if self.outputs.polarized { 9 } else { 0 }
    }

    /// Writes a sample's channels, each times `scale` (0 for a rejected sample), into
    /// `out` (resized to [`Self::len`]).
    pub(crate) fn channels(&self, value: &SampleValue, scale: f64, out: &mut Vec<f64>) {
        out.clear();
        out.resize(self.len(), 0.0);
        if scale == 0.0 {
            // A rejected sample adds nothing (its values may not be finite).
            return;
        }
        for (o, v) in out.iter_mut().zip(value.xyz) {
            *o = v * scale;
        }
        let spectral = self.outputs.spectral_width();
        for &(band, v) in &value.binned {
            out[3 + band] += v * scale;
        }
        let mut at = 3 + spectral;
        if self.outputs.energy {
            out[at] = value.energy[0] * scale;
            out[at + 1] = value.energy[1] * scale;
            at += 2;
        }
        if self.outputs.polarized {
            for (o, v) in out[at..].iter_mut().zip(value.stokes.iter().flatten()) {
                *o = v * scale;
            }
        }
    }

    /// The weighted error of a pixel whose two pilot samples' channels are `a` and `b`:
    /// colour's three channels as the relative MSE weighs them, the energy and Stokes
    /// channels the same way in their own units, averaged over theirs, times three. The
    /// bands are left to [`Self::band_error`]: each is hit by a sample's few wavelengths
    /// or missed, so one pixel's two samples say nothing of a band's level, and weighed by
    /// their own mean every pixel's bands look alike noisy.
    pub(crate) fn error(&self, a: &[f64], b: &[f64]) -> PixelError {
        let weighted = |k: usize, unit: f64| {
            channel_error(a[k] / unit, b[k] / unit, 0.5 * (a[k] + b[k]) / unit)
        };
        let mut error = (0..3).map(|k| weighted(k, 1.0)).sum::<f64>();
        let spectral = self.outputs.spectral_width();
        let mut bands = [0.0; 2];
        for k in 3..3 + spectral {
            let (x, y) = (a[k] / self.band_unit, b[k] / self.band_unit);
            bands[0] += 0.5 * (x - y).powi(2);
            bands[1] += (0.5 * (x + y)).powi(2);
        }
        let mut at = 3 + spectral;
        if self.outputs.energy {
            let sum = weighted(at, self.energy_units[0]) + weighted(at + 1, self.energy_units[1]);
            error += 1.5 * sum;
            at += 2;
        }
        if self.outputs.polarized {
            let sum: f64 = (at..at + 9).map(|k| weighted(k, 1.0)).sum();
            error += sum / 3.0;
        }
        PixelError { error, bands }
    }

    /// The bands' weighted error per pixel, from the pixels' squared differences and
    /// squared means summed over the bands (`PixelError::bands`), each averaged over the
    /// neighbourhood `smooth` averages over first: the relative MSE's weight from the
    /// region's level, not the pixel's two samples'. Three times the bands' mean relative
    /// error, as colour's three channels weigh; None without bands.
    pub(crate) fn band_error(
        &self,
        bands: &[[f64; 2]],
        smooth: impl Fn(&[f64]) -> Vec<f64>,
    ) -> Option<Vec<f64>> {
        let count = self.outputs.spectral_width();
        if count == 0 {
            return None;
        }
        let variance = smooth(&bands.iter().map(|b| b[0]).collect::<Vec<_>>());
        let level = smooth(&bands.iter().map(|b| b[1]).collect::<Vec<_>>());
        let floor = 0.01 * count as f64;
        Some(
            variance
                .iter()
                .zip(&level)
                .map(|(v, l)| 3.0 * v / (l + floor))
                .collect(),
        )
    }
}

/// A pixel's pilot error: colour's and every other output's but the bands', and the bands'
/// sums of squared differences and squared means (in colour's units), which are weighed
/// over a neighbourhood ([`PilotMeasure::band_error`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct PixelError {
    pub error: f64,
    pub bands: [f64; 2],
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SpectralBands;

    fn outputs(bands: Option<SpectralBands>, energy: bool, polarized: bool) -> Outputs {
        Outputs {
            bands,
            energy,
            polarized,
        }
    }

    #[test]
    fn colour_alone_is_measured_as_before() {
        let measure = PilotMeasure::new(
            outputs(None, false, false),
            (360.0, 830.0),
            Observer::Cie1931,
        );
        let (a, b) = ([3.0, 40.0, 0.2], [1.0, 80.0, 0.3]);
        let before: f64 = (0..3)
            .map(|k| channel_error(a[k], b[k], 0.5 * (a[k] + b[k])))
            .sum();
        assert_eq!(measure.error(&a, &b).error.to_bits(), before.to_bits());
        assert_eq!(measure.error(&a, &b).bands, [0.0; 2]);
    }

    /// A region whose colour is the same in both samples but whose bands differ (the sky
    /// seen directly, its bands hit by different wavelengths) has an error in a spectral
    /// render, weighed by the region's level: a band hit by one sample and missed by the
    /// other is a relative error of the size a colour as noisy would have.
    #[test]
    fn bands_that_differ_count_where_colour_does_not() {
        let bands = SpectralBands::new(400.0, 700.0, 2).unwrap();
        let measure = PilotMeasure::new(
            outputs(Some(bands), false, false),
            (400.0, 700.0),
            Observer::Cie1931,
        );
        let y = 1.0 / measure.band_unit;
        // A flat spectrum of 1 in both bands on average: 2 and 0, then 0 and 2.
        let a = [y, y, y, 2.0, 0.0];
        let b = [y, y, y, 0.0, 2.0];
        let pixel = measure.error(&a, &b);
        assert_eq!(pixel.error, 0.0);
        // Averaged over many such pixels, each band's mean is 1 and its variance 2.
        let region = [pixel.bands, [pixel.bands[0], 4.0 * 2.0 * y * y]];
        let smooth = |v: &[f64]| vec![v.iter().sum::<f64>() / v.len() as f64; v.len()];
        let error = measure.band_error(&region, smooth).unwrap();
        assert!(error[0] > 0.0 && error[0] == error[1]);
        assert!(
            measure
                .band_error(&[[0.0, 1.0]], |v: &[f64]| v.to_vec())
                .unwrap()[0]
                == 0.0
        );
    }

    #[test]
    fn every_output_has_its_channels() {
        let bands = SpectralBands::new(400.0, 700.0, 5).unwrap();
        let measure = PilotMeasure::new(
            outputs(Some(bands), true, true),
            (360.0, 830.0),
            Observer::Cie1931,
        );
        assert_eq!(measure.len(), 3 + 20 + 2 + 9);
        let mut value = SampleValue {
            xyz: [1.0, 2.0, 3.0],
            binned: vec![(1, 0.5), (1, 0.25), (7, -0.1)],
            energy: [4.0, 5.0],
            ..Default::default()
        };
        value.stokes[2][2] = 6.0;
        let mut out = Vec::new();
        measure.channels(&value, 2.0, &mut out);
        assert_eq!(out[..3], [2.0, 4.0, 6.0]);
        assert_eq!(out[3 + 1], 1.5);
        assert_eq!(out[3 + 7], -0.2);
        assert_eq!(out[23..25], [8.0, 10.0]);
        assert_eq!(out[33], 12.0);
        let same = measure.error(&out, &out);
        assert_eq!((same.error, same.bands[0]), (0.0, 0.0));
        let apart = measure.error(&out, &vec![0.0; out.len()]);
        assert!(apart.error.is_finite() && apart.bands.iter().all(|v| v.is_finite()));
    }
}
