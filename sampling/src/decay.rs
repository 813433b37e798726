//! Delays of phosphorescent re-emission: light absorbed at time t_i is re-emitted at
//! t_o = t_i + d, the delay d following a decay law (a single or multi-exponential
//! lifetime distribution), sampled where it can matter: restricted to the delays at which
//! some light source was on.
//!
//! For a decay density p(d) and a set W of admissible delays (windows), a delay drawn
//! with density p(d) 1[d in W] / Z, where Z is p's mass on W, weighs its path by Z: the
//! estimator of the integral of p(d) L(t - d) over all delays is unbiased whenever L
//! vanishes outside W (no source shines at those times), and it never wastes a sample on
//! a dark time.

use crate::SamplingError;

/// A decay law: the density of delays sum_k w_k / tau_k exp(-d / tau_k) over d >= 0
/// (weights w_k summing to 1, lifetimes tau_k > 0 in seconds).
#[derive(Debug, Clone, PartialEq)]
pub struct Decay {
    components: Vec<(f64, f64)>,
}

/// Weights may sum to 1 within this (files write them rounded).
const WEIGHT_TOLERANCE: f64 = 1e-6;

impl Decay {
    /// Exponential decay of mean lifetime `lifetime` seconds (finite, > 0).
    pub fn exponential(lifetime: f64) -> Result<Self, SamplingError> {
        Self::multi(&[(lifetime, 1.0)])
    }

    /// Multi-exponential decay: (lifetime in seconds, weight) pairs, lifetimes finite and
    /// positive, weights non-negative and summing to 1 (within 1e-6).
    pub fn multi(components: &[(f64, f64)]) -> Result<Self, SamplingError> {
        if components.is_empty() {
            return Err(SamplingError::Empty);
        }
        for (index, &(tau, w)) in components.iter().enumerate() {
            if !(tau.is_finite() && tau > 0.0) {
                return Err(SamplingError::InvalidParameter(format!(
                    "lifetime {tau} s (component {index}) must be finite and positive"
                )));
            }
            if !(w.is_finite() && w >= 0.0) {
                return Err(SamplingError::InvalidValue { index, value: w });
            }
        }
        let total: f64 = components.iter().map(|c| c.1).sum();
        if (total - 1.0).abs() > WEIGHT_TOLERANCE {
            return Err(SamplingError::InvalidParameter(format!(
                "lifetime weights sum to {total}, not 1"
            )));
        }
        Ok(Self {
            components: components.to_vec(),
        })
    }

    /// The (lifetime, weight) pairs.
    pub fn components(&self) -> &[(f64, f64)] {
        &self.components
    }

    /// The density of delay `d` (0 for negative or NaN delays).
    pub fn pdf(&self, d: f64) -> f64 {
        if d.is_nan() || d < 0.0 {
            return 0.0;
        }
        self.components
            .iter()
            .map(|&(tau, w)| w / tau * (-d / tau).exp())
            .sum()
    }

    /// The probability of a delay in [a, b] (`b` may be infinite; empty for b <= a).
    pub fn mass(&self, a: f64, b: f64) -> f64 {
        self.components
            .iter()
            .map(|&(tau, w)| w * component_mass(tau, a, b))
            .sum()
    }

    /// A delay drawn with `u` in [0, 1) from the decay restricted to `windows` (delay
    /// intervals [a, b], a >= 0, `b` possibly infinite, disjoint), and the decay's mass on
    /// them, Z: the delay's density is pdf(d) / Z there, so the path it continues weighs
    /// Z. None when Z is 0 (no admissible delay: nothing was on).
    pub fn sample_within(&self, u: f64, windows: &[(f64, f64)]) -> Option<(f64, f64)> {
        let masses = self.components.iter().flat_map(|&(tau, w)| {
            windows
                .iter()
                .map(move |&(a, b)| w * component_mass(tau, a, b))
        });
        let total: f64 = masses.clone().sum();
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        let u = if u.is_finite() {
            u.clamp(0.0, 1.0 - f64::EPSILON)
        } else {
            0.0
        };
        let mut target = u * total;
        let count = masses.clone().count();
        for (k, m) in masses.enumerate() {
            if m <= 0.0 {
                continue;
            }
            if target < m || k + 1 == count {
                let tau = self.components[k / windows.len()].0;
                let (a, b) = windows[k % windows.len()];
                let v = (target / m).clamp(0.0, 1.0 - f64::EPSILON);
                // Inverse of the exponential truncated to [a, b], stable for short windows.
                let d = a - tau * (v * (-(b - a) / tau).exp_m1()).ln_1p();
                return Some((d.clamp(a, b), total));
            }
            target -= m;
        }
        None
    }
}

/// exp(-a / tau) - exp(-b / tau) for 0 <= a < b, computed without cancellation.
fn component_mass(tau: f64, a: f64, b: f64) -> f64 {
    let a = a.max(0.0);
    if b.is_nan() || b <= a {
        return 0.0;
    }
    // e^{-a/tau} (1 - e^{-(b-a)/tau})
    let m = (-a / tau).exp() * -(-(b - a) / tau).exp_m1();
    if m.is_finite() { m.max(0.0) } else { 0.0 }
}

/// The delays at which light emitted during `on` (time intervals [start, end], `end`
/// possibly infinite) can be re-emitted at time `t`: [max(0, t - end), t - start] for each
/// interval that began by `t`.
pub fn delay_windows(t: f64, on: &[(f64, f64)]) -> Vec<(f64, f64)> {
    on.iter()
        .filter(|&&(start, _)| start <= t)
        .map(|&(start, end)| ((t - end).max(0.0), t - start))
        .filter(|&(a, b)| b > a)
        .collect()
}
