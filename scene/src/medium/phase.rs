//! Phase functions: how a medium scatters light by angle. Directions are directions of
//! travel: `incoming` is where the light was going when it reached the scattering point,
//! `outgoing` where it goes after, so cos theta = incoming . outgoing (1: straight on).
//! Both phase functions here are wavelength-independent and normalized over the sphere
//! (integral of p over all outgoing directions = 1), so sampling them exactly leaves a
//! weight p / pdf of 1 at every wavelength.

use glam::{Vec2, Vec3};

use crate::geometry::Frame;

/// |g| at or below which Henyey-Greenstein is sampled as the isotropic function it is
/// within f32 rounding (pbrt-v4 §11.3.1 uses the same cut-off).
const ISOTROPIC_G: f32 = 1e-3;

/// The largest |g| a scene may give: beyond it the lobe is narrower than f32 directions
/// resolve and p overflows.
pub const MAX_ABS_G: f64 = 0.999;

/// A phase function.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Phase {
    /// Henyey and Greenstein (1941), asymmetry g = mean cos theta in (-1, 1): forward
    /// scattering for g > 0 (fog, milk's fat droplets), backward for g < 0, isotropic at 0.
    HenyeyGreenstein {
        /// The asymmetry parameter.
        g: f32,
    },
    /// Rayleigh scattering by particles much smaller than the wavelength (air, the blue of
    /// the sky): p = 3 / (16 pi) (1 + cos^2 theta). Its wavelength dependence is the
    /// medium's sigma_s, not the phase function's.
    Rayleigh,
}

/// A sampled direction: the outgoing direction of travel, with p and the density (equal
/// for both phase functions, which are sampled exactly).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhaseSample {
    /// Outgoing direction of travel (unit).
    pub outgoing: Vec3,
    /// The phase function's value.
    pub p: f32,
    /// The solid-angle density of the sample.
    pub pdf: f32,
}

impl Phase {
    /// Henyey-Greenstein with asymmetry `g`, which must be finite with |g| <= MAX_ABS_G.
    pub fn henyey_greenstein(g: f64) -> Result<Self, String> {
        if g.is_finite() && g.abs() <= MAX_ABS_G {
            Ok(Phase::HenyeyGreenstein { g: g as f32 })
        } else {
            Err(format!(
                "g {g} must be in (-1, 1) (at most {MAX_ABS_G} in magnitude)"
            ))
        }
    }

    /// p for light scattered by cos theta = `cos_theta` (clamped to [-1, 1]).
    #[inline]
    pub fn p(&self, cos_theta: f32) -> f32 {
        let c = if cos_theta.is_nan() {
            0.0
        } else {
            cos_theta.clamp(-1.0, 1.0)
        };
        match *self {
            Phase::HenyeyGreenstein { g } => henyey_greenstein(c, g),
            Phase::Rayleigh => 3.0 / (16.0 * std::f32::consts::PI) * (1.0 + c * c),
        }
    }

    /// p and its density (the same) for light travelling along `incoming` that leaves
    /// along `outgoing`.
    #[inline]
    pub fn eval(&self, incoming: Vec3, outgoing: Vec3) -> f32 {
        self.p(incoming.dot(outgoing))
    }

    /// Samples an outgoing direction for light travelling along unit `incoming`, with `u`
    /// in [0, 1)^2.
    pub fn sample(&self, incoming: Vec3, u: Vec2) -> PhaseSample {
        let cos_theta = self.sample_cos_theta(u.x);
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let phi = std::f32::consts::TAU * u.y;
        let local = Vec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta);
        let outgoing = Frame::from_normal(incoming)
            .to_world(local)
            .normalize_or(incoming);
        let p = self.p(cos_theta);
        PhaseSample {
            outgoing,
            p,
            pdf: p,
        }
    }

    /// cos theta distributed as p, by inverting its cumulative distribution at `u`.
    fn sample_cos_theta(&self, u: f32) -> f32 {
        let u = if u.is_nan() { 0.5 } else { u.clamp(0.0, 1.0) };
        match *self {
            Phase::HenyeyGreenstein { g } if g.abs() > ISOTROPIC_G => {
                // pbrt-v4 §11.3.1, written for cos theta from the direction of travel.
                let s = (1.0 - g * g) / (1.0 + g - 2.0 * g * u);
                ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
            }
            Phase::HenyeyGreenstein { .. } => 1.0 - 2.0 * u,
            Phase::Rayleigh => {
                // F(mu) = (mu^3 + 3 mu + 4) / 8: the depressed cubic mu^3 + 3 mu - (8u - 4)
                // = 0 has one real root, by Cardano's formula with z = 4u - 2.
                let z = 4.0 * u - 2.0;
                let root = (z * z + 1.0).sqrt();
                ((z + root).cbrt() + (z - root).cbrt()).clamp(-1.0, 1.0)
            }
        }
    }

    /// The mean cosine of the scattering angle (g for Henyey-Greenstein, 0 for Rayleigh).
    pub fn mean_cosine(&self) -> f32 {
        match *self {
            Phase::HenyeyGreenstein { g } => g,
            Phase::Rayleigh => 0.0,
        }
    }
}

/// Henyey-Greenstein: (1 - g^2) / (4 pi (1 + g^2 - 2 g cos theta)^(3/2)).
#[inline]
fn henyey_greenstein(cos_theta: f32, g: f32) -> f32 {
    let denominator = (1.0 + g * g - 2.0 * g * cos_theta).max(1e-12);
    (1.0 - g * g) / (4.0 * std::f32::consts::PI * denominator * denominator.sqrt())
}
