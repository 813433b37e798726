//! The warps written over `Real` give, lane by lane, what the scalar warps give: to the bit
//! where no transcendental function is involved, and within the error of the lanes' sine,
//! arcsine and arctangent (a few f32 epsilons, see `lanes::trig`) elsewhere. A direction
//! or a density that differed by more would be a different estimator, not a rounding.

use glam::{Vec2, Vec3};
use prism_sampling::lanes::Lanes;
use prism_sampling::lanes::real::{Reals, V3};
use prism_sampling::mis::{power_heuristic, power_heuristic_of};
use prism_sampling::warp::{
    cosine_direction, cosine_hemisphere, solid_angle, spherical_triangle,
    spherical_triangle_sample, spherical_triangle_solid_angle,
};
use proptest::prelude::*;

const W: usize = 8;

fn lanes(values: [f32; W]) -> Reals<W> {
    Reals(Lanes(values))
}

fn coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![-10.0f32..10.0, Just(0.0f32), -1e-3f32..1e-3]
}

fn point() -> impl Strategy<Value = Vec3> {
    (coordinate(), coordinate(), coordinate()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn unit() -> impl Strategy<Value = f32> {
    prop_oneof![
        0.0f32..1.0,
        Just(0.0f32),
        Just(1.0f32),
        Just(f32::NAN),
        Just(-0.5f32)
    ]
}

/// The power heuristic as it was written before it went over `Real` (Veach's thesis,
/// section 9.2, with branches): the oracle of the branch-free form.
fn power_heuristic_branching(f: f32, g: f32) -> f32 {
    if f.is_infinite() {
        return 1.0;
    }
    let scale = f.max(g);
    if scale.is_nan() || scale <= 0.0 {
        return 0.0;
    }
    let (f, g) = (f / scale, g / scale);
    let (f, g) = (f * f, g * g);
    if f.is_infinite() {
        return 1.0;
    }
    if g.is_infinite() {
        return 0.0;
    }
    let sum = f + g;
    if sum > 0.0 && f.is_finite() {
        (f / sum).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

fn density() -> impl Strategy<Value = f32> {
    prop_oneof![
        0.0f32..10.0,
        Just(0.0f32),
        Just(-0.0f32),
        Just(f32::INFINITY),
        Just(f32::NEG_INFINITY),
        Just(f32::NAN),
        Just(f32::MAX),
        Just(f32::MIN_POSITIVE / 4.0),
        Just(-1.0f32),
        1e18f32..1e38,
    ]
}

proptest! {
    #[test]
    fn power_heuristic_lanes_are_the_scalar_weight(pairs in prop::array::uniform8((density(), density()))) {
        let w = power_heuristic_of(lanes(pairs.map(|p| p.0)), lanes(pairs.map(|p| p.1)));
        for (i, &(f, g)) in pairs.iter().enumerate() {
            let scalar = power_heuristic(1, f, 1, g);
            let oracle = power_heuristic_branching(f, g);
            prop_assert_eq!(scalar.to_bits(), oracle.to_bits(), "{} {}", f, g);
            prop_assert_eq!(w.lane(i).to_bits(), scalar.to_bits(), "{} {}", f, g);
        }
    }

    #[test]
    fn cosine_lanes_are_the_scalar_warp(u in prop::array::uniform8((unit(), unit()))) {
        let dirs = cosine_direction([lanes(u.map(|p| p.0)), lanes(u.map(|p| p.1))]);
        for (i, &(x, y)) in u.iter().enumerate() {
            let scalar = cosine_hemisphere(Vec2::new(x, y));
            let lane = dirs.lane(i);
            // z = sqrt(1 - x^2 - y^2) magnifies the disk's rounding at the rim: compared
            // squared.
            prop_assert!((lane.truncate() - scalar.truncate()).abs().max_element() <= 4e-7, "{:?} vs {:?}", lane, scalar);
            prop_assert!((lane.z * lane.z - scalar.z * scalar.z).abs() <= 1e-6, "{:?} vs {:?}", lane, scalar);
            prop_assert!(lane.z >= 0.0 && lane.is_finite());
        }
    }

    #[test]
    fn spherical_triangle_lanes_are_the_scalar_warp(
        p in prop::array::uniform8(point()),
        v in prop::array::uniform3(point()),
        u in prop::array::uniform8((unit(), unit())),
    ) {
        let vertices = v.map(|q| V3::from_fn(|_| q));
        let (dirs, pdfs, valid) = spherical_triangle_sample::<Reals<W>>(
            V3::from_fn(|i| p[i]),
            vertices,
            [lanes(u.map(|q| q.0)), lanes(u.map(|q| q.1))],
        );
        let omegas = solid_angle::<Reals<W>>(V3::from_fn(|i| p[i]), vertices);
        for i in 0..W {
            let omega = spherical_triangle_solid_angle(p[i], v);
            prop_assert!((omegas.lane(i) - omega).abs() <= 1e-6 * omega.max(1.0), "{} vs {}", omegas.lane(i), omega);
            let scalar = spherical_triangle(p[i], v, Vec2::new(u[i].0, u[i].1));
            // Only triangles the renderer samples by solid angle (from 0.05 sr: below it the
            // area, a sum of three angles minus pi, cancels to a few digits) and only
            // well-conditioned ones are compared: every two vertices at least
            // 3 degrees from the same or the opposite direction as seen from p (near
            // degenerate ones, p on an edge or a vertex, the scalar warp itself loses its
            // digits; callers sample tiny ones by area).
            let d = v.map(|q| (q - p[i]).normalize_or_zero());
            let separated = [(0, 1), (1, 2), (2, 0)]
                .iter()
                .all(|&(a, b)| d[a].cross(d[b]).length() >= 0.05);
            // Nor the edge u.x = 0 (NaN and negatives clamp to it), where Arvo's sub-area
            // angle cancels (sin(pi + 0)) and the last bit of a sine moves the sample:
            // the exact-lane test below covers those to the bit.
            let interior = (1e-3..=1.0).contains(&u[i].0);
            if !separated || !interior || !(0.05..=6.0).contains(&omega) {
                continue;
            }
            match scalar {
                Some(s) => {
                    prop_assert!(valid.get(i), "lane {} invalid, scalar {:?}", i, s);
                    let d = dirs.lane(i);
                    prop_assert!((d - s.direction).length() <= 2e-3, "{:?} vs {:?}", d, s.direction);
                    prop_assert!((pdfs.lane(i) - s.pdf).abs() <= 1e-4 * s.pdf, "{} vs {}", pdfs.lane(i), s.pdf);
                }
                None => prop_assert!(!valid.get(i), "lane {} valid, scalar not", i),
            }
        }
    }
}

proptest! {
    /// With libm's functions in every lane, the lanes are the scalar warps to the bit,
    /// degenerate triangles included: the generic code is the scalar code.
    #[test]
    fn exact_lanes_are_the_scalar_warps_to_the_bit(
        p in prop::array::uniform8(point()),
        v in prop::array::uniform3(point()),
        u in prop::array::uniform8((unit(), unit())),
    ) {
        type Exact = Reals<W, true>;
        let vertices = v.map(|q| V3::<Exact>::from_fn(|_| q));
        let points = V3::<Exact>::from_fn(|i| p[i]);
        let (us, vs) = (Reals(Lanes(u.map(|q| q.0))), Reals(Lanes(u.map(|q| q.1))));
        let (dirs, pdfs, valid) = spherical_triangle_sample::<Exact>(points, vertices, [us, vs]);
        let omegas = solid_angle::<Exact>(points, vertices);
        let cosines = cosine_direction::<Exact>([us, vs]);
        for i in 0..W {
            let uv = Vec2::new(u[i].0, u[i].1);
            prop_assert_eq!(omegas.lane(i).to_bits(), spherical_triangle_solid_angle(p[i], v).to_bits());
            prop_assert_eq!(cosines.lane(i).to_array().map(f32::to_bits), cosine_hemisphere(uv).to_array().map(f32::to_bits));
            match spherical_triangle(p[i], v, uv) {
                Some(s) => {
                    prop_assert!(valid.get(i));
                    prop_assert_eq!(dirs.lane(i).to_array().map(f32::to_bits), s.direction.to_array().map(f32::to_bits));
                    prop_assert_eq!(pdfs.lane(i).to_bits(), s.pdf.to_bits());
                }
                None => prop_assert!(!valid.get(i)),
            }
        }
    }
}

/// Well inside the range where Arvo's construction is exact in f32, lanes and scalar
/// agree far more closely than the bound above allows for the general case.
#[test]
fn a_light_overhead_samples_alike() {
    let v = [
        Vec3::new(-1.0, 2.0, -1.0),
        Vec3::new(1.0, 2.0, -1.0),
        Vec3::new(0.0, 2.0, 1.0),
    ];
    let p: [Vec3; W] =
        std::array::from_fn(|i| Vec3::new(i as f32 * 0.3 - 1.0, 0.0, 0.1 * i as f32));
    let u: [[f32; 2]; W] =
        std::array::from_fn(|i| [(i as f32 + 0.5) / W as f32, ((i * 5) % W) as f32 / W as f32]);
    let (dirs, pdfs, valid) = spherical_triangle_sample::<Reals<W>>(
        V3::from_fn(|i| p[i]),
        v.map(|q| V3::from_fn(|_| q)),
        [lanes(u.map(|q| q[0])), lanes(u.map(|q| q[1]))],
    );
    for i in 0..W {
        let s = spherical_triangle(p[i], v, Vec2::from(u[i])).expect("a valid sample");
        assert!(valid.get(i));
        assert!(
            (dirs.lane(i) - s.direction).length() < 1e-5,
            "{:?} vs {:?}",
            dirs.lane(i),
            s.direction
        );
        assert!((pdfs.lane(i) - s.pdf).abs() < 1e-5 * s.pdf);
    }
}
