//! Vertex colours blended as spectra: each corner's colour upsampled, the three spectra
//! weighted by the hit's barycentrics. Mitsuba 3's spectral variants interpolate a mesh's
//! colour attribute so (`Mesh::interpolate_attribute`: the corners' sigmoid coefficients
//! are each evaluated, then blended), where glTF's `COLOR_0` blends the RGB first. The
//! sigmoid model is not linear in RGB, so the two differ inside a triangle whose corners
//! differ (by little in XYZ, by more at single wavelengths).

use glam::{Vec3, Vec4};
use prism_spectrum::{SampledSpectrum, SampledWavelengths};
use prism_upsample::CoefficientTable;

use crate::textures::reflectance_lanes;

/// The reflectance tint at `p` on the triangle `v` whose corners have colours `colors`.
pub(super) fn blended_tint<const N: usize>(
    v: &[Vec3; 3],
    colors: &[Vec4; 3],
    p: Vec3,
    table: &CoefficientTable,
    wavelengths: &SampledWavelengths<N>,
) -> SampledSpectrum<N> {
    let b = barycentrics(v, p);
    let mut sum = SampledSpectrum::splat(0.0);
    for (weight, color) in b.iter().zip(colors) {
        if *weight > 0.0 {
            let lanes = reflectance_lanes(color.truncate().to_array(), table, wavelengths);
            sum += lanes * *weight;
        }
    }
    sum
}

/// The barycentrics of `p` on `v`, from the sub-triangles' areas (the first corner's
/// alone for a degenerate triangle).
fn barycentrics(v: &[Vec3; 3], p: Vec3) -> [f32; 3] {
    let area = |a: Vec3, b: Vec3, c: Vec3| (b - a).cross(c - a).length();
    let total = area(v[0], v[1], v[2]);
    if total.is_nan() || total <= 0.0 {
        return [1.0, 0.0, 0.0];
    }
    let b1 = (area(v[0], p, v[2]) / total).clamp(0.0, 1.0);
    let b2 = (area(v[0], v[1], p) / total).clamp(0.0, 1.0 - b1);
    [1.0 - b1 - b2, b1, b2]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn barycentrics_of_corners_and_centre() {
        let v = [Vec3::ZERO, Vec3::X, Vec3::Y];
        assert_eq!(barycentrics(&v, Vec3::X), [0.0, 1.0, 0.0]);
        let c = barycentrics(&v, Vec3::new(1.0 / 3.0, 1.0 / 3.0, 0.0));
        assert!(c.iter().all(|b| (b - 1.0 / 3.0).abs() < 1e-6), "{c:?}");
        assert_eq!(barycentrics(&[Vec3::ZERO; 3], Vec3::X), [1.0, 0.0, 0.0]);
    }
}
