//! What a render writes and reports: its images with prism's facts, the polarization
//! PNG, the statistics, and how it ended.

use std::ops::Range;
use std::path::{Path, PathBuf};
use std::time::Instant;

use prism_integrator::{
    DisplaySettings, Estimators, ExrMetadata, Film, RenderSettings, RenderStats, encode_exr,
    encode_png, encode_png_rgb, encode_polarization_png, replace_rgb_exr,
};
use prism_spectrum::color::{Mat3, RgbSpaceId, ToneMap};

use super::args::RenderArgs;
use crate::denoise::Denoiser;
use crate::output::{check_writable, write_atomically};
use crate::session::{Ending, Outcome};

/// The rendered image to every output, adapted to the white balance if one is asked for,
/// with the facts that reproduce it; and the polarization PNG. With `--denoise` the
/// outputs show `denoised` ([`denoised_image`]'s, computed here where None).
#[allow(clippy::too_many_arguments)]
pub fn write_render(
    args: &RenderArgs,
    film: &Film,
    settings: &RenderSettings,
    stats: &RenderStats,
    space: RgbSpaceId,
    white_balance: Option<&Mat3>,
    denoised: Option<&[[f32; 3]]>,
) -> Result<(), String> {
    let mut facts = vec![
        ("seed".into(), args.seed.to_string()),
        ("wavelengths".into(), args.wavelengths.to_string()),
        ("lambda_sampler".into(), args.lambda_sampler.clone()),
        (
            "wavelength_range".into(),
            format!("{}:{}", settings.range.0, settings.range.1),
        ),
    ];
    if let Some(spec) = &args.white_balance {
        facts.push(("white_balance".into(), spec.clone()));
    }
    if settings.is_polarized() {
        facts.push(("polarized".into(), "1".into()));
    }
    if let Some(angle) = settings.camera_polarizer {
        facts.push(("camera_polarizer".into(), angle.to_string()));
    }
    if let Some(t) = settings.at {
        facts.push(("at".into(), t.to_string()));
    }
    if stats.splits > 1 {
        facts.push(("splits".into(), stats.splits.to_string()));
    }
    if stats.reuse > 1 {
        facts.push(("reuse".into(), stats.reuse.to_string()));
    }
    if stats.adaptive {
        facts.push(("adaptive".into(), "1".into()));
    }
    let shown = match white_balance {
        Some(m) => film.adapted(m),
        None => film.clone(),
    };
    let computed;
    let denoised = match denoised {
        Some(rgb) => Some(rgb),
        None => {
            computed = denoised_image(args, &shown, space)?;
            computed.as_deref()
        }
    };
    if denoised.is_some() {
        facts.push(("denoised".into(), "oidn".into()));
    }
    write_images(
        &shown,
        &args.outputs,
        space,
        display(args)?,
        facts,
        denoised,
    )?;
    if let Some(path) = &args.polarization_png
        && let Some(bytes) = encode_polarization_png(&shown, space.space(), display(args)?)
    {
        write_atomically(path, &bytes)?;
    }
    Ok(())
}

/// With `--denoise`, the image the outputs show: `shown` (the film as shown: white
/// balanced where asked) in `space`, denoised ([`denoise_film`]); None without.
pub fn denoised_image(
    args: &RenderArgs,
    shown: &Film,
    space: RgbSpaceId,
) -> Result<Option<Vec<[f32; 3]>>, String> {
    if !args.denoise {
        return Ok(None);
    }
    denoise_film(shown, space).map(Some)
}

/// --stats: the statistics of a render as one JSON object.
pub fn stats_json(
    args: &RenderArgs,
    settings: &RenderSettings,
    outcome: &Outcome,
    started: Instant,
) -> serde_json::Value {
    let Outcome {
        film,
        stats,
        ending,
        seconds,
    } = outcome;
    serde_json::json!({
        "spp": film.samples(),
        "width": settings.width,
        "height": settings.height,
        "seconds": seconds,
        "total_seconds": started.elapsed().as_secs_f64(),
        "paths": stats.paths,
        "paths_per_second": stats.paths as f64 / seconds.max(1e-9),
        "rays": stats.rays,
        "rays_per_second": stats.rays as f64 / seconds.max(1e-9),
        "nonfinite_samples": stats.nonfinite,
        "ending": format!("{ending:?}"),
        "peak_memory_bytes": crate::memory::peak_bytes(),
        "wavelengths": args.wavelengths,
        "splits": stats.splits,
        "reuse": stats.reuse,
        "adaptive": stats.adaptive,
        "estimators": estimators_json(&stats.estimators),
        "focus_distance": stats.focus_distance.map(|d| {
            if d.is_finite() { serde_json::json!(d) } else { serde_json::json!("infinity") }
        }),
        "lambda_sampler": args.lambda_sampler,
        "energy": energy_stats(film, settings.range),
        "polarized": settings.is_polarized(),
        "camera_polarizer": settings.camera_polarizer,
        "at": settings.at,
        "shutter": settings.shutter,
        "aovs": settings.aovs.iter().map(|a| a.name()).collect::<Vec<_>>(),
        "denoised": args.denoise,
    })
}

/// Which estimators the render used, each with why (`prism_integrator::Estimators`).
fn estimators_json(e: &Estimators) -> serde_json::Value {
    serde_json::json!({
        "tracer": e.tracer.to_string(),
        "tracer_why": e.tracer_why,
        "splits": e.splits,
        "splits_why": e.splits_why,
        "reuse": e.reuse,
        "reuse_why": e.reuse_why,
        "light_paths": e.light_paths,
        "light_paths_why": e.light_paths_why,
        "adaptive": e.adaptive,
        "adaptive_why": e.adaptive_why,
    })
}

/// How the render ended, said where it did not complete; an interrupted render exits 130
/// (128 + SIGINT), its image written.
pub(super) fn finish(
    args: &RenderArgs,
    outcome: &Outcome,
    range: &Range<u64>,
) -> Result<(), String> {
    let done = outcome.film.samples();
    match outcome.ending {
        Ending::Complete => Ok(()),
        Ending::TimeBudget => {
            if !args.quiet {
                eprintln!(
                    "prism: time budget reached at {done} spp of {}",
                    range.end - range.start
                );
            }
            Ok(())
        }
        Ending::Interrupted => {
            eprintln!(
                "prism: interrupted at {done} spp of {}; the image so far was written",
                range.end - range.start
            );
            std::process::exit(130);
        }
    }
}

/// The image means of the energy channels, or null without --energy.
fn energy_stats(film: &Film, range: (f32, f32)) -> serde_json::Value {
    if !film.has_energy() {
        return serde_json::Value::Null;
    }
    let (w, h) = (film.width(), film.height());
    let mut sum = [0.0f64; 2];
    for y in 0..h {
        for x in 0..w {
            let e = film.energy(x, y).unwrap_or_default();
            sum[0] += e[0];
            sum[1] += e[1];
        }
    }
    let n = f64::from(w) * f64::from(h);
    let ev = prism_spectrum::constants::ELEMENTARY_CHARGE;
    serde_json::json!({
        "range_nm": [range.0, range.1],
        "mean_radiance_w_m2_sr": sum[0] / n,
        "mean_radiance_ev_s_m2_sr": sum[0] / n / ev,
        "mean_photon_radiance_s_m2_sr": sum[1] / n,
    })
}

pub fn has_extension(path: &Path, extension: &str) -> bool {
    path.extension().and_then(|e| e.to_str()) == Some(extension)
}

/// Every output is a .exr or .png file that can be written.
pub fn check_outputs(outputs: &[PathBuf]) -> Result<(), String> {
    for out in outputs {
        if !(has_extension(out, "exr") || has_extension(out, "png")) {
            return Err(format!(
                "output '{}': the extension must be .exr or .png",
                out.display()
            ));
        }
        check_writable(out)?;
    }
    Ok(())
}

/// How --exposure, --tonemap and --transparent show a film in a PNG.
fn display(args: &RenderArgs) -> Result<DisplaySettings, String> {
    Ok(DisplaySettings::default()
        .exposure(args.exposure)
        .tone_map(ToneMap::from_name(&args.tonemap).map_err(|e| e.to_string())?)
        .alpha(args.transparent))
}

/// Writes `film` to every output: .exr as linear RGB and alpha in `space` with prism's
/// facts, .png as `display` says; where the image was `denoised` (RGB in `space`), that
/// is what they show, and EXR outputs keep the film's as `noisy.R`, `noisy.G`, `noisy.B`.
pub fn write_images(
    film: &Film,
    outputs: &[PathBuf],
    space: RgbSpaceId,
    display: DisplaySettings,
    facts: Vec<(String, String)>,
    denoised: Option<&[[f32; 3]]>,
) -> Result<(), String> {
    let space = space.space();
    for out in outputs {
        let bytes = if has_extension(out, "exr") {
            let metadata = ExrMetadata::default()
                .spp(film.samples())
                .strings(facts.clone());
            let bytes = encode_exr(film, space, &metadata).map_err(|e| e.to_string())?;
            match denoised {
                Some(rgb) => replace_rgb_exr(&bytes, rgb).map_err(|e| e.to_string())?,
                None => bytes,
            }
        } else {
            match denoised {
                Some(rgb) => {
                    let (w, h) = (film.width(), film.height());
                    encode_png_rgb(w, h, rgb, &film.alphas(), space, display)
                }
                None => encode_png(film, space, display),
            }
        };
        write_atomically(out, &bytes)?;
    }
    Ok(())
}

/// `film`'s image in `space`, denoised by Open Image Denoise with its albedo and normal
/// buffers (which the film must record: `--denoise` asks for them).
pub fn denoise_film(film: &Film, space: RgbSpaceId) -> Result<Vec<[f32; 3]>, String> {
    let space = space.space();
    let aovs = film.aov_images(space);
    let buffer = |layer: &str, names: [&str; 3]| -> Result<Vec<[f32; 3]>, String> {
        let channels: Vec<&Vec<f32>> = names
            .iter()
            .map(|n| {
                let name = format!("{layer}.{n}");
                aovs.iter()
                    .find(|(c, _)| *c == name)
                    .map(|(_, v)| v)
                    .ok_or_else(|| format!("denoising needs the {layer} AOV"))
            })
            .collect::<Result<_, _>>()?;
        Ok((0..channels[0].len())
            .map(|i| [channels[0][i], channels[1][i], channels[2][i]])
            .collect())
    };
    let albedo = buffer("albedo", ["R", "G", "B"])?;
    let normal = buffer("normal", ["X", "Y", "Z"])?;
    let denoiser = Denoiser::load()?;
    let (w, h) = (film.width() as usize, film.height() as usize);
    denoiser.denoise(w, h, space, &film.to_rgb(space), &albedo, &normal)
}
