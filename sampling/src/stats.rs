//! Statistics for testing samplers and estimators: Pearson's chi-square test with the
//! customary merging of sparse bins, and the p-value from the regularized incomplete
//! gamma function; Welch's t-test of two means, from the regularized incomplete beta
//! function. Public so that every crate's tests (BSDFs in prism-scene, the integrator's
//! estimators) use the same, tested machinery.

/// The outcome of a chi-square goodness-of-fit test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChiSquare {
    /// Pearson's statistic, sum (observed - expected)^2 / expected over merged bins.
    pub statistic: f64,
    /// Degrees of freedom: merged bins minus one.
    pub degrees_of_freedom: usize,
    /// Probability of a statistic at least this large if the sampler is correct.
    pub p_value: f64,
}

/// Bins whose expected count is below this are pooled with their neighbours (the usual
/// rule of thumb for the chi-square approximation; Cochran 1954).
pub const MIN_EXPECTED_PER_BIN: f64 = 5.0;

/// Pearson's chi-square test of `observed` counts against `expected` counts (same total).
/// Sparse bins (expected < 5) are pooled in order until each pooled bin expects at least
/// 5. A bin that expects 0 but observed samples is an immediate failure (p = 0): the
/// sampler produced something impossible.
pub fn chi_square_test(observed: &[u64], expected: &[f64]) -> ChiSquare {
    assert_eq!(
        observed.len(),
        expected.len(),
        "observed and expected differ in length"
    );
    let mut statistic = 0.0;
    let mut bins = 0usize;
    let (mut pooled_observed, mut pooled_expected) = (0.0, 0.0);
    for (&o, &e) in observed.iter().zip(expected) {
        if e <= 0.0 {
            if o > 0 {
                return ChiSquare {
                    statistic: f64::INFINITY,
                    degrees_of_freedom: bins,
                    p_value: 0.0,
                };
            }
            continue;
        }
        pooled_observed += o as f64;
        pooled_expected += e;
        if pooled_expected >= MIN_EXPECTED_PER_BIN {
            statistic += (pooled_observed - pooled_expected).powi(2) / pooled_expected;
            bins += 1;
            pooled_observed = 0.0;
            pooled_expected = 0.0;
        }
    }
    if pooled_expected > 0.0 {
        statistic += (pooled_observed - pooled_expected).powi(2) / pooled_expected;
        bins += 1;
    }
    let degrees_of_freedom = bins.saturating_sub(1).max(1);
    ChiSquare {
        statistic,
        degrees_of_freedom,
        p_value: chi_square_p_value(statistic, degrees_of_freedom),
    }
}

/// P(X >= statistic) for X chi-square distributed with `dof` degrees of freedom: the
/// regularized upper incomplete gamma function Q(dof / 2, statistic / 2).
pub fn chi_square_p_value(statistic: f64, dof: usize) -> f64 {
    if statistic.is_nan() {
        return 0.0;
    }
    if statistic <= 0.0 {
        return 1.0;
    }
    regularized_gamma_q(dof as f64 / 2.0, statistic / 2.0)
}

/// Q(a, x) = Gamma(a, x) / Gamma(a), by the series for x < a + 1 and Lentz's continued
/// fraction otherwise (Press et al., *Numerical Recipes*, 3rd ed., §6.2).
fn regularized_gamma_q(a: f64, x: f64) -> f64 {
    if x.is_infinite() {
        return 0.0;
    }
    let log_prefactor = a * x.ln() - x - ln_gamma(a);
    if x < a + 1.0 {
        // P(a, x) by its series; Q = 1 - P.
        let (mut term, mut sum, mut ap) = (1.0 / a, 1.0 / a, a);
        for _ in 0..10_000 {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if term.abs() < sum.abs() * 1e-16 {
                break;
            }
        }
        (1.0 - sum * log_prefactor.exp()).clamp(0.0, 1.0)
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let delta = d * c;
            h *= delta;
            if (delta - 1.0).abs() < 1e-16 {
                break;
            }
        }
        (log_prefactor.exp() * h).clamp(0.0, 1.0)
    }
}

/// The outcome of Welch's t-test of two samples' means.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Welch {
    /// The difference of the means over its standard error.
    pub t: f64,
    /// The Welch-Satterthwaite degrees of freedom.
    pub degrees_of_freedom: f64,
    /// Probability of a |t| at least this large if the means are equal (two-sided).
    pub p_value: f64,
}

/// Welch's t-test of whether samples `a` and `b` (at least two values each, of any
/// variances) have the same mean (Welch 1947; the degrees of freedom by Satterthwaite's
/// approximation). Two samples that are each constant are equal (p = 1) when their values
/// are, and differ certainly (p = 0) when not.
pub fn welch_t_test(a: &[f64], b: &[f64]) -> Welch {
    let moments = |x: &[f64]| {
        let n = x.len() as f64;
        let mean = x.iter().sum::<f64>() / n;
        let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
        (n, mean, var / n)
    };
    let ((na, ma, va), (nb, mb, vb)) = (moments(a), moments(b));
    let error = (va + vb).sqrt();
    if error.is_nan() || error <= 0.0 {
        let same = ma == mb;
        return Welch {
            t: if same { 0.0 } else { f64::INFINITY },
            degrees_of_freedom: na + nb - 2.0,
            p_value: if same { 1.0 } else { 0.0 },
        };
    }
    let t = (ma - mb) / error;
    let dof = (va + vb).powi(2) / (va * va / (na - 1.0).max(1.0) + vb * vb / (nb - 1.0).max(1.0));
    Welch {
        t,
        degrees_of_freedom: dof,
        p_value: student_t_p_value(t, dof),
    }
}

/// P(|T| >= |t|) for T Student-t distributed with `dof` degrees of freedom: the
/// regularized incomplete beta function I_{dof / (dof + t^2)}(dof / 2, 1 / 2).
pub fn student_t_p_value(t: f64, dof: f64) -> f64 {
    if t.is_nan() || dof.is_nan() || dof <= 0.0 {
        return 0.0;
    }
    if t.is_infinite() {
        return 0.0;
    }
    regularized_beta(dof / (dof + t * t), 0.5 * dof, 0.5)
}

/// I_x(a, b) by its continued fraction, on whichever side converges (Press et al.,
/// *Numerical Recipes*, 3rd ed., §6.4).
fn regularized_beta(x: f64, a: f64, b: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    if x >= 1.0 {
        return 1.0;
    }
    let log_front = ln_gamma(a + b) - ln_gamma(a) - ln_gamma(b) + a * x.ln() + b * (1.0 - x).ln();
    if x < (a + 1.0) / (a + b + 2.0) {
        (log_front.exp() * beta_fraction(x, a, b) / a).clamp(0.0, 1.0)
    } else {
        (1.0 - log_front.exp() * beta_fraction(1.0 - x, b, a) / b).clamp(0.0, 1.0)
    }
}

/// The continued fraction of the incomplete beta function, by Lentz's method.
fn beta_fraction(x: f64, a: f64, b: f64) -> f64 {
    let tiny = 1e-300;
    let (qab, qap, qam) = (a + b, a + 1.0, a - 1.0);
    let mut c = 1.0;
    let mut d = 1.0 - qab * x / qap;
    if d.abs() < tiny {
        d = tiny;
    }
    d = 1.0 / d;
    let mut h = d;
    for m in 1..10_000 {
        let m = m as f64;
        let m2 = 2.0 * m;
        for aa in [
            m * (b - m) * x / ((qam + m2) * (a + m2)),
            -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2)),
        ] {
            d = 1.0 + aa * d;
            if d.abs() < tiny {
                d = tiny;
            }
            c = 1.0 + aa / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            h *= d * c;
        }
        if (d * c - 1.0).abs() < 1e-15 {
            break;
        }
    }
    h
}

/// ln Gamma(x) for x > 0 by the Lanczos approximation (g = 7, n = 9), accurate to ~1e-15.
fn ln_gamma(x: f64) -> f64 {
    const COEFFICIENTS: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection: Gamma(x) Gamma(1 - x) = pi / sin(pi x).
        return (std::f64::consts::PI / (std::f64::consts::PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let t = x + 7.5;
    let series = COEFFICIENTS[1..]
        .iter()
        .enumerate()
        .fold(COEFFICIENTS[0], |acc, (i, c)| {
            acc + c / (x + i as f64 + 1.0)
        });
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + series.ln()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Critical values from standard chi-square tables (e.g. NIST/SEMATECH e-Handbook,
    /// Table 1.3.6.7.4): the statistic exceeded with probability 0.05 and 0.01.
    /// Two-sided critical values of Student's t (any statistics table, e.g. NIST's
    /// Engineering Statistics Handbook, §1.3.6.7.2): p = 0.05 at t = 12.706 (1 degree of
    /// freedom), 2.228 (10), 1.960 (infinite, the normal's); p = 0.001 at 4.587 (10).
    #[test]
    fn student_t_p_values_match_published_critical_values() {
        for (t, dof, p) in [
            (12.706, 1.0, 0.05),
            (2.228, 10.0, 0.05),
            (4.587, 10.0, 0.001),
            (2.042, 30.0, 0.05),
            (1.960, 1e7, 0.05),
            (0.0, 5.0, 1.0),
        ] {
            let got = student_t_p_value(t, dof);
            assert!(
                (got - p).abs() < 2e-3 * p.max(0.01),
                "t {t}, dof {dof}: {got} vs {p}"
            );
            assert_eq!(student_t_p_value(-t, dof), got);
        }
        assert_eq!(student_t_p_value(f64::NAN, 3.0), 0.0);
        assert_eq!(student_t_p_value(f64::INFINITY, 3.0), 0.0);
    }

    /// Welch's test passes samples of equal means (and unequal variances and sizes) at its
    /// stated rate, and fails a shift of many standard errors.
    #[test]
    fn welch_passes_equal_means_and_fails_a_shift() {
        let mut state = 0x1234_5678_u64;
        let mut uniform = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let trials = 2000;
        let mut rejected = 0;
        for _ in 0..trials {
            let a: Vec<f64> = (0..8).map(|_| uniform()).collect();
            let b: Vec<f64> = (0..12)
                .map(|_| 3.0 * uniform())
                .collect::<Vec<_>>()
                .iter()
                .map(|v| v / 3.0)
                .collect();
            rejected += u32::from(welch_t_test(&a, &b).p_value < 0.05);
        }
        // 5% of 2000 is 100, with a binomial standard deviation of about 10.
        assert!(
            (60..140).contains(&rejected),
            "{rejected} of {trials} rejected at 5%"
        );
        let a: Vec<f64> = (0..8).map(|_| uniform()).collect();
        let b: Vec<f64> = (0..8).map(|_| uniform() + 2.0).collect();
        assert!(welch_t_test(&a, &b).p_value < 1e-6);
        assert_eq!(welch_t_test(&[1.0, 1.0], &[1.0, 1.0]).p_value, 1.0);
        assert_eq!(welch_t_test(&[1.0, 1.0], &[2.0, 2.0]).p_value, 0.0);
    }

    #[test]
    fn p_values_match_published_critical_values() {
        for (dof, x05, x01) in [
            (1, 3.841, 6.635),
            (2, 5.991, 9.210),
            (10, 18.307, 23.209),
            (100, 124.342, 135.807),
        ] {
            assert!(
                (chi_square_p_value(x05, dof) - 0.05).abs() < 1e-4,
                "dof {dof}"
            );
            assert!(
                (chi_square_p_value(x01, dof) - 0.01).abs() < 1e-4,
                "dof {dof}"
            );
        }
        assert_eq!(chi_square_p_value(0.0, 3), 1.0);
        assert_eq!(chi_square_p_value(f64::INFINITY, 3), 0.0);
    }

    #[test]
    fn ln_gamma_of_integers_is_log_factorial() {
        let mut factorial: f64 = 1.0;
        for n in 1..20 {
            assert!((ln_gamma(n as f64) - factorial.ln()).abs() < 1e-12, "{n}");
            factorial *= n as f64;
        }
        assert!((ln_gamma(0.5) - std::f64::consts::PI.sqrt().ln()).abs() < 1e-12);
    }

    #[test]
    fn impossible_samples_fail_immediately() {
        let r = chi_square_test(&[10, 1], &[11.0, 0.0]);
        assert_eq!(r.p_value, 0.0);
    }

    #[test]
    fn perfect_fit_passes_and_gross_misfit_fails() {
        assert!(chi_square_test(&[100, 100, 100], &[100.0, 100.0, 100.0]).p_value > 0.99);
        assert!(chi_square_test(&[150, 50, 100], &[100.0, 100.0, 100.0]).p_value < 1e-6);
    }
}
