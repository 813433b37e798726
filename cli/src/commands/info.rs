//! `prism info`: what a scene contains.

use std::path::PathBuf;

use clap::Args;
use prism_scene::geometry::{Bvh, BvhQuality};

#[derive(Debug, Args)]
#[command(after_help = "Example:\n  prism info scenes/cornell-bunny.gltf")]
pub struct InfoArgs {
    /// A .gltf or .glb file, or a Mitsuba 3 scene (.xml).
    pub scene: PathBuf,
    /// Which scene of the file (default: its default scene).
    #[arg(long, visible_alias = "scene", value_name = "N")]
    pub scene_index: Option<usize>,
}

pub fn run(args: &InfoArgs) -> Result<(), String> {
    let loaded = crate::scene_file::load(&args.scene, args.scene_index)?;
    let s = loaded.summary();
    let start = std::time::Instant::now();
    let bvh = Bvh::build(&loaded.triangles, BvhQuality::Medium);
    let build = start.elapsed().as_secs_f64();
    outln!("scene          {}", args.scene.display());
    outln!(
        "triangles      {} ({} degenerate skipped)",
        s.triangles,
        bvh.skipped()
    );
    outln!("instances      {}", s.instances);
    outln!("materials      {}", s.materials);
    outln!(
        "area lights    {} instances, {} triangles",
        s.emissive_instances,
        s.emissive_triangles
    );
    outln!(
        "cameras        {}",
        if s.cameras.is_empty() {
            "none (a default camera frames the scene)".into()
        } else {
            s.cameras.join(", ")
        }
    );
    for camera in &loaded.cameras {
        if let Some(lens) = &camera.lens {
            outln!("lens           {}: {}", camera.name, describe_lens(lens));
        }
        if let Some(system) = &camera.system {
            outln!(
                "lens           {}: {}",
                camera.name,
                describe_system(system)
            );
        }
    }
    outln!("bounds         {:?} .. {:?}", s.bounds.0, s.bounds.1);
    outln!(
        "features       transmission: {}, dispersion: {}, fluorescence: {}, textures: {}",
        yes(s.uses_transmission),
        yes(s.uses_dispersion),
        yes(s.uses_fluorescence),
        yes(s.uses_textures)
    );
    outln!(
        "media          {}",
        if s.media.is_empty() {
            "none (a vacuum: the path tracer renders it)".into()
        } else {
            format!(
                "{} (the volumetric path tracer renders it)",
                s.media.join("; ")
            )
        }
    );
    let (elements, lights) = s.polarizing;
    outln!(
        "polarization   {}",
        if elements + lights == 0 {
            "no polarizers, retarders or polarized lights (--polarized still shows what glass and metals do)".into()
        } else {
            format!(
                "{elements} polarizing materials (polarizers, retarders), {lights} polarized lights: render with --polarized to see them"
            )
        }
    );
    let (scheduled, phosphors) = s.timed;
    outln!(
        "time           {}",
        if scheduled + phosphors == 0 {
            "no schedules or phosphors (--at renders the same image at any time)".into()
        } else {
            format!(
                "{scheduled} scheduled sources, {phosphors} phosphorescent materials: render an instant with --at SECONDS"
            )
        }
    );
    // A Mitsuba scene lists what prism makes of its plugins where it is not the plugin
    // itself (shapes it tessellates, instances it copies); a glTF file its features.
    let (format, plain) = if crate::scene_file::is_mitsuba(&args.scene) {
        ("Mitsuba        ", "every plugin as it is")
    } else {
        ("glTF           ", "core only")
    };
    outln!(
        "{format}{}",
        if s.gltf_features.is_empty() {
            plain.into()
        } else {
            s.gltf_features.join(", ")
        }
    );
    outln!(
        "light spectra  {}",
        if s.light_spectra.is_empty() {
            "none (a neutral D65 environment lights the scene)".into()
        } else {
            s.light_spectra.join("; ")
        }
    );
    outln!(
        "wavelengths    {}-{} nm needed (lights and fluorescence; --spectral-range and the samplers' range should cover it)",
        s.wavelength_range.0,
        s.wavelength_range.1
    );
    outln!(
        "memory         {:.1} MB triangles + BVH (built in {:.0} ms)",
        bvh.memory_bytes() as f64 / 1e6,
        build * 1e3
    );
    Ok(())
}

fn yes(b: bool) -> &'static str {
    if b { "yes" } else { "no" }
}

/// A lens system in a line: its file, focal length and f-number, focus, sensor.
fn describe_system(mounted: &prism_scene::camera::MountedLens) -> String {
    use prism_scene::camera::system::D_LINE_NM;
    let optics = match mounted.system.paraxial(D_LINE_NM) {
        Ok(p) => format!("{:.1} mm f/{:.2} wide open", p.efl_mm, p.f_number),
        Err(e) => e,
    };
    let stop = mounted
        .f_number
        .map_or(String::new(), |n| format!(", stopped to f/{n}"));
    let focus = mounted
        .focus_distance
        .map_or("focused on what the image's centre sees".into(), |d| {
            format!("focused at {d} m")
        });
    format!(
        "lens system {} ({optics}{stop}, {} interfaces{}), {focus}, sensor {} mm wide",
        mounted.source,
        mounted.system.interfaces().len(),
        if mounted.system.dispersive() {
            ", dispersive glass"
        } else {
            ""
        },
        mounted.sensor_width * 1000.0
    )
}

/// A thin lens in a line: aperture, shape, focus, sensor.
fn describe_lens(lens: &prism_scene::camera::ThinLens) -> String {
    use prism_scene::camera::{ApertureShape, ApertureSize};
    let size = match lens.size {
        ApertureSize::FNumber(n) => format!("f/{n}"),
        ApertureSize::Radius(r) => format!("aperture radius {r} m"),
    };
    let shape = match &lens.shape {
        ApertureShape::Disk => "round".to_string(),
        ApertureShape::Polygon { blades, .. } => format!("{blades} blades"),
        ApertureShape::Image(_) => "shaped by an image".to_string(),
    };
    let focus = lens
        .focus_distance
        .map_or("focused on what the image's centre sees".into(), |d| {
            format!("focused at {d} m")
        });
    format!(
        "thin lens, {size}, {shape}, {focus}, sensor {} mm wide",
        lens.sensor_width * 1000.0
    )
}
