//! Cameras that are not the CIE observer: three measured response curves over any band
//! (a near-infrared or UV camera, a real sensor's RGB). The film then holds the camera's
//! raw channels, displayed as they are: false colour where the band is not visible.

use prism_spectrum::spectra::{Extrapolation, PiecewiseLinear};
use prism_spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};

use crate::RenderError;

/// Three response curves (channels shown as R, G, B), zero outside their table.
#[derive(Debug, Clone, PartialEq)]
pub struct CameraResponse {
    curves: [PiecewiseLinear; 3],
    range: (f32, f32),
}

impl CameraResponse {
    /// Parses CSV text with four columns, `nm, r, g, b` (commas or whitespace; a header
    /// line and `#` comments are skipped), wavelengths increasing, responses finite and
    /// >= 0, at least two rows and some response.
    pub fn from_csv(text: &str) -> Result<Self, RenderError> {
        let bad = |m: String| RenderError::Setting(format!("camera response: {m}"));
        let mut columns: [Vec<f64>; 4] = Default::default();
        for (i, line) in text.lines().enumerate() {
            let line = line.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            let fields: Vec<&str> = line
                .split(|c: char| c == ',' || c.is_whitespace())
                .filter(|f| !f.is_empty())
                .collect();
            let numbers: Option<Vec<f64>> = fields.iter().map(|f| f.parse().ok()).collect();
            match numbers {
                Some(n) if n.len() == 4 => {
                    for (column, v) in columns.iter_mut().zip(n) {
                        column.push(v);
                    }
                }
                // A header (a line of words before any data).
                None if columns[0].is_empty() => continue,
                _ => {
                    return Err(bad(format!(
                        "line {} is not four numbers (nm, r, g, b): '{line}'",
                        i + 1
                    )));
                }
            }
        }
        let [nm, r, g, b] = columns;
        if nm.len() < 2 {
            return Err(bad("needs at least two rows".into()));
        }
        if let Some(v) = r
            .iter()
            .chain(&g)
            .chain(&b)
            .find(|v| !(v.is_finite() && **v >= 0.0))
        {
            return Err(bad(format!("response {v} is not finite and >= 0")));
        }
        let curve = |values: Vec<f64>| {
            PiecewiseLinear::new(nm.clone(), values, Extrapolation::Zero)
                .map_err(|e| bad(e.to_string()))
        };
        let curves = [curve(r)?, curve(g)?, curve(b)?];
        if curves.iter().all(|c| c.max_value() == 0.0) {
            return Err(bad("every response is zero".into()));
        }
        let range = (nm[0] as f32, nm[nm.len() - 1] as f32);
        if !(range.0 > 0.0 && range.0 < range.1) {
            return Err(bad(format!(
                "wavelengths {}-{} nm must be positive and increasing",
                range.0, range.1
            )));
        }
        Ok(Self { curves, range })
    }

    /// The three responses at `lambda_nm`.
    pub fn response(&self, lambda_nm: f64) -> [f64; 3] {
        self.curves.each_ref().map(|c| c.evaluate(lambda_nm))
    }

    /// The wavelengths the curves cover, nm.
    pub fn range(&self) -> (f32, f32) {
        self.range
    }
}

impl CameraResponse {
    /// Monte Carlo estimate of the three channels, (1/N) sum_i r(l_i) S_i / p(l_i): the
    /// camera's counterpart of `SampledSpectrum::to_xyz`.
    pub fn channels<const N: usize>(
        &self,
        radiance: &SampledSpectrum<N>,
        wavelengths: &SampledWavelengths<N>,
    ) -> [f64; 3] {
        let mut out = [0.0f64; 3];
        for i in 0..N {
            let pdf = wavelengths.pdf(i);
            if pdf > 0.0 {
                let weight = f64::from(radiance[i]) / f64::from(pdf);
                for (acc, r) in out
                    .iter_mut()
                    .zip(self.response(f64::from(wavelengths.lambda(i))))
                {
                    *acc += r * weight;
                }
            }
        }
        out.map(|v| v / N as f64)
    }
}
