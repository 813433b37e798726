//! Precomputed coefficient tables in the layout of Jakob and Hanika (2019, §5): for each
//! choice of largest channel, a grid over that channel's value (the brightness axis,
//! remapped by smoothstep(smoothstep(t)) so that dark colours get more nodes) and the two
//! other channels divided by it.
//!
//! One departure, measured: the ratio axes are smoothstep-remapped too (node i at ratio
//! smoothstep(i / (r - 1)); lookups invert it in closed form) instead of uniform. The
//! coefficients diverge as a ratio goes to 0 (a saturated colour needs a steep sigmoid)
//! and, for bright colours, as it goes to 1 (a spectrum close to 1 everywhere): the ends
//! of the ratio axes are where rgb2spec's uniform axes make their largest errors.

#[cfg(feature = "parallel")]
use rayon::prelude::*;

use crate::fit::{FitContext, normalize};
use crate::lanes::F32x4;
use crate::model::SigmoidPolynomial;

/// Lab tolerance of table nodes: at 64^3 fifty times below the largest interpolation
/// error and ten times below the mean (looser tolerances save iterations, not accuracy).
const TABLE_TOLERANCE: f64 = 1e-3;

/// A fitted table for one colour space.
#[derive(Debug, Clone, PartialEq)]
pub struct CoefficientTable {
    /// The axis inverses, held by reference so that lookups skip the lazy-init check.
    pub(crate) axes: &'static AxisInverses,
    /// The space the table was fitted for (name, primaries, white).
    pub(crate) space: TableSpace,
    pub(crate) resolution: usize,
    /// Brightness nodes, increasing from 0 to 1.
    pub(crate) z_nodes: Vec<f32>,
    /// Coefficients for l in nm premultiplied by sqrt(z), indexed [largest channel][z][y]
    /// [x], each padded to four lanes (the fourth is 0) so that interpolation runs on
    /// whole 16-byte nodes. In nm rather than in the fitter's normalized t, because the
    /// conversion is linear and so commutes with interpolation: done once per node here,
    /// it is not on every lookup's critical path (measured: a faster lookup).
    pub(crate) nodes: Vec<[f32; 4]>,
}

/// The colour space a table belongs to, as stored in its file.
#[derive(Debug, Clone, PartialEq)]
pub struct TableSpace {
    /// The space's name.
    pub name: String,
    /// Red, green, blue primaries (x, y).
    pub primaries: [[f64; 2]; 3],
    /// The white the table was fitted for (the illuminant's chromaticity).
    pub white: [f64; 2],
}

impl TableSpace {
    pub(crate) fn of(context: &FitContext) -> Self {
        let space = context.space();
        Self {
            name: space.name().to_string(),
            primaries: space.primaries().map(|p| [p.x, p.y]),
            white: [space.white().xy().x, space.white().xy().y],
        }
    }

    /// Whether `context` fits for this space (same primaries and white to 1e-9).
    pub fn matches(&self, context: &FitContext) -> bool {
        let other = Self::of(context);
        let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
        self.primaries
            .iter()
            .flatten()
            .zip(other.primaries.iter().flatten())
            .all(|(a, b)| close(*a, *b))
            && close(self.white[0], other.white[0])
            && close(self.white[1], other.white[1])
    }
}

/// The ratio at node `i` of a ratio axis (see the module documentation).
fn ratio_node(i: usize, scale: f64) -> f64 {
    smoothstep(i as f64 / scale)
}

/// The inverse of smoothstep on [0, 1]: u = 1/2 - sin(asin(1 - 2r) / 3).
fn inverse_smoothstep(r: f64) -> f64 {
    (0.5 - ((1.0 - 2.0 * r.clamp(0.0, 1.0)).asin() / 3.0).sin()).clamp(0.0, 1.0)
}

/// Octaves of the tabulated axis inverses: a in [2^-40, 1/2]. Below, u is taken as 0: at
/// most 4e-4 for the brightness axis, inside the first cell at every resolution (node 1 is
/// above 6e-9 up to 256), and 6e-7 for the ratio axes.
const AXIS_OCTAVES: u32 = 40;
/// Mantissa bits indexing the segments of one octave (64 segments).
const AXIS_SEGMENT_BITS: u32 = 6;
/// Table entries: every segment's start, and 1/2's end.
const AXIS_ENTRIES: usize = ((AXIS_OCTAVES << AXIS_SEGMENT_BITS) + 1) as usize;
/// The f32 exponent field of 2^-40, the first octave.
const AXIS_FIRST_EXPONENT: u32 = 127 - AXIS_OCTAVES;

/// An axis inverse a -> u that is symmetric (u(1 - a) = 1 - u(a)) and behaves like a
/// power (a / k)^p near 0, tabulated for a in [0, 1/2] on the grid of an f32's exponent
/// and leading mantissa bits: 64 linear segments per octave. For a power the relative
/// error of linear interpolation over a segment is p (1 - p) / 8 / 64^2 (6e-6 for
/// p = 1/4, 8e-6 for 1/2), and the index is the float's bits shifted: no root, no
/// search, no trigonometry on the lookup's critical path.
#[derive(PartialEq)]
pub(crate) struct AxisInverse {
    /// u at the start of each segment (u(0) = 0 for the first), then 1 - u at the same
    /// points: the upper half of the axis, read through the symmetry.
    values: [f32; 2 * AXIS_ENTRIES],
}

impl AxisInverse {
    fn new(exact: impl Fn(f64) -> f64) -> Self {
        let mut values = [0f32; 2 * AXIS_ENTRIES];
        for i in 0..AXIS_ENTRIES {
            let octave = (i >> AXIS_SEGMENT_BITS) as i32 - AXIS_OCTAVES as i32;
            let segment = (i & ((1 << AXIS_SEGMENT_BITS) - 1)) as f64;
            let a = 2f64.powi(octave) * (1.0 + segment / f64::from(1u32 << AXIS_SEGMENT_BITS));
            let u = if i == 0 { 0.0 } else { exact(a) };
            values[i] = u as f32;
            values[AXIS_ENTRIES + i] = (1.0 - u) as f32;
        }
        Self { values }
    }

    /// u for a in [0, 1/2] (NaN counts as 0), or 1 - u when `upper`.
    #[inline(always)]
    fn eval_half(&self, a: f32, upper: bool) -> f32 {
        const SEGMENT_SHIFT: u32 = 23 - AXIS_SEGMENT_BITS;
        let bits = a.max(f32::from_bits(AXIS_FIRST_EXPONENT << 23)).to_bits();
        let i = ((bits >> SEGMENT_SHIFT).wrapping_sub(AXIS_FIRST_EXPONENT << AXIS_SEGMENT_BITS)
            as usize)
            .min(AXIS_ENTRIES - 2)
            + usize::from(upper) * AXIS_ENTRIES;
        // The remaining mantissa bits are the position within the segment: placed in the
        // mantissa of 1.0 they make 1 + t.
        let fraction = (bits & ((1 << SEGMENT_SHIFT) - 1)) << AXIS_SEGMENT_BITS;
        let t = f32::from_bits(0x3f80_0000 | fraction) - 1.0;
        let (low, high) = (self.values[i], self.values[i + 1]);
        low + t * (high - low)
    }

    /// u for a in [0, 1], by the symmetry u(1 - a) = 1 - u(a) and the table.
    #[inline(always)]
    fn eval(&self, a: f32) -> f32 {
        // The half is chosen by an index offset before the load rather than by a select
        // after it, which shortens the chain (measured: a faster lookup).
        self.eval_half(a.min(1.0 - a), a > 0.5)
    }

    /// The cells (node index and fraction, as [`cell`] gives them) of four values of a
    /// in SSE2 lanes (in [0, 1], not NaN), for `resolution` - 1 = `scale`: the operations
    /// of [`AxisInverse::eval`] and [`cell`] on the same values, so the same bits (tested).
    /// Batch lookups use it (`table_batch`); a lone lookup keeps one scalar chain per
    /// axis, which is shorter (measured: three axes of one colour in lanes made a lookup
    /// slower).
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    #[allow(unsafe_code, reason = "SSE2 intrinsics, in the x86_64 baseline")]
    pub(crate) fn cells_lanes(
        &self,
        a: std::arch::x86_64::__m128,
        last: usize,
        scale: f32,
    ) -> ([usize; 4], [f32; 4]) {
        use std::arch::x86_64::*;
        const SEGMENT_SHIFT: i32 = 23 - AXIS_SEGMENT_BITS as i32;
        // SAFETY: SSE and SSE2 are part of the x86_64 baseline (always enabled); the
        // intrinsics compute on registers, and the stores write the 16 bytes of local
        // four-lane arrays. The table is read by checked indexing.
        unsafe {
            let one = _mm_set1_ps(1.0);
            // minps and maxps are exactly f32::min and max for inputs that are not NaN.
            let upper = _mm_castps_si128(_mm_cmpgt_ps(a, _mm_set1_ps(0.5)));
            let first = f32::from_bits(AXIS_FIRST_EXPONENT << 23);
            let bits = _mm_castps_si128(_mm_max_ps(
                _mm_min_ps(a, _mm_sub_ps(one, a)),
                _mm_set1_ps(first),
            ));
            let segment = _mm_sub_epi32(
                _mm_srli_epi32::<SEGMENT_SHIFT>(bits),
                _mm_set1_epi32((AXIS_FIRST_EXPONENT << AXIS_SEGMENT_BITS) as i32),
            );
            let i = _mm_add_epi32(
                segment,
                _mm_and_si128(upper, _mm_set1_epi32(AXIS_ENTRIES as i32)),
            );
            let position = _mm_slli_epi32::<{ AXIS_SEGMENT_BITS as i32 }>(_mm_and_si128(
                bits,
                _mm_set1_epi32((1 << SEGMENT_SHIFT) - 1),
            ));
            let t = _mm_sub_ps(
                _mm_castsi128_ps(_mm_or_si128(position, _mm_set1_epi32(0x3f80_0000))),
                one,
            );
            let mut segments = [0i32; 4];
            _mm_storeu_si128(segments.as_mut_ptr().cast(), i);
            // In range for inputs that are not NaN; the bound spares the bounds checks.
            let at = segments.map(|i| (i as u32 as usize).min(2 * AXIS_ENTRIES - 2));
            let v = &self.values;
            let low = _mm_setr_ps(v[at[0]], v[at[1]], v[at[2]], v[at[3]]);
            let high = _mm_setr_ps(v[at[0] + 1], v[at[1] + 1], v[at[2] + 1], v[at[3] + 1]);
            let u = _mm_add_ps(low, _mm_mul_ps(t, _mm_sub_ps(high, low)));
            let x = _mm_mul_ps(u, _mm_set1_ps(scale));
            // `cell` in lanes. The bound is taken on the float, not the integer (SSE2 has
            // no integer minimum): the same, as both are integers in the rounding's format.
            let rounding = _mm_set1_ps(ROUNDING);
            let rounded = _mm_min_ps(
                _mm_add_ps(_mm_sub_ps(x, _mm_set1_ps(0.5)), rounding),
                _mm_set1_ps(last as u32 as f32 + ROUNDING),
            );
            let index = _mm_and_si128(_mm_castps_si128(rounded), _mm_set1_epi32(0x003f_ffff));
            let fraction = _mm_sub_ps(x, _mm_sub_ps(rounded, rounding));
            let mut out_index = [0i32; 4];
            let mut out_fraction = [0f32; 4];
            _mm_storeu_si128(out_index.as_mut_ptr().cast(), index);
            _mm_storeu_ps(out_fraction.as_mut_ptr(), fraction);
            (out_index.map(|i| i as u32 as usize), out_fraction)
        }
    }
}

/// 1.5 * 2^23: adding it rounds a float in [0, 2^22) to an integer in the mantissa.
const ROUNDING: f32 = 12_582_912.0;

/// The cell of x in [0, `last` + 1] (finite): node i <= `last` and fraction t = x - i in
/// [0, 1]. Adding 1.5 * 2^23 rounds x - 1/2 to an integer held in the low mantissa bits,
/// a few instructions off the critical path where a saturating float-to-usize conversion
/// takes a dozen on it (measured: those conversions were a tenth of a lookup).
#[inline(always)]
fn cell(x: f32, last: usize, last_f32: f32) -> (usize, f32) {
    let rounded = (x - 0.5) + ROUNDING;
    let i = ((rounded.to_bits() & 0x003f_ffff) as usize).min(last);
    (i, x - (rounded - ROUNDING).min(last_f32))
}

/// The inverses of the table's axis remaps.
#[derive(PartialEq)]
pub(crate) struct AxisInverses {
    /// The ratio axes': smoothstep^-1 (like sqrt(a / 3) near 0).
    pub(crate) ratio: AxisInverse,
    /// The brightness axis': (smoothstep o smoothstep)^-1 (like (a / 27)^(1/4) near 0).
    pub(crate) brightness: AxisInverse,
}

impl std::fmt::Debug for AxisInverses {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("AxisInverses")
    }
}

static AXIS_INVERSES: std::sync::LazyLock<AxisInverses> =
    std::sync::LazyLock::new(|| AxisInverses {
        ratio: AxisInverse::new(inverse_smoothstep),
        brightness: AxisInverse::new(|z| inverse_smoothstep(inverse_smoothstep(z))),
    });

/// The process-wide axis inverses (built on first use).
pub(crate) fn axis_inverses() -> &'static AxisInverses {
    &AXIS_INVERSES
}

/// The smoothstep remap of the brightness axis.
fn smoothstep(x: f64) -> f64 {
    x * x * (3.0 - 2.0 * x)
}

/// What a lookup gives for black: the limit of the sigmoid towards zero.
pub(crate) const BLACK: SigmoidPolynomial = SigmoidPolynomial {
    coefficients: [0.0, 0.0, f64::NEG_INFINITY],
};

/// Statistics of a table fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitStatistics {
    /// Nodes fitted.
    pub nodes: usize,
    /// Largest Lab residual of any node (unreachable colours show up here).
    pub max_residual: f64,
    /// Nodes whose residual exceeds 1e-3 Lab (not reachable by a reflectance).
    pub unreachable: usize,
    /// Total Levenberg-Marquardt iterations.
    pub iterations: u64,
}

impl CoefficientTable {
    /// Resolutions accepted by [`CoefficientTable::fit`]: 2 to 256 nodes per axis.
    pub const RESOLUTIONS: std::ops::RangeInclusive<usize> = 2..=256;

    /// Fits a table of `resolution`^3 nodes per largest channel in parallel. Each worker
    /// fits one (channel, y) row; along it, every column over brightness starts at the
    /// middle node from the previous column's solution and walks up and down, each node
    /// warm-started from its neighbour, so most nodes converge in two or three steps.
    /// `progress` is called with the number of rows finished (of 3 `resolution`).
    pub fn fit(
        context: &FitContext,
        resolution: usize,
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<(Self, FitStatistics), crate::UpsampleError> {
        if !Self::RESOLUTIONS.contains(&resolution) {
            return Err(crate::UpsampleError::InvalidTable(format!(
                "resolution {resolution} is outside {:?}",
                Self::RESOLUTIONS
            )));
        }
        let res = resolution;
        let scale = (res - 1) as f64;
        let z_nodes: Vec<f64> = (0..res)
            .map(|i| smoothstep(smoothstep(i as f64 / scale)))
            .collect();
        let done = std::sync::atomic::AtomicUsize::new(0);
        let rows = 0..3 * res;
        // One row per task on rayon's pool; without the `parallel` feature, in order.
        #[cfg(feature = "parallel")]
        let rows = rows.into_par_iter();
        let rows: Vec<(Vec<f32>, FitStatistics)> = rows
            .map(|row| {
                let (channel, yi) = (row / res, row % res);
                let mut out = vec![0f32; res * res * 3];
                let mut stats = FitStatistics {
                    nodes: 0,
                    max_residual: 0.0,
                    unreachable: 0,
                    iterations: 0,
                };
                let mut column_start = [0.0; 3];
                let middle = res / 5;
                for xi in 0..res {
                    let (x, y) = (ratio_node(xi, scale), ratio_node(yi, scale));
                    let mut fit_node = |zi: usize, start: [f64; 3]| {
                        let z = z_nodes[zi];
                        let mut rgb = [0.0; 3];
                        rgb[channel] = z;
                        rgb[(channel + 1) % 3] = x * z;
                        rgb[(channel + 2) % 3] = y * z;
                        let fit = context.fit_table_node(rgb, start, TABLE_TOLERANCE);
                        stats.nodes += 1;
                        stats.iterations += u64::from(fit.iterations);
                        stats.max_residual = stats.max_residual.max(fit.residual);
                        stats.unreachable += usize::from(fit.residual > 1e-3);
                        // Stored in nm, premultiplied by sqrt(z) (see `lookup`).
                        let at = (zi * res + xi) * 3;
                        let stored = fit.spectrum.coefficients.map(|c| (c * z.sqrt()) as f32);
                        out[at..at + 3].copy_from_slice(&stored);
                        fit.normalized
                    };
                    // Along the column each start extrapolates linearly from the two previous
                    // solutions: the coefficients vary smoothly with the axis parameter.
                    let extrapolate =
                        |a: [f64; 3], b: [f64; 3]| std::array::from_fn(|k| 2.0 * b[k] - a[k]);
                    let first = fit_node(middle, column_start);
                    column_start = first;
                    let (mut previous, mut current) = (first, first);
                    for zi in middle + 1..res {
                        let next = fit_node(zi, extrapolate(previous, current));
                        (previous, current) = (current, next);
                    }
                    (previous, current) = (first, first);
                    // Down to z node 1; node 0 is black, which no sigmoid reaches: it keeps
                    // node 1's premultiplied values (lookups of black are exact zeros before
                    // the table; colours below node 1 darken as z^(-1/2) scales them).
                    for zi in (1..middle).rev() {
                        let next = fit_node(zi, extrapolate(previous, current));
                        (previous, current) = (current, next);
                    }
                    let (from, to) = ((res + xi) * 3, xi * 3);
                    let copied: [f32; 3] = [out[from], out[from + 1], out[from + 2]];
                    out[to..to + 3].copy_from_slice(&copied);
                }
                progress(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
                (out, stats)
            })
            .collect();
        // Rows come back in order: row = channel * res + y, each [z][x][3]; reorder to
        // [channel][z][y][x].
        let mut nodes = vec![[0f32; 4]; 3 * res * res * res];
        let mut total = FitStatistics {
            nodes: 0,
            max_residual: 0.0,
            unreachable: 0,
            iterations: 0,
        };
        for (row, (values, stats)) in rows.into_iter().enumerate() {
            let (channel, yi) = (row / res, row % res);
            for zi in 0..res {
                for xi in 0..res {
                    let src = (zi * res + xi) * 3;
                    let dst = ((channel * res + zi) * res + yi) * res + xi;
                    nodes[dst][..3].copy_from_slice(&values[src..src + 3]);
                }
            }
            total.nodes += stats.nodes;
            total.iterations += stats.iterations;
            total.unreachable += stats.unreachable;
            total.max_residual = total.max_residual.max(stats.max_residual);
        }
        Ok((
            Self {
                axes: axis_inverses(),
                space: TableSpace::of(context),
                resolution: res,
                z_nodes: z_nodes.iter().map(|&z| z as f32).collect(),
                nodes,
            },
            total,
        ))
    }

    /// The resolution.
    pub fn resolution(&self) -> usize {
        self.resolution
    }

    /// The colour space the table was fitted for.
    pub fn space(&self) -> &TableSpace {
        &self.space
    }

    /// The interpolated spectrum for `rgb` (components in [0, 1], not all zero; others are
    /// clamped). Black has no sigmoid: callers handle it first (here it is the limit, a
    /// sigmoid at -inf).
    pub fn lookup(&self, rgb: [f64; 3]) -> SigmoidPolynomial {
        // The hot path runs in f32 (the table is f32; interpolation weights need no more)
        // and is a chain of dependent steps (channel, ratios, axis inverses, cells, loads,
        // weights): each step is written for latency. f64::max and min return the other
        // operand for NaN, so NaN components count as 0.
        #[allow(clippy::manual_clamp, reason = "clamp keeps NaN; this maps it to 0")]
        let [r, g, b] = rgb.map(|c| c.max(0.0).min(1.0) as f32);
        // The largest channel and the two others in cyclic order after it. Branches, not
        // selects: a predicted branch lets the core start on the rest before the
        // comparison resolves (measured: a branch-free choice was slower).
        let (channel, z, first, second) = if r >= g && r >= b {
            (0, r, g, b)
        } else if g >= b {
            (1, g, b, r)
        } else {
            (2, b, r, g)
        };
        if z == 0.0 {
            return BLACK;
        }
        let res = self.resolution;
        let last = res - 2;
        // Through u32: a usize-to-f32 conversion takes a branch.
        let (scale, last_f32) = ((res - 1) as u32 as f32, last as u32 as f32);
        let x = self.axes.ratio.eval(first / z) * scale;
        let y = self.axes.ratio.eval(second / z) * scale;
        // Interpolate in the axis parameter u (z = smoothstep(smoothstep(u))), in which the
        // nodes are uniform, rather than in z: the coefficients vary much more evenly in u
        // (dark colours especially), and no search is needed.
        let u = self.axes.brightness.eval(z) * scale;
        let ((xi, tx), (yi, ty), (zi, tz)) = (
            cell(x, last, last_f32),
            cell(y, last, last_f32),
            cell(u, last, last_f32),
        );
        // The table holds coefficients premultiplied by sqrt(z): a dark colour's sigmoid
        // tail is ~1 / (4 x^2), so its coefficients grow like z^(-1/2) and the product is
        // nearly constant in z, which linear interpolation follows (it halved the largest
        // error of dark saturated colours). Below the first node the premultiplied values
        // stay constant, so colours keep darkening towards black.
        let unmultiply = 1.0 / z.sqrt();
        self.interpolate(channel, [(xi, tx), (yi, ty), (zi, tz)], unmultiply)
    }

    /// The coefficients at the cells (node index and fraction along x, y and z) in the
    /// slab of largest channel `channel`, times `unmultiply` (1 / sqrt(z), see `lookup`),
    /// which is folded into the y-z weights, off the chain that waits for the loads.
    #[inline(always)]
    pub(crate) fn interpolate(
        &self,
        channel: usize,
        cells: [(usize, f32); 3],
        unmultiply: f32,
    ) -> SigmoidPolynomial {
        let [(xi, tx), (yi, ty), (zi, tz)] = cells;
        let res = self.resolution;
        let (sy, sz) = (res, res * res);
        let base = channel * sz * res + zi * sz + yi * sy + xi;
        let corners = &self.nodes[base..=base + sz + sy + 1];
        // Lerps along x (whole nodes as SIMD lanes), then one weighted sum over y and z:
        // a shorter dependency chain after the loads than nested lerps.
        let tx = F32x4::splat(tx);
        let along_x = |at: usize| {
            let low = F32x4::load(&corners[at]);
            low.add(F32x4::load(&corners[at + 1]).sub(low).mul(tx))
        };
        let (low, high) = ((1.0 - tz) * unmultiply, tz * unmultiply);
        let w = [low * (1.0 - ty), low * ty, high * (1.0 - ty), high * ty].map(F32x4::splat);
        let near = along_x(0).mul(w[0]).add(along_x(sy).mul(w[1]));
        let far = along_x(sz).mul(w[2]).add(along_x(sz + sy).mul(w[3]));
        let c = near.add(far).to_array();
        SigmoidPolynomial {
            coefficients: [c[0], c[1], c[2]].map(f64::from),
        }
    }

    /// [`CoefficientTable::lookup`]'s coefficients in the fitter's normalized wavelength
    /// t = (l - 360) / 470: the start of a refined lookup.
    pub fn lookup_normalized(&self, rgb: [f64; 3]) -> [f64; 3] {
        normalize(self.lookup(rgb).coefficients)
    }

    /// The refined lookup: the interpolated coefficients improved by `steps`
    /// Levenberg-Marquardt steps of the exact fit (accuracy over speed).
    pub fn lookup_refined(
        &self,
        context: &FitContext,
        rgb: [f64; 3],
        steps: u32,
    ) -> SigmoidPolynomial {
        context
            .fit_with_budget(rgb, self.lookup_normalized(rgb), steps)
            .spectrum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn exact_ratio(a: f32) -> f64 {
        inverse_smoothstep(f64::from(a))
    }

    fn exact_brightness(a: f32) -> f64 {
        inverse_smoothstep(inverse_smoothstep(f64::from(a)))
    }

    /// The tabulated inverses agree with the exact ones to 1e-5 in the axis parameter
    /// everywhere, ends included. The lookup runs in f32, so the exact value is taken at
    /// the f32-rounded input (near a = 1 that rounding alone moves u by ~2e-5).
    #[test]
    fn tabulated_axis_inverses_are_accurate() {
        for i in 0..=100_000 {
            let a = (i as f64 / 100_000.0) as f32;
            let ratio = f64::from(axis_inverses().ratio.eval(a));
            assert!(
                (ratio - exact_ratio(a)).abs() < 1e-5,
                "ratio {a}: {ratio} vs {}",
                exact_ratio(a)
            );
            let z = f64::from(axis_inverses().brightness.eval(a));
            assert!(
                (z - exact_brightness(a)).abs() < 1e-5,
                "brightness {a}: {z} vs {}",
                exact_brightness(a)
            );
        }
    }

    /// Down to the table's second segment (2^-40 (1 + 1/64)) the error is within 2e-5 of
    /// u relative, on both sides of 1/2 and at segment ends and middles; the ends are exact.
    #[test]
    fn tabulated_axis_inverses_hold_over_forty_octaves() {
        let first = f32::from_bits(AXIS_FIRST_EXPONENT << 23);
        let mut a = first * (1.0 + 1.0 / 64.0);
        while a < 0.5 {
            for probe in [a, a * (1.0 + 1.0 / 128.0)] {
                for (name, table, exact) in [
                    (
                        "ratio",
                        &axis_inverses().ratio,
                        exact_ratio as fn(f32) -> f64,
                    ),
                    ("brightness", &axis_inverses().brightness, exact_brightness),
                ] {
                    let u = f64::from(table.eval(probe));
                    let want = exact(probe);
                    assert!(
                        (u - want).abs() <= 2e-5 * want + 1e-7,
                        "{name} {probe:e}: {u} vs {want}"
                    );
                    let mirrored = f64::from(table.eval(1.0 - probe));
                    let want = exact(1.0 - probe);
                    assert!((mirrored - want).abs() < 1e-5, "{name} 1 - {probe:e}");
                }
            }
            a *= 1.0 + 1.0 / 64.0;
        }
        for table in [&axis_inverses().ratio, &axis_inverses().brightness] {
            assert_eq!(table.eval(0.0), 0.0);
            assert_eq!(table.eval(1.0), 1.0);
            assert_eq!(table.eval(f32::from_bits(1)), 0.0, "subnormal");
            assert!((table.eval(0.5) - 0.5).abs() < 1e-6);
            assert!(table.eval(first / 2.0) <= table.eval(first * 2.0));
        }
    }

    /// The SIMD lanes give the scalar path's bits for every input: on a grid of values
    /// with the extremes (0, subnormals, 2^-40, the fold at 1/2, 1), on both axes, at
    /// every resolution, in every lane.
    #[cfg(target_arch = "x86_64")]
    #[test]
    #[allow(unsafe_code, reason = "an SSE load of a local array")]
    fn simd_cells_are_the_scalar_cells() {
        let first = f32::from_bits(AXIS_FIRST_EXPONENT << 23);
        let special = [
            0.0,
            f32::from_bits(1),
            f32::MIN_POSITIVE,
            first,
            first * 0.75,
            1e-7,
            0.25,
            0.5,
            0.5f32.next_down(),
            0.5f32.next_up(),
            1.0f32.next_down(),
            1.0,
        ];
        let mut state = 0x9e37_79b9u32;
        let mut random = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            (state >> 8) as f32 / (1u32 << 24) as f32
        };
        let mut values: Vec<f32> = special.to_vec();
        values.extend((0..2000).map(|_| random()));
        values.extend((0..500).map(|_| random().powi(12)));
        values.extend((0..500).map(|_| 1.0 - random().powi(12)));
        for resolution in [2usize, 3, 17, 64, 256] {
            let (last, scale) = (resolution - 2, (resolution - 1) as f32);
            for axis in [&axis_inverses().ratio, &axis_inverses().brightness] {
                for (k, lanes) in values.chunks_exact(4).enumerate() {
                    // Rotate so that every value visits every lane.
                    let a: [f32; 4] = std::array::from_fn(|j| lanes[(j + k) % 4]);
                    // SAFETY: SSE is in the x86_64 baseline; reads the 16 bytes of `a`.
                    let packed = unsafe { std::arch::x86_64::_mm_loadu_ps(a.as_ptr()) };
                    let (index, fraction) = axis.cells_lanes(packed, last, scale);
                    for j in 0..4 {
                        let (i, t) = cell(axis.eval(a[j]) * scale, last, last as f32);
                        assert_eq!(
                            (index[j], fraction[j].to_bits()),
                            (i, t.to_bits()),
                            "{:e} at {resolution}, lane {j}",
                            a[j]
                        );
                    }
                }
            }
        }
    }
}
