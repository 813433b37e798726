//! A grid of spectra: Mitsuba 3's `gridvolume` of RGB values as its spectral variants read
//! it (`src/volumes/grid.cpp` of mitsuba-renderer/mitsuba3). Each voxel's colour is kept
//! as a scale, 2 max(r, g, b), and the sigmoid polynomial fitted to the colour over that
//! scale (a reflectance whose largest channel is 1/2), so that any positive colour, however
//! bright, is a smooth spectrum: the scale times a sigmoid in [0, 1].
//!
//! Between voxel centres the voxels' spectra and their scales are each blended with the
//! grid's weights, and the two blends multiplied, as Mitsuba does. That is not the blend of
//! the voxels' values (the two differ where neighbouring scales differ); a render matches
//! Mitsuba's only with Mitsuba's rule.

use glam::Vec3;
use prism_spectrum::{SampledSpectrum, SampledWavelengths};
use prism_upsample::sigmoid::sigmoid_polynomial_lanes;

use super::grid::Grid;

/// Spectra on a regular grid over an axis-aligned box.
#[derive(Debug, Clone)]
pub struct SpectralGrid {
    /// The scale of each voxel: also the grid's box, filter and majorants (a spectrum is at
    /// most its scale, a sigmoid being at most 1).
    scales: Grid,
    /// Per voxel, the sigmoid polynomial's coefficients in nanometres (c0, c1, c2 of
    /// S(c0 l^2 + c1 l + c2)); c2 = -inf is black.
    coefficients: Vec<[f32; 3]>,
}

impl SpectralGrid {
    /// The spectra `scales[i] S(coefficients[i])` on `scales`' grid (its box and filter).
    /// There must be one set of coefficients per voxel, c0 and c1 finite and c2 not NaN.
    pub fn new(scales: Grid, coefficients: Vec<[f32; 3]>) -> Result<Self, String> {
        let r = scales.resolution();
        let voxels = u64::from(r.x) * u64::from(r.y) * u64::from(r.z);
        if coefficients.len() as u64 != voxels {
            return Err(format!(
                "{} sets of coefficients for a grid of {} x {} x {} voxels",
                coefficients.len(),
                r.x,
                r.y,
                r.z
            ));
        }
        if let Some((i, c)) = coefficients
            .iter()
            .enumerate()
            .find(|(_, c)| !(c[0].is_finite() && c[1].is_finite() && !c[2].is_nan()))
        {
            return Err(format!(
                "voxel {i}'s sigmoid coefficients {c:?} are not finite"
            ));
        }
        Ok(Self {
            scales,
            coefficients,
        })
    }

    /// The grid of scales: the box, the filter, and the bounds tracking steps through.
    pub fn scales(&self) -> &Grid {
        &self.scales
    }

    /// The largest value at any wavelength, or more.
    pub fn max_value(&self) -> f32 {
        self.scales.max_value()
    }

    /// The same spectra over another box.
    pub fn placed(mut self, min: Vec3, max: Vec3) -> Result<Self, String> {
        self.scales = self.scales.placed(min, max)?;
        Ok(self)
    }

    /// The spectrum at `p` at `wavelengths`: 0 outside the box.
    #[inline]
    pub fn lookup<const N: usize>(
        &self,
        p: Vec3,
        wavelengths: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        match self.scales.unit_inside(p) {
            Some(unit) => self.at_unit(unit, wavelengths),
            None => SampledSpectrum::splat(0.0),
        }
    }

    /// The spectrum at `p` clamped into the box (the faces' values extend outwards, as
    /// Mitsuba's clamped wrapping).
    #[inline]
    pub fn lookup_clamped<const N: usize>(
        &self,
        p: Vec3,
        wavelengths: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        self.at_unit(self.scales.clamped_unit(p), wavelengths)
    }

    fn at_unit<const N: usize>(
        &self,
        unit: Vec3,
        wavelengths: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let stencil = self.scales.stencil(unit);
        let mut spectrum = [0.0f32; N];
        let mut scale = 0.0f32;
        for (&voxel, &w) in stencil.voxels.iter().zip(&stencil.weights) {
            if w == 0.0 {
                continue;
            }
            scale += w * self.scales.value(voxel);
            let s =
                sigmoid_polynomial_lanes(self.coefficients[voxel as usize], wavelengths.lambdas());
            for (out, s) in spectrum.iter_mut().zip(s) {
                *out += w * s;
            }
        }
        SampledSpectrum::from_fn(|i| spectrum[i] * scale)
    }
}

#[cfg(test)]
mod tests {
    use glam::UVec3;

    use super::*;
    use crate::medium::grid::Filter;

    fn wavelengths() -> SampledWavelengths<4> {
        SampledWavelengths::new([400.0, 500.0, 600.0, 700.0], [1.0; 4]).unwrap()
    }

    /// Two voxels along x over [0, 2] x [0, 1]^2: a flat 0.25 at scale 4, and a flat 0.5
    /// at scale 1 (constant sigmoids: c2 = S^-1(v)).
    fn pair(filter: Filter) -> SpectralGrid {
        let scales = Grid::new(
            UVec3::new(2, 1, 1),
            Vec3::ZERO,
            Vec3::new(2.0, 1.0, 1.0),
            vec![4.0, 1.0],
        )
        .unwrap()
        .with_filter(filter);
        let flat = |v: f64| [0.0, 0.0, prism_upsample::inverse_sigmoid(v) as f32];
        SpectralGrid::new(scales, vec![flat(0.25), flat(0.5)]).unwrap()
    }

    /// At the voxel centres each voxel's value; halfway, the blend of the spectra times
    /// the blend of the scales (0.375 x 2.5), not the blend of the values (1.5 / 2).
    #[test]
    fn blends_spectra_and_scales_apart_as_mitsuba() {
        let g = pair(Filter::Trilinear);
        let w = wavelengths();
        let at = |x: f32| g.lookup(Vec3::new(x, 0.5, 0.5), &w)[1];
        assert!((at(0.5) - 1.0).abs() < 1e-5, "{}", at(0.5));
        assert!((at(1.5) - 0.5).abs() < 1e-5, "{}", at(1.5));
        assert!((at(1.0) - 0.375 * 2.5).abs() < 1e-5, "{}", at(1.0));
        // Outside the box: 0, or the face's value when clamped.
        assert_eq!(g.lookup(Vec3::new(2.5, 0.5, 0.5), &w)[0], 0.0);
        let clamped = g.lookup_clamped(Vec3::new(2.5, 0.5, 0.5), &w)[0];
        assert!((clamped - 0.5).abs() < 1e-5, "{clamped}");
        assert!(g.max_value() >= 1.0);
    }

    #[test]
    fn nearest_takes_the_voxel_the_point_is_in() {
        let g = pair(Filter::Nearest);
        let w = wavelengths();
        let at = |x: f32| g.lookup(Vec3::new(x, 0.5, 0.5), &w)[2];
        assert!((at(0.99) - 1.0).abs() < 1e-5);
        assert!((at(1.01) - 0.5).abs() < 1e-5);
    }

    #[test]
    fn black_voxels_and_bad_coefficients() {
        let scales = Grid::new(UVec3::ONE, Vec3::ZERO, Vec3::ONE, vec![0.0]).unwrap();
        let black = SpectralGrid::new(scales.clone(), vec![[0.0, 0.0, f32::NEG_INFINITY]]);
        let v = black.unwrap().lookup(Vec3::splat(0.5), &wavelengths());
        assert!(v.is_finite() && v.is_black(), "{v:?}");
        assert!(SpectralGrid::new(scales.clone(), vec![[f32::NAN, 0.0, 0.0]]).is_err());
        assert!(SpectralGrid::new(scales, vec![]).is_err());
    }
}
