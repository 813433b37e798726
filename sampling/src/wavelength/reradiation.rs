use super::WavelengthRange;
use crate::distribution::{PiecewiseConstant1D, density_f32};
use crate::error::SamplingError;

/// A sampled wavelength change at a fluorescent vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReradiationSample {
    /// The sampled wavelength, nm.
    pub lambda: f32,
    /// Its density, per nm.
    pub pdf: f32,
    /// The re-radiation value divided by the density: the throughput factor of the step.
    pub weight: f32,
}

/// Sampling of a discretized re-radiation (bispectral) matrix M, with rows the incident
/// wavelength bins and columns the outgoing ones; the diagonal is the ordinary reflectance,
/// off-diagonal entries fluorescence (the re-radiation matrix of bispectral rendering). Within a bin
/// the sampled wavelength is uniform, so M is treated as piecewise constant in both
/// wavelengths; entries are the density of re-radiated energy per nm of the sampled
/// wavelength.
///
/// Camera paths know the outgoing wavelength and sample the incident one from the column;
/// light paths know the incident wavelength and sample the outgoing one from the row.
#[derive(Debug, Clone, PartialEq)]
pub struct ReradiationSampler {
    range: WavelengthRange,
    bins: usize,
    matrix: Vec<f64>,
    /// Per outgoing bin: the distribution over incident wavelength (None: column all zero).
    by_outgoing: Vec<Option<PiecewiseConstant1D>>,
    /// Per incident bin: the distribution over outgoing wavelength (None: row all zero).
    by_incident: Vec<Option<PiecewiseConstant1D>>,
}

impl ReradiationSampler {
    /// A sampler for the `bins x bins` matrix `matrix` (row-major, rows incident) over
    /// `range`; entries finite and >= 0.
    pub fn new(range: WavelengthRange, bins: usize, matrix: &[f64]) -> Result<Self, SamplingError> {
        if bins == 0 || bins.checked_mul(bins) != Some(matrix.len()) {
            return Err(SamplingError::InvalidParameter(format!(
                "a re-radiation matrix of {bins} bins needs {} entries, got {}",
                bins.saturating_mul(bins),
                matrix.len()
            )));
        }
        crate::error::validate(matrix)?;
        let (lo, hi) = (f64::from(range.min()), f64::from(range.max()));
        let make = |values: Vec<f64>| match PiecewiseConstant1D::new(&values, lo, hi) {
            Ok(d) => Ok(Some(d)),
            Err(SamplingError::AllZero) => Ok(None),
            Err(e) => Err(e),
        };
        let by_incident = (0..bins)
            .map(|i| make(matrix[i * bins..(i + 1) * bins].to_vec()))
            .collect::<Result<Vec<_>, _>>()?;
        let by_outgoing = (0..bins)
            .map(|o| make((0..bins).map(|i| matrix[i * bins + o]).collect()))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            range,
            bins,
            matrix: matrix.to_vec(),
            by_outgoing,
            by_incident,
        })
    }

    /// The wavelength range the matrix covers, nm.
    pub fn range_nm(&self) -> (f32, f32) {
        (self.range.min(), self.range.max())
    }

    /// The bin of `lambda`, or None outside the range.
    pub fn bin(&self, lambda: f32) -> Option<usize> {
        if !self.range.contains(lambda) {
            return None;
        }
        let t = (lambda - self.range.min()) / self.range.width();
        Some(((t * self.bins as f32) as u32 as usize).min(self.bins - 1))
    }

    /// M(incident, outgoing) at two wavelengths (0 outside the range).
    pub fn value(&self, lambda_incident: f32, lambda_outgoing: f32) -> f64 {
        match (self.bin(lambda_incident), self.bin(lambda_outgoing)) {
            (Some(i), Some(o)) => self.matrix[i * self.bins + o],
            _ => 0.0,
        }
    }

    /// The integral over incident wavelengths of M(., outgoing): what a camera path's
    /// throughput is multiplied by when it samples the incident wavelength (0 when
    /// nothing re-radiates into `lambda_outgoing`).
    pub fn incident_integral(&self, lambda_outgoing: f32) -> f64 {
        self.bin(lambda_outgoing)
            .and_then(|o| self.by_outgoing[o].as_ref())
            .map_or(0.0, PiecewiseConstant1D::integral)
    }

    /// The integral over outgoing wavelengths of M(incident, .): the fraction of light
    /// arriving at `lambda_incident` that is re-radiated (its absorption times quantum
    /// yield, for a fluorescent dye).
    pub fn outgoing_integral(&self, lambda_incident: f32) -> f64 {
        self.bin(lambda_incident)
            .and_then(|i| self.by_incident[i].as_ref())
            .map_or(0.0, PiecewiseConstant1D::integral)
    }

    /// Camera paths: an incident wavelength for outgoing `lambda_outgoing`, with density
    /// proportional to M(., outgoing). None if nothing re-radiates into that wavelength.
    pub fn sample_incident(&self, lambda_outgoing: f32, u: f64) -> Option<ReradiationSample> {
        let column = self.by_outgoing[self.bin(lambda_outgoing)?].as_ref()?;
        let s = column.sample(u);
        Some(ReradiationSample {
            lambda: self.range.clamp(s.value as f32),
            pdf: density_f32(s.pdf),
            weight: (column.integral()) as f32,
        })
    }

    /// Light paths: an outgoing wavelength for incident `lambda_incident`, with density
    /// proportional to M(incident, .). None if that wavelength is not re-radiated at all.
    pub fn sample_outgoing(&self, lambda_incident: f32, u: f64) -> Option<ReradiationSample> {
        let row = self.by_incident[self.bin(lambda_incident)?].as_ref()?;
        let s = row.sample(u);
        Some(ReradiationSample {
            lambda: self.range.clamp(s.value as f32),
            pdf: density_f32(s.pdf),
            weight: row.integral() as f32,
        })
    }

    /// The density with which [`ReradiationSampler::sample_incident`] returns
    /// `lambda_incident` given `lambda_outgoing`.
    pub fn pdf_incident(&self, lambda_incident: f32, lambda_outgoing: f32) -> f32 {
        self.bin(lambda_outgoing)
            .and_then(|o| self.by_outgoing[o].as_ref())
            .map_or(0.0, |c| density_f32(c.pdf(f64::from(lambda_incident))))
    }

    /// The density with which [`ReradiationSampler::sample_outgoing`] returns
    /// `lambda_outgoing` given `lambda_incident`.
    pub fn pdf_outgoing(&self, lambda_outgoing: f32, lambda_incident: f32) -> f32 {
        self.bin(lambda_incident)
            .and_then(|i| self.by_incident[i].as_ref())
            .map_or(0.0, |r| density_f32(r.pdf(f64::from(lambda_outgoing))))
    }
}
