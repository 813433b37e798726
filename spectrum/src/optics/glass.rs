use super::Sellmeier;
use crate::error::SpectrumError;

/// A named optical material of the catalogue: its dispersion model and where the
/// coefficients come from.
#[derive(Debug, Clone, PartialEq)]
pub struct Glass {
    /// Canonical name (see [`GLASS_NAMES`]).
    pub name: &'static str,
    /// The dispersion model.
    pub ior: Sellmeier,
    /// Where the coefficients were published.
    pub source: &'static str,
}

/// Names accepted by [`named_glass`] (case-insensitive; `n-bk7`, `n-baf10`, `silica`,
/// `sapphire-o`, `fluorite` accepted as aliases).
pub const GLASS_NAMES: &str = "bk7, fused-silica, sf11, f2, baf10, sapphire, caf2, water, diamond";

struct Entry {
    name: &'static str,
    aliases: &'static [&'static str],
    // (B_i, C_i in um^2)
    terms: &'static [(f64, f64)],
    range_nm: (f64, f64),
    source: &'static str,
}

/// Coefficients as published (Sellmeier form "formula 2", C in um^2; where the source
/// gives resonance wavelengths lambda_i in um, C_i = lambda_i^2 is written as a square).
/// Each was checked against the CC0 transcription in the refractiveindex.info database;
/// `tests/optics.rs` checks n_d and V_d against the manufacturers' data sheets.
const CATALOG: &[Entry] = &[
    Entry {
        name: "bk7",
        aliases: &["n-bk7"],
        terms: &[
            (1.039_612_12, 0.006_000_698_67),
            (0.231_792_344, 0.020_017_914_4),
            (1.010_469_45, 103.560_653),
        ],
        range_nm: (300.0, 2500.0),
        source: "SCHOTT N-BK7, Zemax catalogue 2017-01-20b (n_d 1.5168, V_d 64.17)",
    },
    Entry {
        name: "fused-silica",
        aliases: &["silica", "sio2"],
        terms: &[
            (0.696_166_3, 0.068_404_3 * 0.068_404_3),
            (0.407_942_6, 0.116_241_4 * 0.116_241_4),
            (0.897_479_4, 9.896_161 * 9.896_161),
        ],
        range_nm: (210.0, 6700.0),
        source: "I. H. Malitson, J. Opt. Soc. Am. 55, 1205 (1965), 20 C",
    },
    Entry {
        name: "sf11",
        aliases: &[],
        terms: &[
            (1.738_484_03, 0.013_606_860_4),
            (0.311_168_974, 0.061_596_046_3),
            (1.174_908_71, 121.922_711),
        ],
        range_nm: (390.0, 2500.0),
        source: "SCHOTT SF11, Zemax catalogue 2017-01-20b (n_d 1.78472, V_d 25.76)",
    },
    Entry {
        name: "f2",
        aliases: &[],
        terms: &[
            (1.345_333_59, 0.009_977_438_71),
            (0.209_073_176, 0.047_045_076_7),
            (0.937_357_162, 111.886_764),
        ],
        range_nm: (320.0, 2500.0),
        source: "SCHOTT F2, Zemax catalogue 2017-01-20b (n_d 1.62004, V_d 36.37)",
    },
    Entry {
        name: "baf10",
        aliases: &["n-baf10"],
        terms: &[
            (1.585_149_5, 0.009_266_812_82),
            (0.143_559_385, 0.042_448_980_5),
            (1.085_212_69, 105.613_573),
        ],
        range_nm: (350.0, 2500.0),
        source: "SCHOTT N-BAF10, Zemax catalogue 2017-01-20b (n_d 1.67003, V_d 47.11)",
    },
    Entry {
        name: "sapphire",
        aliases: &["sapphire-o", "al2o3"],
        terms: &[
            (1.431_349_3, 0.072_663_1 * 0.072_663_1),
            (0.650_547_13, 0.119_324_2 * 0.119_324_2),
            (5.341_402_1, 18.028_251 * 18.028_251),
        ],
        range_nm: (200.0, 5000.0),
        source: "I. H. Malitson and M. J. Dodge, J. Opt. Soc. Am. 62, 1405 (1972), ordinary ray, 20 C",
    },
    Entry {
        name: "caf2",
        aliases: &["fluorite"],
        terms: &[
            (0.567_588_8, 0.050_263_605 * 0.050_263_605),
            (0.471_091_4, 0.100_390_9 * 0.100_390_9),
            (3.848_472_3, 34.649_040 * 34.649_040),
        ],
        range_nm: (230.0, 9700.0),
        source: "I. H. Malitson, Appl. Opt. 2, 1103 (1963), 24 C",
    },
    Entry {
        name: "water",
        aliases: &["h2o"],
        terms: &[
            (0.568_402_756_5, 0.005_101_829_712),
            (0.172_617_739_1, 0.018_211_539_36),
            (0.020_861_895_78, 0.026_207_222_93),
            (0.113_074_868_8, 10.697_927_21),
        ],
        range_nm: (182.0, 1129.0),
        source: "M. Daimon and A. Masumura, Appl. Opt. 46, 3811 (2007), distilled water, 20.0 C",
    },
    Entry {
        name: "diamond",
        aliases: &["c"],
        terms: &[(0.3306, 0.1750 * 0.1750), (4.3356, 0.1060 * 0.1060)],
        range_nm: (226.0, 760.0),
        source: "F. Peter, Z. Phys. 15, 358 (1923)",
    },
];

/// The catalogue glass called `name` (see [`GLASS_NAMES`]).
pub fn named_glass(name: &str) -> Result<Glass, SpectrumError> {
    let wanted = name.trim().to_ascii_lowercase().replace('_', "-");
    let entry = CATALOG
        .iter()
        .find(|e| e.name == wanted || e.aliases.contains(&wanted.as_str()))
        .ok_or_else(|| SpectrumError::UnknownName {
            kind: "glass",
            name: name.to_string(),
            valid: GLASS_NAMES.to_string(),
        })?;
    Ok(Glass {
        name: entry.name,
        ior: Sellmeier::new(entry.terms.to_vec(), entry.range_nm)?,
        source: entry.source,
    })
}
