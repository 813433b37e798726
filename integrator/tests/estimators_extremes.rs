//! The resolution of settings into estimators at the extremes: tiny images (1 x 1, 1 x N),
//! sample counts that are not a multiple of adaptive sampling's group or are below its
//! minimum, sample ranges that start past 0, 1 to 16 wavelengths, and every tracer, split,
//! reuse tile, light-path and adaptive setting. Whatever the resolution allows renders
//! finite values in every output, the same for a seed whatever the thread count, and a
//! render in two pieces merges into the render in one wherever both pieces resolve to the
//! whole's estimators (farms rely on it); whatever it refuses is one line.

mod common;

use std::sync::OnceLock;

use prism_integrator::{
    Film, RenderSettings, Renderer, Reuse, SpectralBands, Splits, Tracing, render,
};
use prism_scene::world::Scene;
use proptest::prelude::*;

/// The Cornell box (reuse, splitting, adaptive sampling) and the caustic box (light paths).
fn scenes() -> &'static [Scene; 2] {
    static SCENES: OnceLock<[Scene; 2]> = OnceLock::new();
    SCENES.get_or_init(|| {
        [
            common::cornell(),
            common::repository_scene("cornell-caustic.gltf", |_| {}),
        ]
    })
}

fn all_finite(film: &Film) -> bool {
    let (w, h) = (film.width(), film.height());
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .all(|(x, y)| {
            film.xyz(x, y).to_array().iter().all(|v| v.is_finite())
                && film
                    .spectrum(x, y)
                    .is_none_or(|s| s.iter().all(|v| v.is_finite()))
                && film
                    .energy(x, y)
                    .is_none_or(|e| e.iter().all(|v| v.is_finite()))
        })
}

fn settings() -> impl Strategy<Value = RenderSettings> {
    (
        (
            1u32..=5,
            1u32..=5,
            prop_oneof![3 => Just(0u64), 1 => 1u64..3],
            // Counts adaptive sampling takes (whole groups from 16) half the time.
            prop_oneof![1u64..=36, (4u64..=9).prop_map(|g| 4 * g)],
        ),
        (
            prop::sample::select(vec![1usize, 2, 4, 8, 16]),
            any::<bool>(),
            any::<bool>(),
            any::<bool>(),
        ),
        (
            prop::sample::select(vec![Splits::Fixed(1), Splits::Fixed(2), Splits::Auto]),
            prop::sample::select(vec![
                Reuse::Fixed(1),
                Reuse::Fixed(2),
                Reuse::Fixed(4),
                Reuse::Auto,
            ]),
            prop::sample::select(vec![Tracing::Paths, Tracing::Lanes(None)]),
            any::<bool>(),
            any::<u64>(),
        ),
    )
        .prop_map(
            |(
                (width, height, start, count),
                (wavelengths, adaptive, light_paths, spectral),
                (splits, reuse, tracing, energy, seed),
            )| {
                RenderSettings::default()
                    .width(width)
                    .height(height)
                    .samples(start..start + count)
                    .wavelengths(wavelengths)
                    .adaptive(adaptive)
                    .light_paths(light_paths)
                    .bands(spectral.then(|| SpectralBands::new(400.0, 700.0, 4).unwrap()))
                    .energy(energy)
                    .splits(splits)
                    .reuse(reuse)
                    .tracing(tracing)
                    .seed(seed)
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]
    #[test]
    fn every_allowed_combination_is_finite_deterministic_and_mergeable(
        settings in settings(),
        which in 0usize..2,
    ) {
        let scene = &scenes()[which];
        let renderer = match Renderer::new(scene, &settings) {
            Ok(r) => r,
            Err(e) => {
                let e = e.to_string();
                prop_assert!(!e.contains('\n') && !e.is_empty(), "{e}");
                return Ok(());
            }
        };
        let estimators = renderer.estimators();
        let (one, stats) = render(scene, &settings.clone().threads(1)).unwrap();
        prop_assert!(all_finite(&one), "{estimators}");
        prop_assert_eq!(stats.estimators, estimators);
        let (two, _) = render(scene, &settings.clone().threads(2)).unwrap();
        prop_assert!(one.sums() == two.sums(), "threads change the image: {}", estimators);
        prop_assert!(one.spectral_sums() == two.spectral_sums());
        let samples = settings.samples.clone();
        if samples.end - samples.start >= 2 {
            let middle = samples.start + (samples.end - samples.start) / 2;
            let pieces = [samples.start..middle, middle..samples.end]
                .map(|range| settings.clone().threads(1).samples(range));
            let same = pieces
                .iter()
                .all(|p| Renderer::new(scene, p).unwrap().estimators() == estimators);
            if same && !estimators.adaptive {
                let (mut first, _) = render(scene, &pieces[0]).unwrap();
                let (second, _) = render(scene, &pieces[1]).unwrap();
                first.merge(&second).unwrap();
                for (x, y) in first.sums().iter().zip(one.sums()) {
                    for k in 0..3 {
                        prop_assert!(
                            (x[k] - y[k]).abs() <= 1e-9 * y[k].abs().max(1e-9),
                            "pieces do not merge into the whole: {} vs {} ({})", x[k], y[k], estimators
                        );
                    }
                }
            }
        }
    }
}
