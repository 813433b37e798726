//! Environment images: decoding (Radiance .hdr, OpenEXR), the direction mapping, and the
//! importance sampler (chi-square against its own density, which must integrate to 1).

use std::sync::Arc;

use glam::{Vec2, Vec3};
use prism_sampling::stats::chi_square_test;
use prism_sampling::stream::{IndependentStream, SampleStream};
use prism_scene::load::{decode_hdr_image, environment_map};
use prism_scene::world::EnvironmentMap;
use prism_spectrum::SampledWavelengths;

#[path = "support/rgbe.rs"]
mod rgbe;
use rgbe::rgbe_file;

/// A sky of radiance `sky` with a sun: texels within `sun_radius` texels of (`sx`, `sy`)
/// have radiance `sun`.
fn sky_with_sun(width: u32, height: u32, sky: f32, sun: f32) -> Vec<u8> {
    let (sx, sy) = (width as f32 * 0.3, height as f32 * 0.25);
    rgbe_file(width, height, |x, y| {
        let d = Vec2::new(x as f32 + 0.5 - sx, y as f32 + 0.5 - sy).length();
        if d < 1.5 {
            [sun; 3]
        } else {
            [sky, sky * 0.9, sky * 1.1]
        }
    })
}

fn map(bytes: &[u8], rotation: f64) -> Arc<EnvironmentMap> {
    environment_map(bytes, rotation, 1.0).expect("a valid environment image")
}

#[test]
fn radiance_files_decode_to_their_values() {
    let bytes = rgbe_file(3, 2, |x, y| [0.5 * (x + 1) as f32, 4.0 * y as f32, 0.25]);
    let image = decode_hdr_image(&bytes).unwrap();
    assert_eq!((image.width, image.height), (3, 2));
    assert_eq!(image.rgb[0], [0.5, 0.0, 0.25]);
    assert_eq!(image.rgb[5], [1.5, 4.0, 0.25]);
    for bad in [&b"#?RADIANCE\n"[..], b"not an image", b""] {
        assert!(decode_hdr_image(bad).is_err());
    }
}

#[test]
fn directions_and_coordinates_invert_each_other() {
    let m = map(&rgbe_file(8, 4, |_, _| [1.0; 3]), 0.0);
    // The convention: the image's centre column looks along +x, u = 3/4 along +z, the top
    // row at +y.
    let at = |u: f32, v: f32| m.direction(Vec2::new(u, v)).0;
    assert!(at(0.5, 0.5).abs_diff_eq(Vec3::X, 1e-6));
    assert!(at(0.75, 0.5).abs_diff_eq(Vec3::Z, 1e-6));
    assert!(at(0.0, 0.5).abs_diff_eq(-Vec3::X, 1e-6));
    assert!(at(0.3, 0.0).abs_diff_eq(Vec3::Y, 1e-6));
    for (u, v) in [(0.1, 0.2), (0.6, 0.9), (0.99, 0.5), (0.25, 0.01)] {
        let uv = m.uv(at(u, v));
        assert!(uv.abs_diff_eq(Vec2::new(u, v), 1e-5), "{u} {v}: {uv}");
    }
    // Turned by 90 degrees about +y (counter-clockwise from above), what was along +x
    // comes from -z.
    let turned = map(&rgbe_file(8, 4, |_, _| [1.0; 3]), 90.0);
    assert!(
        turned
            .direction(Vec2::new(0.5, 0.5))
            .0
            .abs_diff_eq(-Vec3::Z, 1e-6)
    );
    assert!(turned.uv(-Vec3::Z).abs_diff_eq(Vec2::new(0.5, 0.5), 1e-6));
}

/// What a test draws directions with: next-event estimation's sampler and density, or
/// light paths'.
#[derive(Clone, Copy)]
enum Sampler {
    LightSamples,
    Emitted,
}

impl Sampler {
    fn sample(
        self,
        m: &EnvironmentMap,
        u: Vec2,
        lambdas: &SampledWavelengths<4>,
    ) -> Option<(Vec3, f32, prism_spectrum::SampledSpectrum<4>)> {
        match self {
            Sampler::LightSamples => m.sample(u, lambdas, &m.white(lambdas)),
            Sampler::Emitted => m.sample_emitted(u, lambdas, &m.white(lambdas)),
        }
    }

    fn pdf(self, m: &EnvironmentMap, d: Vec3) -> f32 {
        match self {
            Sampler::LightSamples => m.pdf(d),
            Sampler::Emitted => m.pdf_emitted(d),
        }
    }
}

/// Sampled directions, binned on the map's own (u, v) grid, against the density
/// integrated over each cell in solid angle; the density integrates to 1. Both for
/// next-event estimation's MIS-compensated sampler and for light paths'.
#[test]
fn sampling_matches_the_density() {
    assert_sampling_matches_the_density(Sampler::LightSamples);
    assert_sampling_matches_the_density(Sampler::Emitted);
}

/// Light samples go only where the image is brighter than its mean (MIS compensation:
/// BSDF sampling finds the rest), light paths leave from wherever it has light.
#[test]
fn light_samples_leave_the_sky_below_its_mean_to_bsdf_sampling() {
    let m = map(&sky_with_sun(32, 16, 0.2, 400.0), 0.0);
    let sky = m.direction(Vec2::new(0.8, 0.7)).0;
    let sun = m
        .direction(Vec2::new(0.3 + 0.5 / 32.0, 0.25 + 0.5 / 16.0))
        .0;
    assert_eq!(m.pdf(sky), 0.0);
    assert!(m.pdf_emitted(sky) > 0.0);
    // The sun's share of the light samples grows by what the sky gave up.
    assert!(m.pdf(sun) > m.pdf_emitted(sun));
    // A constant image has nothing above its mean: both sample alike.
    let flat = map(&rgbe_file(16, 8, |_, _| [1.0; 3]), 0.0);
    let d = flat.direction(Vec2::new(0.4, 0.6)).0;
    assert_eq!(flat.pdf(d), flat.pdf_emitted(d));
}

fn assert_sampling_matches_the_density(sampler: Sampler) {
    let m = map(&sky_with_sun(32, 16, 0.2, 400.0), 30.0);
    // Bins of 2 x 2 cells of the sampler's grid (4 cells a texel per axis for an image
    // this small), so that the midpoint rule below integrates its steps exactly.
    let (nu, nv, samples) = (64usize, 32usize, 300_000usize);
    let lambdas = SampledWavelengths::<4>::new([450.0, 520.0, 600.0, 680.0], [1.0; 4]).unwrap();
    let mut stream = IndependentStream::new(7, 0, 0);
    let mut counts = vec![0u64; nu * nv];
    let (mut valid, mut mismatched) = (0u64, 0u64);
    for _ in 0..samples {
        if let Some((d, pdf, radiance)) = sampler.sample(&m, stream.next_2d(), &lambdas) {
            // The density looked up by direction is the sampled one, except where rounding
            // puts a direction on the other side of a cell's edge.
            if (pdf - sampler.pdf(&m, d)).abs() > 1e-3 * pdf {
                mismatched += 1;
            }
            // What next-event estimation sees is what an escaping ray sees.
            assert_eq!(radiance, m.radiance(d, &lambdas));
            let uv = m.uv(d);
            let (i, j) = ((uv.x * nu as f32) as usize, (uv.y * nv as f32) as usize);
            counts[j.min(nv - 1) * nu + i.min(nu - 1)] += 1;
            valid += 1;
        }
    }
    const Q: usize = 8;
    let expected: Vec<f64> = (0..nu * nv)
        .map(|cell| {
            let (i, j) = (cell % nu, cell / nu);
            let mut mass = 0.0;
            for a in 0..Q {
                for b in 0..Q {
                    let u = (i as f64 + (a as f64 + 0.5) / Q as f64) / nu as f64;
                    let v = (j as f64 + (b as f64 + 0.5) / Q as f64) / nv as f64;
                    let (d, sin_theta) = m.direction(Vec2::new(u as f32, v as f32));
                    // dw = 2 pi^2 sin(theta) du dv.
                    mass += f64::from(sampler.pdf(&m, d))
                        * 2.0
                        * std::f64::consts::PI.powi(2)
                        * f64::from(sin_theta);
                }
            }
            mass / (Q * Q * nu * nv) as f64
        })
        .collect();
    let total: f64 = expected.iter().sum();
    assert!(
        (total - 1.0).abs() < 2e-3,
        "the density integrates to {total}"
    );
    assert!(valid as f64 > 0.999 * samples as f64);
    assert!(
        mismatched < 30,
        "{mismatched} densities differ from the sampled ones"
    );
    let expected: Vec<f64> = expected.iter().map(|e| e * valid as f64).collect();
    let p = chi_square_test(&counts, &expected).p_value;
    assert!(p > 1e-3, "p = {p:.2e}");
}

/// The test has power: a density that ignores the sin(theta) of the map's area element
/// (sampling uniformly in (u, v) within each texel's weight) fails it.
#[test]
fn chi_square_rejects_a_density_without_the_area_element() {
    let m = map(&rgbe_file(16, 8, |_, _| [1.0; 3]), 0.0);
    let (nv, samples) = (16usize, 100_000usize);
    let lambdas = SampledWavelengths::<1>::new([550.0], [1.0]).unwrap();
    let mut stream = IndependentStream::new(3, 0, 0);
    let mut counts = vec![0u64; nv];
    for _ in 0..samples {
        let (d, _, _) = m
            .sample(stream.next_2d(), &lambdas, &m.white(&lambdas))
            .unwrap();
        counts[((m.uv(d).y * nv as f32) as usize).min(nv - 1)] += 1;
    }
    let uniform_in_v = vec![samples as f64 / nv as f64; nv];
    assert!(chi_square_test(&counts, &uniform_in_v).p_value < 1e-6);
}

#[test]
fn a_black_image_gives_no_samples_and_no_density() {
    let m = map(&rgbe_file(4, 2, |_, _| [0.0; 3]), 0.0);
    let lambdas = SampledWavelengths::<1>::new([550.0], [1.0]).unwrap();
    assert!(
        m.sample(Vec2::new(0.3, 0.6), &lambdas, &m.white(&lambdas))
            .is_none()
    );
    assert_eq!(m.pdf(Vec3::Y), 0.0);
}

mod extremes {
    use super::*;
    use proptest::prelude::*;
    use std::sync::OnceLock;

    fn extreme() -> impl Strategy<Value = f32> {
        prop_oneof![
            Just(0.0f32),
            Just(-0.0f32),
            Just(1e-40f32),
            Just(1e30f32),
            Just(f32::MAX),
            Just(f32::INFINITY),
            Just(f32::NAN),
            Just(-1.0f32),
            0.0..100.0f32,
        ]
    }

    /// The table behind every map, fitted once for the whole property run.
    fn upsampling() -> (
        Arc<prism_upsample::CoefficientTable>,
        Arc<prism_upsample::FitContext>,
        Arc<prism_spectrum::spectra::DenselySampled>,
    ) {
        static TABLE: OnceLock<Arc<prism_upsample::CoefficientTable>> = OnceLock::new();
        let space = prism_spectrum::color::RgbSpaceId::Srgb;
        let context =
            Arc::new(prism_upsample::FitContext::new(space.space(), &space.illuminant()).unwrap());
        let table = TABLE
            .get_or_init(|| {
                Arc::new(
                    prism_upsample::CoefficientTable::fit(&context, 16, &|_| {})
                        .unwrap()
                        .0,
                )
            })
            .clone();
        (table, context, prism_scene::world::unit_d65())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// Any texels, strength, rotation and direction: coordinates in [0, 1], unit
        /// directions, and finite, non-negative densities and radiance; samples likewise.
        #[test]
        fn maps_stay_finite(
            texels in prop::collection::vec(prop::array::uniform3(extreme()), 8),
            strength in prop_oneof![Just(0.0f64), Just(1e300f64), 0.0..10.0f64],
            rotation in prop_oneof![Just(1e30f64), -720.0..720.0f64],
            d in prop::array::uniform3(extreme()),
            u in prop::array::uniform2(0.0..1.0f32),
        ) {
            let map = EnvironmentMap::new(4, 2, texels, rotation, strength, upsampling()).unwrap();
            let lambdas = SampledWavelengths::<4>::new([380.0, 500.0, 600.0, 780.0], [1.0; 4]).unwrap();
            let d = Vec3::from(d);
            let uv = map.uv(d);
            prop_assert!(uv.is_finite() && uv.min_element() >= 0.0 && uv.max_element() <= 1.0);
            let (w, _) = map.direction(uv);
            prop_assert!((w.length() - 1.0).abs() < 1e-4);
            for pdf in [map.pdf(d), map.pdf_emitted(d)] {
                prop_assert!(pdf.is_finite() && pdf >= 0.0);
            }
            let l = map.radiance(d, &lambdas);
            prop_assert!(l.0.iter().all(|v| v.is_finite() && *v >= 0.0));
            let white = map.white(&lambdas);
            let samples = [
                map.sample(Vec2::from(u), &lambdas, &white),
                map.sample_emitted(Vec2::from(u), &lambdas, &white),
            ];
            for (w, pdf, l) in samples.into_iter().flatten() {
                prop_assert!(w.is_finite() && pdf.is_finite() && pdf > 0.0);
                prop_assert!(l.0.iter().all(|v| v.is_finite() && *v >= 0.0));
            }
        }
    }
}
