//! Mitsuba 3's `roughplastic` as Mitsuba models it (`src/bsdfs/roughplastic.cpp`; the
//! model of Weidlich and Wilkie, "Arbitrarily layered micro-facet surfaces", GRAPHITE
//! 2007, in the form of W. Jakob's Mitsuba 0.5 manual, §8.2.8), beside prism's own
//! [`super::Plastic`], which keeps the energy this one loses:
//!
//! f(wo, wi) = F(wo.h) D(h) G1(wo) G1(wi) / (4 cos_o cos_i)
//!           + rho / (1 - r_i) / (pi eta^2) t(cos_o) t(cos_i)
//!
//! - D and G1 are the scene's distribution (Beckmann by default) and Smith's separable
//!   masking, as Mitsuba's `MicrofacetDistribution::G`;
//! - t(mu) is the coating's single-scattering transmittance from outside, the mean over
//!   visible normals of (1 - F) G1 of the refracted direction (`eval_transmittance`),
//!   tabulated at 64 cosines 0, 1/63, ..., 1 and interpolated linearly;
//! - r_i is the diffuse light the coating reflects back inside, 2 times the mean over
//!   the same 64 cosines mu of mu times the single-scattering reflectance at index 1/eta
//!   (`eval_reflectance`): single scattering loses what masking removes, so a white
//!   substrate does not reflect everything in a white furnace (mitsuba3 issue #1155);
//! - `nonlinear` uses 1 - rho r_i in place of 1 - r_i.
//!
//! Both quadratures are Gauss-Legendre over the sampler's unit square, 32 x 32 points
//! from outside and 128 x 128 from inside (where total internal reflection makes the
//! integrand less smooth), as Mitsuba's. Lobes are chosen as Mitsuba does, the coating's
//! with probability in proportion to (1 - t(cos_o)) times the specular sampling weight
//! 1 / (1 + mean rho); rho's mean is the hit's over its lanes (Mitsuba's is the
//! texture's over its texels: a sampling choice, which changes noise, not the image).

use glam::{Vec2, Vec3};
use prism_sampling::distribution::positive_finite;
use prism_sampling::warp::{cosine_hemisphere, cosine_hemisphere_pdf};
use prism_spectrum::SampledSpectrum;

use super::gauss_legendre::gauss_legendre;
use super::microfacet::Microfacet;
use super::{BsdfSample, Distribution, fresnel_dielectric};

/// Cosines at which the transmittance is tabulated (Mitsuba's
/// `MI_ROUGH_TRANSMITTANCE_RES`).
const NODES: usize = 64;

/// The coating of a rough plastic: its distribution, index and tables, made once per
/// material at load.
#[derive(Debug, Clone, PartialEq)]
pub struct RoughPlasticCoating {
    distribution: Distribution,
    eta: f32,
    transmittance: [f32; NODES],
    internal_reflectance: f32,
}

/// The mean over visible normals from `wi` (the sampler's unit square by an n x n
/// Gauss-Legendre rule) of `integrand(wm)`.
fn visible_mean(
    distribution: &Distribution,
    wi: Vec3,
    n: usize,
    integrand: impl Fn(Vec3) -> f32,
) -> f32 {
    let (nodes, weights) = gauss_legendre(n);
    let mut sum = 0.0f64;
    for (x, wx) in nodes.iter().zip(&weights) {
        for (y, wy) in nodes.iter().zip(&weights) {
            let u = Vec2::new((0.5 * x + 0.5) as f32, (0.5 * y + 0.5) as f32);
            let wm = distribution.sample_visible_normal(wi, u);
            let value = integrand(wm);
            if value.is_finite() {
                sum += f64::from(value) * wx * wy * 0.25;
            }
        }
    }
    sum as f32
}

impl RoughPlasticCoating {
    /// The coating of relative index `eta` (coating over outside) and `distribution`.
    pub fn new(distribution: Distribution, eta: f32) -> Self {
        let cosines: [f32; NODES] =
            std::array::from_fn(|i| (i as f32 / (NODES - 1) as f32).max(1e-6));
        let direction = |mu: f32| Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
        let side = |eta: f32| if eta > 1.0 { 32 } else { 128 };
        let transmittance = cosines.map(|mu| {
            let wi = direction(mu);
            visible_mean(&distribution, wi, side(eta), |wm| {
                let cos = wi.dot(wm);
                let Some(wt) = refract(wi, wm, cos, eta) else {
                    return 0.0;
                };
                if wt.z * wi.z >= 0.0 {
                    return 0.0;
                }
                g1_oriented(&distribution, wt, wm) * (1.0 - fresnel_dielectric(cos, eta))
            })
        });
        let inverse = 1.0 / eta;
        let reflectance_sum: f32 = cosines
            .iter()
            .map(|&mu| {
                let wi = direction(mu);
                let r = visible_mean(&distribution, wi, side(inverse), |wm| {
                    let wo = 2.0 * wi.dot(wm) * wm - wi;
                    if wo.z <= 0.0 {
                        return 0.0;
                    }
                    g1_oriented(&distribution, wo, wm) * fresnel_dielectric(wi.dot(wm), inverse)
                });
                r * mu
            })
            .sum();
        Self {
            distribution,
            eta,
            transmittance,
            internal_reflectance: (2.0 * reflectance_sum / NODES as f32).clamp(0.0, 0.999),
        }
    }

    /// The coating's index.
    pub fn eta(&self) -> f32 {
        self.eta
    }

    /// The coating's distribution.
    pub fn distribution(&self) -> Distribution {
        self.distribution
    }

    /// t(mu), interpolated as Mitsuba's `lerp_gather`.
    pub fn transmittance(&self, mu: f32) -> f32 {
        let x = mu.clamp(0.0, 1.0) * (NODES - 1) as f32;
        let i = (x as usize).min(NODES - 2);
        let w = x - i as f32;
        self.transmittance[i] * (1.0 - w) + self.transmittance[i + 1] * w
    }

    /// r_i.
    pub fn internal_reflectance(&self) -> f32 {
        self.internal_reflectance
    }
}

/// Smith's G1 of `v` for normal `m`, zero where `v` sees the microfacet's back (Mitsuba's
/// `smith_g1`).
fn g1_oriented(distribution: &Distribution, v: Vec3, m: Vec3) -> f32 {
    if v.dot(m) * v.z <= 0.0 {
        0.0
    } else {
        distribution.g1(v)
    }
}

/// `wi` refracted through a microfacet `m` at cosine `cos` (wi.m) into a medium of
/// relative index `eta`; None at total internal reflection.
fn refract(wi: Vec3, m: Vec3, cos: f32, eta: f32) -> Option<Vec3> {
    let (eta, m, cos) = if cos < 0.0 {
        (1.0 / eta, -m, -cos)
    } else {
        (eta, m, cos)
    };
    let sin2_t = (1.0 - cos * cos).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    (-wi / eta + (cos / eta - cos_t) * m).try_normalize()
}

/// A rough plastic at one hit. Two-sided, as prism's other opaque surfaces (Mitsuba's
/// is one-sided; its scenes put it in `twosided` where both sides show).
#[derive(Debug, Clone, Copy)]
pub struct RoughPlastic<'a, const N: usize> {
    coating: &'a RoughPlasticCoating,
    /// rho / (1 - r_i) / (pi eta^2) per lane (or with rho r_i, nonlinear).
    diffuse: SampledSpectrum<N>,
    /// Mitsuba's specular sampling weight, 1 / (1 + mean rho).
    specular_weight: f32,
}

impl<'a, const N: usize> RoughPlastic<'a, N> {
    /// The plastic with substrate `reflectance` (clamped to [0, 1]) under `coating`.
    pub fn new(
        reflectance: SampledSpectrum<N>,
        coating: &'a RoughPlasticCoating,
        nonlinear: bool,
    ) -> Self {
        let rho = reflectance.map(|r| if r.is_nan() { 0.0 } else { r.clamp(0.0, 1.0) });
        let ri = coating.internal_reflectance;
        let scale = std::f32::consts::FRAC_1_PI / (coating.eta * coating.eta);
        let diffuse = rho.map(|r| {
            let kept = if nonlinear { 1.0 - r * ri } else { 1.0 - ri };
            r / kept * scale
        });
        let mean = (0..N).map(|i| rho[i]).sum::<f32>() / N as f32;
        Self {
            coating,
            diffuse,
            specular_weight: 1.0 / (1.0 + mean),
        }
    }

    /// Both directions on the upper side (the lower side mirrored up); None where they
    /// are on different sides or grazing.
    fn upper(wo: Vec3, wi: Vec3) -> Option<(Vec3, Vec3)> {
        if wo.z * wi.z <= 0.0 || !wo.is_finite() || !wi.is_finite() {
            return None;
        }
        let flip = |w: Vec3| Vec3::new(w.x, w.y, -w.z);
        Some(if wo.z < 0.0 {
            (flip(wo), flip(wi))
        } else {
            (wo, wi)
        })
    }

    /// The probability of sampling the coating's lobe from cos_o.
    fn specular_probability(&self, cos_o: f32) -> f32 {
        let t = self.coating.transmittance(cos_o);
        let specular = (1.0 - t) * self.specular_weight;
        let diffuse = t * (1.0 - self.specular_weight);
        if specular + diffuse > 0.0 {
            specular / (specular + diffuse)
        } else {
            0.0
        }
    }

    /// f(wo, wi).
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        let Some((wo, wi)) = Self::upper(wo, wi) else {
            return SampledSpectrum::splat(0.0);
        };
        let c = self.coating;
        let d = &c.distribution;
        let mut specular = 0.0;
        if let Some(h) = (wo + wi).try_normalize() {
            let g = g1_oriented(d, wo, h) * g1_oriented(d, wi, h);
            let value = fresnel_dielectric(wo.dot(h), c.eta) * d.d(h) * g / (4.0 * wo.z * wi.z);
            if value.is_finite() {
                specular = value;
            }
        }
        let through = c.transmittance(wo.z) * c.transmittance(wi.z);
        self.diffuse * through + SampledSpectrum::splat(specular)
    }

    /// The density of [`RoughPlastic::sample`] returning `wi`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some((wo, wi)) = Self::upper(wo, wi) else {
            return 0.0;
        };
        let p = self.specular_probability(wo.z);
        let specular = match (wo + wi).try_normalize() {
            Some(h) if wo.dot(h) > 0.0 => {
                self.coating.distribution.d_visible(wo, h) / (4.0 * wo.dot(h))
            }
            _ => 0.0,
        };
        let pdf = p * specular + (1.0 - p) * cosine_hemisphere_pdf(wi);
        if pdf.is_finite() { pdf } else { 0.0 }
    }

    /// The coating's lobe (a visible normal's reflection) or the substrate's (cosine
    /// distributed), chosen by `uc`.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        if wo.z == 0.0 || !wo.is_finite() {
            return None;
        }
        let below = wo.z < 0.0;
        let up = Vec3::new(wo.x, wo.y, wo.z.abs());
        let wi = if uc < self.specular_probability(up.z) {
            let wm = self.coating.distribution.sample_visible_normal(up, u);
            2.0 * up.dot(wm) * wm - up
        } else {
            cosine_hemisphere(u)
        };
        if wi.z <= 0.0 {
            return None;
        }
        let wi = if below {
            Vec3::new(wi.x, wi.y, -wi.z)
        } else {
            wi
        };
        let pdf = self.pdf(wo, wi);
        if !positive_finite(pdf) {
            return None;
        }
        Some(BsdfSample::smooth(wi, self.f(wo, wi), [pdf; N]))
    }
}
