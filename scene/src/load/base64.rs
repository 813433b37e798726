//! Decoding of base64 `data:` URIs (RFC 4648 §4), the only place glTF embeds buffers in
//! JSON.

/// The bytes of standard base64 text (padding optional, no whitespace), or None.
pub fn decode(text: &str) -> Option<Vec<u8>> {
    let value = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return None,
        } as u32)
    };
    let bytes = text.trim_end_matches('=').as_bytes();
    if bytes.len() % 4 == 1 {
        return None;
    }
    let mut out = Vec::with_capacity(bytes.len() * 3 / 4);
    for chunk in bytes.chunks(4) {
        let mut n = 0u32;
        for (i, &c) in chunk.iter().enumerate() {
            n |= value(c)? << (18 - 6 * i);
        }
        let produced = chunk.len() - 1;
        out.extend_from_slice(&n.to_be_bytes()[1..1 + produced]);
    }
    Some(out)
}

/// The bytes a URI names: a base64 `data:` URI decoded here, anything else through
/// `resolve` (a path relative to the scene file).
pub(crate) fn uri_bytes(uri: &str, resolve: &super::Resolver) -> Result<Vec<u8>, String> {
    match uri.strip_prefix("data:") {
        Some(rest) => {
            let payload = rest
                .split_once(";base64,")
                .map(|(_, p)| p)
                .ok_or("only base64 data URIs are supported")?;
            decode(payload).ok_or_else(|| "malformed base64 data URI".into())
        }
        None => resolve(uri).map_err(|e| format!("'{uri}': {e}")),
    }
}

#[cfg(test)]
mod tests {
    use super::decode;

    /// RFC 4648 §10 test vectors.
    #[test]
    fn rfc_4648_vectors() {
        for (plain, encoded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(decode(encoded).unwrap(), plain.as_bytes());
        }
        assert!(decode("Zm9v!").is_none());
        assert!(decode("Z").is_none());
    }
}
