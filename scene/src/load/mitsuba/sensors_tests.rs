//! Sensors, films and their filters as Mitsuba defines them, and the warnings for what
//! prism ignores.

use glam::{Vec2, Vec3};

use super::ParseOptions;
use super::scene::{MitsubaScene, load};
use super::sensors::PixelFilter;
use crate::camera::{ApertureSize, Projection};
use crate::load::LoadOptions;

fn scene(sensor: &str) -> Result<MitsubaScene, String> {
    let text = format!(
        r#"<scene version="3.0.0">
    {sensor}
    <shape type="rectangle"><bsdf type="diffuse"/></shape>
</scene>"#
    );
    let none = |name: &str| -> std::io::Result<Vec<u8>> {
        Err(std::io::Error::other(format!("no file {name}")))
    };
    let options = ParseOptions {
        defines: &[],
        resolve: &none,
    };
    load(&text, "s.xml", &options, &LoadOptions::default()).map_err(|e| e.to_string())
}

fn film(rfilter: &str) -> String {
    format!(
        r#"<film type="hdrfilm"><integer name="width" value="40"/><integer name="height" value="20"/>{rfilter}</film>"#
    )
}

#[test]
fn orthographic_views_two_by_two_over_aspect_in_its_scaled_frame() {
    // Mitsuba's view is x in [-1, 1], y in [-1/aspect, 1/aspect], scaled by to_world; the
    // image's left is the sensor's local +x (which lookat makes world +x here).
    let s = scene(&format!(
        r#"<sensor type="orthographic"><transform name="to_world"><scale x="2" y="3"/>
        <lookat origin="0, 0, 0" target="0, 0, 1" up="0, 1, 0"/></transform>{}</sensor>"#,
        film("")
    ))
    .unwrap();
    let camera = &s.geometry.cameras[0];
    let Projection::Orthographic { xmag, ymag } = camera.projection else {
        panic!("{:?}", camera.projection)
    };
    assert!(
        (xmag - 2.0).abs() < 1e-6 && (ymag - 1.5).abs() < 1e-6,
        "{xmag} {ymag}"
    );
    let left = camera.generate_ray(Vec2::new(0.0, 0.5), 2.0);
    assert!(
        (left.origin - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-5,
        "{:?}",
        left.origin
    );
    assert!((left.direction - Vec3::Z).length() < 1e-6);
    let top = camera.generate_ray(Vec2::new(0.5, 0.0), 2.0);
    assert!(
        (top.origin - Vec3::new(0.0, 1.5, 0.0)).length() < 1e-5,
        "{:?}",
        top.origin
    );
}

#[test]
fn an_orthographic_frame_with_shear_is_refused() {
    let e = scene(
        r#"<sensor type="orthographic"><transform name="to_world">
        <matrix value="1 1 0 0  0 1 0 0  0 0 1 0  0 0 0 1"/></transform></sensor>"#,
    )
    .unwrap_err();
    assert!(e.contains("s.xml:2") && e.contains("rotation"), "{e}");
}

#[test]
fn thinlens_keeps_its_aperture_and_focus() {
    let s = scene(
        r#"<sensor type="thinlens"><float name="aperture_radius" value="0.1"/>
        <float name="focus_distance" value="3"/><float name="fov" value="30"/></sensor>"#,
    )
    .unwrap();
    let lens = s.geometry.cameras[0].lens.as_ref().unwrap();
    assert_eq!(lens.size, ApertureSize::Radius(0.1));
    assert_eq!(lens.focus_distance, Some(3.0));
    let e = scene(r#"<sensor type="thinlens"/>"#).unwrap_err();
    assert!(e.contains("aperture_radius"), "{e}");
}

#[test]
fn the_film_filter_is_mitsubas_with_its_default_gaussian() {
    let filter = |rfilter: &str| {
        scene(&format!(
            r#"<sensor type="perspective">{}</sensor>"#,
            film(rfilter)
        ))
        .map(|s| (s.film.filter, s.geometry.warnings))
    };
    let gaussian = PixelFilter::Gaussian { stddev: 0.5 };
    assert_eq!(filter("").unwrap().0, gaussian);
    assert_eq!(
        scene("<sensor type=\"perspective\"/>").unwrap().film.filter,
        gaussian
    );
    assert_eq!(
        filter(r#"<rfilter type="box"/>"#).unwrap().0,
        PixelFilter::Box
    );
    assert_eq!(
        filter(r#"<rfilter type="gaussian"><float name="stddev" value="0.25"/></rfilter>"#)
            .unwrap()
            .0,
        PixelFilter::Gaussian { stddev: 0.25 }
    );
    assert_eq!(
        filter(r#"<rfilter type="tent"/>"#).unwrap().0,
        PixelFilter::Tent { radius: 1.0 }
    );
    let (f, warnings) = filter(r#"<rfilter type="mitchell"/>"#).unwrap();
    assert_eq!(f, gaussian);
    assert!(
        warnings
            .iter()
            .any(|w| w.contains("mitchell") && w.contains("negative")),
        "{warnings:?}"
    );
    assert!(
        filter(r#"<rfilter type="bogus"/>"#)
            .unwrap_err()
            .contains("bogus")
    );
    let e = filter(r#"<integer name="crop_width" value="4"/>"#).unwrap_err();
    assert!(e.contains("crop_width"), "{e}");
}

#[test]
fn every_parameter_prism_does_not_read_is_one_warning_with_its_line() {
    let s = scene(
        r#"<sensor type="perspective"><float name="fov" value="40"/>
        <float name="shutter_close" value="1"/>
        <film type="hdrfilm"><boolean name="sample_border" value="true"/></film></sensor>"#,
    )
    .unwrap();
    let unread: Vec<&String> = s
        .geometry
        .warnings
        .iter()
        .filter(|w| w.contains("is not read"))
        .collect();
    assert_eq!(unread.len(), 2, "{unread:?}");
    assert!(unread[0].starts_with("s.xml:3:") && unread[0].contains("'shutter_close'"));
    assert!(unread[1].starts_with("s.xml:4:") && unread[1].contains("'sample_border'"));
    assert!(!s.geometry.warnings.iter().any(|w| w.contains("'fov'")));
}

#[test]
fn without_a_fov_the_lens_is_50mm_on_the_full_frame_diagonal() {
    let yfov = |sensor: &str| {
        let s = scene(sensor).unwrap();
        match s.geometry.cameras[0].projection {
            Projection::Perspective { yfov } => f64::from(yfov),
            other => panic!("{other:?}"),
        }
    };
    // 40 x 20 pixels: the diagonal is sqrt(5) of the height.
    let expected = |mm: f64| {
        let half_diagonal = (36.0f64.hypot(24.0) / (2.0 * mm)).atan();
        2.0 * (half_diagonal.tan() / 5.0f64.sqrt()).atan()
    };
    let default = yfov(&format!(
        r#"<sensor type="perspective">{}</sensor>"#,
        film("")
    ));
    assert!((default - expected(50.0)).abs() < 1e-6, "{default}");
    let wide = yfov(&format!(
        r#"<sensor type="perspective"><string name="focal_length" value="35mm"/>{}</sensor>"#,
        film("")
    ));
    assert!((wide - expected(35.0)).abs() < 1e-6, "{wide}");
    let e = scene(
        r#"<sensor type="perspective"><float name="fov" value="40"/><string name="focal_length" value="35mm"/></sensor>"#,
    )
    .unwrap_err();
    assert!(e.contains("either"), "{e}");
    assert!(
        scene(r#"<sensor type="perspective"><string name="focal_length" value="wide"/></sensor>"#)
            .unwrap_err()
            .contains("focal_length")
    );
}
