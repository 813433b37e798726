//! `prism denoise`: a rendered EXR that has the albedo and normal AOVs, denoised by Intel
//! Open Image Denoise as `prism render --denoise` does it.

use std::path::PathBuf;

use clap::Args;
use prism_integrator::{decode_exr, encode_png_rgb, replace_rgb_exr};

use super::render::check_outputs;
use crate::denoise::Denoiser;
use crate::image_args::ImageArgs;
use crate::output::{read_file, write_atomically};

#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  prism render scene.gltf --spp 16 --aov albedo,normal -o noisy.exr\n  prism denoise noisy.exr -o clean.exr -o clean.png\n\nThe image is denoised in RGB (after the spectral film; spectral bands are kept as they\nare), by OIDN's HDR filter guided by the albedo and normal layers, each denoised first.\nEXR outputs are the input with R, G, B replaced and the noisy ones kept as noisy.R, noisy.G,\nnoisy.B. Needs the OIDN library: pip install pyoidn (or PRISM_OIDN=its path)."
)]
pub struct DenoiseArgs {
    /// A render (.exr) with albedo.R/G/B and normal.X/Y/Z layers (prism render --aov
    /// albedo,normal).
    pub input: PathBuf,
    /// Output file(s), .exr or .png; repeat for several.
    #[arg(short = 'o', long = "output", required = true)]
    pub outputs: Vec<PathBuf>,
    #[command(flatten)]
    pub image: ImageArgs,
}

pub fn run(args: &DenoiseArgs) -> Result<(), String> {
    let (space, display) = args.image.parse()?;
    check_outputs(&args.outputs)?;
    let name = args.input.display().to_string();
    let bytes = read_file(&args.input)?;
    let image = decode_exr(&bytes).map_err(|e| format!("'{name}': {e}"))?;
    let channel = |c: &str| -> Result<&Vec<f32>, String> {
        image
            .channels
            .iter()
            .find(|(n, _)| n == c)
            .map(|(_, v)| v)
            .ok_or_else(|| {
                format!("'{name}' has no {c} channel (render it with --aov albedo,normal)")
            })
    };
    let triple = |names: [&str; 3]| -> Result<Vec<[f32; 3]>, String> {
        let [a, b, c] = [channel(names[0])?, channel(names[1])?, channel(names[2])?];
        Ok((0..a.len()).map(|i| [a[i], b[i], c[i]]).collect())
    };
    let color = triple(["R", "G", "B"])?;
    let albedo = triple(["albedo.R", "albedo.G", "albedo.B"])?;
    let normal = triple(["normal.X", "normal.Y", "normal.Z"])?;
    let denoiser = Denoiser::load()?;
    let (w, h) = (image.width, image.height);
    let denoised = denoiser.denoise(w, h, space.space(), &color, &albedo, &normal)?;
    for out in &args.outputs {
        let encoded = if super::render::has_extension(out, "exr") {
            replace_rgb_exr(&bytes, &denoised).map_err(|e| e.to_string())?
        } else {
            let alpha = channel("A").cloned().unwrap_or_else(|_| vec![1.0; w * h]);
            encode_png_rgb(
                w as u32,
                h as u32,
                &denoised,
                &alpha,
                space.space(),
                display,
            )
        };
        write_atomically(out, &encoded)?;
    }
    Ok(())
}
