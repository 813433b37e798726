//! Mitsuba's `principled` and `principledthin` as materials: their parameters as
//! spectra and numbers that may vary over the surface (Mitsuba's textures), read at a hit
//! into [`Principled`] or [`PrincipledThin`].

use glam::{Vec2, Vec3};
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use super::SurfaceFrame;
use crate::bsdf::{
    Bsdf, Principled, PrincipledParams, PrincipledRates, PrincipledThin, PrincipledThinParams,
    PrincipledThinRates, TransportMode,
};
use crate::textures::{FloatTexture, SceneSpectrum, TexCoords};

/// Mitsuba's `principled`: its base colour and numbers (each constant or a texture).
#[derive(Debug, Clone)]
pub struct PrincipledDesc {
    /// `base_color`.
    pub base_color: SceneSpectrum,
    /// `roughness`.
    pub roughness: FloatTexture,
    /// `anisotropic`.
    pub anisotropic: FloatTexture,
    /// `metallic`.
    pub metallic: FloatTexture,
    /// `spec_trans`.
    pub spec_trans: FloatTexture,
    /// `spec_tint`.
    pub spec_tint: FloatTexture,
    /// `sheen`.
    pub sheen: FloatTexture,
    /// `sheen_tint`.
    pub sheen_tint: FloatTexture,
    /// `flatness`.
    pub flatness: FloatTexture,
    /// `clearcoat`.
    pub clearcoat: FloatTexture,
    /// `clearcoat_gloss`.
    pub clearcoat_gloss: FloatTexture,
    /// The relative index (`eta`, or of `specular`).
    pub eta: f32,
    /// The sampling rates.
    pub rates: PrincipledRates,
}

/// Mitsuba's `principledthin`.
#[derive(Debug, Clone)]
pub struct PrincipledThinDesc {
    /// `base_color`.
    pub base_color: SceneSpectrum,
    /// `roughness`.
    pub roughness: FloatTexture,
    /// `anisotropic`.
    pub anisotropic: FloatTexture,
    /// `spec_trans`.
    pub spec_trans: FloatTexture,
    /// `spec_tint`.
    pub spec_tint: FloatTexture,
    /// `sheen`.
    pub sheen: FloatTexture,
    /// `sheen_tint`.
    pub sheen_tint: FloatTexture,
    /// `flatness`.
    pub flatness: FloatTexture,
    /// `diff_trans` (0 to 2).
    pub diff_trans: FloatTexture,
    /// `eta`, the sheet's index.
    pub eta: FloatTexture,
    /// The sampling rates.
    pub rates: PrincipledThinRates,
}

/// The base colour at a hit and Mitsuba's luminance of it.
fn base<const N: usize>(
    s: &SceneSpectrum,
    at: &TexCoords,
    wavelengths: &SampledWavelengths<N>,
    tint: Option<SampledSpectrum<N>>,
) -> (SampledSpectrum<N>, f32) {
    let mut b = s.at_uv(*at, wavelengths);
    if let Some(t) = tint {
        b *= t;
    }
    let lum = crate::bsdf::principled_luminance(&b.0, wavelengths.lambdas());
    (b, lum)
}

/// The anisotropy's axis in the local frame: the surface's tangent where it has one.
fn axis(frame: Option<&SurfaceFrame>) -> Vec2 {
    frame
        .and_then(|f| {
            let (t, _) = f.tangents()?;
            let l: Vec3 = f.frame.to_local(t);
            Some(Vec2::new(l.x, l.y))
        })
        .unwrap_or(Vec2::X)
}

impl PrincipledDesc {
    /// Whether light can cross it (a transmissive share anywhere).
    pub fn transmissive(&self) -> bool {
        self.spec_trans.constant() != Some(0.0) && self.metallic.constant() != Some(1.0)
    }

    /// Whether any parameter varies over the surface.
    pub fn textured(&self) -> bool {
        self.base_color.varies()
            || [
                &self.roughness,
                &self.anisotropic,
                &self.metallic,
                &self.spec_trans,
                &self.spec_tint,
                &self.sheen,
                &self.sheen_tint,
                &self.flatness,
                &self.clearcoat,
                &self.clearcoat_gloss,
            ]
            .iter()
            .any(|t| t.constant().is_none())
    }

    /// Whether its lobe is anisotropic somewhere (and so needs the surface's tangent).
    pub fn anisotropic(&self) -> bool {
        self.anisotropic.constant() != Some(0.0)
    }

    /// The BSDF at a hit.
    pub fn bsdf<const N: usize>(
        &self,
        at: &TexCoords,
        wavelengths: &SampledWavelengths<N>,
        mode: TransportMode,
        tint: Option<SampledSpectrum<N>>,
        frame: Option<&SurfaceFrame>,
    ) -> Bsdf<'static, N> {
        let uv = at.uv[0];
        let (b, lum) = base(&self.base_color, at, wavelengths, tint);
        let p = PrincipledParams {
            roughness: self.roughness.value(uv),
            anisotropic: self.anisotropic.value(uv),
            metallic: self.metallic.value(uv),
            spec_trans: self.spec_trans.value(uv),
            spec_tint: self.spec_tint.value(uv),
            sheen: self.sheen.value(uv),
            sheen_tint: self.sheen_tint.value(uv),
            flatness: self.flatness.value(uv),
            clearcoat: self.clearcoat.value(uv),
            clearcoat_gloss: self.clearcoat_gloss.value(uv),
            eta: self.eta,
        };
        let bsdf = Principled::new(b, lum, p, self.rates, mode).with_axis(axis(frame));
        Bsdf::Principled(Box::new(bsdf))
    }
}

impl PrincipledThinDesc {
    /// Whether light can cross it.
    pub fn transmissive(&self) -> bool {
        self.spec_trans.constant() != Some(0.0) || self.diff_trans.constant() != Some(0.0)
    }

    /// Whether any parameter varies over the surface.
    pub fn textured(&self) -> bool {
        self.base_color.varies()
            || [
                &self.roughness,
                &self.anisotropic,
                &self.spec_trans,
                &self.spec_tint,
                &self.sheen,
                &self.sheen_tint,
                &self.flatness,
                &self.diff_trans,
                &self.eta,
            ]
            .iter()
            .any(|t| t.constant().is_none())
    }

    /// Whether its lobes are anisotropic somewhere.
    pub fn anisotropic(&self) -> bool {
        self.anisotropic.constant() != Some(0.0)
    }

    /// The BSDF at a hit.
    pub fn bsdf<const N: usize>(
        &self,
        at: &TexCoords,
        wavelengths: &SampledWavelengths<N>,
        tint: Option<SampledSpectrum<N>>,
        frame: Option<&SurfaceFrame>,
    ) -> Bsdf<'static, N> {
        let uv = at.uv[0];
        let (b, lum) = base(&self.base_color, at, wavelengths, tint);
        let p = PrincipledThinParams {
            roughness: self.roughness.value(uv),
            anisotropic: self.anisotropic.value(uv),
            spec_trans: self.spec_trans.value(uv),
            spec_tint: self.spec_tint.value(uv),
            sheen: self.sheen.value(uv),
            sheen_tint: self.sheen_tint.value(uv),
            flatness: self.flatness.value(uv),
            diff_trans: self.diff_trans.value(uv),
            eta: self.eta.value(uv),
        };
        let bsdf = PrincipledThin::new(b, lum, p, self.rates).with_axis(axis(frame));
        Bsdf::PrincipledThin(Box::new(bsdf))
    }
}
