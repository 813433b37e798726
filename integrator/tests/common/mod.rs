//! Shared by the integrator's tests.

#![allow(dead_code)]

use glam::Vec3;
use prism_integrator::Film;
use prism_scene::geometry::BvhQuality;
use prism_scene::world::{Light, Material, Scene, SceneParts, SceneSpectrum};

/// The repository's Cornell box as a render-ready scene.
pub fn cornell() -> Scene {
    cornell_with(|_| {})
}

/// The Cornell box, its loaded description edited by `edit` first.
pub fn cornell_with(edit: impl FnOnce(&mut prism_scene::load::LoadedGeometry)) -> Scene {
    repository_scene("cornell-box.gltf", edit)
}

/// The repository's scene `scenes/<file>`, its loaded description edited by `edit` first.
pub fn repository_scene(
    file: &str,
    edit: impl FnOnce(&mut prism_scene::load::LoadedGeometry),
) -> Scene {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let bytes = std::fs::read(dir.join(file)).unwrap();
    let loaded =
        prism_scene::load::load_geometry(&bytes, &|uri| std::fs::read(dir.join(uri)), None)
            .unwrap();
    let mut loaded = loaded;
    edit(&mut loaded);
    Scene::from_loaded(loaded, &Default::default()).unwrap()
}

/// Refraction of unit `d` at a surface with unit normal `n` facing against `d`, relative
/// index `eta` = n_incident / n_transmitted (None: total internal reflection): Snell's law
/// in 2D, for tests that predict where light goes independently of the renderer.
pub fn refract_2d(d: glam::DVec2, n: glam::DVec2, eta: f64) -> Option<glam::DVec2> {
    let cos_i = -n.dot(d);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    (k >= 0.0).then(|| eta * d + (eta * cos_i - k.sqrt()) * n)
}

/// A square of half-width `half` in the plane z = 0, facing +z, as two triangles.
pub fn square_z0(half: f32) -> Vec<[glam::Vec3; 3]> {
    use glam::Vec3;
    vec![
        [
            Vec3::new(-half, -half, 0.0),
            Vec3::new(half, -half, 0.0),
            Vec3::new(half, half, 0.0),
        ],
        [
            Vec3::new(-half, -half, 0.0),
            Vec3::new(half, half, 0.0),
            Vec3::new(-half, half, 0.0),
        ],
    ]
}

/// An orthographic camera at `eye` looking down -z, seeing a square of half-size `half`.
pub fn ortho_camera(eye: glam::Vec3, half: f32) -> prism_scene::camera::Camera {
    prism_scene::camera::Camera {
        name: "test".into(),
        to_world: glam::Mat4::from_translation(eye),
        aspect_ratio: None,
        lens: None,
        system: None,
        projection: prism_scene::camera::Projection::Orthographic {
            xmag: half,
            ymag: half,
        },
    }
}

/// A black square emitting `emission` from its front (+z), larger than the view of an
/// orthographic camera one unit in front of it: every pixel sees the emitter.
pub fn emitter_filling_the_view(emission: prism_scene::world::SceneSpectrum) -> Scene {
    emitter_behind(emission, &[])
}

/// [`emitter_filling_the_view`] seen through `layers` (material, height above the
/// emitter): squares as large as it, between it and the camera.
pub fn emitter_behind(
    emission: prism_scene::world::SceneSpectrum,
    layers: &[(prism_scene::world::Material, f32)],
) -> Scene {
    use prism_scene::world::{Light, Material, SceneParts, SceneSpectrum};
    let mut triangles = square_z0(2.0);
    let mut triangle_material = vec![0, 0];
    let mut materials = vec![Material::Diffuse {
        reflectance: SceneSpectrum::Constant(0.0),
    }];
    for (k, (material, z)) in layers.iter().enumerate() {
        let lift = glam::Vec3::Z * *z;
        triangles.extend(square_z0(2.0).into_iter().map(|t| t.map(|v| v + lift)));
        triangle_material.extend([k as u32 + 1; 2]);
        materials.push(material.clone());
    }
    Scene::new(SceneParts {
        attributes: Default::default(),
        triangles,
        triangle_material,
        materials,
        emission: vec![emission],
        lights: (0..2)
            .map(|t| Light::Triangle {
                triangle: t,
                emission: 0,
                two_sided: false,
            })
            .collect(),
        camera: ortho_camera(glam::Vec3::new(0.0, 0.0, 1.0), 0.5),
        quality: prism_scene::geometry::BvhQuality::Medium,
    })
    .unwrap()
}

/// A unit icosphere subdivided `levels` times, outward winding.
pub fn icosphere(levels: u32) -> Vec<[Vec3; 3]> {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let v: Vec<Vec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let faces = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let mut tris: Vec<[Vec3; 3]> = faces.iter().map(|f| f.map(|i| v[i])).collect();
    for _ in 0..levels {
        tris = tris
            .iter()
            .flat_map(|&[a, b, c]| {
                let (ab, bc, ca) = (
                    (a + b).normalize(),
                    (b + c).normalize(),
                    (c + a).normalize(),
                );
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    tris
}

/// The mean over all pixels of a film, and its standard error from the pixel-to-pixel
/// spread (valid where every pixel has the same expectation).
pub fn mean_and_error(film: &Film, channel: usize) -> (f64, f64) {
    let n = f64::from(film.width() * film.height());
    let values: Vec<f64> = (0..film.height())
        .flat_map(|y| (0..film.width()).map(move |x| (x, y)))
        .map(|(x, y)| film.xyz(x, y).to_array()[channel])
        .collect();
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// A furnace: `triangles` (material `triangle_material[i]` of `materials`) in a uniform
/// environment of radiance 1, seen from +z by an orthographic camera of half-size `half`.
pub fn furnace(
    triangles: Vec<[Vec3; 3]>,
    triangle_material: Vec<u32>,
    materials: Vec<Material>,
    half: f32,
) -> Scene {
    Scene::new(SceneParts {
        attributes: Default::default(),
        triangle_material,
        triangles,
        materials,
        emission: vec![],
        lights: vec![Light::Environment {
            radiance: SceneSpectrum::Constant(1.0),
        }],
        camera: ortho_camera(Vec3::new(0.0, 0.0, 3.0), half),
        quality: BvhQuality::Medium,
    })
    .unwrap()
}

pub fn furnace_scene() -> Scene {
    let triangles = icosphere(2);
    let white = Material::Diffuse {
        reflectance: SceneSpectrum::Constant(1.0),
    };
    let triangle_material = vec![0; triangles.len()];
    furnace(triangles, triangle_material, vec![white], 0.6)
}

/// Asserts that each channel's image mean of `film` is `expected` within five standard
/// errors and 0.1% (a scene whose every pixel has the same expectation); `what` names the
/// configuration in the message.
pub fn assert_image_mean(film: &Film, expected: [f64; 3], what: &str) {
    for (k, expected) in expected.into_iter().enumerate() {
        let (mean, error) = mean_and_error(film, k);
        let tolerance = 5.0 * error + 1e-3 * expected;
        assert!(
            (mean - expected).abs() < tolerance,
            "{what} channel {k}: {mean} vs {expected} (+-{tolerance})"
        );
    }
}

/// The mean of each 4 x 4 block of `film`'s pixels, channel by channel.
pub fn blocks(film: &Film) -> Vec<[f64; 3]> {
    let (w, h) = (film.width(), film.height());
    let mut out = vec![];
    for by in (0..h).step_by(4) {
        for bx in (0..w).step_by(4) {
            let mut sum = [0.0; 3];
            for y in by..(by + 4).min(h) {
                for x in bx..(bx + 4).min(w) {
                    let v = film.xyz(x, y).to_array();
                    for k in 0..3 {
                        sum[k] += v[k] / 16.0;
                    }
                }
            }
            out.push(sum);
        }
    }
    out
}

/// The relative mean squared error of `film` against `reference`, per pixel and channel.
pub fn relative_mse(film: &Film, reference: &Film) -> f64 {
    let mut sum = 0.0;
    let mut n = 0.0;
    for y in 0..film.height() {
        for x in 0..film.width() {
            let (a, b) = (film.xyz(x, y).to_array(), reference.xyz(x, y).to_array());
            for k in 0..3 {
                sum += (a[k] - b[k]).powi(2) / (b[k] * b[k] + 0.01);
                n += 1.0;
            }
        }
    }
    sum / n
}

/// Per 4 x 4 block of the renders of `scene` with `settings_of(seed)` for eight seeds,
/// per channel: the mean over the seeds and its squared standard error.
pub fn block_statistics(
    scene: &Scene,
    settings_of: impl Fn(u64) -> prism_integrator::RenderSettings,
) -> Vec<[(f64, f64); 3]> {
    let runs: Vec<Vec<[f64; 3]>> = (0..8)
        .map(|seed| {
            blocks(
                &prism_integrator::render(scene, &settings_of(seed))
                    .unwrap()
                    .0,
            )
        })
        .collect();
    let n = runs.len() as f64;
    (0..runs[0].len())
        .map(|b| {
            [0, 1, 2].map(|k| {
                let mean = runs.iter().map(|r| r[b][k]).sum::<f64>() / n;
                let var = runs.iter().map(|r| (r[b][k] - mean).powi(2)).sum::<f64>() / (n - 1.0);
                (mean, var / n)
            })
        })
        .collect()
}

/// Asserts that two sets of [`block_statistics`] agree, every block and channel within
/// five standard errors; `what` names the pair in the message.
pub fn assert_blocks_agree(a: &[[(f64, f64); 3]], b: &[[(f64, f64); 3]], what: &str) {
    for (i, (u, s)) in a.iter().zip(b).enumerate() {
        for k in 0..3 {
            let sigma = (u[k].1 + s[k].1).sqrt();
            assert!(
                (u[k].0 - s[k].0).abs() < 5.0 * sigma + 1e-6,
                "{what}: block {i} channel {k}: {} against {} (sigma {sigma})",
                u[k].0,
                s[k].0
            );
        }
    }
}

/// Asserts that `scene` rendered with `settings` (one thread, samples 0..6) gives the same
/// sums on two threads, and the same to rounding when rendered as samples 0..2 and 2..6
/// and merged.
pub fn assert_deterministic_and_merges(scene: &Scene, settings: &prism_integrator::RenderSettings) {
    use prism_integrator::render;
    let one = settings.clone().threads(1).samples(0..6);
    let (a, _) = render(scene, &one).unwrap();
    let (b, _) = render(scene, &one.clone().threads(2)).unwrap();
    assert_eq!(a.sums(), b.sums());
    let (mut first, _) = render(scene, &one.clone().samples(0..2)).unwrap();
    let (second, _) = render(scene, &one.clone().samples(2..6)).unwrap();
    first.merge(&second).unwrap();
    for (x, y) in first.sums().iter().zip(a.sums()) {
        for k in 0..3 {
            assert!((x[k] - y[k]).abs() <= 1e-12 * y[k].abs().max(1.0));
        }
    }
}

/// The image's mean S0..S3 in the luminance (Y) channel of a polarized film.
pub fn mean_stokes(film: &Film) -> [f64; 4] {
    let mut sum = [0.0; 4];
    for y in 0..film.height() {
        for x in 0..film.width() {
            let s = film.stokes(x, y).expect("a polarized film");
            for (acc, c) in sum.iter_mut().zip(s) {
                *acc += c[1];
            }
        }
    }
    sum.map(|v| v / f64::from(film.width() * film.height()))
}

/// The luminance-weighted mean of r^2 about the image's centroid, in pixels^2: the size of
/// a blur spot.
pub fn second_moment(film: &Film) -> f64 {
    let (w, h) = (film.width(), film.height());
    let (mut sum, mut sx, mut sy) = (0.0, 0.0, 0.0);
    for y in 0..h {
        for x in 0..w {
            let v = film.xyz(x, y).y;
            sum += v;
            sx += v * (f64::from(x) + 0.5);
            sy += v * (f64::from(y) + 0.5);
        }
    }
    assert!(sum > 0.0, "the light is not seen");
    let (cx, cy) = (sx / sum, sy / sum);
    let mut m = 0.0;
    for y in 0..h {
        for x in 0..w {
            let (dx, dy) = (f64::from(x) + 0.5 - cx, f64::from(y) + 0.5 - cy);
            m += film.xyz(x, y).y * (dx * dx + dy * dy);
        }
    }
    m / sum
}
pub mod matrix;
