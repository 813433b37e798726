use crate::Spectrum;
use crate::error::{SpectrumError, require_finite};

/// A spectrum stored at every whole nanometre of a range, for O(1) evaluation in hot
/// loops. Between whole nanometres it interpolates linearly; outside the range it is 0.
#[derive(Debug, Clone, PartialEq)]
pub struct DenselySampled {
    first_nm: f64,
    values: Vec<f64>,
    max: f64,
}

impl DenselySampled {
    /// Samples `spectrum` at `first_nm, first_nm + 1, ..., last_nm` (whole nanometres,
    /// `first_nm <= last_nm`, at most 10^7 samples).
    pub fn from_spectrum<S: Spectrum + ?Sized>(
        spectrum: &S,
        first_nm: i32,
        last_nm: i32,
    ) -> Result<Self, SpectrumError> {
        if last_nm < first_nm || i64::from(last_nm) - i64::from(first_nm) >= 10_000_000 {
            return Err(SpectrumError::InvalidTable(format!(
                "dense range {first_nm}..={last_nm} nm is empty or longer than 10^7 nm"
            )));
        }
        let values = (first_nm..=last_nm)
            .map(|l| spectrum.evaluate(f64::from(l)))
            .collect();
        Self::from_values(f64::from(first_nm), values)
    }

    /// Values at `first_nm, first_nm + 1, ...` (all finite, at least one).
    pub fn from_values(first_nm: f64, values: Vec<f64>) -> Result<Self, SpectrumError> {
        require_finite("first wavelength (nm)", first_nm)?;
        if values.is_empty() {
            return Err(SpectrumError::InvalidTable("no samples".into()));
        }
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            return Err(SpectrumError::InvalidTable(format!(
                "value {v} is not finite"
            )));
        }
        let max = values.iter().copied().fold(0.0, f64::max);
        Ok(Self {
            first_nm,
            values,
            max,
        })
    }

    /// The spectrum at `N` wavelengths (nm) at once, in f32: what a renderer samples per
    /// path, without an f64 call per wavelength (measured: the f64 path was a noticeable
    /// share of a Cornell box render's instructions, through its light's D65). The same linear
    /// interpolation as [`Spectrum::evaluate`], 0 outside the range and for NaN; within
    /// f32 rounding of it.
    pub fn evaluate_lanes<const N: usize>(&self, lambda: &[f32; N]) -> [f32; N] {
        let last = self.values.len() - 1;
        let (first, span) = (self.first_nm as f32, last as f32);
        std::array::from_fn(|k| {
            let x = lambda[k] - first;
            // Written so that NaN fails the test and gives 0.
            if !(x >= 0.0 && x <= span) {
                return 0.0;
            }
            // x >= 0: truncation is the floor (through u32, a few instructions where the
            // saturating cast to usize is a dozen).
            let i = (x as u32 as usize).min(last);
            let t = x - i as f32;
            let (a, b) = (self.values[i] as f32, self.values[(i + 1).min(last)] as f32);
            (1.0 - t) * a + t * b
        })
    }

    /// First wavelength, nm.
    pub fn first_nm(&self) -> f64 {
        self.first_nm
    }

    /// The samples, one per nanometre.
    pub fn values(&self) -> &[f64] {
        &self.values
    }
}

impl Spectrum for DenselySampled {
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        let x = lambda_nm - self.first_nm;
        let last = (self.values.len() - 1) as f64;
        // Written so that NaN fails the test and returns 0.
        if !(x >= 0.0 && x <= last) {
            return 0.0;
        }
        // x >= 0, so truncation is the floor (f64::floor is a libm call on baseline
        // x86-64: measured, a noticeable share of a Cornell box render's instructions).
        let i = (x as u32 as usize).min(self.values.len() - 1);
        if i + 1 == self.values.len() {
            return self.values[i];
        }
        let t = x - i as f64;
        (1.0 - t) * self.values[i] + t * self.values[i + 1]
    }

    fn max_value(&self) -> f64 {
        self.max
    }
}
