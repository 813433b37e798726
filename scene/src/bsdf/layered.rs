//! The glTF material's layers over its metallic-roughness base: sheen on the base and a
//! clear coat on top (glTF 2.0 Appendix B with `KHR_materials_sheen` and
//! `KHR_materials_clearcoat`), combined by albedo scaling.

use glam::{Vec2, Vec3};
use prism_sampling::distribution::positive_finite;
use prism_sampling::warp::{cosine_hemisphere, cosine_hemisphere_pdf};
use prism_spectrum::SampledSpectrum;

use super::{BsdfSample, Clearcoat, MetallicRoughness, Sheen, TransportMode};

/// A metallic-roughness base under a sheen and a clear coat (either may be absent):
///
/// f = c f_coat + (1 - c E_coat(mu_v)) (f_sheen + (1 - s(lambda) E_sheen(mu_v)) f_base)
///
/// where c is the coat's weight, s the sheen colour per lane and E the layers'
/// directional albedos. Each layer takes from those below what it reflects itself, so a
/// white furnace stays white (every layer's albedo is exact up to its table). mu_v is the
/// cosine of the direction towards the camera (wo on camera paths, wi on light paths, so
/// that both transport the same adjoint): the extension's simplified albedo scaling, per
/// wavelength rather than by the colour's largest channel.
#[derive(Debug, Clone)]
pub struct Layered<'a, const N: usize> {
    /// The base.
    pub base: MetallicRoughness<'a, N>,
    /// The sheen on the base, if any.
    pub sheen: Option<Sheen<N>>,
    /// The coat on top, if any.
    pub clearcoat: Option<Clearcoat>,
    /// Which end of the path is the camera's.
    pub mode: TransportMode,
}

/// A [`Layered`] BSDF's reflection, lobe by lobe ([`Layered::parts`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LayeredParts<const N: usize> {
    /// The clear coat's lobe (the same in every lane), if there is a coat.
    pub coat: Option<f32>,
    /// The sheen's lobe under the coat, per lane.
    pub sheen: SampledSpectrum<N>,
    /// What the base's f is multiplied by under the sheen and the coat, per lane.
    pub base_weight: SampledSpectrum<N>,
}

impl<const N: usize> Layered<'_, N> {
    /// Directions mirrored into the upper hemisphere when `wo` is below (a back face is
    /// coated alike).
    fn upper(wo: Vec3, wi: Vec3) -> (Vec3, Vec3) {
        if wo.z < 0.0 {
            (Vec3::new(wo.x, wo.y, -wo.z), Vec3::new(wi.x, wi.y, -wi.z))
        } else {
            (wo, wi)
        }
    }

    /// f(wo, wi) per lane; reflection only.
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        if wo.z * wi.z <= 0.0 {
            return self.f_through(wo, wi);
        }
        let mut f = self.base.f(wo, wi);
        let (wo, wi) = Self::upper(wo, wi);
        let view = match self.mode {
            TransportMode::Radiance => wo,
            TransportMode::Importance => wi,
        };
        if let Some(sheen) = &self.sheen {
            let lobe = sheen.f_white(wo, wi);
            let albedo = sheen.albedo(view.z);
            f = SampledSpectrum::from_fn(|i| {
                sheen.color[i] * lobe + (1.0 - sheen.color[i] * albedo) * f[i]
            });
        }
        if let Some(coat) = &self.clearcoat {
            let lobe = coat.f(wo, wi);
            let kept = 1.0 - coat.reflected(view);
            f = f.map(|v| lobe + kept * v);
        }
        f
    }

    /// f(wo, wi) for reflection, apart: f = coat + sheen + base_weight f_base(wo, wi),
    /// the clear coat's lobe (None without a coat), the sheen's (per lane) and what the
    /// base's is multiplied by under them ([`Layered::f`] sums the same terms). None
    /// across the surface.
    pub fn parts(&self, wo: Vec3, wi: Vec3) -> Option<LayeredParts<N>> {
        if wo.z * wi.z <= 0.0 {
            return None;
        }
        let (wo, wi) = Self::upper(wo, wi);
        let view = match self.mode {
            TransportMode::Radiance => wo,
            TransportMode::Importance => wi,
        };
        let (sheen, under_sheen) = match &self.sheen {
            Some(sheen) => {
                let lobe = sheen.f_white(wo, wi);
                let albedo = sheen.albedo(view.z);
                (
                    SampledSpectrum::from_fn(|i| sheen.color[i] * lobe),
                    SampledSpectrum::from_fn(|i| 1.0 - sheen.color[i] * albedo),
                )
            }
            None => (SampledSpectrum::splat(0.0), SampledSpectrum::splat(1.0)),
        };
        let (coat, kept) = match &self.clearcoat {
            Some(coat) => (Some(coat.f(wo, wi)), 1.0 - coat.reflected(view)),
            None => (None, 1.0),
        };
        Some(LayeredParts {
            coat,
            sheen: sheen * kept,
            base_weight: under_sheen * kept,
        })
    }

    /// What the base transmits through the surface (diffuse transmission), through the
    /// layers on the camera's side: each keeps what it does not reflect.
    fn f_through(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        if wo.z * wi.z >= 0.0 {
            return SampledSpectrum::splat(0.0);
        }
        let f = self.base.f(wo, wi);
        if f.is_black() {
            return f;
        }
        let camera = match self.mode {
            TransportMode::Radiance => wo,
            TransportMode::Importance => wi,
        };
        let view = Vec3::new(camera.x, camera.y, camera.z.abs());
        let coat = self.clearcoat.map_or(0.0, |c| c.reflected(view));
        SampledSpectrum::from_fn(|i| {
            let sheen = self.sheen.map_or(0.0, |s| s.color[i] * s.albedo(view.z));
            f[i] * (1.0 - coat) * (1.0 - sheen)
        })
    }

    /// The probabilities of sampling the coat and the sheen from `wo` (upper hemisphere):
    /// what each reflects.
    fn lobe_probabilities(&self, wo: Vec3) -> (f32, f32) {
        let coat = self.clearcoat.map_or(0.0, |c| c.reflected(wo));
        let sheen = self.sheen.map_or(0.0, |s| {
            let mean = s.color.0.iter().sum::<f32>() / N as f32;
            (1.0 - coat) * mean * s.albedo(wo.z)
        });
        (coat.min(0.95), sheen.min(0.95 - coat.min(0.95)))
    }

    /// The density of [`Layered::sample`] returning `wi`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let base = self.base.pdf(wo, wi);
        let (wo, wi) = Self::upper(wo, wi);
        let (p_coat, p_sheen) = self.lobe_probabilities(wo);
        if wi.z <= 0.0 {
            return (1.0 - p_coat - p_sheen) * base;
        }
        let coat = self.clearcoat.map_or(0.0, |c| c.pdf(wo, wi));
        p_coat * coat + p_sheen * cosine_hemisphere_pdf(wi) + (1.0 - p_coat - p_sheen) * base
    }

    /// Chooses the coat (its visible normals), the sheen (cosine) or the base (its own
    /// sampling) with `uc`, returning the mixture density.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        if wo.z == 0.0 || !wo.is_finite() {
            return None;
        }
        let below = wo.z < 0.0;
        let (up, _) = Self::upper(wo, wo);
        let (p_coat, p_sheen) = self.lobe_probabilities(up);
        let flip = |w: Vec3| if below { Vec3::new(w.x, w.y, -w.z) } else { w };
        let wi = if uc < p_coat {
            flip(self.clearcoat?.sample(up, u)?)
        } else if uc < p_coat + p_sheen {
            flip(cosine_hemisphere(u))
        } else {
            let rest = 1.0 - p_coat - p_sheen;
            let uc = ((uc - p_coat - p_sheen) / rest).clamp(0.0, 1.0 - f32::EPSILON);
            self.base.sample(wo, uc, u)?.wi
        };
        if wi.z * wo.z == 0.0 {
            return None;
        }
        let pdf = self.pdf(wo, wi);
        if !positive_finite(pdf) {
            return None;
        }
        Some(BsdfSample::smooth(wi, self.f(wo, wi), [pdf; N]))
    }
}
