//! What every path of a render shares (`Integrator`): the scene, the wavelengths' sampling,
//! the sensor, the camera and the clock; the sample stream's dimensions; and what every
//! estimator asks of them (a camera ray, a package of wavelengths, a light's schedule).

use glam::Vec2;
use prism_sampling::stream::{SampleStream, SobolStream};
use prism_sampling::wavelength::{PackageScheme, WavelengthDistribution, WavelengthPackage};
use prism_scene::geometry::Ray;
use prism_scene::world::Scene;
use prism_spectrum::colorimetry::Observer;
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use crate::transport::clock::Clock;
use crate::transport::footprint::Footprint;
use crate::transport::throughput::Carried;

/// What every path of a render shares.
pub(crate) struct Integrator<'a> {
    pub scene: &'a Scene,
    pub distribution: &'a WavelengthDistribution,
    pub scheme: PackageScheme,
    pub observer: Observer,
    /// A camera's response curves replacing the observer, if any.
    pub camera: Option<&'a crate::CameraResponse>,
    /// Bounces after which a path ends (u32::MAX: unbounded).
    pub max_depth: u32,
    /// Whether light paths carry caustics (light, then one or more delta bounces, then
    /// non-fluorescent surfaces, the last a non-delta one the camera sees): camera paths
    /// then leave those to them, so that each path is counted by one estimator.
    pub light_caustics: bool,
    /// Light paths' aim at the surfaces where their first bounce can be focused
    /// (`Material::focuses`): light from infinity crosses their bounding sphere (None: no
    /// light paths).
    pub aim: Option<&'a prism_scene::world::CausticTarget>,
    /// Whether camera rays that leave the scene show nothing (a transparent background).
    pub transparent: bool,
    /// How wide a pixel's footprint is where a path meets a surface, for filtering
    /// textures (None: the scene has no texture to filter).
    pub footprint: Option<Footprint>,
    /// The polarized camera frame (read only by polarized renders).
    pub camera_frame: crate::transport::throughput::CameraFrame,
    /// The instant or exposure rendered on the scene's clock (None: the steady state,
    /// every source always on).
    pub clock: Option<Clock>,
    /// Continuations per camera sample from its first non-delta vertex (1: none split).
    pub splits: u32,
    /// The media the camera is in (read only by the volumetric path tracer).
    pub camera_media: crate::transport::volume::MediumStack,
    /// The camera's thin lens, ready (None: a pinhole).
    pub focus: Option<prism_scene::camera::Focus>,
    /// The camera's lens system, focused (None: a pinhole or a thin lens).
    pub system: Option<std::sync::Arc<prism_scene::camera::FocusedSystem>>,
}

/// The sample-stream dimension of a camera ray's point on the lens: far past any bounce's,
/// so that a pinhole camera's samples draw what they always did.
pub(crate) const LENS_DIMENSION: u64 = 1 << 40;

/// The sample-stream dimensions: the wavelength and the film position first, then a fixed
/// block per bounce so that bounce k always draws from the same dimensions.
pub(crate) const FIRST_BOUNCE_DIMENSION: u64 = 3;
pub(crate) const DIMENSIONS_PER_BOUNCE: u64 = 8;

/// The first bounce at which Russian roulette may end a path.
pub(crate) const ROULETTE_DEPTH: u32 = 3;

/// The throughput below which Russian roulette puts a path at risk: it survives with
/// probability min(0.95, throughput / ROULETTE_THROUGHPUT), so survivors carry at least
/// this much. Survival equal to the throughput (1 here) ended too many paths that still
/// had light to bring: measured as efficiency, 1 / (seconds x relative MSE), on five
/// scenes, 0.25 was the most efficient of the values measured, or within noise of the
/// most efficient, on every one, for fewer paths per second (docs/trade-offs.md, "Russian
/// roulette").
pub(crate) const ROULETTE_THROUGHPUT: f32 = 0.25;

/// The result of one path; its light went to the caller's sink.
pub(crate) struct PathResult {
    /// Whether the path could be traced (its wavelengths were valid).
    pub valid: bool,
    /// Rays traced (camera, continuation and shadow rays).
    pub rays: u64,
    /// Of `rays`, path reuse's connections to other pixels' second vertices (each a
    /// shadow ray, and cheaper than a ray of the path with the work around it).
    pub connections: u64,
    /// Whether the camera ray met geometry (the pixel's coverage, its alpha).
    pub covered: bool,
}

impl PathResult {
    /// A path that traced nothing: a sample of invalid wavelengths (not `valid`, not
    /// counted), or one whose camera ray a lens stopped (`valid`: a black sample).
    pub(crate) const fn nothing(valid: bool) -> Self {
        Self {
            valid,
            rays: 0,
            connections: 0,
            covered: false,
        }
    }
}

/// Beer-Lambert absorption of the segment `ray` just traced to `hit`, if it ran inside an
/// absorbing volume (the ray meets the inside of its boundary).
pub(crate) fn absorb<const N: usize>(
    scene: &Scene,
    ray: &Ray,
    hit: &prism_scene::world::Hit,
    transport: &SampledWavelengths<N>,
    beta: &mut impl Carried<N>,
) {
    if let Some(sigma) = scene.material(hit).absorption()
        && ray.direction.dot(hit.normal) > 0.0
    {
        let distance = hit.t * ray.direction.length();
        let sigma = sigma.at(transport);
        beta.scale(SampledSpectrum::from_fn(|i| (-sigma[i] * distance).exp()));
    }
}

pub(crate) fn wavelengths<const N: usize>(
    package: &WavelengthPackage<N>,
) -> Option<SampledWavelengths<N>> {
    SampledWavelengths::new(package.lambda, package.pdf).ok()
}

/// Where a camera path starts: its wavelengths, its times on the scene's clock (None:
/// the steady state), its camera ray and the lens's weight on that ray.
#[derive(Clone, Copy)]
pub(crate) struct CameraStart<const N: usize> {
    pub lambdas: SampledWavelengths<N>,
    pub times: Option<[f64; N]>,
    pub ray: Ray,
    pub lens_weight: f32,
}

impl<'a> Integrator<'a> {
    /// What turns this render's spectra into the film's colour.
    #[inline(always)]
    pub(crate) fn sensor(&self) -> crate::film::sample_value::Sensor<'a> {
        crate::film::sample_value::Sensor {
            observer: self.observer,
            camera: self.camera,
        }
    }

    /// The start of the camera path of sample `stream` (after the film dimensions)
    /// through film point `film`, with the wavelengths of `package`: the one place every
    /// camera path tracer starts. Err is the path's result when there is nothing to trace:
    /// invalid wavelengths (not counted), or a camera ray a lens stopped (a black sample).
    #[inline(always)]
    pub(crate) fn start_camera_path<const N: usize>(
        &self,
        stream: &mut SobolStream,
        package: &WavelengthPackage<N>,
        film: Vec2,
        aspect: f32,
    ) -> Result<CameraStart<N>, PathResult> {
        let Some(lambdas) = wavelengths(package) else {
            return Err(PathResult::nothing(false));
        };
        let times = self.clock.map(|clock| [clock.time(stream); N]);
        let Some((ray, lens_weight)) = self.camera_ray(film, aspect, stream, package.lambda[0])
        else {
            return Err(PathResult::nothing(true));
        };
        Ok(CameraStart {
            lambdas,
            times,
            ray,
            lens_weight,
        })
    }

    /// The camera ray of the sample `stream` belongs to (at any dimension) through film
    /// point `film`, for the hero wavelength `lambda` (nm), and its weight: through the
    /// pinhole (weight 1), from the thin lens's point the sample's lens dimensions choose
    /// (weight 1), or through a lens system's elements along the path those dimensions
    /// choose. None where a lens system's elements stop the ray: the sample sees black.
    #[inline(always)]
    pub(crate) fn camera_ray(
        &self,
        film: Vec2,
        aspect: f32,
        stream: &SobolStream,
        lambda: f32,
    ) -> Option<(Ray, f32)> {
        let camera = self.scene.camera();
        let lens_numbers = || {
            let mut lens = stream.clone();
            lens.set_dimension(LENS_DIMENSION);
            lens.next_2d()
        };
        if let Some(system) = &self.system {
            return camera.generate_ray_system(film, system, lens_numbers(), lambda);
        }
        Some(match &self.focus {
            None => (camera.generate_ray(film, aspect), 1.0),
            Some(focus) => (
                camera.generate_ray_through(film, aspect, Some(focus), lens_numbers()),
                1.0,
            ),
        })
    }

    /// The package of wavelengths a sample draws with `u_lambda` (its hero's number): only
    /// the hero behind a lens system whose glass disperses, since each wavelength's camera
    /// ray takes its own way through the elements.
    pub(crate) fn package<const N: usize>(&self, u_lambda: f32) -> WavelengthPackage<N> {
        let mut package =
            WavelengthPackage::<N>::sample(self.distribution, f64::from(u_lambda), self.scheme);
        if self.system.as_ref().is_some_and(|s| s.dispersive()) {
            package.terminate_secondary();
        }
        package
    }
}

impl Integrator<'_> {
    /// Darkens the lanes of `le`, light `light`'s, whose time finds it off.
    pub(crate) fn gate<const N: usize>(
        &self,
        light: Option<u32>,
        times: &[f64; N],
        le: &mut SampledSpectrum<N>,
    ) {
        let Some(light) = light else { return };
        let timeline = self.scene.timeline();
        for (j, t) in times.iter().enumerate() {
            if !timeline.on(light, *t) {
                le[j] = 0.0;
            }
        }
    }

    /// At a phosphor, sends each re-emitting lane back to when its light was absorbed: a
    /// delay drawn with `u` from the decay law restricted to when some source shone,
    /// weighing the lane by the law's mass there (`prism_sampling::decay`); a lane with
    /// nothing to absorb is dark.
    pub(crate) fn delay<const N: usize>(
        &self,
        decay: &prism_sampling::decay::Decay,
        u: f32,
        reemitted: &[bool; N],
        times: &mut [f64; N],
        weights: &mut SampledSpectrum<N>,
    ) {
        let on = self.scene.timeline().any_on();
        for j in 0..N {
            if !reemitted[j] {
                continue;
            }
            let windows = prism_sampling::decay::delay_windows(times[j], on);
            match decay.sample_within(f64::from(u), &windows) {
                Some((d, mass)) => {
                    times[j] -= d;
                    weights[j] *= mass as f32;
                }
                None => weights[j] = 0.0,
            }
        }
    }
}
