//! The flags of commands that write images from files (`prism merge`, `prism denoise`):
//! the colour space and how PNGs show it.

use clap::Args;
use prism_integrator::DisplaySettings;
use prism_spectrum::color::{RgbSpaceId, ToneMap};

#[derive(Debug, Clone, Args)]
pub struct ImageArgs {
    /// Colour space of EXR and PNG files (for prism denoise: the one the input was
    /// rendered in, which the denoiser converts from).
    #[arg(long, default_value = "srgb")]
    pub space: String,
    /// PNG exposure in stops.
    #[arg(long, default_value_t = 0.0)]
    pub exposure: f64,
    /// PNG tone mapping: neutral (Khronos PBR Neutral), aces, reinhard[:WHITE] or clamp.
    #[arg(long, default_value = "neutral")]
    pub tonemap: String,
    /// PNG outputs carry the alpha channel (for renders made with --transparent).
    #[arg(long)]
    pub transparent: bool,
}

impl ImageArgs {
    /// The colour space, and how PNG outputs show the image.
    pub fn parse(&self) -> Result<(RgbSpaceId, DisplaySettings), String> {
        let space = RgbSpaceId::from_name(&self.space).map_err(|e| e.to_string())?;
        let display = DisplaySettings::default()
            .exposure(self.exposure)
            .tone_map(ToneMap::from_name(&self.tonemap).map_err(|e| e.to_string())?)
            .alpha(self.transparent);
        Ok((space, display))
    }
}
