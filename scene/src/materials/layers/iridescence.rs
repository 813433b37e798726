//! `KHR_materials_iridescence` as a material describes it: a thin film over the surface,
//! its strength and thickness possibly textured; at a hit it becomes the
//! [`Iridescence`](crate::bsdf::Iridescence) of the BSDF, solved per wavelength.

use std::sync::Arc;

use prism_spectrum::SampledWavelengths;

use crate::bsdf::{Iridescence, ThinFilm};
use crate::textures::{RgbTexture, SceneSpectrum, TexCoords};

/// A material's thin film.
#[derive(Debug, Clone)]
pub struct IridescenceDesc {
    /// `iridescenceFactor`, in [0, 1] (default 0: no film).
    pub factor: f32,
    /// Its texture (linear, the red channel multiplies the factor).
    pub factor_texture: Option<Arc<RgbTexture>>,
    /// `iridescenceIor`, the film's index (default 1.3).
    pub ior: f32,
    /// A measured spectral index replacing it (`PRISM_spectral`'s `film_ior`).
    pub ior_spectrum: Option<SceneSpectrum>,
    /// `iridescenceThicknessMinimum` in nanometres (default 100).
    pub thickness_min_nm: f32,
    /// `iridescenceThicknessMaximum` in nanometres (default 400).
    pub thickness_max_nm: f32,
    /// `iridescenceThicknessTexture` (linear, the green channel mixes minimum to
    /// maximum); without it the film is `thickness_max_nm` thick everywhere, as the
    /// extension says.
    pub thickness_texture: Option<Arc<RgbTexture>>,
}

impl IridescenceDesc {
    /// The film at texture coordinates `at`, for a path at `wavelengths`.
    pub fn at<const N: usize>(
        &self,
        at: &TexCoords,
        wavelengths: &SampledWavelengths<N>,
    ) -> Iridescence<N> {
        let factor = match &self.factor_texture {
            Some(t) => self.factor * t.sample_at(at)[0],
            None => self.factor,
        };
        let thickness_nm = match &self.thickness_texture {
            Some(t) => {
                let g = t.sample_at(at)[1];
                self.thickness_min_nm + g * (self.thickness_max_nm - self.thickness_min_nm)
            }
            None => self.thickness_max_nm,
        };
        Iridescence {
            factor,
            film: ThinFilm {
                ior: self.ior,
                thickness_nm,
            },
            lambdas: *wavelengths.lambdas(),
            iors: self.ior_spectrum.as_ref().map(|s| s.at(wavelengths).0),
        }
    }

    /// Whether a texture varies it.
    pub fn textured(&self) -> bool {
        self.factor_texture.is_some() || self.thickness_texture.is_some()
    }
}
