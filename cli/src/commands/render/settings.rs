//! The render's settings from the command line: each flag parsed and checked, with one
//! line naming the flag when it is wrong.

use std::ops::Range;
use std::sync::Arc;
use std::time::Duration;

use prism_integrator::{
    Aov, Aovs, CameraResponse, Filter, LambdaSampler, RenderSettings, Reuse, SpectralBands, Splits,
    Tracing,
};
use prism_spectrum::Readable;
use prism_spectrum::color::RgbSpaceId;

use super::args::RenderArgs;
use super::outputs::has_extension;
use crate::session::SessionOptions;

/// What `run` settled before the scene's settings: the image's size (which needs the
/// scene's camera), its samples and the flags checked before the scene was loaded.
pub(super) struct Image {
    pub width: u32,
    pub height: u32,
    pub samples: Range<u64>,
    pub lambda_sampler: LambdaSampler,
    pub filter: Filter,
    /// Longest path in bounces (None: unbounded).
    pub max_depth: Option<u32>,
}

/// `--sample-range`, whose renders write accumulation files, so only .exr outputs.
pub(super) fn samples_only(args: &RenderArgs) -> Result<Option<Range<u64>>, String> {
    let samples_only = args.sample_range.as_deref().map(parse_range).transpose()?;
    if samples_only.is_some()
        && let Some(out) = args.outputs.iter().find(|o| !has_extension(o, "exr"))
    {
        return Err(format!(
            "output '{}': --sample-range writes accumulation files, which must be .exr",
            out.display()
        ));
    }
    if samples_only.is_some() && args.denoise {
        return Err("--denoise: --sample-range writes accumulation files; render them with --aov albedo,normal, merge them, then run prism denoise on the image".into());
    }
    Ok(samples_only)
}

/// The settings of the render the command line asks for, checked as a whole.
pub(super) fn render_settings(
    args: &RenderArgs,
    image: Image,
    camera: Option<CameraResponse>,
) -> Result<RenderSettings, String> {
    if camera.is_some() && args.denoise {
        return Err(
            "--denoise works on colour images; with a camera response the channels are the camera's own"
                .into(),
        );
    }
    if camera.is_some() && args.white_balance.is_some() {
        return Err(
            "--white-balance applies to XYZ; with a camera response the channels are the camera's own"
                .into(),
        );
    }
    let range = match (&args.wavelength_range, &camera) {
        (Some(text), _) => parse_nm_range("--wavelength-range", text)?,
        (None, Some(c)) => c.range(),
        (None, None) => (360.0, 830.0),
    };
    let settings = RenderSettings::default()
        .width(image.width)
        .height(image.height)
        .samples(image.samples)
        .seed(args.seed)
        .max_depth(image.max_depth)
        .splits(args.splits.parse::<Splits>()?)
        .reuse(reuse(args)?)
        .tracing(args.tracer.parse::<Tracing>()?)
        .wavelengths(args.wavelengths)
        .lambda_sampler(image.lambda_sampler)
        .threads(args.threads)
        .filter(image.filter)
        .clamp(args.clamp)
        .bands(spectral_bands(args)?)
        .energy(args.energy)
        .polarized(args.polarized)
        .camera_polarizer(args.camera_polarizer)
        .at(args.at)
        .shutter(args.shutter.as_deref().map(parse_shutter).transpose()?)
        .light_paths(!args.no_light_paths)
        .adaptive(args.adaptive == "on")
        .piece(args.sample_range.is_some())
        .denoised(args.denoise)
        .transparent(args.transparent)
        .range(range)
        .aovs(aovs(args)?)
        .camera(camera.map(Arc::new));
    settings.validate().map_err(|e| e.to_string())?;
    if args.polarization_png.is_some() && !settings.is_polarized() {
        return Err("--polarization-png needs a polarized render (--polarized)".into());
    }
    Ok(settings)
}

/// Path reuse: `--reuse` (a denoised render's `auto` is none: the resolution step's
/// choice), with a warning where a denoised render asks for it.
fn reuse(args: &RenderArgs) -> Result<Reuse, String> {
    let reuse = args.reuse.parse::<Reuse>()?;
    if let Reuse::Fixed(t) = reuse
        && t > 1
        && args.denoise
    {
        eprintln!(
            "prism: warning: --reuse {t} leaves noise in blocks that the denoiser keeps as detail"
        );
    }
    Ok(reuse)
}

/// The AOVs the film records: `--aov`'s, and the albedo and normal `--denoise` reads.
pub(super) fn aovs(args: &RenderArgs) -> Result<Aovs, String> {
    let set: Aovs = args
        .aov
        .as_deref()
        .unwrap_or("")
        .parse()
        .map_err(|e| format!("--aov: {e}"))?;
    Ok(if args.denoise {
        set.with(Aov::Albedo).with(Aov::Normal)
    } else {
        set
    })
}

/// A film of `width` x `height` fits in the memory available (where that is known).
pub(super) fn check_film_memory(width: u32, height: u32, aovs: Aovs) -> Result<(), String> {
    // The film, one pass's film and the output's RGB: 24 + 24 + 12 bytes per pixel, and
    // the AOVs' sums in both films.
    let per_pixel = 60 + 2 * aovs.bytes_per_pixel();
    let film_bytes = u64::from(width) * u64::from(height) * per_pixel;
    if let Some(available) = crate::memory::available_bytes()
        && film_bytes > available
    {
        return Err(format!(
            "a {width}x{height} image needs {:.1} GiB for its film, more than the {:.1} GiB available",
            film_bytes as f64 / f64::from(1u32 << 30),
            available as f64 / f64::from(1u32 << 30)
        ));
    }
    Ok(())
}

/// How the session runs: --time, --checkpoint (next to the first output) and --quiet.
pub(super) fn session_options(
    args: &RenderArgs,
    fingerprint: String,
) -> Result<SessionOptions, String> {
    let time_budget = seconds_arg("time", args.time)?;
    let checkpoint = seconds_arg("checkpoint", args.checkpoint)?.map(|every| {
        let first = &args.outputs[0];
        let mut name = first.file_name().unwrap_or_default().to_os_string();
        name.push(".checkpoint.exr");
        (every, first.with_file_name(name))
    });
    Ok(SessionOptions {
        time_budget,
        checkpoint,
        quiet: args.quiet,
        fingerprint,
        done: Default::default(),
        tev: tev_target(args)?,
    })
}

/// --tev: the viewer's address, and the image's name there (the scene file's name).
fn tev_target(args: &RenderArgs) -> Result<Option<(String, String, RgbSpaceId)>, String> {
    let Some(spec) = &args.tev else {
        return Ok(None);
    };
    let address = crate::tev::address(spec)?;
    let scene = args
        .scene
        .as_ref()
        .and_then(|p| p.file_name())
        .map_or("effects".into(), |n| n.to_string_lossy().into_owned());
    let space = RgbSpaceId::from_name(&args.space).map_err(|e| e.to_string())?;
    Ok(Some((address, format!("prism: {scene}"), space)))
}

/// A span in seconds. Duration::from_secs_f64 panics past u64 seconds (1e300 did); such a
/// span is a mistake, not a plan, so it is an error like any other out-of-range value.
fn seconds_arg(name: &str, value: Option<f64>) -> Result<Option<Duration>, String> {
    value
        .map(|s| {
            Duration::try_from_secs_f64(s).map_err(|_| {
                format!(
                    "--{name} {} must be a finite number of seconds >= 0",
                    Readable(s)
                )
            })
        })
        .transpose()
}

/// `A:B` in seconds, A < B (the settings check the order).
fn parse_shutter(text: &str) -> Result<(f64, f64), String> {
    let bad = || format!("--shutter '{text}': expected A:B in seconds, A before B");
    let (a, b) = text.split_once(':').ok_or_else(bad)?;
    let (a, b): (f64, f64) = (
        a.trim().parse().map_err(|_| bad())?,
        b.trim().parse().map_err(|_| bad())?,
    );
    Ok((a, b))
}

/// `A:B` in nm, 0 < A < B.
fn parse_nm_range(flag: &str, text: &str) -> Result<(f32, f32), String> {
    // The renderer's wavelengths are f32: 1e-300 reads as 0 and 1e300 as infinity.
    let bad = || {
        format!("{flag} '{text}': expected A:B in nm with 0 < A < B, both from 1.2e-38 to 3.4e38")
    };
    let (a, b) = text.split_once(':').ok_or_else(bad)?;
    let (a, b): (f32, f32) = (
        a.trim().parse().map_err(|_| bad())?,
        b.trim().parse().map_err(|_| bad())?,
    );
    if a.is_finite() && b.is_finite() && 0.0 < a && a < b {
        Ok((a, b))
    } else {
        Err(bad())
    }
}

/// The chromatic adaptation (Bradford) from the white of the illuminant `spec` to the
/// white of the output space.
pub(super) fn white_balance(
    spec: &str,
    space: RgbSpaceId,
) -> Result<prism_spectrum::color::Mat3, String> {
    use prism_spectrum::color::{AdaptationMethod, adaptation_matrix};
    use prism_spectrum::colorimetry::{Observer, WhitePoint, emission_xyz};
    let spectrum = crate::spectrum_spec::parse(spec).map_err(|e| format!("--white-balance {e}"))?;
    let white = WhitePoint::from_xyz(emission_xyz(&*spectrum, Observer::Cie1931))
        .map_err(|e| format!("--white-balance '{spec}': {e}"))?;
    Ok(adaptation_matrix(
        white,
        space.space().white(),
        AdaptationMethod::Bradford,
    ))
}

/// The bands of `--spectral-bands N --spectral-range A:B`.
fn spectral_bands(args: &RenderArgs) -> Result<Option<SpectralBands>, String> {
    // Checked even without bands: a mistyped range is an error, not silently unused.
    let range = parse_nm_range("--spectral-range", &args.spectral_range)?;
    let Some(count) = args.spectral_bands else {
        return Ok(None);
    };
    SpectralBands::new(range.0, range.1, count)
        .map(Some)
        .map_err(|e| e.to_string())
}

/// `A..B` with A < B.
fn parse_range(text: &str) -> Result<Range<u64>, String> {
    let parsed = text
        .split_once("..")
        .and_then(|(a, b)| Some(a.trim().parse::<u64>().ok()?..b.trim().parse::<u64>().ok()?));
    match parsed {
        Some(r) if r.start < r.end => Ok(r),
        _ => Err(format!(
            "--sample-range '{text}': expected A..B with whole numbers A < B"
        )),
    }
}
