//! Gauss-Legendre quadrature nodes and weights on [-1, 1] (Abramowitz and Stegun 25.4.29),
//! found by Newton's method on the Legendre polynomial from Chebyshev's initial guesses.

/// The `n` nodes and weights of the n-point Gauss-Legendre rule on [-1, 1].
pub(crate) fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; n];
    let mut weights = vec![0.0; n];
    for i in 0..n.div_ceil(2) {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            // P_n(x) by the three-term recurrence, and P_n'(x).
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 0 {
                1.0
            } else if n == 1 {
                x
            } else {
                p1
            };
            let pm = if n == 1 { 1.0 } else { p0 };
            derivative = n as f64 * (x * pn - pm) / (x * x - 1.0);
            let step = pn / derivative;
            x -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * derivative * derivative);
        nodes[i] = -x;
        nodes[n - 1 - i] = x;
        weights[i] = w;
        weights[n - 1 - i] = w;
    }
    (nodes, weights)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The n-point rule integrates polynomials of degree 2n - 1 exactly.
    #[test]
    fn integrates_polynomials_exactly() {
        for n in [1usize, 2, 5, 32, 128] {
            let (x, w) = gauss_legendre(n);
            assert!((w.iter().sum::<f64>() - 2.0).abs() < 1e-12, "{n}");
            let degree = (2 * n - 1).min(20) as i32;
            let even = degree - degree % 2;
            let integral: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(even)).sum();
            assert!(
                (integral - 2.0 / (even + 1) as f64).abs() < 1e-12,
                "{n}: {integral}"
            );
        }
    }
}
