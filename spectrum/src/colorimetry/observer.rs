use crate::data::cie_cmf::{self, CMF_FIRST_NM, CMF_LEN};
use crate::error::SpectrumError;

/// A CIE standard colorimetric observer: the colour matching functions x-bar, y-bar,
/// z-bar, tabulated at 1 nm from 360 to 830 nm (CIE 015:2018, Tables 1 and 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Observer {
    /// CIE 1931 2-degree standard observer.
    #[default]
    Cie1931,
    /// CIE 1964 10-degree supplementary standard observer.
    Cie1964,
}

impl Observer {
    /// Names accepted by [`Observer::from_name`].
    pub const NAMES: &'static str = "cie1931, cie1964";

    /// Parses `cie1931` (also `1931`, `2`) or `cie1964` (also `1964`, `10`), any case.
    pub fn from_name(name: &str) -> Result<Self, SpectrumError> {
        match name.to_ascii_lowercase().as_str() {
            "cie1931" | "1931" | "2" | "cie1931-2" => Ok(Observer::Cie1931),
            "cie1964" | "1964" | "10" | "cie1964-10" => Ok(Observer::Cie1964),
            _ => Err(SpectrumError::UnknownName {
                kind: "observer",
                name: name.to_string(),
                valid: Self::NAMES.to_string(),
            }),
        }
    }

    /// The canonical name.
    pub fn name(self) -> &'static str {
        match self {
            Observer::Cie1931 => "cie1931",
            Observer::Cie1964 => "cie1964",
        }
    }

    /// The three tables (x-bar, y-bar, z-bar) at 360..=830 nm.
    pub fn tables(self) -> [&'static [f64; CMF_LEN]; 3] {
        match self {
            Observer::Cie1931 => [
                &cie_cmf::CIE1931_X,
                &cie_cmf::CIE1931_Y,
                &cie_cmf::CIE1931_Z,
            ],
            Observer::Cie1964 => [
                &cie_cmf::CIE1964_X,
                &cie_cmf::CIE1964_Y,
                &cie_cmf::CIE1964_Z,
            ],
        }
    }

    /// x-bar, y-bar, z-bar at `lambda_nm`, linearly interpolated; 0 outside 360-830 nm
    /// and for NaN.
    pub fn cmf(self, lambda_nm: f64) -> [f64; 3] {
        let x = lambda_nm - CMF_FIRST_NM;
        let last = (CMF_LEN - 1) as f64;
        if !(x >= 0.0 && x <= last) {
            return [0.0; 3];
        }
        // Through u32: Rust's saturating float-to-usize cast is a dozen instructions on
        // baseline x86-64 (no AVX-512), to u32 a few; x is in range, so both agree.
        let i = (x as u32 as usize).min(CMF_LEN - 2);
        let t = x - i as f64;
        // The film calls this for every lane of every sample: both nodes' three values
        // are two adjacent rows of one table rather than six loads from three.
        let table = match self {
            Observer::Cie1931 => &CIE1931_ROWS,
            Observer::Cie1964 => &CIE1964_ROWS,
        };
        let (a, b) = (table[i], table[i + 1]);
        [0, 1, 2].map(|k| (1.0 - t) * a[k] + t * b[k])
    }
}

/// The three tables of an observer as rows (x-bar, y-bar, z-bar) per nm, made at compile
/// time from the generated tables, so there is still one source of the data.
const fn rows(tables: [&[f64; CMF_LEN]; 3]) -> [[f64; 3]; CMF_LEN] {
    let mut rows = [[0.0; 3]; CMF_LEN];
    let mut i = 0;
    while i < CMF_LEN {
        rows[i] = [tables[0][i], tables[1][i], tables[2][i]];
        i += 1;
    }
    rows
}

static CIE1931_ROWS: [[f64; 3]; CMF_LEN] = rows([
    &cie_cmf::CIE1931_X,
    &cie_cmf::CIE1931_Y,
    &cie_cmf::CIE1931_Z,
]);
static CIE1964_ROWS: [[f64; 3]; CMF_LEN] = rows([
    &cie_cmf::CIE1964_X,
    &cie_cmf::CIE1964_Y,
    &cie_cmf::CIE1964_Z,
]);
