//! Checkpoints: what a render's fingerprint holds, and the film of a checkpoint to resume.

use std::ops::Range;
use std::path::Path;

use prism_integrator::{Film, decode_accumulation};

use super::args::RenderArgs;

/// What must match for a checkpoint to be resumed or parts merged: everything that changes
/// the estimate or what the film accumulates (bands, energy, a camera's channels). Not
/// `--splits`: every choice estimates the same image, only with more or less noise per
/// sample, so parts split differently merge into an unbiased whole.
pub(super) fn fingerprint(
    args: &RenderArgs,
    width: u32,
    height: u32,
    aovs: prism_integrator::Aovs,
    filter: &str,
) -> String {
    let bands = args
        .spectral_bands
        .map_or("none".into(), |n| format!("{n}@{}", args.spectral_range));
    format!(
        "scene={};camera={:?};size={width}x{height};seed={};max_depth={:?};wavelengths={};lambda_sampler={};filter={};clamp={:?};environment={:?};wavelength_range={};scene_index={:?};light_paths={};bands={bands};energy={};camera_response={:?};transparent={};lens={:?}/{:?}/{:?}",
        args.scene
            .as_ref()
            .map_or("(default)".into(), |p| p.display().to_string()),
        args.camera,
        args.seed,
        args.max_depth,
        args.wavelengths,
        args.lambda_sampler,
        filter,
        args.clamp,
        args.environment.as_ref().map(|e| format!(
            "{e}@{}deg*{}",
            args.environment_rotation, args.environment_strength
        )),
        args.wavelength_range.as_deref().unwrap_or("360:830"),
        args.scene_index,
        !args.no_light_paths,
        args.energy,
        args.camera_response,
        args.transparent,
        args.f_number,
        args.aperture_radius,
        args.focus_distance
    ) + &later_settings_fingerprint(args)
        + &aovs_fingerprint(aovs)
}

/// The AOVs' part: empty without them, so that earlier checkpoints still resume.
fn aovs_fingerprint(aovs: prism_integrator::Aovs) -> String {
    if aovs.is_empty() {
        String::new()
    } else {
        format!(";aovs={aovs}")
    }
}

/// The polarization and time settings' part of the fingerprint: empty for a render without,
/// so that checkpoints written before polarization existed still resume.
fn later_settings_fingerprint(args: &RenderArgs) -> String {
    let polarization = match (args.polarized, args.camera_polarizer) {
        (false, None) => String::new(),
        (_, filter) => format!(";polarized=1;camera_polarizer={filter:?}"),
    };
    // The instant, likewise only when one is rendered.
    let timed = match (args.at, &args.shutter) {
        (Some(t), _) => format!("{polarization};at={t}"),
        (None, Some(s)) => format!("{polarization};shutter={s}"),
        (None, None) => polarization,
    };
    // And the lens system, by its prescription's path.
    match &args.lens {
        Some(lens) => format!("{timed};lens={}", lens.display()),
        None => timed,
    }
}

/// The film of a checkpoint, checked against this render's settings and range.
pub(super) fn resume(path: &Path, fingerprint: &str, range: &Range<u64>) -> Result<Film, String> {
    let bytes = crate::output::read_file(path)?;
    let saved = decode_accumulation(&bytes).map_err(|e| format!("'{}': {e}", path.display()))?;
    if saved.settings != fingerprint {
        return Err(format!(
            "'{}' was rendered with other settings than this render: {} (the file's vs this \
             render's)",
            path.display(),
            prism_integrator::settings_difference(&saved.settings, fingerprint)
        ));
    }
    if saved.samples.start != range.start || saved.samples.end > range.end {
        return Err(format!(
            "'{}' holds samples {}..{}, not a start of {}..{}",
            path.display(),
            saved.samples.start,
            saved.samples.end,
            range.start,
            range.end
        ));
    }
    Ok(saved.film)
}
