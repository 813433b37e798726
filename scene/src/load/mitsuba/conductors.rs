//! Mitsuba's named conductors: the measured complex indices of refraction its
//! `conductor` and `roughconductor` plugins read for `material` (Mitsuba 3,
//! `include/mitsuba/render/ior.h`, `complex_ior_from_file`), embedded from Mitsuba 3's
//! data files (`ior/`, with their provenance and licence in `ior/PROVENANCE.md`).
//!
//! A Mitsuba scene renders as Mitsuba renders it: gold, silver, copper and aluminium too
//! take Mitsuba's data here (Luxpop's compilation, mostly Palik's measurements), not
//! prism's own tables (Johnson and Christy's, Rakic's), which glTF and prism's scene
//! format keep using.

use std::sync::Arc;

use prism_spectrum::spectra::{Extrapolation, PiecewiseLinear};

use super::tree::SpectrumValue;
use super::values::spd_file;
use crate::textures::SceneSpectrum;

/// One preset: `(name, eta file, k file)`, named as Mitsuba names them (its file names,
/// case-sensitive as its file lookup is).
macro_rules! presets {
    ($($name:literal),* $(,)?) => {
        [$((
            $name,
            include_str!(concat!("ior/", $name, ".eta.spd")),
            include_str!(concat!("ior/", $name, ".k.spd")),
        )),*]
    };
}

/// Every preset Mitsuba 3 ships (`resources/data/ior/`).
const PRESETS: [(&str, &str, &str); 71] = presets![
    "Ag",
    "Al",
    "AlAs",
    "AlAs_palik",
    "AlSb",
    "AlSb_palik",
    "Au",
    "Be",
    "Be_palik",
    "Cr",
    "CsI",
    "CsI_palik",
    "Cu",
    "Cu2O",
    "Cu2O_palik",
    "CuO",
    "CuO_palik",
    "Cu_palik",
    "Hg",
    "HgTe",
    "HgTe_palik",
    "Hg_palik",
    "Ir",
    "Ir_palik",
    "K",
    "K_palik",
    "Li",
    "Li_palik",
    "MgO",
    "MgO_palik",
    "Mo",
    "Mo_palik",
    "Na_palik",
    "Nb",
    "Nb_palik",
    "Ni_palik",
    "Rh",
    "Rh_palik",
    "Se",
    "Se-e",
    "Se-e_palik",
    "Se_palik",
    "SiC",
    "SiC_palik",
    "SnTe",
    "SnTe_palik",
    "Ta",
    "Ta_palik",
    "Te",
    "Te-e",
    "Te-e_palik",
    "Te_palik",
    "ThF4",
    "ThF4_palik",
    "TiC",
    "TiC_palik",
    "TiN",
    "TiN_palik",
    "TiO2",
    "TiO2-e",
    "TiO2-e_palik",
    "TiO2_palik",
    "VC",
    "VC_palik",
    "VN",
    "VN_palik",
    "V_palik",
    "W",
    "a-C",
    "d-C",
    "d-C_palik",
];

/// The names of every preset, for an error message.
pub(crate) fn names() -> Vec<&'static str> {
    PRESETS.iter().map(|(name, _, _)| *name).collect()
}

/// eta and k of the preset `name` as Mitsuba reads them (irregular spectra: linear
/// between samples, zero outside the data), or None if Mitsuba has no such preset.
pub(crate) fn preset(name: &str) -> Option<(SceneSpectrum, SceneSpectrum)> {
    let (_, eta, k) = PRESETS.iter().find(|(n, _, _)| *n == name)?;
    Some((table(eta), table(k)))
}

/// An embedded file as a spectrum; the files are checked by the tests below, so a
/// failure here is a broken build, not a user's error.
fn table(text: &str) -> SceneSpectrum {
    let Ok(SpectrumValue::Samples(samples)) = spd_file(text) else {
        unreachable!("the embedded .spd files parse (tested)");
    };
    let (lambdas, values): (Vec<f64>, Vec<f64>) = samples.into_iter().unzip();
    let table = PiecewiseLinear::new(lambdas, values, Extrapolation::Zero)
        .expect("the embedded .spd files are valid tables (tested)");
    SceneSpectrum::Table(Arc::new(table))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_parses_and_is_finite_and_non_negative() {
        for (name, eta, k) in PRESETS {
            for (part, text) in [("eta", eta), ("k", k)] {
                let Ok(SpectrumValue::Samples(samples)) = spd_file(text) else {
                    panic!("{name}.{part}.spd does not parse");
                };
                assert!(samples.len() >= 2, "{name}.{part}");
                for (lambda, v) in samples {
                    assert!(lambda > 0.0 && v.is_finite() && v >= 0.0, "{name}.{part}");
                }
            }
        }
    }

    #[test]
    fn the_task_list_of_mitsubas_presets_is_here() {
        // Mitsuba 3's documented list (src/bsdfs/conductor.cpp, "conductor-ior-list").
        for name in [
            "a-C", "Ag", "Al", "AlAs", "AlSb", "Au", "Be", "Cr", "CsI", "Cu", "Cu2O", "CuO", "d-C",
            "Hg", "HgTe", "Ir", "K", "Li", "MgO", "Mo", "Na_palik", "Nb", "Ni_palik", "Rh", "Se",
            "SiC", "SnTe", "Ta", "Te", "ThF4", "TiC", "TiN", "TiO2", "VC", "V_palik", "VN", "W",
        ] {
            assert!(preset(name).is_some(), "{name}");
        }
        assert!(
            preset("au").is_none(),
            "names are case-sensitive, as Mitsuba's files"
        );
    }

    #[test]
    fn gold_at_550nm_is_mitsubas() {
        // Au.eta.spd / Au.k.spd at 551.04 nm (Luxpop): eta 0.3455, k 2.7306.
        let (eta, k) = preset("Au").unwrap();
        let (SceneSpectrum::Table(eta), SceneSpectrum::Table(k)) = (eta, k) else {
            panic!()
        };
        use prism_spectrum::Spectrum;
        let (e, kk) = (eta.evaluate(550.0), k.evaluate(550.0));
        assert!(
            (0.3..0.4).contains(&e) && (2.6..2.9).contains(&kk),
            "{e} {kk}"
        );
    }
}
