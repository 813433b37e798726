//! Wavelength bands of a spectral film.

use crate::RenderError;

/// `count` equal bands over `[min, max)` nm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectralBands {
    min: f32,
    max: f32,
    count: usize,
}

impl SpectralBands {
    /// Bands over `[min, max)`: 1 to 4096 of them, 0 < min < max, finite.
    ///
    /// ```
    /// use prism_integrator::SpectralBands;
    ///
    /// let bands = SpectralBands::new(400.0, 700.0, 30)?;
    /// assert_eq!(bands.range(), (400.0, 700.0));
    /// assert!(SpectralBands::new(700.0, 400.0, 30).is_err());
    /// assert!(SpectralBands::new(400.0, 700.0, 0).is_err());
    /// # Ok::<(), prism_integrator::RenderError>(())
    /// ```
    pub fn new(min: f32, max: f32, count: usize) -> Result<Self, RenderError> {
        if !(min.is_finite() && max.is_finite() && min > 0.0 && min < max) {
            return Err(RenderError::Setting(format!(
                "spectral range {min}:{max} nm must satisfy 0 < A < B"
            )));
        }
        if !(1..=4096).contains(&count) {
            return Err(RenderError::Setting(format!(
                "{count} spectral bands: expected 1 to 4096"
            )));
        }
        Ok(Self { min, max, count })
    }

    /// The range `(min, max)` the bands divide, nm.
    pub fn range(&self) -> (f32, f32) {
        (self.min, self.max)
    }

    /// Number of bands.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Width of each band, nm.
    pub fn width(&self) -> f64 {
        f64::from(self.max - self.min) / self.count as f64
    }

    /// The centre of band `i`, nm.
    pub fn center(&self, i: usize) -> f64 {
        f64::from(self.min) + (i as f64 + 0.5) * self.width()
    }

    /// The band holding `lambda`, if any.
    pub fn band_of(&self, lambda: f32) -> Option<usize> {
        if !(lambda >= self.min && lambda < self.max) {
            return None;
        }
        let i = (f64::from(lambda - self.min) / self.width()) as usize;
        Some(i.min(self.count - 1))
    }
}
