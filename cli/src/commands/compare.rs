//! `prism compare`: error measures of an image against a reference, for scripts and CI.

use std::path::{Path, PathBuf};

use clap::Args;
use prism_integrator::{
    ChannelImage, MITSUBA_SIGNIFICANCE, ZTest, compare_images, decode_exr, z_test,
};

#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  prism compare render.exr reference.exr\n  prism compare render.exr reference.exr --json --max-relmse 1e-3   # exits 1 above the threshold\n  prism compare render.exr mean.exr --variance var.exr --spp 868     # Mitsuba's render test\n\nrelmse is the mean of (a - b)^2 / (b^2 + 0.01) over pixels and channels; psnr uses the\nreference's largest value as the peak. Measures that are undefined (the psnr of equal\nimages, the mean ratio to a black channel) print as -, and as null with --json.\n\nWith --variance (the reference's per-sample variance) and --spp (the image's samples per\npixel), the image is also z-tested per pixel as Mitsuba 3's render suite tests its\nrenders: in XYZ, Sidak-corrected at 0.01 over the pixels, passing when 99.75% of the\npixels' channels pass; the command exits non-zero when it does not."
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
    /// The reference's per-sample variance (.exr): z-test the image against the reference.
    #[arg(long, requires = "spp")]
    pub variance: Option<PathBuf>,
    /// The image's samples per pixel, for the z-test.
    #[arg(long, requires = "variance")]
    pub spp: Option<u64>,
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
    let z = match (&args.variance, args.spp) {
        (Some(path), Some(spp)) => Some(
            z_test(&image, &reference, &load(path)?, spp, MITSUBA_SIGNIFICANCE)
                .map_err(|e| e.to_string())?,
        ),
        _ => None,
    };
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
            "ztest": z.as_ref().map(|z| serde_json::json!({
                "accepted": z.accepted,
                "pixels": z.pixels,
                "passed": z.passed,
                "alpha": z.alpha,
                "min_p": z.min_p.0,
                "min_p_pixel": [z.min_p.1, z.min_p.2],
                "min_p_channel": (["X", "Y", "Z"][z.min_p.3]),
                "mean_ratio_xyz": z.mean_ratio,
            })),
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
        if let Some(z) = &z {
            print_z_test(z);
        }
    }
    if let Some(z) = &z
        && !z.accepted
    {
        return Err(format!(
            "z-test rejected: {} of {} pixel channels pass (99.75% needed), smallest p {:.3e} at ({}, {}) {}",
            z.passed,
            3 * z.pixels,
            z.min_p.0,
            z.min_p.1,
            z.min_p.2,
            ["X", "Y", "Z"][z.min_p.3]
        ));
    }
    match args.max_relmse {
        Some(t) if c.relmse > t => Err(format!(
            "relative MSE {:.6e} exceeds --max-relmse {t:e}",
            c.relmse
        )),
        _ => Ok(()),
    }
}

fn print_z_test(z: &ZTest) {
    outln!(
        "z-test          {} ({} of {} pixel channels pass, alpha {:.3e})",
        if z.accepted { "accepted" } else { "rejected" },
        z.passed,
        3 * z.pixels,
        z.alpha
    );
    outln!(
        "smallest p      {:.3e} at pixel ({}, {}) {}",
        z.min_p.0,
        z.min_p.1,
        z.min_p.2,
        ["X", "Y", "Z"][z.min_p.3]
    );
    let ratios: Vec<String> = z
        .mean_ratio
        .iter()
        .map(|r| r.map_or("-".to_string(), |r| format!("{r:.6}")))
        .collect();
    outln!("mean ratio XYZ  {}", ratios.join(", "));
}
