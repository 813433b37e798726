//! The scene `prism render` renders: the file (or the embedded effects stage) with the
//! command line's camera, thin lens, environment and tree quality, and what the user should
//! know of it.

use std::path::Path;
use std::sync::Arc;

use prism_integrator::{CameraResponse, ResponseCurve};
use prism_scene::camera::system::parse_prescription;
use prism_scene::camera::{ApertureSize, Camera, MountedLens, Projection, ThinLens};
use prism_scene::geometry::BvhQuality;
use prism_scene::load::{LoadedGeometry, environment_map, load_geometry};
use prism_scene::world::{DEFAULT_ENVIRONMENT, Environment, Scene, SceneOptions, grey_environment};
use prism_spectrum::Readable;

use super::args::RenderArgs;
use crate::scene_file::FileDefaults;

/// The scene `prism render` renders without a SCENE argument: the repository's spectral
/// effects stage (`scenes/effects.gltf`, one file with its buffer embedded): dispersion,
/// fluorescence under UV, and a blackbody and a standard illuminant side by side.
const DEFAULT_GLTF: &[u8] = include_bytes!("../../../../scenes/effects.gltf");

/// The scene, and the camera response to render it with (the command line's, else the
/// scene's own, else none: the CIE observer). Notes on stderr what the render will not
/// show of it, or where it adds light.
pub(super) fn prepare(
    args: &RenderArgs,
    loaded: Option<(LoadedGeometry, FileDefaults)>,
) -> Result<(Scene, Option<CameraResponse>, FileDefaults), String> {
    let (loaded, defaults) = match loaded {
        Some(loaded) => loaded,
        None => load(args)?,
    };
    let quality = match args.bvh.as_str() {
        "medium" => BvhQuality::Medium,
        "slow" => BvhQuality::Slow,
        other => return Err(format!("--bvh '{other}': expected medium or slow")),
    };
    let options = SceneOptions::default()
        .camera(args.camera.clone())
        .environment(environment(args)?)
        .quality(quality);
    let camera = args
        .camera_response
        .as_deref()
        .map(|path| {
            let text = crate::output::read_text(path)?;
            CameraResponse::from_csv(&text).map_err(|e| format!("'{}': {e}", path.display()))
        })
        .transpose()?;
    // The command line's camera wins over the scene's own.
    let camera = match camera {
        Some(c) => Some(c),
        None => scene_camera(&loaded)?,
    };
    let mut loaded = loaded;
    let lens_flags = lens_overrides(args, &mut loaded.cameras)?;
    let summary = loaded.summary();
    let (polarizing, timed) = (summary.polarizing, summary.timed);
    let scene = Scene::from_loaded(loaded, &options).map_err(|e| e.to_string())?;
    if polarizing != (0, 0) && !args.polarized && args.camera_polarizer.is_none() {
        eprintln!(
            "prism: note: the scene has polarizers, retarders or polarized lights, which only a polarized render shows (--polarized); this one sees their intensity only"
        );
    }
    if timed != (0, 0) && args.at.is_none() && args.shutter.is_none() && !args.quiet {
        eprintln!(
            "prism: note: the scene has schedules or phosphors; without --at every source has always been on (the steady state)"
        );
    }
    if lens_flags && !matches!(scene.camera().projection, Projection::Perspective { .. }) {
        return Err(format!(
            "--lens, --f-number, --aperture-radius and --focus-distance need a perspective camera; '{}' is orthographic",
            scene.camera().name
        ));
    }
    let features = scene.features();
    if features.media && features.specular {
        eprintln!(
            "prism: warning: the scene has participating media, which light paths do not cross yet: caustics that only light paths find (a point, spot or directional light through glass or off a mirror onto a diffuse surface) do not show"
        );
    }
    if scene.lit_by_default() {
        eprintln!(
            "prism: the scene has no light source (only glowing surfaces, if any); lighting it with a \
             neutral environment (CIE D65, --environment {DEFAULT_ENVIRONMENT}); choose another with --environment VALUE|FILE"
        );
    }
    Ok((scene, camera, defaults))
}

fn load(args: &RenderArgs) -> Result<(LoadedGeometry, FileDefaults), String> {
    if let Some(path) = args.scene.as_deref()
        && crate::scene_file::is_mitsuba(path)
    {
        let scene = crate::scene_file::load_mitsuba(path, &args.defines)?;
        let defaults = FileDefaults::of_mitsuba(&scene);
        return Ok((scene.geometry, defaults));
    }
    if !args.defines.is_empty() {
        return Err("-D sets a Mitsuba scene's parameters; this scene is not one (.xml)".into());
    }
    let geometry = load_geometry_file(args.scene.as_deref(), args.scene_index)?;
    Ok((geometry, FileDefaults::default()))
}

fn load_geometry_file(path: Option<&Path>, scene: Option<usize>) -> Result<LoadedGeometry, String> {
    match path {
        Some(p) => crate::scene_file::load(p, scene),
        None => load_geometry(
            DEFAULT_GLTF,
            &|uri| Err(std::io::Error::other(format!("no file '{uri}'"))),
            scene,
        )
        .map_err(|e| format!("embedded scene: {e}")),
    }
}

/// The output size: what the command line gives, the rest from the camera's aspect ratio
/// (square without one), 512 pixels high when neither is given.
pub(super) fn image_size(
    width: Option<u32>,
    height: Option<u32>,
    aspect: Option<f32>,
) -> (u32, u32) {
    let aspect = f64::from(aspect.unwrap_or(1.0));
    let scaled = |v: u32, by: f64| ((f64::from(v) * by).round() as u32).max(1);
    match (width, height) {
        (Some(w), Some(h)) => (w, h),
        (Some(w), None) => (w, scaled(w, 1.0 / aspect)),
        (None, h) => {
            let h = h.unwrap_or(512);
            (scaled(h, aspect), h)
        }
    }
}

/// The camera response a scene describes (`camera_response` on the root's
/// `PRISM_spectral`), over where its curves exceed 0.1% of their peaks.
fn scene_camera(loaded: &LoadedGeometry) -> Result<Option<CameraResponse>, String> {
    let Some(curves) = &loaded.spectral.camera_response else {
        return Ok(None);
    };
    let range = curves
        .iter()
        .filter_map(|c| c.extent(1e-3))
        .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))
        .ok_or("the scene's camera_response is zero everywhere")?;
    let curves: [ResponseCurve; 3] = curves.clone().map(|c| Arc::new(c) as ResponseCurve);
    CameraResponse::new(curves, range)
        .map(Some)
        .map_err(|e| format!("the scene's {e}"))
}

/// The environment the command line asks for: a grey of an emissive-colour value, or an
/// image file, either times --environment-strength.
fn environment(args: &RenderArgs) -> Result<Option<Environment>, String> {
    let (rotation, strength) = (args.environment_rotation, args.environment_strength);
    if !rotation.is_finite() {
        return Err(format!(
            "--environment-rotation {} must be a finite number of degrees",
            Readable(rotation)
        ));
    }
    // Radiance is f32 in the renderer: beyond f32::MAX a value would saturate there.
    let in_range = |v: f64| v >= 0.0 && v <= f64::from(f32::MAX);
    if !in_range(strength) {
        return Err(format!(
            "--environment-strength {} must be >= 0 and at most f32's largest value, 3.4e38",
            Readable(strength)
        ));
    }
    let Some(text) = &args.environment else {
        return Ok(None);
    };
    if let Ok(value) = text.parse::<f64>() {
        let value = value * strength;
        if !in_range(value) {
            return Err(format!(
                "--environment {} must be >= 0 and at most f32's largest value, 3.4e38",
                Readable(value)
            ));
        }
        return Ok(Some(Environment::Uniform(grey_environment(value))));
    }
    let path = Path::new(text);
    let bytes =
        std::fs::read(path).map_err(|e| format!("--environment '{}': {e}", path.display()))?;
    let map = environment_map(&bytes, rotation, strength)
        .map_err(|e| format!("--environment '{}': {e}", path.display()))?;
    Ok(Some(Environment::Map(map)))
}

/// Applies the command line's lens (`--lens`, `--f-number`, `--aperture-radius`,
/// `--focus-distance`) to every perspective camera, over what the scene says; whether any
/// was given. A camera with a lens system (its own or `--lens`) takes the f-number and
/// the distance in focus for it.
fn lens_overrides(args: &RenderArgs, cameras: &mut [Camera]) -> Result<bool, String> {
    if let Some(path) = &args.lens {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("--lens '{}': {e}", path.display()))?;
        let system =
            parse_prescription(&text).map_err(|e| format!("--lens '{}': {e}", path.display()))?;
        for camera in cameras
            .iter_mut()
            .filter(|c| matches!(c.projection, Projection::Perspective { .. }))
        {
            // The film's size, the distance in focus and a lens system's f-number stay
            // the camera's.
            let mounted = MountedLens {
                f_number: camera.system.as_ref().and_then(|s| s.f_number),
                focus_distance: camera
                    .system
                    .as_ref()
                    .and_then(|s| s.focus_distance)
                    .or(camera.lens.as_ref().and_then(|l| l.focus_distance)),
                sensor_width: camera
                    .system
                    .as_ref()
                    .map(|s| s.sensor_width)
                    .or(camera.lens.as_ref().map(|l| l.sensor_width))
                    .unwrap_or(prism_scene::camera::FULL_FRAME_WIDTH),
                ..MountedLens::new(path.display().to_string(), system.clone())
            };
            camera.lens = None;
            camera.system = Some(mounted);
        }
    }
    let mut any = args.lens.is_some();
    for camera in cameras.iter_mut() {
        let Some(mounted) = &mut camera.system else {
            continue;
        };
        if args.aperture_radius.is_some() {
            return Err(format!(
                "--aperture-radius is a thin lens's; camera '{}' has a lens system, whose stop --f-number closes",
                camera.name
            ));
        }
        if let Some(n) = args.f_number {
            if !(n.is_finite() && n > 0.0) {
                return Err(format!("--f-number {n} must be finite and > 0"));
            }
            mounted.f_number = Some(n);
            any = true;
        }
        if let Some(d) = args.focus_distance {
            if !(d.is_finite() && d > 0.0) {
                return Err(format!("--focus-distance {d} must be finite and > 0"));
            }
            mounted.focus_distance = Some(d);
            any = true;
        }
    }
    if cameras.iter().any(|c| c.system.is_some()) {
        return Ok(any);
    }
    let size = match (args.f_number, args.aperture_radius) {
        (Some(n), _) => Some(ApertureSize::FNumber(n)),
        (None, Some(r)) => Some(ApertureSize::Radius(r)),
        (None, None) => None,
    };
    if size.is_none() && args.focus_distance.is_none() {
        return Ok(false);
    }
    for camera in cameras
        .iter_mut()
        .filter(|c| matches!(c.projection, Projection::Perspective { .. }))
    {
        let mut lens = match (camera.lens.clone(), size) {
            (_, Some(size)) => ThinLens {
                size,
                ..camera.lens.clone().unwrap_or(ThinLens::new(size))
            },
            (Some(lens), None) => lens,
            (None, None) => {
                return Err(format!(
                    "--focus-distance needs an aperture: give --f-number or --aperture-radius (camera '{}' has none)",
                    camera.name
                ));
            }
        };
        if let Some(d) = args.focus_distance {
            lens.focus_distance = Some(d);
        }
        lens.validate()
            .map_err(|e| format!("camera '{}': {e}", camera.name))?;
        camera.lens = Some(lens);
    }
    Ok(true)
}
