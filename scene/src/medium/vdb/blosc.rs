//! Blosc 1 buffers, as OpenVDB compresses node values with `COMPRESS_BLOSC` (c-blosc's
//! `blosc_compress_ctx` with LZ4 and byte shuffling, `io/Compression.cc`).
//!
//! A buffer is a 16-byte header (format version, codec version, flags, type size, then
//! the uncompressed size, the block size and the compressed size as 32-bit integers),
//! then either the bytes as they are (flag 0x2, "memcpyed") or one offset per block and
//! the blocks. A block is compressed whole, or as one stream per byte of the type
//! ("split", unless flag 0x10 says not, the block is the last and shorter, or it is small),
//! each stream a 32-bit length and its bytes (stored as they are when the length equals
//! the stream's size). Byte shuffling (flag 0x1) had stored byte k of every value
//! together; it is undone after decompression. The layout follows c-blosc 1.21
//! (`blosc/blosc.c`: `blosc_run_decompression_with_context`, `blosc_d`;
//! `shuffle-generic.h`). LZ4 and zlib streams are read; BloscLZ, Snappy and Zstd, which
//! OpenVDB does not write, are errors that say so.

/// Header flags.
const SHUFFLE: u8 = 0x1;
const MEMCPYED: u8 = 0x2;
const BITSHUFFLE: u8 = 0x4;
const DELTA: u8 = 0x8;
const DONT_SPLIT: u8 = 0x10;
/// Blocks are split by type size only when each stream has at least this many bytes,
/// and for at most this many bytes per value (`MIN_BUFFERSIZE`, `MAX_SPLITS`).
const MIN_SPLIT_STREAM: usize = 128;
const MAX_SPLITS: usize = 16;
const HEADER: usize = 16;

/// Decompresses a Blosc buffer that holds `expected` bytes.
pub(super) fn decompress(src: &[u8], expected: usize) -> Result<Vec<u8>, String> {
    if src.len() < HEADER {
        return Err(format!(
            "a Blosc buffer of {} bytes (its header alone is 16)",
            src.len()
        ));
    }
    let int = |at: usize| i32::from_le_bytes(src[at..at + 4].try_into().expect("4 bytes"));
    let (version, flags, typesize) = (src[0], src[2], usize::from(src[3]));
    let (nbytes, blocksize, cbytes) = (int(4), int(8), int(12));
    if version == 0 || version > 2 {
        return Err(format!(
            "Blosc format version {version} (prism reads Blosc 1, versions 1-2)"
        ));
    }
    if nbytes < 0 || nbytes as usize != expected {
        return Err(format!(
            "a Blosc buffer of {nbytes} bytes where {expected} were expected"
        ));
    }
    if cbytes < HEADER as i32 || cbytes as usize > src.len() {
        return Err(format!(
            "a Blosc buffer says it is {cbytes} bytes long but {} are stored",
            src.len()
        ));
    }
    let src = &src[..cbytes as usize];
    let nbytes = nbytes as usize;
    if nbytes == 0 {
        return Ok(Vec::new());
    }
    if flags & MEMCPYED != 0 {
        return src
            .get(HEADER..HEADER + nbytes)
            .map(<[u8]>::to_vec)
            .ok_or_else(|| "a stored Blosc buffer is shorter than its data".to_string());
    }
    if flags & (BITSHUFFLE | DELTA) != 0 {
        return Err(
            "a Blosc buffer with bit shuffling or delta coding (OpenVDB writes neither)".into(),
        );
    }
    if blocksize <= 0 || typesize == 0 {
        return Err(format!(
            "a Blosc buffer with blocks of {blocksize} bytes of {typesize}-byte values"
        ));
    }
    let codec = Codec::from_flags(flags)?;
    let blocksize = blocksize as usize;
    let blocks = nbytes.div_ceil(blocksize);
    if blocks > (src.len() - HEADER) / 4 {
        return Err("a Blosc buffer too short for its block offsets".into());
    }
    let mut out = vec![0u8; nbytes];
    let mut scratch = vec![0u8; blocksize];
    for (b, dest) in out.chunks_mut(blocksize).enumerate() {
        let start = int(HEADER + 4 * b);
        let last_short = dest.len() < blocksize;
        let shuffled = flags & SHUFFLE != 0 && typesize > 1;
        let streams = if flags & DONT_SPLIT == 0
            && typesize <= MAX_SPLITS
            && dest.len() / typesize >= MIN_SPLIT_STREAM
            && !last_short
        {
            typesize
        } else {
            1
        };
        let target: &mut [u8] = if shuffled {
            &mut scratch[..dest.len()]
        } else {
            &mut *dest
        };
        decompress_block(src, start, streams, codec, target)?;
        if shuffled {
            unshuffle(&scratch[..dest.len()], typesize, dest);
        }
    }
    Ok(out)
}

/// The codec in bits 5-7 of the flags.
#[derive(Debug, Clone, Copy)]
enum Codec {
    Lz4,
    Zlib,
}

impl Codec {
    fn from_flags(flags: u8) -> Result<Self, String> {
        match flags >> 5 {
            1 => Ok(Self::Lz4),
            3 => Ok(Self::Zlib),
            0 => {
                Err("Blosc's BloscLZ codec (prism reads LZ4 and zlib, which OpenVDB writes)".into())
            }
            2 => {
                Err("Blosc's Snappy codec (prism reads LZ4 and zlib, which OpenVDB writes)".into())
            }
            4 => Err("Blosc's Zstd codec (prism reads LZ4 and zlib, which OpenVDB writes)".into()),
            c => Err(format!("Blosc codec {c} is unknown")),
        }
    }
}

/// Fills `dest` from the block at `start` of `src`, stored as `streams` equal streams.
fn decompress_block(
    src: &[u8],
    start: i32,
    streams: usize,
    codec: Codec,
    dest: &mut [u8],
) -> Result<(), String> {
    let mut at = usize::try_from(start).map_err(|_| "a negative Blosc block offset".to_string())?;
    let size = dest.len() / streams;
    for stream in dest.chunks_mut(size).take(streams) {
        let length = src
            .get(at..at + 4)
            .map(|b| i32::from_le_bytes(b.try_into().expect("4 bytes")))
            .ok_or("a Blosc block runs past its buffer")?;
        at += 4;
        let data = usize::try_from(length)
            .ok()
            .and_then(|n| src.get(at..at + n))
            .ok_or("a Blosc stream runs past its buffer")?;
        at += data.len();
        if data.len() == stream.len() {
            stream.copy_from_slice(data);
            continue;
        }
        let written = match codec {
            Codec::Lz4 => lz4_flex::block::decompress_into(data, stream)
                .map_err(|e| format!("a Blosc LZ4 stream: {e}"))?,
            Codec::Zlib => {
                let bytes =
                    miniz_oxide::inflate::decompress_to_vec_zlib_with_limit(data, stream.len())
                        .map_err(|e| format!("a Blosc zlib stream: {e:?}"))?;
                stream[..bytes.len()].copy_from_slice(&bytes);
                bytes.len()
            }
        };
        if written != stream.len() {
            return Err(format!(
                "a Blosc stream gave {written} bytes where {} were expected",
                stream.len()
            ));
        }
    }
    Ok(())
}

/// Undoes byte shuffling: byte `k` of value `i` was stored at `k * n + i` (n values);
/// bytes past the last whole value were stored as they are.
fn unshuffle(src: &[u8], typesize: usize, dest: &mut [u8]) {
    let n = src.len() / typesize;
    for i in 0..n {
        for k in 0..typesize {
            dest[i * typesize + k] = src[k * n + i];
        }
    }
    let whole = n * typesize;
    dest[whole..].copy_from_slice(&src[whole..]);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A buffer of one block of 256 floats, shuffled and split into 4 streams stored as they are.
    #[test]
    fn stored_streams_unshuffle() {
        let values: Vec<f32> = (0..256).map(|i| i as f32 * 0.25).collect();
        let plain: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let n = values.len();
        let mut shuffled = vec![0u8; plain.len()];
        for i in 0..n {
            for k in 0..4 {
                shuffled[k * n + i] = plain[i * 4 + k];
            }
        }
        let mut buffer = vec![2, 1, SHUFFLE | (1 << 5), 4];
        let total = HEADER + 4 + 4 * (4 + n);
        for v in [
            plain.len() as i32,
            plain.len() as i32,
            total as i32,
            (HEADER + 4) as i32,
        ] {
            buffer.extend_from_slice(&v.to_le_bytes());
        }
        for stream in shuffled.chunks(n) {
            buffer.extend_from_slice(&(n as i32).to_le_bytes());
            buffer.extend_from_slice(stream);
        }
        assert_eq!(decompress(&buffer, plain.len()).unwrap(), plain);
        assert!(decompress(&buffer[..total - 1], plain.len()).is_err());
        assert!(decompress(&buffer, plain.len() + 4).is_err());
    }
}
