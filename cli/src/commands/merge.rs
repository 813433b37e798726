//! `prism merge`: accumulation files of disjoint sample ranges into one image.

use std::path::PathBuf;

use clap::Args;
use prism_integrator::{decode_accumulation, encode_accumulation, merge_accumulations};

use super::render::{check_outputs, write_images};
use crate::image_args::ImageArgs;
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
    #[command(flatten)]
    pub image: ImageArgs,
}

pub fn run(args: &MergeArgs) -> Result<(), String> {
    let (space, display) = args.image.parse()?;
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
    write_images(&merged.film, &args.outputs, space, display, facts, None)
}
