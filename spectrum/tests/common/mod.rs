//! Helpers shared by the integration tests: fixture loading.

#![allow(dead_code)]

use serde_json::Value;

/// Parses a fixture file from `tests/fixtures`.
pub fn fixture(name: &str) -> Value {
    let path = format!("{}/tests/fixtures/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// A JSON number as f64.
pub fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// A JSON array of numbers.
pub fn nums(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(num)
        .collect()
}

/// A JSON 3x3 array.
pub fn mat3(v: &Value) -> [[f64; 3]; 3] {
    let rows: Vec<Vec<f64>> = v.as_array().unwrap().iter().map(nums).collect();
    std::array::from_fn(|r| std::array::from_fn(|c| rows[r][c]))
}

/// Asserts every entry of `got` is within `tolerance` of `expected`.
pub fn assert_mat3_close(
    got: &[[f64; 3]; 3],
    expected: &[[f64; 3]; 3],
    tolerance: f64,
    label: &str,
) {
    for (r, (g_row, e_row)) in got.iter().zip(expected).enumerate() {
        for (c, (g, e)) in g_row.iter().zip(e_row).enumerate() {
            assert!((g - e).abs() < tolerance, "{label}[{r}][{c}]: {g} vs {e}");
        }
    }
}

/// Any f64 at all, with the awkward ones (signed zeros, subnormals, extremes, NaN,
/// infinities) well represented.
pub fn any_f64() -> impl proptest::strategy::Strategy<Value = f64> {
    use proptest::prelude::*;
    prop_oneof![
        Just(0.0),
        Just(-0.0),
        Just(1.0),
        Just(f64::MIN_POSITIVE),
        Just(5e-324),
        Just(f64::MAX),
        Just(f64::MIN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(f64::NAN),
        -1e4..1e5f64,
        any::<f64>(),
    ]
}
