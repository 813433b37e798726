//! Spectra that vary over a surface as Mitsuba 3's textures do: a bitmap of reflectances
//! upsampled texel by texel, a bitmap of plain numbers, or a checkerboard of two spectra.
//!
//! Mitsuba's spectral variants turn each texel of a colour bitmap into sigmoid
//! coefficients once (`srgb_model_fetch`, Jakob and Hanika 2019) and, at a lookup,
//! evaluate the spectra of the texels around the point and blend those
//! (`interpolate_spectral` in src/textures/bitmap.cpp): the spectrum between two texels is
//! the blend of their spectra, not the spectrum of their blended colour, as prism's glTF
//! textures have it ([`super::SpectralTexture`]). This type does what Mitsuba does, with
//! prism's coefficient table in place of Mitsuba's.

use std::sync::Arc;

use glam::{Affine2, Vec2};
use prism_spectrum::spectra::{Extrapolation, PiecewiseLinear};
use prism_spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};
use prism_upsample::sigmoid::{sigmoid_f32, sigmoid_polynomial_lanes};
use prism_upsample::{CoefficientTable, inverse_sigmoid};

use super::{SceneSpectrum, Texels};

/// A spectrum varying over a surface (by its first texture coordinate set).
#[derive(Debug, Clone)]
pub enum Pattern {
    /// Reflectances: each texel holds sigmoid coefficients (c0, c1, c2) in nanometres.
    Sigmoid {
        /// The coefficients, three channels.
        texels: Texels,
        /// The mean spectrum over the texels (what a spectrum without a point is).
        mean: Arc<PiecewiseLinear>,
    },
    /// One number per texel, the same at every wavelength.
    Scalar(Texels),
    /// `color0` and `color1` in alternate squares of the unit square mapped by `to_uv`
    /// (Mitsuba's `checkerboard`).
    Checkerboard {
        /// Where u and v are both in the same half of their unit interval.
        color0: SceneSpectrum,
        /// Elsewhere.
        color1: SceneSpectrum,
        /// Texture coordinates to the checkerboard's.
        to_uv: Affine2,
    },
}

impl Pattern {
    /// Reflectance spectra of `rgb` (three channels of linear sRGB, clamped into [0, 1]),
    /// upsampled texel by texel through `table`.
    pub fn reflectances(rgb: &Texels, table: &CoefficientTable) -> Result<Self, String> {
        if rgb.channels() != 3 {
            return Err("a reflectance bitmap needs three channels".into());
        }
        let texels = rgb.map(3, |t| reflectance_coefficients([t[0], t[1], t[2]], table))?;
        // The mean at every 5 nm of 360-830 nm, from (a stride of) the texels.
        let lambdas: Vec<f64> = (0..=94).map(|i| 360.0 + 5.0 * f64::from(i)).collect();
        let values: Vec<f64> = lambdas
            .iter()
            .map(|&l| {
                texels.mean_of(|c| {
                    let x = (f64::from(c[0]) * l + f64::from(c[1])) * l + f64::from(c[2]);
                    f64::from(sigmoid_f32(x as f32))
                })
            })
            .collect();
        let mean = PiecewiseLinear::new(lambdas, values, Extrapolation::Clamp)
            .map_err(|e| e.to_string())?;
        Ok(Pattern::Sigmoid {
            texels,
            mean: Arc::new(mean),
        })
    }

    /// The values at texture coordinates `uv`, at the package's wavelengths (finite).
    pub fn at<const N: usize>(
        &self,
        uv: Vec2,
        wavelengths: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        match self {
            Pattern::Sigmoid { texels, .. } => {
                let lambdas = wavelengths.lambdas();
                texels.filtered(uv, |c| {
                    SampledSpectrum(sigmoid_polynomial_lanes([c[0], c[1], c[2]], lambdas))
                })
            }
            Pattern::Scalar(texels) => SampledSpectrum::splat(texels.scalar(uv)),
            Pattern::Checkerboard {
                color0,
                color1,
                to_uv,
            } => {
                // Mitsuba's `eval`: color0 where both coordinates fall in the same half.
                if same_halves(*to_uv, uv) {
                    color0.at_uv(uv, wavelengths)
                } else {
                    color1.at_uv(uv, wavelengths)
                }
            }
        }
    }
}

/// The sigmoid coefficients of a linear sRGB reflectance (clamped into [0, 1]): the
/// table's, or for greys (black included, which has no sigmoid) a constant exactly, as
/// prism's other colour textures have them. The constant's c2 is S^-1 of the grey,
/// bounded by +-1e30, where S in f32 is exactly 0 or 1 as at +-inf.
fn reflectance_coefficients(rgb: [f32; 3], table: &CoefficientTable) -> [f32; 3] {
    let rgb = rgb.map(|c| if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) });
    if rgb[0] == rgb[1] && rgb[1] == rgb[2] {
        let c2 = inverse_sigmoid(f64::from(rgb[0])).clamp(-1e30, 1e30);
        return [0.0, 0.0, c2 as f32];
    }
    table
        .lookup(rgb.map(f64::from))
        .coefficients
        .map(|c| c as f32)
}

/// Whether u and v of `to_uv(uv)` are both above, or both not above, the middle of their
/// unit cell.
pub(crate) fn same_halves(to_uv: Affine2, uv: Vec2) -> bool {
    let p = to_uv.transform_point2(uv);
    let f = p - p.floor();
    (f.x > 0.5) == (f.y > 0.5)
}

impl Spectrum for Pattern {
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        match self {
            Pattern::Sigmoid { mean, .. } => mean.evaluate(lambda_nm),
            Pattern::Scalar(texels) => texels.mean_of(|t| f64::from(t[0])),
            Pattern::Checkerboard { color0, color1, .. } => {
                0.5 * (color0.evaluate(lambda_nm) + color1.evaluate(lambda_nm))
            }
        }
    }

    fn max_value(&self) -> f64 {
        match self {
            Pattern::Sigmoid { .. } => 1.0,
            Pattern::Scalar(texels) => texels.data().iter().fold(0.0f32, |m, v| m.max(*v)).into(),
            Pattern::Checkerboard { color0, color1, .. } => {
                color0.max_value().max(color1.max_value())
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::textures::{Filter, Wrap};

    fn wavelengths() -> SampledWavelengths<4> {
        SampledWavelengths::new([450.0, 520.0, 600.0, 680.0], [0.01; 4]).unwrap()
    }

    /// Between two texels the spectrum is the blend of theirs, exactly: not the spectrum
    /// of the blended colour.
    #[test]
    fn bitmaps_blend_texel_spectra() {
        let table = CoefficientTable::shipped(prism_spectrum::color::RgbSpaceId::Srgb)
            .expect("the shipped table");
        let rgb = Texels::new(
            2,
            1,
            3,
            vec![0.8, 0.1, 0.1, 0.1, 0.1, 0.8],
            Wrap::Clamp,
            Filter::Bilinear,
            Affine2::IDENTITY,
        )
        .unwrap();
        let pattern = Pattern::reflectances(&rgb, &table).unwrap();
        let w = wavelengths();
        let left = pattern.at(Vec2::new(0.25, 0.5), &w);
        let right = pattern.at(Vec2::new(0.75, 0.5), &w);
        let middle = pattern.at(Vec2::new(0.5, 0.5), &w);
        for i in 0..4 {
            assert!((middle[i] - 0.5 * (left[i] + right[i])).abs() < 1e-6);
        }
        // Red reflects more at 680 nm than at 450 nm; blue the other way.
        assert!(left[3] > left[0] && right[0] > right[3]);
        // Greys are constants, black and white exactly.
        for (grey, expected) in [(0.0, 0.0), (1.0, 1.0), (0.5, 0.5)] {
            let c = reflectance_coefficients([grey; 3], &table);
            let s = sigmoid_polynomial_lanes(c, w.lambdas());
            assert!(
                s.iter().all(|v| (v - expected).abs() < 1e-6),
                "{grey}: {s:?}"
            );
        }
        assert!((0.0..=1.0).contains(&pattern.evaluate(550.0)));
    }

    /// The checkerboard alternates per half cell of its transformed coordinates.
    #[test]
    fn checkerboards_alternate() {
        let board = Pattern::Checkerboard {
            color0: SceneSpectrum::Constant(0.4),
            color1: SceneSpectrum::Constant(0.2),
            to_uv: Affine2::from_scale(Vec2::splat(2.0)),
        };
        let w = wavelengths();
        let at = |u: f32, v: f32| board.at(Vec2::new(u, v), &w)[0];
        assert_eq!(at(0.1, 0.1), 0.4);
        assert_eq!(at(0.3, 0.1), 0.2);
        assert_eq!(at(0.3, 0.3), 0.4);
        assert_eq!(at(0.6, 0.1), 0.4);
        assert!((board.evaluate(500.0) - 0.3).abs() < 1e-12);
    }
}
