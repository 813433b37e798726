//! What a light path carries from a light: a spectrum of power, or for polarized renders
//! a Stokes vector per wavelength lane in the frame of the light's direction of travel,
//! turned by each delta bounce's Mueller matrix and, where the path is seen, by the last
//! surface's and the camera's frame (and its filter). Light travels forwards here, so the
//! state is a Stokes vector rather than the camera paths' Mueller matrix.

use glam::{Mat4, Vec3, Vec4};
use prism_scene::polarization::{Stokes, interactions, polarizes, rotate_frame};
use prism_spectrum::SampledSpectrum;

use crate::film::radiance::{Radiance, StokesSpectrum};
use crate::transport::throughput::{CameraFrame, Carried, Vertex, camera_basis};

/// A light path's throughput.
pub(crate) trait LightThroughput<const N: usize>: Carried<N> + Sized {
    /// What reaches the camera.
    type Radiance: Radiance<N>;

    /// Light of throughput `beta` leaving a light along `travel`, unpolarized unless
    /// `polarization` gives its Stokes vector of unit intensity and its frame's basis.
    fn start(
        beta: SampledSpectrum<N>,
        travel: Vec3,
        polarization: impl FnOnce() -> Option<(Stokes, Vec3)>,
    ) -> Self;

    /// The light arriving at `vertex` (from `vertex.wo`, local) leaving towards `wi`
    /// (local) through a delta lobe of weight `f`, times `weight`.
    fn bounce(&mut self, vertex: &Vertex<'_, '_, N>, wi: Vec3, f: &SampledSpectrum<N>, weight: f32);

    /// What reaches the camera from `vertex` towards `wi` (local; `toward` in the world,
    /// opposite the camera's ray) with BSDF value `f`, times `weight`.
    fn seen(
        &self,
        vertex: &Vertex<'_, '_, N>,
        wi: Vec3,
        toward: Vec3,
        f: &SampledSpectrum<N>,
        weight: f32,
        camera: &CameraFrame,
    ) -> Self::Radiance;
}

impl<const N: usize> LightThroughput<N> for SampledSpectrum<N> {
    type Radiance = SampledSpectrum<N>;

    #[inline]
    fn start(
        beta: SampledSpectrum<N>,
        _: Vec3,
        _: impl FnOnce() -> Option<(Stokes, Vec3)>,
    ) -> Self {
        beta
    }
    #[inline]
    fn bounce(&mut self, _: &Vertex<'_, '_, N>, _: Vec3, f: &SampledSpectrum<N>, weight: f32) {
        *self *= *f * weight;
    }
    #[inline]
    fn seen(
        &self,
        _: &Vertex<'_, '_, N>,
        _: Vec3,
        _: Vec3,
        f: &SampledSpectrum<N>,
        weight: f32,
        _: &CameraFrame,
    ) -> Self::Radiance {
        *self * *f * weight
    }
}

/// Per lane, the Stokes vector of the light a light path carries, in the frame with
/// basis `basis` about its direction of travel.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PolarizedLight<const N: usize> {
    stokes: [Vec4; N],
    basis: Vec3,
}

impl<const N: usize> Carried<N> for PolarizedLight<N> {
    fn scale(&mut self, factor: SampledSpectrum<N>) {
        for (s, f) in self.stokes.iter_mut().zip(factor.0) {
            *s *= f;
        }
    }
    fn scale_uniform(&mut self, factor: f32) {
        for s in &mut self.stokes {
            *s *= factor;
        }
    }
    fn max_value(&self) -> f32 {
        self.stokes.iter().map(|s| s.x).fold(0.0, f32::max)
    }
}

impl<const N: usize> PolarizedLight<N> {
    /// The light after the interactions of `vertex` towards `wi` (local), in the frame of
    /// lane 0's outgoing basis, and that basis (world); depolarizing surfaces keep S0.
    fn through(
        &self,
        vertex: &Vertex<'_, '_, N>,
        wi: Vec3,
        f: &SampledSpectrum<N>,
        delta: bool,
    ) -> ([Vec4; N], Vec3) {
        let out_travel = vertex.frame.to_world(wi);
        if !polarizes(vertex.bsdf, delta) {
            let stokes =
                std::array::from_fn(|lane| Vec4::new(self.stokes[lane].x * f[lane], 0.0, 0.0, 0.0));
            return (stokes, out_travel.any_orthonormal_vector());
        }
        // The light arrives from wo and leaves towards wi: the interactions' roles.
        let lanes = interactions(vertex.bsdf, wi, vertex.wo, f, delta);
        let in_travel = -vertex.frame.to_world(vertex.wo);
        let out_basis = vertex.frame.to_world(lanes[0].outgoing_basis);
        let stokes = std::array::from_fn(|lane| {
            let interaction = &lanes[lane];
            let arriving = rotate_frame(
                in_travel,
                self.basis,
                vertex.frame.to_world(interaction.incident_basis),
            );
            let leaving = rotate_frame(
                out_travel,
                vertex.frame.to_world(interaction.outgoing_basis),
                out_basis,
            );
            leaving.matrix() * interaction.mueller.matrix() * arriving.matrix() * self.stokes[lane]
        });
        (stokes, out_basis)
    }
}

impl<const N: usize> LightThroughput<N> for PolarizedLight<N> {
    type Radiance = StokesSpectrum<N>;

    fn start(
        beta: SampledSpectrum<N>,
        travel: Vec3,
        polarization: impl FnOnce() -> Option<(Stokes, Vec3)>,
    ) -> Self {
        let (shape, basis) = polarization()
            .map_or((Vec4::X, travel.any_orthonormal_vector()), |(s, b)| {
                (s.0, b)
            });
        Self {
            stokes: std::array::from_fn(|lane| shape * beta[lane]),
            basis,
        }
    }

    fn bounce(
        &mut self,
        vertex: &Vertex<'_, '_, N>,
        wi: Vec3,
        f: &SampledSpectrum<N>,
        weight: f32,
    ) {
        let (stokes, basis) = self.through(vertex, wi, f, true);
        self.stokes = stokes.map(|s| s * weight);
        self.basis = basis;
    }

    fn seen(
        &self,
        vertex: &Vertex<'_, '_, N>,
        wi: Vec3,
        toward: Vec3,
        f: &SampledSpectrum<N>,
        weight: f32,
        camera: &CameraFrame,
    ) -> Self::Radiance {
        let (stokes, basis) = self.through(vertex, wi, f, false);
        // Into the camera's frame for the ray that sees the point, through its filter.
        let into_camera = rotate_frame(toward, basis, camera_basis(-toward, camera.up)).matrix();
        let camera_side = camera.filter.unwrap_or(Mat4::IDENTITY) * into_camera;
        let mut radiance = StokesSpectrum {
            s0: SampledSpectrum::splat(0.0),
            polarization: [SampledSpectrum::splat(0.0); 3],
        };
        for (lane, s) in stokes.iter().enumerate() {
            radiance.add(lane, camera_side * *s * weight);
        }
        radiance
    }
}
