//! Normal textures (glTF `normalTexture`): tangent-space normals, one per texel, that tilt
//! the interpolated shading normal. The tangent frame is glTF's: the tangent from the
//! mesh (or derived from its texture coordinates), the bitangent normal x tangent times
//! the tangent's handedness sign, the normal map's +y pointing up the image.

use glam::{Vec2, Vec3, Vec4};

use crate::geometry::unit_or_zero;
use crate::textures::{RgbTexture, TexCoords};

/// A normal texture and its scale.
#[derive(Debug, Clone, PartialEq)]
pub struct NormalMap {
    texture: RgbTexture,
    scale: f32,
}

impl NormalMap {
    /// `texture` (linear bytes: a texel c encodes the normal 2c - 1) whose normals' x and
    /// y are multiplied by `scale` (glTF's `normalTexture.scale`). Errors for a non-finite
    /// scale.
    pub fn new(texture: RgbTexture, scale: f32) -> Result<Self, crate::LoadError> {
        if !scale.is_finite() {
            return Err(crate::LoadError::Scene(format!(
                "normal texture scale {scale} is not finite"
            )));
        }
        Ok(Self { texture, scale })
    }

    /// The texture coordinate set it reads (its tangents follow that set's u direction).
    pub fn set(&self) -> usize {
        self.texture.set()
    }

    /// The unit shading normal `n` tilted by the texel at `at`, in the frame of `tangent`
    /// (xyz, interpolated; w: the sign of the bitangent). None where the frame or the
    /// tilted normal degenerates (a tangent along `n`, a texel encoding zero): the caller
    /// keeps `n`.
    pub fn perturb(&self, n: Vec3, tangent: Vec4, at: impl Into<TexCoords>) -> Option<Vec3> {
        let (uv, _) = at.into().set(self.texture.set());
        let [x, y, z] = self.texture.sample(uv).map(|c| 2.0 * c - 1.0);
        let t = tangent.truncate();
        let t = unit_or_zero(t - n * n.dot(t));
        if t == Vec3::ZERO {
            return None;
        }
        let sign = if tangent.w < 0.0 { -1.0 } else { 1.0 };
        let b = n.cross(t) * sign;
        let tilted = unit_or_zero(t * (x * self.scale) + b * (y * self.scale) + n * z);
        (tilted != Vec3::ZERO).then_some(tilted)
    }
}

/// A tangent for a triangle from its world-space vertices `p` and texture coordinates
/// `uv` (the direction in which u grows, in the plane), with glTF's handedness: w is 1
/// where normal x tangent points up the image (v decreasing, glTF's v runs down), else
/// -1. Where the texture coordinates do not span the triangle, any tangent of the plane.
#[cfg_attr(not(feature = "gltf"), allow(dead_code))]
pub(crate) fn triangle_tangent(p: [Vec3; 3], uv: [Vec2; 3], normal: Vec3) -> Vec4 {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let (d1, d2) = (uv[1] - uv[0], uv[2] - uv[0]);
    let det = d1.x * d2.y - d2.x * d1.y;
    let dpdu = (e1 * d2.y - e2 * d1.y) / det;
    let dpdv = (e2 * d1.x - e1 * d2.x) / det;
    let t = unit_or_zero(dpdu);
    if t == Vec3::ZERO || !dpdv.is_finite() {
        // Any unit tangent of the plane; of a degenerate triangle (no normal), x.
        let any = if normal == Vec3::ZERO {
            Vec3::X
        } else {
            normal.any_orthonormal_vector()
        };
        return any.extend(1.0);
    }
    let up = -dpdv;
    t.extend(if normal.cross(t).dot(up) < 0.0 {
        -1.0
    } else {
        1.0
    })
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use proptest::prelude::*;

    use super::*;
    use crate::textures::{Encoding, UvTransform, Wrap};

    fn map(texel: [u8; 3], scale: f32) -> NormalMap {
        let texture = RgbTexture::new(
            1,
            1,
            Arc::new(vec![texel]),
            [Wrap::Repeat; 2],
            UvTransform::default(),
            [1.0; 3],
        )
        .unwrap()
        .encoded(Encoding::Linear);
        NormalMap::new(texture, scale).unwrap()
    }

    /// A flat texel (0.5, 0.5, 1) keeps the normal; one tilted toward +x in tangent space
    /// tilts toward the tangent, toward +y toward the bitangent, whose side the handedness
    /// picks; the scale shrinks the tilt.
    #[test]
    fn texels_tilt_the_normal_in_the_tangent_frame() {
        let (n, t) = (Vec3::Z, Vec4::new(1.0, 0.0, 0.0, 1.0));
        let flat = map([128, 128, 255], 1.0).perturb(n, t, Vec2::ZERO).unwrap();
        assert!((flat - n).length() < 1e-2, "{flat}");
        let right = map([255, 128, 128], 1.0).perturb(n, t, Vec2::ZERO).unwrap();
        assert!(right.x > 0.99, "{right}");
        let up = map([128, 255, 128], 1.0).perturb(n, t, Vec2::ZERO).unwrap();
        assert!(up.y > 0.99, "{up}");
        let mirrored = map([128, 255, 128], 1.0)
            .perturb(n, Vec4::new(1.0, 0.0, 0.0, -1.0), Vec2::ZERO)
            .unwrap();
        assert!(mirrored.y < -0.99, "{mirrored}");
        let half = map([255, 128, 255], 0.5).perturb(n, t, Vec2::ZERO).unwrap();
        let full = map([255, 128, 255], 1.0).perturb(n, t, Vec2::ZERO).unwrap();
        assert!(
            half.x > 0.0 && half.x < full.x && half.z > full.z,
            "{half} {full}"
        );
        // A tangent along the normal leaves no frame.
        assert!(
            map([255, 128, 128], 1.0)
                .perturb(n, Vec4::new(0.0, 0.0, 1.0, 1.0), Vec2::ZERO)
                .is_none()
        );
        assert!(NormalMap::new(map([0; 3], 1.0).texture, f32::NAN).is_err());
    }

    fn any_f32() -> impl Strategy<Value = f32> {
        prop_oneof![
            Just(0.0f32),
            Just(-0.0),
            Just(1.0),
            Just(-1.0),
            Just(1e-45),
            Just(3e38),
            Just(f32::INFINITY),
            Just(f32::NAN),
            -2.0..2.0f32,
        ]
    }

    proptest! {
        /// Every input gives a unit normal or None (the caller keeps its own): nothing
        /// non-finite leaves, whatever the tangent, texel or coordinates.
        #[test]
        fn perturbation_is_a_unit_vector_or_none(
            n in prop::array::uniform3(-1.0..1.0f32),
            t in prop::array::uniform4(any_f32()),
            texel in prop::array::uniform3(any::<u8>()),
            scale in prop_oneof![Just(0.0f32), Just(1.0), Just(-3.0), Just(3e38)],
            uv in prop::array::uniform2(any_f32()),
        ) {
            let n = unit_or_zero(Vec3::from(n));
            prop_assume!(n != Vec3::ZERO);
            if let Some(p) = map(texel, scale).perturb(n, Vec4::from(t), Vec2::from(uv)) {
                prop_assert!(p.is_finite() && (p.length() - 1.0).abs() < 1e-4, "{p}");
            }
        }

        /// Derived tangents are unit vectors with a handedness of +-1 for any triangle,
        /// degenerate ones and non-finite texture coordinates included.
        #[test]
        fn derived_tangents_are_unit(
            p in prop::array::uniform9(any_f32()),
            uv in prop::array::uniform6(any_f32()),
        ) {
            let v = [Vec3::new(p[0], p[1], p[2]), Vec3::new(p[3], p[4], p[5]), Vec3::new(p[6], p[7], p[8])];
            let uv = [Vec2::new(uv[0], uv[1]), Vec2::new(uv[2], uv[3]), Vec2::new(uv[4], uv[5])];
            let t = triangle_tangent(v, uv, crate::geometry::triangle_normal(v));
            prop_assert!(t.is_finite() && (t.truncate().length() - 1.0).abs() < 1e-4, "{t}");
            prop_assert!(t.w == 1.0 || t.w == -1.0);
        }
    }

    /// The tangent follows u; the handedness is +1 where v runs down the image as glTF
    /// lays textures out, -1 where the texture is mirrored.
    #[test]
    fn triangle_tangents_follow_u_with_gltf_handedness() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
        // u along +x, v growing along -y (down the image): standard.
        let standard = triangle_tangent(p, [Vec2::ZERO, Vec2::X, -Vec2::Y], Vec3::Z);
        assert_eq!(standard, Vec4::new(1.0, 0.0, 0.0, 1.0));
        // v growing along +y: the image is mirrored vertically.
        let mirrored = triangle_tangent(p, [Vec2::ZERO, Vec2::X, Vec2::Y], Vec3::Z);
        assert_eq!(mirrored, Vec4::new(1.0, 0.0, 0.0, -1.0));
        // No texture coordinates: some unit tangent in the plane.
        let none = triangle_tangent(p, [Vec2::ZERO; 3], Vec3::Z);
        assert!((none.truncate().length() - 1.0).abs() < 1e-6 && none.z.abs() < 1e-6);
    }
}
