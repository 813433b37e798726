//! Sampling helpers the BSDF tests share.

use glam::{Vec2, Vec3};
use prism_sampling::stream::{IndependentStream, SampleStream};
use prism_scene::bsdf::BsdfSample;

/// The directional albedo from `wo` per lane, by 200,000 samples of `sample(wo, uc, u)`.
pub fn albedo(sample: impl Fn(Vec3, f32, Vec2) -> Option<BsdfSample<4>>, wo: Vec3) -> [f64; 4] {
    let mut stream = IndependentStream::new(61, 0, 0);
    let n = 200_000;
    let mut sum = [0.0f64; 4];
    for _ in 0..n {
        let uc = stream.next_1d();
        if let Some(s) = sample(wo, uc, stream.next_2d()) {
            for (k, a) in sum.iter_mut().enumerate() {
                *a += f64::from(s.f[k] * s.wi.z.abs() / s.pdf[k]);
            }
        }
    }
    sum.map(|a| a / f64::from(n))
}

/// Samples with one 2D point: the lobe choice from the low bits of `u.x`.
#[allow(dead_code)]
pub fn split(u: Vec2) -> (f32, Vec2) {
    (
        (u.x * 4096.0).fract(),
        Vec2::new((u.x * 4096.0).floor() / 4096.0, u.y),
    )
}
