//! prism-spectrum: the functions on the render and colour hot paths.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use prism_spectrum::colorimetry::{Observer, emission_xyz};
use prism_spectrum::illuminant::StandardIlluminant;
use prism_spectrum::optics::named_glass;
use prism_spectrum::spectra::{Blackbody, planck_radiance};
use prism_spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};

fn spectrum(c: &mut Criterion) {
    let mut lambda = 400.0_f64;
    c.bench_function("planck radiance (f64, one wavelength)", |b| {
        b.iter(|| {
            lambda = if lambda > 800.0 { 400.0 } else { lambda + 0.37 };
            black_box(planck_radiance(black_box(lambda) * 1e-9, 5778.0))
        })
    });
    let bk7 = named_glass("bk7").expect("catalogue");
    c.bench_function("sellmeier BK7 (one wavelength)", |b| {
        b.iter(|| {
            lambda = if lambda > 800.0 { 400.0 } else { lambda + 0.37 };
            black_box(bk7.ior.evaluate(black_box(lambda)))
        })
    });
    let d65 = StandardIlluminant::D65.spectrum();
    c.bench_function("emission XYZ of D65 (471 nm grid)", |b| {
        b.iter(|| black_box(emission_xyz(black_box(&d65), Observer::Cie1931)))
    });
    let body = Blackbody::new(3000.0).expect("valid");
    let wl =
        SampledWavelengths::new([450.0, 550.0, 650.0, 750.0], [1.0 / 470.0; 4]).expect("valid");
    c.bench_function("blackbody sampled at 4 lanes + XYZ", |b| {
        b.iter(|| {
            let s: SampledSpectrum<4> = body.sample(black_box(&wl));
            black_box(s.to_xyz(&wl, Observer::Cie1931))
        })
    });
}

criterion_group!(benches, spectrum);
criterion_main!(benches);
