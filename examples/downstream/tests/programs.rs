//! The programs a new user writes first, one per library crate, against the published
//! API only (this crate is outside the libraries, so nothing private is reachable).

use std::sync::Arc;

#[test]
fn a_reflectance_csv_becomes_xyz_lab_srgb_and_a_cct() -> Result<(), Box<dyn std::error::Error>> {
    use prism_spectrum::color::RgbSpaceId;
    use prism_spectrum::colorimetry::{
        Lab, Observer, WhitePoint, cct_ohno2013, emission_xyz, reflectance_xyz,
    };
    use prism_spectrum::illuminant::StandardIlluminant;
    use prism_spectrum::spectra::{Extrapolation, PiecewiseLinear};

    // A flat 50% grey, as a measurement file gives it.
    let csv = "wavelength_nm,reflectance\n380,0.5\n550,0.5\n780,0.5\n";
    let grey = PiecewiseLinear::from_csv_str(csv, Extrapolation::Clamp)?;
    let d65 = StandardIlluminant::D65.spectrum();
    let xyz = reflectance_xyz(&grey, &d65, Observer::Cie1931)?;
    assert!((xyz.y - 0.5).abs() < 1e-9);
    // Lab against the spectrum's own white is exactly neutral.
    let white = WhitePoint::from_xyz(emission_xyz(&d65, Observer::Cie1931))?;
    let lab = Lab::from_xyz(xyz, white);
    assert!((lab.l - 76.0693).abs() < 1e-3 && lab.a.abs() < 1e-9 && lab.b.abs() < 1e-9);
    let srgb = RgbSpaceId::Srgb.space();
    let encoded = srgb.xyz_to_rgb(xyz).map(|c| srgb.transfer().encode(c));
    assert!(
        encoded.iter().all(|c| (c - 0.7354).abs() < 2e-3),
        "{encoded:?}"
    );
    let cct = cct_ohno2013(emission_xyz(&d65, Observer::Cie1931).uv()?)?;
    assert!((cct.kelvin - 6504.0).abs() < 2.0);
    Ok(())
}

#[test]
fn an_rgb_colour_is_upsampled_looked_up_and_round_tripped() -> Result<(), Box<dyn std::error::Error>>
{
    use prism_spectrum::color::RgbSpaceId;
    use prism_spectrum::colorimetry::{Observer, reflectance_xyz};
    use prism_upsample::{CoefficientTable, FitContext, RgbKind, RgbSpectrum};

    let srgb = RgbSpaceId::Srgb;
    let illuminant = srgb.illuminant();
    let context = FitContext::new(srgb.space(), &illuminant)?;
    let rgb = [0.8, 0.3, 0.1];
    let fitted = RgbSpectrum::fit(&context, rgb, RgbKind::Albedo, None)?;
    let back =
        context
            .space()
            .xyz_to_rgb(reflectance_xyz(&fitted, &illuminant, Observer::Cie1931)?);
    assert!(
        back.iter().zip(rgb).all(|(b, a)| (b - a).abs() < 1e-5),
        "{back:?}"
    );
    // The table that ships: no fitting, close to the fit.
    let table = CoefficientTable::shipped(srgb).ok_or("no shipped table")?;
    let looked_up = table.lookup(rgb);
    let back =
        context
            .space()
            .xyz_to_rgb(reflectance_xyz(&looked_up, &illuminant, Observer::Cie1931)?);
    assert!(
        back.iter().zip(rgb).all(|(b, a)| (b - a).abs() < 2e-3),
        "{back:?}"
    );
    Ok(())
}

#[test]
fn hero_wavelengths_and_sobol_points_are_drawn() -> Result<(), prism_sampling::SamplingError> {
    use prism_sampling::distribution::AliasTable;
    use prism_sampling::stream::{SampleStream, SobolStream};
    use prism_sampling::wavelength::{
        PackageScheme, WavelengthDistribution, WavelengthPackage, WavelengthRange,
    };

    let visible = WavelengthDistribution::visible(WavelengthRange::VISIBLE);
    let mut lanes = Vec::new();
    for mut stream in SobolStream::pixel_samples(3, 17).take(64) {
        let package = WavelengthPackage::<4>::sample(
            &visible,
            f64::from(stream.next_1d()),
            PackageScheme::HeroRotation,
        );
        assert!(package.pdf.iter().all(|p| p.is_finite() && *p > 0.0));
        lanes.extend(package.lambda);
        let u = stream.next_2d();
        assert!((0.0..1.0).contains(&u.x) && (0.0..1.0).contains(&u.y));
    }
    assert!(lanes.iter().all(|l| (360.0..=830.0).contains(l)));
    let lights = AliasTable::new(&[3.0, 1.0])?;
    assert!((lights.pmf(0) - 0.75).abs() < 1e-12);
    Ok(())
}

#[test]
fn a_scene_built_in_code_renders_to_an_image() -> Result<(), Box<dyn std::error::Error>> {
    use prism_integrator::glam::Vec3;
    use prism_integrator::prism_scene::camera::Camera;
    use prism_integrator::prism_scene::world::{Material, SceneBuilder, SceneSpectrum};
    use prism_integrator::{DisplaySettings, RenderSettings, encode_exr, encode_png, render};
    use prism_spectrum::color::RgbSpaceId;

    let v = Vec3::new;
    let camera = Camera::look_at(v(0.0, 1.0, 3.0), v(0.0, 0.3, 0.0), Vec3::Y, 0.8);
    let mut builder = SceneBuilder::new(camera);
    let grey = builder.material(Material::Diffuse {
        reflectance: SceneSpectrum::Constant(0.5),
    });
    let (a, b, c, d) = (
        v(-2.0, 0.0, 2.0),
        v(2.0, 0.0, 2.0),
        v(2.0, 0.0, -2.0),
        v(-2.0, 0.0, -2.0),
    );
    builder.triangles(&[[a, b, c], [a, c, d]], grey);
    let lamp = |x: f32, z: f32| v(x, 2.0, z);
    builder.emitter(
        &[
            [lamp(-0.5, -0.5), lamp(0.5, -0.5), lamp(0.5, 0.5)],
            [lamp(-0.5, -0.5), lamp(0.5, 0.5), lamp(-0.5, 0.5)],
        ],
        SceneSpectrum::Constant(0.5),
        false,
    );
    let scene = builder.build()?;
    let settings = RenderSettings::default().width(32).height(24).samples(0..4);
    let (film, stats) = render(&scene, &settings)?;
    assert_eq!(stats.paths, 32 * 24 * 4);
    assert!(film.xyz(16, 20).y > 0.0);
    let png = encode_png(&film, RgbSpaceId::Srgb.space(), DisplaySettings::default());
    assert_eq!(&png[1..4], b"PNG");
    let exr = encode_exr(&film, RgbSpaceId::Srgb.space(), &Default::default())?;
    assert_eq!(&exr[..4], &[0x76, 0x2f, 0x31, 0x01]);
    Ok(())
}

#[test]
fn fog_fills_a_scene_built_in_code() -> Result<(), Box<dyn std::error::Error>> {
    use prism_integrator::glam::Vec3;
    use prism_integrator::prism_scene::camera::Camera;
    use prism_integrator::prism_scene::medium::{Media, Medium, Phase};
    use prism_integrator::prism_scene::world::{Material, SceneBuilder, SceneSpectrum};
    use prism_integrator::{RenderSettings, render};

    let v = Vec3::new;
    let build = || -> Result<_, Box<dyn std::error::Error>> {
        let mut builder = SceneBuilder::new(Camera::look_at(
            v(0.0, 1.0, 3.0),
            v(0.0, 0.3, 0.0),
            Vec3::Y,
            0.8,
        ));
        let grey = builder.material(Material::Diffuse {
            reflectance: SceneSpectrum::Constant(0.5),
        });
        let (a, b, c, d) = (
            v(-2.0, 0.0, 2.0),
            v(2.0, 0.0, 2.0),
            v(2.0, 0.0, -2.0),
            v(-2.0, 0.0, -2.0),
        );
        builder.triangles(&[[a, b, c], [a, c, d]], grey);
        let lamp = |x: f32, z: f32| v(x, 2.0, z);
        builder.emitter(
            &[
                [lamp(-0.5, -0.5), lamp(0.5, -0.5), lamp(0.5, 0.5)],
                [lamp(-0.5, -0.5), lamp(0.5, 0.5), lamp(-0.5, 0.5)],
            ],
            SceneSpectrum::Constant(0.5),
            false,
        );
        Ok(builder.build()?)
    };
    let settings = RenderSettings::default()
        .width(32)
        .height(24)
        .samples(0..16);
    let (clear, _) = render(&build()?, &settings)?;
    // Grey fog everywhere: a little absorption, more scattering, forward.
    let mut foggy = build()?;
    let fog = Medium::new(
        SceneSpectrum::Constant(0.1),
        SceneSpectrum::Constant(0.3),
        Phase::henyey_greenstein(0.6)?,
        None,
    )?;
    foggy.set_media(Media::new(vec![fog], vec![], Some(0))?)?;
    let (film, stats) = render(&foggy, &settings)?;
    assert_eq!(stats.nonfinite, 0);
    // The floor under the lamp is dimmer through fog, and the air glows where it was black.
    assert!(film.xyz(16, 20).y < clear.xyz(16, 20).y);
    assert!(film.xyz(16, 2).y > clear.xyz(16, 2).y);
    Ok(())
}

#[test]
fn a_gltf_is_loaded_with_a_table_of_the_callers_and_errors_carry_their_cause() {
    use prism_scene::LoadError;
    use prism_scene::load::{LoadOptions, load_scene};
    use prism_scene::world::{Scene, SceneOptions};
    use prism_spectrum::color::RgbSpaceId;
    use prism_upsample::CoefficientTable;

    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let bytes = std::fs::read(dir.join("cornell-box.gltf")).unwrap();
    let resolve = |uri: &str| std::fs::read(dir.join(uri));
    let table: Arc<CoefficientTable> = CoefficientTable::shipped(RgbSpaceId::Srgb).unwrap();
    let options = LoadOptions::default().table(Some(table));
    let loaded = load_scene(&bytes, &resolve, &options).unwrap();
    let scene = Scene::from_loaded(loaded, &SceneOptions::default()).unwrap();
    assert!(scene.radius() > 0.0);

    let nowhere = |_: &str| Err(std::io::Error::from(std::io::ErrorKind::PermissionDenied));
    let error = load_scene(&bytes, &nowhere, &LoadOptions::default()).unwrap_err();
    match &error {
        LoadError::Resource { uri, source, .. } => {
            assert_eq!(uri, "cornell-box.bin");
            assert_eq!(source.kind(), std::io::ErrorKind::PermissionDenied);
        }
        other => panic!("expected a resource error, got {other}"),
    }
    assert!(std::error::Error::source(&error).is_some());
    let not_gltf = load_scene(b"{", &resolve, &LoadOptions::default()).unwrap_err();
    assert!(matches!(not_gltf, LoadError::Invalid { .. }));
    assert!(std::error::Error::source(&not_gltf).is_some());
}
