use std::f32::consts::{FRAC_1_PI, PI};

use glam::{Vec2, Vec3};
use prism_sampling::lanes::real::{Real, V3};
use prism_sampling::warp::cosine_direction;
use prism_spectrum::SampledSpectrum;

use super::{BsdfSample, same_hemisphere};

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
        let (wi, pdf, exists) = lambertian_sample(wo.z, [u.x, u.y]);
        if !exists {
            return None;
        }
        let wi = Vec3::from(wi);
        Some(BsdfSample::smooth(wi, self.f(wo, wi), [pdf; N]))
    }

    /// The density of [`Diffuse::sample`] returning `wi` given `wo`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        lambertian_pdf(wo.z, wi.z)
    }
}

/// [`Diffuse::sample`]'s direction for one path or for lanes of them (`wo_z` the cosine of
/// the outgoing direction in the shading frame): a cosine-distributed direction on
/// `wo_z`'s side, its density, and where it exists (not at a grazing `wo` or a direction
/// of density zero). Written once over [`Real`]: the path tracer's one `f32`, or lanes
/// of them, the same operations lane by lane (`scene/tests/lambertian_lanes.rs`).
#[inline(always)]
pub fn lambertian_sample<R: Real>(wo_z: R, u: [R; 2]) -> (V3<R>, R, R::Mask) {
    let zero = R::splat(0.0);
    let mut wi = cosine_direction(u);
    wi.z = R::select(wo_z.lt(zero), -wi.z, wi.z);
    let pdf = wi.z.abs().max(zero) / R::splat(PI);
    (wi, pdf, pdf.ne(zero) & wo_z.ne(zero))
}

/// [`Diffuse::pdf`] of the cosines `wo_z` and `wi_z`, for one path or lanes of them.
#[inline(always)]
pub fn lambertian_pdf<R: Real>(wo_z: R, wi_z: R) -> R {
    let zero = R::splat(0.0);
    R::select(
        (wo_z * wi_z).gt(zero),
        wi_z.abs().max(zero) / R::splat(PI),
        zero,
    )
}
