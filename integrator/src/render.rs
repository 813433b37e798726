//! The render loop: the plan's setup and pilots once, then passes of camera paths (rows
//! in parallel, or bands of reuse's tiles), the feature buffers' rays and light paths,
//! each pass merged into the caller's film.

use std::ops::Range;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use prism_scene::world::Scene;
use rayon::prelude::*;

use crate::adaptive::SampleMap;
use crate::film::Film;
use crate::pixels::features::features_pass;
use crate::pixels::rows::{RowTracer, row_outputs, trace_row};
use crate::pixels::sample_plan::SamplePlan;
use crate::pixels::splats::add_light_paths;
use crate::plan::adaptive_pilot::sample_map;
use crate::plan::estimators::{Estimators, Modes};
use crate::plan::modes::{mode_pilot, pilot};
use crate::plan::setup::{Setup, specialized, specialized_by_width};
use crate::reuse::pass::reuse_pass;
use crate::transport::context::Integrator;
use crate::{RenderError, RenderSettings};

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

/// A render's plan, run pass by pass: what it sets up once (`crate::plan::setup`) and
/// what its pilots chose, so that rendering in many passes costs no more than rendering
/// in one.
pub struct Renderer<'a> {
    setup: Setup<'a>,
    /// Continuations per camera sample (the settings', or the pilot's choice).
    splits: u32,
    /// The side of the tiles whose paths share their second vertices (1: none).
    reuse: u32,
    /// Where adaptive sampling spreads the samples (None: uniformly).
    map: Option<Arc<SampleMap>>,
    /// The estimators this render uses, after the pilots.
    estimators: Estimators,
    /// The film a pass adds to, kept between passes: sessions render one sample per pixel
    /// per pass, and a fresh film each time cost page faults and TLB flushes on every
    /// thread (a measurable share of a render with AOVs, whose sums are large).
    scratch: std::sync::Mutex<Option<Film>>,
}

impl<'a> Renderer<'a> {
    /// Checks `settings` and prepares to render `scene` with them (`settings.samples` is
    /// ignored: each call to [`Renderer::render_into`] names its samples).
    pub fn new(scene: &'a Scene, settings: &RenderSettings) -> Result<Self, RenderError> {
        let setup = Setup::new(scene, settings)?;
        let resolution = setup.resolution;
        let (splits, reuse) = match resolution.modes {
            Modes::Fixed(splits, reuse) => (splits, reuse),
            Modes::ModePilot => {
                let pilot = specialized!(setup, mode_pilot);
                setup.pool.install(|| pilot(&setup))
            }
            Modes::SplitsPilot => {
                let pilot = specialized!(setup, pilot);
                (setup.pool.install(|| pilot(&setup)).choice(), 1)
            }
        };
        let map = if resolution.adaptive {
            sample_map(&setup, splits, reuse).map(Arc::new)
        } else {
            None
        };
        let estimators = resolution.estimators(splits, reuse, map.is_some());
        Ok(Self {
            setup,
            splits,
            reuse,
            map,
            estimators,
            scratch: Default::default(),
        })
    }

    /// The settings this renderer renders with.
    pub fn settings(&self) -> &RenderSettings {
        &self.setup.settings
    }

    /// The camera's thin lens as this render uses it: its radius, shape and the distance
    /// in focus (None: a pinhole or a lens system).
    pub fn focus(&self) -> Option<prism_scene::camera::Focus> {
        self.setup.focus.clone()
    }

    /// The distance in focus, scene units (infinite: focused at infinity; None: a
    /// pinhole), of the thin lens or the lens system.
    pub fn focus_distance(&self) -> Option<f32> {
        self.setup.focus.as_ref().map(|f| f.distance).or_else(|| {
            self.setup
                .system
                .as_ref()
                .map(|s| (s.focus_distance_mm() / 1000.0) as f32)
        })
    }

    /// The camera's lens system as this render uses it: the film moved to focus, the stop
    /// closed (None: a pinhole or a thin lens).
    pub fn lens_system(&self) -> Option<&prism_scene::camera::FocusedSystem> {
        self.setup.system.as_deref()
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

    /// Whether paths handle re-radiation (the scene has fluorescent materials). Scenes
    /// without it run a path tracer compiled without the fluorescence code.
    pub fn fluorescence(&self) -> bool {
        self.setup.fluorescence()
    }

    /// Whether light paths carry caustics (`crate::plan::estimators`).
    pub fn light_caustics(&self) -> bool {
        self.setup.light_caustics()
    }

    /// Whether the render spreads its samples by adaptive sampling's pilot.
    pub fn adaptive(&self) -> bool {
        self.map.is_some()
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
        let setup = &self.setup;
        let settings = &setup.settings;
        if (film.width(), film.height()) != (settings.width, settings.height) {
            return Err(RenderError::Setting(format!(
                "film is {}x{} but the settings ask for {}x{}",
                film.width(),
                film.height(),
                settings.width,
                settings.height
            )));
        }
        let integrator = setup.integrator(self.splits);
        let (rays, nonfinite) = (AtomicU64::new(0), AtomicU64::new(0));
        let kept = self.scratch.lock().ok().and_then(|mut s| s.take());
        let mut pass = match kept {
            Some(mut film) => {
                film.clear();
                film
            }
            None => Film::for_settings(settings),
        };
        let trace = specialized!(setup, trace_row);
        let plan = setup.plan(settings.seed, samples.clone(), self.map.clone());
        self.trace_camera(
            trace,
            &integrator,
            &plan,
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
            setup.pool.install(|| {
                features(&integrator, setup.filter(), &plan, pass.aovs_mut(), cancel);
            });
        }
        if self.light_caustics() {
            add_light_paths(
                &setup.pool,
                &integrator,
                setup.filter(),
                &plan,
                settings,
                &mut pass,
                cancel,
                (&rays, &nonfinite),
            );
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

    /// Traces the camera paths of `plan`'s samples into `pass` (rows in parallel, or bands
    /// of reuse's tiles), adding the rays traced and samples rejected to `counts`.
    fn trace_camera(
        &self,
        trace: RowTracer,
        integrator: &Integrator,
        plan: &SamplePlan,
        pass: &mut Film,
        cancel: &AtomicBool,
        counts: (&AtomicU64, &AtomicU64),
    ) {
        let setup = &self.setup;
        let settings = &setup.settings;
        let (rays, nonfinite) = counts;
        setup.pool.install(|| {
            let mut outs = row_outputs(pass, settings.width as usize, settings.height);
            if self.reuse > 1 {
                let band = specialized_by_width!(setup, reuse_pass);
                for s in plan.samples.clone() {
                    if cancel.load(Ordering::Relaxed) {
                        return;
                    }
                    let (r, n) = band(integrator, setup.filter(), plan, self.reuse, &mut outs, s);
                    rays.fetch_add(r, Ordering::Relaxed);
                    nonfinite.fetch_add(n, Ordering::Relaxed);
                }
                return;
            }
            outs.par_iter_mut().enumerate().for_each(|(y, out)| {
                if cancel.load(Ordering::Relaxed) {
                    return;
                }
                let (r, n) = trace(integrator, setup.filter(), plan, y as u32, out);
                rays.fetch_add(r, Ordering::Relaxed);
                nonfinite.fetch_add(n, Ordering::Relaxed);
            });
        });
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
