//! One continuation of a camera path between its bounces: what it carries, how a sampled
//! bounce moves it on, and Russian roulette.

use glam::Vec3;
use prism_sampling::lanes::real::Real;
use prism_sampling::wavelength::WavelengthPackage;
use prism_scene::bsdf::BsdfSample;
use prism_scene::geometry::Ray;
use prism_scene::world::Hit;
use prism_spectrum::SampledWavelengths;

use crate::transport::context::{CameraStart, ROULETTE_DEPTH, ROULETTE_THROUGHPUT, wavelengths};
use crate::transport::light_path::CAUSTIC_ALPHA;
use crate::transport::reuse_record::{ReuseRecord, SecondVertex};
use crate::transport::throughput::{CameraFrame, Throughput, Vertex};

/// A path between bounces: `T` is what it carries (a spectrum, or Mueller matrices).
pub(crate) struct Walk<const N: usize, T: Throughput<N>> {
    /// The package of wavelengths, whose secondaries a dispersive bounce ends.
    pub package: WavelengthPackage<N>,
    /// The film's wavelengths, whose densities weigh the estimate.
    pub lambdas: SampledWavelengths<N>,
    /// The wavelengths light is evaluated at. They are the film's until a fluorescent
    /// vertex changes them: past it, each lane carries the incident wavelength it sampled,
    /// while its radiance still counts at the film wavelength it started with.
    pub transport: SampledWavelengths<N>,
    /// The time each lane's light is evaluated at, when rendering an instant: the
    /// camera's, until a phosphor sends a lane back to when its light was absorbed.
    pub times: Option<[f64; N]>,
    /// The ray to the next vertex.
    pub ray: Ray,
    pub radiance: T::Radiance,
    pub beta: T,
    /// The BSDF density and origin of the last bounce, for MIS on emitters it hits; None
    /// after the camera or a delta bounce (no light sampling competed).
    pub previous: Option<(f32, Vec3)>,
    /// Bounces so far.
    pub depth: u32,
    /// The product of eta^2 over the refractions so far, and the split count: `beta`
    /// carries 1 / eta^2 from each refraction and 1 / splits from the split, neither of
    /// which Russian roulette may read as lost energy.
    pub eta_scale: f32,
    /// Whether the path so far could end in light that light paths carry: its first
    /// bounce was not focused (neither a delta nor off a narrow surface), and no vertex so
    /// far was fluorescent (light paths stop at fluorescent surfaces and connect to the
    /// camera only from a surface it sees that is not narrow).
    pub caustic_eligible: bool,
    /// Whether light met at the vertex this bounce leads to is the light paths': the path
    /// is eligible and the bounce was focused, a delta or off a narrow surface (the light
    /// reaches the path through a caustic).
    pub light_caustic: bool,
}

impl<const N: usize, T: Throughput<N>> Walk<N, T> {
    /// A path leaving the camera along `ray` with the wavelengths of `package`.
    #[inline(always)]
    pub fn new(
        package: WavelengthPackage<N>,
        lambdas: SampledWavelengths<N>,
        times: Option<[f64; N]>,
        ray: Ray,
        camera: &CameraFrame,
    ) -> Self {
        Self {
            package,
            lambdas,
            transport: lambdas,
            times,
            ray,
            radiance: T::black(),
            beta: T::start(ray.direction.normalize(), camera),
            previous: None,
            depth: 0,
            eta_scale: 1.0,
            caustic_eligible: false,
            light_caustic: false,
        }
    }

    /// A path leaving the camera from `start` with the wavelengths of `package`, weighed
    /// by its lens.
    #[inline(always)]
    pub fn from_camera(
        package: WavelengthPackage<N>,
        start: &CameraStart<N>,
        camera: &CameraFrame,
    ) -> Self {
        let mut walk = Self::new(package, start.lambdas, start.times, start.ray, camera);
        walk.weigh_camera_ray(start.lens_weight);
        walk
    }

    /// Scales the path by its camera ray's `weight` (a lens system's: what the film gathers
    /// along the ray relative to a pinhole); a pinhole's and a thin lens's 1 leaves it as
    /// it was, to the bit.
    #[inline(always)]
    pub fn weigh_camera_ray(&mut self, weight: f32) {
        if weight != 1.0 {
            self.beta.scale_uniform(weight);
        }
    }

    /// At the second vertex `hit` (seen from `wo_world`), which the tile's pixels share
    /// (`crate::reuse`): from here the path estimates what the vertex reflects per unit of
    /// throughput, and the light gathered before it goes to `record`. Russian roulette
    /// still reads the path's whole throughput.
    #[inline(always)]
    pub fn restart_at_second(
        &mut self,
        hit: &Hit,
        wo_world: Vec3,
        camera: &CameraFrame,
        record: &mut ReuseRecord<'_, N, T::Radiance>,
    ) {
        self.eta_scale *= self.beta.max_value();
        self.beta = T::start(self.ray.direction.normalize(), camera);
        record.second = Some(SecondVertex::at(hit, &self.ray, wo_world));
        record.own = std::mem::replace(&mut self.radiance, T::black());
    }

    /// Moves the path on along `sample`, drawn at `vertex` (at `hit`) with density `pdf`:
    /// the throughput scattered, a dispersive bounce's secondary wavelengths ended (their
    /// light so far handed to `sink` first), the ray spawned. `caustic_start` says whether
    /// a caustic light paths carry could start at this vertex, were it the first (its
    /// material neither a delta nor fluorescent, and light paths carrying caustics).
    /// False where no wavelength is left to carry.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn follow<const FLUORESCENCE: bool>(
        &mut self,
        hit: &Hit,
        vertex: &Vertex<'_, '_, N>,
        sample: &BsdfSample<N>,
        pdf: f32,
        caustic_start: bool,
        sink: &mut impl FnMut(&T::Radiance, &SampledWavelengths<N>),
    ) -> bool {
        self.beta.scatter(
            vertex,
            sample.wi,
            &sample.f,
            sample.delta,
            sample.wi.z.abs() / pdf,
        );
        self.eta_scale *= sample.eta * sample.eta;
        if sample.wavelength_dependent && !self.package.secondary_terminated() {
            // The secondaries' light so far was estimated with the whole package; it goes
            // to the film with the package's densities before they change.
            sink(&self.radiance, &self.lambdas);
            self.radiance = T::black();
            self.package.terminate_secondary();
            self.lambdas = match wavelengths(&self.package) {
                Some(l) => l,
                None => return false,
            };
            if !FLUORESCENCE {
                self.transport = self.lambdas;
            }
        }
        let wi_world = vertex.frame.to_world(sample.wi);
        let focused = sample.delta || (caustic_start && vertex.bsdf.is_narrow(CAUSTIC_ALPHA));
        self.advance(hit, sample.delta, focused, pdf, wi_world, caustic_start);
        true
    }

    /// The rest of a bounce from `hit` once the throughput has scattered: whether the path
    /// is a caustic light paths carry (`caustic_start` as in [`Walk::follow`]; `focused`:
    /// the bounce was a delta or off a narrow surface, `Bsdf::is_narrow`), the bounce's
    /// density `pdf` for MIS unless it was a `delta`, the ray towards `wi_world`, the depth.
    #[inline(always)]
    pub fn advance(
        &mut self,
        hit: &Hit,
        delta: bool,
        focused: bool,
        pdf: f32,
        wi_world: Vec3,
        caustic_start: bool,
    ) {
        if self.depth == 0 {
            self.caustic_eligible = caustic_start && !focused;
        } else {
            self.caustic_eligible &= caustic_start;
            self.light_caustic = self.caustic_eligible && focused;
        }
        self.previous = (!delta).then_some((pdf, hit.p));
        self.ray = hit.spawn(wi_world);
        self.depth += 1;
    }

    /// Russian roulette on the throughput, from the third bounce, with `u`: survivors are
    /// divided by their survival probability, so it is unbiased. Survival is capped at 0.95
    /// so that a path in a closed scene of albedo 1 (throughput never below 1) still ends.
    /// The throughput is read without the refractions' 1 / eta^2 (what a path inside glass
    /// regains on leaving it): with it, paths inside glass died at every bounce with
    /// probability 1 - 1/eta^2 (56% at 1.5).
    #[inline(always)]
    pub fn survives_roulette(&mut self, u: f32) -> bool {
        if self.depth >= ROULETTE_DEPTH {
            let (survives, q) = roulette(self.beta.max_value() * self.eta_scale, u);
            if !survives {
                return false;
            }
            self.beta.scale_uniform(1.0 / q);
        }
        true
    }
}

/// Russian roulette for one path or lanes of them: whether a path of `throughput` survives
/// the draw `u`, and its survival probability q = min(0.95, throughput /
/// ROULETTE_THROUGHPUT), by which a survivor's throughput is divided (a NaN or
/// non-positive q ends it).
#[inline(always)]
pub(crate) fn roulette<R: Real>(throughput: R, u: R) -> (R::Mask, R) {
    roulette_capped(throughput, u, R::splat(0.95))
}

/// [`roulette`] with the survival probability at most `cap` rather than 0.95.
#[inline(always)]
pub(crate) fn roulette_capped<R: Real>(throughput: R, u: R, cap: R) -> (R::Mask, R) {
    let q = (throughput / R::splat(ROULETTE_THROUGHPUT)).min(cap);
    (q.gt(R::splat(0.0)) & !q.le(u), q)
}
