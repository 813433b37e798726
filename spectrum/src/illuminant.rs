//! CIE standard illuminants and the CIE daylight series.
//!
//! Tables from CIE 015:2018 (Table 5 for A, D-series and E; Table 10 for F1-F12; Table 6
//! for the daylight basis S0, S1, S2), via colour-science (see `data/PROVENANCE.md`).

use crate::colorimetry::{Chromaticity, Observer, emission_xyz};
use crate::data::cie_illuminants::{self as tables, RegularTable};
use crate::error::SpectrumError;
use crate::spectra::{Extrapolation, PiecewiseLinear};

/// A CIE standard illuminant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum StandardIlluminant {
    /// Incandescent tungsten, 2856 K.
    A,
    /// Horizon daylight, ~5003 K.
    D50,
    /// Mid-morning daylight, ~5503 K.
    D55,
    /// Noon daylight, ~6504 K: the white of sRGB and Rec.2020.
    D65,
    /// North sky daylight, ~7504 K.
    D75,
    /// Equal energy.
    E,
    /// Fluorescent lamps F1 to F12 (the number, 1..=12).
    F(u8),
}

impl StandardIlluminant {
    /// Names accepted by [`StandardIlluminant::from_name`].
    pub const NAMES: &'static str = "A, D50, D55, D65, D75, E, F1-F12 (or FL1-FL12)";

    /// Every standard illuminant.
    pub fn all() -> impl Iterator<Item = Self> {
        use StandardIlluminant::*;
        [A, D50, D55, D65, D75, E]
            .into_iter()
            .chain((1..=12).map(F))
    }

    /// Parses a CIE name, any case: `A`, `D50`, `D55`, `D65`, `D75`, `E`, `F1`..`F12`
    /// (`FL1`..`FL12` too).
    pub fn from_name(name: &str) -> Result<Self, SpectrumError> {
        use StandardIlluminant::*;
        let upper = name.trim().to_ascii_uppercase();
        let parsed = match upper.as_str() {
            "A" => Some(A),
            "D50" => Some(D50),
            "D55" => Some(D55),
            "D65" => Some(D65),
            "D75" => Some(D75),
            "E" => Some(E),
            other => other
                .strip_prefix("FL")
                .or_else(|| other.strip_prefix('F'))
                .and_then(|n| n.parse::<u8>().ok())
                .filter(|n| (1..=12).contains(n))
                .map(F),
        };
        parsed.ok_or_else(|| SpectrumError::UnknownName {
            kind: "illuminant",
            name: name.to_string(),
            valid: Self::NAMES.to_string(),
        })
    }

    /// The CIE name (`F` series as `F1`..`F12`).
    pub fn name(self) -> String {
        match self {
            StandardIlluminant::F(n) => format!("F{n}"),
            other => format!("{other:?}"),
        }
    }

    fn table(self) -> &'static RegularTable {
        use StandardIlluminant::*;
        match self {
            A => &tables::A,
            D50 => &tables::D50,
            D55 => &tables::D55,
            D65 => &tables::D65,
            D75 => &tables::D75,
            E => &tables::E,
            F(n) => [
                &tables::F1,
                &tables::F2,
                &tables::F3,
                &tables::F4,
                &tables::F5,
                &tables::F6,
                &tables::F7,
                &tables::F8,
                &tables::F9,
                &tables::F10,
                &tables::F11,
                &tables::F12,
            ][usize::from(n.clamp(1, 12)) - 1],
        }
    }

    /// The relative spectral power distribution as tabulated by the CIE (normalized to
    /// 100 at 560 nm), linearly interpolated, zero outside the table.
    pub fn spectrum(self) -> PiecewiseLinear {
        regular(self.table())
    }

    /// The chromaticity of the tabulated spectrum under `observer`, integrated at 1 nm
    /// like every chromaticity in this crate (for D65 and CIE 1931: 0.31273, 0.32902).
    pub fn chromaticity(self, observer: Observer) -> Chromaticity {
        let xyz = emission_xyz(&self.spectrum(), observer);
        let sum = xyz.x + xyz.y + xyz.z;
        Chromaticity::new(xyz.x / sum, xyz.y / sum)
    }
}

fn regular(table: &RegularTable) -> PiecewiseLinear {
    let lambdas = (0..table.values.len())
        .map(|i| table.first_nm + table.step_nm * i as f64)
        .collect();
    // The embedded tables are sorted and finite (tests/cie_tables.rs proves it), so this
    // cannot fail; rebuilding the checks here would be a second copy of the same validation.
    PiecewiseLinear::new(lambdas, table.values.to_vec(), Extrapolation::Zero)
        .unwrap_or_else(|e| unreachable!("embedded CIE table is invalid: {e}"))
}

/// Lowest correlated colour temperature of the CIE daylight series, K.
pub const DAYLIGHT_MIN_KELVIN: f64 = 4000.0;
/// Highest correlated colour temperature of the CIE daylight series, K.
pub const DAYLIGHT_MAX_KELVIN: f64 = 25000.0;

/// The chromaticity of CIE daylight at correlated colour temperature `kelvin`
/// (CIE 015:2018 §4.1, eq. 4.1-4.3), for 4000 K <= `kelvin` <= 25000 K.
///
/// The nominal temperatures of D50/D65 used the older radiation constant c2 = 1.4380e-2;
/// to reproduce D65 exactly pass 6500 * 1.4388 / 1.4380 (about 6504 K).
pub fn daylight_chromaticity(kelvin: f64) -> Result<Chromaticity, SpectrumError> {
    if !(DAYLIGHT_MIN_KELVIN..=DAYLIGHT_MAX_KELVIN).contains(&kelvin) {
        return Err(SpectrumError::InvalidValue {
            what: "daylight CCT (K)",
            value: kelvin,
            expected: "4000 <= CCT <= 25000 (the CIE daylight locus)",
        });
    }
    let t = kelvin;
    let x = if t <= 7000.0 {
        -4.6070e9 / (t * t * t) + 2.9678e6 / (t * t) + 0.09911e3 / t + 0.244063
    } else {
        -2.0064e9 / (t * t * t) + 1.9018e6 / (t * t) + 0.24748e3 / t + 0.237040
    };
    let y = -3.000 * x * x + 2.870 * x - 0.275;
    Ok(Chromaticity::new(x, y))
}

/// The relative spectral power of CIE daylight at `kelvin` (4000-25000 K), S0 + M1 S1 +
/// M2 S2 with M1 and M2 rounded to three decimals as CIE 015:2018 §4.1 prescribes (so
/// that 6504 K reproduces the tabulated D65), 300-830 nm at 5 nm, zero outside.
pub fn daylight(kelvin: f64) -> Result<PiecewiseLinear, SpectrumError> {
    let xy = daylight_chromaticity(kelvin)?;
    let m = 0.0241 + 0.2562 * xy.x - 0.7341 * xy.y;
    let round3 = |v: f64| (v * 1000.0).round() / 1000.0;
    let m1 = round3((-1.3515 - 1.7703 * xy.x + 5.9114 * xy.y) / m);
    let m2 = round3((0.0300 - 31.4424 * xy.x + 30.0717 * xy.y) / m);
    let (s0, s1, s2) = (
        &tables::DAYLIGHT_S0,
        &tables::DAYLIGHT_S1,
        &tables::DAYLIGHT_S2,
    );
    let values: Vec<f64> = (0..s0.values.len())
        .map(|i| s0.values[i] + m1 * s1.values[i] + m2 * s2.values[i])
        .collect();
    PiecewiseLinear::from_regular(s0.first_nm, s0.step_nm, &values, Extrapolation::Zero)
}
