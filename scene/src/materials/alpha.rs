//! glTF's alpha coverage (`alphaMode` MASK and BLEND): where a surface is cut out or
//! partly transparent, rays pass through it. MASK is a cutout at `alphaCutoff`; BLEND is
//! stochastic transparency (a ray passes with probability 1 - alpha: unbiased, and alpha
//! blending as a path tracer can do it without ordering surfaces).

use std::sync::Arc;

use glam::Vec3;

use crate::textures::{FloatTexture, RgbTexture, TexCoords};

/// How alpha decides whether a ray meets the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AlphaMode {
    /// Opaque where alpha >= the cutoff, absent elsewhere.
    Mask {
        /// glTF's `alphaCutoff` (default 0.5).
        cutoff: f32,
    },
    /// Opaque with probability alpha.
    Blend,
}

/// A material's alpha: its mode, baseColorFactor's alpha and the base colour texture's
/// alpha channel (times the factor), times the vertex colour's alpha.
#[derive(Debug, Clone, PartialEq)]
pub struct Alpha {
    /// MASK or BLEND.
    pub mode: AlphaMode,
    /// baseColorFactor's alpha.
    pub factor: f32,
    /// The base colour texture's alpha channel (all three channels hold it), times the
    /// factor.
    pub texture: Option<Arc<RgbTexture>>,
    /// An opacity that varies over the surface and replaces the factor and the texture
    /// (Mitsuba's `mask`), if any.
    pub opacity: Option<Arc<FloatTexture>>,
}

impl Alpha {
    /// The alpha at `at` (texels unfiltered: coverage is decided at a point) with vertex
    /// alpha `vertex`.
    pub fn at(&self, at: &TexCoords, vertex: f32) -> f32 {
        let a = match (&self.opacity, &self.texture) {
            (Some(o), _) => o.value(at.uv[0]),
            (None, Some(t)) => t.sample(at.set(t.set()).0)[0],
            (None, None) => self.factor,
        };
        a * vertex
    }

    /// Whether a ray meets the surface at `at` (vertex alpha `vertex`), `u` uniform in
    /// [0, 1) for BLEND's choice.
    pub fn opaque(&self, at: &TexCoords, vertex: f32, u: f32) -> bool {
        let a = self.at(at, vertex);
        match self.mode {
            AlphaMode::Mask { cutoff } => a >= cutoff,
            AlphaMode::Blend => u < a,
        }
    }
}

/// A number uniform in [0, 1) that depends only on where a ray meets a triangle: BLEND's
/// choice. Camera rays through a pixel meet a surface at different points and from
/// different origins, so the choices average to alpha over samples, while an image stays a
/// function of scene, settings and seed. (The hash is SplitMix64's finalizer over the bits
/// of the ray's origin and direction and the triangle.)
pub(crate) fn blend_number(origin: Vec3, direction: Vec3, triangle: u32) -> f32 {
    let mut h = u64::from(triangle);
    for v in [origin, direction] {
        for c in v.to_array() {
            h = mix(h ^ u64::from(c.to_bits()));
        }
    }
    (mix(h) >> 40) as f32 / (1u64 << 24) as f32
}

fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}
