//! The render loop: rows in parallel, each pixel's samples in order, so that every pixel's
//! sum is the same sequence of additions whatever the thread count.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use glam::Vec2;
use prism_sampling::stream::{SampleStream, SobolStream};
use std::ops::Range;

use prism_sampling::wavelength::WavelengthDistribution;
use prism_scene::world::{Light, Scene, SceneSpectrum};
use prism_spectrum::Spectrum;
use rayon::prelude::*;

use crate::filter::FilterSampler;
use crate::path::{FIRST_BOUNCE_DIMENSION, Tracer};
use crate::{Film, RenderError, RenderSettings, SpectralBands};

/// Counts gathered during a render.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RenderStats {
    /// Camera paths traced.
    pub paths: u64,
    /// Rays traced (camera, continuation and shadow rays).
    pub rays: u64,
    /// Samples rejected as non-finite.
    pub nonfinite: u64,
}

/// Everything a render sets up once (the wavelength distribution, the filter table, the
/// thread pool), so that rendering in many passes costs no more than rendering in one.
pub struct Renderer<'a> {
    scene: &'a Scene,
    settings: RenderSettings,
    distribution: WavelengthDistribution,
    filter: FilterSampler,
    pool: rayon::ThreadPool,
}

impl<'a> Renderer<'a> {
    /// Checks `settings` and prepares to render `scene` with them (`settings.samples` is
    /// ignored: each call to [`Renderer::render_into`] names its samples).
    pub fn new(scene: &'a Scene, settings: &RenderSettings) -> Result<Self, RenderError> {
        settings.validate()?;
        let light_spectra: Vec<&SceneSpectrum> = scene
            .lights()
            .all()
            .iter()
            .filter_map(|l| match l {
                Light::Point { intensity: s, .. }
                | Light::Spot { intensity: s, .. }
                | Light::Directional { irradiance: s, .. }
                | Light::Environment { radiance: s } => Some(s),
                Light::Triangle { .. } => None,
            })
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
        Ok(Self {
            scene,
            settings: settings.clone(),
            distribution,
            filter,
            pool,
        })
    }

    /// Whether paths handle re-radiation (the scene has fluorescent materials). Scenes
    /// without it run a path tracer compiled without the fluorescence code.
    pub fn fluorescence(&self) -> bool {
        self.scene.features().fluorescence
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
        let tracer = Tracer {
            scene: self.scene,
            distribution: &self.distribution,
            scheme: settings.scheme,
            observer: settings.observer,
            camera: settings.camera.as_deref(),
            max_depth: settings.max_depth.unwrap_or(u32::MAX),
        };
        let (rays, nonfinite) = (AtomicU64::new(0), AtomicU64::new(0));
        let mut pass = Film::for_settings(settings);
        let trace = match (settings.wavelengths, self.fluorescence()) {
            (1, false) => trace_row::<1, false>,
            (2, false) => trace_row::<2, false>,
            (4, false) => trace_row::<4, false>,
            (8, false) => trace_row::<8, false>,
            (_, false) => trace_row::<16, false>,
            (1, true) => trace_row::<1, true>,
            (2, true) => trace_row::<2, true>,
            (4, true) => trace_row::<4, true>,
            (8, true) => trace_row::<8, true>,
            (_, true) => trace_row::<16, true>,
        };
        let rows = Rows {
            width: settings.width,
            height: settings.height,
            seed: settings.seed,
            clamp: settings.clamp,
            samples: samples.clone(),
            bands: settings.bands,
        };
        self.pool.install(|| {
            let width = settings.width as usize;
            let spectral_width = width * settings.bands.map_or(0, |b| b.count());
            let (sums, spectral, energy) = pass.sums_mut();
            // Films without spectral or energy sums give each row an empty slice.
            let spectral_rows: Vec<&mut [f64]> = if spectral_width == 0 {
                (0..settings.height)
                    .map(|_| -> &mut [f64] { &mut [] })
                    .collect()
            } else {
                spectral.chunks_mut(spectral_width).collect()
            };
            let energy_rows: Vec<&mut [[f64; 2]]> = if energy.is_empty() {
                (0..settings.height)
                    .map(|_| -> &mut [[f64; 2]] { &mut [] })
                    .collect()
            } else {
                energy.chunks_mut(width).collect()
            };
            sums.par_chunks_mut(width)
                .zip(spectral_rows)
                .zip(energy_rows)
                .enumerate()
                .for_each(|(y, ((row, spectral_row), energy_row))| {
                    if cancel.load(Ordering::Relaxed) {
                        return;
                    }
                    let out = RowOutput {
                        xyz: row,
                        spectral: spectral_row,
                        energy: energy_row,
                    };
                    let (r, n) = trace(&tracer, &self.filter, &rows, y as u32, out);
                    rays.fetch_add(r, Ordering::Relaxed);
                    nonfinite.fetch_add(n, Ordering::Relaxed);
                });
        });
        if cancel.load(Ordering::Relaxed) {
            return Ok(None);
        }
        let count = samples.end.saturating_sub(samples.start);
        let nonfinite = nonfinite.into_inner();
        pass.finish_pass(count, nonfinite);
        film.merge(&pass).map_err(RenderError::Setting)?;
        Ok(Some(RenderStats {
            paths: count * u64::from(settings.width) * u64::from(settings.height),
            rays: rays.into_inner(),
            nonfinite,
        }))
    }
}

/// What a row's samples depend on besides the tracer.
struct Rows {
    width: u32,
    height: u32,
    seed: u64,
    clamp: Option<f64>,
    samples: Range<u64>,
    bands: Option<SpectralBands>,
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

/// One row's sums: XYZ, spectral bands (empty when not spectral) and energy (empty
/// without energy output).
struct RowOutput<'a> {
    xyz: &'a mut [[f64; 3]],
    spectral: &'a mut [f64],
    energy: &'a mut [[f64; 2]],
}

/// Photons per joule at 1 nm: a photon of wavelength l nm carries hc / (l 1e-9) J.
const PHOTONS_PER_JOULE_NM: f64 =
    1e-9 / (prism_spectrum::constants::PLANCK * prism_spectrum::constants::SPEED_OF_LIGHT);

/// Traces every sample of every pixel of row `y`; returns rays traced and samples rejected.
fn trace_row<const N: usize, const FLUORESCENCE: bool>(
    tracer: &Tracer,
    filter: &FilterSampler,
    settings: &Rows,
    y: u32,
    out: RowOutput,
) -> (u64, u64) {
    let RowOutput {
        xyz: row,
        spectral: spectral_row,
        energy: energy_row,
    } = out;
    let record_energy = !energy_row.is_empty();
    let (w, h) = (settings.width, settings.height);
    let aspect = w as f32 / h as f32;
    let (mut rays, mut rejected) = (0u64, 0u64);
    let band_count = settings.bands.map_or(0, |b| b.count());
    // (band, spectral radiance estimate) pairs of the current sample, kept until the
    // sample is known to be finite.
    let mut binned: Vec<(usize, f64)> = Vec::new();
    for (x, sum) in row.iter_mut().enumerate() {
        let pixel = u64::from(y) * u64::from(w) + x as u64;
        for s in settings.samples.clone() {
            let mut stream = SobolStream::new(settings.seed, pixel, s);
            let u_lambda = stream.next_1d();
            let offset = filter.offset(stream.next_2d());
            let film = Vec2::new(
                (x as f32 + 0.5 + offset.x) / w as f32,
                (y as f32 + 0.5 + offset.y) / h as f32,
            );
            let mut xyz = [0.0f64; 3];
            let mut energy = [0.0f64; 2];
            binned.clear();
            let result = tracer.trace::<N, FLUORESCENCE>(
                &mut stream,
                FIRST_BOUNCE_DIMENSION,
                u_lambda,
                film,
                aspect,
                &mut |radiance, lambdas| {
                    let c = match tracer.camera {
                        Some(camera) => camera.channels(radiance, lambdas),
                        None => radiance.to_xyz(lambdas, tracer.observer).to_array(),
                    };
                    xyz[0] += c[0];
                    xyz[1] += c[1];
                    xyz[2] += c[2];
                    if record_energy {
                        // (1/C) sum_j L_j / pdf_j estimates the radiance integral; each
                        // lane's photons are its energy times lambda / hc.
                        for j in 0..N {
                            let pdf = f64::from(lambdas.pdf(j));
                            if pdf > 0.0 {
                                let e = f64::from(radiance[j]) / pdf / N as f64;
                                energy[0] += e;
                                energy[1] +=
                                    e * f64::from(lambdas.lambda(j)) * PHOTONS_PER_JOULE_NM;
                            }
                        }
                    }
                    if let Some(bands) = settings.bands {
                        // Each lane estimates (1/C) L / pdf of its band's integral; per nm,
                        // divided by the band's width.
                        let scale = 1.0 / (N as f64 * bands.width());
                        for j in 0..N {
                            let pdf = f64::from(lambdas.pdf(j));
                            if let (true, Some(band)) =
                                (pdf > 0.0, bands.band_of(lambdas.lambda(j)))
                            {
                                binned.push((band, f64::from(radiance[j]) / pdf * scale));
                            }
                        }
                    }
                },
            );
            rays += result.rays;
            let finite = xyz.iter().all(|v| v.is_finite())
                && binned.iter().all(|b| b.1.is_finite())
                && energy.iter().all(|v| v.is_finite());
            if result.valid && finite {
                let scale = match settings.clamp {
                    Some(c) if xyz[1] > c => c / xyz[1],
                    _ => 1.0,
                };
                for (acc, v) in sum.iter_mut().zip(xyz) {
                    *acc += v * scale;
                }
                for &(band, v) in &binned {
                    spectral_row[x * band_count + band] += v * scale;
                }
                if record_energy {
                    energy_row[x][0] += energy[0] * scale;
                    energy_row[x][1] += energy[1] * scale;
                }
            } else {
                rejected += 1;
            }
        }
    }
    (rays, rejected)
}
