use super::{Observer, Uv, emission_xyz};
use crate::error::SpectrumError;
use crate::spectra::Blackbody;

/// Lowest temperature of the Planckian locus searched by [`cct_ohno2013`], K.
pub const CCT_MIN_KELVIN: f64 = 1000.0;
/// Highest temperature of the Planckian locus searched by [`cct_ohno2013`], K.
pub const CCT_MAX_KELVIN: f64 = 100_000.0;

/// A correlated colour temperature and the signed distance from the Planckian locus.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CctResult {
    /// Correlated colour temperature, K.
    pub kelvin: f64,
    /// Distance from the Planckian locus in CIE 1960 (u, v), positive above it (greenish),
    /// negative below (pinkish). CIE 015 considers CCT meaningful for |Duv| <= 0.05.
    pub duv: f64,
}

/// The CIE 1960 (u, v) of a blackbody at `kelvin` under the CIE 1931 observer, integrated
/// at 1 nm over 360-830 nm like every other chromaticity in this crate.
pub fn planckian_uv(kelvin: f64) -> Result<Uv, SpectrumError> {
    let body = Blackbody::normalized(kelvin)?;
    emission_xyz(&body, Observer::Cie1931).uv()
}

/// Points per table in each step of the cascade.
const TABLE_STEPS: usize = 10;
/// The cascade stops once neighbouring table temperatures differ by less than this ratio.
/// Fine enough that the triangular solution is exact to far below 0.01 K, coarse enough
/// that the parabola through three distances is well conditioned in f64.
const FINAL_SPACING: f64 = 1e-4;

/// Correlated colour temperature by the method of Ohno, "Practical use and calculation of
/// CCT and Duv", LEUKOS 10(1), 47-55, 2014 (presented 2013): a table of the Planckian locus
/// is searched for the nearest point and refined by cascade expansion (§3.2) until its
/// spacing is 1e-4 in relative temperature, then the triangular solution (§3.1, eq. 5-8)
/// is used for |Duv| < 0.002 and the parabolic one (eq. 9-11) otherwise.
///
/// Errors if `uv` is not finite or its nearest locus point lies at either end of the
/// searched range ([`CCT_MIN_KELVIN`], [`CCT_MAX_KELVIN`]), where no CCT is defined here.
pub fn cct_ohno2013(uv: Uv) -> Result<CctResult, SpectrumError> {
    if !(uv.u.is_finite() && uv.v.is_finite()) {
        return Err(SpectrumError::Degenerate(format!(
            "(u, v) = ({}, {}) is not finite: no CCT",
            uv.u, uv.v
        )));
    }
    let distance = |p: Uv| (p.u - uv.u).hypot(p.v - uv.v);
    // The first table reaches a little beyond the supported range so that a colour exactly
    // at either end is found in its interior; results outside the range are rejected below.
    let (mut lo, mut hi) = ((0.9 * CCT_MIN_KELVIN).ln(), (1.1 * CCT_MAX_KELVIN).ln());
    loop {
        let step = (hi - lo) / TABLE_STEPS as f64;
        let mut table = Vec::with_capacity(TABLE_STEPS + 1);
        for i in 0..=TABLE_STEPS {
            let kelvin = (lo + step * i as f64).exp();
            let p = planckian_uv(kelvin)?;
            table.push((kelvin, p, distance(p)));
        }
        let nearest = (0..table.len())
            .min_by(|&a, &b| table[a].2.total_cmp(&table[b].2))
            .unwrap_or(0);
        let i = nearest.clamp(1, TABLE_STEPS - 1);
        if step < FINAL_SPACING {
            let result = solve(table[i - 1], table[i], table[i + 1], uv);
            let slack = 1.0 + 1e-6;
            if result.kelvin < CCT_MIN_KELVIN / slack || result.kelvin > CCT_MAX_KELVIN * slack {
                return Err(out_of_range(uv));
            }
            return Ok(result);
        }
        lo = table[i - 1].0.ln();
        hi = table[i + 1].0.ln();
    }
}

fn out_of_range(uv: Uv) -> SpectrumError {
    SpectrumError::Degenerate(format!(
        "(u, v) = ({:.5}, {:.5}) is nearest the Planckian locus outside \
         {CCT_MIN_KELVIN}-{CCT_MAX_KELVIN} K: no CCT",
        uv.u, uv.v
    ))
}

/// Ohno's triangular solution, or the parabolic one away from the locus.
fn solve(prev: (f64, Uv, f64), mid: (f64, Uv, f64), next: (f64, Uv, f64), uv: Uv) -> CctResult {
    let (tp, up, dp) = prev;
    let (ti, _, di) = mid;
    let (tn, un, dn) = next;
    // Triangular: project onto the chord between the neighbours.
    let l = (un.u - up.u).hypot(un.v - up.v);
    let x = (dp * dp - dn * dn + l * l) / (2.0 * l);
    let t_tri = tp + (tn - tp) * (x / l);
    let v_chord = up.v + (un.v - up.v) * (x / l);
    let sign = if uv.v >= v_chord { 1.0 } else { -1.0 };
    let duv_tri = sign * (dp * dp - x * x).max(0.0).sqrt();
    if duv_tri.abs() < 0.002 {
        return CctResult {
            kelvin: t_tri,
            duv: duv_tri,
        };
    }
    // Parabolic: the distance as a quadratic in T through the three points.
    let denominator = (tn - ti) * (tp - tn) * (ti - tp);
    let a = (tp * (dn - di) + ti * (dp - dn) + tn * (di - dp)) / denominator;
    let b = -(tp * tp * (dn - di) + ti * ti * (dp - dn) + tn * tn * (di - dp)) / denominator;
    let c = -(dp * (tn - ti) * ti * tn + di * (tp - tn) * tp * tn + dn * (ti - tp) * tp * ti)
        / denominator;
    let t_par = -b / (2.0 * a);
    if !(t_par.is_finite() && a > 0.0) {
        return CctResult {
            kelvin: t_tri,
            duv: duv_tri,
        };
    }
    CctResult {
        kelvin: t_par,
        duv: sign * (a * t_par * t_par + b * t_par + c).max(0.0),
    }
}
