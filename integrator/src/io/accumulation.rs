//! Accumulation files: a film's exact state (f64 sums per pixel, samples, rejected
//! samples, the sample range) as an OpenEXR file, so that sample ranges rendered on
//! different machines merge into the image one machine would have made.
//!
//! EXR has no f64 channels, and f32 would lose the sums' low bits, so each sum is stored
//! as its IEEE-754 bits split over two u32 channels (`X.hi`, `X.lo`, ...): lossless.
//! Besides XYZ (or a camera's raw channels) a file holds the coverage counts
//! (`Coverage.*`, the alpha channel's) and whatever else the film accumulates: per-band spectral sums (`S0000.hi`, ...; the bands in the facts) and energy
//! sums (`Energy.*` radiance, `Photons.*` photon radiance) and Stokes sums (`S1X.*` ...
//! `S3Z.*`) and AOV sums (`Aov*`), so spectral, energy, polarized and AOV renders
//! checkpoint, resume and merge like any other.

use std::io::Cursor;
use std::ops::Range;

use exr::meta::attribute::AttributeValue;
use exr::prelude::{
    AnyChannel, AnyChannels, Encoding, FlatSamples, Image, Layer, LayerAttributes, SmallVec, Text,
    WritableImage,
};

use crate::io::compare::read_flat;
use crate::{AovSums, Aovs, Film, RenderError, SpectralBands};

const XYZ: [&str; 3] = ["X", "Y", "Z"];
const ENERGY: [&str; 2] = ["Energy", "Photons"];
/// The Stokes components S1..S3's colour sums.
const STOKES: [[&str; 3]; 3] = [
    ["S1X", "S1Y", "S1Z"],
    ["S2X", "S2Y", "S2Z"],
    ["S3X", "S3Y", "S3Z"],
];
/// Per pixel, the camera rays that met geometry (the alpha channel's numerator).
const COVERAGE: &str = "Coverage";
const FACTS: &str = "prismAccumulation";

/// The name of band `i`'s spectral sum channels (zero-padded: EXR sorts channels by name).
fn band_channel(i: usize) -> String {
    format!("S{i:04}")
}

/// The two u32 channels `name.hi` and `name.lo` holding the bits of `values`.
fn split_channels(
    name: &str,
    values: impl Iterator<Item = f64> + Clone,
) -> [AnyChannel<FlatSamples>; 2] {
    let half = |high: bool| {
        let bits = values.clone().map(|v| {
            let b = v.to_bits();
            if high { (b >> 32) as u32 } else { b as u32 }
        });
        FlatSamples::U32(bits.collect())
    };
    [
        AnyChannel::new(format!("{name}.hi").as_str(), half(true)),
        AnyChannel::new(format!("{name}.lo").as_str(), half(false)),
    ]
}

/// A film with the sample range it holds.
#[derive(Debug, Clone, PartialEq)]
pub struct Accumulation {
    /// The sums.
    pub film: Film,
    /// Sample indices rendered in every pixel (merged files: the hull of their ranges).
    pub samples: Range<u64>,
    /// What the caller recorded about the render's settings (checked on resume and merge),
    /// as `key=value` entries joined by `;` so that a mismatch can name what differs
    /// ([`settings_difference`]); any other text is compared whole.
    pub settings: String,
}

/// What differs between two settings records of the `key=value;key=value` form: each key
/// whose values differ (or that only one has, its other value shown as "none"), as
/// "key A vs B" joined by ", ". Records without that form are shown whole.
pub fn settings_difference(a: &str, b: &str) -> String {
    let entries = |s: &'_ str| -> Vec<(String, String)> {
        s.split(';')
            .map(|e| match e.split_once('=') {
                Some((k, v)) => (k.to_string(), v.to_string()),
                None => (String::new(), e.to_string()),
            })
            .collect()
    };
    let (ea, eb) = (entries(a), entries(b));
    let value = |e: &[(String, String)], key: &str| {
        e.iter()
            .find(|(k, _)| k == key)
            .map_or_else(|| "none".to_string(), |(_, v)| v.clone())
    };
    let mut keys: Vec<&str> = Vec::new();
    for (k, _) in ea.iter().chain(&eb) {
        if !keys.contains(&k.as_str()) {
            keys.push(k);
        }
    }
    let differing: Vec<String> = keys
        .into_iter()
        .filter(|k| value(&ea, k) != value(&eb, k))
        .map(|k| match k {
            "" => format!("'{a}' vs '{b}'"),
            k => format!("{k} {} vs {}", value(&ea, k), value(&eb, k)),
        })
        .collect();
    if differing.is_empty() {
        format!("'{a}' vs '{b}'")
    } else {
        differing.join(", ")
    }
}

/// The film of sample range `samples` as accumulation-file bytes, with `settings` (any
/// text) recorded for [`decode_accumulation`] to return.
pub fn encode_accumulation(
    film: &Film,
    samples: Range<u64>,
    settings: &str,
) -> Result<Vec<u8>, RenderError> {
    let (w, h) = (film.width() as usize, film.height() as usize);
    let mut list: Vec<AnyChannel<FlatSamples>> = Vec::new();
    for (k, name) in XYZ.iter().enumerate() {
        list.extend(split_channels(name, film.sums().iter().map(move |s| s[k])));
    }
    list.extend(split_channels(COVERAGE, film.coverage().iter().copied()));
    let mut extra = String::new();
    if let Some(bands) = film.bands() {
        let (n, sums) = (bands.count(), film.spectral_sums());
        let width = film.spectral_width();
        for b in 0..width {
            let values = sums.iter().skip(b).step_by(width).copied();
            list.extend(split_channels(&band_channel(b), values));
        }
        let (min, max) = bands.range();
        // f32 Display round-trips exactly.
        extra += &format!("bands={min}:{max}:{n};");
    }
    if film.has_energy() {
        for (k, name) in ENERGY.iter().enumerate() {
            list.extend(split_channels(
                name,
                film.energy_sums().iter().map(move |e| e[k]),
            ));
        }
        extra += "energy=1;";
    }
    if film.is_polarized() {
        for (k, names) in STOKES.iter().enumerate() {
            for (c, name) in names.iter().enumerate() {
                list.extend(split_channels(
                    name,
                    film.stokes_sums().iter().map(move |s| s[k][c]),
                ));
            }
        }
        extra += "polarized=1;";
    }
    if film.is_raw() {
        extra += "raw=1;";
    }
    let aovs = film.aovs();
    if !aovs.set().is_empty() {
        for (name, values) in aovs.columns() {
            list.extend(split_channels(&name, values.into_iter()));
        }
        // Names joined by '+' (',' would not matter, but ';' and '=' end a fact).
        extra += &format!("aovs={};", aovs.set().to_string().replace(',', "+"));
    }
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
        "samples={};nonfinite={};range={}..{};{extra}settings={settings}",
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
        .map_err(|e| RenderError::exr_encode("accumulation EXR", e))?;
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
    let bad = |m: String| RenderError::Decode {
        reason: format!("not a prism accumulation file: {m}"),
        source: None,
    };
    let image = read_flat(bytes).map_err(|e| match e {
        RenderError::Decode { reason, source } => RenderError::Decode {
            reason: format!("not a prism accumulation file: {reason}"),
            source,
        },
        other => other,
    })?;
    // Written as an image attribute; a reader may file it under the (only) layer.
    let key = Text::from(FACTS);
    let stored =
        (image.attributes.other.get(&key)).or_else(|| image.layer_data.attributes.other.get(&key));
    let (facts, settings) = match stored {
        Some(AttributeValue::Text(t)) => {
            let text = t.to_string();
            // The facts end where the settings (free text, last) begin.
            match text.split_once(";settings=") {
                Some((facts, settings)) => (facts.to_string(), settings.to_string()),
                None => (text, String::new()),
            }
        }
        _ => return Err(bad(format!("no {FACTS} attribute"))),
    };
    let number = |key: &str| -> Result<u64, RenderError> {
        fact(&facts, key)
            .and_then(|v| v.parse().ok())
            .ok_or_else(|| bad(format!("attribute {FACTS} lacks {key}")))
    };
    let (samples, nonfinite) = (number("samples")?, number("nonfinite")?);
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
    // The f64 values whose bits channels `name.hi` and `name.lo` hold.
    let values = |name: &str| -> Result<Vec<f64>, RenderError> {
        let (hi, lo) = (
            channel(&format!("{name}.hi"))?,
            channel(&format!("{name}.lo"))?,
        );
        Ok(hi
            .iter()
            .zip(lo)
            .map(|(&h, &l)| f64::from_bits((u64::from(h) << 32) | u64::from(l)))
            .collect())
    };
    let xyz = XYZ
        .iter()
        .map(|n| values(n))
        .collect::<Result<Vec<_>, _>>()?;
    let sums: Vec<[f64; 3]> = (0..size.area())
        .map(|i| std::array::from_fn(|k| xyz[k][i]))
        .collect();
    let (w, h) = (
        u32::try_from(size.width()).map_err(|_| bad("width".into()))?,
        u32::try_from(size.height()).map_err(|_| bad("height".into()))?,
    );
    let mut film = Film::from_parts(w, h, sums, samples, nonfinite)
        .ok_or_else(|| bad("non-finite sums".into()))?;
    // Files written before coverage was recorded count every sample as covered.
    if layer
        .channel_data
        .list
        .iter()
        .any(|c| c.name == *format!("{COVERAGE}.hi").as_str())
    {
        film = film
            .with_coverage(values(COVERAGE)?)
            .ok_or_else(|| bad("coverage counts that are negative or not finite".into()))?;
    }
    let polarized = fact(&facts, "polarized") == Some("1");
    if polarized {
        film = film.with_polarization();
    }
    if let Some(text) = fact(&facts, "bands") {
        let parse = || -> Option<SpectralBands> {
            let mut parts = text.split(':');
            let (min, max, n) = (parts.next()?, parts.next()?, parts.next()?);
            let bands = SpectralBands::new(min.parse().ok()?, max.parse().ok()?, n.parse().ok()?);
            parts.next().is_none().then_some(bands.ok()?)
        };
        let bands = parse().ok_or_else(|| bad(format!("bands '{text}' are not A:B:N")))?;
        let n = bands.count() * if polarized { 4 } else { 1 };
        let per_band = (0..n)
            .map(|b| values(&band_channel(b)))
            .collect::<Result<Vec<_>, _>>()?;
        let spectral = (0..size.area() * n)
            .map(|i| per_band[i % n][i / n])
            .collect();
        film = film
            .with_spectral_sums(bands, spectral)
            .ok_or_else(|| bad("non-finite spectral sums".into()))?;
    }
    if fact(&facts, "energy") == Some("1") {
        let [radiance, photons] = ENERGY.map(values);
        let (radiance, photons) = (radiance?, photons?);
        let sums = radiance
            .into_iter()
            .zip(photons)
            .map(|(e, p)| [e, p])
            .collect();
        film = film
            .with_energy_sums(sums)
            .ok_or_else(|| bad("non-finite energy sums".into()))?;
    }
    if polarized {
        let channels = STOKES
            .iter()
            .flatten()
            .map(|name| values(name))
            .collect::<Result<Vec<_>, _>>()?;
        let sums = (0..size.area())
            .map(|i| std::array::from_fn(|k| std::array::from_fn(|c| channels[3 * k + c][i])))
            .collect();
        film = film
            .with_stokes_sums(sums)
            .ok_or_else(|| bad("non-finite Stokes sums".into()))?;
    }
    if fact(&facts, "raw") == Some("1") {
        film = film.with_raw_channels();
    }
    if let Some(text) = fact(&facts, "aovs") {
        let set: Aovs = text.replace('+', ",").parse().map_err(bad)?;
        let sums =
            AovSums::from_columns(set, size.area(), &mut |name| values(name).ok()).map_err(bad)?;
        if sums
            .columns()
            .iter()
            .flat_map(|(_, v)| v)
            .any(|v| !v.is_finite())
        {
            return Err(bad("non-finite AOV sums".into()));
        }
        film = film.with_aov_sums(sums);
    }
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
            "parts were rendered with different settings: {}",
            settings_difference(&first.settings, &other.settings)
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
    let mut film = first.film.black_like();
    for part in order {
        film.merge(&part.film)?;
    }
    Ok(Accumulation {
        film,
        samples: ranges[0].start..ranges[ranges.len() - 1].end,
        settings: first.settings.clone(),
    })
}
