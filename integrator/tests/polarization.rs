//! Polarized rendering against Fresnel: light of a uniform unpolarized environment
//! reflected by smooth glass carries the degree of linear polarization Fresnel's
//! equations give at its angle (fully s-polarized at Brewster's angle), its intensity S0
//! is the unpolarized render's, and a camera polarizer obeys Malus's law (crossed with
//! the reflection at Brewster's angle, it sees nothing).

mod common;

use common::{mean_stokes, square_z0};
use glam::Vec3;
use prism_integrator::{RenderSettings, render};
use prism_scene::camera::Camera;
use prism_scene::geometry::BvhQuality;
use prism_scene::world::{Light, Material, Scene, SceneParts, SceneSpectrum};

const ETA: f64 = 1.5;

/// Fresnel's reflectances (R_s, R_p) of glass of index `ETA` from outside at `theta`
/// (Born and Wolf §1.5.2), written out here independently of prism's.
fn fresnel(theta: f64) -> (f64, f64) {
    let (cos_i, sin_i) = (theta.cos(), theta.sin());
    let cos_t = (1.0 - (sin_i / ETA).powi(2)).sqrt();
    let rs = (cos_i - ETA * cos_t) / (cos_i + ETA * cos_t);
    let rp = (ETA * cos_i - cos_t) / (ETA * cos_i + cos_t);
    (rs * rs, rp * rp)
}

/// A smooth glass plane (z = 0, facing +z) over a black one, under a uniform white
/// environment, seen at `theta` from the normal through a narrow lens, the image's x axis
/// perpendicular to the plane of incidence (along s).
fn glass_plane(theta: f64) -> Scene {
    let glass = square_z0(50.0);
    let black: Vec<[Vec3; 3]> = glass
        .iter()
        .map(|t| t.map(|v| v - Vec3::Z * 0.01))
        .collect();
    let theta = theta as f32;
    let eye = Vec3::new(theta.sin(), 0.0, theta.cos()) * 3.0;
    Scene::new(SceneParts {
        attributes: Default::default(),
        triangle_material: vec![0, 0, 1, 1],
        triangles: [glass, black].concat(),
        materials: vec![
            Material::Dielectric {
                ior: SceneSpectrum::Constant(ETA),
                roughness: 0.0,
                absorption: None,
            },
            Material::Diffuse {
                reflectance: SceneSpectrum::Constant(0.0),
            },
        ],
        emission: vec![],
        lights: vec![Light::Environment {
            radiance: SceneSpectrum::Constant(1.0),
        }],
        camera: Camera::look_at(eye, Vec3::ZERO, Vec3::Z, 0.002),
        quality: BvhQuality::Medium,
    })
    .unwrap()
}

fn settings() -> RenderSettings {
    RenderSettings::default()
        .width(6)
        .height(6)
        .samples(0..32)
        .polarized(true)
}

#[test]
fn glass_reflects_fresnels_degree_of_polarization() {
    let brewster = ETA.atan();
    for theta in [
        20f64.to_radians(),
        45f64.to_radians(),
        brewster,
        70f64.to_radians(),
        85f64.to_radians(),
    ] {
        let (film, _) = render(&glass_plane(theta), &settings()).unwrap();
        let [s0, s1, s2, s3] = mean_stokes(&film);
        let (rs, rp) = fresnel(theta);
        let expected = (rs - rp) / (rs + rp);
        assert!(s0 > 0.0);
        // s-polarized light (S1 > 0: along the image's rows) in the proportion Fresnel
        // gives; nothing diagonal or circular.
        let dolp = s1 / s0;
        assert!(
            (dolp - expected).abs() < 2e-3,
            "theta {:.1}: S1/S0 {dolp} but Fresnel {expected}",
            theta.to_degrees()
        );
        assert!(
            s2.abs() < 1e-4 * s0 && s3.abs() < 1e-4 * s0,
            "{s2} {s3} of {s0}"
        );
    }
}

#[test]
fn s0_is_the_unpolarized_render() {
    let scene = glass_plane(60f64.to_radians());
    let (polarized, _) = render(&scene, &settings()).unwrap();
    let (plain, _) = render(&scene, &settings().polarized(false)).unwrap();
    assert!(!plain.is_polarized() && plain.stokes(0, 0).is_none());
    for y in 0..6 {
        for x in 0..6 {
            let (a, b) = (polarized.xyz(x, y), plain.xyz(x, y));
            for (p, q) in [(a.x, b.x), (a.y, b.y), (a.z, b.z)] {
                assert!((p - q).abs() <= 1e-5 * q.abs().max(1e-3), "{p} vs {q}");
            }
        }
    }
}

#[test]
fn camera_polarizer_follows_malus_and_crossed_is_dark_at_brewster() {
    let brewster = ETA.atan();
    let scene = glass_plane(brewster);
    let (open, _) = render(&scene, &settings()).unwrap();
    let [s0, s1, s2, _] = mean_stokes(&open);
    for degrees in [0.0f32, 30.0, 45.0, 90.0, 135.0] {
        let (filtered, _) = render(&scene, &settings().camera_polarizer(Some(degrees))).unwrap();
        let seen = mean_stokes(&filtered)[0];
        let angle = 2.0 * f64::from(degrees).to_radians();
        let malus = 0.5 * (s0 + angle.cos() * s1 + angle.sin() * s2);
        assert!(
            (seen - malus).abs() < 1e-4 * s0,
            "{degrees} degrees: {seen} but Malus {malus}"
        );
    }
    // Crossed with the s-polarized reflection: dark (R_p = 0 at Brewster's angle).
    let (crossed, _) = render(&scene, &settings().camera_polarizer(Some(90.0))).unwrap();
    assert!(mean_stokes(&crossed)[0] < 1e-4 * s0);
}

/// A white emitter filling the view of an orthographic camera, seen through `sheets`
/// (material, height) stacked between them.
fn through_sheets(sheets: &[(Material, f32)]) -> Scene {
    common::emitter_behind(SceneSpectrum::Constant(1.0), sheets)
}

fn polarizer(degrees: f32) -> Material {
    let a = degrees.to_radians();
    Material::Polarizer {
        axis: Vec3::new(a.cos(), a.sin(), 0.0),
        transmittance: SceneSpectrum::Constant(1.0),
    }
}

fn quarter_wave(degrees: f32) -> Material {
    let a = degrees.to_radians();
    Material::Retarder {
        axis: Vec3::new(a.cos(), a.sin(), 0.0),
        retardance: SceneSpectrum::Constant(0.25),
    }
}

/// The mean Stokes vector (Y) of the emitter seen through `sheets`, relative to the bare
/// emitter's intensity.
fn seen_through(sheets: &[(Material, f32)], settings: &RenderSettings) -> [f64; 4] {
    let (bare, _) = render(&through_sheets(&[]), settings).unwrap();
    let (film, _) = render(&through_sheets(sheets), settings).unwrap();
    let reference = mean_stokes(&bare)[0];
    mean_stokes(&film).map(|v| v / reference)
}

/// Ideal polarizers obey Malus's law, cos^2 of the angle between them, and a third at 45
/// degrees between crossed ones lets an eighth through.
#[test]
fn polarizing_sheets_obey_malus() {
    let close = |a: f64, b: f64| (a - b).abs() < 1e-4;
    for degrees in [0.0f32, 30.0, 60.0, 90.0] {
        let s = seen_through(
            &[(polarizer(0.0), 0.2), (polarizer(degrees), 0.5)],
            &settings(),
        );
        let malus = 0.5 * f64::from(degrees.to_radians().cos()).powi(2);
        assert!(close(s[0], malus), "{degrees}: {s:?} vs {malus}");
    }
    // Three sheets deep Russian roulette plays (see below): exact in expectation.
    let three = [
        (polarizer(0.0), 0.2),
        (polarizer(45.0), 0.4),
        (polarizer(90.0), 0.6),
    ];
    let s = seen_through(&three, &settings());
    assert!((s[0] - 0.125).abs() < 0.125 * 0.02, "{s:?}");
    // Light leaving the last polarizer is polarized along y: S1 = -S0.
    assert!((s[1] / s[0] + 1.0).abs() < 1e-4, "{s:?}");
    // The camera frame's x is the image's rows (world x here): light through a polarizer
    // along x has S1 = S0; the camera's own filter crossed with it sees nothing.
    let s = seen_through(&[(polarizer(0.0), 0.5)], &settings());
    assert!(close(s[0], 0.5) && close(s[1], 0.5) && s[2].abs() < 1e-4 && s[3].abs() < 1e-4);
    let crossed = seen_through(
        &[(polarizer(0.0), 0.5)],
        &settings().camera_polarizer(Some(90.0)),
    );
    assert!(crossed[0].abs() < 1e-4, "{crossed:?}");
    // Unpolarized renders see a polarizer as a grey filter of half its transmittance.
    let plain = settings().polarized(false);
    let (bare, _) = render(&through_sheets(&[]), &plain).unwrap();
    let (film, _) = render(&through_sheets(&[(polarizer(0.0), 0.5)]), &plain).unwrap();
    assert!(close(film.xyz(2, 2).y / bare.xyz(2, 2).y, 0.5));
}

/// A quarter-wave plate at 45 degrees to a polarizer makes circular light; two make a
/// half-wave plate, which turns light polarized along x into light polarized along y.
#[test]
fn wave_plates_make_circular_and_rotated_light() {
    let settings = settings();
    let circular = seen_through(
        &[(polarizer(0.0), 0.2), (quarter_wave(45.0), 0.5)],
        &settings,
    );
    assert!((circular[0] - 0.5).abs() < 1e-4, "{circular:?}");
    assert!((circular[3].abs() - 0.5).abs() < 1e-4, "{circular:?}");
    assert!(
        circular[1].abs() < 1e-4 && circular[2].abs() < 1e-4,
        "{circular:?}"
    );
    // Three sheets deep, Russian roulette may end a path (its survivors carry more), so
    // the intensity is exact only in expectation; the polarization is exact per path.
    let turned = seen_through(
        &[
            (polarizer(0.0), 0.2),
            (quarter_wave(45.0), 0.4),
            (quarter_wave(45.0), 0.6),
        ],
        &settings,
    );
    assert!((turned[0] - 0.5).abs() < 1e-2, "{turned:?}");
    assert!((turned[1] / turned[0] + 1.0).abs() < 1e-4, "{turned:?}");
    assert!(turned[3].abs() < 1e-4, "{turned:?}");
    // The same plate along the polarizer's axis leaves the light as it is.
    let along = seen_through(
        &[(polarizer(0.0), 0.2), (quarter_wave(0.0), 0.5)],
        &settings,
    );
    assert!(
        (along[1] - 0.5).abs() < 1e-4 && along[3].abs() < 1e-4,
        "{along:?}"
    );
}

/// With spectral bands a polarized film keeps every Stokes component per band (S1's
/// share of S0 is Fresnel's in every band of the non-dispersive glass), and it survives
/// an EXR (the polarized spectral layout's channels) and an accumulation file, and splits
/// into sample ranges that merge into the whole.
#[test]
fn polarized_bands_files_and_merges() {
    use prism_integrator::{
        ExrMetadata, SpectralBands, decode_accumulation, decode_exr, encode_accumulation,
        encode_exr,
    };
    let theta = 65f64.to_radians();
    let scene = glass_plane(theta);
    let bands = SpectralBands::new(400.0, 700.0, 6).unwrap();
    let settings = settings().bands(Some(bands));
    let (film, _) = render(&scene, &settings).unwrap();
    let (rs, rp) = fresnel(theta);
    let mut checked = 0;
    for (x, y) in [(1, 1), (3, 2), (5, 5)] {
        let s0 = film.stokes_spectrum(x, y, 0).unwrap();
        let s1 = film.stokes_spectrum(x, y, 1).unwrap();
        assert_eq!(Some(s0.clone()), film.spectrum(x, y));
        for (a, b) in s0.iter().zip(&s1) {
            if *a > 0.0 {
                // Within the pixel's spread of angles (a thousandth of a radian).
                assert!((b / a - (rs - rp) / (rs + rp)).abs() < 3e-3, "{b} / {a}");
                checked += 1;
            }
        }
        assert!(
            film.stokes_spectrum(x, y, 3)
                .unwrap()
                .iter()
                .all(|v| v.abs() < 1e-6)
        );
        assert!(film.stokes_spectrum(x, y, 4).is_none());
    }
    assert!(checked > 6);
    // EXR: S0..S3 in RGB and per band.
    let image = decode_exr(
        &encode_exr(
            &film,
            prism_spectrum::color::RgbSpaceId::Srgb.space(),
            &ExrMetadata::default(),
        )
        .unwrap(),
    )
    .unwrap();
    let names: Vec<&str> = image.channels.iter().map(|(n, _)| n.as_str()).collect();
    for name in [
        "R",
        "S0.R",
        "S1.G",
        "S3.B",
        "S0.425,000000nm",
        "S3.675,000000nm",
    ] {
        assert!(names.contains(&name), "{name} missing from {names:?}");
    }
    // Accumulation files keep the Stokes sums exactly; halves merge into the whole.
    let decoded = decode_accumulation(&encode_accumulation(&film, 0..32, "x").unwrap()).unwrap();
    assert_eq!(decoded.film, film);
    let (mut first, _) = render(&scene, &settings.clone().samples(0..16)).unwrap();
    let (second, _) = render(&scene, &settings.clone().samples(16..32)).unwrap();
    first.merge(&second).unwrap();
    for (x, y) in [(0, 0), (4, 3)] {
        let (a, b) = (first.stokes(x, y).unwrap(), film.stokes(x, y).unwrap());
        for (p, q) in a.iter().flatten().zip(b.iter().flatten()) {
            assert!((p - q).abs() <= 1e-12 * q.abs().max(1.0), "{p} vs {q}");
        }
    }
    // A polarized film does not merge with an unpolarized one.
    let (plain, _) = render(&scene, &settings.clone().polarized(false)).unwrap();
    assert!(first.merge(&plain).is_err());
}

/// A directional light polarized along s or p (the light's x axis across or in the plane
/// of incidence), reflected into the camera by nearly smooth glass: the reflections'
/// intensities are in Fresnel's proportion R_p / R_s, p-polarized light all but vanishes
/// at Brewster's angle, and unpolarized light (degree 0) is the unpolarized render.
#[test]
fn polarized_light_reflects_in_fresnels_proportion() {
    use prism_scene::polarization::LinearPolarization;
    let scene = |theta: f64, polarization: Option<f32>| {
        let theta = theta as f32;
        let eye = Vec3::new(theta.sin(), 0.0, theta.cos()) * 3.0;
        let mut scene = Scene::new(SceneParts {
            attributes: Default::default(),
            triangle_material: vec![0, 0],
            triangles: square_z0(50.0),
            materials: vec![Material::Dielectric {
                ior: SceneSpectrum::Constant(ETA),
                roughness: 0.1,
                absorption: None,
            }],
            emission: vec![],
            lights: vec![Light::Directional {
                direction: Vec3::new(theta.sin(), 0.0, -theta.cos()),
                irradiance: SceneSpectrum::Constant(1.0),
            }],
            camera: Camera::look_at(eye, Vec3::ZERO, Vec3::Z, 0.002),
            quality: BvhQuality::Medium,
        })
        .unwrap();
        if let Some(angle) = polarization {
            let p = LinearPolarization {
                degree: if angle.is_nan() { 0.0 } else { 1.0 },
                angle: if angle.is_nan() {
                    0.0
                } else {
                    angle.to_radians()
                },
                // The light's x axis across the plane of incidence: s at angle 0.
                axis: Vec3::Y,
            };
            scene.polarize_light(0, p).unwrap();
        }
        scene
    };
    let seen = |theta: f64, polarization: Option<f32>| {
        let (film, _) = render(&scene(theta, polarization), &settings()).unwrap();
        mean_stokes(&film)
    };
    let theta = 45f64.to_radians();
    let (s_light, p_light) = (seen(theta, Some(0.0)), seen(theta, Some(90.0)));
    let (rs, rp) = fresnel(theta);
    let ratio = p_light[0] / s_light[0];
    assert!(
        (ratio / (rp / rs) - 1.0).abs() < 0.05,
        "{ratio} vs {}",
        rp / rs
    );
    // Both stay polarized as they came: s along the image's rows (S1 > 0), p across.
    assert!(s_light[1] / s_light[0] > 0.99 && p_light[1] / p_light[0] < -0.99);
    let brewster = ETA.atan();
    let (s_light, p_light) = (seen(brewster, Some(0.0)), seen(brewster, Some(90.0)));
    assert!(p_light[0] < 2e-3 * s_light[0], "{p_light:?} {s_light:?}");
    // Degree 0 is unpolarized light.
    let (none, plain) = (seen(theta, Some(f32::NAN)), seen(theta, None));
    assert!((none[0] - plain[0]).abs() < 1e-6 * plain[0] && none[1] == plain[1]);
    // Light at 45 degrees: halfway in intensity, and S2 carries its angle through.
    let diagonal = seen(theta, Some(45.0));
    let (s45, p45) = (seen(theta, Some(0.0)), seen(theta, Some(90.0)));
    assert!(
        (diagonal[0] / (0.5 * (s45[0] + p45[0])) - 1.0).abs() < 1e-3,
        "{diagonal:?}"
    );
    assert!(diagonal[2].abs() > 0.1 * diagonal[0], "{diagonal:?}");
}

/// Light paths carry polarization: a caustic of light reflected by a glass pane (a delta
/// bounce, polarized across its plane of incidence) onto a rough glass floor (which
/// polarizes again) has the same Stokes vector whether light paths find it or camera
/// paths alone do (two unbiased estimators of one image).
#[test]
fn light_paths_and_camera_paths_agree_on_polarized_caustics() {
    let quad = |a: Vec3, b: Vec3, c: Vec3, d: Vec3| vec![[a, b, c], [a, c, d]];
    let v = Vec3::new;
    let floor = quad(
        v(-6.0, -6.0, 0.0),
        v(6.0, -6.0, 0.0),
        v(6.0, 6.0, 0.0),
        v(-6.0, 6.0, 0.0),
    );
    // A glass ceiling, facing down; a lamp on the floor outside the view, facing up: its
    // light reaches the floor only by the ceiling's reflection, polarized across the
    // plane of incidence (Brewster's angle is 56 degrees; it arrives at 11-45).
    let pane = quad(
        v(-8.0, -8.0, 3.0),
        v(-8.0, 8.0, 3.0),
        v(8.0, 8.0, 3.0),
        v(8.0, -8.0, 3.0),
    );
    let lamp = quad(
        v(-4.5, -1.5, 0.5),
        v(-2.5, -1.5, 0.5),
        v(-2.5, 1.5, 0.5),
        v(-4.5, 1.5, 0.5),
    );
    let scene = Scene::new(SceneParts {
        attributes: Default::default(),
        triangle_material: vec![0, 0, 1, 1, 2, 2],
        triangles: [floor, pane, lamp].concat(),
        materials: vec![
            Material::Conductor {
                eta: SceneSpectrum::Constant(0.2),
                k: SceneSpectrum::Constant(3.0),
                roughness: 0.4,
            },
            Material::Dielectric {
                ior: SceneSpectrum::Constant(ETA),
                roughness: 0.0,
                absorption: None,
            },
            Material::Diffuse {
                reflectance: SceneSpectrum::Constant(0.0),
            },
        ],
        emission: vec![SceneSpectrum::Constant(1.0)],
        lights: (4..6)
            .map(|t| Light::Triangle {
                triangle: t,
                emission: 0,
                two_sided: false,
            })
            .collect(),
        camera: Camera::look_at(v(0.0, 0.0, 2.0), v(0.0, 0.0, 0.0), Vec3::Y, 0.9),
        quality: BvhQuality::Medium,
    })
    .unwrap();
    // Means over seeds: each estimator's noise in S0 is about half a percent.
    let mean = |light_paths: bool| {
        let mut sum = [0.0; 4];
        for seed in 0..6 {
            let settings = RenderSettings::default()
                .width(16)
                .height(12)
                .samples(0..1024)
                .seed(seed)
                .polarized(true)
                .light_paths(light_paths);
            let stokes = mean_stokes(&render(&scene, &settings).unwrap().0);
            for (acc, v) in sum.iter_mut().zip(stokes) {
                *acc += v / 6.0;
            }
        }
        sum
    };
    // The intensity of a caustic is noisy either way (light paths spread over the
    // ceiling's whole reflection, camera paths find the lamp through a glossy lobe);
    // its polarization per unit intensity, which each path carries, much less so.
    let (a, b) = (mean(true), mean(false));
    assert!(b[1] < -0.2 * b[0], "the caustic is polarized: {b:?}");
    assert!((a[0] / b[0] - 1.0).abs() < 0.1, "S0: {a:?} vs {b:?}");
    for k in 1..3 {
        assert!(
            (a[k] / a[0] - b[k] / b[0]).abs() < 0.01,
            "S{k}: {a:?} vs {b:?}"
        );
    }
}
