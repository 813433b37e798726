//! What a camera path carries from the camera to its current vertex: a throughput per
//! wavelength lane (the unpolarized renderer), or per lane a Mueller matrix with the
//! reference frame it expects (the polarized one, `--polarized`). The path tracer is
//! written once over this trait; the unpolarized specialization performs exactly the
//! operations it did before polarization existed, so its images are unchanged to the bit.
//!
//! ## The polarized state
//! Per lane, T maps the Stokes vector of light arriving at the current vertex along the
//! path's last ray (travelling along -d, in the frame with basis vector `basis`) to the
//! Stokes vector the camera measures, in the camera's frame: basis d0 x up (the image's
//! x axis for a ray through the image's centre, `up` the camera's y axis), as Mitsuba 3's
//! `stokes` integrator writes its images. At a vertex with polarized interaction M (input
//! frame b_in, output frame b_out), T becomes T R(b_out -> basis) M and the basis b_in
//! (Wilkie and Weidlich 2012, §4: rotate into each element's frame before applying it).

use glam::{Mat4, Vec3, Vec4};
use prism_scene::geometry::Frame;
use prism_scene::medium::Phase;
use prism_scene::polarization::{
    Interaction, Mueller, Stokes, interactions, phase_interaction, polarizes, rotate_frame,
};
use prism_scene::world::Bsdf;
use prism_spectrum::SampledSpectrum;

use crate::film::radiance::{Radiance, StokesSpectrum};

/// A scattering vertex: the BSDF in its local frame and the direction the path arrived
/// from (local, pointing away from the surface).
pub(crate) struct Vertex<'v, 'b, const N: usize> {
    pub bsdf: &'v Bsdf<'b, N>,
    pub frame: &'v Frame,
    pub wo: Vec3,
}

/// Light arriving at a vertex from a sampled light: its direction `wi` (local), the
/// BSDF's value there `f` (cosine included), its `radiance` and the estimator's `weight`.
pub(crate) struct Arrival<'a, const N: usize> {
    pub wi: Vec3,
    pub f: &'a SampledSpectrum<N>,
    pub radiance: &'a SampledSpectrum<N>,
    pub weight: f32,
}

/// What camera and light paths alike do to what they carry: weigh it per lane or as a
/// whole, and read its size (Russian roulette).
pub(crate) trait Carried<const N: usize> {
    /// Multiplies every lane by its factor (absorption, the lanes' re-radiation weights).
    fn scale(&mut self, factor: SampledSpectrum<N>);
    /// Multiplies every lane by `factor` (Russian roulette's survival).
    fn scale_uniform(&mut self, factor: f32);
    /// The largest lane's intensity (its throughput for unpolarized light).
    fn max_value(&self) -> f32;
}

/// A camera path's throughput.
pub(crate) trait Throughput<const N: usize>: Carried<N> + Sized {
    /// What the path gathers.
    type Radiance: Radiance<N>;

    /// The throughput of a camera ray along `direction` (unit) from `camera`: one, or
    /// the camera's filter.
    fn start(direction: Vec3, camera: &CameraFrame) -> Self;
    /// No radiance.
    fn black() -> Self::Radiance;
    /// Adds unpolarized radiance `le` arriving along the path's last ray, times `weight`.
    fn add_emitted(&self, radiance: &mut Self::Radiance, le: &SampledSpectrum<N>, weight: f32);
    /// Adds the light `arrival` describes, scattered at `vertex` towards the path; the
    /// light is unpolarized unless `polarization` gives its Stokes vector of unit
    /// intensity and the basis of its frame (world), read only by polarized paths.
    fn add_scattered(
        &self,
        radiance: &mut Self::Radiance,
        vertex: &Vertex<'_, '_, N>,
        arrival: Arrival<'_, N>,
        polarization: impl FnOnce() -> Option<(Stokes, Vec3)>,
    );
    /// Continues the path at `vertex` towards `wi` (local) with BSDF value (or delta
    /// weight, `delta`) `f`, times `weight` (the cosine over the density).
    fn scatter(
        &mut self,
        vertex: &Vertex<'_, '_, N>,
        wi: Vec3,
        f: &SampledSpectrum<N>,
        delta: bool,
        weight: f32,
    );
    /// Continues the path, which arrived along unit `d`, at a medium's particle scattering
    /// by `phase` towards world direction `wi`, each lane times `weight` over the phase
    /// function (the direction's weight p / pdf is `weight`).
    fn scatter_phase(&mut self, phase: &Phase, d: Vec3, wi: Vec3, weight: f32);
    /// Adds light `light` (per lane, already weighed) arriving at a particle of `phase`
    /// from world direction `wi` and scattered towards the path, which arrived along `d`;
    /// `polarization` gives the light's Stokes vector and frame where it is polarized.
    fn add_phase_scattered(
        &self,
        radiance: &mut Self::Radiance,
        phase: &Phase,
        d: Vec3,
        wi: Vec3,
        light: &SampledSpectrum<N>,
        polarization: impl FnOnce() -> Option<(Stokes, Vec3)>,
    );
}

impl<const N: usize> Carried<N> for SampledSpectrum<N> {
    #[inline]
    fn scale(&mut self, factor: SampledSpectrum<N>) {
        *self *= factor;
    }
    #[inline]
    fn scale_uniform(&mut self, factor: f32) {
        *self *= factor;
    }
    #[inline]
    fn max_value(&self) -> f32 {
        SampledSpectrum::max_value(self)
    }
}

impl<const N: usize> Throughput<N> for SampledSpectrum<N> {
    type Radiance = SampledSpectrum<N>;

    #[inline]
    fn start(_: Vec3, _: &CameraFrame) -> Self {
        SampledSpectrum::splat(1.0)
    }
    #[inline]
    fn black() -> Self::Radiance {
        SampledSpectrum::splat(0.0)
    }
    #[inline]
    fn add_emitted(&self, radiance: &mut Self::Radiance, le: &SampledSpectrum<N>, weight: f32) {
        *radiance += *self * *le * weight;
    }
    #[inline]
    fn add_scattered(
        &self,
        radiance: &mut Self::Radiance,
        _: &Vertex<'_, '_, N>,
        arrival: Arrival<'_, N>,
        _: impl FnOnce() -> Option<(Stokes, Vec3)>,
    ) {
        *radiance += *self * *arrival.f * *arrival.radiance * arrival.weight;
    }
    #[inline]
    fn scatter(
        &mut self,
        _: &Vertex<'_, '_, N>,
        _: Vec3,
        f: &SampledSpectrum<N>,
        _: bool,
        weight: f32,
    ) {
        *self *= *f * weight;
    }
    #[inline]
    fn scatter_phase(&mut self, _: &Phase, _: Vec3, _: Vec3, weight: f32) {
        *self *= weight;
    }
    #[inline]
    fn add_phase_scattered(
        &self,
        radiance: &mut Self::Radiance,
        phase: &Phase,
        d: Vec3,
        wi: Vec3,
        light: &SampledSpectrum<N>,
        _: impl FnOnce() -> Option<(Stokes, Vec3)>,
    ) {
        *radiance += *self * *light * phase.eval(d, wi);
    }
}

/// The polarized throughput (see the module documentation).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Polarized<const N: usize> {
    /// Per lane, camera Stokes <- Stokes arriving along the last ray in `basis`'s frame.
    mueller: [Mat4; N],
    /// The basis vector of the frame of light arriving along the last ray.
    basis: Vec3,
}

/// The camera's Stokes frame for a ray along `direction`: basis direction x up, as
/// Mitsuba 3's `stokes` integrator (the image's x axis at its centre; for a ray along the
/// up axis, any perpendicular vector).
pub(crate) fn camera_basis(direction: Vec3, up: Vec3) -> Vec3 {
    direction
        .cross(up)
        .try_normalize()
        .unwrap_or_else(|| direction.any_orthonormal_vector())
}

impl<const N: usize> Polarized<N> {
    /// T R(b_out -> basis) M for each lane's interaction at `vertex` (its frames in
    /// world space); the new basis is the interactions' input frame.
    fn compose(&self, vertex: &Vertex<'_, '_, N>, lanes: &[Interaction; N]) -> Self {
        let travel = vertex.frame.to_world(vertex.wo);
        let mut next = *self;
        // Lanes share their frames but where dispersion tilts a rough refraction's
        // microfacet: one rotation serves every lane with the same frame.
        let mut rotation: Option<(Vec3, Mat4)> = None;
        for (lane, interaction) in lanes.iter().enumerate() {
            let local = interaction.outgoing_basis;
            let turn = match rotation {
                Some((basis, m)) if basis == local => m,
                _ => {
                    let out_basis = vertex.frame.to_world(local);
                    let m = rotate_frame(travel, out_basis, self.basis).matrix();
                    rotation = Some((local, m));
                    m
                }
            };
            next.mueller[lane] = self.mueller[lane] * turn * interaction.mueller.matrix();
        }
        // Every lane's input frame is the s axis of its plane of incidence: the same
        // vector for all lanes but a depolarizer's (whose frame is arbitrary, any will do).
        next.basis = vertex.frame.to_world(lanes[0].incident_basis);
        next
    }
}

impl<const N: usize> Carried<N> for Polarized<N> {
    fn scale(&mut self, factor: SampledSpectrum<N>) {
        for (m, f) in self.mueller.iter_mut().zip(factor.0) {
            *m *= f;
        }
    }
    fn scale_uniform(&mut self, factor: f32) {
        for m in &mut self.mueller {
            *m *= factor;
        }
    }
    fn max_value(&self) -> f32 {
        self.mueller.iter().map(|m| m.x_axis.x).fold(0.0, f32::max)
    }
}

impl<const N: usize> Throughput<N> for Polarized<N> {
    type Radiance = StokesSpectrum<N>;

    fn start(direction: Vec3, camera: &CameraFrame) -> Self {
        Self {
            mueller: [camera.filter.unwrap_or(Mat4::IDENTITY); N],
            basis: camera_basis(direction, camera.up),
        }
    }
    fn black() -> Self::Radiance {
        StokesSpectrum {
            s0: SampledSpectrum::splat(0.0),
            polarization: [SampledSpectrum::splat(0.0); 3],
        }
    }
    fn add_emitted(&self, radiance: &mut Self::Radiance, le: &SampledSpectrum<N>, weight: f32) {
        // Unpolarized light is the same in every frame: T's first column.
        for (lane, m) in self.mueller.iter().enumerate() {
            radiance.add(lane, m.x_axis * (le[lane] * weight));
        }
    }
    fn add_scattered(
        &self,
        radiance: &mut Self::Radiance,
        vertex: &Vertex<'_, '_, N>,
        arrival: Arrival<'_, N>,
        polarization: impl FnOnce() -> Option<(Stokes, Vec3)>,
    ) {
        let Arrival {
            wi,
            f,
            radiance: light,
            weight,
        } = arrival;
        if !polarizes(vertex.bsdf, false) {
            // A depolarizer passes only S0, whatever the frames.
            for (lane, m) in self.mueller.iter().enumerate() {
                radiance.add(lane, m.x_axis * (f[lane] * light[lane] * weight));
            }
            return;
        }
        let lanes = interactions(vertex.bsdf, vertex.wo, wi, f, false);
        let through = self.compose(vertex, &lanes);
        let Some((stokes, light_basis)) = polarization() else {
            through.add_emitted(radiance, light, weight);
            return;
        };
        // The light's Stokes vector in the frame the interactions expect.
        let travel = -vertex.frame.to_world(wi);
        let arriving = rotate_frame(travel, light_basis, through.basis)
            .apply(stokes)
            .0;
        for (lane, m) in through.mueller.iter().enumerate() {
            radiance.add(lane, *m * arriving * (light[lane] * weight));
        }
    }
    fn scatter(
        &mut self,
        vertex: &Vertex<'_, '_, N>,
        wi: Vec3,
        f: &SampledSpectrum<N>,
        delta: bool,
        weight: f32,
    ) {
        if !polarizes(vertex.bsdf, delta) {
            // T times a depolarizer of value f: T's first column, scaled; the light
            // arriving next is measured in any frame (only its S0 matters).
            for (lane, m) in self.mueller.iter_mut().enumerate() {
                let column = m.x_axis * (f[lane] * weight);
                *m = Mat4::from_cols(column, Vec4::ZERO, Vec4::ZERO, Vec4::ZERO);
            }
            self.basis = vertex.frame.to_world(wi).any_orthonormal_vector();
            return;
        }
        let lanes = interactions(vertex.bsdf, vertex.wo, wi, f, delta);
        *self = self.compose(vertex, &lanes);
        self.scale_uniform(weight);
    }
    fn scatter_phase(&mut self, phase: &Phase, d: Vec3, wi: Vec3, weight: f32) {
        match phase_interaction(phase, -wi, -d) {
            None => {
                // A depolarizer: T's first column, as at a diffuse surface.
                for m in &mut self.mueller {
                    *m = Mat4::from_cols(m.x_axis * weight, Vec4::ZERO, Vec4::ZERO, Vec4::ZERO);
                }
                self.basis = wi.any_orthonormal_vector();
            }
            Some((mueller, basis)) => {
                // T R(basis -> T's basis, along the light leaving towards the camera) M,
                // over p (what the direction's weight already holds): M / p per lane.
                let p = mueller.rows()[0][0];
                let turn = rotate_frame(-d, basis, self.basis).matrix();
                let step = turn * mueller.matrix() * (weight / p);
                for m in &mut self.mueller {
                    *m *= step;
                }
                self.basis = basis;
            }
        }
    }
    fn add_phase_scattered(
        &self,
        radiance: &mut Self::Radiance,
        phase: &Phase,
        d: Vec3,
        wi: Vec3,
        light: &SampledSpectrum<N>,
        polarization: impl FnOnce() -> Option<(Stokes, Vec3)>,
    ) {
        let Some((mueller, basis)) = phase_interaction(phase, -wi, -d) else {
            let p = phase.eval(d, wi);
            for (lane, m) in self.mueller.iter().enumerate() {
                radiance.add(lane, m.x_axis * (light[lane] * p));
            }
            return;
        };
        let through = rotate_frame(-d, basis, self.basis).matrix() * mueller.matrix();
        // The light's Stokes vector in the particle's frame (unpolarized: (1, 0, 0, 0)).
        let arriving = match polarization() {
            Some((stokes, light_basis)) => rotate_frame(-wi, light_basis, basis).apply(stokes).0,
            None => Vec4::X,
        };
        let s = through * arriving;
        for (lane, m) in self.mueller.iter().enumerate() {
            radiance.add(lane, *m * s * light[lane]);
        }
    }
}

/// What the polarized camera frame needs: the camera's up axis and its filter.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CameraFrame {
    /// The camera's y axis in the world.
    pub up: Vec3,
    /// A filter in front of the lens, in the camera's Stokes frame.
    pub filter: Option<Mat4>,
}

impl CameraFrame {
    /// The frame of `camera`, with an ideal linear polarizer at `polarizer` degrees from
    /// the frame's x axis towards its y axis (the image's right and up).
    pub(crate) fn new(camera: &prism_scene::camera::Camera, polarizer: Option<f32>) -> Self {
        Self {
            up: camera
                .to_world
                .transform_vector3(Vec3::Y)
                .normalize_or(Vec3::Y),
            filter: polarizer.map(|degrees| {
                Mueller::rotated(degrees.to_radians(), &Mueller::linear_polarizer(1.0)).matrix()
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_scene::bsdf::Diffuse;

    /// The depolarizer's shortcut is the general composition: T R M with M a depolarizer
    /// keeps T's first column times the value, whatever the frames.
    #[test]
    fn depolarizing_shortcut_is_the_general_product() {
        let t = Polarized::<2> {
            mueller: [
                Mat4::from_cols_array(&[
                    0.9, 0.2, -0.1, 0.05, 0.3, 0.7, 0.1, 0.0, -0.2, 0.1, 0.6, 0.2, 0.0, 0.1, -0.3,
                    0.5,
                ]),
                Mat4::IDENTITY * 0.4,
            ],
            basis: Vec3::X,
        };
        let bsdf = Bsdf::Diffuse(Diffuse::new(SampledSpectrum([0.8, 0.3])));
        let frame = Frame::from_normal(Vec3::new(0.2, 0.3, 0.9).normalize());
        let wo = Vec3::new(0.3, -0.2, 0.9).normalize();
        let wi = Vec3::new(-0.5, 0.4, 0.7).normalize();
        let vertex = Vertex {
            bsdf: &bsdf,
            frame: &frame,
            wo,
        };
        let f = bsdf.f(wo, wi);
        let mut fast = t;
        fast.scatter(&vertex, wi, &f, false, 1.7);
        let mut general = t.compose(&vertex, &interactions(&bsdf, wo, wi, &f, false));
        general.scale_uniform(1.7);
        for (a, b) in fast.mueller.iter().zip(&general.mueller) {
            assert!(a.abs_diff_eq(*b, 1e-6), "{a} vs {b}");
        }
        let light = SampledSpectrum([2.0, 3.0]);
        let (mut a, mut b) = (Polarized::<2>::black(), Polarized::<2>::black());
        let arrival = Arrival {
            wi,
            f: &f,
            radiance: &light,
            weight: 0.5,
        };
        t.add_scattered(&mut a, &vertex, arrival, || None);
        t.compose(&vertex, &interactions(&bsdf, wo, wi, &f, false))
            .add_emitted(&mut b, &light, 0.5);
        for k in 0..3 {
            for lane in 0..2 {
                let (x, y) = (a.polarization[k][lane], b.polarization[k][lane]);
                assert!((x - y).abs() < 1e-6, "{x} vs {y}");
            }
        }
        assert!((a.s0[0] - b.s0[0]).abs() < 1e-6 && (a.s0[1] - b.s0[1]).abs() < 1e-6);
    }
}
