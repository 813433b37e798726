//! The sigmoid S(x) = 1/2 + x / (2 sqrt(1 + x^2)) of Jakob and Hanika (2019, eq. 3),
//! evaluated without overflow or cancellation.

/// S(x) in f64. Exact limits at +-inf (1 and 0), never NaN for non-NaN input (NaN gives
/// 0.5, the value at 0), and no cancellation for large negative x: there S(x) is computed
/// as 1 / (2 sqrt(1 + x^2) (sqrt(1 + x^2) + |x|)), which keeps full relative precision
/// where the textbook form would subtract nearly equal numbers.
pub fn sigmoid(x: f64) -> f64 {
    sigmoid_with_derivative(x).0
}

/// dS/dx = 1 / (2 (1 + x^2)^(3/2)), 0 at +-inf.
pub fn sigmoid_derivative(x: f64) -> f64 {
    sigmoid_with_derivative(x).1
}

/// S(x) and dS/dx together, sharing one square root and one division: the fitter's inner
/// loop. Branch-free, so loops over it vectorize. Where x^2 overflows (|x| > 1.3e154) r is
/// +inf and both tails are exactly 0: the limits at +-inf, and within 1e-308 of the truth
/// wherever it happens.
#[inline]
pub fn sigmoid_with_derivative(x: f64) -> (f64, f64) {
    let a = x.abs();
    let r = (1.0 + x * x).sqrt();
    let inverse = 1.0 / r;
    let lower = 0.5 * inverse / (r + a);
    let s = if x < 0.0 { lower } else { 1.0 - lower };
    let ds = 0.5 * inverse * inverse * inverse;
    if x.is_nan() { (0.5, 0.5) } else { (s, ds) }
}

/// S(x) in f32 for the render hot path, with the same guarantees as [`sigmoid`], and
/// branch-free so that lanes vectorize. Where x^2 overflows (|x| > 1.8e19) r becomes +inf
/// and the tail term 1 / (2 r (r + |x|)) exactly 0: the exact limits at +-inf, and correct
/// to f32 precision wherever it happens (the true tail is below 1e-39). NaN gives 0.5.
#[inline]
pub fn sigmoid_f32(x: f32) -> f32 {
    let a = x.abs();
    let r = (1.0 + x * x).sqrt();
    let lower = 0.5 / (r * (r + a));
    let s = if x < 0.0 { lower } else { 1.0 - lower };
    if x.is_nan() { 0.5 } else { s }
}

/// Evaluates the sigmoid polynomial S(c0 l^2 + c1 l + c2) at `N` wavelengths at once
/// (l in nm). Written as straight-line lane arithmetic so it auto-vectorizes.
#[inline]
pub fn sigmoid_polynomial_lanes<const N: usize>(c: [f32; 3], lambda: &[f32; N]) -> [f32; N] {
    std::array::from_fn(|i| {
        let l = lambda[i];
        sigmoid_f32((c[0] * l + c[1]) * l + c[2])
    })
}
