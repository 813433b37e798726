//! `prism.render` and `prism.Render`: a scene rendered by the command line's own code
//! (`prism_cli::commands::render`), its settings the flags of `prism render` in
//! snake_case, the GIL released meanwhile and Ctrl-C stopping it cleanly.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::Duration;

use clap::{CommandFactory, Parser};
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray2, PyArray3};
use prism_cli::commands::render::Failure;
use prism_cli::commands::render::{RenderArgs, Rendered, denoised_image, stats_json, write_render};
use prism_integrator::Film;
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyList, PyTuple};

use crate::SceneError;
use crate::scene::Scene;

/// `prism render`'s flags, parsed as the command line parses them.
#[derive(Parser)]
#[command(name = "prism.render", no_binary_name = true)]
struct Line {
    #[command(flatten)]
    args: RenderArgs,
}

/// Python's names that differ from the flags' (the spellings).
fn flag_of(name: &str) -> String {
    match name {
        "bands" => "--spectral-bands".into(),
        "band_range" => "--spectral-range".into(),
        other => format!("--{}", other.replace('_', "-")),
    }
}

/// The flags for keyword `name` = `value`: True is the flag alone, False and None nothing,
/// a list or tuple the flag once per item, anything else its `str()`.
fn flags_of(name: &str, value: &Bound<'_, PyAny>, out: &mut Vec<String>) -> PyResult<()> {
    let flag = flag_of(name);
    if value.is_none() {
        return Ok(());
    }
    if let Ok(b) = value.cast::<PyBool>() {
        if b.is_true() {
            out.push(flag);
        }
        return Ok(());
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        for item in value.try_iter()? {
            out.push(flag.clone());
            out.push(item?.str()?.to_string());
        }
        return Ok(());
    }
    out.push(flag);
    out.push(value.str()?.to_string());
    Ok(())
}

/// A finished render: images as numpy arrays, its statistics, and files written as
/// `prism render` writes them.
#[pyclass(module = "prism", frozen)]
pub struct Render {
    args: RenderArgs,
    /// `--stats`' JSON, taken when the render ended (its total time is the render's).
    stats: String,
    rendered: Rendered,
    /// The film as the outputs show it (white-balanced where asked).
    shown: Film,
    /// The denoised image (`denoise=True`), RGB in the render's space.
    denoised: Option<Vec<[f32; 3]>>,
}

/// Renders `scene` with `spp` samples per pixel at `width` x `height` (None: from the
/// camera's aspect ratio), `seed`, on `threads` threads (None: one per core), and any other
/// setting of `prism render` as a keyword in snake_case (`max_depth=8`, `wavelengths=4`,
/// `polarized=True`, `at=0.5`, `bands=16`, `band_range="400:700"`, `space="acescg"`...).
/// The image depends only on the scene, the settings and the seed, and equals the command
/// line's. `progress=True` prints the command line's progress line on stderr;
/// `progress=callable` calls it with (samples per pixel done, asked for) after passes.
///
/// The GIL is released while it renders. Ctrl-C stops it at the next whole sample per
/// pixel and raises KeyboardInterrupt whose second argument is the `Render` of what was
/// done.
#[pyfunction]
#[pyo3(signature = (scene, spp = None, width = None, height = None, seed = 0, threads = None, progress = None, **settings))]
#[allow(clippy::too_many_arguments)]
pub fn render(
    py: Python<'_>,
    scene: &Scene,
    spp: Option<i64>,
    width: Option<i64>,
    height: Option<i64>,
    seed: i64,
    threads: Option<i64>,
    progress: Option<&Bound<'_, PyAny>>,
    settings: Option<&Bound<'_, PyDict>>,
) -> PyResult<Render> {
    // A Mitsuba scene's film and sampler say the size and samples where the call does not;
    // other scenes render 64 x 64 at 16 spp unless asked otherwise.
    let from_file = scene.defaults.size.is_some();
    let spp = spp.or((!from_file).then_some(16));
    let (width, height) = match (width, height) {
        (None, None) if !from_file => (Some(64), Some(64)),
        other => other,
    };
    if let Some(spp) = spp
        && spp < 1
    {
        return Err(PyValueError::new_err(format!(
            "spp {spp}: expected at least 1"
        )));
    }
    let mut line = vec!["--seed".to_string(), seed.to_string()];
    if let Some(spp) = spp {
        line.extend(["--spp".to_string(), spp.to_string()]);
    }
    for (flag, value) in [
        ("--width", width),
        ("--height", height),
        ("--threads", threads),
    ] {
        if let Some(v) = value {
            line.extend([flag.to_string(), v.to_string()]);
        }
    }
    // progress: True shows the command line's progress line; a callable is called with
    // (samples per pixel done, asked for) as passes finish.
    let callback: Option<Py<PyAny>> = match progress {
        Some(p) if p.is_callable() => Some(p.clone().unbind()),
        Some(p) if p.is_truthy()? => None,
        _ => {
            line.push("--quiet".into());
            None
        }
    };
    if callback.is_some() {
        line.push("--quiet".into());
    }
    if let Some(settings) = settings {
        for (key, value) in settings.iter() {
            let name: String = key.extract()?;
            if matches!(
                name.as_str(),
                "output" | "outputs" | "stats" | "scene" | "sample_range" | "resume" | "checkpoint"
            ) {
                return Err(PyValueError::new_err(format!(
                    "'{name}' is not a setting of prism.render (files are written by Render.save)"
                )));
            }
            let flag = flag_of(&name);
            let known = Line::command()
                .get_arguments()
                .any(|a| a.get_long().is_some_and(|l| format!("--{l}") == flag));
            if !known {
                // As Python says it of any function's unknown keyword.
                return Err(PyTypeError::new_err(format!(
                    "prism.render() got an unexpected keyword argument '{name}'"
                )));
            }
            flags_of(&name, &value, &mut line)?;
        }
    }
    // Outputs are written by Render.save; the command line's default stands in.
    let args = Line::try_parse_from(&line)
        .map_err(|e| PyValueError::new_err(one_line(&e.render().to_string())))?
        .args;
    let loaded = (scene.loaded.clone(), scene.defaults);
    let cancel = Arc::new(AtomicBool::new(false));
    let done = Arc::new(AtomicU64::new(0));
    let mut interrupt: Option<PyErr> = None;
    let mut reported = 0u64;
    // The CLI renders 64 spp where neither the call nor the file says.
    let total = spp.map_or(scene.defaults.spp.unwrap_or(64), |s| s as u64);
    let result = py.detach(|| {
        std::thread::scope(|s| {
            // The worker wakes this thread when it is done, so that a render returns as
            // soon as it ends rather than at the next poll.
            let watcher = std::thread::current();
            let (args, cancel, done) = (&args, &cancel, &done);
            let worker = s.spawn(move || {
                let rendered =
                    prism_cli::commands::render::render(args, Some(loaded), cancel, done);
                watcher.unpark();
                rendered
            });
            loop {
                let finished = worker.is_finished();
                let now = done.load(Ordering::Relaxed);
                if interrupt.is_none() {
                    // Signals first (Ctrl-C), then the callback with what is new.
                    let checked = Python::attach(|py| {
                        py.check_signals()?;
                        if let Some(callback) = &callback
                            && now != reported
                        {
                            callback.call1(py, (now, total))?;
                        }
                        Ok::<(), PyErr>(())
                    });
                    reported = now;
                    if let Err(e) = checked {
                        cancel.store(true, Ordering::Relaxed);
                        interrupt = Some(e);
                    }
                }
                if finished {
                    break;
                }
                std::thread::park_timeout(Duration::from_millis(50));
            }
            worker.join()
        })
    });
    let rendered = match result {
        Ok(Ok(rendered)) => rendered,
        Ok(Err(Failure::Setting(message))) => return Err(PyValueError::new_err(message)),
        Ok(Err(Failure::Scene(message))) => return Err(SceneError::new_err(message)),
        Err(panic) => {
            let why = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            return Err(PyRuntimeError::new_err(format!(
                "prism panicked (a bug): {why}"
            )));
        }
    };
    let shown = match &rendered.white_balance {
        Some(m) => rendered.outcome.film.adapted(m),
        None => rendered.outcome.film.clone(),
    };
    let stats = stats_json(
        &args,
        &rendered.settings,
        &rendered.outcome,
        rendered.started,
    )
    .to_string();
    let denoised = if interrupt.is_none() {
        py.detach(|| denoised_image(&args, &shown, rendered.space))
            .map_err(SceneError::new_err)?
    } else {
        None
    };
    let done = Render {
        args,
        stats,
        rendered,
        shown,
        denoised,
    };
    if let Some(e) = interrupt {
        if !e.is_instance_of::<PyKeyboardInterrupt>(py) {
            return Err(e);
        }
        let spp = done.rendered.outcome.film.samples();
        let object = Py::new(py, done)?;
        return Err(PyKeyboardInterrupt::new_err((
            format!("render interrupted after {spp} samples per pixel"),
            object,
        )));
    }
    Ok(done)
}

/// clap's message as one line, without its usage block.
fn one_line(rendered: &str) -> String {
    rendered
        .lines()
        .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(" ")
        .trim_start_matches("error: ")
        .replace("--", "")
        .replace('-', "_")
}

impl Render {
    fn size(&self) -> (usize, usize) {
        (self.shown.height() as usize, self.shown.width() as usize)
    }

    /// `rgb` (row-major) as an (H, W, 3) array.
    fn image<'py>(
        &self,
        py: Python<'py>,
        rgb: Vec<[f32; 3]>,
    ) -> PyResult<Bound<'py, PyArray3<f32>>> {
        let (h, w) = self.size();
        let flat: Vec<f32> = rgb.into_iter().flatten().collect();
        let array = Array3::from_shape_vec((h, w, 3), flat)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok(array.into_pyarray(py))
    }
}

#[pymethods]
impl Render {
    /// Linear RGB in the render's space (`space=`, default srgb): float32, (H, W, 3); the
    /// denoised image where the render was (`denoise=True`).
    #[getter]
    fn rgb<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        match &self.denoised {
            Some(rgb) => self.image(py, rgb.clone()),
            None => self.noisy(py),
        }
    }

    /// The film's own RGB, before any denoising: float32, (H, W, 3).
    #[getter]
    fn noisy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        self.image(py, self.shown.to_rgb(self.rendered.space.space()))
    }

    /// The names of the AOVs the render recorded (`aov="albedo,normal"`, `denoise=True`).
    #[getter]
    fn aovs(&self) -> Vec<&'static str> {
        self.rendered
            .settings
            .aovs
            .iter()
            .map(|a| a.name())
            .collect()
    }

    /// AOV `name` as the EXR holds it: float32, (H, W, 3) for albedo, normal, position and
    /// variance, (H, W) for depth and material_id. KeyError for one not recorded.
    fn aov<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let (h, w) = self.size();
        let images = self.shown.aov_images(self.rendered.space.space());
        let layer: Vec<&Vec<f32>> = images
            .iter()
            .filter(|(n, _)| n.split_once('.').is_some_and(|(l, _)| l == name))
            .map(|(_, v)| v)
            .collect();
        match layer.len() {
            0 => Err(pyo3::exceptions::PyKeyError::new_err(format!(
                "no AOV '{name}' in this render (recorded: {})",
                self.aovs().join(", ")
            ))),
            1 => Ok(Array2::from_shape_vec((h, w), layer[0].clone())
                .map_err(|e| PyRuntimeError::new_err(e.to_string()))?
                .into_pyarray(py)
                .into_any()),
            _ => {
                let flat: Vec<f32> = (0..h * w)
                    .flat_map(|i| layer.iter().map(move |c| c[i]))
                    .collect();
                Ok(Array3::from_shape_vec((h, w, layer.len()), flat)
                    .map_err(|e| PyRuntimeError::new_err(e.to_string()))?
                    .into_pyarray(py)
                    .into_any())
            }
        }
    }

    /// Coverage (the share of each pixel's samples that met the scene): float32, (H, W).
    #[getter]
    fn alpha<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let (h, w) = self.size();
        let array = Array2::from_shape_vec((h, w), self.shown.alphas())
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok(array.into_pyarray(py))
    }

    /// CIE 1931 XYZ: float64, (H, W, 3).
    #[getter]
    fn xyz<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let (h, w) = self.size();
        let flat: Vec<f64> = (0..h as u32)
            .flat_map(|y| (0..w as u32).flat_map(move |x| self.shown.xyz(x, y).to_array()))
            .collect();
        let array = Array3::from_shape_vec((h, w, 3), flat)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok(array.into_pyarray(py))
    }

    /// Spectral radiance per band (renders with `bands=N`): float64, (H, W, N); None
    /// otherwise.
    #[getter]
    fn spectral<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArray3<f64>>>> {
        let Some(bands) = self.shown.bands() else {
            return Ok(None);
        };
        let (h, w) = self.size();
        let n = bands.count();
        let mut flat = Vec::with_capacity(h * w * n);
        for y in 0..h as u32 {
            for x in 0..w as u32 {
                let s = self.shown.spectrum(x, y).unwrap_or_else(|| vec![0.0; n]);
                flat.extend(s);
            }
        }
        let array = Array3::from_shape_vec((h, w, n), flat)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok(Some(array.into_pyarray(py)))
    }

    /// The centres of the spectral bands, nm (None without `bands=`).
    #[getter]
    fn wavelengths(&self) -> Option<Vec<f64>> {
        let bands = self.shown.bands()?;
        Some((0..bands.count()).map(|i| bands.center(i)).collect())
    }

    /// The statistics `prism render --stats` prints, as a dict.
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        py.import("json")?
            .call_method1("loads", (self.stats.as_str(),))
    }

    /// Writes the image as `prism render -o PATH` writes it: .exr (linear RGB and alpha in
    /// the render's space, with prism's facts and any spectral bands) or .png (tone mapped
    /// as the settings say). Written to a temporary file, then renamed.
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let mut args = self.args.clone();
        args.outputs = vec![path];
        args.polarization_png = None;
        prism_cli::commands::render::check_outputs(&args.outputs).map_err(PyValueError::new_err)?;
        let r = &self.rendered;
        py.detach(|| {
            write_render(
                &args,
                &r.outcome.film,
                &r.settings,
                &r.outcome.stats,
                r.space,
                r.white_balance.as_ref(),
                self.denoised.as_deref(),
            )
        })
        .map_err(PyRuntimeError::new_err)
    }

    /// The spectral bands as a colour-science `MultiSpectralDistributions`, one column per
    /// pixel in row order (needs `bands=` and colour-science).
    fn to_colour<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (Some(spectral), Some(wavelengths)) = (self.spectral(py)?, self.wavelengths()) else {
            return Err(PyValueError::new_err(
                "this render has no spectral bands: render with bands=N",
            ));
        };
        let (h, w) = self.size();
        // Rows are wavelengths, columns pixels.
        let data = spectral
            .call_method1("reshape", ((h * w, wavelengths.len()),))?
            .getattr("T")?;
        let colour = py.import("colour")?;
        let kwargs = PyDict::new(py);
        kwargs.set_item("domain", wavelengths)?;
        colour
            .getattr("MultiSpectralDistributions")?
            .call((data,), Some(&kwargs))
    }

    fn __repr__(&self) -> String {
        let (h, w) = self.size();
        format!("Render({w} x {h}, {} spp)", self.shown.samples())
    }
}
