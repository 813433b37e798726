//! Extremes: 1 bin and 10^6 bins, bins of 1e-38, u = 0 and u just below 1, wavelengths at
//! both ends of the range, hero wrap-around at lambda_max, packages of size 1 and 16; no
//! NaN or infinity anywhere.

use glam::{Vec2, Vec3};
use prism_sampling::distribution::{
    AliasTable, ONE_MINUS_EPSILON, PiecewiseConstant1D, PiecewiseLinear1D,
};
use prism_sampling::mis::{balance_heuristic, power_heuristic};
use prism_sampling::warp::*;
use prism_sampling::wavelength::*;
use proptest::prelude::*;

fn unit() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(ONE_MINUS_EPSILON),
        Just(1.0),
        Just(-0.0),
        Just(f64::NAN),
        Just(2.0),
        Just(-1.0),
        0.0..1.0f64
    ]
}

fn weight() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(1e-38),
        Just(1e-300),
        Just(1.0),
        Just(1e30),
        0.0..10.0f64
    ]
}

#[test]
fn a_million_bins() {
    let values: Vec<f64> = (0..1_000_000)
        .map(|i| {
            if i % 3 == 0 {
                0.0
            } else {
                (i % 97) as f64 + 1e-38
            }
        })
        .collect();
    let d = PiecewiseConstant1D::new(&values, 0.0, 1.0).unwrap();
    for u in [0.0, 1e-12, 0.5, 0.999_999, ONE_MINUS_EPSILON] {
        let s = d.sample(u);
        assert!(
            values[s.bin] > 0.0
                && s.pdf.is_finite()
                && s.pdf > 0.0
                && (0.0..1.0).contains(&s.value)
        );
    }
}

proptest! {
    #[test]
    fn piecewise_constant_is_total(values in prop::collection::vec(weight(), 1..40), u in unit()) {
        match PiecewiseConstant1D::new(&values, -1.0, 1.0) {
            Ok(d) => {
                let s = d.sample(u);
                prop_assert!(values[s.bin] > 0.0, "zero bin {} sampled", s.bin);
                prop_assert!(s.pdf.is_finite() && s.pdf > 0.0 && s.value.is_finite());
                prop_assert!((-1.0..=1.0).contains(&s.value));
                prop_assert!(d.invert(s.value).is_finite());
            }
            Err(_) => prop_assert!(values.iter().all(|&v| v == 0.0) || values.iter().sum::<f64>() * 2.0 / values.len() as f64 == f64::INFINITY),
        }
    }

    /// The guide table picks the bin a search of the whole CDF picks, for any weights
    /// (runs of empty bins included) and any u, boundaries of the guide's intervals too.
    #[test]
    fn the_guide_table_picks_the_searched_bin(values in prop::collection::vec(weight(), 1..300), u in unit(), j in 0..300usize, nudge in -2i64..=2) {
        if let Ok(d) = PiecewiseConstant1D::new(&values, 0.0, 1.0) {
            prop_assert_eq!(d.sample(u).bin, d.bin_by_search(u));
            // A guide boundary j / n, moved by a few units in the last place.
            let at = (j % values.len()) as f64 / values.len() as f64;
            let at = f64::from_bits((at.to_bits() as i64 + nudge).max(0) as u64);
            prop_assert_eq!(d.sample(at).bin, d.bin_by_search(at));
        }
    }

    #[test]
    fn one_bin_is_uniform(v in 1e-38..1e30f64, u in unit()) {
        let d = PiecewiseConstant1D::new(&[v], 2.0, 4.0).unwrap();
        let s = d.sample(u);
        prop_assert!((s.pdf - 0.5).abs() < 1e-12 && (2.0..=4.0).contains(&s.value));
    }

    #[test]
    fn alias_and_linear_are_total(values in prop::collection::vec(weight(), 2..40), u in unit()) {
        if let Ok(t) = AliasTable::new(&values) {
            let (i, p) = t.sample(u);
            prop_assert!(values[i] > 0.0 && p > 0.0 && p <= 1.0);
            let (j, q, rest) = t.sample_remapped(u);
            prop_assert_eq!((i, p), (j, q));
            prop_assert!((0.0..1.0).contains(&rest), "{}", rest);
        }
        if let Ok(l) = PiecewiseLinear1D::new(&values, 0.0, 1.0) {
            let (x, p) = l.sample(u);
            prop_assert!(x.is_finite() && (0.0..=1.0).contains(&x) && p.is_finite() && p >= 0.0);
        }
    }

    /// Packages at the extremes: any u, sizes 1 and 16, ranges into UV and IR; every lane
    /// in range, the hero's density positive and finite, every density finite.
    #[test]
    fn packages_are_total(u in unit(), lo in 1.0..600.0f32, width in 1.0..1000.0f32, which in 0..3usize, rotate in any::<bool>()) {
        let range = WavelengthRange::new(lo, lo + width).unwrap();
        let d = match which {
            0 => WavelengthDistribution::uniform(range),
            1 => WavelengthDistribution::visible(range),
            // Zero at some bin centres (at all of them for some ranges: then AllZero).
            _ => match WavelengthDistribution::tabulated(range, 64, |l| if (l as i64) % 3 == 0 { 0.0 } else { 1e-38 + l }) {
                Ok(d) => d,
                Err(e) => {
                    prop_assert_eq!(e, prism_sampling::SamplingError::AllZero);
                    return Ok(());
                }
            },
        };
        let scheme = if rotate { PackageScheme::HeroRotation } else { PackageScheme::Stratified };
        let p1 = WavelengthPackage::<1>::sample(&d, u, scheme);
        let mut p16 = WavelengthPackage::<16>::sample(&d, u, scheme);
        for (lambda, pdf, hero_pdf) in p1.lambda.iter().zip(p1.pdf).zip(p1.hero_pdf).map(|((a, b), c)| (a, b, c))
            .chain(p16.lambda.iter().zip(p16.pdf).zip(p16.hero_pdf).map(|((a, b), c)| (a, b, c)))
        {
            prop_assert!(range.contains(*lambda), "{lambda} outside {range:?}");
            prop_assert!(pdf.is_finite() && pdf >= 0.0 && hero_pdf.is_finite() && hero_pdf >= 0.0);
        }
        prop_assert!(p1.pdf[0] > 0.0 && p16.pdf[0] > 0.0 && p16.hero_pdf[0] > 0.0);
        p16.terminate_secondary();
        prop_assert!(p16.pdf[0] > 0.0 && p16.pdf[1..].iter().all(|&x| x == 0.0));
        let weights = p16.mis_weights(&[1.0; 16]);
        prop_assert!(weights.iter().all(|w| w.is_finite()));
    }

    /// The hero at the very top of the range wraps the rotation around to the bottom.
    #[test]
    fn rotation_wraps_at_lambda_max(k in 0..8usize) {
        let range = WavelengthRange::VISIBLE;
        let d = WavelengthDistribution::uniform(range);
        let p = WavelengthPackage::<8>::sample(&d, ONE_MINUS_EPSILON, PackageScheme::HeroRotation);
        prop_assert!((p.hero() - 830.0).abs() < 1e-3);
        let expected = 360.0 + (470.0 * k as f32 / 8.0 + 470.0) % 470.0;
        prop_assert!((p.lambda[k] - expected).abs() < 1e-2 || (k == 0 && (p.lambda[0] - 830.0).abs() < 1e-3), "{:?}", p.lambda);
    }

    #[test]
    fn warps_are_total(x in unit(), y in unit(), cos_max in prop_oneof![Just(1.0f32), Just(-1.0f32), Just(f32::NAN), -1.0..1.0f32]) {
        let u = Vec2::new(x as f32, y as f32);
        for w in [cosine_hemisphere(u), uniform_sphere(u), uniform_cone(u, cos_max)] {
            prop_assert!(w.is_finite() && (w.length() - 1.0).abs() < 1e-4, "{w:?}");
        }
        prop_assert!(uniform_disk_concentric(u).length() <= 1.0 + 1e-6);
        let b = uniform_triangle(u);
        prop_assert!(b.iter().all(|v| v.is_finite() && *v >= 0.0));
    }

    #[test]
    fn spherical_triangle_is_total(
        p in prop::array::uniform3(-10.0..10.0f32),
        v in prop::array::uniform9(prop_oneof![Just(0.0f32), Just(1e-30f32), -10.0..10.0f32]),
        u in prop::array::uniform2(0.0..1.0f32),
    ) {
        let tri = [Vec3::new(v[0], v[1], v[2]), Vec3::new(v[3], v[4], v[5]), Vec3::new(v[6], v[7], v[8])];
        if let Some(s) = spherical_triangle(Vec3::from(p), tri, Vec2::from(u)) {
            prop_assert!(s.direction.is_finite() && (s.direction.length() - 1.0).abs() < 1e-3);
            prop_assert!(s.pdf.is_finite() && s.pdf > 0.0);
        }
        prop_assert!(spherical_triangle_solid_angle(Vec3::from(p), tri).is_finite());
    }

    #[test]
    fn heuristics_are_weights(nf in 0..4u32, ng in 0..4u32, f in prop_oneof![Just(0.0f32), Just(f32::INFINITY), Just(1e30f32), 0.0..10.0f32], g in prop_oneof![Just(0.0f32), Just(f32::INFINITY), Just(1e-30f32), 0.0..10.0f32]) {
        for w in [balance_heuristic(nf, f, ng, g), power_heuristic(nf, f, ng, g)] {
            prop_assert!((0.0..=1.0).contains(&w), "{w}");
        }
        if nf > 0 && ng > 0 && f > 0.0 && g > 0.0 && f.is_finite() && g.is_finite() {
            let sum = balance_heuristic(nf, f, ng, g) + balance_heuristic(ng, g, nf, f);
            prop_assert!((sum - 1.0).abs() < 1e-5);
            let sum = power_heuristic(nf, f, ng, g) + power_heuristic(ng, g, nf, f);
            prop_assert!((sum - 1.0).abs() < 1e-5);
        }
    }

    #[test]
    fn reradiation_is_total(m in prop::collection::vec(weight(), 9), l in prop_oneof![Just(f32::NAN), Just(300.0f32), Just(800.0f32), 0.0..1000.0f32], u in unit()) {
        let range = WavelengthRange::new(300.0, 800.0).unwrap();
        if let Ok(s) = ReradiationSampler::new(range, 3, &m) {
            for sample in [s.sample_incident(l, u), s.sample_outgoing(l, u)].into_iter().flatten() {
                prop_assert!(range.contains(sample.lambda) && sample.pdf > 0.0 && sample.pdf.is_finite() && sample.weight.is_finite());
            }
        }
    }
}

#[test]
fn heuristics_match_their_definitions() {
    assert!((balance_heuristic(1, 2.0, 1, 6.0) - 0.25).abs() < 1e-7);
    assert!((power_heuristic(1, 2.0, 1, 6.0) - 0.1).abs() < 1e-7);
    assert_eq!(power_heuristic(1, f32::INFINITY, 1, 3.0), 1.0);
    assert_eq!(balance_heuristic(1, 0.0, 1, 0.0), 0.0);
    assert!(
        (power_heuristic(1, 1e30, 1, 1e30) - 0.5).abs() < 1e-6,
        "no overflow in the squares"
    );
}
