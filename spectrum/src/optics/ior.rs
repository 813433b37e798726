use crate::Spectrum;
use crate::error::{SpectrumError, require_finite, require_positive};

/// Fraunhofer d line (helium), nm: where n_d is specified.
pub const FRAUNHOFER_D_NM: f64 = 587.5618;
/// Fraunhofer F line (hydrogen), nm.
pub const FRAUNHOFER_F_NM: f64 = 486.1327;
/// Fraunhofer C line (hydrogen), nm.
pub const FRAUNHOFER_C_NM: f64 = 656.2725;

/// A wavelength moved into a model's valid range; NaN goes to the range start. This is the
/// documented clamp of every index model here: outside its fitted range a dispersion
/// formula is meaningless (or runs into a pole), so the nearest valid index is used.
fn clamp_to_range(lambda_nm: f64, (lo, hi): (f64, f64)) -> f64 {
    if lambda_nm.is_nan() {
        lo
    } else {
        lambda_nm.clamp(lo, hi)
    }
}

/// The Sellmeier dispersion formula n^2(l) = 1 + sum_i B_i l^2 / (l^2 - C_i), with l in
/// micrometres and C_i in square micrometres (the convention of glass catalogues, SCHOTT's
/// BK7 data sheet among them).
///
/// Each term has a pole (a resonance) at l = sqrt(C_i). The formula is only meaningful
/// between poles, on the range it was fitted to, so a `Sellmeier` carries its valid range
/// and [`Spectrum::evaluate`] clamps the wavelength into it: outside the range the index is
/// that of the nearest end (documented clamp; never NaN, never a pole).
#[derive(Debug, Clone, PartialEq)]
pub struct Sellmeier {
    terms: Vec<(f64, f64)>,
    range_nm: (f64, f64),
}

impl Sellmeier {
    /// A Sellmeier model from `(B_i, C_i)` terms (C_i in um^2, B_i >= 0, C_i >= 0, all finite)
    /// valid over `range_nm`. Errors when a pole lies inside the range, or when n^2 <= 0
    /// somewhere in it (checked exactly: with non-negative B and C, n^2 decreases
    /// monotonically between poles, so the range ends bound it).
    pub fn new(terms: Vec<(f64, f64)>, range_nm: (f64, f64)) -> Result<Self, SpectrumError> {
        if terms.is_empty() {
            return Err(SpectrumError::InvalidTable(
                "a Sellmeier model needs at least one term".into(),
            ));
        }
        let (lo, hi) = range_nm;
        require_positive("Sellmeier range start (nm)", lo)?;
        require_positive("Sellmeier range end (nm)", hi)?;
        if lo >= hi {
            return Err(SpectrumError::InvalidTable(format!(
                "Sellmeier range {lo}-{hi} nm is empty"
            )));
        }
        for &(b, c) in &terms {
            if !(b.is_finite() && c.is_finite() && b >= 0.0 && c >= 0.0) {
                return Err(SpectrumError::InvalidTable(format!(
                    "Sellmeier term (B = {b}, C = {c}) must have finite B >= 0 and C >= 0"
                )));
            }
            let pole_nm = c.sqrt() * 1000.0;
            if pole_nm >= lo && pole_nm <= hi {
                return Err(SpectrumError::InvalidTable(format!(
                    "Sellmeier resonance at {pole_nm:.1} nm lies inside the valid range {lo}-{hi} nm"
                )));
            }
        }
        let model = Self { terms, range_nm };
        for end in [lo, hi] {
            let n2 = model.n_squared(end);
            if !(n2.is_finite() && n2 > 0.0) {
                return Err(SpectrumError::InvalidTable(format!(
                    "Sellmeier n^2 = {n2} at {end} nm: the model is not a refractive index there"
                )));
            }
        }
        Ok(model)
    }

    /// The valid range, nm.
    pub fn range_nm(&self) -> (f64, f64) {
        self.range_nm
    }

    /// The `(B_i, C_i)` terms.
    pub fn terms(&self) -> &[(f64, f64)] {
        &self.terms
    }

    fn n_squared(&self, lambda_nm: f64) -> f64 {
        let l2 = (lambda_nm * 1e-3).powi(2);
        1.0 + self
            .terms
            .iter()
            .map(|&(b, c)| b * l2 / (l2 - c))
            .sum::<f64>()
    }
}

impl Spectrum for Sellmeier {
    /// n at `lambda_nm` clamped into the valid range; NaN wavelengths evaluate at the range
    /// start.
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        let l = clamp_to_range(lambda_nm, self.range_nm);
        self.n_squared(l).sqrt()
    }

    fn max_value(&self) -> f64 {
        // With B, C >= 0, n^2 decreases monotonically in wavelength between poles (each
        // term's derivative in l^2 is -B C / (l^2 - C)^2 <= 0): the maximum is at an end.
        let (lo, hi) = self.range_nm;
        self.evaluate(lo).max(self.evaluate(hi))
    }
}

/// Cauchy's equation n(l) = A + B / l^2 + C / l^4 with l in nm, clamped to n >= 1 and to
/// its valid wavelength range (outside it the nearest end's index is used).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cauchy {
    a: f64,
    b_nm2: f64,
    c_nm4: f64,
    range_nm: (f64, f64),
}

impl Cauchy {
    /// Range used by [`Cauchy::from_abbe`]: wide enough for UV and near-IR rendering; the
    /// two-term model is an approximation everywhere and not meant beyond it.
    pub const ABBE_RANGE_NM: (f64, f64) = (200.0, 2500.0);

    /// A Cauchy model with coefficients A, B (nm^2), C (nm^4), valid over `range_nm`.
    pub fn new(
        a: f64,
        b_nm2: f64,
        c_nm4: f64,
        range_nm: (f64, f64),
    ) -> Result<Self, SpectrumError> {
        require_finite("Cauchy A", a)?;
        require_finite("Cauchy B (nm^2)", b_nm2)?;
        require_finite("Cauchy C (nm^4)", c_nm4)?;
        let lo = require_positive("Cauchy range start (nm)", range_nm.0)?;
        let hi = require_positive("Cauchy range end (nm)", range_nm.1)?;
        if lo >= hi {
            return Err(SpectrumError::InvalidTable(format!(
                "Cauchy range {lo}-{hi} nm is empty"
            )));
        }
        Ok(Self {
            a,
            b_nm2,
            c_nm4,
            range_nm,
        })
    }

    /// The two-term Cauchy model that glTF `KHR_materials_dispersion` defines from the
    /// index at the d line `n_d` and the Abbe number `abbe` (V_d = 20 / dispersion):
    /// n(l) = max(n_d + (n_d - 1) / V_d (523655 / l^2 - 1.5168), 1). The constants are the
    /// extension's own (they are 1 / (l_F^-2 - l_C^-2) and l_d^2 times that, rounded; a
    /// test derives them from the Fraunhofer lines). Needs n_d >= 1 and V_d > 0, finite.
    pub fn from_abbe(n_d: f64, abbe: f64) -> Result<Self, SpectrumError> {
        if !(n_d.is_finite() && n_d >= 1.0) {
            return Err(SpectrumError::InvalidValue {
                what: "index of refraction n_d",
                value: n_d,
                expected: "a finite number >= 1",
            });
        }
        let abbe = require_positive("Abbe number", abbe)?;
        let k = (n_d - 1.0) / abbe;
        Self::new(n_d - 1.5168 * k, 523_655.0 * k, 0.0, Self::ABBE_RANGE_NM)
    }

    /// A, B (nm^2), C (nm^4).
    pub fn coefficients(&self) -> (f64, f64, f64) {
        (self.a, self.b_nm2, self.c_nm4)
    }
}

impl Spectrum for Cauchy {
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        let l = clamp_to_range(lambda_nm, self.range_nm);
        let inv2 = 1.0 / (l * l);
        (self.a + self.b_nm2 * inv2 + self.c_nm4 * inv2 * inv2).max(1.0)
    }

    fn max_value(&self) -> f64 {
        let (lo, hi) = self.range_nm;
        self.evaluate(lo).max(self.evaluate(hi))
    }
}

/// The Abbe number V_d = (n_d - 1) / (n_F - n_C) of an index-of-refraction spectrum.
/// Errors for a non-dispersive (or anomalously flat) index where n_F = n_C.
pub fn abbe_number<S: Spectrum + ?Sized>(ior: &S) -> Result<f64, SpectrumError> {
    let n_d = ior.evaluate(FRAUNHOFER_D_NM);
    let spread = ior.evaluate(FRAUNHOFER_F_NM) - ior.evaluate(FRAUNHOFER_C_NM);
    let v = (n_d - 1.0) / spread;
    if spread == 0.0 || !v.is_finite() {
        return Err(SpectrumError::Degenerate(
            "the index does not vary between the F and C lines: Abbe number is infinite".into(),
        ));
    }
    Ok(v)
}
