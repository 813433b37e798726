//! A measured spectrum from a CSV file to colour: XYZ, CIELAB and sRGB as a reflectance
//! under D65, and its correlated colour temperature as a light.
//!
//! `cargo run -p prism-spectrum --example csv_to_colour [-- FILE.csv]`
//! (two columns, wavelength in nm and value; without a file, a built-in orange paint).

use prism_spectrum::color::RgbSpaceId;
use prism_spectrum::colorimetry::{Lab, Observer, cct_ohno2013, emission_xyz, reflectance_xyz};
use prism_spectrum::illuminant::StandardIlluminant;
use prism_spectrum::spectra::{Extrapolation, PiecewiseLinear};

const ORANGE_PAINT: &str = "nm,reflectance
400,0.05\n450,0.06\n500,0.08\n550,0.20\n580,0.45\n600,0.62\n650,0.70\n700,0.72\n";

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let text = match std::env::args().nth(1) {
        Some(path) => std::fs::read_to_string(&path).map_err(|e| format!("{path}: {e}"))?,
        None => ORANGE_PAINT.to_string(),
    };
    let spectrum = PiecewiseLinear::from_csv_str(&text, Extrapolation::Clamp)?;

    let d65 = StandardIlluminant::D65.spectrum();
    let xyz = reflectance_xyz(&spectrum, &d65, Observer::Cie1931)?;
    let srgb = RgbSpaceId::Srgb.space();
    let lab = Lab::from_xyz(xyz, srgb.white());
    let linear = srgb.xyz_to_rgb(xyz);
    let encoded = linear.map(|c| (srgb.transfer().encode(c.clamp(0.0, 1.0)) * 255.0).round());

    println!("as a reflectance under D65:");
    println!("  XYZ    {:.4} {:.4} {:.4}", xyz.x, xyz.y, xyz.z);
    println!("  L*a*b* {:.2} {:.2} {:.2}", lab.l, lab.a, lab.b);
    println!(
        "  sRGB   {} {} {} (8 bit)",
        encoded[0], encoded[1], encoded[2]
    );

    let as_light = emission_xyz(&spectrum, Observer::Cie1931);
    let cct = cct_ohno2013(as_light.uv()?)?;
    println!("as a light: {:.0} K, Duv {:.4}", cct.kelvin, cct.duv);
    Ok(())
}
