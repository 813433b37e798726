//! `prism compare`: error measures of an image against a reference, for scripts and CI.

use std::path::{Path, PathBuf};

use clap::Args;
use prism_integrator::{ChannelImage, compare_images, decode_exr};

#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  prism compare render.exr reference.exr\n  prism compare render.exr reference.exr --json --max-relmse 1e-3   # exits 1 above the threshold\n\nrelmse is the mean of (a - b)^2 / (b^2 + 0.01) over pixels and channels; psnr uses the\nreference's largest value as the peak. Measures that are undefined (the psnr of equal\nimages, the mean ratio to a black channel) print as -, and as null with --json."
)]
pub struct CompareArgs {
    /// The image to judge (.exr).
    pub image: PathBuf,
    /// The reference (.exr) with the same size and channels.
    pub reference: PathBuf,
    /// Print one JSON object instead of lines.
    #[arg(long)]
    pub json: bool,
    /// Exit non-zero when the relative MSE exceeds this.
    #[arg(long)]
    pub max_relmse: Option<f64>,
}

fn load(path: &Path) -> Result<ChannelImage, String> {
    let bytes = crate::output::read_file(path)?;
    let image = decode_exr(&bytes).map_err(|e| format!("'{}': {e}", path.display()))?;
    if image.channels.iter().any(|(name, _)| name.ends_with(".hi")) {
        return Err(format!(
            "'{}' is an accumulation file: turn it into an image with prism merge first",
            path.display()
        ));
    }
    Ok(image)
}

pub fn run(args: &CompareArgs) -> Result<(), String> {
    if let Some(t) = args.max_relmse
        && !(t.is_finite() && t >= 0.0)
    {
        return Err(format!(
            "--max-relmse {} must be finite and >= 0",
            prism_spectrum::Readable(t)
        ));
    }
    let (image, reference) = (load(&args.image)?, load(&args.reference)?);
    let c = compare_images(&image, &reference).map_err(|e| e.to_string())?;
    if args.json {
        // Undefined measures (the PSNR of equal images, the ratio to a black channel) are null.
        let json = serde_json::json!({
            "channels": c.channels,
            "rmse": c.rmse,
            "relmse": c.relmse,
            "mae": c.mae,
            "psnr": c.psnr,
            "max_difference": c.max_difference,
            "mean_ratio": c.mean_ratio,
            "channel_relmse": c.channel_relmse,
        });
        outln!("{json}");
    } else {
        outln!("channels        {}", c.channels.join(", "));
        outln!("rmse            {:.6e}", c.rmse);
        outln!("relmse          {:.6e}", c.relmse);
        outln!("mae             {:.6e}", c.mae);
        match c.psnr {
            Some(p) => outln!("psnr            {p:.3} dB"),
            None => outln!("psnr            - (equal images or black reference)"),
        }
        outln!("max difference  {:.6e}", c.max_difference);
        for ((name, ratio), rel) in c.channels.iter().zip(&c.mean_ratio).zip(&c.channel_relmse) {
            let ratio = ratio.map_or("-".to_string(), |r| format!("{r:.6}"));
            outln!("{name:<15} mean ratio {ratio}, relmse {rel:.6e}");
        }
    }
    match args.max_relmse {
        Some(t) if c.relmse > t => Err(format!(
            "relative MSE {:.6e} exceeds --max-relmse {t:e}",
            c.relmse
        )),
        _ => Ok(()),
    }
}
