//! Monte Carlo over wavelength the way a spectral renderer does it: packages of four hero
//! wavelengths drawn from Owen-scrambled Sobol points estimate the integral of a spectrum
//! times a colour-matching-like weight, and converge to the exact value; then a tabulated
//! distribution picks lights in proportion to their power.
//!
//! `cargo run -p prism-sampling --example hero_wavelengths`

use prism_sampling::distribution::AliasTable;
use prism_sampling::stream::{SampleStream, SobolStream};
use prism_sampling::wavelength::{
    PackageScheme, WavelengthDistribution, WavelengthPackage, WavelengthRange,
};

/// What is integrated: a green-peaked bump (a stand-in for radiance times y-bar).
fn integrand(lambda: f64) -> f64 {
    (-((lambda - 555.0) / 40.0).powi(2)).exp()
}

fn main() -> Result<(), prism_sampling::SamplingError> {
    let range = WavelengthRange::VISIBLE;
    let exact: f64 = (0..100_000)
        .map(|i| {
            let l = f64::from(range.min()) + f64::from(range.width()) * (i as f64 + 0.5) / 1e5;
            integrand(l) * f64::from(range.width()) / 1e5
        })
        .sum();

    let density = WavelengthDistribution::visible(range);
    println!(
        "integral over {}-{} nm: {exact:.4}",
        range.min(),
        range.max()
    );
    println!("  samples  estimate  relative error");
    for count in [4u64, 16, 64, 256, 1024] {
        let mut sum = 0.0;
        for mut stream in SobolStream::pixel_samples(1, 0).take(count as usize) {
            let package = WavelengthPackage::<4>::sample(
                &density,
                f64::from(stream.next_1d()),
                PackageScheme::HeroRotation,
            );
            // The package's densities make (1/4) sum f / pdf the balance-heuristic estimate.
            sum += package
                .lambda
                .iter()
                .zip(package.pdf)
                .map(|(&l, pdf)| integrand(f64::from(l)) / f64::from(pdf))
                .sum::<f64>()
                / 4.0;
        }
        let estimate = sum / count as f64;
        println!(
            "  {count:7}  {estimate:.4}    {:.2e}",
            (estimate / exact - 1.0).abs()
        );
    }

    let lights = AliasTable::new(&[100.0, 25.0, 5.0, 0.0])?;
    let mut picks = [0u32; 4];
    for mut stream in SobolStream::pixel_samples(2, 0).take(1300) {
        picks[lights.sample(f64::from(stream.next_1d())).0] += 1;
    }
    println!("lights of power 100 : 25 : 5 : 0 picked {picks:?} times of 1300");
    Ok(())
}
