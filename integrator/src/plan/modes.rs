//! The choice of [`Splits::Auto`](crate::Splits): how many continuations a camera sample
//! splits into at its first vertex, from a pilot of the render.
//!
//! Splitting (Arvo and Kirk, "Particle transport and image synthesis", SIGGRAPH 1990, §4)
//! trades the variance of what follows the first vertex against the cost of tracing it
//! more than once. With a sample's variance V(K) = V_b + V_c / K (V_b: what the camera ray
//! and the first light sample leave, the variance of the continuations' mean; V_c: a
//! continuation's variance given that prefix) and its cost C(K) = C_p + K C_c, efficiency
//! 1 / (V(K) C(K)) is greatest at K* = sqrt(V_c C_p / (V_b C_c)). The pilot traces the
//! same samples of a grid of pixels unsplit and split in two: V(1) - V(2) = V_c / 2, and
//! the rays they trace give C_p and C_c. Variances are weighted as the relative MSE weighs
//! errors (by 1 / (mean^2 + 0.01)), costs counted in rays (measured, a render's time is
//! nearly proportional to its rays), so the choice is a pure function of the scene, the
//! image size, the settings and the seed: every thread count and every machine of a farm
//! makes the same one.
//!
//! Where light paths carry caustics, what they add to a pixel neither splits nor depends
//! on the splits: their variance adds to the prefix's, their rays to the prefix's cost
//! (`LightPilot`, one light path per pixel under each pilot seed). Left out, a caustic
//! scene's pilot saw only the camera paths' part of the error and split where one
//! continuation reached an error sooner.

use crate::adaptive::error::channel_error;
use crate::film::sample_value::SampleValue;
use crate::pixels::sample::trace_sample;
use crate::pixels::sample_plan::SamplePlan;
use crate::plan::setup::Setup;
use crate::reuse::Tile;
use crate::transport::context::Integrator;
use crate::transport::throughput::Throughput;

/// The choices. Against Mitsuba's references four continuations beat two on the Cornell
/// box and lost to them on the bunny box, both by little (docs/trade-offs.md, "Splitting
/// at the first vertex"), a difference the pilot cannot resolve (its estimates of the
/// prefix's small variance are mostly its own noise), while between one and two it is
/// clear on every scene measured; and a render asked for N samples should not take
/// several times as long as N unsplit samples do (two continuations take nearly twice as
/// long). `--splits 4` remains for those who know their scene.
const CHOICES: [u32; 2] = [1, 2];

/// Pilot pixels per image side (at most), and samples per pilot pixel.
const GRID: u32 = 32;
const SAMPLES: u64 = 8;

/// The share of pilot pixels with the largest errors left out of the estimate.
const TRIMMED: f64 = 0.02;

/// The pilot's two seeds (each combined with the render's), other than the render's own so
/// that the pilot's samples are not the render's first ones.
const PILOT_SEEDS: [u64; 2] = [0x5b11_7e5a_a1e5_0001, 0x5b11_7e5a_a1e5_0002];

/// What light paths add to the pilot's pixels: per seed, the light paths' estimate of
/// every pixel from one light path per pixel, and their rays per light path.
pub(crate) struct LightPilot {
    width: u32,
    values: [Vec<[f64; 3]>; 2],
    rays: f64,
}

impl LightPilot {
    /// Traces one pass of light paths under each pilot seed for `setup` (None where
    /// its render traces no light paths).
    pub(crate) fn trace(setup: &Setup) -> Option<Self> {
        if !setup.light_caustics() {
            return None;
        }
        let settings = setup.settings();
        let (width, height) = (settings.width, settings.height);
        let mut rays = 0u64;
        let values = PILOT_SEEDS.map(|s| {
            let (film, r) = setup.light_pass(settings.seed ^ s);
            rays += r;
            (0..height)
                .flat_map(|y| (0..width).map(move |x| (x, y)))
                .map(|(x, y)| {
                    let xyz = film.xyz(x, y);
                    [xyz.x, xyz.y, xyz.z]
                })
                .collect()
        });
        let paths = 2.0 * f64::from(width) * f64::from(height);
        Some(Self {
            width,
            values,
            rays: rays as f64 / paths,
        })
    }

    /// What light paths add to pixel (`x`, `y`)'s error of a mean of `SAMPLES` samples
    /// (one light path's variance over `SAMPLES`), each channel weighted with the pixel's
    /// whole value, `camera` (its camera paths' mean) plus the light paths' mean.
    fn variance(&self, x: u32, y: u32, camera: [f64; 3]) -> f64 {
        let i = (y * self.width + x) as usize;
        let (a, b) = (self.values[0][i], self.values[1][i]);
        (0..3)
            .map(|k| {
                let mean = camera[k] + 0.5 * (a[k] + b[k]);
                channel_error(a[k], b[k], mean) / SAMPLES as f64
            })
            .sum()
    }
}

/// The mean over modes and seeds of a pixel's camera estimates.
fn camera_mean(means: &[[[f64; 3]; 2]]) -> [f64; 3] {
    let n = (2 * means.len()) as f64;
    std::array::from_fn(|k| means.iter().flatten().map(|m| m[k]).sum::<f64>() / n)
}

/// What a pilot measured: the relative-MSE-weighted squared error of a pixel's mean,
/// unsplit and split in two (the variance of a sample, as Sobol samples realize it), and
/// rays per sample for each.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Pilot {
    pub variance: [f64; 2],
    pub rays: [f64; 2],
}

impl Pilot {
    /// The number of continuations the pilot predicts reaches a given error soonest (1
    /// when the pilot saw nothing to split: no variance, or no continuation traced).
    pub(crate) fn choice(&self) -> u32 {
        let [v1, v2] = self.variance;
        let [r1, r2] = self.rays;
        let continuation_variance = 2.0 * (v1 - v2);
        let continuation_rays = r2 - r1;
        if !(continuation_variance > 0.0 && continuation_rays > 0.0) {
            return 1;
        }
        // The prefix's variance can come out negative from the pilot's own noise; it is at
        // least what a twentieth of the unsplit variance would be, which keeps K bounded
        // by the cost ratio rather than by that noise. The prefix costs at least its
        // camera ray.
        let prefix_variance = (v1 - continuation_variance).max(0.05 * v1);
        let prefix_rays = (r1 - continuation_rays).max(1.0);
        let inverse_efficiency = |k: f64| {
            (prefix_variance + continuation_variance / k) * (prefix_rays + k * continuation_rays)
        };
        // The first of the best: ties keep the cheaper render.
        let mut best = CHOICES[0];
        for &k in &CHOICES[1..] {
            if inverse_efficiency(f64::from(k)) < inverse_efficiency(f64::from(best)) {
                best = k;
            }
        }
        best
    }
}

/// Traces the pilot for `setup`: up to `GRID` x `GRID` pixels spread over the image,
/// each estimated twice (two seeds, `SAMPLES` samples each) unsplit and twice split in
/// two with the same streams. The two estimates' difference measures the error of a
/// pixel's mean as the render's Sobol samples make it (lower than independent samples'
/// variance says, and most for what the camera ray and the first light sample find, which
/// lie in a few well-stratified dimensions); the same streams for both modes make the
/// difference between the modes mostly the split's.
pub(crate) fn pilot<const N: usize, const FLUORESCENCE: bool, T: Throughput<N>>(
    setup: &Setup,
) -> Pilot {
    use rayon::prelude::*;
    let settings = setup.settings();
    let (width, height) = (settings.width, settings.height);
    let (columns, rows) = (width.min(GRID), height.min(GRID));
    let integrators = [setup.integrator(1), setup.integrator(2)];
    let seeds = PILOT_SEEDS.map(|s| setup.pilot_plan(settings.seed ^ s, 0..SAMPLES));
    let light = LightPilot::trace(setup);
    let per_pixel: Vec<Pilot> = (0..columns * rows)
        .into_par_iter()
        .map(|i| {
            // The centres of a columns x rows grid of equal cells.
            let x = ((2 * (i % columns) + 1) * width / (2 * columns)).min(width - 1);
            let y = ((2 * (i / columns) + 1) * height / (2 * rows)).min(height - 1);
            let (means, rays) =
                pixel_estimates::<N, FLUORESCENCE, T>(setup, &integrators, &seeds, x, y);
            let mut pixel = weighted_errors(&means, rays);
            if let Some(light) = &light {
                let added = light.variance(x, y, camera_mean(&means));
                for mode in 0..2 {
                    pixel.variance[mode] += added;
                    pixel.rays[mode] += light.rays * (2 * SAMPLES) as f64;
                }
            }
            pixel
        })
        .collect();
    summarize(&per_pixel)
}

/// The tile sides a pilot tries where paths can share their second vertices (the
/// `reuse` module). Two, four: on the Cornell box three was between them, and each
/// side's pilot costs its tile's pixels.
pub(crate) const REUSE_CHOICES: [u32; 2] = [2, 4];

/// Pilot tiles per image side (at most) for the choice with reuse: a tile of four by four
/// pixels is sixteen pilot pixels.
const REUSE_GRID: u32 = 16;

/// How much less error per ray reuse must promise to be chosen over the best split: its
/// noise is shared within tiles, and the pilot's estimates are themselves noisy.
const REUSE_MARGIN: f64 = 0.85;

/// The margin of [`REUSE_MARGIN`] for a render that samples adaptively, which reuses in
/// [`WIDEST_TILES`]: the pilot measures tiles of two under uniform samples, and with
/// adaptive sampling's spread tiles of four gain more than it sees. Measured against the
/// margin of uniform renders (each render's pilot included), it was more efficient on the
/// glossy, specular and caustic boxes at every size, and on the plastic box but at the
/// smallest size; a margin of 1.3 measured the same (docs/trade-offs.md, "Path reuse
/// across tiles of pixels").
const ADAPTIVE_REUSE_MARGIN: f64 = 1.1;

/// What reuse must do to its own tiles' error per ray (at most this share of it without
/// reuse, [`ModePilot::reuse_gain`]) to be chosen under [`ADAPTIVE_REUSE_MARGIN`]: where
/// no path shares a vertex (textured walls, no Lambertian second vertex) the pilot
/// measures about 1 either side, within its noise, and 4 x 4 tiles that share nothing
/// cost time (their wavelengths are shared too); the glossy, specular and caustic boxes
/// measure below this, the plastic box well below (docs/trade-offs.md, "Path reuse across
/// tiles of pixels").
const ADAPTIVE_REUSE_GAIN: f64 = 0.97;

/// What a connection of path reuse costs in the pilot's unit, a ray of a path: its shadow
/// ray, the pair's geometry (eight pairs at a time in SIMD lanes) and the BSDF's value.
/// callgrind on the Cornell box (32 x 32, 32 spp, `--reuse 2`, one thread) counts 761
/// instructions per connection against 2112 per ray of the paths, all of their work
/// included; counted as whole rays, reuse looked dearer than it measured on the medium
/// box, whose render time grows much less than its rays with reuse.
const CONNECTION_COST: f64 = 0.35;

/// What the pilot with reuse measured, per mode (unsplit, split in two, then each of
/// [`REUSE_CHOICES`]): the mean weighted squared error of a pixel's mean and rays per
/// sample (connections weighed by [`CONNECTION_COST`]), over the same cells of the image.
/// Splitting is measured at each cell's corner pixel, reuse on a tile at that corner; each
/// tile's pixels are also traced unsplit (`unsplit`), so that reuse is judged against
/// the same pixels and streams without it: against the corner pixel alone, the pilot's
/// estimate of reuse's gain was mostly the noise of comparing different pixels (a scene
/// where no path can share a vertex measured more error with reuse than without).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct ModePilot {
    pub variance: [f64; 4],
    pub rays: [f64; 4],
    /// Per tile side of [`REUSE_CHOICES`], the error and rays per sample of its tile's
    /// pixels unsplit and without reuse.
    pub unsplit: [f64; 2],
    pub unsplit_rays: [f64; 2],
    /// What light paths add to every mode's variance and rays per sample (a cell's;
    /// folded into the modes when cells are summarized).
    pub light_variance: f64,
    pub light_rays: f64,
}

impl ModePilot {
    /// (splits, reuse tile side) predicted to reach a given error soonest with uniform
    /// samples.
    pub(crate) fn choice(&self) -> (u32, u32) {
        let (k, split_cost) = self.best_split();
        if !(split_cost.is_finite() && split_cost > 0.0) {
            return (k, 1);
        }
        let mut best = (k, 1, split_cost);
        for (j, &t) in REUSE_CHOICES.iter().enumerate() {
            let c = self.reuse_cost(j);
            if c.is_finite() && c > 0.0 && c < REUSE_MARGIN * split_cost && c < best.2 {
                best = (1, t, c);
            }
        }
        (best.0, best.1)
    }

    /// The choice for a render that samples adaptively, from the first stage (tiles of
    /// two) alone: reuse in [`WIDEST_TILES`] where reuse changes its tiles' error
    /// ([`ADAPTIVE_REUSE_GAIN`]) and promises no more than [`ADAPTIVE_REUSE_MARGIN`] times
    /// the best split's error per ray, else the best split.
    pub(crate) fn adaptive_choice(&self) -> (u32, u32) {
        let (k, split_cost) = self.best_split();
        let c = self.reuse_cost(0);
        let gain = self.reuse_gain(0);
        let reuses = split_cost.is_finite()
            && split_cost > 0.0
            && c.is_finite()
            && c > 0.0
            && gain < ADAPTIVE_REUSE_GAIN
            && c < ADAPTIVE_REUSE_MARGIN * split_cost;
        if reuses { (1, WIDEST_TILES) } else { (k, 1) }
    }

    /// The best number of continuations and its error per ray.
    fn best_split(&self) -> (u32, f64) {
        let split = Pilot {
            variance: [self.variance[0], self.variance[1]],
            rays: [self.rays[0], self.rays[1]],
        };
        let k = split.choice();
        (k, self.variance[k as usize - 1] * self.rays[k as usize - 1])
    }

    /// The error per ray predicted with reuse on tiles of side `REUSE_CHOICES[j]`: the
    /// corner pixels' unsplit, times what reuse did to its own tiles' pixels (NaN where
    /// not measured).
    fn reuse_cost(&self, j: usize) -> f64 {
        self.variance[0] * self.rays[0] * self.reuse_gain(j)
    }

    /// What reuse on tiles of side `REUSE_CHOICES[j]` did to its own tiles' error per ray:
    /// their error per ray with reuse over without (NaN where not measured).
    fn reuse_gain(&self, j: usize) -> f64 {
        (self.variance[2 + j] / self.unsplit[j]) * (self.rays[2 + j] / self.unsplit_rays[j])
    }

    /// Whether the smallest tiles promise enough for the larger ones to be worth trying
    /// (at most [`WIDE_TILES_BELOW`] of the best split's error per ray).
    fn worth_wider_tiles(&self) -> bool {
        self.reuse_cost(0) <= WIDE_TILES_BELOW * self.best_split().1
    }
}

/// The larger tiles of [`REUSE_CHOICES`] are tried only where the smallest promise at most
/// this share of the best split's error per ray. Measured with every repository scene at
/// 64, 128 and 256 pixels square: where tiles of four paid (the Cornell and bunny boxes,
/// where four measure clearly better than two) tiles of two promised less than this, and
/// where they promised more (the medium, plastic and specular boxes) four measured no
/// better than two, for a stage of the pilot that costs more than the rest of it
/// (docs/trade-offs.md, "Path reuse across tiles of pixels").
const WIDE_TILES_BELOW: f64 = 0.8;

/// The tiles a render that samples adaptively shares vertices in wherever the pilot
/// chooses reuse ([`ModePilot::adaptive_choice`]): the largest of [`REUSE_CHOICES`],
/// without the pilot's stage that compares them. The pilot measures each mode with
/// uniform samples, where tiles of four measured no better than two on the medium box;
/// with adaptive sampling's spread (`adaptive`), four measured better than two there and
/// on the plastic, specular, glossy and caustic boxes and the milky bunny, where the
/// pilot chooses two (docs/trade-offs.md, "Path reuse across tiles of pixels"); the boxes
/// the pilot gave four keep them (images byte-identical), and every such render skips
/// the pilot's stage that compares the tiles.
const WIDEST_TILES: u32 = REUSE_CHOICES[REUSE_CHOICES.len() - 1];

/// Traces the pilot for a scene whose paths can share their second vertices: up to
/// `REUSE_GRID` x `REUSE_GRID` cells, in each the pixel at the cell's corner unsplit and
/// split in two (as [`pilot`]), and the tiles of [`REUSE_CHOICES`] at that corner with
/// reuse (the larger only where the smallest promise much, [`WIDE_TILES_BELOW`]), each
/// estimated twice (two seeds, `SAMPLES` samples each). A cell's error per
/// mode is its pixels' mean; the cells with the largest errors are left out as in
/// [`pilot`]. Returns (splits, reuse tile side); a render that samples adaptively chooses
/// from the first stage alone ([`ModePilot::adaptive_choice`]).
pub(crate) fn mode_pilot<const N: usize, const FLUORESCENCE: bool, T: Throughput<N>>(
    setup: &Setup,
) -> (u32, u32) {
    use rayon::prelude::*;
    let settings = setup.settings();
    let (width, height) = (settings.width, settings.height);
    let (columns, rows) = (width.min(REUSE_GRID), height.min(REUSE_GRID));
    let integrators = [setup.integrator(1), setup.integrator(2)];
    let seeds = PILOT_SEEDS.map(|s| setup.pilot_plan(settings.seed ^ s, 0..SAMPLES));
    let light = LightPilot::trace(setup);
    let corner = |i: u32| {
        (
            (i % columns) * width / columns,
            (i / columns) * height / rows,
        )
    };
    // The modes 0 and 1: a cell's corner pixel, unsplit and split in two.
    let split = |i: u32, cell: &mut ModePilot| {
        let (x, y) = corner(i);
        let (means, rays) =
            pixel_estimates::<N, FLUORESCENCE, T>(setup, &integrators, &seeds, x, y);
        for mode in 0..2 {
            cell.variance[mode] = weighted_error(&means[mode]);
            cell.rays[mode] = rays[mode] / (2 * SAMPLES) as f64;
        }
        // Light paths add to every mode alike (the cell's corner pixel stands for it).
        if let Some(light) = &light {
            cell.light_variance = light.variance(x, y, camera_mean(&means));
            cell.light_rays = light.rays;
        }
    };
    // Mode 2 + j: the tile of side REUSE_CHOICES[j] at the cell's corner, with reuse,
    // and the same pixels on the same streams without it.
    let reuse = |i: u32, j: usize, cell: &mut ModePilot| {
        let (x, y) = corner(i);
        let side = REUSE_CHOICES[j];
        let xs = x..(x + side).min(width);
        let ys = y..(y + side).min(height);
        let pixels = xs.len() * ys.len();
        // Per pixel of the tile and seed, the mean colour of its samples.
        let mut means = vec![[[0.0f64; 3]; 2]; pixels];
        let mut tile = Tile::new();
        let mut rays = 0.0;
        for (seed, rows) in seeds.iter().enumerate() {
            for s in 0..SAMPLES {
                crate::reuse::trace_tile_at::<N>(
                    &integrators[0],
                    setup.filter(),
                    rows,
                    xs.clone(),
                    ys.clone(),
                    s,
                    &mut tile,
                );
                for (p, out) in tile.pixels().iter().enumerate() {
                    let connections = out.result.connections as f64;
                    rays += out.result.rays as f64 - (1.0 - CONNECTION_COST) * connections;
                    if out.result.valid && out.value.finite() {
                        for (mean, v) in means[p][seed].iter_mut().zip(out.value.xyz) {
                            *mean += v / SAMPLES as f64;
                        }
                    }
                }
            }
        }
        let samples = (2 * SAMPLES as usize * pixels) as f64;
        cell.variance[2 + j] = means.iter().map(weighted_error).sum::<f64>() / pixels as f64;
        cell.rays[2 + j] = rays / samples;
        let (mut unsplit, mut unsplit_rays) = (0.0, 0.0);
        for py in ys.clone() {
            for px in xs.clone() {
                // The corner pixel's unsplit estimate is mode 0's, traced already.
                if (px, py) == (x, y) {
                    unsplit += cell.variance[0];
                    unsplit_rays += cell.rays[0] * (2 * SAMPLES) as f64;
                    continue;
                }
                let (means, rays) =
                    unsplit_estimates::<N, FLUORESCENCE, T>(setup, &integrators[0], &seeds, px, py);
                unsplit += weighted_error(&means);
                unsplit_rays += rays;
            }
        }
        cell.unsplit[j] = unsplit / pixels as f64;
        cell.unsplit_rays[j] = unsplit_rays / samples;
    };
    // The larger tiles cost their pixels: they are tried only where the smallest promise
    // to pay well (a scene whose error is in what the camera ray finds pays for two modes).
    let mut per_cell: Vec<ModePilot> = (0..columns * rows)
        .into_par_iter()
        .map(|i| {
            let mut cell = ModePilot::default();
            split(i, &mut cell);
            reuse(i, 0, &mut cell);
            cell
        })
        .collect();
    let first = summarize_modes(&per_cell, 3);
    if setup.samples_adaptively() {
        return first.adaptive_choice();
    }
    let choice = first.choice();
    if choice.1 == 1 {
        return choice;
    }
    if !first.worth_wider_tiles() {
        return choice;
    }
    per_cell.par_iter_mut().enumerate().for_each(|(i, cell)| {
        for j in 1..REUSE_CHOICES.len() {
            reuse(i as u32, j, cell);
        }
    });
    summarize_modes(&per_cell, 4).choice()
}

/// The cells' mean errors and rays over the first `modes` modes; the other modes stay
/// zero, which [`ModePilot::choice`] reads as not measured.
///
/// Splitting's comparison (unsplit and split at the corner pixels) leaves out the cells of
/// the largest errors over all modes (`TRIMMED` of them, as [`summarize`]). Each tile
/// side's comparison (with reuse and without, on its tiles) leaves out its own largest,
/// and counts each such cell's error as their mean in both: the tail of a scene's error
/// (a caustic's rare paths, which reuse does not touch) still weighs against reuse's
/// gain, while the noise of its few cells cannot decide for either. Left out entirely, the
/// tail made reuse look much better than it was on the caustic box; counted as measured,
/// one firefly decides.
fn summarize_modes(per_cell: &[ModePilot], modes: usize) -> ModePilot {
    let mut total = ModePilot::default();
    let all = per_cell.len() as f64;
    let kept = kept_in_order(
        &per_cell
            .iter()
            .map(|p| p.variance[..modes].iter().sum::<f64>())
            .collect::<Vec<_>>(),
    );
    let n = kept.len() as f64;
    for &i in &kept {
        let cell = &per_cell[i];
        for mode in 0..2 {
            total.variance[mode] += (cell.variance[mode] + cell.light_variance) / n;
            total.rays[mode] += (cell.rays[mode] + cell.light_rays) / n;
        }
    }
    for j in 0..modes - 2 {
        let errors: Vec<f64> = per_cell
            .iter()
            .map(|c| c.variance[2 + j] + c.unsplit[j])
            .collect();
        let kept = kept_in_order(&errors);
        let mut is_kept = vec![false; per_cell.len()];
        for &i in &kept {
            is_kept[i] = true;
        }
        // Summed in the kept cells' order, then the others' by position: the same on any
        // thread count.
        let others = (0..per_cell.len()).filter(|&i| !is_kept[i]);
        for i in kept.iter().copied().chain(others) {
            let cell = &per_cell[i];
            let (with, without) = if is_kept[i] {
                (cell.variance[2 + j], cell.unsplit[j])
            } else {
                let mean = 0.5 * (cell.variance[2 + j] + cell.unsplit[j]);
                (mean, mean)
            };
            total.variance[2 + j] += (with + cell.light_variance) / all;
            total.unsplit[j] += (without + cell.light_variance) / all;
            total.rays[2 + j] += (cell.rays[2 + j] + cell.light_rays) / all;
            total.unsplit_rays[j] += (cell.unsplit_rays[j] + cell.light_rays) / all;
        }
    }
    total
}

/// One pixel's squared error of a mean, (a - b)^2 / 2 for its two seeds' means a and b,
/// each channel's weighted by 1 / (mean^2 + 0.01) (as the relative MSE weighs errors),
/// summed over the channels.
fn weighted_error(means: &[[f64; 3]; 2]) -> f64 {
    (0..3)
        .map(|k| channel_error(means[0][k], means[1][k], 0.5 * (means[0][k] + means[1][k])))
        .sum()
}

/// Per mode (unsplit, split in two) and seed, the mean colour of pixel (`x`, `y`)'s
/// `SAMPLES` samples, and per mode the rays they traced.
fn pixel_estimates<const N: usize, const FLUORESCENCE: bool, T: Throughput<N>>(
    setup: &Setup,
    integrators: &[Integrator; 2],
    seeds: &[SamplePlan; 2],
    x: u32,
    y: u32,
) -> ([[[f64; 3]; 2]; 2], [f64; 2]) {
    let [a, b] = integrators
        .each_ref()
        .map(|integrator| unsplit_estimates::<N, FLUORESCENCE, T>(setup, integrator, seeds, x, y));
    ([a.0, b.0], [a.1, b.1])
}

/// Per seed, the mean colour of pixel (`x`, `y`)'s `SAMPLES` samples by `integrator`, and the
/// rays they traced.
fn unsplit_estimates<const N: usize, const FLUORESCENCE: bool, T: Throughput<N>>(
    setup: &Setup,
    integrator: &Integrator,
    seeds: &[SamplePlan; 2],
    x: u32,
    y: u32,
) -> ([[f64; 3]; 2], f64) {
    let mut means = [[0.0f64; 3]; 2];
    let mut rays = 0.0;
    let mut value = SampleValue::default();
    for (seed, rows) in seeds.iter().enumerate() {
        for s in 0..SAMPLES {
            let result = trace_sample::<N, FLUORESCENCE, T>(
                integrator,
                setup.filter(),
                rows,
                x,
                y,
                s,
                &mut value,
            );
            rays += result.rays as f64;
            if result.valid && value.finite() {
                for (mean, v) in means[seed].iter_mut().zip(value.xyz) {
                    *mean += v / SAMPLES as f64;
                }
            }
        }
    }
    (means, rays)
}

/// The pilot's pixels' mean error and rays, without the pixels of the largest errors
/// (`TRIMMED` of them): a squared difference of two estimates is heavy-tailed where
/// rare paths carry much light (caustics, small bright sources), and one such pixel
/// decided the choice on the effects stage, differently at each image size. Sorted by
/// value, ties by position, and summed in order: the same result on any thread count.
fn summarize(per_pixel: &[Pilot]) -> Pilot {
    let errors: Vec<f64> = per_pixel
        .iter()
        .map(|p| p.variance[0] + p.variance[1])
        .collect();
    let kept = kept_in_order(&errors);
    let n = kept.len() as f64;
    let mut total = Pilot::default();
    for &i in &kept {
        let p = &per_pixel[i];
        for mode in 0..2 {
            total.variance[mode] += p.variance[mode] / n;
            total.rays[mode] += p.rays[mode] / (n * (2 * SAMPLES) as f64);
        }
    }
    total
}

/// The indices of `errors` without the `TRIMMED` share of the largest, sorted by error
/// (ties by position): summed in this order, the result is the same on any thread count.
fn kept_in_order(errors: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..errors.len()).collect();
    order.sort_by(|&a, &b| errors[a].total_cmp(&errors[b]).then(a.cmp(&b)));
    let kept = errors.len() - (errors.len() as f64 * TRIMMED).ceil() as usize;
    order.truncate(kept.max(1).min(errors.len()));
    order
}

/// One pixel's squared error of a mean per mode, (a - b)^2 / 2 for the two seeds' means a
/// and b, each channel's weighted by 1 / (mean^2 + 0.01) with the mean of all four
/// estimates (as the relative MSE weighs errors), summed over the channels.
fn weighted_errors(means: &[[[f64; 3]; 2]; 2], rays: [f64; 2]) -> Pilot {
    let mut pilot = Pilot {
        variance: [0.0; 2],
        rays,
    };
    for k in 0..3 {
        let mean = means.iter().flatten().map(|m| m[k]).sum::<f64>() / 4.0;
        for (mode, [a, b]) in means.iter().enumerate() {
            pilot.variance[mode] += channel_error(a[k], b[k], mean);
        }
    }
    pilot
}

#[cfg(test)]
mod tests {
    use super::{ModePilot, Pilot, summarize_modes};

    fn pilot(v1: f64, v2: f64, r1: f64, r2: f64) -> Pilot {
        Pilot {
            variance: [v1, v2],
            rays: [r1, r2],
        }
    }

    /// The Cornell box's measured figures (relative MSE 2.02e-3 unsplit, 0.98e-3 split in
    /// two; 6.50 and 11.34 rays per sample): nearly all its variance follows the first
    /// vertex, so continuations pay.
    #[test]
    fn indirect_light_splits() {
        assert_eq!(pilot(2.02e-3, 0.98e-3, 6.50, 11.34).choice(), 2);
    }

    /// The effects stage's (8.56e-3, 7.23e-3; 4.94 and 6.93 rays): most of its error is in
    /// what the camera ray and the first light sample find, so splitting does not pay.
    #[test]
    fn direct_light_does_not_split() {
        assert_eq!(pilot(8.56e-3, 7.23e-3, 4.94, 6.93).choice(), 1);
    }

    /// V_b = V_c: splitting pays only where continuations are cheap.
    #[test]
    fn balanced_cases_follow_the_costs() {
        // V(1) = 2, V(2) = 1.5 (V_b = V_c = 1); C_p = 1, C_c = 1: inverse efficiencies
        // 2 * 2 = 4 against 1.5 * 3 = 4.5, one. With C_c = 0.25: 2 * 1.25 against 1.5 * 1.5.
        assert_eq!(pilot(2.0, 1.5, 2.0, 3.0).choice(), 1);
        assert_eq!(pilot(2.0, 1.5, 1.25, 1.5).choice(), 2);
    }

    /// One pixel whose estimates disagree wildly (a rare bright path in one of them) does
    /// not decide: without it splitting gains nothing here, and it is left out.
    #[test]
    fn an_outlier_pixel_does_not_decide() {
        let mut pixels = vec![pilot(1.0, 0.9, 80.0, 128.0); 99];
        pixels.push(pilot(1000.0, 1.0, 80.0, 128.0));
        let summary = super::summarize(&pixels);
        assert!(
            (summary.variance[0] - 1.0).abs() < 1e-12 && (summary.variance[1] - 0.9).abs() < 1e-12
        );
        assert!((summary.rays[0] - 5.0).abs() < 1e-12 && (summary.rays[1] - 8.0).abs() < 1e-12);
        assert_eq!(summary.choice(), 1);
        // Counted in, it would have split.
        let all = pixels.iter().fold([0.0; 2], |s, p| {
            [s[0] + p.variance[0], s[1] + p.variance[1]]
        });
        assert_eq!(pilot(all[0], all[1], 5.0, 8.0).choice(), 2);
    }

    /// Nothing measured, or nothing gained, splits nothing; no input gives a NaN choice.
    #[test]
    fn degenerate_pilots_do_not_split() {
        for p in [
            pilot(0.0, 0.0, 0.0, 0.0),
            pilot(1.0, 1.0, 5.0, 8.0),
            pilot(1.0, 2.0, 5.0, 8.0),
            pilot(2.0, 1.0, 5.0, 5.0),
            pilot(f64::NAN, 1.0, 5.0, 8.0),
            pilot(2.0, 1.0, f64::NAN, 8.0),
        ] {
            assert_eq!(p.choice(), 1, "{p:?}");
        }
    }

    /// A cell of the reuse pilot: unsplit and split errors at its corner, and reuse's
    /// and unsplit's on its tile of side two.
    fn cell(v: [f64; 2], reuse: f64, unsplit: f64) -> ModePilot {
        ModePilot {
            variance: [v[0], v[1], reuse, 0.0],
            rays: [5.0, 8.0, 6.0, 0.0],
            unsplit: [unsplit, 0.0],
            unsplit_rays: [5.0, 0.0],
            ..ModePilot::default()
        }
    }

    /// Reuse is judged against its own tiles without it: where no path shares a vertex (the
    /// same error on the tiles either way) it is not chosen, however the corner pixels'
    /// error compares; where it halves the tiles' error at 1.2x the rays, it is.
    #[test]
    fn reuse_is_judged_on_its_own_tiles() {
        let cells = |reuse: f64| -> Vec<ModePilot> {
            (0..100)
                .map(|i| cell([2.0 + f64::from(i % 3), 2.5], reuse, 1.0 + f64::from(i % 2)))
                .collect()
        };
        let same: Vec<ModePilot> = (0..100)
            .map(|i| {
                let u = 1.0 + f64::from(i % 2);
                cell([2.0 + f64::from(i % 3), 2.5], u, u)
            })
            .collect();
        assert_eq!(summarize_modes(&same, 3).choice(), (1, 1));
        let halved: Vec<ModePilot> = cells(0.0)
            .iter()
            .map(|c| {
                cell(
                    [c.variance[0], c.variance[1]],
                    0.5 * c.unsplit[0],
                    c.unsplit[0],
                )
            })
            .collect();
        assert_eq!(summarize_modes(&halved, 3).choice(), (1, 2));
    }

    /// The larger tiles are tried where the smallest halve the error per ray, not where
    /// they cut it by a sixth (though both choose reuse over splitting).
    #[test]
    fn wider_tiles_are_tried_where_the_smallest_gain_much() {
        let cells = |reuse: f64| -> Vec<ModePilot> {
            (0..100).map(|_| cell([2.0, 2.5], reuse, 2.0)).collect()
        };
        // Unsplit 2 x 5 rays is the best split; reuse's cost is that times
        // (reuse / 2) x (6 / 5).
        let much = summarize_modes(&cells(0.8), 3);
        assert_eq!(much.choice(), (1, 2));
        assert!(much.worth_wider_tiles());
        let little = summarize_modes(&cells(1.38), 3);
        assert_eq!(little.choice(), (1, 2));
        assert!(!little.worth_wider_tiles());
    }

    /// A render that samples adaptively reuses (in tiles of four) where reuse promises
    /// up to 1.1x the best split's error per ray, provided it changes its own tiles'
    /// error; one that samples uniformly keeps the stricter margin.
    #[test]
    fn adaptive_renders_reuse_where_it_changes_the_error() {
        // Unsplit 2 x 5 rays is the best split; reuse's gain is (reuse / 2) x (6 / 5).
        let summary = |reuse: f64| summarize_modes(&vec![cell([2.0, 2.5], reuse, 2.0); 100], 3);
        // Gain 0.93: within the adaptive margin, outside the uniform one.
        let some = summary(1.55);
        assert_eq!(some.adaptive_choice(), (1, 4));
        assert_eq!(some.choice(), (1, 1));
        // Gain 0.99: reuse shares next to nothing, however close its cost.
        assert_eq!(summary(1.65).adaptive_choice(), (1, 1));
        // Gain 1.2x the split's cost: over the margin.
        assert_eq!(summary(2.0).adaptive_choice(), (1, 1));
        // Much gain: both reuse.
        assert_eq!(summary(0.8).adaptive_choice(), (1, 4));
        assert_eq!(summary(0.8).choice(), (1, 2));
        // A pilot that measured nothing neither reuses nor splits.
        assert_eq!(ModePilot::default().adaptive_choice(), (1, 1));
    }

    /// A cell whose unsplit estimates met a firefly does not decide for reuse, and does
    /// not vanish either: it counts alike in both, diluting reuse's gain elsewhere.
    #[test]
    fn the_tail_counts_alike_with_reuse_and_without() {
        let mut cells: Vec<ModePilot> = (0..100).map(|_| cell([1.0, 0.9], 0.7, 1.0)).collect();
        cells.push(cell([1.0, 0.9], 1.0, 1000.0));
        let summary = summarize_modes(&cells, 3);
        let ratio = summary.variance[2] / summary.unsplit[0];
        // Three cells are trimmed (2% of 101, rounded up): the firefly's and two ordinary
        // cells, each counted at its mean in both modes.
        let expected = (98.0 * 0.7 + 2.0 * 0.85 + 500.5) / (98.0 + 2.0 * 0.85 + 500.5);
        assert!((ratio - expected).abs() < 1e-12, "{ratio} vs {expected}");
        // Counted as measured, the firefly would have made reuse look a hundred times better.
        assert!(ratio > 0.9);
    }
}
