//! Lanes compute, lane for lane, what the scalar code computes: the Sobol lane stream is
//! bit-identical to the scalar streams of the same samples, and every lane operation to
//! its scalar operation.

use prism_sampling::lanes::{Lanes, Word, native_width};
use prism_sampling::stream::{SampleStream, SobolLanes, SobolStream};
use proptest::prelude::*;

/// Draws `pattern` (true: a 2D draw, false: 1D) from `dimension` on with W lanes and with
/// W scalar streams; asserts every value equal to the bit.
fn lanes_equal_streams<const W: usize>(
    seed: u64,
    pixel: u64,
    first: u64,
    dimension: u64,
    pattern: &[bool],
) {
    let mut lanes = SobolLanes::<W>::new(seed, pixel, first);
    lanes.set_dimension(dimension);
    let mut streams: Vec<SobolStream> = (0..W as u64)
        .map(|i| {
            let mut s = SobolStream::new(seed, pixel, first.wrapping_add(i));
            s.set_dimension(dimension);
            s
        })
        .collect();
    for &two in pattern {
        if two {
            let [x, y] = lanes.next_2d();
            for (i, s) in streams.iter_mut().enumerate() {
                let p = s.next_2d();
                assert_eq!(
                    (x.0[i].to_bits(), y.0[i].to_bits()),
                    (p.x.to_bits(), p.y.to_bits())
                );
            }
        } else {
            let x = lanes.next_1d();
            for (i, s) in streams.iter_mut().enumerate() {
                assert_eq!(x.0[i].to_bits(), s.next_1d().to_bits());
            }
        }
    }
}

#[test]
fn a_bounce_of_draws_matches_at_every_width() {
    // The integrator's per-bounce pattern: light 2D, lobe 1D, BSDF 2D, roulette 1D.
    let bounce = [true, false, true, false, false, true];
    for (seed, pixel, first, dimension) in [
        (0, 0, 0, 0),
        (7, 42, 64, 3),
        (u64::MAX, 1 << 40, 1000, 1 << 24),
        (3, 5, u64::from(u32::MAX) - 3, 11),
    ] {
        lanes_equal_streams::<1>(seed, pixel, first, dimension, &bounce);
        lanes_equal_streams::<4>(seed, pixel, first, dimension, &bounce);
        lanes_equal_streams::<8>(seed, pixel, first, dimension, &bounce);
        lanes_equal_streams::<16>(seed, pixel, first, dimension, &bounce);
    }
}

#[test]
fn the_native_width_is_one_the_batch_tracer_can_take() {
    let w = native_width();
    assert!([4, 8, 16].contains(&w), "{w}");
    #[cfg(target_arch = "x86_64")]
    {
        let expected = if std::arch::is_x86_feature_detected!("avx512f") {
            16
        } else if std::arch::is_x86_feature_detected!("avx2") {
            8
        } else {
            4
        };
        assert_eq!(w, expected);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn sobol_lanes_are_the_scalar_streams(
        seed in any::<u64>(),
        pixel in any::<u64>(),
        first in any::<u64>(),
        dimension in 0u64..(1 << 30),
        pattern in proptest::collection::vec(any::<bool>(), 1..24),
    ) {
        lanes_equal_streams::<8>(seed, pixel, first, dimension, &pattern);
        lanes_equal_streams::<16>(seed, pixel, first, dimension, &pattern);
    }

    #[test]
    fn split_lanes_are_the_split_streams(
        seed in any::<u64>(),
        pixel in any::<u64>(),
        first in any::<u64>(),
        dimension in 0u64..(1 << 30),
        parts in 1u32..9,
        part_seed in any::<u32>(),
    ) {
        let part = part_seed % parts;
        let mut lanes = SobolLanes::<8>::new(seed, pixel, first);
        lanes.set_dimension(dimension);
        let mut split = lanes.split(part, parts);
        let [x, y] = split.next_2d();
        let z = split.next_1d();
        for i in 0..8u64 {
            let mut stream = SobolStream::new(seed, pixel, first.wrapping_add(i));
            stream.set_dimension(dimension);
            let mut s = stream.split(part, parts);
            let p = s.next_2d();
            prop_assert_eq!((x.0[i as usize].to_bits(), y.0[i as usize].to_bits()), (p.x.to_bits(), p.y.to_bits()));
            prop_assert_eq!(z.0[i as usize].to_bits(), s.next_1d().to_bits());
        }
    }

    #[test]
    fn draws_stay_in_the_unit_interval(seed in any::<u64>(), pixel in any::<u64>(), first in any::<u64>()) {
        let mut lanes = SobolLanes::<16>::new(seed, pixel, first);
        for _ in 0..8 {
            let x = lanes.next_1d();
            let [y, z] = lanes.next_2d();
            for v in x.0.iter().chain(&y.0).chain(&z.0) {
                prop_assert!((0.0..1.0).contains(v));
            }
        }
    }

    #[test]
    fn word_lanes_are_words(a in any::<[u32; 8]>(), b in any::<[u32; 8]>()) {
        let (la, lb) = (Lanes(a), Lanes(b));
        for i in 0..8 {
            prop_assert_eq!(Word::add(la, lb).0[i], Word::add(a[i], b[i]));
            prop_assert_eq!(Word::mul(la, lb).0[i], Word::mul(a[i], b[i]));
            prop_assert_eq!(Word::xor(la, lb).0[i], Word::xor(a[i], b[i]));
            prop_assert_eq!(Word::reverse_bits(la).0[i], a[i].reverse_bits());
            prop_assert_eq!((la - lb).0[i], a[i].wrapping_sub(b[i]));
            prop_assert_eq!((la & lb).0[i], a[i] & b[i]);
            prop_assert_eq!((la >> 7).0[i], a[i] >> 7);
            prop_assert_eq!((la << 5).0[i], a[i] << 5);
        }
    }

    #[test]
    fn float_lanes_are_floats(a in any::<[f32; 8]>(), b in any::<[f32; 8]>()) {
        // Any bits, NaN and infinities included: a lane must round (and propagate) as the
        // scalar operation does.
        let (la, lb) = (Lanes(a), Lanes(b));
        for i in 0..8 {
            let same = |x: f32, y: f32| x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan());
            prop_assert!(same((la + lb).0[i], a[i] + b[i]));
            prop_assert!(same((la - lb).0[i], a[i] - b[i]));
            prop_assert!(same((la * lb).0[i], a[i] * b[i]));
            prop_assert!(same(la.min(lb).0[i], a[i].min(b[i])));
            prop_assert!(same(la.max(lb).0[i], a[i].max(b[i])));
        }
    }
}
