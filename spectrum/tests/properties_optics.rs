//! Numerical stability of refractive index models and energy at the extremes.

use prism_spectrum::Spectrum;
use prism_spectrum::optics::{
    Cauchy, Sellmeier, named_glass, named_metal, photon_energy_ev, photon_energy_joules,
};
use proptest::prelude::*;

mod common;
use common::any_f64;

const GLASSES: [&str; 9] = [
    "bk7",
    "fused-silica",
    "sf11",
    "f2",
    "baf10",
    "sapphire",
    "caf2",
    "water",
    "diamond",
];

proptest! {
    /// Catalogue glasses: finite n >= 1 at any wavelength whatsoever (clamped outside the
    /// fitted range, so never near a pole).
    #[test]
    fn catalogue_indices_are_finite(lambda in any_f64(), which in 0..GLASSES.len()) {
        let glass = named_glass(GLASSES[which]).unwrap();
        let n = glass.ior.evaluate(lambda);
        prop_assert!(n.is_finite() && n >= 1.0, "{} at {lambda}: {n}", GLASSES[which]);
        prop_assert!(n <= glass.ior.max_value());
    }

    /// Any Sellmeier model is either rejected or finite everywhere, including right next to
    /// a pole that sits just outside its range.
    #[test]
    fn sellmeier_models_are_valid_or_rejected(
        terms in prop::collection::vec((0.0..10.0f64, 0.0..200.0f64), 0..4),
        lo in 1.0..3000.0f64,
        width in 0.0..5000.0f64,
        lambda in any_f64(),
    ) {
        if let Ok(model) = Sellmeier::new(terms, (lo, lo + width)) {
            let n = model.evaluate(lambda);
            prop_assert!(n.is_finite() && n > 0.0);
        }
    }

    #[test]
    fn near_pole_range_end_stays_finite(c in 0.001..1.0f64, eps in 1e-12..1e-3f64) {
        // The pole at sqrt(c) um; the range ends eps (relative) above it.
        let pole_nm = c.sqrt() * 1000.0;
        if let Ok(model) = Sellmeier::new(vec![(1.0, c)], (pole_nm * (1.0 + eps), pole_nm * 10.0)) {
            let n = model.evaluate(0.0);
            prop_assert!(n.is_finite() && n > 1.0);
        }
    }

    /// KHR_materials_dispersion's Cauchy model: n >= 1 and finite for any wavelength.
    #[test]
    fn abbe_cauchy_is_finite(n_d in 1.0..4.0f64, abbe in prop_oneof![Just(1e-300), 1e-3..1e3f64], lambda in any_f64()) {
        let ior = Cauchy::from_abbe(n_d, abbe).unwrap();
        let n = ior.evaluate(lambda);
        prop_assert!(n.is_finite() && n >= 1.0);
    }

    #[test]
    fn metals_are_finite(lambda in any_f64(), which in 0..4usize) {
        let metal = named_metal(["au", "ag", "cu", "al"][which]).unwrap();
        let r = metal.normal_reflectance(lambda);
        prop_assert!(r.is_finite() && (0.0..=1.0).contains(&r));
    }

    #[test]
    fn photon_energy_is_finite_or_error(lambda in any_f64()) {
        for energy in [photon_energy_joules(lambda), photon_energy_ev(lambda)] {
            match energy {
                Ok(e) => prop_assert!(e.is_finite() && e >= 0.0),
                Err(_) => prop_assert!(!(lambda > 0.0 && lambda.is_finite()) || lambda < 1e-280),
            }
        }
    }
}
