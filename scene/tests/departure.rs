//! `Hit::departure` precomputes the two origins `Hit::spawn_to` chooses between: its rays
//! must be `spawn_to`'s to the bit, for any hit, direction and distance (NaN for NaN).

use glam::{Vec3, Vec4};
use prism_scene::world::{Hit, TexCoords};
use proptest::prelude::*;

fn component() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0f32),
        Just(-0.0f32),
        Just(1e-30f32),
        Just(1e30f32),
        Just(f32::INFINITY),
        Just(f32::NAN),
        -10.0..10.0f32,
        -1e6..1e6f32,
    ]
}

fn vector() -> impl Strategy<Value = Vec3> {
    prop::array::uniform3(component()).prop_map(Vec3::from_array)
}

/// The bits of each component, NaN as one value: Rust leaves a NaN's sign and payload
/// unspecified, so two NaNs computed alike may differ in them.
fn bits(v: Vec3) -> [u32; 3] {
    v.to_array().map(scalar_bits)
}

fn scalar_bits(x: f32) -> u32 {
    if x.is_nan() { u32::MAX } else { x.to_bits() }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4096))]
    #[test]
    fn rays_are_spawn_to_s(
        p in vector(),
        error in prop::array::uniform3(prop_oneof![Just(0.0f32), 0.0..1e-3f32]).prop_map(Vec3::from_array),
        normal in prop_oneof![vector(), vector().prop_map(|v| v.normalize_or_zero())],
        direction in prop_oneof![vector(), vector().prop_map(|v| v.normalize_or_zero())],
        distance in prop_oneof![component(), 0.0..100.0f32],
    ) {
        let hit = Hit {
            p,
            error,
            normal,
            shading_normal: normal,
            tex: TexCoords::default(),
            color: Vec4::ONE,
            t: 1.0,
            triangle: 0,
        };
        let expected = hit.spawn_to(direction, distance);
        let got = hit.departure().ray_to(direction, distance);
        prop_assert_eq!(bits(got.origin), bits(expected.origin));
        prop_assert_eq!(bits(got.direction), bits(expected.direction));
        prop_assert_eq!(scalar_bits(got.t_max), scalar_bits(expected.t_max));
    }
}
