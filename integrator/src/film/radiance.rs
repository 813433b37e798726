//! What a sample brings to the film: the radiance a path gathered per wavelength lane, a
//! spectrum, or per lane a Stokes vector when polarized.

use glam::Vec4;
use prism_spectrum::SampledSpectrum;

/// The radiance a path gathers: a spectrum, or per lane a Stokes vector.
pub(crate) trait Radiance<const N: usize>: Clone {
    /// Intensity (S0) per lane.
    fn intensity(&self) -> &SampledSpectrum<N>;
    /// S1, S2, S3 per lane, when polarized.
    fn polarization(&self) -> Option<&[SampledSpectrum<N>; 3]>;
}

impl<const N: usize> Radiance<N> for SampledSpectrum<N> {
    fn intensity(&self) -> &SampledSpectrum<N> {
        self
    }
    fn polarization(&self) -> Option<&[SampledSpectrum<N>; 3]> {
        None
    }
}

/// Stokes vectors per lane, component by component.
#[derive(Debug, Clone, Copy)]
pub(crate) struct StokesSpectrum<const N: usize> {
    pub s0: SampledSpectrum<N>,
    pub polarization: [SampledSpectrum<N>; 3],
}

impl<const N: usize> Radiance<N> for StokesSpectrum<N> {
    fn intensity(&self) -> &SampledSpectrum<N> {
        &self.s0
    }
    fn polarization(&self) -> Option<&[SampledSpectrum<N>; 3]> {
        Some(&self.polarization)
    }
}

impl<const N: usize> StokesSpectrum<N> {
    /// Adds `weight` times the Stokes vector `stokes` in lane `lane`.
    pub(crate) fn add(&mut self, lane: usize, stokes: Vec4) {
        self.s0[lane] += stokes.x;
        self.polarization[0][lane] += stokes.y;
        self.polarization[1][lane] += stokes.z;
        self.polarization[2][lane] += stokes.w;
    }
}
