use glam::Vec3;
use prism_spectrum::SampledSpectrum;

use super::{BsdfSample, cos_theta};

/// Whether radiance (camera paths) or importance (light paths) is being transported: a
/// refraction scales radiance by 1 / eta^2 but not importance (Veach 1997, §5.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TransportMode {
    /// Camera paths.
    #[default]
    Radiance,
    /// Light paths.
    Importance,
}

/// Unpolarized Fresnel reflectance of a dielectric interface for cos(theta_i) (negative:
/// from the inside) and relative index eta = n_inside / n_outside. Total internal
/// reflection gives 1.
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let (cos_i, eta) = if cos_i < 0.0 {
        (-cos_i, 1.0 / eta)
    } else {
        (cos_i, eta)
    };
    let cos_i = cos_i.min(1.0);
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).max(0.0).sqrt();
    let r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    0.5 * (r_parallel * r_parallel + r_perpendicular * r_perpendicular)
}

/// The refraction of `wo` (pointing away from the surface, local frame) through an
/// interface of relative index `eta` (inside over outside, normal +z pointing outside), or
/// None at total internal reflection. Returns the direction and the eta of the crossing
/// (n_t / n_i).
pub fn refract(wo: Vec3, eta: f32) -> Option<(Vec3, f32)> {
    let (n, eta, cos_i) = if wo.z >= 0.0 {
        (Vec3::Z, eta, wo.z)
    } else {
        (-Vec3::Z, 1.0 / eta, -wo.z)
    };
    let sin2_i = (1.0 - cos_i * cos_i).max(0.0);
    let sin2_t = sin2_i / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let wt = -wo / eta + (cos_i / eta - cos_t) * n;
    Some((wt.normalize(), eta))
}

/// A smooth (perfectly specular) dielectric interface with an index of refraction per
/// wavelength lane (dispersion when they differ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmoothDielectric<const N: usize> {
    /// Relative index (inside over outside) per lane, each > 0.
    pub eta: [f32; N],
}

impl<const N: usize> SmoothDielectric<N> {
    /// An interface with relative index `eta` per lane (non-finite or non-positive values
    /// become 1, no interface).
    pub fn new(eta: [f32; N]) -> Self {
        Self {
            eta: eta.map(|e| if e.is_finite() && e > 0.0 { e } else { 1.0 }),
        }
    }

    /// Whether the lanes' indices differ, so refracted directions depend on wavelength.
    pub fn dispersive(&self) -> bool {
        self.eta.iter().any(|&e| e != self.eta[0])
    }

    /// Chooses reflection or refraction with the hero lane's Fresnel probabilities (`uc`),
    /// like *PBR* 4th ed. §9.5.1. Reflection's direction is the same for all lanes, so each
    /// lane gets its own choice probability and value; a refraction through a dispersive
    /// interface follows the hero's index only, is flagged wavelength-dependent, and
    /// gives the other lanes density 0.
    pub fn sample(&self, wo: Vec3, uc: f32, mode: TransportMode) -> Option<BsdfSample<N>> {
        if wo.z == 0.0 || !wo.is_finite() {
            return None;
        }
        let cos_o = cos_theta(wo);
        let reflectance: [f32; N] = self.eta.map(|e| fresnel_dielectric(cos_o, e));
        let r0 = reflectance[0];
        if uc < r0 {
            let wi = Vec3::new(-wo.x, -wo.y, wo.z);
            let f = SampledSpectrum(reflectance) / cos_o.abs();
            return Some(BsdfSample::specular(wi, f, reflectance));
        }
        let (wi, eta_hero) = refract(wo, self.eta[0])?;
        let dispersive = self.dispersive();
        let transmit = |lane: usize| {
            let t = 1.0 - reflectance[lane];
            let eta_lane = if wo.z >= 0.0 {
                self.eta[lane]
            } else {
                1.0 / self.eta[lane]
            };
            let scale = if mode == TransportMode::Radiance {
                1.0 / (eta_lane * eta_lane)
            } else {
                1.0
            };
            (t, t * scale / cos_theta(wi).abs())
        };
        let mut pdf = [0.0; N];
        let mut f = SampledSpectrum::splat(0.0);
        for lane in 0..N {
            if lane == 0 || !dispersive {
                let (p, value) = transmit(lane);
                pdf[lane] = p;
                f[lane] = value;
            }
        }
        debug_assert!(eta_hero > 0.0);
        Some(BsdfSample {
            wi,
            f,
            pdf,
            delta: true,
            wavelength_dependent: dispersive,
            eta: eta_hero,
        })
    }
}
