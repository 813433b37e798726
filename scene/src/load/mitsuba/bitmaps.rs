//! Image files as Mitsuba's `bitmap` texture reads them (its `Bitmap` class,
//! src/core/bitmap.cpp, then `expand_bitmap` in src/textures/bitmap.cpp): PNG (8 or 16
//! bits, grey or colour, alpha dropped), JPEG (grey or colour), OpenEXR and Radiance HDR,
//! as floats of one channel (grey) or three (colour).
//!
//! PNG and JPEG hold sRGB-encoded values, which are decoded to linear ones unless the
//! texture is `raw` (normal maps, heights); OpenEXR and HDR are linear already. An image
//! with a side of one texel has that side doubled, as Mitsuba resamples it to two.

use crate::load::environment::decode_hdr;

/// A decoded image: `channels` (1 or 3) floats per texel, rows from the top.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Image {
    pub width: u32,
    pub height: u32,
    pub channels: usize,
    pub data: Vec<f32>,
}

/// Images larger than this many texels are refused before they are allocated.
const MAX_TEXELS: u64 = 1 << 28;

/// Decodes `bytes` (told apart by their signatures); `raw` keeps PNG and JPEG values as
/// stored (byte / 255), otherwise they are decoded from sRGB.
pub(crate) fn decode(bytes: &[u8], raw: bool) -> Result<Image, String> {
    let caught = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
            png(bytes, raw)
        } else if bytes.starts_with(&[0xFF, 0xD8]) {
            jpeg(bytes, raw)
        } else if bytes.starts_with(&[0x76, 0x2f, 0x31, 0x01]) || bytes.starts_with(b"#?") {
            let hdr = decode_hdr(bytes)?;
            check_size(hdr.width, hdr.height)?;
            Ok(Image {
                width: hdr.width,
                height: hdr.height,
                channels: 3,
                data: hdr.rgb.iter().flatten().copied().collect(),
            })
        } else {
            Err("not a PNG, JPEG, OpenEXR or Radiance HDR image".into())
        }
    }));
    let image = caught.map_err(|_| "the image decoder failed on malformed data".to_string())??;
    Ok(at_least_two(image))
}

fn check_size(width: u32, height: u32) -> Result<(), String> {
    if width == 0 || height == 0 {
        return Err("the image is empty".into());
    }
    if u64::from(width) * u64::from(height) > MAX_TEXELS {
        return Err(format!(
            "{width}x{height} texels is larger than prism accepts"
        ));
    }
    Ok(())
}

/// The sRGB transfer curve's inverse (IEC 61966-2-1), as Mitsuba's `srgb_to_linear`.
#[cfg(feature = "images")]
fn linear(v: f32) -> f32 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// Stored values (`max` the largest) as floats: decoded from sRGB unless `raw`.
#[cfg(feature = "images")]
fn floats(values: impl Iterator<Item = u16>, max: f32, raw: bool) -> Vec<f32> {
    values
        .map(|v| {
            let v = f32::from(v) / max;
            if raw { v } else { linear(v) }
        })
        .collect()
}

#[cfg(feature = "images")]
fn png(bytes: &[u8], raw: bool) -> Result<Image, String> {
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    // Palettes to RGB, transparency to alpha, grey below 8 bits to 8 (as Mitsuba asks
    // libpng); 16 bits stay 16.
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(|e| format!("PNG: {e}"))?;
    let (width, height) = (reader.info().width, reader.info().height);
    check_size(width, height)?;
    let mut buffer = vec![0; reader.output_buffer_size()];
    let frame = reader
        .next_frame(&mut buffer)
        .map_err(|e| format!("PNG: {e}"))?;
    let data = &buffer[..frame.buffer_size()];
    let (stride, keep) = match frame.color_type {
        png::ColorType::Grayscale => (1, 1),
        png::ColorType::GrayscaleAlpha => (2, 1),
        png::ColorType::Rgb => (3, 3),
        png::ColorType::Rgba => (4, 3),
        png::ColorType::Indexed => return Err("PNG: palette was not expanded".into()),
    };
    let texels = width as usize * height as usize;
    let (values, max): (Vec<u16>, f32) = match frame.bit_depth {
        png::BitDepth::Sixteen => (
            data.chunks_exact(2)
                .map(|b| u16::from_be_bytes([b[0], b[1]]))
                .collect(),
            65535.0,
        ),
        png::BitDepth::Eight => (data.iter().map(|&b| u16::from(b)).collect(), 255.0),
        other => return Err(format!("PNG: bit depth {other:?} was not expanded")),
    };
    if values.len() < texels * stride {
        return Err(format!(
            "PNG: {} values for {width}x{height} texels",
            values.len()
        ));
    }
    let kept = values
        .chunks_exact(stride)
        .take(texels)
        .flat_map(|t| t[..keep].iter().copied());
    Ok(Image {
        width,
        height,
        channels: keep,
        data: floats(kept, max, raw),
    })
}

#[cfg(feature = "images")]
fn jpeg(bytes: &[u8], raw: bool) -> Result<Image, String> {
    use zune_jpeg::zune_core::colorspace::ColorSpace;
    use zune_jpeg::zune_core::options::DecoderOptions;
    let probe_options = DecoderOptions::default()
        .set_max_width(1 << 16)
        .set_max_height(1 << 16);
    let mut probe = zune_jpeg::JpegDecoder::new_with_options(bytes, probe_options);
    probe.decode_headers().map_err(|e| format!("JPEG: {e:?}"))?;
    let grey = probe.get_input_colorspace() == Some(ColorSpace::Luma);
    let (out, channels) = if grey {
        (ColorSpace::Luma, 1)
    } else {
        (ColorSpace::RGB, 3)
    };
    let options = probe_options.jpeg_set_out_colorspace(out);
    let mut decoder = zune_jpeg::JpegDecoder::new_with_options(bytes, options);
    decoder
        .decode_headers()
        .map_err(|e| format!("JPEG: {e:?}"))?;
    let info = decoder.info().ok_or("JPEG: no image information")?;
    let (width, height) = (u32::from(info.width), u32::from(info.height));
    check_size(width, height)?;
    let data = decoder.decode().map_err(|e| format!("JPEG: {e:?}"))?;
    let needed = width as usize * height as usize * channels;
    if data.len() < needed {
        return Err(format!(
            "JPEG: {} values for {width}x{height} texels",
            data.len()
        ));
    }
    Ok(Image {
        width,
        height,
        channels,
        data: floats(data[..needed].iter().map(|&b| u16::from(b)), 255.0, raw),
    })
}

/// Without the `images` feature PNG and JPEG are refused by this one function.
#[cfg(not(feature = "images"))]
fn without_codecs(_: &[u8], _: bool) -> Result<Image, String> {
    Err("prism-scene was built without its `images` feature (image decoders)".into())
}
#[cfg(not(feature = "images"))]
use without_codecs as png;
#[cfg(not(feature = "images"))]
use without_codecs as jpeg;

/// A side of one texel doubled: Mitsuba resamples such images to two texels, which
/// along a side of one is the same value twice.
fn at_least_two(image: Image) -> Image {
    if image.width >= 2 && image.height >= 2 {
        return image;
    }
    let (w, h, c) = (image.width as usize, image.height as usize, image.channels);
    let (nw, nh) = (w.max(2), h.max(2));
    let mut data = Vec::with_capacity(nw * nh * c);
    for y in 0..nh {
        for x in 0..nw {
            let i = ((y.min(h - 1)) * w + x.min(w - 1)) * c;
            data.extend_from_slice(&image.data[i..i + c]);
        }
    }
    Image {
        width: nw as u32,
        height: nh as u32,
        channels: c,
        data,
    }
}

#[cfg(all(test, feature = "images"))]
mod tests {
    use super::*;

    /// A PNG of `color` type with `depth` bits from raw samples.
    fn png_bytes(
        width: u32,
        height: u32,
        color: png::ColorType,
        depth: png::BitDepth,
        data: &[u8],
    ) -> Vec<u8> {
        let mut out = Vec::new();
        {
            let mut encoder = png::Encoder::new(&mut out, width, height);
            encoder.set_color(color);
            encoder.set_depth(depth);
            let mut writer = encoder.write_header().unwrap();
            writer.write_image_data(data).unwrap();
        }
        out
    }

    /// Grey stays one channel, alpha is dropped, sRGB is decoded unless raw, 16 bits
    /// keep their precision.
    #[test]
    fn pngs_decode_as_mitsuba_reads_them() {
        let grey_alpha = png_bytes(
            2,
            2,
            png::ColorType::GrayscaleAlpha,
            png::BitDepth::Eight,
            &[255, 0, 0, 9, 188, 9, 10, 9],
        );
        let image = decode(&grey_alpha, false).unwrap();
        assert_eq!((image.width, image.height, image.channels), (2, 2, 1));
        assert_eq!(image.data[0], 1.0);
        assert_eq!(image.data[1], 0.0);
        assert!((image.data[2] - 0.5029).abs() < 1e-3, "{}", image.data[2]);
        let raw = decode(&grey_alpha, true).unwrap();
        assert!((raw.data[2] - 188.0 / 255.0).abs() < 1e-7);
        let rgba = png_bytes(
            2,
            1,
            png::ColorType::Rgba,
            png::BitDepth::Eight,
            &[255, 0, 0, 0, 0, 255, 0, 7],
        );
        let image = decode(&rgba, true).unwrap();
        assert_eq!(image.channels, 3);
        assert_eq!(
            image.data,
            vec![1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
        );
        assert_eq!(image.height, 2, "a row of one texel is doubled");
        let deep = png_bytes(
            2,
            2,
            png::ColorType::Grayscale,
            png::BitDepth::Sixteen,
            &[0x80, 0x00, 0, 0, 0, 0, 0, 1],
        );
        let image = decode(&deep, true).unwrap();
        assert!((image.data[0] - 32768.0 / 65535.0).abs() < 1e-7);
        assert_eq!(image.data[3], 1.0 / 65535.0);
    }

    #[test]
    fn malformed_images_are_errors() {
        assert!(decode(b"nothing", false).is_err());
        assert!(decode(b"\x89PNG\r\n\x1a\nbroken", false).is_err());
        assert!(decode(&[0xFF, 0xD8, 0xFF, 0x00], false).is_err());
    }
}
