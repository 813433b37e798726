//! Light paths for caustics: they must add exactly the light camera paths leave to them.
//! Two checks with independent oracles:
//! - a point light beside a perfect mirror lights a floor as the light and its mirror
//!   image do (camera paths cannot find the image at all: a point light is never hit);
//! - a small area light over a dispersive glass block: camera paths alone find the
//!   caustic too (noisily), so rendering with and without light paths must agree within
//!   Monte Carlo error, with the box filter and with a Gaussian one, where the camera
//!   sees the caustic and where it sees it after a bounce, and the image must not depend
//!   on the thread count.

#[path = "../../scene/tests/support/rgbe.rs"]
mod rgbe;
mod sky;

use std::sync::Arc;

use glam::{Mat4, Vec3};
use prism_integrator::{Film, Filter, LambdaSampler, RenderSettings, render};
use prism_scene::camera::{ApertureShape, ApertureSize, Camera, Projection, ThinLens};
use prism_scene::geometry::BvhQuality;
use prism_scene::world::{Light, Material, Scene, SceneParts, SceneSpectrum, SpotFalloff};
use prism_spectrum::optics::named_glass;
use sky::sunny_sky;

/// A quad as two triangles, wound so that its front faces along `(b - a) x (c - a)`.
fn quad(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> [[Vec3; 3]; 2] {
    [[a, b, c], [a, c, d]]
}

/// A pinhole looking straight down at the floor from height `h`.
fn camera_above(h: f32, yfov_degrees: f32) -> Camera {
    Camera {
        name: "test".into(),
        to_world: Mat4::from_translation(Vec3::new(0.0, h, 0.0))
            * Mat4::from_rotation_x(-std::f32::consts::FRAC_PI_2),
        aspect_ratio: None,
        lens: None,
        system: None,
        projection: Projection::Perspective {
            yfov: yfov_degrees.to_radians(),
        },
    }
}

/// The floor y = 0, facing up, of half-size `half`.
fn floor(half: f32) -> [[Vec3; 3]; 2] {
    quad(
        Vec3::new(-half, 0.0, -half),
        Vec3::new(-half, 0.0, half),
        Vec3::new(half, 0.0, half),
        Vec3::new(half, 0.0, -half),
    )
}

fn settings(size: u32, spp: u64, seed: u64) -> RenderSettings {
    RenderSettings::default()
        .width(size)
        .height(size)
        .samples(0..spp)
        .seed(seed)
        .wavelengths(4)
        .lambda_sampler(LambdaSampler::Visible)
}

/// Mean Y over the pixels of the block [x0, x1) x [y0, y1).
fn block_mean(film: &Film, (x0, x1): (u32, u32), (y0, y1): (u32, u32)) -> f64 {
    let mut sum = 0.0;
    for y in y0..y1 {
        for x in x0..x1 {
            sum += film.xyz(x, y).y;
        }
    }
    sum / f64::from((x1 - x0) * (y1 - y0))
}

/// A floor (albedo 0.5) lit by `light(false)` (near (0.4, 1, 0)), with a perfect mirror
/// standing at x = 1.2, or instead of the mirror `light(true)`, the light's mirror image.
fn mirror_scene(with_mirror: bool, light: &dyn Fn(bool) -> Light) -> Scene {
    let mut triangles: Vec<[Vec3; 3]> = floor(4.0).to_vec();
    let mut lights = vec![light(false)];
    if with_mirror {
        // Facing -x, tall and wide enough that every floor point the camera sees gets
        // the image light through it.
        triangles.extend(quad(
            Vec3::new(1.2, -0.1, -6.0),
            Vec3::new(1.2, -0.1, 6.0),
            Vec3::new(1.2, 6.0, 6.0),
            Vec3::new(1.2, 6.0, -6.0),
        ));
    } else {
        lights.push(light(true));
    }
    let triangle_material = (0..triangles.len())
        .map(|i| u32::from(i >= 2))
        .collect::<Vec<_>>();
    Scene::new(SceneParts {
        attributes: Default::default(),
        triangle_material,
        triangles,
        materials: vec![
            Material::Diffuse {
                reflectance: SceneSpectrum::Constant(0.5),
            },
            // eta 0, k huge: reflectance 1 at every angle.
            Material::Conductor {
                eta: SceneSpectrum::Constant(0.0),
                k: SceneSpectrum::Constant(1e4),
                roughness: 0.0,
            },
        ],
        emission: vec![],
        lights,
        camera: camera_above(3.0, 30.0),
        quality: BvhQuality::Medium,
    })
    .unwrap()
}

/// A point mirrored in the plane x = 1.2 when `image`.
fn mirrored(p: Vec3, image: bool) -> Vec3 {
    if image {
        Vec3::new(2.4 - p.x, p.y, p.z)
    } else {
        p
    }
}

/// A direction mirrored in the plane x = 1.2 when `image`.
fn mirrored_direction(d: Vec3, image: bool) -> Vec3 {
    if image { Vec3::new(-d.x, d.y, d.z) } else { d }
}

/// The mirror's light reaches the floor only through light paths, which start on
/// `light` by its emission sampling; with them, the floor is lit as by the light plus its
/// mirror image (rendered with camera paths alone, its direct light, which the analytic
/// tests of transport.rs pin down).
fn assert_the_mirror_lights_the_floor_as_the_image_does(light: &dyn Fn(bool) -> Light) {
    // 1024 spp: at 256 the worst block strays 12% of the image share for some seeds.
    // Two bounces: floor and mirror. The floor's light via the mirror and back to the
    // floor would differ between the two scenes.
    let settings = (settings(24, 1024, 1)).max_depth(Some(2));
    let (mirrored, _) = render(&mirror_scene(true, light), &settings).unwrap();
    let (two_lights, _) = render(&mirror_scene(false, light), &settings).unwrap();
    let without = settings.clone().light_paths(false);
    let (camera_only, _) = render(&mirror_scene(true, light), &without).unwrap();
    for by in 0..3 {
        for bx in 0..3 {
            let range = |b: u32| (b * 8, b * 8 + 8);
            let got = block_mean(&mirrored, range(bx), range(by));
            let want = block_mean(&two_lights, range(bx), range(by));
            let direct = block_mean(&camera_only, range(bx), range(by));
            assert!(
                (got - want).abs() < 0.1 * (want - direct),
                "block ({bx}, {by}): light paths give {got}, the image light {want}, direct {direct}"
            );
            // The image's light is a large share, so the check above sees it.
            assert!(
                want - direct > 0.1 * want,
                "block ({bx}, {by}): {direct} vs {want}"
            );
        }
    }
}

#[test]
fn a_point_light_in_a_mirror_lights_the_floor_as_its_image_does() {
    assert_the_mirror_lights_the_floor_as_the_image_does(&|image| Light::Point {
        position: mirrored(Vec3::new(0.4, 1.0, 0.0), image),
        intensity: SceneSpectrum::Constant(1.0),
    });
}

#[test]
fn a_spot_light_in_a_mirror_lights_the_floor_as_its_image_does() {
    // Aimed at the mirror so that its axis reflects onto the view's centre; the view's
    // floor is 0 to ~0.25 rad off the axis, across the falloff's ramp (0.1 to 0.45 rad):
    // light paths must leave it with its cone and falloff.
    assert_the_mirror_lights_the_floor_as_the_image_does(&|image| Light::Spot {
        position: mirrored(Vec3::new(0.4, 1.0, 0.0), image),
        direction: mirrored_direction(Vec3::new(2.0, -1.0, 0.0).normalize(), image),
        cos_inner: 0.1f32.cos(),
        cos_outer: 0.45f32.cos(),
        intensity: SceneSpectrum::Constant(2.0),
        falloff: SpotFalloff::Smooth,
        texture: None,
    });
}

#[test]
fn a_directional_light_in_a_mirror_lights_the_floor_as_its_image_does() {
    // Parallel light falling towards the mirror: light paths start on a disk that covers
    // the scene, and must carry the light's irradiance.
    assert_the_mirror_lights_the_floor_as_the_image_does(&|image| Light::Directional {
        direction: mirrored_direction(Vec3::new(0.5, -1.0, 0.0).normalize(), image),
        irradiance: SceneSpectrum::Constant(0.3),
    });
}

/// A box of SF11 glass (dispersive) over a white floor, lit by a small square light
/// above and beside it; the camera looks down at the floor, the block, its shadow and
/// the caustic its side casts. With `wall`, a white wall stands behind the block and the
/// camera looks at it across the floor: much of the caustic's light reaches the wall
/// after a bounce on the floor. `roughness` roughens the glass (GGX alpha its square);
/// `lens` puts a thin lens on the camera that looks at the wall.
fn glass_block_scene(wall: bool, roughness: f32, lens: Option<ThinLens>) -> Scene {
    Scene::new(glass_block_parts(wall, roughness, lens)).unwrap()
}

fn glass_block_parts(wall: bool, roughness: f32, lens: Option<ThinLens>) -> SceneParts {
    let mut triangles: Vec<[Vec3; 3]> = floor(3.0).to_vec();
    if wall {
        triangles.extend(quad(
            Vec3::new(-3.0, 0.0, -1.2),
            Vec3::new(3.0, 0.0, -1.2),
            Vec3::new(3.0, 3.0, -1.2),
            Vec3::new(-3.0, 3.0, -1.2),
        ));
    }
    let walls = triangles.len();
    let (lo, hi) = (Vec3::new(-0.5, 0.4, -0.5), Vec3::new(0.5, 0.9, 0.5));
    let corner =
        |x: usize, y: usize, z: usize| Vec3::new([lo.x, hi.x][x], [lo.y, hi.y][y], [lo.z, hi.z][z]);
    // Six outward-facing faces.
    for [a, b, c, d] in [
        [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)],
        [(0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0)],
        [(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)],
        [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)],
        [(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)],
        [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)],
    ] {
        let v = |(x, y, z)| corner(x, y, z);
        triangles.extend(quad(v(a), v(b), v(c), v(d)));
    }
    let glass = triangles.len();
    // The light, facing down, beside the camera's view and above the block's side.
    let (x0, x1, y, s) = (0.8, 1.8, 1.6, 0.5);
    triangles.extend(quad(
        Vec3::new(x0, y, -s),
        Vec3::new(x1, y, -s),
        Vec3::new(x1, y, s),
        Vec3::new(x0, y, s),
    ));
    let triangle_material = (0..triangles.len())
        .map(|i| match i {
            i if i < walls => 0,
            i if i < glass => 1,
            _ => 2,
        })
        .collect();
    let lights = (glass..glass + 2)
        .map(|t| Light::Triangle {
            triangle: t as u32,
            emission: 0,
            two_sided: false,
        })
        .collect();
    SceneParts {
        attributes: Default::default(),
        triangle_material,
        triangles,
        materials: vec![
            Material::Diffuse {
                reflectance: SceneSpectrum::Constant(0.8),
            },
            Material::Dielectric {
                ior: SceneSpectrum::Sellmeier(Arc::new(named_glass("sf11").unwrap().ior)),
                roughness,
                absorption: None,
            },
            Material::Diffuse {
                reflectance: SceneSpectrum::Constant(0.0),
            },
        ],
        emission: vec![SceneSpectrum::Constant(20.0)],
        lights,
        camera: if wall {
            Camera {
                lens,
                ..Camera::look_at(
                    Vec3::new(0.3, 1.3, 3.0),
                    Vec3::new(0.3, 0.5, -1.2),
                    Vec3::Y,
                    45f32.to_radians(),
                )
            }
        } else {
            camera_above(3.5, 40.0)
        },
        quality: BvhQuality::Medium,
    }
}

/// With and without light paths the glass block's caustic and the floor converge to the
/// same image. Camera paths are the same in both renders of a seed (light paths draw from
/// their own streams), so the per-seed difference is light paths' contribution minus the
/// camera paths' share they replace: its mean over seeds must be zero within 4 standard
/// errors (plus 2%: the camera paths' caustic is heavy-tailed, so its spread understates
/// the error) in every block of pixels, for the box and the Gaussian filter. Camera paths
/// that also counted the caustic change the caustic's blocks by 10-40 standard errors.
#[test]
fn light_paths_and_camera_paths_agree_on_a_dispersive_caustic() {
    assert_light_and_camera_paths_agree(&glass_block_scene(false, 0.0, None), 4);
}

/// The same where the camera sees the caustic mostly after a bounce (light, glass, floor,
/// wall, camera): light paths go on past the floor and connect to the camera from the
/// wall, and camera paths leave them every path that reaches the light through glass
/// after a first bounce that is not a delta.
#[test]
fn light_paths_and_camera_paths_agree_on_a_caustic_seen_after_a_bounce() {
    assert_light_and_camera_paths_agree(&glass_block_scene(true, 0.0, None), 4);
}

/// The same through slightly rough glass (alpha 0.0625): its light is focused too, so
/// light paths carry it, and camera paths leave them the light they would find through it,
/// by a bounce off the glass or a light sample there, past their first bounce.
#[test]
fn light_paths_and_camera_paths_agree_on_a_rough_glass_caustic() {
    assert_light_and_camera_paths_agree(&glass_block_scene(true, 0.25, None), 4);
}

/// The same through a wide thin lens focused in front of the block (everything blurred
/// by several pixels): light paths connect to points of the aperture, with the lens's
/// importance (connecting to the pinhole instead fails by 7 standard errors).
#[test]
fn light_paths_and_camera_paths_agree_through_a_thin_lens() {
    let lens = ThinLens {
        focus_distance: Some(1.5),
        shape: ApertureShape::Polygon {
            blades: 5,
            rotation: 0.0,
        },
        ..ThinLens::new(ApertureSize::Radius(0.8))
    };
    assert_light_and_camera_paths_agree(&glass_block_scene(true, 0.0, Some(lens)), 4);
}

/// The same under a sunny sky alone (the block's emitter dark): light paths leave the
/// environment through a disk over the block alone (`Tracer::aim`), and camera paths leave
/// them the sky they would reach through the glass past their first bounce, by a bounce
/// or a light sample.
#[test]
fn light_paths_and_camera_paths_agree_on_a_sun_caustic() {
    let mut parts = glass_block_parts(false, 0.0, None);
    parts.lights = vec![Light::EnvironmentMap { map: sunny_sky() }];
    let scene = Scene::new(parts).unwrap();
    assert_light_and_camera_paths_agree(&scene, 4);
}

/// The same with the block a smooth plastic instead of glass (the only material focusing
/// light): its coating's mirror reflection is a delta lobe beside a diffuse one, so light
/// paths carry the light the mirror throws onto the floor and the wall (the lobe sampled
/// at their first bounce decides), and camera paths leave them what they find through
/// that lobe alone.
#[test]
fn light_paths_and_camera_paths_agree_on_a_smooth_plastic_caustic() {
    let mut parts = glass_block_parts(true, 0.0, None);
    parts.materials[1] = Material::Plastic {
        reflectance: SceneSpectrum::Constant(0.3),
        nonlinear: false,
        coating: Arc::new(prism_scene::bsdf::PlasticCoating::new(1.49, 0.0)),
    };
    let scene = Scene::new(parts).unwrap();
    assert!(
        traces_light_paths(&scene),
        "a smooth plastic starts light paths"
    );
    assert_light_and_camera_paths_agree(&scene, 2);
}

/// Whether rendering `scene` traces light paths.
fn traces_light_paths(scene: &Scene) -> bool {
    prism_integrator::Renderer::new(scene, &settings(8, 1, 0))
        .unwrap()
        .light_caustics()
}

/// Renders `scene` with and without light paths over seeds and checks every block of
/// pixels agrees, and that light paths carry a visible share in at least `caustic`
/// blocks.
fn assert_light_and_camera_paths_agree(scene: &Scene, caustic: usize) {
    const SIZE: u32 = 16;
    // Eight seeds once left a corner block 4.8 standard errors out (the caustic's tail;
    // 64 seeds put the same block at 0.05), so sixteen.
    const RUNS: u64 = 16;
    for filter in [Filter::Box, Filter::from_name("gaussian").unwrap()] {
        let mut differences = vec![Vec::new(); 16];
        let mut level = [0.0; 16];
        for seed in 0..RUNS {
            let base = (settings(SIZE, 128, seed)).filter(filter);
            let with = render(scene, &base).unwrap().0;
            let off = base.light_paths(false);
            let without = render(scene, &off).unwrap().0;
            for b in 0..16u32 {
                let (bx, by) = (b % 4 * 4, b / 4 * 4);
                let a = block_mean(&with, (bx, bx + 4), (by, by + 4));
                let c = block_mean(&without, (bx, bx + 4), (by, by + 4));
                differences[b as usize].push(a - c);
                level[b as usize] += a / RUNS as f64;
            }
        }
        let mut caustic_blocks = 0;
        for (b, d) in differences.iter().enumerate() {
            let n = d.len() as f64;
            let mean = d.iter().sum::<f64>() / n;
            let var = d.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
            let se = (var / n).sqrt();
            assert!(
                mean.abs() <= 4.0 * se + 0.02 * level[b],
                "{filter:?} block {b}: light paths change its mean by {mean} (standard error {se}, level {})",
                level[b]
            );
            // Blocks whose light paths carry a visible share are the caustic's.
            if d.iter().any(|v| v.abs() > 0.01 * level[b]) {
                caustic_blocks += 1;
            }
        }
        assert!(
            caustic_blocks >= caustic,
            "{filter:?}: caustic in {caustic_blocks} blocks"
        );
    }
}

/// Light paths splat anywhere on the film; the image still does not depend on threads.
#[test]
fn light_paths_do_not_depend_on_the_thread_count() {
    let scene = glass_block_scene(false, 0.0, None);
    let one = (settings(20, 4, 7)).threads(1);
    let two = one.clone().threads(2);
    let (a, _) = render(&scene, &one).unwrap();
    let (b, _) = render(&scene, &two).unwrap();
    assert_eq!(a.sums(), b.sums());
}
