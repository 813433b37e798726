//! Coefficient tables: interpolation accuracy against exact colorimetry, at a resolution
//! small enough for the default test run. The 64^3 accuracy targets are measured by the
//! ignored test `table_accuracy_report` (PRISM_TABLE_RES=64 cargo test --release ...).

use prism_spectrum::color::RgbSpaceId;
use prism_spectrum::colorimetry::{Lab, Observer, ciede2000, reflectance_xyz};
use prism_spectrum::illuminant::StandardIlluminant;
use prism_upsample::{CoefficientTable, FitContext};

fn srgb() -> FitContext {
    FitContext::new(
        RgbSpaceId::Srgb.space(),
        &StandardIlluminant::D65.spectrum(),
    )
    .unwrap()
}

fn random_colours(n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut x = seed;
    (0..n)
        .map(|_| {
            std::array::from_fn(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 11) as f64 / (1u64 << 53) as f64
            })
        })
        .collect()
}

/// Mean, 99th percentile and max CIEDE2000 of `spectrum_of(rgb)` against `rgb`.
fn accuracy(
    context: &FitContext,
    colours: &[[f64; 3]],
    spectrum_of: impl Fn([f64; 3]) -> prism_upsample::SigmoidPolynomial,
) -> (f64, f64, f64) {
    let d65 = StandardIlluminant::D65.spectrum();
    let white = context.white();
    let mut errors: Vec<f64> = colours
        .iter()
        .map(|&rgb| {
            let xyz = reflectance_xyz(&spectrum_of(rgb), &d65, Observer::Cie1931).unwrap();
            ciede2000(
                Lab::from_xyz(xyz, white),
                Lab::from_xyz(context.rgb_xyz(rgb), white),
            )
        })
        .collect();
    errors.sort_by(f64::total_cmp);
    let mean = errors.iter().sum::<f64>() / errors.len() as f64;
    (
        mean,
        errors[errors.len() * 99 / 100],
        errors[errors.len() - 1],
    )
}

#[test]
fn nodes_are_exact_and_interpolation_is_close() {
    let context = srgb();
    let (table, stats) = CoefficientTable::fit(&context, 16, &|_| {}).unwrap();
    assert_eq!(stats.nodes, 3 * 16 * 16 * 15);
    assert_eq!(
        stats.unreachable, 0,
        "sRGB lies inside the reflectance gamut: {stats:?}"
    );
    // At the nodes the lookup returns the fitted coefficients: exact colour.
    // Ratio nodes are smoothstep(i / 15): smoothstep(1/3) = 7/27, smoothstep(2/3) = 20/27.
    let node = [1.0, 7.0 / 27.0, 20.0 / 27.0];
    let (mean, _, max) = accuracy(&context, &[node, [1.0, 1.0, 1.0], [0.0, 0.0, 1.0]], |rgb| {
        table.lookup(rgb)
    });
    assert!(max < 1e-3, "nodes: mean {mean} max {max}");
    // Between nodes at 16^3: a coarse table, so a loose bound; the refined lookup recovers
    // the exact fit's accuracy.
    let colours = random_colours(500, 7);
    let (mean, p99, max) = accuracy(&context, &colours, |rgb| table.lookup(rgb));
    eprintln!("16^3 trilinear: mean {mean:.4} p99 {p99:.4} max {max:.4}");
    assert!(
        mean < 0.5 && max < 5.0,
        "16^3 trilinear: mean {mean} max {max}"
    );
    let (mean_r, _, max_r) = accuracy(&context, &colours, |rgb| {
        table.lookup_refined(&context, rgb, 3)
    });
    eprintln!("16^3 refined (3 steps): mean {mean_r:.2e} max {max_r:.2e}");
    assert!(
        mean_r < 0.01 * mean && max_r < 0.1 * max,
        "refinement must improve: mean {mean_r} max {max_r}"
    );
}

/// The accuracy-versus-resolution report (slow at 64^3 in debug builds):
/// `PRISM_TABLE_RES=64 cargo test --release -p prism-upsample --test table -- --ignored --nocapture`.
#[test]
#[ignore]
fn table_accuracy_report() {
    let res: usize = std::env::var("PRISM_TABLE_RES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(64);
    let context = srgb();
    let start = std::time::Instant::now();
    let (table, stats) = CoefficientTable::fit(&context, res, &|_| {}).unwrap();
    let seconds = start.elapsed().as_secs_f64();
    let colours = random_colours(20_000, 11);
    let (mean, p99, max) = accuracy(&context, &colours, |rgb| table.lookup(rgb));
    let (mean_r, p99_r, max_r) = accuracy(&context, &colours, |rgb| {
        table.lookup_refined(&context, rgb, 1)
    });
    // Where the worst interpolation errors are, to guide the layout.
    let d65 = StandardIlluminant::D65.spectrum();
    let white = context.white();
    let mut worst: Vec<(f64, [f64; 3])> = colours
        .iter()
        .map(|&rgb| {
            let xyz = reflectance_xyz(&table.lookup(rgb), &d65, Observer::Cie1931).unwrap();
            (
                ciede2000(
                    Lab::from_xyz(xyz, white),
                    Lab::from_xyz(context.rgb_xyz(rgb), white),
                ),
                rgb,
            )
        })
        .collect();
    worst.sort_by(|a, b| b.0.total_cmp(&a.0));
    for (de, rgb) in worst.iter().take(8) {
        let m = rgb.iter().copied().fold(0.0, f64::max);
        eprintln!(
            "  worst: dE {de:.3} rgb {rgb:.4?} max {m:.4} ratios {:.4?}",
            rgb.map(|c| c / m)
        );
    }
    eprintln!(
        "{res}^3 sRGB: fit {seconds:.1} s wall, {} nodes, {:.2} iterations/node, max node residual {:.1e}\n  trilinear: mean {mean:.4} p99 {p99:.4} max {max:.4}\n  refined (1 step): mean {mean_r:.4} p99 {p99_r:.4} max {max_r:.4}",
        stats.nodes,
        stats.iterations as f64 / stats.nodes as f64,
        stats.max_residual
    );
}

/// Any RGB space can be fitted: primaries of one's own under CIE D50. Exact fits of
/// in-gamut colours round-trip under that illuminant, a table fitted for the space
/// records it (and is told apart from sRGB's), and its lookups stay close.
#[test]
fn user_defined_spaces_fit() {
    use prism_spectrum::color::{RgbColorSpace, TransferFunction};
    use prism_spectrum::colorimetry::{Chromaticity, WhitePoint, emission_xyz};
    let d50 = StandardIlluminant::D50.spectrum();
    let white = WhitePoint::from_xyz(emission_xyz(&d50, Observer::Cie1931)).unwrap();
    let space = RgbColorSpace::new(
        "mine",
        [(0.66, 0.32), (0.24, 0.68), (0.15, 0.07)].map(|(x, y)| Chromaticity::new(x, y)),
        white.xy(),
        TransferFunction::Linear,
    )
    .unwrap();
    let context = FitContext::new(&space, &d50).unwrap();
    let error = |rgb: [f64; 3], spectrum: &prism_upsample::SigmoidPolynomial| {
        let xyz = reflectance_xyz(spectrum, &d50, Observer::Cie1931).unwrap();
        let w = context.white();
        ciede2000(
            Lab::from_xyz(xyz, w),
            Lab::from_xyz(context.rgb_xyz(rgb), w),
        )
    };
    for rgb in [
        [0.8, 0.2, 0.1],
        [0.2, 0.5, 0.3],
        [0.1, 0.2, 0.6],
        [0.9, 0.9, 0.85],
    ] {
        let de = error(rgb, &context.fit(rgb, [0.0; 3]).spectrum);
        assert!(de < 1e-3, "{rgb:?}: dE2000 {de}");
    }
    let (table, stats) = CoefficientTable::fit(&context, 12, &|_| {}).unwrap();
    assert_eq!(table.space().name, "mine");
    assert!(table.space().matches(&context));
    assert!(!table.space().matches(&srgb()));
    assert!(stats.unreachable < stats.nodes / 10, "{stats:?}");
    let colours = random_colours(300, 7);
    let mean = colours
        .iter()
        .map(|&rgb| error(rgb, &table.lookup(rgb)))
        .sum::<f64>()
        / colours.len() as f64;
    assert!(mean < 0.5, "mean dE2000 {mean} at 12^3");
}
