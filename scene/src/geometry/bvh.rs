use std::time::Duration;

use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::builder::build_cwbvh;
use obvhs::ray::{Ray as ObvhsRay, RayHit};

use super::Ray;
use super::triangle::{TriangleHit, WatertightRay};

/// How much effort the BVH build spends for faster traversal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BvhQuality {
    /// obvhs's medium preset: the default, a good trade for scenes rendered once.
    #[default]
    Medium,
    /// obvhs's slow preset (deeper search): for long renders.
    Slow,
}

/// A triangle's bounds, padded outward by a relative margin. obvhs's slab test has no
/// floating-point margin, so a ray through a vertex (a corner of its leaf box) could be
/// culled by rounding: measured, 6 of 8192 rays aimed at the vertices of a closed mesh
/// leaked. The margin (1e-6 of the coordinates' magnitude, far above the slab test's
/// few-ulp error, far below any triangle) keeps such rays inside the box; the exact test
/// still decides every hit.
fn padded_bounds(t: &[Vec3; 3]) -> Aabb {
    let (lo, hi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
    let pad = (lo.abs().max(hi.abs()) + (hi - lo)) * 1e-6 + Vec3::splat(f32::MIN_POSITIVE);
    Aabb::new(Vec3A::from(lo - pad), Vec3A::from(hi + pad))
}

/// The closest hit of a ray in a [`Bvh`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceHit {
    /// Index of the triangle in the slice the BVH was built from.
    pub triangle: usize,
    /// Ray parameter and barycentrics.
    pub hit: TriangleHit,
}

/// A compressed wide BVH (Ylitie, Karras and Laine, "Efficient incoherent ray traversal on
/// GPUs through compressed wide BVHs", HPG 2017) over triangles, built by obvhs, traversed
/// with prism's watertight triangle test.
pub struct Bvh {
    bvh: Option<CwBvh>,
    /// The non-degenerate triangles, in input order, and their input indices.
    triangles: Vec<[Vec3; 3]>,
    original: Vec<usize>,
    skipped: usize,
}

impl Bvh {
    /// A BVH over `triangles`. Degenerate ones (non-finite vertices or zero area) can never
    /// be hit and are left out; [`Bvh::skipped`] counts them.
    pub fn build(triangles: &[[Vec3; 3]], quality: BvhQuality) -> Self {
        let (mut kept, mut original) = (Vec::new(), Vec::new());
        for (i, t) in triangles.iter().enumerate() {
            let finite = t.iter().all(|v| v.is_finite());
            if finite && (t[1] - t[0]).cross(t[2] - t[0]).length_squared() > 0.0 {
                kept.push(*t);
                original.push(i);
            }
        }
        let skipped = triangles.len() - kept.len();
        let bvh = (!kept.is_empty()).then(|| {
            let bounds: Vec<Aabb> = kept.iter().map(padded_bounds).collect();
            let params = match quality {
                BvhQuality::Medium => BvhBuildParams::medium_build(),
                BvhQuality::Slow => BvhBuildParams::slow_build(),
            };
            build_cwbvh(&bounds, params, &mut Duration::default())
        });
        Self {
            bvh,
            triangles: kept,
            original,
            skipped,
        }
    }

    /// Bytes held: BVH nodes and indices, triangles, index map.
    pub fn memory_bytes(&self) -> usize {
        let tree = self.bvh.as_ref().map_or(0, |b| {
            std::mem::size_of_val(b.nodes.as_slice())
                + std::mem::size_of_val(b.primitive_indices.as_slice())
        });
        tree + std::mem::size_of_val(self.triangles.as_slice())
            + std::mem::size_of_val(self.original.as_slice())
    }

    /// Triangles left out as degenerate.
    pub fn skipped(&self) -> usize {
        self.skipped
    }

    /// Triangles in the BVH.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Whether the BVH holds no triangle.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The closest hit along `ray` with 0 < t < `ray.t_max`.
    pub fn intersect(&self, ray: &Ray) -> Option<SurfaceHit> {
        let bvh = self.bvh.as_ref()?;
        let watertight = WatertightRay::new(ray)?;
        let mut best: Option<SurfaceHit> = None;
        let mut hit = RayHit::none();
        bvh.ray_traverse(Self::traversal_ray(ray), &mut hit, |r, id| {
            let index = bvh.primitive_indices[id] as usize;
            match watertight.intersect(self.triangles[index], r.tmax) {
                Some(h) => {
                    best = Some(SurfaceHit {
                        triangle: self.original[index],
                        hit: h,
                    });
                    h.t
                }
                None => f32::INFINITY,
            }
        });
        best
    }

    /// Whether anything lies along `ray` with 0 < t < `ray.t_max` (shadow rays): traversal
    /// stops at the first hit found, whichever it is.
    pub fn occluded(&self, ray: &Ray) -> bool {
        let (Some(bvh), Some(watertight)) = (self.bvh.as_ref(), WatertightRay::new(ray)) else {
            return false;
        };
        !bvh.ray_traverse_miss(Self::traversal_ray(ray), |r, id| {
            let index = bvh.primitive_indices[id] as usize;
            watertight
                .intersect(self.triangles[index], r.tmax)
                .map_or(f32::INFINITY, |h| h.t)
        })
    }

    fn traversal_ray(ray: &Ray) -> ObvhsRay {
        ObvhsRay::new(
            Vec3A::from(ray.origin),
            Vec3A::from(ray.direction),
            0.0,
            ray.t_max,
        )
    }
}
