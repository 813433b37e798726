use glam::Vec3;
use prism_spectrum::SampledSpectrum;

use super::BsdfSample;

/// What a polarizing sheet does to light crossing it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SheetElement<const N: usize> {
    /// An ideal linear polarizer: light polarized along the axis passes (times the
    /// sheet's transmittance), light polarized across it is absorbed.
    Polarizer,
    /// A linear retarder (wave plate): light polarized across the fast axis is delayed
    /// by this phase per lane, radians.
    Retarder([f32; N]),
}

/// A thin optical sheet (a polarizing filter or a wave plate): light crosses it without
/// bending and nothing reflects. Its axis lies in the sheet. For unpolarized light (every
/// unpolarized render) a polarizer is a grey filter passing half of its transmittance and
/// a retarder is clear; polarized renders apply the element's Mueller matrix
/// (`polarization::interactions`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sheet<const N: usize> {
    /// The element.
    pub element: SheetElement<N>,
    /// The axis (transmission axis of a polarizer, fast axis of a retarder) in the local
    /// frame.
    pub axis: Vec3,
    /// The fraction of the intensity of unpolarized light that crosses, per lane.
    pub transmittance: SampledSpectrum<N>,
}

impl<const N: usize> Sheet<N> {
    /// The straight continuation of `wo` through the sheet (a delta).
    pub fn sample(&self, wo: Vec3) -> Option<BsdfSample<N>> {
        let cos = wo.z.abs();
        if cos == 0.0 || !wo.is_finite() {
            return None;
        }
        Some(BsdfSample::specular(
            -wo,
            self.transmittance / cos,
            [1.0; N],
        ))
    }
}
