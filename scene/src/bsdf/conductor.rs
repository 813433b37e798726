use glam::Vec3;
use prism_spectrum::SampledSpectrum;

use super::{BsdfSample, cos_theta};

/// Unpolarized Fresnel reflectance of a conductor with complex index eta + i k (relative
/// to the outside medium) at cos(theta_i), from the complex form of Fresnel's equations
/// (*PBR* 4th ed. §9.4.1): r_s = (cos_i - n cos_t) / (cos_i + n cos_t),
/// r_p = (n cos_i - cos_t) / (n cos_i + cos_t) with n complex and
/// cos_t = sqrt(1 - sin_i^2 / n^2). Values in [0, 1].
pub fn fresnel_conductor(cos_i: f32, eta: f32, k: f32) -> f32 {
    reflectance(
        f64::from(cos_i.abs().min(1.0)),
        f64::from(eta),
        f64::from(k),
    )
}

/// [`fresnel_conductor`] for every lane at one cosine: the same values to the bit, the
/// lanes computed side by side (the body has no branch, so the compiler vectorizes the
/// square roots and divisions; the conductor's Fresnel was a noticeable share of the
/// glossy box's time).
pub fn fresnel_conductor_lanes<const N: usize>(
    cos_i: f32,
    eta: &SampledSpectrum<N>,
    k: &SampledSpectrum<N>,
) -> SampledSpectrum<N> {
    let c = f64::from(cos_i.abs().min(1.0));
    SampledSpectrum::from_fn(|i| reflectance(c, f64::from(eta[i]), f64::from(k[i])))
}

/// The body of [`fresnel_conductor`], without branches: special cases are selected at
/// the end.
#[inline(always)]
fn reflectance(c: f64, a: f64, b: f64) -> f32 {
    // n^2 = (a^2 - b^2) + 2ab i; sin^2 / n^2 = s2 * conj(n^2) / |n^2|^2.
    let s2 = 1.0 - c * c;
    let (n2r, n2i) = (a * a - b * b, 2.0 * a * b);
    let denominator = n2r * n2r + n2i * n2i;
    let (qr, qi) = (1.0 - s2 * n2r / denominator, s2 * n2i / denominator);
    // cos_t = sqrt(q), principal branch.
    let modulus = (qr * qr + qi * qi).sqrt();
    let ct_r = ((modulus + qr) / 2.0).max(0.0).sqrt();
    let ct_i_magnitude = ((modulus - qr) / 2.0).max(0.0).sqrt();
    let ct_i = if qi < 0.0 {
        -ct_i_magnitude
    } else {
        ct_i_magnitude
    };
    let mul = |(xr, xi): (f64, f64), (yr, yi): (f64, f64)| (xr * yr - xi * yi, xr * yi + xi * yr);
    let norm2 = |(xr, xi): (f64, f64)| xr * xr + xi * xi;
    let n_cos_t = mul((a, b), (ct_r, ct_i));
    let rs = norm2((c - n_cos_t.0, -n_cos_t.1)) / norm2((c + n_cos_t.0, n_cos_t.1));
    let n_cos_i = (a * c, b * c);
    let rp =
        norm2((n_cos_i.0 - ct_r, n_cos_i.1 - ct_i)) / norm2((n_cos_i.0 + ct_r, n_cos_i.1 + ct_i));
    let r = 0.5 * (rs + rp);
    if denominator == 0.0 || !r.is_finite() {
        1.0
    } else {
        r.clamp(0.0, 1.0) as f32
    }
}

/// A smooth conductor (perfect mirror) with a complex index per lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmoothConductor<const N: usize> {
    /// Real part of the index per lane.
    pub eta: SampledSpectrum<N>,
    /// Extinction coefficient per lane.
    pub k: SampledSpectrum<N>,
}

impl<const N: usize> SmoothConductor<N> {
    /// The mirror direction with each lane's Fresnel reflectance (wavelength-independent).
    pub fn sample(&self, wo: Vec3) -> Option<BsdfSample<N>> {
        let cos_o = cos_theta(wo);
        if cos_o == 0.0 || !wo.is_finite() {
            return None;
        }
        let wi = Vec3::new(-wo.x, -wo.y, wo.z);
        let f = fresnel_conductor_lanes(cos_o, &self.eta, &self.k) / cos_o.abs();
        Some(BsdfSample::specular(wi, f, [1.0; N]))
    }
}
