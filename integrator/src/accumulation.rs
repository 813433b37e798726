//! Accumulation files: a film's exact state (f64 sums per pixel, samples, rejected
//! samples, the sample range) as an OpenEXR file, so that sample ranges rendered on
//! different machines merge into the image one machine would have made.
//!
//! EXR has no f64 channels, and f32 would lose the sums' low bits, so each sum is stored
//! as its IEEE-754 bits split over two u32 channels (`X.hi`, `X.lo`, ...): lossless.

use std::io::Cursor;
use std::ops::Range;

use exr::meta::attribute::AttributeValue;
use exr::prelude::{
    AnyChannel, AnyChannels, Encoding, FlatSamples, Image, Layer, LayerAttributes, SmallVec, Text,
    WritableImage,
};

use crate::compare::read_flat;
use crate::{Film, RenderError};

const CHANNELS: [&str; 6] = ["X.hi", "X.lo", "Y.hi", "Y.lo", "Z.hi", "Z.lo"];
const FACTS: &str = "prismAccumulation";

/// A film with the sample range it holds.
#[derive(Debug, Clone, PartialEq)]
pub struct Accumulation {
    /// The sums.
    pub film: Film,
    /// Sample indices rendered in every pixel (merged files: the hull of their ranges).
    pub samples: Range<u64>,
    /// What the caller recorded about the render's settings (checked on resume and merge).
    pub settings: String,
}

/// The film of sample range `samples` as accumulation-file bytes, with `settings` (any
/// text) recorded for [`decode_accumulation`] to return.
pub fn encode_accumulation(
    film: &Film,
    samples: Range<u64>,
    settings: &str,
) -> Result<Vec<u8>, RenderError> {
    let (w, h) = (film.width() as usize, film.height() as usize);
    let channel = |name: &str, k: usize, high: bool| {
        let bits = film.sums().iter().map(|s| {
            let b = s[k].to_bits();
            if high { (b >> 32) as u32 } else { b as u32 }
        });
        AnyChannel::new(name, FlatSamples::U32(bits.collect()))
    };
    let list: Vec<AnyChannel<FlatSamples>> = CHANNELS
        .iter()
        .enumerate()
        .map(|(i, name)| channel(name, i / 2, i % 2 == 0))
        .collect();
    let layer = Layer::new(
        (w, h),
        LayerAttributes::default(),
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(SmallVec::from_vec(list)),
    );
    let mut image = Image::from_layer(layer);
    // One attribute (the exr crate orders extra attributes by a HashMap); the settings come
    // last and run to its end, so they may contain any character.
    let facts = format!(
        "samples={};nonfinite={};range={}..{};settings={settings}",
        film.samples(),
        film.nonfinite(),
        samples.start,
        samples.end
    );
    image.attributes.other.insert(
        Text::from(FACTS),
        AttributeValue::Text(Text::from(facts.as_str())),
    );
    let mut bytes = Cursor::new(Vec::new());
    image
        .write()
        .to_buffered(&mut bytes)
        .map_err(|e| RenderError::Encode(format!("accumulation EXR: {e}")))?;
    Ok(bytes.into_inner())
}

fn fact<'a>(facts: &'a str, key: &str) -> Option<&'a str> {
    facts
        .split(';')
        .find_map(|kv| kv.strip_prefix(key)?.strip_prefix('='))
}

/// Reads an accumulation file. Errors (never panics) on anything that is not one: another
/// EXR, a truncated or corrupted file, missing channels or facts, non-finite sums.
pub fn decode_accumulation(bytes: &[u8]) -> Result<Accumulation, RenderError> {
    let bad = |m: String| RenderError::Encode(format!("not a prism accumulation file: {m}"));
    let image = read_flat(bytes).map_err(|e| bad(e.to_string()))?;
    // Written as an image attribute; a reader may file it under the (only) layer.
    let key = Text::from(FACTS);
    let stored =
        (image.attributes.other.get(&key)).or_else(|| image.layer_data.attributes.other.get(&key));
    let facts = match stored {
        Some(AttributeValue::Text(t)) => t.to_string(),
        _ => return Err(bad(format!("no {FACTS} attribute"))),
    };
    let number = |key: &str| -> Result<u64, RenderError> {
        fact(&facts, key)
            .and_then(|v| v.parse().ok())
            .ok_or_else(|| bad(format!("attribute {FACTS} lacks {key}")))
    };
    let (samples, nonfinite) = (number("samples")?, number("nonfinite")?);
    let settings = facts
        .split_once(";settings=")
        .map_or_else(String::new, |(_, s)| s.to_string());
    let range = fact(&facts, "range")
        .and_then(|r| r.split_once(".."))
        .and_then(|(a, b)| Some(a.parse::<u64>().ok()?..b.parse::<u64>().ok()?))
        .ok_or_else(|| bad(format!("attribute {FACTS} lacks range")))?;
    let layer = &image.layer_data;
    let size = layer.size;
    let channel = |name: &str| -> Result<&Vec<u32>, RenderError> {
        match layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name == *name)
            .map(|c| &c.sample_data)
        {
            Some(FlatSamples::U32(v)) if v.len() == size.area() => Ok(v),
            _ => Err(bad(format!("channel {name} is missing or not u32"))),
        }
    };
    let halves = CHANNELS
        .iter()
        .map(|n| channel(n))
        .collect::<Result<Vec<_>, _>>()?;
    let sums: Vec<[f64; 3]> = (0..size.area())
        .map(|i| {
            std::array::from_fn(|k| {
                f64::from_bits(
                    (u64::from(halves[2 * k][i]) << 32) | u64::from(halves[2 * k + 1][i]),
                )
            })
        })
        .collect();
    let (w, h) = (
        u32::try_from(size.width()).map_err(|_| bad("width".into()))?,
        u32::try_from(size.height()).map_err(|_| bad("height".into()))?,
    );
    let film = Film::from_parts(w, h, sums, samples, nonfinite)
        .ok_or_else(|| bad("non-finite sums".into()))?;
    Ok(Accumulation {
        film,
        samples: range,
        settings,
    })
}

/// Merges accumulation files of disjoint sample ranges of one image: their sums add up to
/// the film of the union of the ranges. Sizes and settings must match and ranges must not
/// overlap.
pub fn merge_accumulations(parts: &[Accumulation]) -> Result<Accumulation, RenderError> {
    let first = parts
        .first()
        .ok_or_else(|| RenderError::Setting("nothing to merge".into()))?;
    if let Some(other) = parts.iter().find(|p| p.settings != first.settings) {
        return Err(RenderError::Setting(format!(
            "parts were rendered with different settings: '{}' and '{}'",
            first.settings, other.settings
        )));
    }
    let mut ranges: Vec<&Range<u64>> = parts.iter().map(|p| &p.samples).collect();
    ranges.sort_by_key(|r| r.start);
    for pair in ranges.windows(2) {
        if pair[0].end > pair[1].start {
            return Err(RenderError::Setting(format!(
                "sample ranges {}..{} and {}..{} overlap",
                pair[0].start, pair[0].end, pair[1].start, pair[1].end
            )));
        }
    }
    // Add in sample order, whatever order the files were given in.
    let mut order: Vec<&Accumulation> = parts.iter().collect();
    order.sort_by_key(|p| p.samples.start);
    let mut film = Film::new(first.film.width(), first.film.height());
    for part in order {
        film.merge(&part.film).map_err(RenderError::Setting)?;
    }
    Ok(Accumulation {
        film,
        samples: ranges[0].start..ranges[ranges.len() - 1].end,
        settings: first.settings.clone(),
    })
}
