//! Hits on surfaces under Mitsuba's normal and bump maps: the tilted shading normal (at
//! the intersection, which knows the viewer) and the BSDF about it (at the BSDF, which
//! weighs light by the surface's own normal too). Out of line, so that scenes without
//! them keep their code as it was. See [`crate::materials::Perturbation`].

use glam::Vec3;

use super::{Hit, Scene};
use crate::bsdf::{Bsdf, Perturbed};
use crate::geometry::{Frame, unit_or_zero};
use crate::materials::{Perturbation, PerturbationInput};
use crate::textures::TexCoords;

impl Scene {
    /// The normal or bump map of `hit`'s material, if any.
    pub(super) fn perturbation(&self, hit: &Hit) -> Option<&Perturbation> {
        let material = self.triangle_material[hit.triangle as usize] as usize;
        self.attributes.perturbations.get(material)?.as_deref()
    }

    /// dp/du and dp/dv of `triangle` as Mitsuba's meshes have them: over its texture
    /// coordinates where the scene has some (any pair across the plane where they do not
    /// span it), over its barycentrics otherwise.
    pub(super) fn surface_derivatives(&self, triangle: usize, geometric: Vec3) -> (Vec3, Vec3) {
        let v = self.triangles[triangle];
        let (dp0, dp1) = (v[1] - v[0], v[2] - v[0]);
        let Some(uv) = self.attributes.uvs.get(triangle) else {
            return (dp0, dp1);
        };
        let (duv0, duv1) = (uv[1] - uv[0], uv[2] - uv[0]);
        let det = duv0.x * duv1.y - duv0.y * duv1.x;
        let du = (dp0 * duv1.y - dp1 * duv0.y) / det;
        let dv = (dp1 * duv0.x - dp0 * duv1.x) / det;
        if det == 0.0 || !du.is_finite() || !dv.is_finite() {
            let s = geometric.any_orthonormal_vector();
            return (s, geometric.cross(s));
        }
        (du, dv)
    }

    /// The shading normal `n` of `triangle` tilted by its material's normal or bump map,
    /// seen along `direction`.
    #[inline(never)]
    pub(super) fn perturbed_normal(
        &self,
        triangle: usize,
        n: Vec3,
        geometric: Vec3,
        tex: &TexCoords,
        direction: Vec3,
    ) -> Vec3 {
        let material = self.triangle_material[triangle] as usize;
        let Some(Some(perturbation)) = self.attributes.perturbations.get(material) else {
            return n;
        };
        let (dp_du, dp_dv) = self.surface_derivatives(triangle, geometric);
        let tilted = perturbation.normal(&PerturbationInput {
            n,
            geometric,
            dp_du,
            dp_dv,
            uv: tex.uv[0],
            wi: unit_or_zero(-direction),
        });
        if tilted.is_finite() && tilted != Vec3::ZERO {
            tilted
        } else {
            n
        }
    }

    /// The shading normal `hit` had before its tilt: the interpolated vertex normals on
    /// the geometric normal's side, or the geometric normal.
    fn untilted_normal(&self, hit: &Hit) -> Vec3 {
        let t = hit.triangle as usize;
        let (Some(normals), Some(v)) = (self.attributes.normals.get(t), self.triangles.get(t))
        else {
            return hit.normal;
        };
        let area = |a: Vec3, b: Vec3, c: Vec3| (b - a).cross(c - a).length();
        let total = area(v[0], v[1], v[2]);
        if total.is_nan() || total <= 0.0 {
            return hit.normal;
        }
        let b1 = area(v[0], hit.p, v[2]) / total;
        let b2 = area(v[0], v[1], hit.p) / total;
        let b0 = (1.0 - b1 - b2).max(0.0);
        let s = unit_or_zero(b0 * normals[0] + b1 * normals[1] + b2 * normals[2]);
        match s.dot(hit.normal) {
            d if d > 0.0 => s,
            d if d < 0.0 => -s,
            _ => hit.normal,
        }
    }

    /// `inner`, the BSDF of `hit`'s material about its tilted normal, with Mitsuba's
    /// guards against the surface's own normal.
    #[inline(never)]
    pub(super) fn bsdf_perturbed<'s, const N: usize>(
        &self,
        hit: &Hit,
        inner: Bsdf<'s, N>,
    ) -> Bsdf<'s, N> {
        let frame = Frame::from_normal(hit.shading_normal);
        let n = frame.to_local(self.untilted_normal(hit));
        Bsdf::Perturbed(Box::new(Perturbed { inner, n }))
    }
}
