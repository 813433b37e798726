//! Decoding glTF images (PNG and JPEG, the formats glTF core allows, and WebP for
//! `EXT_texture_webp`) to 8-bit RGB and alpha.

use std::panic::{AssertUnwindSafe, catch_unwind};

/// A decoded image: rows top to bottom, 8-bit RGB as stored (sRGB-encoded for colour
/// textures).
#[derive(Debug, Clone, PartialEq)]
pub struct DecodedImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Pixels, row-major from the top-left.
    pub rgb: Vec<[u8; 3]>,
    /// The alpha channel, when the image has one (PNG with alpha).
    pub alpha: Option<Vec<u8>>,
}

/// Images larger than this many pixels are refused rather than allocated (a 16k x 16k
/// texture; a corrupt header must not ask for terabytes).
#[cfg(feature = "images")]
const MAX_PIXELS: u64 = 1 << 28;

/// Decodes a PNG or JPEG (told apart by their signatures). Errors say why; decoder
/// panics on malformed data are caught and reported as errors too
/// ([`LoadError::Image`](super::LoadError::Image)).
pub fn decode_image(bytes: &[u8]) -> Result<DecodedImage, super::LoadError> {
    decode(bytes).map_err(super::LoadError::Image)
}

pub(crate) fn decode(bytes: &[u8]) -> Result<DecodedImage, String> {
    let decoded = if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        catch_unwind(AssertUnwindSafe(|| decode_png(bytes)))
    } else if bytes.starts_with(&[0xFF, 0xD8]) {
        catch_unwind(AssertUnwindSafe(|| decode_jpeg(bytes)))
    } else if bytes.len() >= 12 && &bytes[..4] == b"RIFF" && &bytes[8..12] == b"WEBP" {
        catch_unwind(AssertUnwindSafe(|| decode_webp(bytes)))
    } else {
        return Err("not a PNG, JPEG or WebP image".into());
    };
    let image = decoded.map_err(|_| "the image decoder failed on malformed data".to_string())??;
    if image.width == 0 || image.height == 0 {
        return Err("the image is empty".into());
    }
    Ok(image)
}

#[cfg(feature = "images")]
fn check_size(width: u32, height: u32) -> Result<(), String> {
    if u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(format!(
            "{width}x{height} pixels is larger than prism accepts"
        ));
    }
    Ok(())
}

#[cfg(feature = "images")]
fn decode_png(bytes: &[u8]) -> Result<DecodedImage, String> {
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    // Palettes and low bit depths expand to 8 bits, 16 bits strip to 8.
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = decoder.read_info().map_err(|e| format!("PNG: {e}"))?;
    let (width, height) = (reader.info().width, reader.info().height);
    check_size(width, height)?;
    let mut buffer = vec![0; reader.output_buffer_size()];
    let frame = reader
        .next_frame(&mut buffer)
        .map_err(|e| format!("PNG: {e}"))?;
    let data = &buffer[..frame.buffer_size()];
    let channels = match frame.color_type {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => return Err("PNG: palette was not expanded".into()),
    };
    let alpha = matches!(channels, 2 | 4).then(|| {
        data.chunks_exact(channels)
            .map(|p| p[channels - 1])
            .collect()
    });
    Ok(DecodedImage {
        width,
        height,
        rgb: to_rgb(data, channels, width, height)?,
        alpha,
    })
}

#[cfg(feature = "images")]
fn decode_jpeg(bytes: &[u8]) -> Result<DecodedImage, String> {
    use zune_jpeg::zune_core::colorspace::ColorSpace;
    use zune_jpeg::zune_core::options::DecoderOptions;
    let options = DecoderOptions::default()
        .jpeg_set_out_colorspace(ColorSpace::RGB)
        .set_max_width(1 << 16)
        .set_max_height(1 << 16);
    let mut decoder = zune_jpeg::JpegDecoder::new_with_options(bytes, options);
    decoder
        .decode_headers()
        .map_err(|e| format!("JPEG: {e:?}"))?;
    let info = decoder.info().ok_or("JPEG: no image information")?;
    let (width, height) = (u32::from(info.width), u32::from(info.height));
    check_size(width, height)?;
    let data = decoder.decode().map_err(|e| format!("JPEG: {e:?}"))?;
    Ok(DecodedImage {
        width,
        height,
        rgb: to_rgb(&data, 3, width, height)?,
        alpha: None,
    })
}

#[cfg(feature = "images")]
fn decode_webp(bytes: &[u8]) -> Result<DecodedImage, String> {
    use image::ImageDecoder;
    let decoder = image::codecs::webp::WebPDecoder::new(std::io::Cursor::new(bytes))
        .map_err(|e| format!("WebP: {e}"))?;
    let (width, height) = decoder.dimensions();
    check_size(width, height)?;
    let has_alpha = decoder.color_type().has_alpha();
    let rgba = image::DynamicImage::from_decoder(decoder)
        .map_err(|e| format!("WebP: {e}"))?
        .into_rgba8();
    let data = rgba.as_raw();
    Ok(DecodedImage {
        width,
        height,
        rgb: to_rgb(data, 4, width, height)?,
        alpha: has_alpha.then(|| data.chunks_exact(4).map(|p| p[3]).collect()),
    })
}

#[cfg(feature = "images")]
fn to_rgb(data: &[u8], channels: usize, width: u32, height: u32) -> Result<Vec<[u8; 3]>, String> {
    let pixels = width as usize * height as usize;
    if data.len() < pixels * channels {
        return Err(format!(
            "{} bytes of pixel data for {width}x{height} pixels of {channels} channels",
            data.len()
        ));
    }
    Ok(data
        .chunks_exact(channels)
        .take(pixels)
        .map(|p| match channels {
            1 | 2 => [p[0]; 3],
            _ => [p[0], p[1], p[2]],
        })
        .collect())
}

/// Without the `images` feature every image is refused by the one function below, which
/// stands in for each decoder.
#[cfg(not(feature = "images"))]
fn without_codecs(_: &[u8]) -> Result<DecodedImage, String> {
    Err("prism-scene was built without its `images` feature (image decoders)".into())
}
#[cfg(not(feature = "images"))]
use without_codecs as decode_png;
#[cfg(not(feature = "images"))]
use without_codecs as decode_jpeg;
#[cfg(not(feature = "images"))]
use without_codecs as decode_webp;
