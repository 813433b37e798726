use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};
use prism_sampling::warp::{cosine_hemisphere, cosine_hemisphere_pdf};
use prism_spectrum::SampledSpectrum;

use super::{BsdfSample, cos_theta, same_hemisphere};

/// Lambertian reflection: f = R / pi in the hemisphere of `wo`, sampled with density
/// cos(theta) / pi, so a sample's weight f cos / pdf is exactly R.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Diffuse<const N: usize> {
    /// Reflectance per lane, clamped into [0, 1] (energy conservation).
    pub reflectance: SampledSpectrum<N>,
}

impl<const N: usize> Diffuse<N> {
    /// A Lambertian BSDF; reflectance values outside [0, 1] (and NaN) are clamped.
    pub fn new(reflectance: SampledSpectrum<N>) -> Self {
        Self {
            reflectance: reflectance.map(|r| if r.is_nan() { 0.0 } else { r.clamp(0.0, 1.0) }),
        }
    }

    /// f(wo, wi): R / pi when both directions are on the same side, else 0.
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        if same_hemisphere(wo, wi) {
            self.reflectance * FRAC_1_PI
        } else {
            SampledSpectrum::splat(0.0)
        }
    }

    /// A cosine-distributed direction on `wo`'s side.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample<N>> {
        let mut wi = cosine_hemisphere(u);
        if wo.z < 0.0 {
            wi.z = -wi.z;
        }
        let pdf = cosine_hemisphere_pdf(Vec3::new(wi.x, wi.y, wi.z.abs()));
        if pdf == 0.0 || cos_theta(wo) == 0.0 {
            return None;
        }
        Some(BsdfSample::smooth(wi, self.f(wo, wi), [pdf; N]))
    }

    /// The density of [`Diffuse::sample`] returning `wi` given `wo`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if same_hemisphere(wo, wi) {
            cosine_hemisphere_pdf(Vec3::new(wi.x, wi.y, wi.z.abs()))
        } else {
            0.0
        }
    }
}
