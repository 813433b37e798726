//! `EXT_meshopt_compression`: buffer views stored compressed by meshoptimizer's codecs
//! (what gltfpack writes), decoded with the `meshopt` crate into the bytes the rest of the
//! loader reads as any buffer view. The extension's text: each compressed view names its
//! source range (`buffer`, `byteOffset`, `byteLength`), the decoded `byteStride` and
//! `count`, a `mode` (ATTRIBUTES, TRIANGLES or INDICES) and a `filter` (NONE, OCTAHEDRAL,
//! QUATERNION, EXPONENTIAL, COLOR) applied after decoding; the view's own buffer is often a
//! placeholder marked `"fallback": true` with no data.

use serde_json::Value;

use super::LoadError;

const EXTENSION: &str = "EXT_meshopt_compression";

/// Whether `buffer` is a placeholder for decoded data (no bytes of its own).
pub(super) fn is_fallback(buffer: &gltf::Buffer) -> bool {
    buffer
        .extension_value(EXTENSION)
        .and_then(|e| e.get("fallback"))
        .and_then(Value::as_bool)
        .unwrap_or(false)
}

/// Decodes every compressed view of `gltf` into its place in `buffers` (growing a
/// placeholder buffer as needed). Errors name the view.
pub(super) fn decode_views(
    gltf: &gltf::Document,
    buffers: &mut [Vec<u8>],
) -> Result<(), LoadError> {
    for view in gltf.views() {
        let Some(ext) = view.extension_value(EXTENSION) else {
            continue;
        };
        let fail = |why: String| {
            LoadError::Buffer(format!("buffer view {} ({EXTENSION}): {why}", view.index()))
        };
        let number = |key: &str| -> Result<usize, LoadError> {
            ext.get(key)
                .and_then(Value::as_u64)
                .and_then(|v| usize::try_from(v).ok())
                .ok_or_else(|| fail(format!("{key} is missing or not a count")))
        };
        let (source, offset, length) = (
            number("buffer")?,
            ext.get("byteOffset")
                .map_or(Ok(0), |_| number("byteOffset"))?,
            number("byteLength")?,
        );
        let (stride, count) = (number("byteStride")?, number("count")?);
        let mode = ext.get("mode").and_then(Value::as_str).unwrap_or("");
        let filter = ext.get("filter").and_then(Value::as_str).unwrap_or("NONE");
        let encoded = buffers
            .get(source)
            .and_then(|b| b.get(offset..offset.checked_add(length)?))
            .ok_or_else(|| fail("its compressed range runs past its buffer".into()))?;
        let size = stride
            .checked_mul(count)
            .filter(|&s| s <= view.length() && s <= 1 << 31)
            .ok_or_else(|| fail(format!("{count} x {stride} bytes do not fit the view")))?;
        let decoded = decode(encoded, mode, filter, stride, count).map_err(fail)?;
        debug_assert_eq!(decoded.len(), size);
        let target = &mut buffers[view.buffer().index()];
        let end = view.offset() + decoded.len();
        if target.len() < end {
            target.resize(end, 0);
        }
        target[view.offset()..end].copy_from_slice(&decoded);
    }
    Ok(())
}

/// Without the `meshopt` feature, compressed views are refused.
#[cfg(not(feature = "meshopt"))]
fn decode(_: &[u8], _: &str, _: &str, _: usize, _: usize) -> Result<Vec<u8>, String> {
    Err("prism-scene was built without its `meshopt` feature".into())
}

/// Bytes of `count` elements of `stride` bytes decoded from `encoded`.
#[cfg(feature = "meshopt")]
fn decode(
    encoded: &[u8],
    mode: &str,
    filter: &str,
    stride: usize,
    count: usize,
) -> Result<Vec<u8>, String> {
    let error = |e: meshopt::Error| format!("{mode} data does not decode: {e}");
    match mode {
        "ATTRIBUTES" => {
            let mut bytes = vertices(encoded, stride, count).map_err(error)?;
            unfilter(&mut bytes, filter, stride)?;
            Ok(bytes)
        }
        "TRIANGLES" | "INDICES" => {
            if stride != 2 && stride != 4 {
                return Err(format!("indices of {stride} bytes (2 or 4 expected)"));
            }
            // The index codecs do not depend on the index width: decoded as u32, each
            // index keeps its low `stride` bytes.
            let v: Vec<u32> = if mode == "TRIANGLES" {
                meshopt::decode_index_buffer(encoded, count).map_err(error)?
            } else {
                meshopt::decode_index_sequence(encoded, count).map_err(error)?
            };
            Ok(v.iter()
                .flat_map(|i| i.to_le_bytes()[..stride].to_vec())
                .collect())
        }
        other => Err(format!(
            "mode '{other}' is not ATTRIBUTES, TRIANGLES or INDICES"
        )),
    }
}

/// Vertex data of `stride` bytes (a multiple of 4, at most 128) per element.
#[cfg(feature = "meshopt")]
fn vertices(encoded: &[u8], stride: usize, count: usize) -> meshopt::Result<Vec<u8>> {
    macro_rules! by_stride {
        ($($words:literal),*) => {
            match stride {
                $(s if s == 4 * $words => meshopt::decode_vertex_buffer::<[[u8; 4]; $words]>(encoded, count)
                    .map(|v| v.into_iter().flatten().flatten().collect()),)*
                _ => Err(meshopt::Error::Parse(format!("a byte stride of {stride} (a multiple of 4 up to 128 expected)"))),
            }
        };
    }
    by_stride!(
        1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25,
        26, 27, 28, 29, 30, 31, 32
    )
}

/// Undoes a filter in place on decoded vertex bytes.
#[cfg(feature = "meshopt")]
fn unfilter(bytes: &mut [u8], filter: &str, stride: usize) -> Result<(), String> {
    fn as_words<const N: usize>(bytes: &[u8]) -> Vec<[u8; N]> {
        bytes
            .chunks_exact(N)
            .map(|c| c.try_into().unwrap_or([0; N]))
            .collect()
    }
    match (filter, stride) {
        ("NONE", _) => {}
        ("OCTAHEDRAL", 4) => {
            let mut v: Vec<[i8; 4]> = as_words::<4>(bytes)
                .into_iter()
                .map(|w| w.map(|b| b as i8))
                .collect();
            meshopt::decode_filter_oct(&mut v);
            for (out, w) in bytes.chunks_exact_mut(4).zip(v) {
                out.copy_from_slice(&w.map(|b| b as u8));
            }
        }
        ("COLOR", 4) => {
            let mut v: Vec<[u8; 4]> = as_words::<4>(bytes);
            meshopt::decode_filter_color(&mut v);
            for (out, w) in bytes.chunks_exact_mut(4).zip(v) {
                out.copy_from_slice(&w);
            }
        }
        ("OCTAHEDRAL" | "QUATERNION" | "COLOR", 8) => {
            let mut v: Vec<[i16; 4]> = as_words::<8>(bytes)
                .into_iter()
                .map(|w| std::array::from_fn(|k| i16::from_le_bytes([w[2 * k], w[2 * k + 1]])))
                .collect();
            match filter {
                "OCTAHEDRAL" => meshopt::decode_filter_oct(&mut v),
                "QUATERNION" => meshopt::decode_filter_quat(&mut v),
                _ => {
                    let mut u: Vec<[u16; 4]> = v.iter().map(|w| w.map(|c| c as u16)).collect();
                    meshopt::decode_filter_color(&mut u);
                    v = u.iter().map(|w| w.map(|c| c as i16)).collect();
                }
            }
            for (out, w) in bytes.chunks_exact_mut(8).zip(v) {
                for (k, c) in w.iter().enumerate() {
                    out[2 * k..2 * k + 2].copy_from_slice(&c.to_le_bytes());
                }
            }
        }
        ("EXPONENTIAL", s) if s % 4 == 0 => {
            let mut v: Vec<[u32; 1]> = as_words::<4>(bytes)
                .into_iter()
                .map(|w| [u32::from_le_bytes(w)])
                .collect();
            meshopt::decode_filter_exp(&mut v);
            for (out, w) in bytes.chunks_exact_mut(4).zip(v) {
                out.copy_from_slice(&w[0].to_le_bytes());
            }
        }
        (other, s) => {
            return Err(format!(
                "filter '{other}' on {s}-byte elements is not supported"
            ));
        }
    }
    Ok(())
}
