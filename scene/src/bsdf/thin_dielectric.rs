//! A thin dielectric sheet (glTF's thin-walled transmission: `KHR_materials_transmission`
//! without `KHR_materials_volume`): light crossing it leaves parallel to how it came in, so
//! a window pane or a leaf modelled as one surface transmits without bending.

use glam::{Vec2, Vec3};
use prism_sampling::distribution::positive_finite;
use prism_spectrum::SampledSpectrum;

use super::microfacet::Ggx;
use super::{BsdfSample, fresnel_dielectric};

/// A sheet of relative index `eta` per lane: the slab's reflectance summed over its
/// internal reflections, R' = R + T^2 R / (1 - R^2) = 2R / (1 + R), and T' = 1 - R' (no
/// absorption; *PBR* 4th ed. §9.5.3). Smooth, reflection and transmission are deltas
/// (transmission straight through); rough, the reflection is the GGX lobe with R' and the
/// transmission the same lobe mirrored through the sheet with T', so that roughness blurs
/// what is seen through it as much as what it reflects (both lobes single-scattering, as
/// prism's other microfacet lobes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThinDielectric<const N: usize> {
    /// The microfacet distribution.
    pub distribution: Ggx,
    /// Relative index per lane.
    pub eta: [f32; N],
}

/// The sheet's reflectance at cos `cos` for index `eta`.
pub(crate) fn sheet_reflectance(cos: f32, eta: f32) -> f32 {
    // A non-finite or non-positive index is no interface, as for the smooth dielectric.
    let eta = if eta.is_finite() && eta > 0.0 {
        eta
    } else {
        1.0
    };
    let r = fresnel_dielectric(cos.abs().min(1.0), eta);
    if !r.is_finite() {
        return 0.0;
    }
    if r >= 1.0 { 1.0 } else { 2.0 * r / (1.0 + r) }
}

fn mirrored(w: Vec3) -> Vec3 {
    Vec3::new(w.x, w.y, -w.z)
}

impl<const N: usize> ThinDielectric<N> {
    /// f(wo, wi) per lane (0 for a smooth sheet, whose lobes are deltas).
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        match self.lobe(wo, wi) {
            Some((value, cos_h, transmitted)) => SampledSpectrum::from_fn(|i| {
                let r = sheet_reflectance(cos_h, self.eta[i]);
                value * if transmitted { 1.0 - r } else { r }
            }),
            None => SampledSpectrum::splat(0.0),
        }
    }

    /// The microfacet lobe D G / (4 |cos_o cos_i|) at (wo, wi) with wi mirrored back to
    /// wo's side when it crossed, the cosine at the microfacet, and whether it crossed.
    fn lobe(&self, wo: Vec3, wi: Vec3) -> Option<(f32, f32, bool)> {
        if self.distribution.effectively_smooth() || wo.z == 0.0 || wi.z == 0.0 {
            return None;
        }
        let transmitted = wo.z * wi.z < 0.0;
        let wi = if transmitted { mirrored(wi) } else { wi };
        let wm = (wo + wi).try_normalize()?;
        let wm = if wm.z < 0.0 { -wm } else { wm };
        let d = &self.distribution;
        let value = d.d(wm) * d.g(wo, wi) / (4.0 * (wo.z * wi.z).abs());
        value
            .is_finite()
            .then_some((value, wo.dot(wm).abs(), transmitted))
    }

    /// The density of [`ThinDielectric::sample`] returning `wi` (the hero's).
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some((_, cos_h, transmitted)) = self.lobe(wo, wi) else {
            return 0.0;
        };
        let wi = if transmitted { mirrored(wi) } else { wi };
        let Some(wm) = (wo + wi).try_normalize() else {
            return 0.0;
        };
        let wm = if wm.dot(wo) < 0.0 { -wm } else { wm };
        let r = sheet_reflectance(cos_h, self.eta[0]);
        let choice = if transmitted { 1.0 - r } else { r };
        self.distribution.d_visible(wo, wm) / (4.0 * cos_h) * choice
    }

    /// Reflects about a visible normal, or crosses (the reflection mirrored), by the
    /// hero's sheet reflectance (`uc`); smooth: the two deltas.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        if wo.z == 0.0 || !wo.is_finite() {
            return None;
        }
        if self.distribution.effectively_smooth() {
            let cos = wo.z.abs();
            let reflectance = self.eta.map(|e| sheet_reflectance(cos, e));
            let reflect = uc < reflectance[0];
            let choice = reflectance.map(|r| if reflect { r } else { 1.0 - r });
            let wi = if reflect {
                Vec3::new(-wo.x, -wo.y, wo.z)
            } else {
                -wo
            };
            return Some(BsdfSample::specular(
                wi,
                SampledSpectrum(choice) / cos,
                choice,
            ));
        }
        let wm = self.distribution.sample_visible_normal(wo, u);
        let reflected = 2.0 * wo.dot(wm) * wm - wo;
        if reflected.z * wo.z <= 0.0 {
            return None;
        }
        let r = sheet_reflectance(wo.dot(wm), self.eta[0]);
        let wi = if uc < r {
            reflected
        } else {
            mirrored(reflected)
        };
        let pdf = self.pdf(wo, wi);
        if !positive_finite(pdf) {
            return None;
        }
        Some(BsdfSample::smooth(wi, self.f(wo, wi), [pdf; N]))
    }
}
