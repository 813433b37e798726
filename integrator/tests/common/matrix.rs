//! The estimator matrix's machinery: every combination of estimator settings the
//! resolution step allows, rendered over seeds, and a test of whether its expectation
//! equals the reference mode's in every output, block by block.
//!
//! The test is Welch's t-test per block and channel, over seeds: a block's mean in one
//! render is one value, and the renders of different seeds are independent, so their
//! spread is the block mean's own noise, whatever the estimator shares between pixels
//! (path reuse's tiles, adaptive sampling's rates). A comparison's blocks and channels
//! are many tests; Bonferroni's correction makes [`FALSE_ALARM`] the chance that a right
//! combination fails any of them (as Mitsuba 3's render tests correct their per-pixel
//! tests, src/render/tests/test_renders.py).

use prism_integrator::{
    Aovs, Film, LambdaSampler, RenderSettings, Reuse, SpectralBands, Splits, Tracing, render,
};
use prism_sampling::stats::welch_t_test;
use prism_scene::world::Scene;
use prism_spectrum::color::RgbSpaceId;

/// The chance that a right combination fails its comparison (family-wise, per scene and
/// combination).
pub const FALSE_ALARM: f64 = 1e-3;

/// A scene of the matrix and how it is rendered.
pub struct Case {
    pub name: &'static str,
    pub scene: Scene,
    pub size: u32,
    pub spp: u64,
    /// Seeds per combination: the t-tests' replicates.
    pub seeds: u64,
    /// Pixels per side of a block.
    pub block: u32,
    pub polarized: bool,
}

/// Settings of one combination, over the outputs every render of the matrix writes:
/// colour, spectral bands, energy, albedo, normal and depth (and Stokes components where
/// polarized).
pub fn base(case: &Case) -> RenderSettings {
    RenderSettings::default()
        .width(case.size)
        .height(case.size)
        .samples(0..case.spp)
        .lambda_sampler(LambdaSampler::Visible)
        .bands(Some(SpectralBands::new(400.0, 700.0, 6).unwrap()))
        .energy(true)
        .polarized(case.polarized)
        .aovs("albedo,normal,depth".parse::<Aovs>().unwrap())
}

/// The reference mode: uniform samples, unsplit paths without reuse, the path tracer.
pub fn reference(case: &Case) -> RenderSettings {
    base(case)
        .adaptive(false)
        .splits(Splits::Fixed(1))
        .reuse(Reuse::Fixed(1))
        .tracing(Tracing::Paths)
}

/// One combination of the estimator settings: a name and its settings.
pub struct Combination {
    pub name: String,
    pub settings: RenderSettings,
}

/// Every combination of adaptive sampling, splits and reuse, tracer, light paths and
/// `wavelengths`, over `case`'s base settings.
pub fn combinations(case: &Case, wavelengths: &[usize]) -> Vec<Combination> {
    let modes = [
        ("splits 1 reuse 1", Splits::Fixed(1), Reuse::Fixed(1)),
        ("splits 2", Splits::Fixed(2), Reuse::Fixed(1)),
        ("reuse 2", Splits::Fixed(1), Reuse::Fixed(2)),
        ("reuse 4", Splits::Fixed(1), Reuse::Fixed(4)),
        ("splits auto reuse auto", Splits::Auto, Reuse::Auto),
        ("splits auto reuse 1", Splits::Auto, Reuse::Fixed(1)),
    ];
    let mut out = Vec::new();
    for &n in wavelengths {
        for adaptive in [false, true] {
            for (mode, splits, reuse) in modes {
                for light_paths in [true, false] {
                    let name = format!(
                        "{n} wavelengths, adaptive {adaptive}, {mode}, light paths {light_paths}"
                    );
                    let settings = base(case)
                        .wavelengths(n)
                        .adaptive(adaptive)
                        .splits(splits)
                        .reuse(reuse)
                        .light_paths(light_paths);
                    out.push(Combination { name, settings });
                }
            }
        }
    }
    out
}

/// The combinations the resolution step allows, one per distinct set of estimators it
/// resolves to (and the refused ones' errors, each checked to be one line).
pub fn allowed(case: &Case, combinations: Vec<Combination>) -> Vec<Combination> {
    let mut seen = Vec::new();
    let mut out = Vec::new();
    for combination in combinations {
        match prism_integrator::Renderer::new(&case.scene, &combination.settings) {
            Ok(renderer) => {
                let e = renderer.estimators();
                let key = (
                    combination.settings.wavelengths,
                    e.tracer,
                    e.splits,
                    e.reuse,
                    e.light_paths,
                    e.adaptive,
                );
                if !seen.contains(&key) {
                    seen.push(key);
                    out.push(Combination {
                        name: format!("{} ({e})", combination.name),
                        settings: combination.settings,
                    });
                }
            }
            Err(e) => {
                let e = e.to_string();
                assert!(!e.contains('\n'), "{}: {e}", combination.name);
            }
        }
    }
    out
}

/// Per channel (named), per seed, per block: the block's mean.
pub type Blocks = Vec<(String, Vec<Vec<f64>>)>;

/// Renders `settings` under each of `case`'s seeds and gathers its block means.
pub fn render_blocks(case: &Case, settings: &RenderSettings) -> Blocks {
    let mut out: Blocks = Vec::new();
    for seed in 0..case.seeds {
        let (film, stats) = render(&case.scene, &settings.clone().seed(seed)).unwrap();
        assert_eq!(stats.nonfinite, 0, "{}: non-finite samples", case.name);
        for (k, (name, values)) in channels(&film).into_iter().enumerate() {
            let blocks = block_means(&values, case.size, case.block);
            if out.len() == k {
                out.push((name, Vec::new()));
            }
            out[k].1.push(blocks);
        }
    }
    out
}

/// Every output of `film` as named per-pixel channels.
pub fn channels(film: &Film) -> Vec<(String, Vec<f64>)> {
    let (w, h) = (film.width(), film.height());
    let pixels: Vec<(u32, u32)> = (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).collect();
    let mut out = Vec::new();
    for (k, name) in ["X", "Y", "Z"].into_iter().enumerate() {
        out.push((
            name.into(),
            pixels
                .iter()
                .map(|&(x, y)| film.xyz(x, y).to_array()[k])
                .collect(),
        ));
    }
    if let Some(bands) = film.bands() {
        let components = if film.is_polarized() { 4 } else { 1 };
        for c in 0..components {
            for b in 0..bands.count() {
                out.push((
                    format!("S{c} band {:.0} nm", bands.center(b)),
                    pixels
                        .iter()
                        .map(|&(x, y)| film.stokes_spectrum(x, y, c).unwrap()[b])
                        .collect(),
                ));
            }
        }
    }
    if film.has_energy() {
        for (k, name) in ["energy", "photons"].into_iter().enumerate() {
            out.push((
                name.into(),
                pixels
                    .iter()
                    .map(|&(x, y)| film.energy(x, y).unwrap()[k])
                    .collect(),
            ));
        }
    }
    if film.is_polarized() {
        for s in 1..4 {
            for (k, name) in ["X", "Y", "Z"].into_iter().enumerate() {
                out.push((
                    format!("S{s} {name}"),
                    pixels
                        .iter()
                        .map(|&(x, y)| film.stokes(x, y).unwrap()[s][k])
                        .collect(),
                ));
            }
        }
    }
    for (name, values) in film.aov_images(RgbSpaceId::Srgb.space()) {
        out.push((name, values.into_iter().map(f64::from).collect()));
    }
    out
}

/// The means of `block` x `block` blocks of a `size` x `size` channel.
fn block_means(values: &[f64], size: u32, block: u32) -> Vec<f64> {
    let per_side = size.div_ceil(block);
    let mut sums = vec![(0.0, 0u32); (per_side * per_side) as usize];
    for y in 0..size {
        for x in 0..size {
            let b = &mut sums[((y / block) * per_side + x / block) as usize];
            b.0 += values[(y * size + x) as usize];
            b.1 += 1;
        }
    }
    sums.into_iter().map(|(s, n)| s / f64::from(n)).collect()
}

/// The outcome of one comparison: its smallest p-value, where, and how many tests.
#[derive(Debug)]
pub struct Verdict {
    pub smallest_p: f64,
    pub worst: String,
    pub tests: usize,
}

impl Verdict {
    /// Whether the expectations differ at the family-wise rate [`FALSE_ALARM`].
    pub fn differs(&self) -> bool {
        self.smallest_p < FALSE_ALARM / self.tests as f64
    }
}

/// Compares two sets of block means, channel by channel and block by block. Channels
/// whose blocks are the same in every seed of both (a constant output) pass.
pub fn compare(a: &Blocks, b: &Blocks) -> Verdict {
    let mut verdict = Verdict {
        smallest_p: 1.0,
        worst: String::new(),
        tests: 0,
    };
    for ((name, seeds_a), (name_b, seeds_b)) in a.iter().zip(b) {
        assert_eq!(name, name_b, "the outputs differ");
        let blocks = seeds_a[0].len();
        for block in 0..blocks {
            let xa: Vec<f64> = seeds_a.iter().map(|s| s[block]).collect();
            let xb: Vec<f64> = seeds_b.iter().map(|s| s[block]).collect();
            let test = welch_t_test(&xa, &xb);
            verdict.tests += 1;
            if test.p_value < verdict.smallest_p {
                let mean = |x: &[f64]| x.iter().sum::<f64>() / x.len() as f64;
                verdict.smallest_p = test.p_value;
                verdict.worst = format!(
                    "{name}, block {block}: {:.5} vs {:.5} (t {:.2}, {:.1} degrees of freedom)",
                    mean(&xa),
                    mean(&xb),
                    test.t,
                    test.degrees_of_freedom
                );
            }
        }
    }
    verdict
}

/// `blocks` with one channel's values scaled by `factor` (a deliberately wrong
/// estimator, for the test's power).
pub fn scaled(blocks: &Blocks, channel: &str, factor: f64) -> Blocks {
    blocks
        .iter()
        .map(|(name, seeds)| {
            let f = if name == channel { factor } else { 1.0 };
            (
                name.clone(),
                seeds
                    .iter()
                    .map(|s| s.iter().map(|v| v * f).collect())
                    .collect(),
            )
        })
        .collect()
}
