//! Directions at the extremes for the BSDF property tests.

use glam::Vec3;
use proptest::prelude::*;

/// Unnormalized directions with components at the extremes: zero, a denormal-sized
/// 1e-30 of either sign, exactly +-1 (grazing and normal incidence), NaN, and anywhere in
/// between.
pub fn extreme_direction() -> impl Strategy<Value = Vec3> {
    (
        prop_oneof![
            Just(0.0f32),
            Just(1e-30),
            Just(-1.0),
            Just(1.0),
            -1.0..1.0f32
        ],
        prop_oneof![Just(0.0f32), Just(f32::NAN), -1.0..1.0f32],
        prop_oneof![
            Just(0.0f32),
            Just(1e-30),
            Just(-1e-30),
            Just(1.0),
            -1.0..1.0f32
        ],
    )
        .prop_map(|(x, y, z)| Vec3::new(x, y, z))
}
