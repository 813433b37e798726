//! Mitsuba 3's `normalmap` and `bumpmap` BSDF adapters: the shading normal tilted by a
//! texture, the nested BSDF evaluated about the tilted normal, and Mitsuba's two guards
//! around it (src/bsdfs/normalmap.cpp and bumpmap.cpp of mitsuba-renderer/mitsuba3, 3.9).
//!
//! The frame is Mitsuba's shading frame: the interpolated normal n, s along dp/du made
//! perpendicular to n (dp/du of the triangle's positions over its texture coordinates, or
//! of its barycentrics without them), t = n x s. A normal map's texel c is the normal
//! 2c - 1 in (s, t, n); a bump map tilts dp/du and dp/dv by the height's gradient in
//! (u, v) times `scale` and takes their cross product, turned to the geometric normal's
//! side. Either way a tilted normal that faces away from the viewer has its tilt
//! mirrored (`flip_invalid_normals`). Light arriving on the other side of the tilted
//! normal than of n gives nothing, and the BSDF is multiplied by Estevez et al.'s
//! shadowing term (*Ray Tracing Gems*, 2019, ch. 12: `use_shadowing_function`), both
//! applied by [`crate::bsdf::Bsdf::Perturbed`].

use glam::{Vec2, Vec3};

use crate::geometry::unit_or_zero;
use crate::textures::{FloatTexture, Texels};

/// A texture that tilts shading normals.
#[derive(Debug, Clone, PartialEq)]
pub enum Perturbation {
    /// A normal map: three channels, each texel (x, y, z) the normal 2 c - 1 in the
    /// shading frame (`raw` values).
    NormalMap(Texels),
    /// The same normal everywhere (Mitsuba's `rawconstant` texture as a normal map).
    ConstantNormal(Vec3),
    /// A height field whose gradient, times `scale`, tilts the surface.
    Bump {
        /// The heights.
        height: FloatTexture,
        /// Mitsuba's `scale`, the gradient's multiplier.
        scale: f32,
    },
}

/// Where the tilt is computed: a hit's shading and geometric normals, its surface
/// derivatives and texture coordinates, and the direction it is seen from.
#[derive(Debug, Clone, Copy)]
pub struct PerturbationInput {
    /// The interpolated (unit) shading normal.
    pub n: Vec3,
    /// The geometric normal.
    pub geometric: Vec3,
    /// dp/du and dp/dv.
    pub dp_du: Vec3,
    /// dp/dv.
    pub dp_dv: Vec3,
    /// The texture coordinates.
    pub uv: Vec2,
    /// The unit direction towards the viewer.
    pub wi: Vec3,
}

impl Perturbation {
    /// The tilted unit shading normal (world space), or `n` where the frame degenerates.
    pub fn normal(&self, at: &PerturbationInput) -> Vec3 {
        let n = at.n;
        let s = unit_or_zero(at.dp_du - n * n.dot(at.dp_du));
        let s = if s == Vec3::ZERO {
            n.any_orthonormal_vector()
        } else {
            s
        };
        let t = n.cross(s);
        let to_local = |v: Vec3| Vec3::new(v.dot(s), v.dot(t), v.dot(n));
        let local = match self {
            Perturbation::NormalMap(texels) => Vec3::from(texels.rgb(at.uv)) * 2.0 - 1.0,
            Perturbation::ConstantNormal(v) => *v,
            Perturbation::Bump { height, scale } => {
                let g = height.gradient(at.uv) * *scale;
                let du = at.dp_du + n * (g.x - n.dot(at.dp_du));
                let dv = at.dp_dv + n * (g.y - n.dot(at.dp_dv));
                let mut bumped = unit_or_zero(du.cross(dv));
                if bumped.dot(at.geometric) < 0.0 {
                    bumped = -bumped;
                }
                to_local(bumped)
            }
        };
        // Mitsuba's flip_invalid_normals: the tilt mirrored where the viewer is behind it.
        let wi = to_local(at.wi);
        let local = if wi.z * wi.dot(local) <= 0.0 {
            Vec3::new(-local.x, -local.y, local.z)
        } else {
            local
        };
        let local = unit_or_zero(local);
        if local == Vec3::ZERO || !local.is_finite() {
            return n;
        }
        unit_or_zero(s * local.x + t * local.y + n * local.z)
    }
}

#[cfg(test)]
mod tests {
    use glam::Affine2;

    use super::*;
    use crate::textures::{Filter, Wrap};

    fn input(uv: Vec2) -> PerturbationInput {
        PerturbationInput {
            n: Vec3::Z,
            geometric: Vec3::Z,
            dp_du: Vec3::X,
            dp_dv: Vec3::Y,
            uv,
            wi: Vec3::Z,
        }
    }

    /// A flat normal map keeps the normal; a tilted texel tilts it along dp/du; a tilt
    /// away from the viewer is mirrored towards it.
    #[test]
    fn normal_maps_tilt_in_mitsubas_frame() {
        let flat = Perturbation::ConstantNormal(Vec3::Z);
        assert_eq!(flat.normal(&input(Vec2::ZERO)), Vec3::Z);
        let texels = Texels::new(
            2,
            2,
            3,
            [0.8, 0.5, 1.0].repeat(4),
            Wrap::Repeat,
            Filter::Bilinear,
            Affine2::IDENTITY,
        )
        .unwrap();
        let tilted = Perturbation::NormalMap(texels).normal(&input(Vec2::splat(0.5)));
        assert!(tilted.x > 0.4 && tilted.y.abs() < 1e-6, "{tilted}");
        let mut grazing = input(Vec2::ZERO);
        grazing.wi = Vec3::new(-1.0, 0.0, 0.1).normalize();
        let away = Perturbation::ConstantNormal(Vec3::new(0.9, 0.0, 0.1));
        let n = away.normal(&grazing);
        assert!(n.x < 0.0 && n.dot(grazing.wi) > 0.0, "{n}");
    }

    /// A height rising along u tilts the normal against u, by the slope times the scale.
    #[test]
    fn bumps_tilt_against_the_slope() {
        let ramp = Texels::new(
            2,
            1,
            1,
            vec![0.0, 1.0],
            Wrap::Clamp,
            Filter::Bilinear,
            Affine2::IDENTITY,
        )
        .unwrap();
        let bump = Perturbation::Bump {
            height: FloatTexture::Texels(ramp),
            scale: 0.25,
        };
        // The slope is 2 per unit of u; times 0.25, dp/du gains 0.5 along n.
        let n = bump.normal(&input(Vec2::new(0.5, 0.5)));
        let expected = Vec3::new(-0.5, 0.0, 1.0).normalize();
        assert!((n - expected).length() < 1e-6, "{n}");
        use crate::bsdf::shadow_terminator;
        assert_eq!(shadow_terminator(1.0, 0.2), 1.0);
        assert!(shadow_terminator(0.8, 0.1) < shadow_terminator(0.8, 0.9));
        assert!(shadow_terminator(0.8, 0.0).is_finite());
    }
}
