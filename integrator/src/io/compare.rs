//! Comparing two images: the error measures renderers are judged by.

#[cfg(feature = "exr")]
use std::io::Cursor;

#[cfg(feature = "exr")]
use exr::prelude::{AnyChannels, FlatSamples, Image, Layer, ReadChannels, ReadLayers, read};

use crate::RenderError;

/// An image's named channels of f32 samples, row-major.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelImage {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Channel names and samples, in the file's (alphabetical) order.
    pub channels: Vec<(String, Vec<f32>)>,
}

/// An EXR's first layer with every channel as stored, and every attribute.
#[cfg(feature = "exr")]
pub(crate) type FlatImage = Image<Layer<AnyChannels<FlatSamples>>>;

/// Reads an EXR's first valid layer from bytes: every channel as stored, all attributes.
#[cfg(feature = "exr")]
pub(crate) fn read_flat(bytes: &[u8]) -> Result<FlatImage, RenderError> {
    // OpenEXR's magic number first: the reader's own complaint ("file identifier
    // missing") would not say that a PNG, say, is the wrong kind of file.
    if !bytes.starts_with(&[0x76, 0x2f, 0x31, 0x01]) {
        return Err(RenderError::Decode {
            reason: "not an OpenEXR file".into(),
            source: None,
        });
    }
    read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(Cursor::new(bytes))
        .map_err(|e| RenderError::Decode {
            reason: format!("EXR: {e}"),
            source: Some(std::sync::Arc::new(e)),
        })
}

/// Reads every channel of an EXR's first layer as f32 (f16 and u32 samples converted).
#[cfg(feature = "exr")]
pub fn decode_exr(bytes: &[u8]) -> Result<ChannelImage, RenderError> {
    let image = read_flat(bytes)?;
    let layer = image.layer_data;
    let channels = layer
        .channel_data
        .list
        .into_iter()
        .map(|c| {
            let samples = match c.sample_data {
                FlatSamples::F32(v) => v,
                FlatSamples::F16(v) => v.into_iter().map(f32::from).collect(),
                FlatSamples::U32(v) => v.into_iter().map(|x| x as f32).collect(),
            };
            (c.name.to_string(), samples)
        })
        .collect();
    Ok(ChannelImage {
        width: layer.size.width(),
        height: layer.size.height(),
        channels,
    })
}

/// Error measures of an image against a reference, per channel and overall.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// Channel names compared.
    pub channels: Vec<String>,
    /// Root mean squared error.
    pub rmse: f64,
    /// Relative MSE: mean of (a - b)^2 / (b^2 + 1e-2), the measure of Rousselle et al.
    /// (2011) used by renderer comparisons; insensitive to absolute scale.
    pub relmse: f64,
    /// Mean absolute error.
    pub mae: f64,
    /// Peak signal-to-noise ratio in dB, with the reference's maximum as the peak; None
    /// when the images are equal (or the reference is black).
    pub psnr: Option<f64>,
    /// Largest absolute difference.
    pub max_difference: f64,
    /// Per channel: mean of the image over mean of the reference; None where the
    /// reference's mean is 0.
    pub mean_ratio: Vec<Option<f64>>,
    /// Per channel: relative MSE.
    pub channel_relmse: Vec<f64>,
}

/// Compares `image` against `reference` over the channels both have (an error when they
/// share none): both must have the same size and only finite samples (a NaN or infinity
/// is an error naming its channel and pixel).
pub fn compare_images(
    image: &ChannelImage,
    reference: &ChannelImage,
) -> Result<Comparison, RenderError> {
    let bad = RenderError::Comparison;
    if (image.width, image.height) != (reference.width, reference.height) {
        return Err(bad(format!(
            "sizes differ: {}x{} and {}x{}",
            image.width, image.height, reference.width, reference.height
        )));
    }
    let names = |i: &ChannelImage| i.channels.iter().map(|c| c.0.clone()).collect::<Vec<_>>();
    // The channels both have: a render with alpha compares with a reference without it
    // (an older render, another renderer's).
    let pairs: Vec<(&String, &Vec<f32>, &Vec<f32>)> = image
        .channels
        .iter()
        .filter_map(|(name, a)| {
            let b = reference.channels.iter().find(|(n, _)| n == name)?;
            Some((name, a, &b.1))
        })
        .collect();
    if pairs.is_empty() {
        return Err(bad(format!(
            "channels differ: {:?} and {:?} have none in common",
            names(image),
            names(reference)
        )));
    }
    for (which, img) in [("image", image), ("reference", reference)] {
        for (name, values) in &img.channels {
            if let Some(i) = values.iter().position(|v| !v.is_finite()) {
                return Err(bad(format!(
                    "{which} channel {name} has a non-finite sample at pixel ({}, {})",
                    i % img.width.max(1),
                    i / img.width.max(1)
                )));
            }
        }
    }
    let n = (image.width * image.height) as f64;
    let (mut squared, mut relative, mut absolute, mut max_difference) = (0.0, 0.0, 0.0, 0.0f64);
    let mut peak = 0.0f64;
    let (mut mean_ratio, mut channel_relmse) = (vec![], vec![]);
    for (_, a, b) in &pairs {
        let (mut sum_a, mut sum_b, mut rel) = (0.0, 0.0, 0.0);
        for (&x, &y) in a.iter().zip(b.iter()) {
            let (x, y) = (f64::from(x), f64::from(y));
            let d = x - y;
            squared += d * d;
            rel += d * d / (y * y + 1e-2);
            absolute += d.abs();
            max_difference = max_difference.max(d.abs());
            peak = peak.max(y.abs());
            sum_a += x;
            sum_b += y;
        }
        relative += rel;
        channel_relmse.push(rel / n);
        mean_ratio.push((sum_b != 0.0).then(|| sum_a / sum_b));
    }
    let count = n * pairs.len() as f64;
    let mse = squared / count;
    Ok(Comparison {
        channels: pairs.iter().map(|(name, _, _)| (*name).clone()).collect(),
        rmse: mse.sqrt(),
        relmse: relative / count,
        mae: absolute / count,
        psnr: (mse > 0.0 && peak > 0.0).then(|| 10.0 * (peak * peak / mse).log10()),
        max_difference,
        mean_ratio,
        channel_relmse,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(values: &[f32]) -> ChannelImage {
        ChannelImage {
            width: values.len(),
            height: 1,
            channels: vec![("Y".into(), values.to_vec())],
        }
    }

    #[test]
    fn measures_match_their_definitions() {
        let c =
            compare_images(&image(&[1.0, 2.0, 3.0, 4.0]), &image(&[1.0, 2.0, 3.0, 2.0])).unwrap();
        assert_eq!(c.rmse, 1.0); // one difference of 2 among four samples
        assert_eq!(c.mae, 0.5);
        assert_eq!(c.max_difference, 2.0);
        assert!((c.relmse - 4.0 / 4.01 / 4.0).abs() < 1e-12);
        assert!((c.psnr.unwrap() - 10.0 * (9.0f64).log10()).abs() < 1e-12);
        assert!((c.mean_ratio[0].unwrap() - 10.0 / 8.0).abs() < 1e-12);
        let same = compare_images(&image(&[1.0, 2.0]), &image(&[1.0, 2.0])).unwrap();
        assert_eq!((same.rmse, same.relmse, same.psnr), (0.0, 0.0, None));
        let black = compare_images(&image(&[1.0, 2.0]), &image(&[0.0, 0.0])).unwrap();
        assert_eq!((black.psnr, black.mean_ratio[0]), (None, None));
        assert!(compare_images(&image(&[1.0]), &image(&[1.0, 2.0])).is_err());
        let e = compare_images(&image(&[1.0, f32::NAN]), &image(&[1.0, 2.0])).unwrap_err();
        assert!(e.to_string().contains("(1, 0)"), "{e}");
        assert!(compare_images(&image(&[1.0]), &image(&[f32::INFINITY])).is_err());
    }

    /// A render with an alpha channel compares with a reference without one over the
    /// channels both have; images with no channel in common are an error.
    #[test]
    fn only_shared_channels_are_compared() {
        let mut with_alpha = image(&[1.0, 4.0]);
        with_alpha.channels.insert(0, ("A".into(), vec![1.0, 0.0]));
        let c = compare_images(&with_alpha, &image(&[1.0, 2.0])).unwrap();
        assert_eq!(c.channels, vec!["Y".to_string()]);
        assert_eq!(c.max_difference, 2.0);
        let mut other = image(&[1.0, 2.0]);
        other.channels[0].0 = "Z".into();
        let e = compare_images(&other, &image(&[1.0, 2.0])).unwrap_err();
        assert!(e.to_string().contains("none in common"), "{e}");
    }
}
