//! Cameras that are not the CIE observer: three measured response curves over any band
//! (a near-infrared or UV camera, a real sensor's RGB). The film then holds the camera's
//! raw channels, displayed as they are: false colour where the band is not visible.

use std::sync::Arc;

use prism_spectrum::spectra::{Extrapolation, PiecewiseLinear};
use prism_spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};

use crate::RenderError;

/// A response curve: any spectrum (tabulated from a file, or a scene's description).
pub type ResponseCurve = Arc<dyn Spectrum + Send + Sync>;

/// Three response curves (channels shown as R, G, B) and the band they cover.
#[derive(Clone)]
pub struct CameraResponse {
    curves: [ResponseCurve; 3],
    range: (f32, f32),
}

impl std::fmt::Debug for CameraResponse {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "CameraResponse({}-{} nm)", self.range.0, self.range.1)
    }
}

/// Two responses are the same when they share their curves (they are compared to tell
/// settings apart, not evaluated).
impl PartialEq for CameraResponse {
    fn eq(&self, other: &Self) -> bool {
        self.range == other.range
            && self
                .curves
                .iter()
                .zip(&other.curves)
                .all(|(a, b)| Arc::ptr_eq(a, b))
    }
}

impl CameraResponse {
    /// A camera of three curves over `range` nm (0 < start < end). Errors when a curve is
    /// negative or not finite in the range (checked at every nanometre), or all are zero.
    pub fn new(curves: [ResponseCurve; 3], range: (f32, f32)) -> Result<Self, RenderError> {
        let bad = |m: String| RenderError::Setting(format!("camera response: {m}"));
        if !(range.0.is_finite() && range.1.is_finite() && range.0 > 0.0 && range.0 < range.1) {
            return Err(bad(format!(
                "wavelengths {}-{} nm must be positive and increasing",
                range.0, range.1
            )));
        }
        let (lo, hi) = (range.0.floor() as i64, range.1.ceil() as i64);
        let mut any = false;
        for nm in lo..=hi {
            for c in &curves {
                let v = c.evaluate(nm as f64);
                if !(v.is_finite() && v >= 0.0) {
                    return Err(bad(format!(
                        "response {v} at {nm} nm is not finite and >= 0"
                    )));
                }
                any |= v > 0.0;
            }
        }
        if !any {
            return Err(bad("every response is zero".into()));
        }
        Ok(Self { curves, range })
    }

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
        let curve = |values: Vec<f64>| -> Result<ResponseCurve, RenderError> {
            Ok(Arc::new(
                PiecewiseLinear::new(nm.clone(), values, Extrapolation::Zero)
                    .map_err(|e| bad(e.to_string()))?,
            ))
        };
        let curves = [curve(r)?, curve(g)?, curve(b)?];
        Self::new(curves, (nm[0] as f32, nm[nm.len() - 1] as f32))
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
