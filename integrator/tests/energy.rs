//! Energy output: a panel of known spectral radiance seen directly gives its radiance
//! integral and its photon radiance (E = hc / lambda) per pixel and in the EXR.

mod common;

use std::sync::Arc;

use prism_integrator::{
    ExrMetadata, LambdaSampler, RenderSettings, decode_exr, encode_exr, render,
};
use prism_scene::world::SceneSpectrum;
use prism_spectrum::color::RgbSpaceId;
use prism_spectrum::constants::{ELEMENTARY_CHARGE, PLANCK, SPEED_OF_LIGHT};
use prism_spectrum::spectra::Gaussian;

#[test]
fn energy_and_photons_of_a_known_emitter() {
    // A Gaussian band at 550 nm (FWHM 40 nm, peak 2 W m^-2 sr^-1 nm^-1), well inside the
    // range: its radiance integral is peak sigma sqrt(2 pi) and, being symmetric, its
    // photon radiance that times 550 nm / hc.
    let (peak, fwhm, centre) = (2.0, 40.0, 550.0);
    let sigma = fwhm / (2.0 * (2.0 * std::f64::consts::LN_2).sqrt());
    let radiance = peak * sigma * (2.0 * std::f64::consts::PI).sqrt();
    let photons = radiance * centre * 1e-9 / (PLANCK * SPEED_OF_LIGHT);
    let scene = common::emitter_filling_the_view(SceneSpectrum::Scaled(
        Arc::new(SceneSpectrum::Gaussian(
            Gaussian::new(centre, fwhm, 1.0).unwrap(),
        )),
        peak,
    ));
    for (c, sampler) in [(4, LambdaSampler::Visible), (1, LambdaSampler::Uniform)] {
        let settings = RenderSettings::default()
            .width(8)
            .height(8)
            .samples(0..64)
            .wavelengths(c)
            .lambda_sampler(sampler)
            .energy(true);
        let (film, _) = render(&scene, &settings).unwrap();
        let mut mean = [0.0f64; 2];
        for y in 0..8 {
            for x in 0..8 {
                let e = film.energy(x, y).unwrap();
                mean[0] += e[0] / 64.0;
                mean[1] += e[1] / 64.0;
            }
        }
        // 4096 estimates of a smooth band: well within 2%.
        assert!(
            (mean[0] - radiance).abs() < 0.02 * radiance,
            "C={c}: {} vs {radiance}",
            mean[0]
        );
        assert!(
            (mean[1] - photons).abs() < 0.02 * photons,
            "C={c}: {} vs {photons}",
            mean[1]
        );
        let exr = encode_exr(&film, RgbSpaceId::Srgb.space(), &ExrMetadata::default()).unwrap();
        let decoded = decode_exr(&exr).unwrap();
        let channel = |name: &str| {
            let (_, values) = decoded
                .channels
                .iter()
                .find(|(n, _)| n == name)
                .unwrap_or_else(|| panic!("{name} missing"));
            values.iter().map(|&v| f64::from(v)).sum::<f64>() / values.len() as f64
        };
        assert!((channel("energy.radiance") - mean[0]).abs() < 1e-5 * mean[0]);
        assert!(
            (channel("energy.eV") - mean[0] / ELEMENTARY_CHARGE).abs()
                < 1e-5 * mean[0] / ELEMENTARY_CHARGE
        );
        assert!((channel("energy.photons") - mean[1]).abs() < 1e-5 * mean[1]);
    }
}
