//! The rainbow measured against geometry: `scenes/rainbow.gltf` (Descartes' experiment, a
//! water drop lit through a hole in a screen) rendered by a camera on the beam's axis.
//! Light that refracts into the drop, reflects once inside and refracts out reaches the
//! screen no further from the axis than a caustic radius that depends on the wavelength
//! through water's index: the primary bow's outer edge. The edge of each spectral band's
//! ring in the image must be where tracing the drop's circle in 2D puts it, with the
//! scene's own light and screen positions and the Sellmeier index (independently of the
//! renderer's refraction and of its light paths, which are what draws the ring).

mod common;

use common::refract_2d;

use glam::{DVec2, Mat4, Vec3};
use prism_integrator::{LambdaSampler, RenderSettings, SpectralBands, render};
use prism_scene::camera::{Camera, Projection};
use prism_spectrum::Spectrum;
use prism_spectrum::optics::named_glass;

// The scene's layout (scenes/tools/make_rainbow.py).
const DROP: DVec2 = DVec2::new(0.0, 0.0); // (radius from the axis, z)
const DROP_RADIUS: f64 = 0.05;
const LIGHT_Z: f64 = 8.0;
const SCREEN_Z: f64 = 2.0;
const CAMERA_Z: f64 = -1.0;
const AXIS_Y: f32 = 1.0;

const SIZE: u32 = 160;
/// tan(yfov / 2): the image spans 2.1 units either side of the axis on the screen.
const HALF_VIEW: f64 = 2.1 / (SCREEN_Z - CAMERA_Z);

/// The far intersection of the ray (o, d) from inside the circle (centre c, radius r).
fn exit_circle(o: DVec2, d: DVec2, c: DVec2, r: f64) -> DVec2 {
    let f = o - c;
    let b = f.dot(d);
    let t = -b + (b * b - (f.length_squared() - r * r)).sqrt();
    o + t * d
}

/// The primary bow's edge on the screen at index `n`: the largest distance from the axis
/// at which a ray from the light, refracted into the drop, reflected once and refracted
/// out, meets the screen. Traced in the (radius, z) plane over the drop's whole face.
fn bow_edge(n: f64) -> f64 {
    let light = DVec2::new(0.0, LIGHT_Z);
    let mut widest: f64 = 0.0;
    let steps = 200_000;
    for k in 1..steps {
        // Aim at a point across the drop's face: impact parameter b in (0, R).
        let b = DROP_RADIUS * k as f64 / steps as f64;
        let target = DVec2::new(b, DROP.y);
        let d = (target - light).normalize();
        // Entry: the near intersection with the circle.
        let f = light - DROP;
        let half_b = f.dot(d);
        let disc = half_b * half_b - (f.length_squared() - DROP_RADIUS * DROP_RADIUS);
        if disc < 0.0 {
            continue;
        }
        let p1 = light + (-half_b - disc.sqrt()) * d;
        let n1 = (p1 - DROP) / DROP_RADIUS;
        let Some(inside) = refract_2d(d, n1, 1.0 / n) else {
            continue;
        };
        let p2 = exit_circle(p1, inside, DROP, DROP_RADIUS);
        let n2 = (p2 - DROP) / DROP_RADIUS;
        let reflected = inside - 2.0 * inside.dot(n2) * n2;
        let p3 = exit_circle(p2, reflected, DROP, DROP_RADIUS);
        let n3 = (p3 - DROP) / DROP_RADIUS;
        let Some(out) = refract_2d(reflected, -n3, n) else {
            continue;
        };
        if out.y <= 0.0 {
            continue;
        }
        let at_screen = p3 + (SCREEN_Z - p3.y) / out.y * out;
        widest = widest.max(at_screen.x.abs());
    }
    widest
}

#[test]
fn the_primary_bow_is_where_descartes_puts_it() {
    let scene = common::repository_scene("rainbow.gltf", |loaded| {
        // On the axis behind the drop, looking at the screen (-z turned onto +z).
        loaded.cameras = vec![Camera {
            name: "axis".into(),
            to_world: Mat4::from_translation(Vec3::new(0.0, AXIS_Y, CAMERA_Z as f32))
                * Mat4::from_rotation_y(std::f32::consts::PI),
            projection: Projection::Perspective {
                yfov: (2.0 * HALF_VIEW.atan()) as f32,
            },
            aspect_ratio: None,
            lens: None,
            system: None,
        }];
    });
    let bands = SpectralBands::new(430.0, 670.0, 12).unwrap();
    let settings = RenderSettings::default()
        .width(SIZE)
        .height(SIZE)
        .samples(0..64)
        .wavelengths(4)
        .lambda_sampler(LambdaSampler::Uniform)
        .bands(Some(bands));
    let (film, _) = render(&scene, &settings).unwrap();
    // Each pixel's distance from the axis on the screen (the camera's axis is the beam's,
    // square to the screen).
    let screen_radius = |x: u32, y: u32| -> f64 {
        let ndc = |i: u32| 2.0 * (f64::from(i) + 0.5) / f64::from(SIZE) - 1.0;
        (SCREEN_Z - CAMERA_Z) * HALF_VIEW * ndc(x).hypot(ndc(y))
    };
    let water = named_glass("water").unwrap().ior;
    let pixel = 2.0 * (SCREEN_Z - CAMERA_Z) * HALF_VIEW / f64::from(SIZE);
    const BIN: f64 = 0.01;
    let edge = |band: usize| -> f64 {
        let bins = (2.2 / BIN) as usize;
        let mut sum = vec![0.0f64; bins];
        let mut count = vec![0u32; bins];
        for y in 0..SIZE {
            for x in 0..SIZE {
                let bin = (screen_radius(x, y) / BIN) as usize;
                if bin < bins {
                    sum[bin] += film.spectrum(x, y).unwrap()[band];
                    count[bin] += 1;
                }
            }
        }
        let profile: Vec<f64> = sum
            .iter()
            .zip(&count)
            .map(|(s, &c)| if c > 0 { s / f64::from(c) } else { 0.0 })
            .collect();
        // The bow's region: inside the secondary bow (2.5 units), outside the drop's
        // shadow. The edge is the outer end of the outermost bin above a quarter of the
        // peak: beyond it the band falls to ~1% within two bins (measured).
        let region = (1.2 / BIN) as usize..bins;
        let peak = region.clone().map(|i| profile[i]).fold(0.0, f64::max);
        assert!(peak > 0.0, "band {band} never reached the screen");
        let last = region.filter(|&i| profile[i] >= 0.25 * peak).max().unwrap();
        (last + 1) as f64 * BIN
    };
    let (blue, green, red) = (0, 6, 11);
    let mut measured = Vec::new();
    for band in [blue, green, red] {
        let predicted = bow_edge(water.evaluate(bands.center(band)));
        let found = edge(band);
        // A pixel's box filter spreads light up to half a diagonal (0.71 px) past the
        // caustic, and bins are read at their outer end: the edge is found up to about
        // one pixel out, never in. (A 1% error in the index would move it 0.12 units,
        // 4.6 px.)
        assert!(
            found >= predicted - 0.25 * pixel && found <= predicted + pixel,
            "band {band} ({} nm): bow edge at {found:.4}, Descartes puts it at {predicted:.4} (pixel {pixel:.4})",
            bands.center(band)
        );
        measured.push((found, predicted));
    }
    // Dispersion across the bow: red outside violet by what the index predicts (the
    // filter's offset cancels), within a bin and a quarter pixel.
    let spread = measured[2].0 - measured[0].0;
    let predicted_spread = measured[2].1 - measured[0].1;
    assert!(
        (spread - predicted_spread).abs() <= BIN + 0.25 * pixel,
        "660 nm lies {spread:.4} outside 440 nm; Descartes says {predicted_spread:.4}"
    );
    assert!(measured[0].0 <= measured[1].0 && measured[1].0 <= measured[2].0);
}
