//! The binary file format of coefficient tables, version 2 (all little-endian):
//!
//! | field | bytes |
//! | --- | --- |
//! | magic `PRISMSPC` | 8 |
//! | format version (2) | u32 |
//! | observer (1 = CIE 1931 2 degree) | u8 |
//! | space name length n, then UTF-8 name | u16 + n |
//! | primaries r, g, b (x, y) and white (x, y) | 8 x f64 |
//! | resolution r | u32 |
//! | brightness nodes | r x f32 |
//! | coefficients for l in nm times sqrt(z), [channel][z][y][x][3], ratio axes smoothstep-remapped | 9 r^3 x f32 |
//! | FNV-1a 64 checksum of everything above | u64 |
//!
//! Version 1 held the coefficients in the fitter's normalized wavelength; version 2 holds
//! them as lookups use them, so loading is a copy. A version-1 file is refused by its
//! version field (the command line's cache names files by version and refits).
//!
//! Reading checks every field, the exact length and the checksum, so a truncated,
//! corrupted or foreign file is an error naming what is wrong, never garbage coefficients.

use crate::error::UpsampleError;
use crate::table::{CoefficientTable, TableSpace};

const MAGIC: &[u8; 8] = b"PRISMSPC";
/// The format version this build reads and writes.
pub const FORMAT_VERSION: u32 = 2;
const OBSERVER_CIE1931: u8 = 1;

/// FNV-1a, 64-bit (Fowler, Noll, Vo): a checksum against accidental corruption.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

impl CoefficientTable {
    /// The table in the file format of [`FORMAT_VERSION`]: fit once, keep the bytes,
    /// read them back with [`CoefficientTable::from_bytes`].
    ///
    /// ```
    /// use prism_spectrum::color::RgbSpaceId;
    /// use prism_upsample::{CoefficientTable, FitContext};
    ///
    /// let p3 = RgbSpaceId::DisplayP3;
    /// let context = FitContext::new(p3.space(), &p3.illuminant())?;
    /// let (table, statistics) = CoefficientTable::fit(&context, 8, &|_rows_done| {})?;
    /// assert_eq!((table.resolution(), statistics.max_residual.is_finite()), (8, true));
    /// let bytes = table.to_bytes();
    /// assert_eq!(CoefficientTable::from_bytes(&bytes)?, table);
    /// // A damaged file is an error naming the damage, never garbage coefficients.
    /// let mut damaged = bytes.clone();
    /// damaged[100] ^= 1;
    /// assert!(CoefficientTable::from_bytes(&damaged).unwrap_err().to_string().contains("checksum"));
    /// # Ok::<(), prism_upsample::UpsampleError>(())
    /// ```
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(64 + self.nodes.len() * 12);
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        out.push(OBSERVER_CIE1931);
        let name = self.space.name.as_bytes();
        let name = &name[..name.len().min(u16::MAX as usize)];
        out.extend_from_slice(&(name.len() as u16).to_le_bytes());
        out.extend_from_slice(name);
        for v in self
            .space
            .primaries
            .iter()
            .flatten()
            .chain(&self.space.white)
        {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.extend_from_slice(&(self.resolution as u32).to_le_bytes());
        for v in self
            .z_nodes
            .iter()
            .chain(self.nodes.iter().flat_map(|n| &n[..3]))
        {
            out.extend_from_slice(&v.to_le_bytes());
        }
        let checksum = fnv1a(&out);
        out.extend_from_slice(&checksum.to_le_bytes());
        out
    }

    /// Reads a table written by [`CoefficientTable::to_bytes`].
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, UpsampleError> {
        let mut r = Reader { bytes, at: 0 };
        if r.take(8)? != MAGIC {
            return Err(invalid("not a prism coefficient table (bad magic bytes)"));
        }
        let version = r.u32()?;
        if version != FORMAT_VERSION {
            return Err(invalid(&format!(
                "format version {version}; this build reads version {FORMAT_VERSION}"
            )));
        }
        let observer = r.take(1)?[0];
        if observer != OBSERVER_CIE1931 {
            return Err(invalid(&format!("unknown observer id {observer}")));
        }
        let name_len = usize::from(u16::from_le_bytes([r.take(1)?[0], r.take(1)?[0]]));
        let name = std::str::from_utf8(r.take(name_len)?)
            .map_err(|_| invalid("the colour space name is not UTF-8"))?
            .to_string();
        let mut floats = [0.0f64; 8];
        for f in &mut floats {
            *f = f64::from_le_bytes(r.array()?);
            if !f.is_finite() {
                return Err(invalid("a primary or white chromaticity is not finite"));
            }
        }
        let resolution = r.u32()? as usize;
        if !CoefficientTable::RESOLUTIONS.contains(&resolution) {
            return Err(invalid(&format!(
                "resolution {resolution} is outside {:?}",
                CoefficientTable::RESOLUTIONS
            )));
        }
        let count = 9 * resolution * resolution * resolution;
        let expected_total = r.at + 4 * (resolution + count) + 8;
        if bytes.len() != expected_total {
            return Err(invalid(&format!(
                "{} bytes where a {resolution}^3 table has {expected_total} (truncated or trailing data)",
                bytes.len()
            )));
        }
        let z_nodes: Vec<f32> = (0..resolution)
            .map(|_| r.array().map(f32::from_le_bytes))
            .collect::<Result<_, _>>()?;
        let data: Vec<f32> = (0..count)
            .map(|_| r.array().map(f32::from_le_bytes))
            .collect::<Result<_, _>>()?;
        let stored = u64::from_le_bytes(r.array()?);
        if stored != fnv1a(&bytes[..bytes.len() - 8]) {
            return Err(invalid("checksum mismatch: the file is corrupted"));
        }
        let nodes_ok = z_nodes.first() == Some(&0.0)
            && z_nodes.last() == Some(&1.0)
            && z_nodes.windows(2).all(|w| w[0] < w[1]);
        if !nodes_ok {
            return Err(invalid("brightness nodes must increase from 0 to 1"));
        }
        if data.iter().any(|v| !v.is_finite()) {
            return Err(invalid("a coefficient is not finite"));
        }
        Ok(CoefficientTable {
            axes: crate::table::axis_inverses(),
            space: TableSpace {
                name,
                primaries: [
                    [floats[0], floats[1]],
                    [floats[2], floats[3]],
                    [floats[4], floats[5]],
                ],
                white: [floats[6], floats[7]],
            },
            resolution,
            z_nodes,
            nodes: data
                .chunks_exact(3)
                .map(|c| [c[0], c[1], c[2], 0.0])
                .collect(),
        })
    }
}

fn invalid(msg: &str) -> UpsampleError {
    UpsampleError::InvalidTable(msg.to_string())
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], UpsampleError> {
        let end = self
            .at
            .checked_add(n)
            .filter(|&e| e <= self.bytes.len())
            .ok_or_else(|| {
                invalid(&format!(
                    "truncated: needed {n} bytes at offset {}, the file has {}",
                    self.at,
                    self.bytes.len()
                ))
            })?;
        let slice = &self.bytes[self.at..end];
        self.at = end;
        Ok(slice)
    }

    fn array<const N: usize>(&mut self) -> Result<[u8; N], UpsampleError> {
        let slice = self.take(N)?;
        let mut out = [0u8; N];
        out.copy_from_slice(slice);
        Ok(out)
    }

    fn u32(&mut self) -> Result<u32, UpsampleError> {
        Ok(u32::from_le_bytes(self.array()?))
    }
}
