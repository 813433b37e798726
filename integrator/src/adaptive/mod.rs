//! Adaptive sampling: a render's samples spread over the image in proportion to where
//! its error is, by a pilot of the whole image.
//!
//! With n_i samples in pixel i, each of variance v_i and cost c_i, and errors weighted as
//! the relative MSE weighs them (w_i = 1 / (mean_i^2 + 0.01)), the image's error
//! sum_i w_i v_i / n_i for a fixed cost sum_i c_i n_i is smallest at n_i proportional to
//! sqrt(w_i v_i / c_i) (a Lagrange multiplier; the optimum allocation of stratified
//! sampling, Cochran, *Sampling Techniques*, 3rd ed., §5.5). The total of samples is kept,
//! so that a render of N samples per pixel still takes N on average. Where error gathers (a glass sphere, a caustic, a glossy
//! highlight of the sky), equal samples everywhere waste most of them: the measured gains
//! are in docs/trade-offs.md, "Adaptive sampling".
//!
//! The pilot traces every pixel once under each of two seeds of its own, in the render's
//! own modes (splits, reuse); the two estimates' squared difference over two is a one-sample
//! estimate of w_i v_i, their rays one of c_i. One sample is a poor estimate, so each is
//! averaged over a
//! [`SMOOTHING`]-pixel box (error gathers in regions, not in pixels) and then over tiles
//! of [`TILE`] x [`TILE`] pixels, within which the rate is one. The pilot's samples are not
//! the render's: a count chosen from a pixel's own samples would bias its mean.
//!
//! Samples are handed out in groups of [`GROUP`] passes: a tile of count m takes m samples
//! (at least one, at most [`GROUP`] x [`MAX_RATE`]) in each group, spread evenly over the
//! group's passes, each weighted [`GROUP`] / m, so that every complete group adds to each
//! pixel an unbiased estimate with the weight of [`GROUP`] samples. A tile's samples keep
//! consecutive indices of its pixels' sample sequences (the group's first is g m), so
//! its Sobol points stay a prefix of one sequence. A map of counts all equal to [`GROUP`]
//! is the uniform render, sample for sample.

use std::ops::Range;

pub(crate) mod error;

/// The pilot's two seeds (each combined with the render's), apart from the render's and
/// from the splits pilot's.
pub(crate) const PILOT_SEEDS: [u64; 2] = [0xada7_5a3b_1e00_0001, 0xada7_5a3b_1e00_0002];

/// Passes per group: a tile's rate can be as low as one sample in a group.
pub(crate) const GROUP: u64 = 4;

/// The most samples a tile takes per pass, on average over a group.
const MAX_RATE: u32 = 8;

/// Pixels per side of the tiles of one rate, unless path reuse's tiles are larger (a
/// reuse tile must lie in one rate's tile).
const TILE: u32 = 4;

/// The side of the box (pixels) that averages the pilot's one-sample error estimates.
/// Measured on the specular, glossy, caustic, medium and Cornell boxes and the textured
/// sky (against per-pixel errors from many seeds): boxes of 9 gained at least as much as
/// boxes of 3 and 5. A pilot of a quarter of the pixels (every other one, or every other
/// tile of reuse) gained nearly as much there, but was less efficient than the full pilot
/// on the Cornell and bunny boxes (tiles of reuse 8 pixels apart; docs/trade-offs.md,
/// "Tried and not kept").
const SMOOTHING: u32 = 9;

/// The fewest samples per pixel at which a render samples adaptively: the pilot costs two
/// samples per pixel.
pub(crate) const MIN_SAMPLES: u64 = 16;

/// Per tile, how many samples it takes in each group of [`GROUP`] passes.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SampleMap {
    side: u32,
    columns: u32,
    counts: Vec<u32>,
}

impl SampleMap {
    /// The side of a rate's tiles where path reuse shares vertices in tiles of `reuse`.
    pub(crate) fn tile_side(reuse: u32) -> u32 {
        let reuse = reuse.max(1);
        if reuse >= TILE {
            reuse
        } else {
            reuse * (TILE / reuse)
        }
    }

    /// The map for a `width` x `height` image whose pixels' weighted one-sample error
    /// estimates are `errors` and whose samples cost `costs` (rays; both row-major), in
    /// tiles of `side`: None where the errors say nothing (all zero or not finite), which
    /// leaves the render uniform.
    pub(crate) fn from_errors(
        width: u32,
        height: u32,
        side: u32,
        errors: &[f64],
        costs: &[f64],
    ) -> Option<Self> {
        let (w, h) = (width as usize, height as usize);
        if errors.len() != w * h || costs.len() != w * h || side == 0 {
            return None;
        }
        let clean = |values: &[f64]| -> Vec<f64> {
            values
                .iter()
                .map(|&e| if e.is_finite() && e > 0.0 { e } else { 0.0 })
                .collect()
        };
        let errors = box_mean(&clean(errors), w, h, SMOOTHING as usize);
        let costs = box_mean(&clean(costs), w, h, SMOOTHING as usize);
        let columns = width.div_ceil(side);
        let rows = height.div_ceil(side);
        let mut tiles = vec![(0.0f64, 0.0f64, 0u32); (columns * rows) as usize];
        for y in 0..height {
            for x in 0..width {
                let t = &mut tiles[((y / side) * columns + x / side) as usize];
                let i = (y * width + x) as usize;
                t.0 += errors[i];
                t.1 += costs[i];
                t.2 += 1;
            }
        }
        // The optimal rate of a tile: the square root of its error per unit of cost (a
        // tile that traces nothing costs one ray a sample).
        let rates: Vec<(f64, f64)> = tiles
            .iter()
            .map(|&(error, cost, n)| ((error / cost.max(f64::from(n))).sqrt(), f64::from(n)))
            .collect();
        let pixels = f64::from(width) * f64::from(height);
        let mean_rate = rates.iter().map(|(r, n)| r * n).sum::<f64>() / pixels;
        if !(mean_rate.is_finite() && mean_rate > 0.0) {
            return None;
        }
        // Counts per group: the rate scaled by lambda, rounded, clamped; lambda found by
        // bisection so that the image takes GROUP samples per pixel per group, as the
        // uniform render does (the total is monotone in lambda).
        let budget = GROUP as f64 * pixels;
        let max = GROUP as u32 * MAX_RATE;
        let counts_at = |lambda: f64| -> Vec<u32> {
            rates
                .iter()
                .map(|&(r, _)| ((lambda * r / mean_rate).round().clamp(1.0, f64::from(max))) as u32)
                .collect()
        };
        let total = |counts: &[u32]| -> f64 {
            counts
                .iter()
                .zip(&rates)
                .map(|(&c, &(_, n))| f64::from(c) * n)
                .sum()
        };
        let (mut lo, mut hi) = (0.0, GROUP as f64 * f64::from(max));
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if total(&counts_at(mid)) <= budget {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(Self {
            side,
            columns,
            counts: counts_at(lo),
        })
    }

    /// The same count for every tile: the uniform render.
    #[cfg(test)]
    pub(crate) fn uniform(width: u32, height: u32, side: u32) -> Self {
        let columns = width.div_ceil(side);
        Self {
            side,
            columns,
            counts: vec![GROUP as u32; (columns * height.div_ceil(side)) as usize],
        }
    }

    /// The samples pixel (`x`, `y`) takes in pass `s`, and the weight of each.
    pub(crate) fn samples(&self, x: u32, y: u32, s: u64) -> (Range<u64>, f64) {
        let tile = ((y / self.side) * self.columns + x / self.side) as usize;
        let m = u64::from(self.counts.get(tile).copied().unwrap_or(GROUP as u32));
        let (group, pass) = (s / GROUP, s % GROUP);
        let first = group * m;
        (
            first + pass * m / GROUP..first + (pass + 1) * m / GROUP,
            GROUP as f64 / m as f64,
        )
    }

    /// Per tile, samples per group (row-major over tiles).
    #[cfg(test)]
    pub(crate) fn counts(&self) -> &[u32] {
        &self.counts
    }
}

/// The samples of pixel (`x`, `y`) in pass `s` under `map`, and each one's weight: the
/// pass's own sample, weight 1, without one.
#[inline]
pub(crate) fn samples_of(map: Option<&SampleMap>, x: u32, y: u32, s: u64) -> (Range<u64>, f64) {
    match map {
        Some(map) => map.samples(x, y, s),
        None => (s..s + 1, 1.0),
    }
}

/// `values` (`width` x `height`, row-major) averaged over the box the pilot's errors are
/// averaged over.
pub(crate) fn smoothed(values: &[f64], width: u32, height: u32) -> Vec<f64> {
    box_mean(values, width as usize, height as usize, SMOOTHING as usize)
}

/// The mean of `values` (`w` x `h`, row-major) over a `side` x `side` box around each
/// pixel, the box cut at the image's edges.
fn box_mean(values: &[f64], w: usize, h: usize, side: usize) -> Vec<f64> {
    let r = side / 2;
    let pass = |input: &[f64], stride: usize, len: usize, lines: usize, step: usize| {
        let mut out = vec![0.0; input.len()];
        for line in 0..lines {
            let at = |i: usize| line * step + i * stride;
            for i in 0..len {
                let (a, b) = (i.saturating_sub(r), (i + r).min(len - 1));
                let sum: f64 = (a..=b).map(|j| input[at(j)]).sum();
                out[at(i)] = sum / (b - a + 1) as f64;
            }
        }
        out
    };
    let rows = pass(values, 1, w, h, w);
    pass(&rows, w, h, w, 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_uniform_map_is_the_pass_by_pass_render() {
        let map = SampleMap::uniform(10, 7, 4);
        for s in 0..20 {
            assert_eq!(map.samples(9, 6, s), (s..s + 1, 1.0));
        }
    }

    #[test]
    fn every_group_gives_each_tile_its_count_in_consecutive_samples() {
        let map = SampleMap {
            side: 4,
            columns: 2,
            counts: vec![1, 4, 7, 32],
        };
        for (tile, &m) in map.counts().iter().enumerate() {
            let (x, y) = ((tile as u32 % 2) * 4, (tile as u32 / 2) * 4);
            let mut next = 0;
            for s in 0..3 * GROUP {
                let (range, weight) = map.samples(x, y, s);
                assert_eq!(range.start, next, "tile {tile} pass {s}");
                next = range.end;
                assert_eq!(weight, GROUP as f64 / f64::from(m));
                if s % GROUP == GROUP - 1 {
                    // A complete group: m samples of weight GROUP / m, GROUP in all.
                    assert_eq!(next, (s / GROUP + 1) * u64::from(m));
                }
            }
        }
    }

    #[test]
    fn samples_go_where_the_error_is_and_the_budget_holds() {
        let (w, h) = (64u32, 48u32);
        // A hot square of 16 x 16 pixels with 100 times the error of the rest.
        let errors: Vec<f64> = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                if (20..36).contains(&x) && (8..24).contains(&y) {
                    100.0
                } else {
                    1.0
                }
            })
            .collect();
        let map = SampleMap::from_errors(w, h, 4, &errors, &vec![5.0; errors.len()]).unwrap();
        let pixels: u64 = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                (0..GROUP)
                    .map(|s| map.samples(x, y, s).0.count() as u64)
                    .sum::<u64>()
            })
            .sum();
        let budget = GROUP * u64::from(w * h);
        assert!(
            pixels <= budget && pixels as f64 >= 0.97 * budget as f64,
            "{pixels} of {budget}"
        );
        let hot = map.samples(28, 16, 0).1;
        let cold = map.samples(2, 40, 0).1;
        // Weights are GROUP / m: the hot tile takes about sqrt(100) = 10 times the samples.
        assert!(cold / hot > 6.0 && cold / hot < 14.0, "{cold} / {hot}");
    }

    #[test]
    fn errors_that_say_nothing_leave_the_render_uniform() {
        assert!(SampleMap::from_errors(8, 8, 4, &[0.0; 64], &[1.0; 64]).is_none());
        assert!(SampleMap::from_errors(8, 8, 4, &[f64::NAN; 64], &[1.0; 64]).is_none());
        assert!(SampleMap::from_errors(8, 8, 4, &[1.0; 63], &[1.0; 63]).is_none());
        // Equal errors everywhere: every tile takes the uniform count.
        let map = SampleMap::from_errors(8, 8, 4, &[3.0; 64], &[7.0; 64]).unwrap();
        assert!(map.counts().iter().all(|&c| c == GROUP as u32));
    }

    #[test]
    fn the_box_mean_keeps_a_constant_and_spreads_a_spike() {
        let (w, h) = (20usize, 20usize);
        assert!(
            box_mean(&[3.0; 400], w, h, 9)
                .iter()
                .all(|&v| (v - 3.0).abs() < 1e-12)
        );
        let mut spike = vec![0.0; w * h];
        spike[10 * w + 10] = 81.0;
        let mean = box_mean(&spike, w, h, 9);
        // A box of 9 x 9 inside the image spreads it evenly over its 81 pixels.
        for (x, y, expected) in [(10, 10, 1.0), (6, 6, 1.0), (14, 13, 1.0), (5, 10, 0.0)] {
            assert!((mean[y * w + x] - expected).abs() < 1e-12, "({x}, {y})");
        }
    }

    #[test]
    fn tiles_hold_whole_reuse_tiles() {
        for reuse in 1..=8 {
            let side = SampleMap::tile_side(reuse);
            assert_eq!(side % reuse, 0, "reuse {reuse}: side {side}");
            assert!(
                side >= reuse && side <= TILE.max(reuse),
                "reuse {reuse}: side {side}"
            );
        }
    }
}
