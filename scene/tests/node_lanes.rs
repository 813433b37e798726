//! The BVH's node test four lanes wide (SSE) and eight wide (AVX, chosen at run time where
//! the CPU has it) give the same answers to the bit, so the width a host runs never
//! changes an image: closest hits (triangle, distance, barycentrics) and shadow-ray
//! answers, over triangle soups deep enough for several levels of nodes and rays with
//! zero, signed-zero, tiny, huge and non-finite components.

use glam::Vec3;
use prism_scene::geometry::{Bvh, BvhQuality, NodeLanes, Ray};
use proptest::prelude::*;

/// Clusters of small triangles and a few large ones, as meshes in a room are.
fn soup(seed: u64, count: usize, spread: f32) -> Vec<[Vec3; 3]> {
    let mut state = seed | 1;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    (0..count)
        .map(|i| {
            let size = if i % 13 == 0 { spread } else { spread * 0.02 };
            let c = (Vec3::new(next(), next(), next()) - 0.5) * spread;
            [0, 1, 2].map(|_| c + (Vec3::new(next(), next(), next()) - 0.5) * size)
        })
        .collect()
}

fn component() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0f32),
        Just(-0.0f32),
        Just(1e-30f32),
        Just(-1e-38f32),
        Just(3.0e38f32),
        Just(f32::INFINITY),
        Just(f32::NAN),
        -1.0..1.0f32,
    ]
}

/// A ray's closest hit (triangle, distance and barycentrics as bits) and shadow answer.
type Answer = (Option<(usize, u32, [u32; 3])>, bool);

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn eight_lane_node_tests_answer_as_four_lane_ones(
        seed in any::<u64>(),
        count in 9usize..400,
        spread in prop_oneof![Just(1e-3f32), Just(2.0f32), Just(1e6f32)],
        origins in prop::collection::vec(prop::array::uniform3(-1.5..1.5f32), 64),
        directions in prop::collection::vec(prop::array::uniform3(component()), 64),
        t_max in prop_oneof![Just(f32::INFINITY), Just(0.0f32), 0.0..3.0f32],
    ) {
        let triangles = soup(seed, count, spread);
        let mut bvh = Bvh::build(&triangles, BvhQuality::Medium);
        let rays: Vec<Ray> = origins
            .iter()
            .zip(&directions)
            .map(|(o, d)| Ray::new(Vec3::from(*o) * spread, Vec3::from(*d), t_max * spread))
            .collect();
        let answers = |bvh: &Bvh| -> Vec<Answer> {
            rays.iter()
                .map(|r| {
                    let hit = bvh.intersect(r).map(|h| {
                        (h.triangle, h.hit.t.to_bits(), h.hit.barycentric.map(f32::to_bits))
                    });
                    (hit, bvh.occluded(r))
                })
                .collect()
        };
        prop_assert!(bvh.use_node_lanes(NodeLanes::Four));
        let four = answers(&bvh);
        if bvh.use_node_lanes(NodeLanes::Eight) {
            prop_assert_eq!(answers(&bvh), four);
        }
    }
}

/// The widest node test is the one a BVH starts with.
#[test]
fn a_bvh_uses_the_widest_node_test_the_cpu_has() {
    let bvh = Bvh::build(&soup(7, 20, 1.0), BvhQuality::Medium);
    assert_eq!(bvh.node_lanes(), NodeLanes::widest());
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        assert_eq!(NodeLanes::widest(), NodeLanes::Eight);
    }
}
