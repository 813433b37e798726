//! `prism merge`: accumulation files of disjoint sample ranges into one image.

use std::path::PathBuf;

use clap::Args;
use prism_integrator::{
    DisplaySettings, decode_accumulation, encode_accumulation, merge_accumulations,
};
use prism_spectrum::color::{RgbSpaceId, ToneMap};

use super::render::{check_outputs, write_images};
use crate::output::write_atomically;

#[derive(Debug, Args)]
#[command(
    after_help = "Example (a render split over three machines):\n  prism render scene.gltf --sample-range 0..100 -o part0.exr\n  prism render scene.gltf --sample-range 100..200 -o part1.exr\n  prism render scene.gltf --sample-range 200..256 -o part2.exr\n  prism merge part0.exr part1.exr part2.exr -o image.exr -o image.png\n\nThe merged image equals a single render of 0..256 with the same settings and seed (to\nf64 rounding: the same samples are summed in another grouping)."
)]
pub struct MergeArgs {
    /// Accumulation files written by `prism render --sample-range`.
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// Output image(s), .exr or .png.
    #[arg(short = 'o', long = "output", required = true)]
    pub outputs: Vec<PathBuf>,
    /// Write the merged accumulation file instead of an image (.exr only), to merge further.
    #[arg(long)]
    pub accumulation: bool,
    /// Output colour space of EXR and PNG files.
    #[arg(long, default_value = "srgb")]
    pub space: String,
    /// PNG exposure in stops.
    #[arg(long, default_value_t = 0.0)]
    pub exposure: f64,
    /// PNG tone mapping: neutral (Khronos PBR Neutral), aces, reinhard[:WHITE] or clamp.
    #[arg(long, default_value = "neutral")]
    pub tonemap: String,
    /// PNG outputs carry the alpha channel (for parts rendered with --transparent).
    #[arg(long)]
    pub transparent: bool,
}

pub fn run(args: &MergeArgs) -> Result<(), String> {
    let space = RgbSpaceId::from_name(&args.space).map_err(|e| e.to_string())?;
    check_outputs(&args.outputs)?;
    let parts = args
        .parts
        .iter()
        .map(|path| {
            let bytes = crate::output::read_file(path)?;
            decode_accumulation(&bytes).map_err(|e| format!("'{}': {e}", path.display()))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let merged = merge_accumulations(&parts).map_err(|e| e.to_string())?;
    if args.accumulation {
        let bytes = encode_accumulation(&merged.film, merged.samples.clone(), &merged.settings)
            .map_err(|e| e.to_string())?;
        for out in &args.outputs {
            if out.extension().and_then(|e| e.to_str()) != Some("exr") {
                return Err(format!(
                    "output '{}': accumulation files must be .exr",
                    out.display()
                ));
            }
            write_atomically(out, &bytes)?;
        }
        return Ok(());
    }
    let facts = vec![(
        "samples".to_string(),
        format!("{}..{}", merged.samples.start, merged.samples.end),
    )];
    let display = DisplaySettings::default()
        .exposure(args.exposure)
        .tone_map(ToneMap::from_name(&args.tonemap).map_err(|e| e.to_string())?)
        .alpha(args.transparent);
    write_images(&merged.film, &args.outputs, space, display, facts, None)
}
