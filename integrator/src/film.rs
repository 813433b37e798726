//! The film: per-pixel sums of XYZ samples, in f64 so that a million samples per pixel
//! lose nothing (the sum of 10^6 values near 1 keeps 10^-10 relative precision), with a
//! count of the samples rejected as non-finite.

use prism_spectrum::color::RgbColorSpace;
use prism_spectrum::colorimetry::Xyz;

/// Accumulated XYZ per pixel, row-major from the top-left.
#[derive(Debug, Clone, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    /// Sum of the XYZ of every accepted sample.
    sums: Vec<[f64; 3]>,
    /// Samples taken per pixel (accepted or rejected: a rejected sample counts as zero,
    /// which keeps the estimator's normalization and so its expectation honest).
    samples: u64,
    nonfinite: u64,
}

impl Film {
    /// A black film.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            sums: vec![[0.0; 3]; width as usize * height as usize],
            samples: 0,
            nonfinite: 0,
        }
    }

    /// A film from its parts (merging and resuming): sums per pixel, samples per pixel,
    /// non-finite count. None when the sums do not fit the size or are not finite.
    pub fn from_parts(
        width: u32,
        height: u32,
        sums: Vec<[f64; 3]>,
        samples: u64,
        nonfinite: u64,
    ) -> Option<Self> {
        (sums.len() == width as usize * height as usize
            && sums.iter().flatten().all(|v| v.is_finite()))
        .then_some(Self {
            width,
            height,
            sums,
            samples,
            nonfinite,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Samples per pixel accumulated.
    pub fn samples(&self) -> u64 {
        self.samples
    }

    /// Samples rejected because their value was NaN or infinite.
    pub fn nonfinite(&self) -> u64 {
        self.nonfinite
    }

    /// The per-pixel sums.
    pub fn sums(&self) -> &[[f64; 3]] {
        &self.sums
    }

    pub(crate) fn sums_mut(&mut self) -> &mut [[f64; 3]] {
        &mut self.sums
    }

    pub(crate) fn finish_pass(&mut self, samples: u64, nonfinite: u64) {
        self.samples += samples;
        self.nonfinite += nonfinite;
    }

    /// The estimate of pixel (x, y): its sum over the samples taken.
    pub fn xyz(&self, x: u32, y: u32) -> Xyz {
        let s = self.sums[(y * self.width + x) as usize];
        let n = self.samples.max(1) as f64;
        Xyz::new(s[0] / n, s[1] / n, s[2] / n)
    }

    /// The image as linear RGB in `space` (no chromatic adaptation: XYZ is converted with
    /// the space's own matrix), row-major.
    pub fn to_rgb(&self, space: &RgbColorSpace) -> Vec<[f32; 3]> {
        let n = self.samples.max(1) as f64;
        self.sums
            .iter()
            .map(|s| {
                let rgb = space.xyz_to_rgb(Xyz::new(s[0] / n, s[1] / n, s[2] / n));
                rgb.map(|c| if c.is_finite() { c as f32 } else { 0.0 })
            })
            .collect()
    }

    /// Adds another film of the same size (sample ranges rendered apart).
    pub fn merge(&mut self, other: &Film) -> Result<(), String> {
        if (self.width, self.height) != (other.width, other.height) {
            return Err(format!(
                "film sizes differ: {}x{} and {}x{}",
                self.width, self.height, other.width, other.height
            ));
        }
        for (a, b) in self.sums.iter_mut().zip(&other.sums) {
            for (acc, v) in a.iter_mut().zip(b) {
                *acc += v;
            }
        }
        self.samples += other.samples;
        self.nonfinite += other.nonfinite;
        Ok(())
    }
}
