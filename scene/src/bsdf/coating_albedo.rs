//! The directional albedo E(mu, alpha) of a GGX dielectric reflection lobe, tabulated so
//! that a diffuse base can take exactly the energy the coating leaves (Kulla and Conty,
//! "Revisiting physically based shading at Imageworks", SIGGRAPH 2017 course, §2).

use glam::{Vec2, Vec3};

use super::fresnel_dielectric;
use super::microfacet::Ggx;

const MU_STEPS: usize = 32;
const ALPHA_STEPS: usize = 32;
const SAMPLES: usize = 256;

/// E(mu, alpha) on a 32 x 32 grid for one index of refraction, and its cosine-weighted
/// hemispherical average E_avg(alpha) = 2 int E(mu) mu dmu.
#[derive(Debug, Clone, PartialEq)]
pub struct CoatingAlbedo {
    eta: f32,
    table: Vec<f32>,
    average: Vec<f32>,
}

/// The alpha of grid column `j` (alpha from 0.001 to 1, quadratic spacing for the
/// near-smooth end).
fn alpha_at(j: usize) -> f32 {
    let t = j as f32 / (ALPHA_STEPS - 1) as f32;
    (t * t).max(1e-3)
}

impl CoatingAlbedo {
    /// The table for relative index `eta`, by deterministic Monte Carlo (a 16 x 16
    /// stratified grid of visible normals per entry; error ~1e-3).
    pub fn new(eta: f32) -> Self {
        let mut table = vec![0.0f32; MU_STEPS * ALPHA_STEPS];
        for j in 0..ALPHA_STEPS {
            let ggx = Ggx::new(alpha_at(j), alpha_at(j));
            for i in 0..MU_STEPS {
                let mu = ((i as f32 + 0.5) / MU_STEPS as f32).max(1e-3);
                let wo = Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
                let side = (SAMPLES as f32).sqrt() as usize;
                let mut sum = 0.0f32;
                for a in 0..side {
                    for b in 0..side {
                        let u = Vec2::new(
                            (a as f32 + 0.5) / side as f32,
                            (b as f32 + 0.5) / side as f32,
                        );
                        let wm = ggx.sample_visible_normal(wo, u);
                        let wi = 2.0 * wo.dot(wm) * wm - wo;
                        if wi.z > 0.0 {
                            // Weight of VNDF sampling: F G2 / G1(wo).
                            sum += fresnel_dielectric(wo.dot(wm), eta) * ggx.g(wo, wi) / ggx.g1(wo);
                        }
                    }
                }
                table[j * MU_STEPS + i] = (sum / (side * side) as f32).clamp(0.0, 1.0);
            }
        }
        let average = (0..ALPHA_STEPS)
            .map(|j| {
                (0..MU_STEPS)
                    .map(|i| {
                        let mu = (i as f32 + 0.5) / MU_STEPS as f32;
                        2.0 * table[j * MU_STEPS + i] * mu / MU_STEPS as f32
                    })
                    .sum::<f32>()
                    .min(0.999)
            })
            .collect();
        Self {
            eta,
            table,
            average,
        }
    }

    /// The index the table was made for.
    pub fn eta(&self) -> f32 {
        self.eta
    }

    fn alpha_coordinate(alpha: f32) -> (usize, f32) {
        let t = alpha.clamp(1e-3, 1.0).sqrt() * (ALPHA_STEPS - 1) as f32;
        let j = (t as u32 as usize).min(ALPHA_STEPS - 2);
        (j, t - j as f32)
    }

    /// E(mu, alpha), bilinearly interpolated.
    pub fn albedo(&self, mu: f32, alpha: f32) -> f32 {
        let x =
            (mu.abs().clamp(0.0, 1.0) * MU_STEPS as f32 - 0.5).clamp(0.0, (MU_STEPS - 1) as f32);
        let i = (x as u32 as usize).min(MU_STEPS - 2);
        let tx = x - i as f32;
        let (j, ty) = Self::alpha_coordinate(alpha);
        let at = |i: usize, j: usize| self.table[j * MU_STEPS + i];
        let lower = at(i, j) * (1.0 - tx) + at(i + 1, j) * tx;
        let upper = at(i, j + 1) * (1.0 - tx) + at(i + 1, j + 1) * tx;
        lower * (1.0 - ty) + upper * ty
    }

    /// E_avg(alpha).
    pub fn average(&self, alpha: f32) -> f32 {
        let (j, t) = Self::alpha_coordinate(alpha);
        self.average[j] * (1.0 - t) + self.average[j + 1] * t
    }
}
