//! The sheen of `KHR_materials_sheen`: the "Charlie" lobe of Conty Estevez and Kulla,
//! "Production Friendly Microfacet Sheen BRDF" (SIGGRAPH 2017), the back-scattering of a
//! forest of fibres standing on the surface, and its directional albedo tabulated here so
//! that the layers below keep what the sheen does not reflect.

use std::f32::consts::PI;
use std::sync::OnceLock;

use glam::{Vec2, Vec3};
use prism_sampling::warp::cosine_hemisphere;
use prism_spectrum::SampledSpectrum;

use super::table::bilinear;

/// The smallest sheen roughness prism renders: below it the distribution's exponent
/// 1 / r grows past what f32 powers and the albedo table resolve (Filament's cloth model
/// clamps alike).
pub const MIN_SHEEN_ROUGHNESS: f32 = 0.07;

const MU_STEPS: usize = 32;
const ROUGHNESS_STEPS: usize = 32;
/// Cells per side of the cosine-weighted grid each table entry integrates over.
const SIDE: usize = 64;

/// The sheen lobe at one hit: f = colour D(h) / ((1 + Lambda(o) + Lambda(i)) 4 mu_o mu_i),
/// D(h) = (2 + 1/r) sin(theta_h)^(1/r) / (2 pi), Lambda the paper's fitted form, as the
/// extension's implementation notes give them (alpha_g = sheenRoughness, Fresnel 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sheen<const N: usize> {
    /// `sheenColorFactor` (times its texture) per lane, in [0, 1].
    pub color: SampledSpectrum<N>,
    /// `sheenRoughness`, raised to [`MIN_SHEEN_ROUGHNESS`].
    roughness: f32,
}

impl<const N: usize> Sheen<N> {
    /// A sheen of `color` (clamped into [0, 1]) and `roughness` (into
    /// [[`MIN_SHEEN_ROUGHNESS`], 1]).
    pub fn new(color: SampledSpectrum<N>, roughness: f32) -> Self {
        let unit = |v: f32| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        Self {
            color: color.map(unit),
            roughness: unit(roughness).max(MIN_SHEEN_ROUGHNESS),
        }
    }

    /// The roughness the lobe uses.
    pub fn roughness(&self) -> f32 {
        self.roughness
    }

    /// The lobe for a white colour (the colour multiplies it per lane); both directions
    /// above the surface, else 0.
    pub fn f_white(&self, wo: Vec3, wi: Vec3) -> f32 {
        charlie(self.roughness, wo, wi)
    }

    /// Its directional albedo per unit colour at cos(theta) `mu`, from the table.
    pub fn albedo(&self, mu: f32) -> f32 {
        sheen_albedo(mu, self.roughness)
    }
}

fn charlie(r: f32, wo: Vec3, wi: Vec3) -> f32 {
    let (mu_o, mu_i) = (wo.z, wi.z);
    if mu_o <= 0.0 || mu_i <= 0.0 {
        return 0.0;
    }
    let Some(h) = (wo + wi).try_normalize() else {
        return 0.0;
    };
    let sin2 = (1.0 - h.z * h.z).max(0.0);
    let d = (2.0 + 1.0 / r) * sin2.powf(0.5 / r) / (2.0 * PI);
    let v = 1.0 + lambda(mu_o, r) + lambda(mu_i, r);
    let f = d / (v * 4.0 * mu_o * mu_i);
    if f.is_finite() { f } else { 0.0 }
}

/// The fitted exponent of Lambda (the paper's Table 1, interpolated in (1 - r)^2).
fn l(x: f32, r: f32) -> f32 {
    let t = (1.0 - r) * (1.0 - r);
    let mix = |at_one: f32, at_zero: f32| at_one + (at_zero - at_one) * t;
    let a = mix(21.5473, 25.3245);
    let b = mix(3.82987, 3.32435);
    let c = mix(0.19823, 0.16801);
    let d = mix(-1.97760, -1.27393);
    let e = mix(-4.32054, -4.85967);
    a / (1.0 + b * x.powf(c)) + d * x + e
}

fn lambda(mu: f32, r: f32) -> f32 {
    if mu < 0.5 {
        l(mu, r).exp()
    } else {
        (2.0 * l(0.5, r) - l(1.0 - mu, r)).exp()
    }
}

/// The roughness of table column `j`.
fn roughness_at(j: usize) -> f32 {
    MIN_SHEEN_ROUGHNESS + (1.0 - MIN_SHEEN_ROUGHNESS) * j as f32 / (ROUGHNESS_STEPS - 1) as f32
}

/// E(mu, r) = int f_white cos dwi, by a midpoint rule over a 64 x 64 grid of
/// cosine-distributed directions (the integrand is smooth), computed once per process.
fn table() -> &'static [f32] {
    static TABLE: OnceLock<Vec<f32>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut table = vec![0.0f32; MU_STEPS * ROUGHNESS_STEPS];
        for j in 0..ROUGHNESS_STEPS {
            let r = roughness_at(j);
            for i in 0..MU_STEPS {
                let mu = (i as f32 + 0.5) / MU_STEPS as f32;
                let wo = Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
                let mut sum = 0.0f32;
                for a in 0..SIDE {
                    for b in 0..SIDE {
                        let u = Vec2::new(a as f32 + 0.5, b as f32 + 0.5) / SIDE as f32;
                        sum += charlie(r, wo, cosine_hemisphere(u));
                    }
                }
                table[j * MU_STEPS + i] = (PI * sum / (SIDE * SIDE) as f32).clamp(0.0, 1.0);
            }
        }
        table
    })
}

/// E(mu, r), bilinearly interpolated.
fn sheen_albedo(mu: f32, r: f32) -> f32 {
    let x = mu.abs().min(1.0) * MU_STEPS as f32 - 0.5;
    let y = (r - MIN_SHEEN_ROUGHNESS) / (1.0 - MIN_SHEEN_ROUGHNESS) * (ROUGHNESS_STEPS - 1) as f32;
    bilinear(table(), MU_STEPS, x, y)
}
