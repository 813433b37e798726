//! The embedded CIE tables equal their source, value for value.
//!
//! `fixtures/cie_source.json` is colour-science's data exported by `json.dump`, a different
//! path from the one that wrote `src/data/*.rs`, so a transcription or formatting error in
//! either shows up here.

mod common;

use common::{fixture, num, nums};
use prism_spectrum::__tables::{cie_cmf, cie_illuminants};

#[test]
fn colour_matching_functions_equal_source() {
    let source = fixture("cie_source.json");
    for (key, tables) in [
        (
            "cie1931",
            [
                &cie_cmf::CIE1931_X,
                &cie_cmf::CIE1931_Y,
                &cie_cmf::CIE1931_Z,
            ],
        ),
        (
            "cie1964",
            [
                &cie_cmf::CIE1964_X,
                &cie_cmf::CIE1964_Y,
                &cie_cmf::CIE1964_Z,
            ],
        ),
    ] {
        let wavelengths = nums(&source["cmfs"][key]["wavelengths"]);
        assert_eq!(wavelengths.len(), cie_cmf::CMF_LEN);
        assert_eq!(wavelengths[0], cie_cmf::CMF_FIRST_NM);
        for (i, row) in source["cmfs"][key]["xyz"]
            .as_array()
            .unwrap()
            .iter()
            .enumerate()
        {
            assert_eq!(wavelengths[i], cie_cmf::CMF_FIRST_NM + i as f64);
            for (axis, table) in tables.iter().enumerate() {
                assert_eq!(table[i], num(&row[axis]), "{key} axis {axis} at row {i}");
            }
        }
    }
}

#[test]
fn illuminant_tables_equal_source() {
    let source = fixture("cie_source.json");
    let embedded: Vec<(&str, &cie_illuminants::RegularTable)> = vec![
        ("A", &cie_illuminants::A),
        ("D50", &cie_illuminants::D50),
        ("D55", &cie_illuminants::D55),
        ("D65", &cie_illuminants::D65),
        ("D75", &cie_illuminants::D75),
        ("E", &cie_illuminants::E),
        ("F1", &cie_illuminants::F1),
        ("F2", &cie_illuminants::F2),
        ("F3", &cie_illuminants::F3),
        ("F4", &cie_illuminants::F4),
        ("F5", &cie_illuminants::F5),
        ("F6", &cie_illuminants::F6),
        ("F7", &cie_illuminants::F7),
        ("F8", &cie_illuminants::F8),
        ("F9", &cie_illuminants::F9),
        ("F10", &cie_illuminants::F10),
        ("F11", &cie_illuminants::F11),
        ("F12", &cie_illuminants::F12),
        ("S0", &cie_illuminants::DAYLIGHT_S0),
        ("S1", &cie_illuminants::DAYLIGHT_S1),
        ("S2", &cie_illuminants::DAYLIGHT_S2),
    ];
    let all = source["illuminants"].as_object().unwrap();
    assert_eq!(all.len(), embedded.len(), "every source table is embedded");
    for (name, table) in embedded {
        let s = &source["illuminants"][name];
        assert_eq!(table.first_nm, num(&s["first_nm"]), "{name}");
        assert_eq!(table.step_nm, num(&s["step_nm"]), "{name}");
        assert_eq!(table.values, nums(&s["values"]).as_slice(), "{name}");
    }
}

#[test]
fn published_spot_values() {
    // Values of the CIE 018:2019 1 nm dataset and CIE 015:2018 Table 5, typed by hand: a check on
    // the source itself.
    let at = |table: &[f64], nm: usize| table[nm - 360];
    assert_eq!(at(&cie_cmf::CIE1931_Y, 555), 1.0);
    assert_eq!(at(&cie_cmf::CIE1931_X, 600), 1.0622);
    assert_eq!(at(&cie_cmf::CIE1931_Z, 450), 1.77211);
    let d65 = &cie_illuminants::D65;
    let d65_at = |nm: f64| d65.values[((nm - d65.first_nm) / d65.step_nm) as usize];
    assert_eq!(d65_at(560.0), 100.0);
    assert_eq!(d65_at(460.0), 117.812);
}
