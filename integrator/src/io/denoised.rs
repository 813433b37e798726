//! An EXR whose R, G, B are replaced by another image of the same size (a denoised one),
//! the file's own kept beside them as `noisy.R`, `noisy.G`, `noisy.B`: every other channel
//! (alpha, AOVs, spectral bands) and every attribute (chromaticities, prism's facts) stays
//! as it was.

use std::io::Cursor;

use exr::prelude::{AnyChannel, AnyChannels, FlatSamples, SmallVec, WritableImage};

use crate::RenderError;
use crate::io::compare::read_flat;

/// The layer the replaced channels move to.
pub const NOISY_LAYER: &str = "noisy";

/// `bytes` (an EXR with R, G and B) with `rgb` (row-major, one per pixel) as its R, G, B
/// and its own as `noisy.R`, `noisy.G`, `noisy.B`. A file that already has a noisy layer
/// keeps it (denoising a denoised file replaces only R, G, B).
pub fn replace_rgb_exr(bytes: &[u8], rgb: &[[f32; 3]]) -> Result<Vec<u8>, RenderError> {
    let mut image = read_flat(bytes)?;
    let layer = &mut image.layer_data;
    if rgb.len() != layer.size.area() {
        return Err(RenderError::Setting(format!(
            "{} pixels to write into an image of {}",
            rgb.len(),
            layer.size.area()
        )));
    }
    let mut list: Vec<AnyChannel<FlatSamples>> = layer.channel_data.list.to_vec();
    let had_noisy = list
        .iter()
        .any(|c| c.name.to_string().starts_with(&format!("{NOISY_LAYER}.")));
    for (k, name) in ["R", "G", "B"].iter().enumerate() {
        let Some(at) = list.iter().position(|c| c.name == **name) else {
            return Err(RenderError::Decode {
                reason: format!("the image has no {name} channel"),
                source: None,
            });
        };
        let values = FlatSamples::F32(rgb.iter().map(|p| p[k]).collect());
        let old = std::mem::replace(&mut list[at].sample_data, values);
        if !had_noisy {
            let noisy = format!("{NOISY_LAYER}.{name}");
            list.push(AnyChannel::new(noisy.as_str(), old));
        }
    }
    layer.channel_data = AnyChannels::sort(SmallVec::from_vec(list));
    let mut out = Cursor::new(Vec::new());
    image
        .write()
        .to_buffered(&mut out)
        .map_err(|e| RenderError::exr_encode("EXR", e))?;
    Ok(out.into_inner())
}
