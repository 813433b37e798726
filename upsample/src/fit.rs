//! Fitting sigmoid-polynomial coefficients to an RGB colour (Jakob and Hanika 2019, §4):
//! minimize the CIELAB difference between the target and the colour of the spectrum under
//! the colour space's illuminant and the CIE 1931 observer.

use nalgebra::{Matrix3, Vector3};
use prism_spectrum::Spectrum;
use prism_spectrum::color::RgbColorSpace;
use prism_spectrum::colorimetry::{Lab, Observer, WhitePoint, Xyz, emission_xyz};
use prism_spectrum::constants::{LAMBDA_MAX, LAMBDA_MIN};

use crate::error::UpsampleError;
use crate::model::SigmoidPolynomial;
use crate::sigmoid::sigmoid_with_derivative;

/// Everything the fitter needs about a colour space, precomputed once: the CIE 1931
/// colour-matching functions weighted by the space's illuminant on the 1 nm grid
/// 360-830 nm, normalized so that a perfect reflector has Y = 1, and the RGB -> XYZ matrix.
#[derive(Debug, Clone)]
pub struct FitContext {
    /// The 1 nm grid the fit is exact on.
    fine: Grid,
    /// Every second point of the 1 nm grid with twice the weight, for table nodes: half
    /// the cost, and a difference from the 1 nm sums (~1e-5 Lab) far below the 1e-3 Lab
    /// that table nodes are fitted to and the ~1e-2 their interpolation errs by.
    table_grid: Grid,
    white: WhitePoint,
    rgb_to_xyz: Matrix3<f64>,
    space: RgbColorSpace,
}

/// Integration points of the colorimetric sums.
#[derive(Debug, Clone)]
struct Grid {
    /// Normalized wavelength t = (l - 360) / 470 of each point: the fit works in t so that
    /// its three coefficients are of similar magnitude.
    t: Vec<f64>,
    /// t squared.
    t2: Vec<f64>,
    /// Illuminant-weighted x-bar, y-bar, z-bar per point, one array each so the inner loop
    /// vectorizes.
    wx: Vec<f64>,
    wy: Vec<f64>,
    wz: Vec<f64>,
}

impl Grid {
    /// The points whose weights are not all zero (the sums are exact without the others:
    /// the CIE D65 table, for one, ends at 780 nm).
    fn new<'a>(points: impl Iterator<Item = (f64, &'a [f64; 3])>) -> Self {
        let mut g = Grid {
            t: vec![],
            t2: vec![],
            wx: vec![],
            wy: vec![],
            wz: vec![],
        };
        for (t, w) in points.filter(|(_, w)| w.iter().any(|&v| v != 0.0)) {
            g.t.push(t);
            g.t2.push(t * t);
            g.wx.push(w[0]);
            g.wy.push(w[1]);
            g.wz.push(w[2]);
        }
        g
    }
}

/// The result of a fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fit {
    /// The spectrum, coefficients for l in nm.
    pub spectrum: SigmoidPolynomial,
    /// The coefficients in normalized wavelength t = (l - 360) / 470, a good warm start
    /// for a neighbouring colour.
    pub normalized: [f64; 3],
    /// The CIE76 distance in Lab between target and fit (the objective's square root).
    pub residual: f64,
    /// Gauss-Newton iterations taken.
    pub iterations: u32,
}

const SPAN: f64 = LAMBDA_MAX - LAMBDA_MIN;
/// The fit stops once the Lab residual is below this (1e-6 dE: far below visibility and
/// below the f32 precision of rendering).
const TOLERANCE: f64 = 1e-6;
const MAX_ITERATIONS: u32 = 100;
/// A fit whose Lab residual stays above this did not converge (reachable colours converge
/// to ~1e-6; unreachable ones are far above it either way) and is retried.
const RESTART_THRESHOLD: f64 = 1e-3;

impl FitContext {
    /// The context for `space` with reflectances seen under `illuminant` (the space's
    /// white, e.g. CIE D65 for sRGB). RGB is taken relative to the illuminant's own white:
    /// the RGB -> XYZ matrix is derived from the space's primaries and the chromaticity of
    /// the illuminant as tabulated (for sRGB and the CIE D65 table, (0.31273, 0.32902)
    /// instead of the rounded (0.3127, 0.3290)), so that RGB (1, 1, 1) is exactly the
    /// perfect reflector, greys are exactly constant spectra, and the Lab white is
    /// Lab (100, 0, 0).
    pub fn new<S: Spectrum + ?Sized>(
        space: &RgbColorSpace,
        illuminant: &S,
    ) -> Result<Self, UpsampleError> {
        let observer = Observer::Cie1931;
        let lambdas: Vec<f64> = (LAMBDA_MIN as i32..=LAMBDA_MAX as i32)
            .map(f64::from)
            .collect();
        let raw: Vec<[f64; 3]> = lambdas
            .iter()
            .map(|&l| {
                let s = illuminant.evaluate(l);
                observer.cmf(l).map(|c| c * s)
            })
            .collect();
        let y_total: f64 = raw.iter().map(|w| w[1]).sum();
        if !(y_total > 0.0 && y_total.is_finite()) {
            return Err(UpsampleError::Spectrum(
                prism_spectrum::SpectrumError::Degenerate(
                    "the illuminant has no luminance: nothing can be fitted under it".into(),
                ),
            ));
        }
        let weights: Vec<[f64; 3]> = raw.iter().map(|w| w.map(|v| v / y_total)).collect();
        let white_xyz = emission_xyz(illuminant, observer);
        let white = WhitePoint::from_xyz(white_xyz)?;
        let adapted = RgbColorSpace::new(
            space.name(),
            space.primaries(),
            white.xy(),
            space.transfer(),
        )?;
        let m = adapted.rgb_to_xyz_matrix().0;
        let t: Vec<f64> = lambdas.iter().map(|l| (l - LAMBDA_MIN) / SPAN).collect();
        let doubled: Vec<[f64; 3]> = weights.iter().map(|w| w.map(|v| 2.0 * v)).collect();
        Ok(Self {
            table_grid: Grid::new(t.iter().copied().zip(&doubled).step_by(2)),
            fine: Grid::new(t.iter().copied().zip(&weights)),
            white,
            rgb_to_xyz: Matrix3::from_fn(|r, c| m[r][c]),
            space: adapted,
        })
    }

    /// The XYZ of linear `rgb` in the space.
    pub fn rgb_xyz(&self, rgb: [f64; 3]) -> Xyz {
        let v = self.rgb_to_xyz * Vector3::from(rgb);
        Xyz::new(v[0], v[1], v[2])
    }

    /// The reference white.
    pub fn white(&self) -> WhitePoint {
        self.white
    }

    /// The colour space fitted for: the given primaries with the illuminant's own white.
    ///
    /// Round trips go through this space, not the one the context was made from: the CIE
    /// D65 spectrum's white is (0.31272, 0.32903), sRGB's rounded D65 is (0.3127,
    /// 0.3290), and a fit is exact against the white the illuminant actually has.
    ///
    /// ```
    /// use prism_spectrum::color::RgbSpaceId;
    /// use prism_spectrum::colorimetry::{reflectance_xyz, Observer};
    /// use prism_upsample::{FitContext, RgbKind, RgbSpectrum};
    ///
    /// let srgb = RgbSpaceId::Srgb;
    /// let context = FitContext::new(srgb.space(), &srgb.illuminant())?;
    /// let grey = RgbSpectrum::fit(&context, [0.8, 0.8, 0.8], RgbKind::Albedo, None)?;
    /// let xyz = reflectance_xyz(&grey, &srgb.illuminant(), Observer::Cie1931)?;
    /// let exact = context.space().xyz_to_rgb(xyz);
    /// assert!(exact.iter().all(|c| (c - 0.8).abs() < 1e-5));
    /// // The nominal space's rounded white is off in the fourth decimal.
    /// let nominal = srgb.space().xyz_to_rgb(xyz);
    /// assert!(nominal.iter().any(|c| (c - 0.8).abs() > 1e-5));
    /// # Ok::<(), prism_upsample::UpsampleError>(())
    /// ```
    pub fn space(&self) -> &RgbColorSpace {
        &self.space
    }

    /// XYZ of the reflectance S(c0 t^2 + c1 t + c2) on `grid` and its Jacobian with
    /// respect to c.
    fn xyz_and_jacobian(grid: &Grid, c: [f64; 3]) -> (Vector3<f64>, Matrix3<f64>) {
        // Twelve scalar accumulators over structure-of-arrays input, and a branch-free
        // sigmoid, so the loop vectorizes.
        let mut acc = [0.0f64; 12];
        for i in 0..grid.t.len() {
            let (t, t2) = (grid.t[i], grid.t2[i]);
            let (s, ds) = sigmoid_with_derivative(c[0] * t2 + c[1] * t + c[2]);
            let (d2, d1) = (ds * t2, ds * t);
            for (k, w) in [grid.wx[i], grid.wy[i], grid.wz[i]].into_iter().enumerate() {
                acc[4 * k] += w * s;
                acc[4 * k + 1] += w * d2;
                acc[4 * k + 2] += w * d1;
                acc[4 * k + 3] += w * ds;
            }
        }
        let xyz = Vector3::new(acc[0], acc[4], acc[8]);
        let jacobian = Matrix3::from_fn(|row, col| acc[4 * row + 1 + col]);
        (xyz, jacobian)
    }

    /// Lab of `xyz` and d Lab / d XYZ.
    fn lab_and_derivative(&self, xyz: Vector3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
        const EPSILON: f64 = 216.0 / 24389.0;
        const KAPPA: f64 = 24389.0 / 27.0;
        let w = self.white.xyz().to_array();
        let f_and_df = |v: f64, wv: f64| {
            let t = v / wv;
            if t > EPSILON {
                let c = t.cbrt();
                (c, 1.0 / (3.0 * c * c * wv))
            } else {
                ((KAPPA * t + 16.0) / 116.0, KAPPA / (116.0 * wv))
            }
        };
        let (fx, dfx) = f_and_df(xyz[0], w[0]);
        let (fy, dfy) = f_and_df(xyz[1], w[1]);
        let (fz, dfz) = f_and_df(xyz[2], w[2]);
        let lab = Vector3::new(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz));
        let d = Matrix3::new(
            0.0,
            116.0 * dfy,
            0.0,
            500.0 * dfx,
            -500.0 * dfy,
            0.0,
            0.0,
            200.0 * dfy,
            -200.0 * dfz,
        );
        (lab, d)
    }

    /// Fits `rgb` (linear, in the space; components in [0, 1]) from the normalized
    /// coefficients `start` ([0, 0, 0] is a neutral start). Levenberg-Marquardt on the
    /// Lab residual with the analytic Jacobian, from a neighbour's coefficients in two or
    /// three steps. A start deep in the sigmoid's saturation (where its gradient vanishes)
    /// can stall; then the fit restarts from the neutral start, so it converges from any
    /// start.
    pub fn fit(&self, rgb: [f64; 3], start: [f64; 3]) -> Fit {
        self.fit_to(rgb, start, TOLERANCE)
    }

    /// [`FitContext::fit`] to a Lab `tolerance` of the caller's choice (tables use 1e-4:
    /// a hundred times below their interpolation error, and fewer iterations).
    pub fn fit_to(&self, rgb: [f64; 3], start: [f64; 3], tolerance: f64) -> Fit {
        self.fit_with_restart(&self.fine, rgb, start, tolerance)
    }

    /// A table node: [`FitContext::fit_to`] on the 2 nm subset of the grid.
    pub(crate) fn fit_table_node(&self, rgb: [f64; 3], start: [f64; 3], tolerance: f64) -> Fit {
        self.fit_with_restart(&self.table_grid, rgb, start, tolerance)
    }

    fn fit_with_restart(&self, grid: &Grid, rgb: [f64; 3], start: [f64; 3], tolerance: f64) -> Fit {
        let first = self.fit_iterations(grid, rgb, start, MAX_ITERATIONS, tolerance);
        if first.residual <= RESTART_THRESHOLD || start == [0.0; 3] {
            return first;
        }
        let second = self.fit_iterations(grid, rgb, [0.0; 3], MAX_ITERATIONS, tolerance);
        let iterations = first.iterations + second.iterations;
        let best = if second.residual < first.residual {
            second
        } else {
            first
        };
        Fit { iterations, ..best }
    }

    /// At most `max_iterations` Levenberg-Marquardt steps from `start`, without restarts:
    /// the refined table lookup.
    pub fn fit_with_budget(&self, rgb: [f64; 3], start: [f64; 3], max_iterations: u32) -> Fit {
        self.fit_iterations(&self.fine, rgb, start, max_iterations, TOLERANCE)
    }

    fn fit_iterations(
        &self,
        grid: &Grid,
        rgb: [f64; 3],
        start: [f64; 3],
        max_iterations: u32,
        tolerance: f64,
    ) -> Fit {
        let target_xyz = self.rgb_xyz(rgb);
        let target_lab = Lab::from_xyz(target_xyz, self.white);
        let target = Vector3::new(target_lab.l, target_lab.a, target_lab.b);
        let residual_at = |c: [f64; 3]| {
            let (xyz, j) = Self::xyz_and_jacobian(grid, c);
            let (lab, d) = self.lab_and_derivative(xyz);
            (lab - target, d * j)
        };
        let mut c = start.map(|v| if v.is_finite() { v } else { 0.0 });
        let (mut r, mut j) = residual_at(c);
        let mut error = r.norm();
        let mut damping = 1e-3;
        let mut iterations = 0;
        while error > tolerance && iterations < max_iterations {
            iterations += 1;
            let jt = j.transpose();
            let jtj = jt * j;
            let scale = Matrix3::from_diagonal(&jtj.diagonal().map(|v| v.max(1e-12)));
            let Some(step) = (jtj + scale * damping).lu().solve(&(-(jt * r))) else {
                damping *= 10.0;
                continue;
            };
            let candidate = [c[0] + step[0], c[1] + step[1], c[2] + step[2]];
            let (r_new, j_new) = residual_at(candidate);
            let e_new = r_new.norm();
            if e_new.is_finite() && e_new < error {
                (c, r, j, error) = (candidate, r_new, j_new, e_new);
                damping = (damping * 0.1).max(1e-12);
            } else {
                damping *= 10.0;
                if damping > 1e12 {
                    break;
                }
            }
        }
        Fit {
            spectrum: SigmoidPolynomial {
                coefficients: denormalize(c),
            },
            normalized: c,
            residual: error,
            iterations,
        }
    }
}

/// Coefficients in normalized t = (l - 360) / 470 to coefficients in l (nm):
/// c0 t^2 + c1 t + c2 expanded with t = (l - a) s.
/// The products of a and s are constants, so each coefficient is one product deep.
pub fn denormalize(c: [f64; 3]) -> [f64; 3] {
    const S: f64 = 1.0 / SPAN;
    const S2: f64 = S * S;
    const AS: f64 = LAMBDA_MIN * S;
    const AS2: f64 = LAMBDA_MIN * S2;
    const A2S2: f64 = AS * AS;
    [
        c[0] * S2,
        c[1] * S - c[0] * (2.0 * AS2),
        (c[2] - c[1] * AS) + c[0] * A2S2,
    ]
}

/// The inverse of [`denormalize`]: coefficients in l (nm) to coefficients in normalized
/// t, c0 l^2 + c1 l + c2 expanded with l = a + t / s.
pub fn normalize(c: [f64; 3]) -> [f64; 3] {
    const W: f64 = SPAN;
    const A: f64 = LAMBDA_MIN;
    [
        c[0] * (W * W),
        (c[1] + c[0] * (2.0 * A)) * W,
        (c[0] * A + c[1]) * A + c[2],
    ]
}
