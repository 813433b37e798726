//! The Lambertian vertex written over `Real` (the frame, the sampled direction, the density)
//! gives, lane by lane, what the scalar BSDF and frame give, to the bit: with libm's sine
//! in every lane (`Reals<W, true>`) lanes of paths are the scalar paths.

use glam::{Vec2, Vec3};
use prism_sampling::lanes::Lanes;
use prism_sampling::lanes::real::{Reals, V3};
use prism_scene::bsdf::{Diffuse, lambertian_pdf, lambertian_sample};
use prism_scene::geometry::{Frame, Frames};
use prism_spectrum::SampledSpectrum;
use proptest::prelude::*;

const W: usize = 8;
type Exact = Reals<W, true>;

fn lanes(values: [f32; W]) -> Exact {
    Reals(Lanes(values))
}

fn component() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0f32),
        Just(-0.0f32),
        Just(1.0f32),
        Just(-1.0f32),
        Just(1e-30f32),
        Just(f32::NAN),
        -1.0..1.0f32,
    ]
}

fn normal() -> impl Strategy<Value = Vec3> {
    prop::array::uniform3(component()).prop_map(|a| Vec3::from_array(a).normalize_or(Vec3::Z))
}

fn unit() -> impl Strategy<Value = f32> {
    prop_oneof![
        0.0f32..1.0,
        Just(0.0f32),
        Just(0.5f32),
        Just(1.0f32),
        Just(f32::NAN)
    ]
}

/// Bits with every NaN as one value (Rust leaves a NaN's sign and payload unspecified).
fn bits(v: Vec3) -> [u32; 3] {
    v.to_array()
        .map(|x| if x.is_nan() { u32::MAX } else { x.to_bits() })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2048))]
    #[test]
    fn frames_in_lanes_are_the_scalar_frames(
        n in prop::array::uniform8(normal()),
        v in prop::array::uniform8(prop::array::uniform3(component()).prop_map(Vec3::from_array)),
    ) {
        let frames = Frames::<Exact>::from_normal(V3::from_fn(|i| n[i]));
        let local = frames.to_local(V3::from_fn(|i| v[i]));
        let world = frames.to_world(V3::from_fn(|i| v[i]));
        for i in 0..W {
            let frame = Frame::from_normal(n[i]);
            let (x, y) = n[i].any_orthonormal_pair();
            prop_assert_eq!(bits(frame.x), bits(x));
            prop_assert_eq!(bits(frame.y), bits(y));
            prop_assert_eq!(bits(frames.x.lane(i)), bits(frame.x));
            prop_assert_eq!(bits(frames.y.lane(i)), bits(frame.y));
            prop_assert_eq!(bits(local.lane(i)), bits(frame.to_local(v[i])));
            prop_assert_eq!(bits(world.lane(i)), bits(frame.to_world(v[i])));
        }
    }

    #[test]
    fn lambertian_lanes_are_the_scalar_bsdf(
        wo in prop::array::uniform8(normal()),
        u in prop::array::uniform8((unit(), unit())),
        wi in prop::array::uniform8(normal()),
    ) {
        let bsdf = Diffuse::new(SampledSpectrum::<4>::splat(0.5));
        let wo_z = lanes(wo.map(|w| w.z));
        let (dirs, pdf, exists) = lambertian_sample(wo_z, [lanes(u.map(|p| p.0)), lanes(u.map(|p| p.1))]);
        let pdfs = lambertian_pdf(wo_z, lanes(wi.map(|w| w.z)));
        for i in 0..W {
            let scalar = bsdf.sample(wo[i], Vec2::new(u[i].0, u[i].1));
            prop_assert_eq!(exists.get(i), scalar.is_some());
            if let Some(s) = scalar {
                prop_assert_eq!(bits(dirs.lane(i)), bits(s.wi));
                prop_assert_eq!(pdf.lane(i).to_bits(), s.pdf[0].to_bits());
            }
            let expected = bsdf.pdf(wo[i], wi[i]);
            prop_assert!(pdfs.lane(i).to_bits() == expected.to_bits() || (pdfs.lane(i).is_nan() && expected.is_nan()));
            // The density is the cosine's over pi on wo's side, nothing elsewhere.
            let same_side = wo[i].z * wi[i].z > 0.0;
            let closed_form = if same_side { wi[i].z.abs() / std::f32::consts::PI } else { 0.0 };
            prop_assert!((pdfs.lane(i) - closed_form).abs() <= 1e-7 || !wi[i].is_finite());
        }
    }
}
