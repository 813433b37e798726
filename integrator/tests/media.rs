//! The volumetric path tracer against closed forms: Beer-Lambert per band through a
//! chromatic absorbing slab, the radiance of an emissive slab, white furnaces of
//! scattering media (chromatic sigma_s, forward, isotropic and backward scattering, and
//! inside a dielectric boundary), single scattering of a thin medium, and the settings it
//! refuses with one clear error.

mod common;

use common::{assert_image_mean, furnace, icosphere, mean_stokes, ortho_camera, square_z0};
use glam::Vec3;
use prism_integrator::{LambdaSampler, RenderSettings, SpectralBands, render};
use prism_scene::medium::{Media, Medium, Phase};
use prism_scene::world::{Light, Material, Scene, SceneParts, SceneSpectrum};
use prism_spectrum::colorimetry::{Observer, emission_xyz};
use prism_spectrum::spectra::{Constant, Extrapolation, PiecewiseLinear};

/// sigma rising linearly from `lo` at 400 nm to `hi` at 700 nm (clamped beyond).
fn linear(lo: f64, hi: f64) -> SceneSpectrum {
    SceneSpectrum::Table(std::sync::Arc::new(
        PiecewiseLinear::new(vec![400.0, 700.0], vec![lo, hi], Extrapolation::Clamp).unwrap(),
    ))
}

fn linear_at(lo: f64, hi: f64, nm: f64) -> f64 {
    lo + (hi - lo) * ((nm - 400.0) / 300.0).clamp(0.0, 1.0)
}

fn constant_xyz(value: f64) -> [f64; 3] {
    emission_xyz(&Constant::new(value).unwrap(), Observer::Cie1931).to_array()
}

/// The closed box [-h, h]^2 x [z0, z1], outward winding.
fn slab(h: f32, z0: f32, z1: f32) -> Vec<[Vec3; 3]> {
    let c = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let quad = |a: Vec3, b: Vec3, cc: Vec3, d: Vec3| [[a, b, cc], [a, cc, d]];
    let mut t = vec![];
    // Top (+z), bottom (-z), then the four sides.
    t.extend(quad(c(-h, -h, z1), c(h, -h, z1), c(h, h, z1), c(-h, h, z1)));
    t.extend(quad(c(-h, -h, z0), c(-h, h, z0), c(h, h, z0), c(h, -h, z0)));
    t.extend(quad(
        c(-h, -h, z0),
        c(h, -h, z0),
        c(h, -h, z1),
        c(-h, -h, z1),
    ));
    t.extend(quad(c(h, h, z0), c(-h, h, z0), c(-h, h, z1), c(h, h, z1)));
    t.extend(quad(c(h, -h, z0), c(h, h, z0), c(h, h, z1), c(h, -h, z1)));
    t.extend(quad(
        c(-h, h, z0),
        c(-h, -h, z0),
        c(-h, -h, z1),
        c(-h, h, z1),
    ));
    t
}

/// An emitter of radiance `emission` filling the view of an orthographic camera at z = 1
/// looking down, behind an interface slab from z = 0.2 to 0.2 + `d` holding `medium`.
fn emitter_behind_slab(emission: f64, medium: Medium, d: f32) -> Scene {
    let lights = (0..2)
        .map(|t| Light::Triangle {
            triangle: t,
            emission: 0,
            two_sided: false,
        })
        .collect();
    slab_scene(emission, lights, medium, d)
}

/// [`emitter_behind_slab`] lit by `lights` as well.
fn slab_scene(emission: f64, lights: Vec<Light>, medium: Medium, d: f32) -> Scene {
    let mut triangles = square_z0(2.0);
    let mut triangle_material = vec![0, 0];
    let box_ = slab(3.0, 0.2, 0.2 + d);
    triangle_material.extend(vec![1; box_.len()]);
    triangles.extend(box_);
    let mut scene = Scene::new(SceneParts {
        attributes: Default::default(),
        triangles,
        triangle_material,
        materials: vec![
            Material::Diffuse {
                reflectance: SceneSpectrum::Constant(0.0),
            },
            Material::Interface,
        ],
        emission: vec![SceneSpectrum::Constant(emission)],
        lights,
        camera: ortho_camera(Vec3::new(0.0, 0.0, 1.0), 0.5),
        quality: prism_scene::geometry::BvhQuality::Medium,
    })
    .unwrap();
    scene
        .set_media(Media::new(vec![medium], vec![None, Some(0)], None).unwrap())
        .unwrap();
    scene
}

fn settings(size: u32, spp: u64, wavelengths: usize) -> RenderSettings {
    RenderSettings::default()
        .width(size)
        .height(size)
        .samples(0..spp)
        .wavelengths(wavelengths)
        .lambda_sampler(LambdaSampler::Uniform)
}

/// A chromatic absorber in front of an emitter: each spectral band is the band's mean of
/// L exp(-sigma_a(lambda) d), with every lane kept through the medium.
#[test]
fn absorbing_slab_is_beer_lambert_per_band() {
    let (lo, hi, d) = (0.5, 4.0, 0.5f32);
    let medium = Medium::new(
        linear(lo, hi),
        SceneSpectrum::Constant(0.0),
        Phase::henyey_greenstein(0.0).unwrap(),
        None,
    )
    .unwrap();
    let scene = emitter_behind_slab(2.0, medium, d);
    let bands = SpectralBands::new(400.0, 700.0, 6).unwrap();
    for wavelengths in [1, 4, 8] {
        let (film, stats) =
            render(&scene, &settings(8, 256, wavelengths).bands(Some(bands))).unwrap();
        assert_eq!(stats.nonfinite, 0);
        for b in 0..bands.count() {
            let (mean, error) = band_mean(&film, b);
            let centre = bands.center(b);
            let expected = (0..64)
                .map(|k| {
                    let nm = centre - 0.5 * bands.width() + (k as f64 + 0.5) / 64.0 * bands.width();
                    2.0 * (-linear_at(lo, hi, nm) * f64::from(d)).exp()
                })
                .sum::<f64>()
                / 64.0;
            assert!(
                (mean - expected).abs() < 5.0 * error + 2e-3 * expected,
                "{wavelengths} wavelengths, band {b} ({centre} nm): {mean} vs {expected} (+-{error})"
            );
        }
    }
}

/// Single scattering: a slab of chromatic, absorbing, forward-scattering medium lit by a
/// sun at 40 degrees from its normal, seen face on with one bounce allowed. Light reaching
/// depth z has crossed z / mu_l of medium and leaves along z more, so per wavelength
/// L = E sigma_s p(-mu_l) (1 - exp(-sigma_t d (1 + 1/mu_l))) / (sigma_t (1 + 1/mu_l)).
#[test]
fn single_scattering_matches_its_closed_form() {
    let (a_lo, a_hi, s_lo, s_hi, g, d) = (0.2, 1.0, 1.5, 0.3, 0.4, 0.6f32);
    let theta = 40f32.to_radians();
    let sun = Light::Directional {
        direction: Vec3::new(theta.sin(), 0.0, -theta.cos()),
        irradiance: SceneSpectrum::Constant(3.0),
    };
    let medium = Medium::new(
        linear(a_lo, a_hi),
        linear(s_lo, s_hi),
        Phase::henyey_greenstein(g).unwrap(),
        None,
    )
    .unwrap();
    let phase = Phase::henyey_greenstein(g).unwrap();
    let scene = slab_scene(0.0, vec![sun], medium, d);
    let bands = SpectralBands::new(400.0, 700.0, 5).unwrap();
    let mu = f64::from(theta.cos());
    let p = f64::from(phase.p(-theta.cos()));
    for wavelengths in [1, 4] {
        let settings = settings(16, 4096, wavelengths)
            .bands(Some(bands))
            .max_depth(Some(1));
        let (film, stats) = render(&scene, &settings).unwrap();
        assert_eq!(stats.nonfinite, 0);
        for b in 0..bands.count() {
            let (mean, error) = band_mean(&film, b);
            let centre = bands.center(b);
            let expected = (0..64)
                .map(|k| {
                    let nm = centre - 0.5 * bands.width() + (k as f64 + 0.5) / 64.0 * bands.width();
                    let sigma_s = linear_at(s_lo, s_hi, nm);
                    let sigma_t = linear_at(a_lo, a_hi, nm) + sigma_s;
                    let k = sigma_t * (1.0 + 1.0 / mu);
                    3.0 * sigma_s * p * (1.0 - (-k * f64::from(d)).exp()) / k
                })
                .sum::<f64>()
                / 64.0;
            assert!(
                (mean - expected).abs() < 5.0 * error + 2e-3 * expected,
                "{wavelengths} wavelengths, band {b} ({centre} nm): {mean} vs {expected} (+-{error})"
            );
        }
    }
}

/// The mean over a film's pixels of band `b`, and its standard error.
fn band_mean(film: &prism_integrator::Film, b: usize) -> (f64, f64) {
    let values: Vec<f64> = (0..film.height())
        .flat_map(|y| (0..film.width()).map(move |x| (x, y)))
        .map(|(x, y)| film.spectrum(x, y).unwrap()[b])
        .collect();
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// A slab that only absorbs and emits, seen face on against black: L = epsilon (1 -
/// exp(-sigma_a d)) / sigma_a, and epsilon d where it does not absorb.
#[test]
fn emissive_slab_matches_its_closed_form() {
    for (sigma_a, epsilon, d) in [(2.0, 1.5, 0.3f32), (0.0, 0.8, 0.25), (30.0, 0.5, 0.4)] {
        let medium = Medium::new(
            SceneSpectrum::Constant(sigma_a),
            SceneSpectrum::Constant(0.0),
            Phase::henyey_greenstein(0.0).unwrap(),
            Some(SceneSpectrum::Constant(epsilon)),
        )
        .unwrap();
        let scene = emitter_behind_slab(0.0, medium, d);
        let expected = if sigma_a > 0.0 {
            epsilon * (1.0 - (-sigma_a * f64::from(d)).exp()) / sigma_a
        } else {
            epsilon * f64::from(d)
        };
        let (film, stats) = render(&scene, &settings(8, 128, 4)).unwrap();
        assert_eq!(stats.nonfinite, 0);
        assert_image_mean(
            &film,
            constant_xyz(expected),
            &format!("sigma_a {sigma_a}, epsilon {epsilon}, d {d}"),
        );
    }
}

/// A sphere of medium of albedo 1 in a uniform environment of radiance 1 is invisible:
/// every pixel sees 1 at every wavelength, whatever the phase function, with sigma_s
/// varying tenfold across the spectrum, bounded by an interface or by glass.
#[test]
fn scattering_furnace_returns_the_environment() {
    let sphere = icosphere(3);
    let ids = vec![0; sphere.len()];
    let boundaries = [
        ("interface", Material::Interface),
        (
            "glass",
            Material::Dielectric {
                ior: SceneSpectrum::Constant(1.5),
                roughness: 0.0,
                absorption: None,
            },
        ),
    ];
    let expected = constant_xyz(1.0);
    for (boundary, material) in boundaries {
        for g in [-0.7, 0.0, 0.9] {
            let medium = Medium::new(
                SceneSpectrum::Constant(0.0),
                linear(0.5, 5.0),
                Phase::henyey_greenstein(g).unwrap(),
                None,
            )
            .unwrap();
            let mut scene = furnace(sphere.clone(), ids.clone(), vec![material.clone()], 1.2);
            scene
                .set_media(Media::new(vec![medium], vec![Some(0)], None).unwrap())
                .unwrap();
            let (film, stats) = render(&scene, &settings(12, 48, 4)).unwrap();
            assert_eq!(stats.nonfinite, 0);
            assert_image_mean(&film, expected, &format!("{boundary}, g {g}"));
        }
    }
}

/// Kirchhoff's law as a furnace: a sphere of medium that absorbs (sigma_a rising sixfold
/// across the spectrum), scatters (sigma_s falling fivefold) and emits epsilon = sigma_a
/// L, in a uniform environment of radiance L = 1, is in equilibrium with it: every pixel
/// sees 1 at every wavelength. What absorption takes at a collision the emission there
/// gives back, so a collision's absorption weight that were wrong for any lane, or any
/// mismatch between the lanes' albedos and their densities, would show.
#[test]
fn absorbing_glowing_furnace_is_in_equilibrium() {
    let sphere = icosphere(3);
    let ids = vec![0; sphere.len()];
    for g in [0.0, 0.9] {
        let medium = Medium::new(
            linear(0.5, 3.0),
            linear(4.0, 0.8),
            Phase::henyey_greenstein(g).unwrap(),
            Some(linear(0.5, 3.0)),
        )
        .unwrap();
        let mut scene = furnace(sphere.clone(), ids.clone(), vec![Material::Interface], 1.2);
        scene
            .set_media(Media::new(vec![medium], vec![Some(0)], None).unwrap())
            .unwrap();
        let (film, stats) = render(&scene, &settings(12, 48, 4)).unwrap();
        assert_eq!(stats.nonfinite, 0);
        let expected = constant_xyz(1.0);
        for (k, &value) in expected.iter().enumerate() {
            // A wrong weight can diverge instead of biasing: its error bar would be huge.
            let (_, error) = common::mean_and_error(&film, k);
            assert!(
                error < 0.01 * value,
                "g {g} channel {k}: standard error {error}"
            );
        }
        assert_image_mean(&film, expected, &format!("g {g}"));
    }
}

/// Fog filling the world, scattering by Rayleigh's phase function with sigma_s rising
/// eightfold across the spectrum, with a sphere of another medium in it, inside a closed
/// black room whose walls glow with radiance 1: without absorption the radiance is 1
/// everywhere and in every direction. Light reaches every vertex through fog both ways,
/// by next-event estimation and by hitting the walls, weighed against each other.
#[test]
fn fog_in_a_glowing_room_returns_the_walls() {
    let sphere = icosphere(2);
    let mut triangles: Vec<[Vec3; 3]> = icosphere(2)
        .into_iter()
        .map(|[a, b, c]| [a * 4.0, c * 4.0, b * 4.0])
        .collect();
    let walls = triangles.len() as u32;
    let mut triangle_material = vec![0; triangles.len()];
    triangle_material.extend(vec![1; sphere.len()]);
    triangles.extend(sphere);
    let mut scene = Scene::new(SceneParts {
        attributes: Default::default(),
        triangles,
        triangle_material,
        materials: vec![
            Material::Diffuse {
                reflectance: SceneSpectrum::Constant(0.0),
            },
            Material::Interface,
        ],
        emission: vec![SceneSpectrum::Constant(1.0)],
        lights: (0..walls)
            .map(|t| Light::Triangle {
                triangle: t,
                emission: 0,
                two_sided: false,
            })
            .collect(),
        camera: ortho_camera(Vec3::new(0.0, 0.0, 3.0), 1.2),
        quality: prism_scene::geometry::BvhQuality::Medium,
    })
    .unwrap();
    let fog = Medium::new(
        SceneSpectrum::Constant(0.0),
        linear(0.05, 0.4),
        Phase::Rayleigh,
        None,
    )
    .unwrap();
    let inner = Medium::new(
        SceneSpectrum::Constant(0.0),
        SceneSpectrum::Constant(3.0),
        Phase::henyey_greenstein(0.5).unwrap(),
        None,
    )
    .unwrap();
    scene
        .set_media(Media::new(vec![inner, fog], vec![None, Some(0)], Some(1)).unwrap())
        .unwrap();
    let (film, stats) = render(&scene, &settings(12, 48, 4)).unwrap();
    assert_eq!(stats.nonfinite, 0);
    assert_image_mean(&film, constant_xyz(1.0), "fog");
}

/// What the volumetric path tracer does not do is refused with one clear error.
#[test]
fn media_refuse_what_they_do_not_support() {
    let medium = Medium::new(
        SceneSpectrum::Constant(1.0),
        SceneSpectrum::Constant(0.0),
        Phase::Rayleigh,
        None,
    )
    .unwrap();
    let scene = emitter_behind_slab(1.0, medium, 0.3);
    let splitting = settings(4, 1, 4).splits(prism_integrator::Splits::Fixed(2));
    let Err(e) = render(&scene, &splitting) else {
        panic!("splitting: accepted");
    };
    let e = e.to_string();
    assert!(
        e.contains("splitting") && e.contains("media") && !e.contains('\n'),
        "{e}"
    );
}

/// A heterogeneous medium of albedo 1 (a blob of smoke on a grid, chromatic sigma_s,
/// forward scattering) inside an interface sphere is a furnace too: tracking through the
/// coarse majorant grid loses and adds nothing.
#[test]
fn grid_furnace_returns_the_environment() {
    let n = 16u32;
    let values = (0..n * n * n)
        .map(|i| {
            let c = glam::UVec3::new(i % n, (i / n) % n, i / (n * n)).as_vec3();
            let p = (c + 0.5) / n as f32 * 2.0 - 1.0;
            // A lumpy blob: dense at one side, empty in a corner.
            (6.0 * (-3.0 * (p - glam::Vec3::new(0.3, 0.2, 0.0)).length_squared()).exp()).max(0.0)
        })
        .collect();
    let grid = prism_scene::medium::Grid::new(
        glam::UVec3::splat(n),
        Vec3::splat(-1.0),
        Vec3::splat(1.0),
        values,
    )
    .unwrap();
    let medium = Medium::new(
        SceneSpectrum::Constant(0.0),
        linear(0.5, 2.0),
        Phase::henyey_greenstein(0.6).unwrap(),
        None,
    )
    .unwrap()
    .with_density(grid);
    let sphere = icosphere(3);
    let ids = vec![0; sphere.len()];
    let mut scene = furnace(sphere, ids, vec![Material::Interface], 1.2);
    scene
        .set_media(Media::new(vec![medium], vec![Some(0)], None).unwrap())
        .unwrap();
    let (film, stats) = render(&scene, &settings(12, 48, 4)).unwrap();
    assert_eq!(stats.nonfinite, 0);
    assert_image_mean(&film, constant_xyz(1.0), "grid");
}

/// Planck's law, W m^-2 sr^-1 nm^-1 at `nm` nanometres and `kelvin` (CODATA 2018 exact
/// constants), written here apart from the renderer's.
fn planck_per_nm(nm: f64, kelvin: f64) -> f64 {
    let (h, c, k) = (6.626_070_15e-34, 299_792_458.0, 1.380_649e-23);
    let lambda = nm * 1e-9;
    2.0 * h * c * c / lambda.powi(5) / ((h * c / (lambda * k * kelvin)).exp() - 1.0) * 1e-9
}

/// A hot absorbing slab (a uniform temperature grid, no scattering) seen face on glows as
/// Kirchhoff says: L = B_lambda(T) (1 - exp(-sigma_a d)) in every band.
#[test]
fn hot_slab_glows_as_a_grey_body() {
    let (sigma_a, d, kelvin) = (3.0, 0.3f32, 2500.0f32);
    let temperature = prism_scene::medium::Grid::new(
        glam::UVec3::splat(2),
        Vec3::new(-4.0, -4.0, 0.0),
        Vec3::new(4.0, 4.0, 1.0),
        vec![kelvin; 8],
    )
    .unwrap();
    let medium = Medium::new(
        SceneSpectrum::Constant(sigma_a),
        SceneSpectrum::Constant(0.0),
        Phase::henyey_greenstein(0.0).unwrap(),
        None,
    )
    .unwrap()
    .with_temperature(temperature);
    let scene = emitter_behind_slab(0.0, medium, d);
    let bands = SpectralBands::new(400.0, 700.0, 6).unwrap();
    let (film, stats) = render(&scene, &settings(8, 256, 4).bands(Some(bands))).unwrap();
    assert_eq!(stats.nonfinite, 0);
    for b in 0..bands.count() {
        let (mean, error) = band_mean(&film, b);
        let centre = bands.center(b);
        let expected = (0..64)
            .map(|k| {
                let nm = centre - 0.5 * bands.width() + (k as f64 + 0.5) / 64.0 * bands.width();
                planck_per_nm(nm, f64::from(kelvin))
            })
            .sum::<f64>()
            / 64.0
            * (1.0 - (-sigma_a * f64::from(d)).exp());
        assert!(
            (mean - expected).abs() < 5.0 * error + 2e-3 * expected,
            "band {b} ({centre} nm): {mean} vs {expected} (+-{error})"
        );
    }
}

/// A fluorescent furnace: a dye of quantum yield 1 whose absorption is C e(l) / l (e its
/// re-emission spectrum) re-emits at every wavelength exactly what it absorbs there when
/// lit by radiance 1 at every wavelength (in-scattering C e(l_o) / l_o integral of e = its
/// absorption), so a sphere of it in a uniform environment of 1 is invisible. The path
/// changes wavelength at every re-emission, and the balance of the two terms only holds
/// if the dye's events, weights and wavelengths are all right.
#[test]
fn fluorescent_furnace_returns_the_environment() {
    let emission = |nm: f64| (-0.5 * ((nm - 520.0) / 34.0).powi(2)).exp();
    let nodes: Vec<f64> = (300..=830).step_by(2).map(f64::from).collect();
    let absorption: Vec<f64> = nodes.iter().map(|&nm| 1500.0 * emission(nm) / nm).collect();
    let table = |values: Vec<f64>| {
        SceneSpectrum::Table(std::sync::Arc::new(
            PiecewiseLinear::new(nodes.clone(), values, Extrapolation::Zero).unwrap(),
        ))
    };
    let reemission: Vec<f64> = nodes.iter().map(|&nm| emission(nm)).collect();
    let dye = prism_scene::medium::Fluorescence::new(
        table(absorption),
        &table(reemission),
        1.0,
        prism_sampling::wavelength::WavelengthRange::new(300.0, 830.0).unwrap(),
        265,
    )
    .unwrap();
    // The dye alone, and with a scattering of albedo 1 that varies with wavelength.
    for (what, sigma_s) in [
        ("dye", SceneSpectrum::Constant(0.0)),
        ("dye and scattering", linear(0.5, 2.0)),
    ] {
        let medium = Medium::new(
            SceneSpectrum::Constant(0.0),
            sigma_s,
            Phase::henyey_greenstein(0.5).unwrap(),
            None,
        )
        .unwrap()
        .with_fluorescence(dye.clone());
        let sphere = icosphere(3);
        let ids = vec![0; sphere.len()];
        let mut scene = furnace(sphere, ids, vec![Material::Interface], 1.2);
        scene
            .set_media(Media::new(vec![medium], vec![Some(0)], None).unwrap())
            .unwrap();
        assert!(scene.features().fluorescence);
        let bands = SpectralBands::new(440.0, 620.0, 6).unwrap();
        let (film, stats) = render(&scene, &settings(12, 512, 4).bands(Some(bands))).unwrap();
        assert_eq!(stats.nonfinite, 0);
        for b in 0..bands.count() {
            let (mean, error) = band_mean(&film, b);
            assert!(
                (mean - 1.0).abs() < 5.0 * error + 0.01,
                "{what}, band {b} ({} nm): {mean} (+-{error})",
                bands.center(b)
            );
        }
    }
}

/// A dye lit by an ultraviolet lamp: the lamp, with almost no power in the visible, is
/// found by light sampling after the path takes the dye's incident wavelengths, and the
/// dye glows green where nothing else could. Its radiance agrees whether a red lamp it does
/// not absorb competes in the choice of lights or not.
#[test]
fn dye_glows_under_an_ultraviolet_lamp() {
    let dye = || {
        prism_scene::medium::Fluorescence::new(
            SceneSpectrum::Gaussian(
                prism_spectrum::spectra::Gaussian::new(370.0, 40.0, 20.0).unwrap(),
            ),
            &prism_spectrum::spectra::Gaussian::new(520.0, 35.0, 1.0).unwrap(),
            0.9,
            prism_sampling::wavelength::WavelengthRange::new(300.0, 830.0).unwrap(),
            265,
        )
        .unwrap()
    };
    let mut means = vec![];
    for with_white_light in [false, true] {
        let medium = Medium::new(
            SceneSpectrum::Constant(0.0),
            SceneSpectrum::Constant(0.0),
            Phase::henyey_greenstein(0.0).unwrap(),
            None,
        )
        .unwrap()
        .with_fluorescence(dye());
        let mut lights = vec![Light::Point {
            position: Vec3::new(0.0, 0.0, 0.6),
            intensity: SceneSpectrum::Gaussian(
                prism_spectrum::spectra::Gaussian::new(365.0, 10.0, 5.0).unwrap(),
            ),
        }];
        if with_white_light {
            // A red lamp the dye does not absorb, competing in the choice of lights.
            lights.push(Light::Point {
                position: Vec3::new(0.0, 0.0, 5.0),
                intensity: SceneSpectrum::Gaussian(
                    prism_spectrum::spectra::Gaussian::new(700.0, 30.0, 2.0).unwrap(),
                ),
            });
        }
        let scene = slab_scene(0.0, lights, medium, 0.3);
        let bands = SpectralBands::new(490.0, 550.0, 1).unwrap();
        let (film, stats) = render(&scene, &settings(8, 4096, 4).bands(Some(bands))).unwrap();
        assert_eq!(stats.nonfinite, 0);
        // The glow falls off away from the lamp, so the pixels' spread is no error bar:
        // the image's mean, in a band the lamp does not emit in.
        let (mean, _) = band_mean(&film, 0);
        eprintln!("dye glow, competing red lamp {with_white_light}: {mean}");
        means.push(mean);
    }
    let (a, b) = (means[0], means[1]);
    assert!(a > 0.05, "no glow: {a}");
    assert!((a - b).abs() < 0.03 * a, "{a} vs {b}");
}

/// Polarized renders of media: a furnace of Rayleigh or Henyey-Greenstein scattering under
/// an unpolarized uniform environment is invisible and unpolarized (the radiance field is
/// isotropic, so nothing singles out a plane), as in unpolarized renders.
#[test]
fn polarized_furnace_stays_unpolarized() {
    for phase in [Phase::Rayleigh, Phase::henyey_greenstein(0.6).unwrap()] {
        let medium =
            Medium::new(SceneSpectrum::Constant(0.0), linear(0.5, 3.0), phase, None).unwrap();
        let sphere = icosphere(3);
        let ids = vec![0; sphere.len()];
        let mut scene = furnace(sphere, ids, vec![Material::Interface], 1.2);
        scene
            .set_media(Media::new(vec![medium], vec![Some(0)], None).unwrap())
            .unwrap();
        // 256 samples: at 64 the mean Stokes components' noise reaches 1% of S0.
        let (film, stats) = render(&scene, &settings(12, 256, 4).polarized(true)).unwrap();
        assert_eq!(stats.nonfinite, 0);
        assert_image_mean(&film, constant_xyz(1.0), &format!("polarized {phase:?}"));
        let [s0, s1, s2, s3] = mean_stokes(&film);
        for (k, s) in [s1, s2, s3].into_iter().enumerate() {
            assert!(s.abs() < 0.01 * s0, "{phase:?}: S{} = {s} of {s0}", k + 1);
        }
    }
}

/// Single scattering of sunlight by Rayleigh particles, seen face on: every path scatters
/// once at the same angle (140 degrees), so the light is linearly polarized by (1 - c^2) /
/// (1 + c^2) (c = cos 140 degrees), perpendicular to the scattering plane (the image's
/// columns here: S1 < 0 against its rows), as the blue sky is; with Henyey-Greenstein
/// particles it stays unpolarized.
#[test]
fn rayleigh_single_scattering_polarizes_the_sky() {
    let theta = 40f32.to_radians();
    let c = -f64::from(theta.cos());
    let expected = -(1.0 - c * c) / (1.0 + c * c);
    for (phase, dolp) in [
        (Phase::Rayleigh, expected),
        (Phase::henyey_greenstein(0.3).unwrap(), 0.0),
    ] {
        let sun = Light::Directional {
            direction: Vec3::new(theta.sin(), 0.0, -theta.cos()),
            irradiance: SceneSpectrum::Constant(3.0),
        };
        let medium =
            Medium::new(SceneSpectrum::Constant(0.2), linear(1.5, 0.3), phase, None).unwrap();
        let scene = slab_scene(0.0, vec![sun], medium, 0.6);
        let settings = settings(8, 64, 4).polarized(true).max_depth(Some(1));
        let (film, stats) = render(&scene, &settings).unwrap();
        assert_eq!(stats.nonfinite, 0);
        let [s0, s1, s2, s3] = mean_stokes(&film);
        assert!(s0 > 0.0);
        assert!(
            (s1 / s0 - dolp).abs() < 2e-3,
            "{phase:?}: S1/S0 {} but {dolp}",
            s1 / s0
        );
        assert!(
            s2.abs() < 1e-3 * s0 && s3.abs() < 1e-3 * s0,
            "{s2} {s3} of {s0}"
        );
    }
}

/// Media keep the scene's clock (`--at`): an emitter that shone from 0 to 1 s, seen
/// through an absorbing slab, is there at 0.5 s (as in the steady state) and gone at 2 s.
#[test]
fn media_render_instants_of_the_clock() {
    use prism_scene::world::{Schedule, Timeline};
    let medium = || {
        Medium::new(
            SceneSpectrum::Constant(2.0),
            SceneSpectrum::Constant(0.0),
            Phase::henyey_greenstein(0.0).unwrap(),
            None,
        )
        .unwrap()
    };
    let mut scene = emitter_behind_slab(1.0, medium(), 0.3);
    let schedule = std::sync::Arc::new(Schedule::new(vec![(0.0, 1.0)]).unwrap());
    scene
        .set_timeline(Timeline::new(
            2,
            vec![(0, schedule.clone()), (1, schedule)],
            vec![],
        ))
        .unwrap();
    let steady = constant_xyz((-2.0f64 * 0.3).exp());
    let (film, _) = render(&scene, &settings(8, 32, 4)).unwrap();
    assert_image_mean(&film, steady, "steady");
    let (film, _) = render(&scene, &settings(8, 32, 4).at(Some(0.5))).unwrap();
    assert_image_mean(&film, steady, "at 0.5 s");
    let (film, _) = render(&scene, &settings(8, 32, 4).at(Some(2.0))).unwrap();
    let dark = (0..8).all(|y| (0..8).all(|x| film.xyz(x, y).to_array() == [0.0; 3]));
    assert!(dark, "the emitter shows at 2 s");
}

/// A camera inside a closed volume (an absorbing sphere around it, under a uniform
/// environment of 1) sees through its medium: exp(-sigma_a R) in every direction. The
/// render finds the volumes around the camera before it starts.
#[test]
fn a_camera_inside_a_medium_sees_through_it() {
    let radius = 3.0f32;
    let sphere: Vec<[Vec3; 3]> = icosphere(4)
        .into_iter()
        .map(|t| t.map(|v| v * radius))
        .collect();
    let ids = vec![0; sphere.len()];
    let mut scene = Scene::new(SceneParts {
        attributes: Default::default(),
        triangle_material: ids,
        triangles: sphere,
        materials: vec![Material::Interface],
        emission: vec![],
        lights: vec![Light::Environment {
            radiance: SceneSpectrum::Constant(1.0),
        }],
        camera: prism_scene::camera::Camera::look_at(
            Vec3::ZERO,
            Vec3::new(0.3, 0.2, -1.0),
            Vec3::Y,
            1.0,
        ),
        quality: prism_scene::geometry::BvhQuality::Medium,
    })
    .unwrap();
    let sigma = 1.0 / 3.0;
    let medium = Medium::new(
        SceneSpectrum::Constant(sigma),
        SceneSpectrum::Constant(0.0),
        Phase::henyey_greenstein(0.0).unwrap(),
        None,
    )
    .unwrap();
    scene
        .set_media(Media::new(vec![medium], vec![Some(0)], None).unwrap())
        .unwrap();
    let (film, stats) = render(&scene, &settings(8, 64, 4)).unwrap();
    assert_eq!(stats.nonfinite, 0);
    // Within noise (every pixel has the same expectation; the icosphere's faces sit
    // within 0.1% of the sphere).
    let expected = (-sigma * f64::from(radius)).exp();
    assert_image_mean(&film, constant_xyz(expected), "camera inside");
}

/// Mitsuba's `thindielectric` transmits as a null event that its `volpath` leaves out of
/// `max_depth` (src/bsdfs/thindielectric.cpp, src/integrators/volpath.cpp): where crossing
/// sets the medium (Mitsuba's scenes), a path of no bounce sees an emitter through both
/// walls of a thin-sheet box holding a medium, the sheet (index 1) letting all through.
#[test]
fn thin_sheet_crossings_count_no_bounce_where_crossing_sets_the_medium() {
    let d = 0.5f32;
    let sigma_a = 0.4;
    let medium = Medium::new(
        SceneSpectrum::Constant(sigma_a),
        SceneSpectrum::Constant(0.0),
        Phase::henyey_greenstein(0.0).unwrap(),
        None,
    )
    .unwrap();
    let mut triangles = square_z0(2.0);
    let mut triangle_material = vec![0, 0];
    let box_ = slab(3.0, 0.2, 0.2 + d);
    triangle_material.extend(vec![1; box_.len()]);
    triangles.extend(box_);
    let lights = (0..2)
        .map(|t| Light::Triangle {
            triangle: t,
            emission: 0,
            two_sided: false,
        })
        .collect();
    let mut scene = Scene::new(SceneParts {
        attributes: Default::default(),
        triangles,
        triangle_material,
        materials: vec![
            Material::Diffuse {
                reflectance: SceneSpectrum::Constant(0.0),
            },
            Material::ThinDielectric {
                ior: SceneSpectrum::Constant(1.0),
            },
        ],
        emission: vec![SceneSpectrum::Constant(2.0)],
        lights,
        camera: ortho_camera(Vec3::new(0.0, 0.0, 1.0), 0.5),
        quality: prism_scene::geometry::BvhQuality::Medium,
    })
    .unwrap();
    let sides = prism_scene::medium::Sides {
        inside: Some(0),
        outside: None,
    };
    scene
        .set_media(Media::with_sides(vec![medium], vec![None, Some(sides)], None).unwrap())
        .unwrap();
    let (film, stats) = render(&scene, &settings(8, 64, 4).max_depth(Some(0))).unwrap();
    assert_eq!(stats.nonfinite, 0);
    let expected = constant_xyz(2.0 * (-sigma_a * f64::from(d)).exp());
    assert_image_mean(&film, expected, "a box of thin sheets at no bounce");
}
