//! Environment images: equirectangular HDR images (OpenEXR and Radiance `.hdr`) decoded to
//! linear RGB and made into [`EnvironmentMap`]s.

#[cfg(feature = "images")]
use std::io::Cursor;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;

use super::{LoadError, Upsampler, Upsampling};
use crate::lights::EnvironmentMap;

/// A decoded HDR image: linear RGB, rows from the top.
#[derive(Debug, Clone, PartialEq)]
pub struct HdrImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear RGB per pixel, row-major from the top-left.
    pub rgb: Vec<[f32; 3]>,
}

/// Environment images larger than this many pixels are refused (a 16k x 8k map is 2^27).
#[cfg(feature = "images")]
const MAX_PIXELS: usize = 1 << 28;

/// Decodes an OpenEXR (its first RGB layer, largest level; a missing channel reads 0) or
/// a Radiance RGBE `.hdr`, told apart by their signatures. Decoder panics on malformed
/// data are caught and reported as errors ([`LoadError::Image`]).
pub fn decode_hdr_image(bytes: &[u8]) -> Result<HdrImage, LoadError> {
    decode_hdr(bytes).map_err(LoadError::Image)
}

pub(crate) fn decode_hdr(bytes: &[u8]) -> Result<HdrImage, String> {
    let decoded = if bytes.starts_with(&[0x76, 0x2f, 0x31, 0x01]) {
        catch_unwind(AssertUnwindSafe(|| decode_exr(bytes)))
    } else if bytes.starts_with(b"#?") {
        catch_unwind(AssertUnwindSafe(|| decode_radiance(bytes)))
    } else {
        return Err("not an OpenEXR or Radiance .hdr image".into());
    };
    let image = decoded.map_err(|_| "the image decoder failed on malformed data".to_string())??;
    if image.width == 0 || image.height == 0 {
        return Err("the image is empty".into());
    }
    Ok(image)
}

#[cfg(feature = "images")]
fn decode_exr(bytes: &[u8]) -> Result<HdrImage, String> {
    use exr::prelude::*;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |resolution, _| {
                let (w, h) = (resolution.width(), resolution.height());
                if w.saturating_mul(h) > MAX_PIXELS {
                    (w, Vec::new())
                } else {
                    (w, vec![[0.0f32; 3]; w * h])
                }
            },
            |(w, texels): &mut (usize, Vec<[f32; 3]>),
             position: Vec2<usize>,
             (r, g, b, _): (f32, f32, f32, f32)| {
                if let Some(t) = texels.get_mut(position.y() * *w + position.x()) {
                    *t = [r, g, b];
                }
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(Cursor::new(bytes))
        .map_err(|e| format!("OpenEXR: {e}"))?;
    let size = image.layer_data.size;
    let (_, rgb) = image.layer_data.channel_data.pixels;
    if rgb.len() != size.area() {
        return Err(format!(
            "{}x{} pixels is larger than prism accepts",
            size.width(),
            size.height()
        ));
    }
    Ok(HdrImage {
        width: u32::try_from(size.width()).map_err(|_| "OpenEXR: too wide")?,
        height: u32::try_from(size.height()).map_err(|_| "OpenEXR: too tall")?,
        rgb,
    })
}

#[cfg(feature = "images")]
fn decode_radiance(bytes: &[u8]) -> Result<HdrImage, String> {
    use image::ImageDecoder;
    let decoder = image::codecs::hdr::HdrDecoder::new(Cursor::new(bytes))
        .map_err(|e| format!("Radiance .hdr: {e}"))?;
    let (width, height) = decoder.dimensions();
    if (width as usize).saturating_mul(height as usize) > MAX_PIXELS {
        return Err(format!(
            "{width}x{height} pixels is larger than prism accepts"
        ));
    }
    let image = image::DynamicImage::from_decoder(decoder)
        .map_err(|e| format!("Radiance .hdr: {e}"))?
        .into_rgb32f();
    let rgb = image.pixels().map(|p| p.0).collect();
    Ok(HdrImage { width, height, rgb })
}

/// Where an environment image comes from and how it is placed.
#[derive(Debug, Clone, PartialEq)]
pub struct EnvironmentImage {
    /// The decoded image.
    pub image: HdrImage,
    /// Degrees about +y (counter-clockwise seen from above).
    pub rotation: f64,
    /// A factor on every texel.
    pub strength: f64,
}

impl Upsampler {
    /// The environment map of `desc`, its texels upsampled as emissive colours are.
    pub(crate) fn environment_map(&self, desc: EnvironmentImage) -> Result<EnvironmentMap, String> {
        let table = self.table()?;
        EnvironmentMap::new(
            desc.image.width,
            desc.image.height,
            desc.image.rgb,
            desc.rotation,
            desc.strength,
            (table, self.context.clone(), self.illuminant.clone()),
        )
    }
}

/// An environment map from an image file's bytes (`--environment FILE`): decoded,
/// turned by `rotation` degrees about +y and scaled by `strength`.
pub fn environment_map(
    bytes: &[u8],
    rotation: f64,
    strength: f64,
) -> Result<Arc<EnvironmentMap>, LoadError> {
    let image = decode_hdr_image(bytes)?;
    let upsampler = Upsampler::new(Upsampling::Exact, None)?;
    upsampler
        .environment_map(EnvironmentImage {
            image,
            rotation,
            strength,
        })
        .map(Arc::new)
        .map_err(LoadError::Scene)
}

/// Without the `images` feature every image is refused by the one function below, which
/// stands in for each decoder.
#[cfg(not(feature = "images"))]
fn without_codecs(_: &[u8]) -> Result<HdrImage, String> {
    Err("prism-scene was built without its `images` feature (image decoders)".into())
}
#[cfg(not(feature = "images"))]
use without_codecs as decode_exr;
#[cfg(not(feature = "images"))]
use without_codecs as decode_radiance;
