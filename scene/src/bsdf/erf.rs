//! The error function and its inverse, in single precision, for the Beckmann microfacet
//! distribution (its masking term and its visible-normal sampler are written in them).

/// erf(x), by the complementary error function's Chebyshev fit of *Numerical Recipes*
/// (Press et al., 2nd ed., §6.2, `erfcc`: fractional error below 1.2e-7 everywhere),
/// evaluated in double precision.
pub(crate) fn erf(x: f32) -> f32 {
    if x.is_nan() {
        return x;
    }
    let z = f64::from(x).abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -z * z - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let erfc = t * poly.exp();
    let e = (1.0 - erfc) as f32;
    if x < 0.0 { -e } else { e }
}

/// erf^-1(x) for x in (-1, 1), by M. Giles, "Approximating the erfinv function", *GPU
/// Computing Gems, Jade Edition*, 2011, ch. 10 (the single-precision polynomial); +-inf at
/// +-1 and beyond.
pub(crate) fn erfinv(x: f32) -> f32 {
    if x.is_nan() {
        return x;
    }
    if x.abs() >= 1.0 {
        return f32::INFINITY.copysign(x);
    }
    let mut w = -((1.0 - x) * (1.0 + x)).ln();
    let p = if w < 5.0 {
        w -= 2.5;
        let mut p = 2.810_226_4e-8;
        for c in [
            3.432_739_4e-7,
            -3.523_387_7e-6,
            -4.391_506_5e-6,
            2.185_808_7e-4,
            -1.253_725e-3,
            -4.177_681_6e-3,
            2.466_407_3e-1,
            1.501_409_4,
        ] {
            p = c + p * w;
        }
        p
    } else {
        w = w.sqrt() - 3.0;
        let mut p = -2.002_142_6e-4;
        for c in [
            1.009_505_6e-4,
            1.349_343_2e-3,
            -3.673_428_4e-3,
            5.739_507_7e-3,
            -7.622_461_3e-3,
            9.438_870_5e-3,
            1.001_674,
            2.832_976_8,
        ] {
            p = c + p * w;
        }
        p
    };
    p * x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn erf_matches_tabulated_values() {
        // Abramowitz and Stegun, Table 7.1.
        for (x, e) in [
            (0.0f32, 0.0f32),
            (0.5, 0.520_499_9),
            (1.0, 0.842_700_8),
            (2.0, 0.995_322_3),
            (-1.0, -0.842_700_8),
        ] {
            assert!((erf(x) - e).abs() < 3e-7, "erf({x}) = {}", erf(x));
        }
        assert_eq!(erf(40.0), 1.0);
    }

    #[test]
    fn erfinv_inverts_erf() {
        for k in -99..=99 {
            let x = k as f32 / 100.0;
            let y = erfinv(x);
            assert!((erf(y) - x).abs() < 2e-6, "{x}: {y} -> {}", erf(y));
        }
        assert!((erfinv(0.5) - 0.476_936_3).abs() < 1e-6);
        assert_eq!(erfinv(1.0), f32::INFINITY);
        assert!(erfinv(0.999_999).is_finite());
    }
}
