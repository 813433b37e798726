use glam::{Vec2, Vec3};
use prism_sampling::distribution::positive_finite;
use prism_spectrum::SampledSpectrum;

use super::microfacet::{Ggx, Microfacet};
use super::{BsdfSample, SmoothDielectric, TransportMode, fresnel_dielectric};

/// A rough dielectric interface: microfacets (GGX unless `D` says otherwise: Mitsuba's
/// Beckmann, [`super::Distribution`]) reflecting and refracting, after Walter,
/// Marschner, Li and Torrance, "Microfacet models for refraction through rough surfaces",
/// EGSR 2007 (eq. 20-21 with the generalized half vector, and the 1/eta^2 radiance
/// scaling of Veach 1997 §5.2), sampled by visible normals. Per-lane indices make it
/// dispersive; a refraction then follows the hero's index only.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughDielectric<const N: usize, D = Ggx> {
    /// The microfacet distribution.
    pub distribution: D,
    /// Relative index (inside over outside) per lane.
    pub eta: [f32; N],
    /// Camera or light path.
    pub mode: TransportMode,
}

/// Refraction of `wo` through a microfacet with normal `n` (same side as `wo`) and
/// relative index `eta` (transmitted over incident); None at total internal reflection.
fn refract_about(wo: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = wo.dot(n);
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    (-wo / eta + (cos_i / eta - cos_t) * n).try_normalize()
}

impl<const N: usize, D: Microfacet> RoughDielectric<N, D> {
    fn smooth(&self) -> SmoothDielectric<N> {
        SmoothDielectric::new(self.eta)
    }

    /// The relative index across the interface for a path arriving along `wo`: eta from
    /// outside (wo.z > 0), 1 / eta from inside.
    fn crossing(eta: f32, wo: Vec3) -> f32 {
        if wo.z > 0.0 { eta } else { 1.0 / eta }
    }

    /// f(wo, wi) and the density of sampling `wi`, for one lane's index; (0, 0) where
    /// directions so close to the surface that their products underflow would give
    /// 0 / 0.
    fn evaluate_lane(&self, wo: Vec3, wi: Vec3, eta_lane: f32) -> (f32, f32) {
        let (f, pdf) = self.evaluate_lane_unchecked(wo, wi, eta_lane);
        if f.is_finite() && pdf.is_finite() {
            (f, pdf)
        } else {
            (0.0, 0.0)
        }
    }

    fn evaluate_lane_unchecked(&self, wo: Vec3, wi: Vec3, eta_lane: f32) -> (f32, f32) {
        let (cos_o, cos_i) = (wo.z, wi.z);
        if cos_o == 0.0 || cos_i == 0.0 {
            return (0.0, 0.0);
        }
        let reflect = cos_o * cos_i > 0.0;
        let eta = if reflect {
            1.0
        } else {
            Self::crossing(eta_lane, wo)
        };
        let Some(wm) = (wi * eta + wo).try_normalize() else {
            return (0.0, 0.0);
        };
        let wm = if wm.z < 0.0 { -wm } else { wm };
        // Back-facing microfacets contribute nothing.
        if wm.dot(wi) * cos_i < 0.0 || wm.dot(wo) * cos_o < 0.0 {
            return (0.0, 0.0);
        }
        let d = &self.distribution;
        let fresnel = fresnel_dielectric(wo.dot(wm), eta_lane);
        if reflect {
            let f = d.d(wm) * d.g(wo, wi) * fresnel / (4.0 * (cos_o * cos_i).abs());
            let pdf = d.d_visible(wo, if wo.dot(wm) < 0.0 { -wm } else { wm })
                / (4.0 * wo.dot(wm).abs())
                * fresnel;
            return (f, pdf);
        }
        let denominator = wi.dot(wm) + wo.dot(wm) / eta;
        let denominator = denominator * denominator;
        if denominator == 0.0 {
            return (0.0, 0.0);
        }
        let dwm_dwi = wi.dot(wm).abs() / denominator;
        let mut f = d.d(wm)
            * (1.0 - fresnel)
            * d.g(wo, wi)
            * (wi.dot(wm) * wo.dot(wm) / (cos_i * cos_o * denominator)).abs();
        if self.mode == TransportMode::Radiance {
            f /= eta * eta;
        }
        let wm_o = if wo.dot(wm) < 0.0 { -wm } else { wm };
        let pdf = d.d_visible(wo, wm_o) * dwm_dwi * (1.0 - fresnel);
        (f, pdf)
    }

    /// f(wo, wi) per lane (0 for an effectively smooth surface, whose lobes are deltas).
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        if self.distribution.effectively_smooth() {
            return SampledSpectrum::splat(0.0);
        }
        SampledSpectrum::from_fn(|i| self.evaluate_lane(wo, wi, self.eta[i]).0)
    }

    /// The density of [`RoughDielectric::sample`] returning `wi`, with the hero's index.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if self.distribution.effectively_smooth() {
            return 0.0;
        }
        self.evaluate_lane(wo, wi, self.eta[0]).1
    }

    /// A visible normal, then reflection or refraction by the hero's Fresnel term (`uc`).
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        if self.distribution.effectively_smooth() {
            return self.smooth().sample(wo, uc, self.mode);
        }
        if wo.z == 0.0 || !wo.is_finite() {
            return None;
        }
        let wm = self.distribution.sample_visible_normal(wo, u);
        // Fresnel with the normal on the outside (+z), as in `evaluate_lane`: the sign of
        // the cosine says which side the path arrives from, and so whether eta or 1/eta
        // applies (from inside, beyond the critical angle, everything reflects).
        let wm_up = if wm.z < 0.0 { -wm } else { wm };
        let fresnel = fresnel_dielectric(wo.dot(wm_up), self.eta[0]);
        let wi = if uc < fresnel {
            let wi = 2.0 * wo.dot(wm) * wm - wo;
            if wi.z * wo.z <= 0.0 {
                return None;
            }
            wi
        } else {
            let wi = refract_about(wo, wm, Self::crossing(self.eta[0], wo))?;
            if wi.z * wo.z >= 0.0 {
                return None;
            }
            wi
        };
        let transmitted = wi.z * wo.z < 0.0;
        let dispersive = transmitted && self.smooth().dispersive();
        let mut f = SampledSpectrum::splat(0.0);
        let mut pdf = [0.0f32; N];
        for lane in 0..N {
            if lane == 0 || !dispersive {
                let (value, density) = self.evaluate_lane(wo, wi, self.eta[lane]);
                f[lane] = value;
                pdf[lane] = density;
            }
        }
        if !positive_finite(pdf[0]) {
            return None;
        }
        Some(BsdfSample {
            wi,
            f,
            pdf,
            delta: false,
            wavelength_dependent: dispersive,
            eta: if transmitted {
                Self::crossing(self.eta[0], wo)
            } else {
                1.0
            },
        })
    }
}
