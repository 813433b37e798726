//! An RGB colour to a spectrum and back, by an exact fit and by a lookup in the table
//! that ships with the crate, with the colour error of each in CIEDE2000.
//!
//! `cargo run -p prism-upsample --example rgb_round_trip [-- R G B]` (linear sRGB in [0, 1];
//! default 0.8 0.3 0.1).

use prism_spectrum::Spectrum;
use prism_spectrum::color::RgbSpaceId;
use prism_spectrum::colorimetry::{Lab, Observer, ciede2000, reflectance_xyz};
use prism_upsample::{CoefficientTable, FitContext, RgbKind, RgbSpectrum};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse::<f64>())
        .collect::<Result<_, _>>()?;
    let rgb = match args[..] {
        [r, g, b] => [r, g, b],
        [] => [0.8, 0.3, 0.1],
        _ => return Err("give three numbers, R G B, or none".into()),
    };

    let srgb = RgbSpaceId::Srgb;
    let illuminant = srgb.illuminant();
    let context = FitContext::new(srgb.space(), &illuminant)?;
    let table = CoefficientTable::shipped(srgb).ok_or("built without the srgb-table feature")?;

    // Back to RGB in the context's space: the primaries with the illuminant's own white.
    let back = |spectrum: &dyn Spectrum| -> Result<[f64; 3], prism_spectrum::SpectrumError> {
        let xyz = reflectance_xyz(spectrum, &illuminant, Observer::Cie1931)?;
        Ok(context.space().xyz_to_rgb(xyz))
    };
    let error = |other: [f64; 3]| {
        let lab = |c| Lab::from_xyz(context.rgb_xyz(c), context.white());
        ciede2000(lab(rgb), lab(other))
    };

    let fitted = RgbSpectrum::fit(&context, rgb, RgbKind::Albedo, None)?;
    let looked_up = table.lookup(rgb);
    println!("RGB {rgb:?}");
    println!("   nm   fitted  table");
    for nm in (400..=700).step_by(50) {
        let l = f64::from(nm);
        println!(
            "  {nm}  {:.4}  {:.4}",
            fitted.evaluate(l),
            looked_up.evaluate(l)
        );
    }
    let (f, t) = (back(&fitted)?, back(&looked_up)?);
    println!("fit   -> {f:.5?} (dE2000 {:.5})", error(f));
    println!("table -> {t:.5?} (dE2000 {:.5})", error(t));
    Ok(())
}
