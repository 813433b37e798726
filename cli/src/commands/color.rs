//! `prism color`: the colorimetry of one spectrum.

use clap::Args;
use prism_spectrum::color::RgbSpaceId;
use prism_spectrum::colorimetry::{Observer, cct_ohno2013, emission_xyz};
use serde_json::json;

use crate::spectrum_spec;

/// Duv beyond which CIE 015 considers a CCT meaningless.
const MAX_MEANINGFUL_DUV: f64 = 0.05;

#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  prism color blackbody:6500\n  prism color illuminant:D65 --json\n  \
prism color gaussian:550:40 --space rec2020\n  prism color measured.csv --observer cie1964"
)]
pub struct ColorArgs {
    /// The spectrum: blackbody:T, illuminant:NAME (A, D50, D55, D65, D75, E, F1-F12),
    /// daylight:CCT, gaussian:CENTER_NM:FWHM_NM, constant:V, or a CSV file of nm,value rows.
    pub spec: String,
    /// Colour matching functions: cie1931 (2 degree) or cie1964 (10 degree).
    #[arg(long, default_value = "cie1931")]
    pub observer: String,
    /// RGB colour space for the linear RGB output.
    #[arg(long, default_value = "srgb")]
    pub space: String,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &ColorArgs) -> Result<(), String> {
    let observer = Observer::from_name(&args.observer).map_err(|e| e.to_string())?;
    let space = RgbSpaceId::from_name(&args.space)
        .map_err(|e| e.to_string())?
        .space();
    let spectrum = spectrum_spec::parse(&args.spec)?;

    let xyz = emission_xyz(&spectrum, observer)
        .normalized_to_unit_y()
        .map_err(|e| format!("'{}': {e}", args.spec))?;
    let xy = xyz.chromaticity().map_err(|e| e.to_string())?;
    let rgb = space.xyz_to_rgb(xyz);
    // CCT is defined in the CIE 1960 UCS of the 1931 observer whatever the display observer.
    let cct = emission_xyz(&spectrum, Observer::Cie1931)
        .uv()
        .ok()
        .and_then(|uv| cct_ohno2013(uv).ok())
        .filter(|c| c.duv.abs() <= MAX_MEANINGFUL_DUV);

    if args.json {
        let value = json!({
            "spec": args.spec,
            "observer": observer.name(),
            "space": space.name(),
            "XYZ": xyz.to_array(),
            "xy": [xy.x, xy.y],
            "rgb": rgb,
            "cct_kelvin": cct.map(|c| c.kelvin),
            "duv": cct.map(|c| c.duv),
        });
        outln!("{value}");
    } else {
        outln!("spectrum  {}", args.spec);
        outln!("observer  {}", observer.name());
        outln!(
            "XYZ       {:.6} {:.6} {:.6}  (normalized to Y = 1)",
            xyz.x,
            xyz.y,
            xyz.z
        );
        outln!("xy        {:.6} {:.6}", xy.x, xy.y);
        outln!(
            "rgb       {:.6} {:.6} {:.6}  (linear {})",
            rgb[0],
            rgb[1],
            rgb[2],
            space.name()
        );
        match cct {
            Some(c) => outln!("CCT       {:.1} K  (Duv {:+.5})", c.kelvin, c.duv),
            None => outln!(
                "CCT       undefined (too far from the Planckian locus or outside 1000-100000 K)"
            ),
        }
    }
    Ok(())
}
