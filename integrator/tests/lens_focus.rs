//! A render through a real lens shows its chromatic aberration: a small light far in
//! front of an uncorrected BK7 singlet, the film swept through focus, is sharpest in the
//! F line (486 nm) with the film nearest the lens, in the d line (588 nm) further back,
//! and in the C line (656 nm) furthest back, by about the singlet's paraxial focal shifts;
//! through a cemented achromat the three foci nearly coincide.

mod common;

use glam::{Mat4, Vec3};
use prism_integrator::{LambdaSampler, RenderSettings, render};
use prism_scene::camera::system::{D_LINE_NM, LensSystem, parse_prescription};
use prism_scene::camera::{Camera, MountedLens, Projection};
use prism_scene::geometry::BvhQuality;
use prism_scene::world::{Light, Material, Scene, SceneParts, SceneSpectrum};
use prism_spectrum::optics::{FRAUNHOFER_C_NM, FRAUNHOFER_F_NM};

const SIZE: u32 = 40;
/// The film's width, metres: 25 micrometres a pixel.
const SENSOR: f32 = 0.001;
/// The light's distance from the film and its side, metres.
const DISTANCE: f32 = 1.0;
const SIDE: f32 = 3e-4;
const F_NUMBER: f32 = 8.0;

/// The repository's BK7 singlet (f = 97 mm) and BK7-F2 achromat (f = 99.5 mm), each
/// behind a stop.
const SINGLET: &str = "0 5 0 20\n100 4 1.5168 30 bk7\n-100 96.09 1 30\n";
const ACHROMAT: &str =
    "0 5 0 20\n44.781 5 1.5168 30 bk7\n-44.781 2 1.6200 30 f2\n-810.62 94.57 1 30\n";

fn scene(system: &LensSystem, focus: f32) -> Scene {
    let h = 0.5 * SIDE;
    let z = -DISTANCE;
    let (a, b, c, d) = (
        Vec3::new(-h, -h, z),
        Vec3::new(h, -h, z),
        Vec3::new(h, h, z),
        Vec3::new(-h, h, z),
    );
    Scene::new(SceneParts {
        attributes: Default::default(),
        triangle_material: vec![0, 0],
        triangles: vec![[a, b, c], [a, c, d]],
        materials: vec![Material::Diffuse {
            reflectance: SceneSpectrum::Constant(0.0),
        }],
        emission: vec![SceneSpectrum::Constant(1.0)],
        lights: (0..2)
            .map(|t| Light::Triangle {
                triangle: t,
                emission: 0,
                two_sided: false,
            })
            .collect(),
        camera: Camera {
            name: "singlet".into(),
            to_world: Mat4::IDENTITY,
            projection: Projection::Perspective { yfov: 0.5 },
            aspect_ratio: None,
            lens: None,
            system: Some(MountedLens {
                f_number: Some(F_NUMBER),
                focus_distance: Some(focus),
                sensor_width: SENSOR,
                ..MountedLens::new("singlet", system.clone())
            }),
        },
        quality: BvhQuality::Medium,
    })
    .unwrap()
}

/// The spot's second moment with the lens focused at `focus` (metres), seen in the 10 nm
/// around `lambda`.
fn spot(system: &LensSystem, focus: f32, lambda: f64) -> f64 {
    let settings = RenderSettings::default()
        .width(SIZE)
        .height(SIZE)
        .samples(0..256)
        .wavelengths(4)
        .lambda_sampler(LambdaSampler::Uniform)
        .range(((lambda - 5.0) as f32, (lambda + 5.0) as f32));
    common::second_moment(&render(&scene(system, focus), &settings).unwrap().0)
}

/// The focus distance (metres) that puts the film at `film_z` (mm, d line), by bisection
/// on the thick-lens approximation.
fn focus_for(system: &LensSystem, film_z: f64) -> f32 {
    let (mut near, mut far) = (150.0f64, 1e7f64);
    for _ in 0..200 {
        let mid = (near * far).sqrt();
        match system.focus_shift(mid, D_LINE_NM) {
            Some(z) if z > film_z => near = mid,
            _ => far = mid,
        }
    }
    (far / 1000.0) as f32
}

/// The film position (mm) where the spot seen around `lambda` is smallest, among
/// `positions`: the vertex of a parabola through the smallest and its neighbours.
fn sharpest(system: &LensSystem, positions: &[f64], lambda: f64) -> f64 {
    let moments: Vec<f64> = positions
        .iter()
        .map(|&z| spot(system, focus_for(system, z), lambda))
        .collect();
    let k = (1..positions.len() - 1)
        .min_by(|&a, &b| moments[a].total_cmp(&moments[b]))
        .unwrap();
    let (m0, m1, m2) = (moments[k - 1], moments[k], moments[k + 1]);
    let step = positions[1] - positions[0];
    let curvature = m0 - 2.0 * m1 + m2;
    let offset = if curvature > 0.0 {
        0.5 * (m0 - m2) / curvature
    } else {
        0.0
    };
    eprintln!(
        "{lambda} nm: moments {moments:.1?}, sharpest at {:.3} mm",
        positions[k] + offset * step
    );
    positions[k] + offset.clamp(-1.0, 1.0) * step
}

/// The image of the light (mm behind the prescription's film) at `lambda`.
fn image_z(system: &LensSystem, lambda: f64) -> f64 {
    system
        .focus_shift(f64::from(DISTANCE) * 1000.0, lambda)
        .unwrap()
}

/// The rendered foci (film positions, mm) in the F, d and C lines through `prescription`
/// closed to F_NUMBER, and the paraxial ones.
fn foci(prescription: &str) -> ([f64; 3], [f64; 3]) {
    let system = parse_prescription(prescription)
        .unwrap()
        .stopped_to(f64::from(F_NUMBER))
        .unwrap();
    let lines = [FRAUNHOFER_F_NM, D_LINE_NM, FRAUNHOFER_C_NM];
    let paraxial = lines.map(|l| image_z(&system, l));
    // Film positions from well before the F focus (spherical aberration brings every
    // best focus nearer the lens) to past the C focus.
    let (first, last) = (
        paraxial[0].min(paraxial[2]) - 1.0,
        paraxial[0].max(paraxial[2]) + 0.4,
    );
    let positions: Vec<f64> = (0..11)
        .map(|i| first + f64::from(i) * (last - first) / 10.0)
        .collect();
    let found = lines.map(|l| sharpest(&system, &positions, l));
    eprintln!("paraxial foci {paraxial:.3?} mm; rendered {found:.3?}");
    (found, paraxial)
}

#[test]
fn a_singlet_focuses_blue_nearer_than_green_and_red_further() {
    let (found, paraxial) = foci(SINGLET);
    assert!(
        found[0] < found[1] && found[1] < found[2],
        "rendered foci F {:.3}, d {:.3}, C {:.3} mm are not in order",
        found[0],
        found[1],
        found[2]
    );
    // The shifts between the lines are the paraxial ones within 15% (the singlet's
    // spherical aberration moves every line's best focus alike, towards the lens).
    for (a, b) in [(0, 1), (1, 2)] {
        let (got, want) = (found[b] - found[a], paraxial[b] - paraxial[a]);
        assert!(
            (got / want - 1.0).abs() < 0.15,
            "rendered shift {got:.3} mm between lines {a} and {b}, paraxial {want:.3} mm"
        );
    }
    // And the colours' best foci lie near the paraxial ones.
    for (got, want) in found.iter().zip(paraxial) {
        assert!(
            (got - want).abs() < 0.8,
            "rendered {got:.3} mm, paraxial {want:.3} mm"
        );
    }
    // Through the achromat the F and C foci nearly meet.
    let (achromat, _) = foci(ACHROMAT);
    let (spread, singlet) = (
        (achromat[2] - achromat[0]).abs(),
        (found[2] - found[0]).abs(),
    );
    assert!(
        spread < 0.25 * singlet,
        "the achromat's F-C focal shift {spread:.3} mm, the singlet's {singlet:.3} mm"
    );
}
