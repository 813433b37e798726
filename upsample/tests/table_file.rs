//! The table file format: round trip, and every kind of damage is a clear error.

use prism_spectrum::color::RgbSpaceId;
use prism_spectrum::illuminant::StandardIlluminant;
use prism_upsample::{CoefficientTable, FitContext};
use proptest::prelude::*;

/// One small table for the whole file (property tests would otherwise refit it per case).
fn small_table() -> (FitContext, CoefficientTable) {
    static TABLE: std::sync::LazyLock<(FitContext, CoefficientTable)> =
        std::sync::LazyLock::new(|| {
            let context = FitContext::new(
                RgbSpaceId::Srgb.space(),
                &StandardIlluminant::D65.spectrum(),
            )
            .unwrap();
            let (table, _) = CoefficientTable::fit(&context, 4, &|_| {}).unwrap();
            (context, table)
        });
    TABLE.clone()
}

#[test]
fn round_trip_is_exact() {
    let (context, table) = small_table();
    let bytes = table.to_bytes();
    let back = CoefficientTable::from_bytes(&bytes).unwrap();
    assert_eq!(back, table);
    assert!(back.space().matches(&context));
    let rec2020 = FitContext::new(
        RgbSpaceId::Rec2020.space(),
        &StandardIlluminant::D65.spectrum(),
    )
    .unwrap();
    assert!(
        !back.space().matches(&rec2020),
        "a table must not pass for another space"
    );
}

#[test]
fn damage_is_detected() {
    let (_, table) = small_table();
    let bytes = table.to_bytes();
    let message = |b: &[u8]| CoefficientTable::from_bytes(b).unwrap_err().to_string();
    assert!(message(&bytes[..bytes.len() - 1]).contains("bytes"));
    assert!(message(&bytes[..5]).contains("truncated"));
    assert!(message(&[]).contains("truncated"));
    let mut extra = bytes.clone();
    extra.push(0);
    assert!(message(&extra).contains("trailing"));
    let mut magic = bytes.clone();
    magic[0] = b'X';
    assert!(message(&magic).contains("magic"));
    // Another version (here the previous one, whose coefficients were normalized).
    let mut version = bytes.clone();
    version[8] = 1;
    assert!(message(&version).contains("version 1"));
    // Flip one bit in the middle of the coefficients: the checksum catches it.
    let mut flipped = bytes.clone();
    let mid = flipped.len() / 2;
    flipped[mid] ^= 0x10;
    assert!(message(&flipped).contains("checksum"));
}

proptest! {
    /// Any corruption of any byte, and any truncation, is an error or (for flips that the
    /// checksum cannot see, which FNV-1a makes vanishingly rare) an identical table: never
    /// a panic or garbage.
    #[test]
    fn arbitrary_damage_never_panics(position in 0usize..10_000, value in any::<u8>(), cut in 0usize..10_000) {
        let (_, table) = small_table();
        let bytes = table.to_bytes();
        let mut damaged = bytes.clone();
        let p = position % damaged.len();
        damaged[p] = value;
        match CoefficientTable::from_bytes(&damaged) {
            Ok(t) => prop_assert!(damaged == bytes && t == table),
            Err(e) => prop_assert!(!e.to_string().is_empty()),
        }
        prop_assert!(CoefficientTable::from_bytes(&bytes[..cut % bytes.len()]).is_err());
    }

    #[test]
    fn random_bytes_are_rejected(bytes in prop::collection::vec(any::<u8>(), 0..300)) {
        prop_assert!(CoefficientTable::from_bytes(&bytes).is_err());
    }
}
