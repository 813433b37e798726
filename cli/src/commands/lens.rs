//! `prism lens`: a lens prescription's first-order properties per wavelength, from rays
//! traced close to the axis through the same code that renders through it.

use std::path::PathBuf;

use clap::Args;
use prism_scene::camera::system::{Paraxial, parse_prescription};
use prism_spectrum::optics::{FRAUNHOFER_C_NM, FRAUNHOFER_D_NM, FRAUNHOFER_F_NM};

#[derive(Debug, Args)]
#[command(after_help = "Examples:\n  prism lens scenes/lenses/singlet.dat\n  \
    prism lens scenes/lenses/achromat.dat --wavelengths 450,550,650 --json")]
pub struct LensArgs {
    /// A lens prescription: pbrt-v4's lens file format (radius, thickness, index, aperture
    /// diameter per interface, mm; radius 0 is the stop), with an optional fifth column
    /// naming each element's glass (`bk7`, `sf11`, ... or ND:VD).
    pub file: PathBuf,
    /// Wavelengths in nm, comma-separated (default: the F, d and C lines).
    #[arg(long, value_delimiter = ',', value_name = "NM,NM,...")]
    pub wavelengths: Option<Vec<f64>>,
    /// Print one JSON object: `wavelengths` (nm) and, per wavelength, `efl_mm`, `bfd_mm`,
    /// `entrance_pupil_mm` and `f_number`, with `longitudinal_chromatic_aberration_mm`.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &LensArgs) -> Result<(), String> {
    let text = crate::output::read_text(&args.file)?;
    let lens = parse_prescription(&text).map_err(|e| format!("'{}': {e}", args.file.display()))?;
    let wavelengths =
        args.wavelengths
            .clone()
            .unwrap_or(vec![FRAUNHOFER_F_NM, FRAUNHOFER_D_NM, FRAUNHOFER_C_NM]);
    if let Some(bad) = wavelengths
        .iter()
        .find(|w| !(w.is_finite() && (100.0..=5000.0).contains(*w)))
    {
        return Err(format!("--wavelengths: {bad} nm is not in 100-5000 nm"));
    }
    let rows: Vec<Paraxial> = wavelengths
        .iter()
        .map(|&w| lens.paraxial(w))
        .collect::<Result<_, _>>()
        .map_err(|e| format!("'{}': {e}", args.file.display()))?;
    // Longitudinal chromatic aberration: the spread of the paraxial focus over the
    // wavelengths asked for (the F-C shift for the default lines).
    let focus: Vec<f64> = rows.iter().map(|p| p.bfd_mm).collect();
    let spread = focus.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
        - focus.iter().cloned().fold(f64::INFINITY, f64::min);
    if args.json {
        let json = serde_json::json!({
            "file": args.file.display().to_string(),
            "wavelengths": wavelengths,
            "efl_mm": rows.iter().map(|p| p.efl_mm).collect::<Vec<_>>(),
            "bfd_mm": focus,
            "entrance_pupil_mm": rows.iter().map(|p| p.entrance_pupil_mm).collect::<Vec<_>>(),
            "f_number": rows.iter().map(|p| p.f_number).collect::<Vec<_>>(),
            "longitudinal_chromatic_aberration_mm": spread,
            "dispersive": lens.dispersive(),
        });
        outln!("{json}");
        return Ok(());
    }
    outln!(
        "lens           {} ({} interfaces{})",
        args.file.display(),
        lens.interfaces().len(),
        if lens.dispersive() {
            ", dispersive glass"
        } else {
            ""
        }
    );
    outln!("wavelength nm      EFL mm      BFD mm   pupil mm   f-number");
    for p in &rows {
        outln!(
            "{:>13.2} {:>11.4} {:>11.4} {:>10.3} {:>10.3}",
            p.wavelength_nm,
            p.efl_mm,
            p.bfd_mm,
            p.entrance_pupil_mm,
            p.f_number
        );
    }
    outln!("longitudinal chromatic aberration  {spread:.4} mm (spread of the BFD)");
    Ok(())
}
