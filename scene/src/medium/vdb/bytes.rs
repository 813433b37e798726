//! Little-endian reading of an OpenVDB stream, where running out of bytes is an error
//! that says what was being read.

/// A position in a byte slice.
pub(super) struct Bytes<'a> {
    data: &'a [u8],
    at: usize,
}

impl<'a> Bytes<'a> {
    pub(super) fn new(data: &'a [u8]) -> Self {
        Self { data, at: 0 }
    }

    /// Moves to byte `at` of the whole stream.
    pub(super) fn seek(&mut self, at: u64) -> Result<(), String> {
        if at > self.data.len() as u64 {
            return Err(format!(
                "an offset of {at} bytes in a file of {} bytes",
                self.data.len()
            ));
        }
        self.at = at as usize;
        Ok(())
    }

    /// The next `n` bytes, for `what`.
    pub(super) fn take(&mut self, n: u64, what: &str) -> Result<&'a [u8], String> {
        let end = (self.at as u64)
            .checked_add(n)
            .filter(|&end| end <= self.data.len() as u64)
            .ok_or_else(|| format!("the file ends inside {what}"))?;
        let slice = &self.data[self.at..end as usize];
        self.at = end as usize;
        Ok(slice)
    }

    fn array<const N: usize>(&mut self, what: &str) -> Result<[u8; N], String> {
        Ok(self.take(N as u64, what)?.try_into().expect("N bytes"))
    }

    pub(super) fn u8(&mut self, what: &str) -> Result<u8, String> {
        Ok(self.array::<1>(what)?[0])
    }

    pub(super) fn u32(&mut self, what: &str) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.array(what)?))
    }

    pub(super) fn i32(&mut self, what: &str) -> Result<i32, String> {
        Ok(i32::from_le_bytes(self.array(what)?))
    }

    pub(super) fn u64(&mut self, what: &str) -> Result<u64, String> {
        Ok(u64::from_le_bytes(self.array(what)?))
    }

    pub(super) fn i64(&mut self, what: &str) -> Result<i64, String> {
        Ok(i64::from_le_bytes(self.array(what)?))
    }

    pub(super) fn f64(&mut self, what: &str) -> Result<f64, String> {
        Ok(f64::from_le_bytes(self.array(what)?))
    }

    /// Three 32-bit integers (a coordinate).
    pub(super) fn coord(&mut self, what: &str) -> Result<[i32; 3], String> {
        Ok([self.i32(what)?, self.i32(what)?, self.i32(what)?])
    }

    /// Three doubles (a vector of a transform).
    pub(super) fn vec3(&mut self, what: &str) -> Result<[f64; 3], String> {
        Ok([self.f64(what)?, self.f64(what)?, self.f64(what)?])
    }

    /// A string stored as its 32-bit length and its bytes.
    pub(super) fn string(&mut self, what: &str) -> Result<String, String> {
        let n = self.u32(what)?;
        let bytes = self.take(u64::from(n), what)?;
        Ok(String::from_utf8_lossy(bytes).into_owned())
    }

    /// `words` 64-bit words of a node's bit mask.
    pub(super) fn mask(&mut self, words: usize, what: &str) -> Result<Vec<u64>, String> {
        let bytes = self.take(8 * words as u64, what)?;
        Ok(bytes
            .chunks_exact(8)
            .map(|b| u64::from_le_bytes(b.try_into().expect("8 bytes")))
            .collect())
    }
}

/// Whether bit `i` of a mask is set (bit i of word i / 64, least significant first, as
/// OpenVDB's `NodeMask` stores it).
pub(super) fn bit(mask: &[u64], i: usize) -> bool {
    mask[i / 64] >> (i % 64) & 1 == 1
}

/// How many bits of a mask are set.
pub(super) fn ones(mask: &[u64]) -> usize {
    mask.iter().map(|w| w.count_ones() as usize).sum()
}
