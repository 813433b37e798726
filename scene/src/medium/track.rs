//! Tracking along a ray through a medium against a majorant (Miller, Georgiev and Jarosz,
//! "A null-scattering path integral formulation of light transport", SIGGRAPH 2019, §3-4;
//! the sampling routine is pbrt-v4's `SampleT_maj`, *PBR* 4th ed. §14.2.1).
//!
//! Free-flight distances are drawn by the hero lane's majorant `sigma_maj[0]`. At every
//! tentative collision the caller is told the point's coefficients, the majorant per lane
//! and T_maj, the majorant transmittance per lane since the previous collision; the caller
//! decides what the collision is (absorption, scattering, or a null collision) and whether
//! tracking goes on. Lanes whose majorant differs from the hero's carry the ratio of their
//! densities to the hero's: that is the caller's spectral MIS.

use glam::Vec3;

use crate::geometry::Ray;
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use super::grid::Span;
use super::{Medium, MediumPoint};

/// A tentative collision along the ray.
#[derive(Debug, Clone, Copy)]
pub struct Collision<const N: usize> {
    /// The distance along the ray (unit direction) from its origin.
    pub t: f32,
    /// The point.
    pub p: Vec3,
    /// The medium's coefficients there.
    pub point: MediumPoint<N>,
    /// The majorant per lane there.
    pub sigma_maj: SampledSpectrum<N>,
    /// The majorant transmittance per lane since the previous collision (or the start).
    pub t_maj: SampledSpectrum<N>,
}

/// Tracks along `ray` (unit direction; `t_max` may be infinite) through `medium` at
/// `wavelengths`: distances drawn with `u` first, then numbers from `next_u`, every
/// collision handed to `collide`, which returns whether to go on. Returns the majorant
/// transmittance from the last collision to `t_max` if tracking reached it, or ones if
/// `collide` stopped it (as pbrt-v4 does, so that the caller's weights are left as
/// `collide` set them).
pub fn sample_majorant<const N: usize>(
    medium: &Medium,
    ray: &Ray,
    u: f32,
    next_u: &mut impl FnMut() -> f32,
    wavelengths: &SampledWavelengths<N>,
    collide: impl FnMut(&Collision<N>) -> bool,
) -> SampledSpectrum<N> {
    let base = medium.at(wavelengths);
    sample_majorant_at(medium, &base, ray, u, next_u, wavelengths, collide)
}

/// [`sample_majorant`] with the medium's coefficients at `wavelengths` already evaluated
/// (`base`, [`Medium::at`]'s): a path evaluates them once for all its flights.
pub fn sample_majorant_at<const N: usize>(
    medium: &Medium,
    base: &MediumPoint<N>,
    ray: &Ray,
    mut u: f32,
    next_u: &mut impl FnMut() -> f32,
    wavelengths: &SampledWavelengths<N>,
    mut collide: impl FnMut(&Collision<N>) -> bool,
) -> SampledSpectrum<N> {
    let (origin, direction) = (ray.origin, ray.direction);
    let t_max = if ray.t_max.is_nan() {
        0.0
    } else {
        ray.t_max.max(0.0)
    };
    // The majorant transmittance since the last collision, and whether `collide` stopped.
    let mut t_maj = SampledSpectrum::splat(1.0);
    let mut stopped = false;
    let span = |span: Span| -> bool {
        let sigma_maj = medium.majorant_over(base, span.bound);
        if sigma_maj[0] <= 0.0 {
            t_maj *= transmittance(&sigma_maj, span.t1 - span.t0);
            return true;
        }
        let mut t_min = span.t0;
        loop {
            let t = t_min + exponential(u, sigma_maj[0]);
            u = next_u();
            if t.is_nan() || t >= span.t1 {
                t_maj *= transmittance(&sigma_maj, span.t1 - t_min);
                return true;
            }
            t_maj *= transmittance(&sigma_maj, t - t_min);
            let p = origin + direction * t;
            let collision = Collision {
                t,
                p,
                point: medium.point(base, p, wavelengths),
                sigma_maj,
                t_maj,
            };
            if !collide(&collision) {
                stopped = true;
                return false;
            }
            t_maj = SampledSpectrum::splat(1.0);
            // A collision so close to the last one that f32 cannot tell them apart still
            // advances (a majorant of 1e8 per unit in a scene of size 1e2).
            t_min = if t > t_min { t } else { next_after(t_min) };
        }
    };
    medium.spans(origin, direction, t_max, span);
    if stopped {
        SampledSpectrum::splat(1.0)
    } else {
        t_maj
    }
}

/// exp(-sigma d) per lane; 0 for an infinite distance through a medium, 1 through none.
#[inline]
pub fn transmittance<const N: usize>(sigma: &SampledSpectrum<N>, d: f32) -> SampledSpectrum<N> {
    SampledSpectrum::from_fn(|i| {
        let x = sigma[i] * d;
        if x.is_nan() {
            if sigma[i] > 0.0 { 0.0 } else { 1.0 }
        } else {
            (-x).exp()
        }
    })
}

/// A distance distributed as sigma exp(-sigma t), from `u` in [0, 1).
#[inline]
fn exponential(u: f32, sigma: f32) -> f32 {
    let u = if u.is_nan() {
        0.0
    } else {
        u.clamp(0.0, 1.0 - f32::EPSILON)
    };
    -(1.0 - u).ln() / sigma
}

/// The next f32 after `x` >= 0.
fn next_after(x: f32) -> f32 {
    f32::from_bits(x.to_bits() + 1)
}
