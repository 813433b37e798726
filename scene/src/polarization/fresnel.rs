//! Fresnel's amplitude coefficients, complex, for dielectrics and conductors.

use num_complex::Complex64;

/// The complex amplitude reflection coefficients of an interface for s- and p-polarized
/// light, and the fractions of power transmitted (zero for a conductor, whose transmitted
/// wave is absorbed within the skin depth).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FresnelAmplitudes {
    /// r_s = (cos_i - n cos_t) / (cos_i + n cos_t).
    pub s: Complex64,
    /// r_p = (n cos_i - cos_t) / (n cos_i + cos_t).
    pub p: Complex64,
    /// T_s = 1 - |r_s|^2 for a dielectric below the critical angle, else 0.
    pub transmitted_s: f64,
    /// T_p = 1 - |r_p|^2 for a dielectric below the critical angle, else 0.
    pub transmitted_p: f64,
}

/// The amplitudes at cos(theta_i) = `cos_i` for the relative index `eta` = n_t / n_i
/// (complex: eta + i k for a conductor; k = 0 for a dielectric). A negative `cos_i`
/// means light arriving from the inside (a dielectric's index is then inverted; a
/// conductor has no inside and is seen from outside). Beyond the critical angle cos_t is
/// imaginary, |r_s| = |r_p| = 1 and their phases differ: total internal reflection's
/// retardance (Born and Wolf §1.5.4). Every output is finite for every input; NaN or
/// non-positive indices are read as 1 (no interface).
pub fn fresnel_amplitudes(cos_i: f64, eta: Complex64) -> FresnelAmplitudes {
    let usable = eta.re.is_finite() && eta.im.is_finite() && eta.re > 0.0 && eta.im >= 0.0;
    let mut eta = if usable {
        eta
    } else {
        Complex64::new(1.0, 0.0)
    };
    let conductor = eta.im > 0.0;
    let mut cos_i = if cos_i.is_finite() {
        cos_i.clamp(-1.0, 1.0)
    } else {
        1.0
    };
    if cos_i < 0.0 {
        cos_i = -cos_i;
        if !conductor {
            eta = Complex64::new(1.0 / eta.re, 0.0);
        }
    }
    let sin2_i = 1.0 - cos_i * cos_i;
    // cos_t = sqrt(1 - sin_i^2 / eta^2), principal branch: for real eta beyond the
    // critical angle, +i sqrt(sin_i^2 / eta^2 - 1), the evanescent wave's choice.
    let cos_t = (Complex64::new(1.0, 0.0) - sin2_i / (eta * eta)).sqrt();
    let ci = Complex64::new(cos_i, 0.0);
    let divide = |a: Complex64, b: Complex64| {
        if b.norm_sqr() > 0.0 {
            a / b
        } else {
            Complex64::new(1.0, 0.0)
        }
    };
    let s = divide(ci - eta * cos_t, ci + eta * cos_t);
    let p = divide(eta * ci - cos_t, eta * ci + cos_t);
    let total_internal = !conductor && sin2_i >= eta.re * eta.re;
    let (transmitted_s, transmitted_p) = if conductor || total_internal {
        (0.0, 0.0)
    } else {
        ((1.0 - s.norm_sqr()).max(0.0), (1.0 - p.norm_sqr()).max(0.0))
    };
    let finite = |c: Complex64| {
        if c.re.is_finite() && c.im.is_finite() {
            c
        } else {
            Complex64::new(1.0, 0.0)
        }
    };
    FresnelAmplitudes {
        s: finite(s),
        p: finite(p),
        transmitted_s,
        transmitted_p,
    }
}
