//! A node's values as OpenVDB stores them (`io/Compression.h`, `readCompressedValues`):
//! a byte saying which inactive values were left out and how to restore them, those
//! values, a selection mask, then the values themselves (all of them, or only the
//! active ones under `COMPRESS_ACTIVE_MASK`), as floats or halves, raw, zlib- or
//! Blosc-compressed behind a signed 64-bit length (negative: stored as they are).

use super::blosc;
use super::bytes::{Bytes, bit, ones};

/// Per-grid compression flags (`io::COMPRESS_*`).
pub(super) const COMPRESS_ZIP: u32 = 0x1;
pub(super) const COMPRESS_ACTIVE_MASK: u32 = 0x2;
pub(super) const COMPRESS_BLOSC: u32 = 0x4;

/// How a grid's values are stored.
#[derive(Debug, Clone, Copy)]
pub(super) struct Encoding {
    /// `COMPRESS_*` flags.
    pub compression: u32,
    /// Bytes per value in memory: 4 (float) or 8 (double).
    pub size: usize,
    /// Values written as 16-bit halves (`is_saved_as_half_float`).
    pub half: bool,
    /// The tree's background value.
    pub background: f64,
}

impl Encoding {
    /// One value at full precision (root tiles and the background are never halved).
    pub(super) fn value(&self, bytes: &mut Bytes, what: &str) -> Result<f64, String> {
        Ok(match self.size {
            8 => bytes.f64(what)?,
            _ => f64::from(f32::from_le_bytes(
                bytes.take(4, what)?.try_into().expect("4 bytes"),
            )),
        })
    }
}

/// What the byte before a node's values says about its inactive values (0: none, or
/// all are the background).
const NO_MASK_AND_MINUS_BG: u8 = 1;
const NO_MASK_AND_ONE_INACTIVE_VAL: u8 = 2;
const MASK_AND_NO_INACTIVE_VALS: u8 = 3;
const MASK_AND_ONE_INACTIVE_VAL: u8 = 4;
const MASK_AND_TWO_INACTIVE_VALS: u8 = 5;
const NO_MASK_AND_ALL_VALS: u8 = 6;

/// Reads the `count` values of a node whose value mask is `active` (`count` bits).
pub(super) fn read_values(
    bytes: &mut Bytes,
    count: usize,
    active: &[u64],
    encoding: &Encoding,
) -> Result<Vec<f64>, String> {
    let what = "a node's values";
    let flag = bytes.u8(what)?;
    if flag > NO_MASK_AND_ALL_VALS {
        return Err(format!(
            "a node's value layout is {flag} (OpenVDB's are 0-6)"
        ));
    }
    let background = encoding.background;
    let mut inactive1 = background;
    // A level set's inside is its background negated.
    let mut inactive0 = if matches!(flag, NO_MASK_AND_MINUS_BG | MASK_AND_NO_INACTIVE_VALS) {
        -background
    } else {
        background
    };
    if matches!(
        flag,
        NO_MASK_AND_ONE_INACTIVE_VAL | MASK_AND_ONE_INACTIVE_VAL | MASK_AND_TWO_INACTIVE_VALS
    ) {
        inactive0 = encoding.value(bytes, what)?;
        if flag == MASK_AND_TWO_INACTIVE_VALS {
            inactive1 = encoding.value(bytes, what)?;
        }
    }
    let selection = if matches!(
        flag,
        MASK_AND_NO_INACTIVE_VALS | MASK_AND_ONE_INACTIVE_VAL | MASK_AND_TWO_INACTIVE_VALS
    ) {
        Some(bytes.mask(count.div_ceil(64), what)?)
    } else {
        None
    };
    let only_active =
        encoding.compression & COMPRESS_ACTIVE_MASK != 0 && flag != NO_MASK_AND_ALL_VALS;
    let stored = if only_active { ones(active) } else { count };
    let values = read_data(bytes, stored, encoding)?;
    if stored == count {
        return Ok(values);
    }
    let mut stored_values = values.into_iter();
    Ok((0..count)
        .map(|i| {
            if bit(active, i) {
                stored_values.next().unwrap_or(background)
            } else if selection.as_ref().is_some_and(|s| bit(s, i)) {
                inactive1
            } else {
                inactive0
            }
        })
        .collect())
}

/// Reads `count` values as the encoding stores them (`readData`, `HalfReader`).
fn read_data(bytes: &mut Bytes, count: usize, encoding: &Encoding) -> Result<Vec<f64>, String> {
    if encoding.half && count == 0 {
        // OpenVDB neither writes nor reads an empty buffer of halves.
        return Ok(Vec::new());
    }
    let size = if encoding.half { 2 } else { encoding.size };
    let length = size * count;
    let raw = if encoding.compression & (COMPRESS_BLOSC | COMPRESS_ZIP) != 0 {
        let what = "a compressed block of values";
        let stored = bytes.i64(what)?;
        if stored <= 0 {
            if stored.unsigned_abs() != length as u64 {
                return Err(format!(
                    "a block of {} stored bytes where {length} were expected",
                    stored.unsigned_abs()
                ));
            }
            bytes.take(length as u64, what)?.to_vec()
        } else {
            let data = bytes.take(stored as u64, what)?;
            if encoding.compression & COMPRESS_BLOSC != 0 {
                blosc::decompress(data, length)?
            } else {
                let out = miniz_oxide::inflate::decompress_to_vec_zlib_with_limit(data, length)
                    .map_err(|e| format!("a zlib block of values: {e:?}"))?;
                if out.len() != length {
                    return Err(format!(
                        "a zlib block gave {} bytes where {length} were expected",
                        out.len()
                    ));
                }
                out
            }
        }
    } else {
        bytes.take(length as u64, "a block of values")?.to_vec()
    };
    Ok(raw
        .chunks_exact(size)
        .map(|b| match size {
            2 => f64::from(half::f16::from_le_bytes([b[0], b[1]])),
            4 => f64::from(f32::from_le_bytes(b.try_into().expect("4 bytes"))),
            _ => f64::from_le_bytes(b.try_into().expect("8 bytes")),
        })
        .collect())
}
