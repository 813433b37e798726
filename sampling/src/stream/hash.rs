/// A 64-bit finalizing mix with full avalanche (the SplitMix64 finalizer, Steele, Lea and
/// Flood, OOPSLA 2014, with Stafford's "Mix13" constants).
pub const fn mix64(mut x: u64) -> u64 {
    x ^= x >> 30;
    x = x.wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x ^= x >> 27;
    x = x.wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

/// Hashes a tuple of words into one: each word is mixed into the running state, so
/// `(a, b)` and `(b, a)` differ.
pub(crate) fn hash_words(words: &[u64]) -> u64 {
    words.iter().fold(0x9e37_79b9_7f4a_7c15, |h, &w| {
        mix64(h ^ mix64(w.wrapping_add(0x632b_e59b_d9b4_e019)))
    })
}
