use crate::Spectrum;
use crate::error::{Readable, SpectrumError};

/// What a tabulated spectrum is outside its first and last wavelength.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Extrapolation {
    /// Zero outside the table: the convention for emission and colour-matching data,
    /// where "no data" means "no light".
    #[default]
    Zero,
    /// The nearest end value: the convention for material properties (an index of
    /// refraction does not drop to zero past the end of a measurement).
    Clamp,
}

/// A spectrum tabulated at increasing, possibly irregularly spaced wavelengths and
/// linearly interpolated between them.
#[derive(Debug, Clone, PartialEq)]
pub struct PiecewiseLinear {
    lambdas: Vec<f64>,
    values: Vec<f64>,
    extrapolation: Extrapolation,
    max: f64,
}

impl PiecewiseLinear {
    /// A table from wavelengths (nm, strictly increasing, finite) and values (finite), at
    /// least two of each and the same number of both.
    pub fn new(
        lambdas: Vec<f64>,
        values: Vec<f64>,
        extrapolation: Extrapolation,
    ) -> Result<Self, SpectrumError> {
        if lambdas.len() != values.len() {
            return Err(SpectrumError::InvalidTable(format!(
                "{} wavelengths but {} values",
                lambdas.len(),
                values.len()
            )));
        }
        if lambdas.len() < 2 {
            return Err(SpectrumError::InvalidTable(format!(
                "needs at least 2 samples, got {}",
                lambdas.len()
            )));
        }
        if let Some(i) = lambdas.iter().position(|l| !l.is_finite()) {
            return Err(SpectrumError::InvalidTable(format!(
                "wavelength {} at row {} is not finite",
                lambdas[i],
                i + 1
            )));
        }
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(SpectrumError::InvalidTable(format!(
                "value {} at row {} is not finite",
                values[i],
                i + 1
            )));
        }
        if let Some(i) = lambdas.windows(2).position(|w| w[0] >= w[1]) {
            return Err(SpectrumError::InvalidTable(format!(
                "wavelengths must increase strictly: {} nm at row {} is followed by {} nm",
                Readable(lambdas[i]),
                i + 1,
                Readable(lambdas[i + 1])
            )));
        }
        // An upper bound that includes 0, the value at NaN wavelengths (and outside the
        // table under `Extrapolation::Zero`).
        let max = values.iter().copied().fold(0.0, f64::max);
        Ok(Self {
            lambdas,
            values,
            extrapolation,
            max,
        })
    }

    /// A table on a regular grid starting at `first_nm` with spacing `step_nm`.
    pub fn from_regular(
        first_nm: f64,
        step_nm: f64,
        values: &[f64],
        extrapolation: Extrapolation,
    ) -> Result<Self, SpectrumError> {
        let lambdas = (0..values.len())
            .map(|i| first_nm + step_nm * i as f64)
            .collect();
        Self::new(lambdas, values.to_vec(), extrapolation)
    }

    /// Parses two-column text, `wavelength_nm, value` per line. Columns may be separated by
    /// a comma, semicolon, tab or spaces; blank lines and lines starting with `#` are
    /// skipped, and so are lines before the first data row that do not start with a number
    /// (headers).
    ///
    /// ```
    /// use prism_spectrum::spectra::{Extrapolation, PiecewiseLinear};
    /// use prism_spectrum::Spectrum;
    ///
    /// let csv = "wavelength,reflectance\n400,0.1\n500,0.3\n700,0.9\n";
    /// let red = PiecewiseLinear::from_csv_str(csv, Extrapolation::Clamp)?;
    /// assert!((red.evaluate(450.0) - 0.2).abs() < 1e-12);
    /// assert_eq!(red.evaluate(800.0), 0.9);
    /// // Rows out of order are an error naming them, not a silently wrong spectrum.
    /// assert!(PiecewiseLinear::from_csv_str("500,1\n400,1\n", Extrapolation::Zero).is_err());
    /// # Ok::<(), prism_spectrum::SpectrumError>(())
    /// ```
    pub fn from_csv_str(text: &str, extrapolation: Extrapolation) -> Result<Self, SpectrumError> {
        let mut lambdas = Vec::new();
        let mut values = Vec::new();
        let mut seen_data = false;
        for (index, raw) in text.lines().enumerate() {
            let line = raw.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let fields: Vec<&str> = line
                .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
                .filter(|f| !f.is_empty())
                .collect();
            let parsed: Option<Vec<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
            match parsed {
                Some(numbers) if numbers.len() == 2 => {
                    lambdas.push(numbers[0]);
                    values.push(numbers[1]);
                    seen_data = true;
                }
                // A header: text before any data, not starting with a number.
                None if !seen_data && fields.first().is_none_or(|f| f.parse::<f64>().is_err()) => {
                    continue;
                }
                _ => {
                    return Err(SpectrumError::InvalidTable(format!(
                        "line {}: expected two numbers 'wavelength_nm, value', got '{}'",
                        index + 1,
                        line
                    )));
                }
            }
        }
        Self::new(lambdas, values, extrapolation)
    }

    /// The tabulated wavelengths, nm.
    pub fn lambdas(&self) -> &[f64] {
        &self.lambdas
    }

    /// The tabulated values.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The same table with every value multiplied by `factor` (finite).
    pub fn scaled(&self, factor: f64) -> Result<Self, SpectrumError> {
        let values = self.values.iter().map(|v| v * factor).collect();
        Self::new(self.lambdas.clone(), values, self.extrapolation)
    }
}

impl Spectrum for PiecewiseLinear {
    /// Linear interpolation; outside the table as its [`Extrapolation`] says; 0 for NaN.
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        let n = self.lambdas.len();
        if lambda_nm.is_nan() {
            return 0.0;
        }
        if lambda_nm <= self.lambdas[0] || lambda_nm >= self.lambdas[n - 1] {
            let edge = if lambda_nm <= self.lambdas[0] {
                0
            } else {
                n - 1
            };
            return match self.extrapolation {
                Extrapolation::Clamp => self.values[edge],
                Extrapolation::Zero if lambda_nm == self.lambdas[edge] => self.values[edge],
                Extrapolation::Zero => 0.0,
            };
        }
        // First index whose wavelength exceeds lambda: the segment is [i - 1, i].
        let i = self.lambdas.partition_point(|&l| l <= lambda_nm);
        let (l0, l1) = (self.lambdas[i - 1], self.lambdas[i]);
        let t = (lambda_nm - l0) / (l1 - l0);
        // (1 - t) a + t b stays within [a, b] and exact at the nodes.
        (1.0 - t) * self.values[i - 1] + t * self.values[i]
    }

    fn max_value(&self) -> f64 {
        self.max
    }
}
