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

use rayon::prelude::*;

use crate::fit::{FitContext, denormalize};
use crate::model::SigmoidPolynomial;

/// Lab tolerance of table nodes: at 64^3 fifty times below the largest interpolation
/// error and ten times below the mean (looser tolerances save iterations, not accuracy).
const TABLE_TOLERANCE: f64 = 1e-3;

/// A fitted table for one colour space.
#[derive(Debug, Clone, PartialEq)]
pub struct CoefficientTable {
    /// The space the table was fitted for (name, primaries, white).
    pub(crate) space: TableSpace,
    pub(crate) resolution: usize,
    /// Brightness nodes, increasing from 0 to 1.
    pub(crate) z_nodes: Vec<f32>,
    /// Normalized coefficients (t = (l - 360) / 470), indexed
    /// [largest channel][z][y][x][coefficient].
    pub(crate) data: Vec<f32>,
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

/// Intervals of the tabulated axis inverses.
const AXIS_TABLE_INTERVALS: usize = 256;

/// An axis inverse a -> u that is symmetric (u(1 - a) = 1 - u(a)) and behaves like
/// (a / k)^(1/p) near 0, tabulated as a smooth function of v = a^(1/p) on [0, 2^(-1/p)]
/// so that linear interpolation is accurate (to ~1e-6 in u) and costs a root and two
/// loads instead of the trigonometry of the exact inverse.
struct AxisInverse {
    power: i32,
    v_max: f64,
    /// u at v = i / intervals * v_max, in f32 for the lookup hot path.
    values_f32: [f32; AXIS_TABLE_INTERVALS + 1],
}

impl AxisInverse {
    fn new(power: i32, exact: impl Fn(f64) -> f64) -> Self {
        let v_max = 0.5f64.powf(1.0 / f64::from(power));
        let values: [f64; AXIS_TABLE_INTERVALS + 1] = std::array::from_fn(|i| {
            exact((v_max * i as f64 / AXIS_TABLE_INTERVALS as f64).powi(power))
        });
        Self {
            power,
            v_max,
            values_f32: values.map(|v| v as f32),
        }
    }

    /// The table at v = a^(1/p) (given by the caller, who may have the root at hand) for
    /// a <= 1/2, in f32.
    #[inline]
    fn eval_root_f32(&self, v: f32) -> f32 {
        let x = (v * (AXIS_TABLE_INTERVALS as f64 / self.v_max) as f32)
            .min(AXIS_TABLE_INTERVALS as f32);
        let i = (x as usize).min(AXIS_TABLE_INTERVALS - 1);
        let t = x - i as f32;
        self.values_f32[i] + t * (self.values_f32[i + 1] - self.values_f32[i])
    }

    /// u for a in [0, 1], by the symmetry u(1 - a) = 1 - u(a) and the table.
    #[inline]
    fn eval_f32(&self, a: f32) -> f32 {
        let low = a.min(1.0 - a).max(0.0);
        let root = if self.power == 2 {
            low.sqrt()
        } else {
            low.sqrt().sqrt()
        };
        let u = self.eval_root_f32(root);
        if a > 0.5 { 1.0 - u } else { u }
    }
}

/// The ratio axes' inverse: smoothstep^-1 (like sqrt(a / 3) near 0).
static RATIO_AXIS: std::sync::LazyLock<AxisInverse> =
    std::sync::LazyLock::new(|| AxisInverse::new(2, inverse_smoothstep));
/// The brightness axis' inverse: (smoothstep o smoothstep)^-1 (like (a / 27)^(1/4) near 0).
static BRIGHTNESS_AXIS: std::sync::LazyLock<AxisInverse> =
    std::sync::LazyLock::new(|| AxisInverse::new(4, |z| inverse_smoothstep(inverse_smoothstep(z))));

/// The smoothstep remap of the brightness axis.
fn smoothstep(x: f64) -> f64 {
    x * x * (3.0 - 2.0 * x)
}

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
    /// Resolutions accepted by [`CoefficientTable::fit`].
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
        let rows: Vec<(Vec<f32>, FitStatistics)> = (0..3 * res)
            .into_par_iter()
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
                        // Stored premultiplied by sqrt(z) (see `lookup_normalized`).
                        let at = (zi * res + xi) * 3;
                        for k in 0..3 {
                            out[at + k] = (fit.normalized[k] * z.sqrt()) as f32;
                        }
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
        // [channel][z][y][x][3].
        let mut data = vec![0f32; 3 * res * res * res * 3];
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
                    let dst = ((((channel * res + zi) * res + yi) * res) + xi) * 3;
                    data[dst..dst + 3].copy_from_slice(&values[src..src + 3]);
                }
            }
            total.nodes += stats.nodes;
            total.iterations += stats.iterations;
            total.unreachable += stats.unreachable;
            total.max_residual = total.max_residual.max(stats.max_residual);
        }
        Ok((
            Self {
                space: TableSpace::of(context),
                resolution: res,
                z_nodes: z_nodes.iter().map(|&z| z as f32).collect(),
                data,
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

    /// Trilinearly interpolated normalized coefficients for `rgb` (components in [0, 1],
    /// not all zero; others are clamped). Black has no sigmoid: callers handle it first.
    pub fn lookup_normalized(&self, rgb: [f64; 3]) -> [f64; 3] {
        // The hot path runs in f32 (the table is f32; interpolation weights need no more),
        // and shares square roots: sqrt(z) serves the brightness axis and the
        // un-premultiplication, 1 / sqrt(z) = sqrt(z) / z.
        let rgb = rgb.map(|c| {
            if c.is_nan() {
                0.0
            } else {
                c.clamp(0.0, 1.0) as f32
            }
        });
        let res = self.resolution;
        let channel = if rgb[0] >= rgb[1] && rgb[0] >= rgb[2] {
            0
        } else if rgb[1] >= rgb[2] {
            1
        } else {
            2
        };
        let z = rgb[channel];
        if z == 0.0 {
            return [0.0, 0.0, f64::NEG_INFINITY];
        }
        let scale = (res - 1) as f32;
        let inverse_z = 1.0 / z;
        let sqrt_z = z.sqrt();
        let x = (RATIO_AXIS.eval_f32(rgb[(channel + 1) % 3] * inverse_z) * scale).clamp(0.0, scale);
        let y = (RATIO_AXIS.eval_f32(rgb[(channel + 2) % 3] * inverse_z) * scale).clamp(0.0, scale);
        // Interpolate in the axis parameter u (z = smoothstep(smoothstep(u))), in which the
        // nodes are uniform, rather than in z: the coefficients vary much more evenly in u
        // (dark colours especially), and no search is needed.
        let u = if z <= 0.5 {
            BRIGHTNESS_AXIS.eval_root_f32(sqrt_z.sqrt())
        } else {
            1.0 - BRIGHTNESS_AXIS.eval_root_f32((1.0 - z).sqrt().sqrt())
        } * scale;
        let zi = (u as usize).min(res - 2);
        let tz = (u - zi as f32).clamp(0.0, 1.0);
        let xi = (x as usize).min(res - 2);
        let yi = (y as usize).min(res - 2);
        let (tx, ty) = (x - xi as f32, y - yi as f32);
        // The table holds coefficients premultiplied by sqrt(z): a dark colour's sigmoid
        // tail is ~1 / (4 x^2), so its coefficients grow like z^(-1/2) and the product is
        // nearly constant in z, which linear interpolation follows (it halved the largest
        // error of dark saturated colours). Below the first node the premultiplied values
        // stay constant, so colours keep darkening towards black.
        let unmultiply = sqrt_z * inverse_z;
        // One base index and fixed strides for the eight corners.
        let base = (((channel * res + zi) * res + yi) * res + xi) * 3;
        let (sx, sy, sz) = (3, 3 * res, 3 * res * res);
        let (wx, wy, wz) = ([1.0 - tx, tx], [1.0 - ty, ty], [1.0 - tz, tz]);
        let mut out = [0.0f32; 3];
        for (dz, weight_z) in wz.iter().enumerate() {
            for (dy, weight_y) in wy.iter().enumerate() {
                for (dx, weight_x) in wx.iter().enumerate() {
                    let weight = weight_x * weight_y * weight_z;
                    let at = base + dx * sx + dy * sy + dz * sz;
                    let corner = &self.data[at..at + 3];
                    for k in 0..3 {
                        out[k] += weight * corner[k];
                    }
                }
            }
        }
        out.map(|c| f64::from(c * unmultiply))
    }

    /// The interpolated spectrum for `rgb` (l in nm).
    pub fn lookup(&self, rgb: [f64; 3]) -> SigmoidPolynomial {
        SigmoidPolynomial {
            coefficients: denormalize(self.lookup_normalized(rgb)),
        }
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

    /// The tabulated inverses agree with the exact ones to 1e-5 in the axis parameter
    /// everywhere, ends included. The lookup runs in f32, so the exact value is taken at
    /// the f32-rounded input (near a = 1 that rounding alone moves u by ~2e-5).
    #[test]
    fn tabulated_axis_inverses_are_accurate() {
        for i in 0..=100_000 {
            let a = (i as f64 / 100_000.0) as f32;
            let exact_ratio = inverse_smoothstep(f64::from(a));
            let ratio = f64::from(RATIO_AXIS.eval_f32(a));
            assert!(
                (ratio - exact_ratio).abs() < 1e-5,
                "ratio {a}: {ratio} vs {exact_ratio}"
            );
            let exact_z = inverse_smoothstep(inverse_smoothstep(f64::from(a)));
            let z = f64::from(BRIGHTNESS_AXIS.eval_f32(a));
            assert!(
                (z - exact_z).abs() < 1e-5,
                "brightness {a}: {z} vs {exact_z}"
            );
        }
    }
}
