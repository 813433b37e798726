//! The thin film against an independent transfer-matrix calculation (`tmm`, fixtures from
//! scene/tools/thin_film_fixtures.py), the closed forms it must reduce to, and its range
//! at the extremes.

use prism_scene::bsdf::{ThinFilm, fresnel_conductor, fresnel_dielectric};
use proptest::prelude::*;

/// Every fixture case: films of index 1.3, 1.8 and 2.4, 30 to 780 nm thick, over air (a
/// soap bubble), glass, water and two conductors, at 0 to 85 degrees and 380 to 780 nm.
#[test]
fn matches_the_transfer_matrix_method() {
    let text = include_str!("fixtures/thin_film_tmm.json");
    let fixture: serde_json::Value = serde_json::from_str(text).unwrap();
    let cases = fixture["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 1800);
    let mut worst = 0.0f64;
    for case in cases {
        let v: Vec<f64> = case
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let [eta, k, film, d, angle, lambda, expected] = v[..] else {
            panic!("{case}");
        };
        let got = ThinFilm {
            ior: film as f32,
            thickness_nm: d as f32,
        }
        .reflectance(
            angle.to_radians().cos() as f32,
            lambda as f32,
            1.0,
            eta as f32,
            k as f32,
        );
        let error = (f64::from(got) - expected).abs();
        worst = worst.max(error);
        // f32 inputs (the cosine above all, near grazing) against tmm's doubles.
        assert!(error < 2e-5, "{case}: prism {got}");
    }
    assert!(worst > 0.0, "the comparison compared nothing");
}

/// The film shows interference: at normal incidence over glass, a quarter-wave film of
/// index sqrt(1.5) (the ideal antireflection coating) reflects nothing at its design
/// wavelength, and a half-wave film is absent (the bare glass's 4%).
#[test]
fn quarter_and_half_wave_films_behave_as_optics_says() {
    let n = 1.5f32.sqrt();
    let lambda = 550.0;
    let quarter = ThinFilm {
        ior: n,
        thickness_nm: lambda / (4.0 * n),
    };
    assert!(quarter.reflectance(1.0, lambda, 1.0, 1.5, 0.0) < 1e-7);
    let half = ThinFilm {
        ior: 1.3,
        thickness_nm: lambda / (2.0 * 1.3),
    };
    let bare = fresnel_dielectric(1.0, 1.5);
    assert!((half.reflectance(1.0, lambda, 1.0, 1.5, 0.0) - bare).abs() < 1e-6);
}

/// A film of no thickness, or of the outside's index, is the bare base.
#[test]
fn vanishing_films_leave_the_bare_base() {
    for cos in [1.0f32, 0.7, 0.3, 0.05] {
        for (eta, k) in [(1.5f32, 0.0f32), (1.33, 0.0), (0.18, 3.0), (1.2, 7.0)] {
            let bare = if k == 0.0 {
                fresnel_dielectric(cos, eta)
            } else {
                fresnel_conductor(cos, eta, k)
            };
            for film in [
                ThinFilm {
                    ior: 1.8,
                    thickness_nm: 0.0,
                },
                ThinFilm {
                    ior: 1.0,
                    thickness_nm: 300.0,
                },
            ] {
                let r = film.reflectance(cos, 500.0, 1.0, eta, k);
                assert!(
                    (r - bare).abs() < 1e-5,
                    "{film:?} cos {cos} base {eta}+{k}i: {r} vs {bare}"
                );
            }
        }
    }
}

proptest! {
    /// Any input, however extreme or non-finite, gives a reflectance in [0, 1]; over a
    /// lossless base seen from air, the same as it gives seen from the other wavelength's
    /// period (thickness shifted by a whole number of waves at normal incidence).
    #[test]
    fn reflectance_is_a_fraction_for_every_input(
        cos in prop::num::f32::ANY,
        lambda in prop::num::f32::ANY,
        outside in prop::num::f32::ANY,
        ior in prop::num::f32::ANY,
        thickness in prop::num::f32::ANY,
        eta in prop::num::f32::ANY,
        k in prop::num::f32::ANY,
    ) {
        let r = ThinFilm { ior, thickness_nm: thickness }.reflectance(cos, lambda, outside, eta, k);
        prop_assert!((0.0..=1.0).contains(&r), "{r}");
    }

    #[test]
    fn whole_waves_of_film_change_nothing_at_normal_incidence(
        ior in 1.05f32..3.0,
        thickness in 0.0f32..800.0,
        lambda in 360.0f32..830.0,
        eta in 1.0f32..2.5,
        waves in 1u32..4,
    ) {
        let film = ThinFilm { ior, thickness_nm: thickness };
        let thicker = ThinFilm { ior, thickness_nm: thickness + waves as f32 * lambda / (2.0 * ior) };
        let (a, b) = (film.reflectance(1.0, lambda, 1.0, eta, 0.0), thicker.reflectance(1.0, lambda, 1.0, eta, 0.0));
        prop_assert!((a - b).abs() < 2e-4, "{a} vs {b}");
    }
}
