//! The render loop: rows in parallel, each pixel's samples in order, so that every pixel's
//! sum is the same sequence of additions whatever the thread count.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use glam::Vec2;
use prism_sampling::stream::{Replicas, SampleStream, SobolStream};
use std::ops::Range;

use prism_sampling::wavelength::WavelengthDistribution;
use prism_scene::world::{EmissionCache, Light, Scene, SceneSpectrum};
use prism_spectrum::Spectrum;
use rayon::prelude::*;

use crate::adaptive::error::{PilotMeasure, PixelError};
use crate::adaptive::{SampleMap, samples_of};
use crate::film::FilmSums;
use crate::film::filter::FilterSampler;
use crate::film::sample_value::{Outputs, SampleValue};
use crate::film::splatter::Splatter;
use crate::plan::estimators::{Estimators, Modes, Resolution, resolve};
use crate::plan::modes::{mode_pilot, pilot};
use crate::transport::context::{FIRST_BOUNCE_DIMENSION, PathResult, Tracer};
use crate::transport::features::features_pass;
use crate::transport::footprint::Footprint;
use crate::transport::light_path::light_seed;
use crate::transport::light_throughput::{LightThroughput, PolarizedLight};
use crate::transport::reuse_record::ReuseRecord;
use crate::transport::throughput::{CameraFrame, Polarized, Throughput};
use crate::transport::volume::FlightNumbers;
use crate::{Film, RenderError, RenderSettings};
use prism_spectrum::SampledSpectrum;

/// Counts gathered during a render.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RenderStats {
    /// Camera paths traced.
    pub paths: u64,
    /// Rays traced (camera, continuation and shadow rays).
    pub rays: u64,
    /// Samples rejected as non-finite.
    pub nonfinite: u64,
    /// Continuations per camera sample (see [`crate::Splits`]).
    pub splits: u32,
    /// The side of the tiles whose paths share second vertices (see [`crate::Reuse`]).
    pub reuse: u32,
    /// The distance in focus of the camera's thin lens (None: a pinhole).
    pub focus_distance: Option<f32>,
    /// Whether the samples were spread by adaptive sampling's pilot.
    pub adaptive: bool,
    /// The estimators the render used, and why (`Renderer::estimators`).
    pub estimators: Estimators,
}

/// Everything a render sets up once (the wavelength distribution, the filter table, the
/// thread pool), so that rendering in many passes costs no more than rendering in one.
pub struct Renderer<'a> {
    scene: &'a Scene,
    settings: RenderSettings,
    distribution: WavelengthDistribution,
    filter: FilterSampler,
    pool: rayon::ThreadPool,
    /// Continuations per camera sample (the settings', or the pilot's choice).
    splits: u32,
    /// The side of the tiles whose paths share their second vertices (1: none).
    reuse: u32,
    /// The camera's thin lens, ready (None: a pinhole).
    focus: Option<prism_scene::camera::Focus>,
    /// The camera's lens system, focused (None: a pinhole or a thin lens).
    system: Option<std::sync::Arc<prism_scene::camera::FocusedSystem>>,
    /// The film a pass adds to, kept between passes: sessions render one sample per pixel
    /// per pass, and a fresh film each time cost page faults and TLB flushes on every
    /// thread (7% of a render with AOVs: its sums are large).
    scratch: std::sync::Mutex<Option<Film>>,
    /// Where light paths from infinity aim (`Tracer::aim`).
    aim: Option<prism_scene::world::Aim>,
    /// Where adaptive sampling spreads the samples (None: uniformly).
    map: Option<std::sync::Arc<SampleMap>>,
    /// The settings resolved into estimators, before the pilots ran.
    resolution: Resolution,
    /// The estimators this render uses, after the pilots.
    estimators: Estimators,
}

/// The row tracer (or another function generic like it) specialized for a renderer's
/// package size, fluorescence and polarization, so that a scene pays only for what it has.
macro_rules! specialized {
    ($renderer:expr, $function:ident) => {{
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

/// A function generic over the package size alone (the reuse pass, adaptive sampling's
/// pilot of reuse's tiles) specialized for a renderer's.
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

impl<'a> Renderer<'a> {
    /// Checks `settings` and prepares to render `scene` with them (`settings.samples` is
    /// ignored: each call to [`Renderer::render_into`] names its samples).
    pub fn new(scene: &'a Scene, settings: &RenderSettings) -> Result<Self, RenderError> {
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
        let mut renderer = Self {
            scene,
            settings: settings.clone(),
            distribution,
            filter,
            pool,
            splits: 1,
            reuse: 1,
            focus: None,
            system: None,
            scratch: Default::default(),
            aim: None,
            map: None,
            resolution,
            estimators: Estimators::default(),
        };
        if resolution.light_paths {
            renderer.aim = scene.aim(|m| m.focuses(crate::transport::light_path::CAUSTIC_ALPHA));
        }
        let aspect = settings.width as f32 / settings.height as f32;
        renderer.focus = scene.camera().focus(aspect, || auto_focus(scene, aspect));
        if let Some(mounted) = &scene.camera().system {
            let focused = mounted
                .focus(aspect, || auto_focus(scene, aspect))
                .map_err(RenderError::Setting)?;
            renderer.focus = None;
            renderer.system = Some(std::sync::Arc::new(focused));
        }
        (renderer.splits, renderer.reuse) = match resolution.modes {
            Modes::Fixed(splits, reuse) => (splits, reuse),
            Modes::ModePilot => {
                let pilot = specialized!(renderer, mode_pilot);
                renderer.pool.install(|| pilot(&renderer))
            }
            Modes::SplitsPilot => {
                let pilot = specialized!(renderer, pilot);
                (renderer.pool.install(|| pilot(&renderer)).choice(), 1)
            }
        };
        if resolution.adaptive {
            renderer.map = renderer.sample_map().map(std::sync::Arc::new);
        }
        renderer.estimators =
            resolution.estimators(renderer.splits, renderer.reuse, renderer.map.is_some());
        Ok(renderer)
    }

    /// The settings this renderer renders with.
    pub fn settings(&self) -> &RenderSettings {
        &self.settings
    }

    /// The camera's thin lens as this render uses it: its radius, shape and the distance
    /// in focus (None: a pinhole or a lens system).
    pub fn focus(&self) -> Option<prism_scene::camera::Focus> {
        self.focus.clone()
    }

    /// The distance in focus, scene units (infinite: focused at infinity; None: a
    /// pinhole), of the thin lens or the lens system.
    pub fn focus_distance(&self) -> Option<f32> {
        self.focus.as_ref().map(|f| f.distance).or_else(|| {
            self.system
                .as_ref()
                .map(|s| (s.focus_distance_mm() / 1000.0) as f32)
        })
    }

    /// The camera's lens system as this render uses it: the film moved to focus, the stop
    /// closed (None: a pinhole or a thin lens).
    pub fn lens_system(&self) -> Option<&prism_scene::camera::FocusedSystem> {
        self.system.as_deref()
    }

    /// Continuations per camera sample: the settings' number, or the pilot's choice.
    pub fn splits(&self) -> u32 {
        self.splits
    }

    /// The side of the tiles whose paths share their second vertices (1: none): the
    /// settings' (where the scene allows reuse), or the pilot's choice.
    pub fn reuse(&self) -> u32 {
        self.reuse
    }

    /// The estimators this render uses (tracer, splits, reuse, light paths, adaptive
    /// sampling), each with why: the settings resolved, and the pilots' choices.
    pub fn estimators(&self) -> Estimators {
        self.estimators
    }

    /// What every path of this render shares, with `splits` continuations per sample.
    pub(crate) fn tracer(&self, splits: u32) -> Tracer<'_> {
        let settings = &self.settings;
        Tracer {
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

    /// The sample rows' settings for `samples` under `seed`.
    pub(crate) fn rows(&self, seed: u64, samples: Range<u64>) -> Rows {
        let settings = &self.settings;
        Rows {
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
            map: self.map.clone(),
        }
    }

    /// The sample rows for the pilots: one sequence of samples whatever the film
    /// records, so that asking for the variance (two replicates) changes the image's
    /// randomization but not the splits and reuse the pilot picks.
    pub(crate) fn pilot_rows(&self, seed: u64, samples: Range<u64>) -> Rows {
        Rows {
            replicas: Replicas::ONE,
            map: None,
            ..self.rows(seed, samples)
        }
    }

    /// The filter sampler.
    pub(crate) fn filter(&self) -> &FilterSampler {
        &self.filter
    }

    /// Whether paths handle re-radiation (the scene has fluorescent materials). Scenes
    /// without it run a path tracer compiled without the fluorescence code.
    pub fn fluorescence(&self) -> bool {
        self.scene.features().fluorescence
    }

    /// Whether light paths carry caustics (`crate::plan::estimators`).
    pub fn light_caustics(&self) -> bool {
        self.resolution.light_paths
    }

    /// Renders sample indices `samples` of every pixel into `film` (which must have the
    /// settings' size). `cancel` is polled between rows: when set, the render stops and
    /// returns `Ok(None)` leaving `film` as it was, so a caller stopping at a sample
    /// boundary never keeps a partial pass.
    pub fn render_into(
        &self,
        samples: Range<u64>,
        film: &mut Film,
        cancel: &AtomicBool,
    ) -> Result<Option<RenderStats>, RenderError> {
        let settings = &self.settings;
        if (film.width(), film.height()) != (settings.width, settings.height) {
            return Err(RenderError::Setting(format!(
                "film is {}x{} but the settings ask for {}x{}",
                film.width(),
                film.height(),
                settings.width,
                settings.height
            )));
        }
        let tracer = self.tracer(self.splits);
        let (rays, nonfinite) = (AtomicU64::new(0), AtomicU64::new(0));
        let kept = self.scratch.lock().ok().and_then(|mut s| s.take());
        let mut pass = match kept {
            Some(mut film) => {
                film.clear();
                film
            }
            None => Film::for_settings(settings),
        };
        let trace = specialized!(self, trace_row);
        let rows = self.rows(settings.seed, samples.clone());
        self.trace_camera(
            trace,
            &tracer,
            &rows,
            &mut pass,
            cancel,
            (&rays, &nonfinite),
        );
        if settings.aovs.traced() {
            let features = match settings.wavelengths {
                1 => features_pass::<1>,
                2 => features_pass::<2>,
                4 => features_pass::<4>,
                8 => features_pass::<8>,
                _ => features_pass::<16>,
            };
            self.pool.install(|| {
                features(&tracer, &self.filter, &rows, pass.aovs_mut(), cancel);
            });
        }
        if self.light_caustics() {
            self.add_light_paths(&tracer, &rows, &mut pass, cancel, &rays, &nonfinite);
        }
        if cancel.load(Ordering::Relaxed) {
            return Ok(None);
        }
        let count = samples.end.saturating_sub(samples.start);
        let nonfinite = nonfinite.into_inner();
        pass.finish_pass(count, nonfinite);
        film.merge(&pass)?;
        if let Ok(mut scratch) = self.scratch.lock() {
            *scratch = Some(pass);
        }
        Ok(Some(RenderStats {
            paths: count * u64::from(settings.width) * u64::from(settings.height),
            rays: rays.into_inner(),
            nonfinite,
            splits: self.splits,
            reuse: self.reuse,
            focus_distance: self.focus_distance(),
            adaptive: self.adaptive(),
            estimators: self.estimators,
        }))
    }

    /// Traces the camera paths of `rows`' samples into `pass` (rows in parallel, or bands
    /// of reuse's tiles), adding the rays traced and samples rejected to `counts`.
    fn trace_camera(
        &self,
        trace: RowTracer,
        tracer: &Tracer,
        rows: &Rows,
        pass: &mut Film,
        cancel: &AtomicBool,
        counts: (&AtomicU64, &AtomicU64),
    ) {
        let settings = &self.settings;
        let (rays, nonfinite) = counts;
        self.pool.install(|| {
            let mut outs = row_outputs(pass, settings.width as usize, settings.height);
            if self.reuse > 1 {
                let band = specialized_by_width!(self, reuse_pass);
                for s in rows.samples.clone() {
                    if cancel.load(Ordering::Relaxed) {
                        return;
                    }
                    let (r, n) = band(self, tracer, rows, &mut outs, s);
                    rays.fetch_add(r, Ordering::Relaxed);
                    nonfinite.fetch_add(n, Ordering::Relaxed);
                }
                return;
            }
            outs.par_iter_mut().enumerate().for_each(|(y, out)| {
                if cancel.load(Ordering::Relaxed) {
                    return;
                }
                let (r, n) = trace(tracer, &self.filter, rows, y as u32, out);
                rays.fetch_add(r, Ordering::Relaxed);
                nonfinite.fetch_add(n, Ordering::Relaxed);
            });
        });
    }

    /// Adaptive sampling's map for this render, from a pilot of the whole image
    /// (`crate::adaptive`): every pixel traced once under each of two seeds of its own, in
    /// the render's modes, without light paths (they are not spread). A pixel's rate
    /// follows its error per ray traced, so that its rays go where they lower the error
    /// most.
    fn sample_map(&self) -> Option<SampleMap> {
        let settings = &self.settings;
        let tracer = self.tracer(self.splits);
        let (width, height) = (settings.width, settings.height);
        let pixels = (width * height) as usize;
        let seeds =
            crate::adaptive::PILOT_SEEDS.map(|seed| self.pilot_rows(settings.seed ^ seed, 0..1));
        let measure = PilotMeasure::new(seeds[0].outputs, settings.range, settings.observer);
        let size = self.reuse;
        let pilot: Vec<Vec<PilotPixel>> = self.pool.install(|| {
            if size > 1 {
                let band = specialized_by_width!(self, pilot_band);
                (0..height.div_ceil(size))
                    .into_par_iter()
                    .map(|b| band(&tracer, &self.filter, &seeds, &measure, size, b * size))
                    .collect()
            } else {
                let row = specialized!(self, pilot_row);
                (0..height)
                    .into_par_iter()
                    .map(|y| row(&tracer, &self.filter, &seeds, &measure, y))
                    .collect()
            }
        });
        let (mut errors, mut costs) = (vec![0.0; pixels], vec![0.0; pixels]);
        let mut bands = vec![[0.0; 2]; pixels];
        for pixel in pilot.into_iter().flatten() {
            let i = (pixel.y * width + pixel.x) as usize;
            errors[i] = pixel.error.error;
            bands[i] = pixel.error.bands;
            costs[i] = pixel.rays as f64 / 2.0;
        }
        let smooth = |values: &[f64]| crate::adaptive::smoothed(values, width, height);
        if let Some(band_errors) = measure.band_error(&bands, smooth) {
            for (e, b) in errors.iter_mut().zip(band_errors) {
                *e += b;
            }
        }
        SampleMap::from_errors(
            width,
            height,
            SampleMap::tile_side(self.reuse),
            &errors,
            &costs,
        )
    }

    /// Whether the render spreads its samples by adaptive sampling's pilot.
    pub fn adaptive(&self) -> bool {
        self.map.is_some()
    }

    /// Whether this render may spread its samples by a pilot (`crate::plan::estimators`).
    pub(crate) fn samples_adaptively(&self) -> bool {
        self.resolution.adaptive
    }

    /// Passes that make one group of adaptive sampling (1 without it): a render stopped
    /// between a group's passes has that group's samples weighted as if it were complete.
    pub fn pass_group(&self) -> u64 {
        if self.map.is_some() {
            crate::adaptive::GROUP
        } else {
            1
        }
    }

    /// One light path per pixel under `seed` (the light paths of one pass), splatted into
    /// a film of the render's size: what light paths add to each pixel's estimate, and the
    /// rays they traced. For the splits pilot (`splits::LightPilot`).
    pub(crate) fn light_pass(&self, seed: u64) -> (Film, u64) {
        let tracer = self.tracer(1);
        let rows = self.pilot_rows(seed, 0..1);
        let mut pass = Film::for_settings(&self.settings);
        let (rays, nonfinite) = (AtomicU64::new(0), AtomicU64::new(0));
        self.add_light_paths(
            &tracer,
            &rows,
            &mut pass,
            &AtomicBool::new(false),
            &rays,
            &nonfinite,
        );
        pass.finish_pass(1, nonfinite.into_inner());
        (pass, rays.into_inner())
    }

    /// Traces the light paths of the caustics seen directly (`light_path.rs`) for one pass
    /// and splats them into `pass`, counting their rays and rejected samples.
    fn add_light_paths(
        &self,
        tracer: &Tracer,
        rows: &Rows,
        pass: &mut Film,
        cancel: &AtomicBool,
        rays: &AtomicU64,
        nonfinite: &AtomicU64,
    ) {
        let settings = &self.settings;
        macro_rules! light_by_width {
            ($carrier:ident) => {
                match settings.wavelengths {
                    1 => light_row::<1, $carrier<1>>,
                    2 => light_row::<2, $carrier<2>>,
                    4 => light_row::<4, $carrier<4>>,
                    8 => light_row::<8, $carrier<8>>,
                    _ => light_row::<16, $carrier<16>>,
                }
            };
        }
        let light_row = if settings.is_polarized() {
            light_by_width!(PolarizedLight)
        } else {
            light_by_width!(SampledSpectrum)
        };
        // Rows of light paths run in parallel in batches, and each batch's splats are
        // added in row order: the sums do not depend on the threads, and the batch
        // bounds the splats held at once.
        const BATCH_ROWS: u32 = 16;
        let mut splatter = Splatter::new(pass, &self.filter);
        for first in (0..settings.height).step_by(BATCH_ROWS as usize) {
            if cancel.load(Ordering::Relaxed) {
                break;
            }
            let last = (first + BATCH_ROWS).min(settings.height);
            let batch: Vec<RowSplats> = self.pool.install(|| {
                (first..last)
                    .into_par_iter()
                    .map(|y| light_row(tracer, rows, y))
                    .collect()
            });
            for row in batch {
                rays.fetch_add(row.rays, Ordering::Relaxed);
                nonfinite.fetch_add(row.rejected, Ordering::Relaxed);
                for splat in &row.splats {
                    splatter.add(splat.film, &splat.value, settings.clamp, splat.second);
                }
            }
        }
    }
}

/// What a row's samples depend on besides the tracer.
pub(crate) struct Rows {
    pub width: u32,
    pub height: u32,
    pub seed: u64,
    pub clamp: Option<f64>,
    pub samples: Range<u64>,
    /// How samples are split into independently scrambled groups: two when the film
    /// records its variance, whose estimate is their spread (`crate::film::aov`).
    pub replicas: Replicas,
    pub outputs: Outputs,
    /// Where adaptive sampling spreads the samples (None: one per pixel per pass).
    pub map: Option<std::sync::Arc<SampleMap>>,
}

impl Rows {
    /// The stream of sample `s` of `pixel` under `seed` (the render's, or a stream's own
    /// seed derived from it).
    #[inline]
    pub(crate) fn stream(&self, seed: u64, pixel: u64, s: u64) -> SobolStream {
        self.replicas.stream(seed, pixel, s)
    }
}

/// Renders `settings.samples` of every pixel into `film`: a [`Renderer`] for one pass.
pub fn render_into(
    scene: &Scene,
    settings: &RenderSettings,
    film: &mut Film,
    cancel: &AtomicBool,
) -> Result<Option<RenderStats>, RenderError> {
    Renderer::new(scene, settings)?.render_into(settings.samples.clone(), film, cancel)
}

/// Renders a whole image: `render_into` a fresh film, never cancelled.
pub fn render(
    scene: &Scene,
    settings: &RenderSettings,
) -> Result<(Film, RenderStats), RenderError> {
    let mut film = Film::for_settings(settings);
    let stats =
        render_into(scene, settings, &mut film, &AtomicBool::new(false))?.unwrap_or_default();
    Ok((film, stats))
}

/// `pass`'s sums cut into rows of a `width` x `height` image; a film without spectral,
/// energy or Stokes sums gives each row an empty slice of them.
fn row_outputs(pass: &mut Film, width: usize, height: u32) -> Vec<RowOutput<'_>> {
    let spectral_width = width * pass.spectral_width();
    let FilmSums {
        xyz,
        spectral,
        energy,
        stokes,
        coverage,
        replica,
    } = pass.sums_mut();
    xyz.chunks_mut(width)
        .zip(rows_of(spectral, spectral_width, height))
        .zip(rows_of(energy, width, height))
        .zip(rows_of(stokes, width, height))
        .zip(coverage.chunks_mut(width))
        .zip(rows_of(replica, width, height))
        .map(
            |(((((xyz, spectral), energy), stokes), coverage), replica)| RowOutput {
                xyz,
                spectral,
                energy,
                stokes,
                coverage,
                replica,
            },
        )
        .collect()
}

/// `sums` in rows of `row` values, or `height` empty rows where there are none.
fn rows_of<T>(sums: &mut [T], row: usize, height: u32) -> Vec<&mut [T]> {
    if row == 0 || sums.is_empty() {
        (0..height).map(|_| -> &mut [T] { &mut [] }).collect()
    } else {
        sums.chunks_mut(row).collect()
    }
}

/// One row's sums: XYZ, spectral bands (empty when not spectral), energy (empty
/// without energy output), Stokes components (empty unless polarized) and coverage.
pub(crate) struct RowOutput<'a> {
    xyz: &'a mut [[f64; 3]],
    spectral: &'a mut [f64],
    energy: &'a mut [[f64; 2]],
    stokes: &'a mut [[[f64; 3]; 3]],
    coverage: &'a mut [f64],
    /// The second replicate's colour and samples (empty without the variance AOV).
    replica: &'a mut [[f64; 4]],
}

impl RowOutput<'_> {
    /// Adds pixel `x`'s sample `s` (`result`, `value`) to the sums with `weight` (1, or
    /// adaptive sampling's); returns whether it was rejected (invalid wavelengths or a
    /// non-finite value).
    pub(crate) fn add(
        &mut self,
        x: usize,
        s: u64,
        result: &PathResult,
        value: &SampleValue,
        rows: &Rows,
        weight: f64,
    ) -> bool {
        self.coverage[x] += f64::from(u8::from(result.covered)) * weight;
        let replica = match self.replica.get_mut(x) {
            Some(r) if rows.replicas.group(s) == 1 => {
                r[3] += 1.0;
                Some(r)
            }
            _ => None,
        };
        if !(result.valid && value.finite()) {
            return true;
        }
        let band_count = rows.outputs.spectral_width();
        let spectral = self
            .spectral
            .get_mut(x * band_count..(x + 1) * band_count)
            .unwrap_or_default();
        let scale = value.clamp_scale(rows.clamp) * weight;
        value.add_to(
            scale,
            &mut self.xyz[x],
            spectral,
            self.energy.get_mut(x),
            self.stokes.get_mut(x),
        );
        if let Some(r) = replica {
            for (a, b) in r.iter_mut().zip(value.xyz) {
                *a += b * scale;
            }
        }
        false
    }
}

/// A row tracer: traces every sample of every pixel of row `y`; returns rays traced and
/// samples rejected.
type RowTracer = fn(&Tracer, &FilterSampler, &Rows, u32, &mut RowOutput) -> (u64, u64);

/// Traces every sample of every pixel of row `y`; returns rays traced and samples rejected.
fn trace_row<const N: usize, const FLUORESCENCE: bool, T: Throughput<N>>(
    tracer: &Tracer,
    filter: &FilterSampler,
    settings: &Rows,
    y: u32,
    out: &mut RowOutput,
) -> (u64, u64) {
    let (mut rays, mut rejected) = (0u64, 0u64);
    let mut value = SampleValue::default();
    let map = settings.map.as_deref();
    for x in 0..settings.width {
        for pass in settings.samples.clone() {
            let (samples, weight) = samples_of(map, x, y, pass);
            for s in samples {
                let result = trace_sample::<N, FLUORESCENCE, T>(
                    tracer, filter, settings, x, y, s, &mut value,
                );
                rays += result.rays;
                rejected += u64::from(out.add(x as usize, s, &result, &value, settings, weight));
            }
        }
    }
    (rays, rejected)
}

/// Adaptive sampling's pilot of row `y`: each pixel's first sample of both `seeds`, its
/// weighted error by `measure` and the rays both traced.
fn pilot_row<const N: usize, const FLUORESCENCE: bool, T: Throughput<N>>(
    tracer: &Tracer,
    filter: &FilterSampler,
    seeds: &[Rows; 2],
    measure: &PilotMeasure,
    y: u32,
) -> Vec<PilotPixel> {
    let mut value = SampleValue::default();
    let mut channels = [Vec::new(), Vec::new()];
    (0..seeds[0].width)
        .map(|x| {
            let mut rays = 0;
            for (rows, out) in seeds.iter().zip(&mut channels) {
                let s = rows.samples.start;
                let result =
                    trace_sample::<N, FLUORESCENCE, T>(tracer, filter, rows, x, y, s, &mut value);
                measure.channels(&value, pilot_scale(&result, &value, rows), out);
                rays += result.rays;
            }
            PilotPixel {
                x,
                y,
                error: measure.error(&channels[0], &channels[1]),
                rays,
            }
        })
        .collect()
}

/// Adaptive sampling's pilot of the tiles of reuse (`size` pixels) in the band from row
/// `y0`, as [`pilot_row`].
fn pilot_band<const N: usize>(
    tracer: &Tracer,
    filter: &FilterSampler,
    seeds: &[Rows; 2],
    measure: &PilotMeasure,
    size: u32,
    y0: u32,
) -> Vec<PilotPixel> {
    let mut out = Vec::new();
    let (width, height) = (seeds[0].width, seeds[0].height);
    let ys = y0..(y0 + size).min(height);
    let mut tile = crate::reuse::Tile::new();
    let mut first: Vec<(Vec<f64>, u64)> = Vec::new();
    let mut channels = Vec::new();
    for x0 in (0..width).step_by(size as usize) {
        let xs = x0..(x0 + size).min(width);
        for (k, rows) in seeds.iter().enumerate() {
            let s = rows.samples.start;
            crate::reuse::trace_tile_at::<N>(
                tracer,
                filter,
                rows,
                xs.clone(),
                ys.clone(),
                s,
                &mut tile,
            );
            first.resize_with(tile.pixels().len(), Default::default);
            for (pixel, kept) in tile.pixels().iter().zip(&mut first) {
                let scale = pilot_scale(&pixel.result, &pixel.value, rows);
                if k == 0 {
                    measure.channels(&pixel.value, scale, &mut kept.0);
                    kept.1 = pixel.result.rays;
                } else {
                    measure.channels(&pixel.value, scale, &mut channels);
                    out.push(PilotPixel {
                        x: pixel.x,
                        y: pixel.y,
                        error: measure.error(&kept.0, &channels),
                        rays: kept.1 + pixel.result.rays,
                    });
                }
            }
        }
    }
    out
}

/// One pixel of adaptive sampling's pilot: its weighted error and the rays its two
/// samples traced.
struct PilotPixel {
    x: u32,
    y: u32,
    error: PixelError,
    rays: u64,
}

/// The factor a pilot sample is added with, as the film would add it: its clamp's, or 0
/// where it would be rejected.
fn pilot_scale(result: &PathResult, value: &SampleValue, rows: &Rows) -> f64 {
    if result.valid && value.finite() {
        value.clamp_scale(rows.clamp)
    } else {
        0.0
    }
}

/// Traces sample `s` of every pixel in tiles whose paths share their second vertices
/// (`crate::reuse`): bands of tile rows in parallel, each band's tiles in order. Returns
/// rays traced and samples rejected.
fn reuse_pass<const N: usize>(
    renderer: &Renderer,
    tracer: &Tracer,
    rows: &Rows,
    outs: &mut [RowOutput],
    s: u64,
) -> (u64, u64) {
    let size = renderer.reuse;
    let bands: Vec<(u32, &mut [RowOutput])> = outs
        .chunks_mut(size as usize)
        .enumerate()
        .map(|(i, band)| (i as u32 * size, band))
        .collect();
    let totals: Vec<(u64, u64)> = bands
        .into_par_iter()
        .map(|(y0, band)| {
            let (mut rays, mut rejected) = (0u64, 0u64);
            let ys = y0..y0 + band.len() as u32;
            crate::reuse::trace_band::<N>(
                tracer,
                renderer.filter(),
                rows,
                size,
                ys,
                s,
                &mut |pixel, sample, weight| {
                    rays += pixel.result.rays;
                    rejected += u64::from(band[(pixel.y - y0) as usize].add(
                        pixel.x as usize,
                        sample,
                        &pixel.result,
                        &pixel.value,
                        rows,
                        weight,
                    ));
                },
            );
            (rays, rejected)
        })
        .collect();
    totals
        .into_iter()
        .fold((0, 0), |(a, b), (r, n)| (a + r, b + n))
}

/// Sample `s` of pixel (`x`, `y`): its stream (positioned after the film dimensions),
/// the number that chooses its wavelengths and its point on the film (in [0, 1]^2).
pub(crate) fn camera_sample(
    filter: &FilterSampler,
    settings: &Rows,
    x: u32,
    y: u32,
    s: u64,
) -> (SobolStream, f32, Vec2) {
    let (w, h) = (settings.width, settings.height);
    let pixel = u64::from(y) * u64::from(w) + u64::from(x);
    let mut stream = settings.stream(settings.seed, pixel, s);
    let u_lambda = stream.next_1d();
    let offset = filter.offset(stream.next_2d());
    let film = Vec2::new(
        (x as f32 + 0.5 + offset.x) / w as f32,
        (y as f32 + 0.5 + offset.y) / h as f32,
    );
    (stream, u_lambda, film)
}

/// Traces sample `s` of pixel (`x`, `y`) into `value` (cleared first).
pub(crate) fn trace_sample<const N: usize, const FLUORESCENCE: bool, T: Throughput<N>>(
    tracer: &Tracer,
    filter: &FilterSampler,
    settings: &Rows,
    x: u32,
    y: u32,
    s: u64,
    value: &mut SampleValue,
) -> PathResult {
    let (w, h) = (settings.width, settings.height);
    let (mut stream, u_lambda, film) = camera_sample(filter, settings, x, y, s);
    value.clear();
    let aspect = w as f32 / h as f32;
    let mut sink = |radiance: &T::Radiance, lambdas: &_| {
        value.add(tracer.sensor(), settings.outputs, radiance, lambdas)
    };
    if tracer.scene.features().media {
        let pixel = u64::from(y) * u64::from(w) + u64::from(x);
        return tracer.trace_volume::<N, FLUORESCENCE, false, T>(
            &mut stream,
            FIRST_BOUNCE_DIMENSION,
            &tracer.package(u_lambda),
            film,
            aspect,
            &mut sink,
            &mut ReuseRecord::new(T::black()),
            &mut EmissionCache::new(),
            &mut FlightNumbers::new(settings.seed, pixel, s),
        );
    }
    // Unsplit renders run a path tracer compiled without the splitting code.
    let trace = if tracer.splits > 1 {
        Tracer::trace::<N, FLUORESCENCE, true, false, T>
    } else {
        Tracer::trace::<N, FLUORESCENCE, false, false, T>
    };
    trace(
        tracer,
        &mut stream,
        FIRST_BOUNCE_DIMENSION,
        &tracer.package(u_lambda),
        film,
        aspect,
        &mut sink,
        &mut ReuseRecord::new(T::black()),
        &mut EmissionCache::new(),
    )
}

/// A light path's contribution to the film, at a film position.
struct Splat {
    film: Vec2,
    value: SampleValue,
    /// Whether its sample is in the second replicate (`Replicas`).
    second: bool,
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

/// The splats of one row's light paths, in the order they were made.
#[derive(Default)]
struct RowSplats {
    splats: Vec<Splat>,
    rays: u64,
    rejected: u64,
}

/// Traces the light paths of every sample of every pixel of row `y` (one per camera
/// sample: the film's mean divides by the samples per pixel, and light paths' camera
/// importance is per pixel).
fn light_row<const N: usize, L: LightThroughput<N>>(
    tracer: &Tracer,
    settings: &Rows,
    y: u32,
) -> RowSplats {
    let w = settings.width;
    let aspect = w as f32 / settings.height as f32;
    let mut out = RowSplats::default();
    for x in 0..w {
        let pixel = u64::from(y) * u64::from(w) + u64::from(x);
        for s in settings.samples.clone() {
            let mut stream = settings.stream(light_seed(settings.seed), pixel, s);
            out.rays +=
                tracer.trace_light::<N, L>(&mut stream, aspect, &mut |film, radiance, lambdas| {
                    let mut value = SampleValue::default();
                    value.add(tracer.sensor(), settings.outputs, radiance, lambdas);
                    if value.finite() {
                        out.splats.push(Splat {
                            film,
                            value,
                            second: settings.replicas.group(s) == 1,
                        });
                    } else {
                        out.rejected += 1;
                    }
                });
        }
    }
    out
}
