//! Mitsuba's media as prism reads them: the coefficients, phase functions, volumes and
//! `.vol` conventions, where media are (shapes' sides, the sensor), and the errors.

use glam::{UVec3, Vec3};
use prism_spectrum::SampledWavelengths;

use super::ParseOptions;
use super::scene::{MitsubaScene, load};
use crate::LoadError;
use crate::load::LoadOptions;
use crate::medium::{Albedo, Filter, Media, Phase, Sides, write_vol};

/// Loads `body` inside a scene with a sensor and `integrator`, with `files` readable by
/// name.
fn scene(
    integrator: &str,
    body: &str,
    files: &[(&str, Vec<u8>)],
) -> Result<MitsubaScene, LoadError> {
    let text = format!(
        r#"<scene version="3.0.0">
  <integrator type="{integrator}"><integer name="max_depth" value="6"/></integrator>
  <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
{body}
</scene>"#
    );
    let files: Vec<(String, Vec<u8>)> = files
        .iter()
        .map(|(n, b)| (format!("dir/{n}"), b.clone()))
        .collect();
    let resolve = move |name: &str| -> std::io::Result<Vec<u8>> {
        files
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, b)| b.clone())
            .ok_or_else(|| std::io::Error::other(format!("no file {name}")))
    };
    let options = ParseOptions {
        defines: &[],
        resolve: &resolve,
    };
    load(&text, "dir/scene.xml", &options, &LoadOptions::default())
}

fn media(s: &MitsubaScene) -> &Media {
    s.geometry.media.as_ref().expect("media")
}

fn error(result: Result<MitsubaScene, LoadError>) -> String {
    let e = result.expect_err("an error").to_string();
    assert!(!e.contains('\n'), "{e}");
    e
}

fn wavelengths() -> SampledWavelengths<4> {
    SampledWavelengths::new([400.0, 500.0, 600.0, 700.0], [1.0; 4]).unwrap()
}

/// A cube with a null boundary around `medium`.
fn cube_of(medium: &str) -> String {
    format!(
        r#"{medium}
  <shape type="cube"><bsdf type="null"/><ref name="interior" id="m"/></shape>"#
    )
}

#[test]
fn homogeneous_coefficients_are_scale_sigma_t_and_albedo() {
    let s = scene(
        "volpath",
        &cube_of(
            r#"<medium type="homogeneous" id="m">
    <float name="sigma_t" value="2"/><float name="albedo" value="0.25"/><float name="scale" value="3"/>
  </medium>"#,
        ),
        &[],
    )
    .unwrap();
    let media = media(&s);
    assert_eq!(media.all().len(), 1);
    let p = media.get(0).at(&wavelengths());
    assert!(
        (p.sigma_s[0] - 1.5).abs() < 1e-6 && (p.sigma_a[2] - 4.5).abs() < 1e-6,
        "{p:?}"
    );
    assert!(media.get(0).transmittance_in_closed_form());
    // Mitsuba's default phase function is isotropic; the boundary is an interface.
    assert_eq!(*media.get(0).phase(), Phase::HenyeyGreenstein { g: 0.0 });
    let surface = s.geometry.materials[0]
        .spectral
        .as_ref()
        .and_then(|m| m.surface.as_ref());
    assert!(surface.is_some_and(|m| m.interface()));
    assert_eq!(
        media.sides(0),
        Some(Sides {
            inside: Some(0),
            outside: None
        })
    );
    assert!(media.crossing_sets());
}

/// Mitsuba's defaults (sigma_t 1, albedo 0.75), an RGB albedo as a reflectance, and
/// `hg`'s default g of 0.8, forward.
#[test]
fn defaults_colours_and_phase_functions() {
    let s = scene(
        "volpathmis",
        &cube_of(r#"<medium type="homogeneous" id="m"><phase type="hg"/></medium>"#),
        &[],
    )
    .unwrap();
    let m = media(&s).get(0);
    let p = m.at(&wavelengths());
    assert!((p.sigma_s[1] - 0.75).abs() < 1e-6 && (p.sigma_a[1] - 0.25).abs() < 1e-6);
    assert_eq!(*m.phase(), Phase::HenyeyGreenstein { g: 0.8 });
    let s = scene(
        "volpath",
        &cube_of(
            r#"<medium type="homogeneous" id="m"><rgb name="albedo" value="0.9, 0.1, 0.1"/>
    <rgb name="sigma_t" value="1, 0.5, 0.25"/><phase type="rayleigh"/></medium>"#,
        ),
        &[],
    )
    .unwrap();
    let m = media(&s).get(0);
    assert_eq!(*m.phase(), Phase::Rayleigh);
    let p = m.at(&wavelengths());
    let albedo = |i: usize| p.sigma_s[i] / (p.sigma_s[i] + p.sigma_a[i]);
    // Red scatters, green absorbs; the extinction (red the most) rises towards the red.
    assert!(albedo(3) > 0.7 && albedo(1) < 0.3, "{p:?}");
    assert!(p.sigma_s[3] + p.sigma_a[3] > p.sigma_s[1] + p.sigma_a[1]);
}

/// A `.vol` grid as Mitsuba places it: on `to_world`'s unit cube by default (the file's
/// box ignored), on the file's box under `to_world` with `use_grid_bbox`; x fastest;
/// nothing outside the box; nearest filtering when asked.
#[test]
fn grids_follow_mitsubas_vol_conventions() {
    // 4 x 2 x 1 voxels: value = x index + 10 y, on a file box Mitsuba ignores by default.
    let values: Vec<f32> = (0..8)
        .map(|i| (i % 4) as f32 + 10.0 * (i / 4) as f32)
        .collect();
    let vol = write_vol(
        UVec3::new(4, 2, 1),
        Vec3::splat(5.0),
        Vec3::splat(6.0),
        &values,
    );
    let medium = |extra: &str| {
        format!(
            r#"<medium type="heterogeneous" id="m"><float name="albedo" value="0.5"/><float name="scale" value="2"/>
    <volume type="gridvolume" name="sigma_t"><string name="filename" value="d.vol"/>{extra}
      <transform name="to_world"><scale value="2"/><translate x="1"/></transform></volume></medium>"#
        )
    };
    let s = scene("volpath", &cube_of(&medium("")), &[("d.vol", vol.clone())]).unwrap();
    let m = media(&s).get(0);
    let grid = m.density().unwrap();
    assert_eq!(
        grid.bounds(),
        (Vec3::new(1.0, 0.0, 0.0), Vec3::new(3.0, 2.0, 2.0))
    );
    assert_eq!(grid.filter(), Filter::Trilinear);
    // Voxel (2, 1) at its centre: x = 1 + 2 (2.5 / 4), y = 2 (1.5 / 2).
    let centre = Vec3::new(1.0 + 2.0 * 2.5 / 4.0, 1.5, 1.0);
    assert!((grid.lookup(centre) - 12.0).abs() < 1e-5);
    assert_eq!(grid.lookup(Vec3::new(0.5, 1.0, 1.0)), 0.0);
    // The medium's extinction per unit density is the scale, its albedo the constant.
    let p = m.at(&wavelengths());
    assert!((p.sigma_s[0] - 1.0).abs() < 1e-6 && (p.sigma_a[0] - 1.0).abs() < 1e-6);

    let s = scene(
        "volpath",
        &cube_of(&medium(
            r#"<boolean name="use_grid_bbox" value="true"/><string name="filter_type" value="nearest"/>"#,
        )),
        &[("d.vol", vol)],
    )
    .unwrap();
    let grid = media(&s).get(0).density().unwrap().clone();
    assert_eq!(
        grid.bounds(),
        (Vec3::new(11.0, 10.0, 10.0), Vec3::new(13.0, 12.0, 12.0))
    );
    assert_eq!(grid.filter(), Filter::Nearest);
    // Nearest: just past voxel 1's boundary on x is voxel 2's value, not a blend.
    assert_eq!(grid.lookup(Vec3::new(11.0 + 2.0 * 0.51, 10.5, 11.0)), 2.0);
}

/// A grid of three channels is a spectrum per voxel: 2 max(r, g, b) times a reflectance
/// fitted to the colour over it; as sigma_t it is a spectral density, as albedo a
/// varying albedo (clamped outside its box).
#[test]
fn colour_grids_are_spectra() {
    let rgb = [0.8f32, 0.2, 0.1, 0.1, 0.3, 0.9];
    let mut vol = write_vol(UVec3::new(2, 1, 1), Vec3::ZERO, Vec3::ONE, &rgb);
    vol[20..24].copy_from_slice(&3i32.to_le_bytes());
    let s = scene(
        "volpath",
        &cube_of(
            r#"<medium type="heterogeneous" id="m">
    <volume type="gridvolume" name="sigma_t"><string name="filename" value="c.vol"/></volume>
    <volume type="gridvolume" name="albedo"><string name="filename" value="c.vol"/></volume></medium>"#,
        ),
        &[("c.vol", vol)],
    )
    .unwrap();
    let m = media(&s).get(0);
    let grid = m.spectral_density().expect("a spectral density");
    let w = wavelengths();
    let red = grid.lookup(Vec3::new(0.25, 0.5, 0.5), &w);
    let blue = grid.lookup(Vec3::new(0.75, 0.5, 0.5), &w);
    assert!(red[3] > 0.5 && red[3] < 1.6 && red[0] < red[3], "{red:?}");
    assert!(blue[0] > blue[3], "{blue:?}");
    assert!(grid.max_value() >= 1.6 - 1e-6);
    assert!(matches!(m.albedo(), Some(Albedo::Spectral(_))));
    // The albedo at the red voxel: sigma_s / sigma_t is the grid's value there.
    let base = m.at(&w);
    let p = m.point(&base, Vec3::new(0.25, 0.5, 0.5), &w);
    let t = p.sigma_a[3] + p.sigma_s[3];
    assert!((p.sigma_s[3] / t - red[3]).abs() < 1e-4, "{p:?}");
}

/// A `constvolume` extinction fills its box only (Mitsuba clips a heterogeneous medium to
/// its sigma_t's box), with its spectrum.
#[test]
fn a_constant_volume_fills_its_box() {
    let s = scene(
        "volpath",
        &cube_of(
            r#"<medium type="heterogeneous" id="m"><rgb name="albedo" value="0"/><float name="scale" value="5"/>
    <volume type="constvolume" name="sigma_t"><spectrum name="value" value="400:0.2, 700:0.8"/>
      <transform name="to_world"><translate x="-0.5" y="-0.5" z="-0.5"/></transform></volume></medium>"#,
        ),
        &[],
    )
    .unwrap();
    let m = media(&s).get(0);
    assert_eq!(
        m.density().unwrap().bounds(),
        (Vec3::splat(-0.5), Vec3::splat(0.5))
    );
    let w = wavelengths();
    let base = m.at(&w);
    let inside = m.point(&base, Vec3::splat(0.1), &w);
    assert!((inside.sigma_a[0] - 1.0).abs() < 1e-5 && (inside.sigma_a[3] - 4.0).abs() < 1e-5);
    assert_eq!(inside.sigma_s[1], 0.0);
    let outside = m.point(&base, Vec3::splat(0.7), &w);
    assert_eq!(outside.sigma_a[3], 0.0);
}

/// Where media are: the sensor's is the world's; a shape's exterior is the medium in
/// front of it; shapes sharing a BSDF but not media get materials of their own; one
/// medium referenced twice is read once.
#[test]
fn media_are_where_shapes_and_the_sensor_say() {
    let text = r#"<scene version="3.0.0">
  <integrator type="moment"><integrator type="volpath"><integer name="max_depth" value="4"/></integrator></integrator>
  <medium type="homogeneous" id="fog"><float name="sigma_t" value="0.1"/></medium>
  <medium type="homogeneous" id="milk"><float name="sigma_t" value="5"/></medium>
  <bsdf type="dielectric" id="glass"/>
  <sensor type="perspective"><ref id="fog"/></sensor>
  <shape type="cube"><ref id="glass"/><ref name="interior" id="milk"/><ref name="exterior" id="fog"/></shape>
  <shape type="cube"><ref id="glass"/></shape>
  <shape type="rectangle"><ref id="glass"/><ref name="interior" id="milk"/></shape>
</scene>"#;
    let none = |n: &str| -> std::io::Result<Vec<u8>> { Err(std::io::Error::other(n.to_string())) };
    let options = ParseOptions {
        defines: &[],
        resolve: &none,
    };
    let s = load(text, "s.xml", &options, &LoadOptions::default()).unwrap();
    // The moment integrator's nested volpath renders, with its depth.
    assert_eq!(s.max_depth, Some(3));
    let media = media(&s);
    assert_eq!(media.all().len(), 2);
    assert_eq!(media.world(), Some(0));
    let [a, b, c] = [0, 1, 2].map(|i| s.geometry.instances[i].material.unwrap());
    assert!(a != b && a != c && b != c, "{a} {b} {c}");
    let side = |inside, outside| Some(Sides { inside, outside });
    assert_eq!(media.sides(a as u32), side(Some(1), Some(0)));
    assert_eq!(media.sides(b as u32), None);
    assert_eq!(media.sides(c as u32), side(Some(1), None));
}

/// Mitsuba's `path` integrator (also its default) ignores media: so does prism then.
#[test]
fn integrators_without_media_drop_them() {
    let body = cube_of(r#"<medium type="homogeneous" id="m"/>"#);
    let s = scene("path", &body, &[]).unwrap();
    assert!(s.geometry.media.is_none());
    assert!(
        s.geometry
            .warnings
            .iter()
            .any(|w| w.contains("ignores participating media")),
        "{:?}",
        s.geometry.warnings
    );
}

#[test]
fn bad_media_are_one_line_errors() {
    let cases = [
        (
            r#"<medium type="homogeneous" id="m"><rgb name="sigma_t" value="2, 1, 1"/></medium>"#,
            "outside [0, 1]",
        ),
        (
            r#"<medium type="homogeneous" id="m"><float name="albedo" value="1.5"/></medium>"#,
            "albedo must be in [0, 1]",
        ),
        (
            r#"<medium type="homogeneous" id="m"><phase type="hg"><float name="g" value="1"/></phase></medium>"#,
            "must be in (-1, 1)",
        ),
        (
            r#"<medium type="homogeneous" id="m"><phase type="sggx"/></medium>"#,
            "phase 'sggx' is not read yet",
        ),
        (
            r#"<medium type="homogeneous" id="m"><phase type="isotropic"/><phase type="hg"/></medium>"#,
            "one phase function",
        ),
        (
            r#"<medium type="homogeneous" id="m"><float name="density" value="1"/></medium>"#,
            "parameter 'density' is not read",
        ),
        (
            r#"<medium type="homogeneous" id="m"><volume type="gridvolume" name="sigma_t"><string name="filename" value="g.vol"/></volume></medium>"#,
            "sigma_t is one value",
        ),
        (
            r#"<medium type="heterogeneous" id="m"><volume type="gridvolume" name="sigma_t"><string name="filename" value="g.vol"/>
               <transform name="to_world"><rotate y="1" angle="30"/></transform></volume></medium>"#,
            "rotates, shears or mirrors",
        ),
        (
            r#"<medium type="heterogeneous" id="m"><volume type="gridvolume" name="sigma_t"><string name="filename" value="g.vol"/>
               <string name="wrap_mode" value="repeat"/></volume></medium>"#,
            "wrap_mode \"repeat\" is not read yet",
        ),
        (
            r#"<medium type="heterogeneous" id="m"><volume type="gridvolume" name="sigma_t"><string name="filename" value="huge.vol"/></volume></medium>"#,
            "more than prism reads",
        ),
        (
            r#"<medium type="heterogeneous" id="m"><volume type="gridvolume" name="sigma_t"><string name="filename" value="missing.vol"/></volume></medium>"#,
            "missing.vol",
        ),
        (
            r#"<medium type="foggy" id="m"/>"#,
            "medium 'foggy' is not read yet",
        ),
    ];
    let grid = write_vol(UVec3::ONE, Vec3::ZERO, Vec3::ONE, &[1.0]);
    let mut huge = grid.clone();
    for at in [8, 12, 16] {
        huge[at..at + 4].copy_from_slice(&100_000i32.to_le_bytes());
    }
    for (medium, expected) in cases {
        let e = error(scene(
            "volpath",
            &cube_of(medium),
            &[("g.vol", grid.clone()), ("huge.vol", huge.clone())],
        ));
        assert!(e.contains(expected), "{e}");
        assert!(e.starts_with("dir/scene.xml:"), "{e}");
    }
}
