//! What a render sets up once, before any pilot: its settings resolved into estimators,
//! the wavelength distribution, the filter table, the thread pool, the camera's lens
//! focused and light paths' aim. The pilots and the render loop build their tracers and
//! sample plans from it.

use std::ops::Range;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64};

use prism_sampling::stream::Replicas;
use prism_sampling::wavelength::WavelengthDistribution;
use prism_scene::world::{Light, Scene, SceneSpectrum};
use prism_spectrum::Spectrum;

use crate::adaptive::SampleMap;
use crate::film::Film;
use crate::film::filter::FilterSampler;
use crate::film::sample_value::Outputs;
use crate::pixels::sample_plan::SamplePlan;
use crate::pixels::splats::add_light_paths;
use crate::plan::estimators::{Resolution, resolve};
use crate::transport::context::Integrator;
use crate::transport::footprint::Footprint;
use crate::transport::throughput::CameraFrame;
use crate::{RenderError, RenderSettings};

/// The row tracer (or another function generic like it) specialized for a setup's
/// package size, fluorescence and polarization, so that a scene pays only for what it has.
macro_rules! specialized {
    ($renderer:expr, $function:ident) => {{
        use prism_spectrum::SampledSpectrum;
        use $crate::transport::throughput::Polarized;
        macro_rules! by_width {
            ($fluorescence:literal, $carrier:ident) => {
                match $renderer.settings.wavelengths {
                    1 => $function::<1, $fluorescence, $carrier<1>>,
                    2 => $function::<2, $fluorescence, $carrier<2>>,
                    4 => $function::<4, $fluorescence, $carrier<4>>,
                    8 => $function::<8, $fluorescence, $carrier<8>>,
                    _ => $function::<16, $fluorescence, $carrier<16>>,
                }
            };
        }
        match ($renderer.fluorescence(), $renderer.settings.is_polarized()) {
            (false, false) => by_width!(false, SampledSpectrum),
            (true, false) => by_width!(true, SampledSpectrum),
            (false, true) => by_width!(false, Polarized),
            (true, true) => by_width!(true, Polarized),
        }
    }};
}
pub(crate) use specialized;

/// A function generic over the package size alone (the reuse pass, adaptive sampling's
/// pilot of reuse's tiles) specialized for a setup's.
macro_rules! specialized_by_width {
    ($renderer:expr, $function:ident) => {
        match $renderer.settings.wavelengths {
            1 => $function::<1>,
            2 => $function::<2>,
            4 => $function::<4>,
            8 => $function::<8>,
            _ => $function::<16>,
        }
    };
}
pub(crate) use specialized_by_width;

/// What a render sets up once (the wavelength distribution, the filter table, the thread
/// pool), so that rendering in many passes costs no more than rendering in one.
pub(crate) struct Setup<'a> {
    pub scene: &'a Scene,
    pub settings: RenderSettings,
    distribution: WavelengthDistribution,
    filter: FilterSampler,
    pub pool: rayon::ThreadPool,
    /// The camera's thin lens, ready (None: a pinhole).
    pub focus: Option<prism_scene::camera::Focus>,
    /// The camera's lens system, focused (None: a pinhole or a thin lens).
    pub system: Option<Arc<prism_scene::camera::FocusedSystem>>,
    /// Where light paths from infinity aim (`Integrator::aim`).
    aim: Option<prism_scene::world::CausticTarget>,
    /// The settings resolved into estimators, before the pilots ran.
    pub resolution: Resolution,
}

impl<'a> Setup<'a> {
    /// Checks `settings`, resolves them into estimators for `scene`, and sets up what
    /// every pass shares.
    pub(crate) fn new(scene: &'a Scene, settings: &RenderSettings) -> Result<Self, RenderError> {
        let resolution = resolve(scene, settings, scene.camera().system.is_some())?;
        let light_spectra: Vec<&SceneSpectrum> = scene
            .lights()
            .all()
            .iter()
            .filter_map(Light::spectrum)
            .chain(scene.emission_spectra())
            .collect();
        let closures: Vec<Box<dyn Fn(f64) -> f64 + '_>> = light_spectra
            .iter()
            .map(|s| Box::new(move |x| s.evaluate(x)) as Box<dyn Fn(f64) -> f64>)
            .collect();
        let spectra: Vec<&dyn Fn(f64) -> f64> = closures.iter().map(|b| &**b).collect();
        let distribution = settings.distribution(&spectra)?;
        let filter = FilterSampler::new(settings.filter)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(settings.threads)
            .build()
            .map_err(|e| RenderError::Setting(format!("thread pool: {e}")))?;
        let aim = if resolution.light_paths {
            scene.aim(|m| m.focuses(crate::transport::light_path::CAUSTIC_ALPHA))
        } else {
            None
        };
        let aspect = settings.width as f32 / settings.height as f32;
        let mut focus = scene.camera().focus(aspect, || auto_focus(scene, aspect));
        let mut system = None;
        if let Some(mounted) = &scene.camera().system {
            let focused = mounted
                .focus(aspect, || auto_focus(scene, aspect))
                .map_err(RenderError::Setting)?;
            focus = None;
            system = Some(Arc::new(focused));
        }
        Ok(Self {
            scene,
            settings: settings.clone(),
            distribution,
            filter,
            pool,
            focus,
            system,
            aim,
            resolution,
        })
    }

    /// The settings this render renders with.
    pub(crate) fn settings(&self) -> &RenderSettings {
        &self.settings
    }

    /// What every path of this render shares, with `splits` continuations per sample.
    pub(crate) fn integrator(&self, splits: u32) -> Integrator<'_> {
        let settings = &self.settings;
        Integrator {
            scene: self.scene,
            distribution: &self.distribution,
            scheme: settings.scheme,
            observer: settings.observer,
            camera: settings.camera.as_deref(),
            max_depth: settings.max_depth.unwrap_or(u32::MAX),
            light_caustics: self.light_caustics(),
            aim: self.aim.as_ref(),
            transparent: settings.transparent,
            footprint: self.scene.filters_textures().then(|| {
                Footprint::new(
                    self.scene.camera(),
                    self.system.as_ref().map(|s| s.yfov() as f32),
                    settings.height,
                )
            }),
            camera_frame: CameraFrame::new(self.scene.camera(), settings.camera_polarizer),
            clock: crate::transport::clock::Clock::of(settings),
            splits,
            camera_media: crate::transport::volume::MediumStack::around_camera(self.scene),
            focus: self.focus.clone(),
            system: self.system.clone(),
        }
    }

    /// The plan of samples `samples` under `seed`, spread by `map` (None: uniformly).
    pub(crate) fn plan(
        &self,
        seed: u64,
        samples: Range<u64>,
        map: Option<Arc<SampleMap>>,
    ) -> SamplePlan {
        let settings = &self.settings;
        SamplePlan {
            width: settings.width,
            height: settings.height,
            seed,
            clamp: settings.clamp,
            samples,
            replicas: if settings.aovs.has(crate::Aov::Variance) {
                Replicas::new(2)
            } else {
                Replicas::ONE
            },
            outputs: Outputs {
                bands: settings.bands,
                energy: settings.energy,
                polarized: settings.is_polarized(),
            },
            map,
        }
    }

    /// The sample plan for the pilots: one sequence of samples whatever the film
    /// records, so that asking for the variance (two replicates) changes the image's
    /// randomization but not the splits and reuse the pilot picks.
    pub(crate) fn pilot_plan(&self, seed: u64, samples: Range<u64>) -> SamplePlan {
        SamplePlan {
            replicas: Replicas::ONE,
            ..self.plan(seed, samples, None)
        }
    }

    /// The filter sampler.
    pub(crate) fn filter(&self) -> &FilterSampler {
        &self.filter
    }

    /// Whether paths handle re-radiation (the scene has fluorescent materials). Scenes
    /// without it run a path tracer compiled without the fluorescence code.
    pub(crate) fn fluorescence(&self) -> bool {
        self.scene.features().fluorescence
    }

    /// Whether light paths carry caustics (`crate::plan::estimators`).
    pub(crate) fn light_caustics(&self) -> bool {
        self.resolution.light_paths
    }

    /// Whether this render may spread its samples by a pilot (`crate::plan::estimators`).
    pub(crate) fn samples_adaptively(&self) -> bool {
        self.resolution.adaptive
    }

    /// One light path per pixel under `seed` (the light paths of one pass), splatted into
    /// a film of the render's size: what light paths add to each pixel's estimate, and the
    /// rays they traced. For the splits pilot (`crate::plan::modes::LightPilot`).
    pub(crate) fn light_pass(&self, seed: u64) -> (Film, u64) {
        let integrator = self.integrator(1);
        let plan = self.pilot_plan(seed, 0..1);
        let mut pass = Film::for_settings(&self.settings);
        let (rays, nonfinite) = (AtomicU64::new(0), AtomicU64::new(0));
        add_light_paths(
            &self.pool,
            &integrator,
            &self.filter,
            &plan,
            &self.settings,
            &mut pass,
            &AtomicBool::new(false),
            (&rays, &nonfinite),
        );
        pass.finish_pass(1, nonfinite.into_inner());
        (pass, rays.into_inner())
    }
}

/// The distance to what the image's centre sees (the pinhole's ray there runs along the
/// view), through the boundaries of media, which are not seen (None: nothing).
fn auto_focus(scene: &Scene, aspect: f32) -> Option<f32> {
    let mut ray = scene.camera().generate_ray(glam::Vec2::splat(0.5), aspect);
    let mut distance = 0.0;
    // Nested boundaries are few; a ray caught between coincident ones gives up.
    for _ in 0..64 {
        let hit = scene.intersect(&ray)?;
        distance += hit.t * ray.direction.length();
        if !scene.is_interface(&hit) {
            return Some(distance);
        }
        ray = hit.spawn(ray.direction);
    }
    None
}
