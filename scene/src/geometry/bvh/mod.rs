//! The BVH: obvhs builds a binary tree (PLOC with reinsertion), prism collapses it into an
//! eight-wide tree with runs of triangle packets for leaves and traverses it with SSE, or
//! with AVX where the CPU has it.

#[cfg(target_arch = "x86_64")]
mod avx;
mod packet;
mod traverse;
mod wide;

use std::cell::RefCell;
use std::time::Duration;

use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use obvhs::bvh2::builder::build_bvh2;

use super::Ray;
use super::triangle::{TriangleHit, WatertightRay, triangle_normal};
use traverse::{BoxRay, Pending, stack_size};
use wide::{Source, WideBvh};

/// How much effort the BVH build spends for faster traversal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BvhQuality {
    /// obvhs's medium preset: the default, a good trade for scenes rendered once.
    #[default]
    Medium,
    /// obvhs's slow preset (deeper search): for long renders.
    Slow,
}

/// A triangle's bounds, padded outward by a relative margin. A slab test rounds, so a ray
/// through a vertex (a corner of its leaf box) could be culled by rounding: measured with
/// obvhs's unpadded traversal, 6 of 8192 rays aimed at the vertices of a closed mesh
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
    /// The triangle's vertices, as given to [`Bvh::build`].
    pub vertices: [Vec3; 3],
}

/// How many of a node's eight children one instruction tests: four (SSE, every x86-64
/// CPU, and the portable code elsewhere) or eight (AVX, with the traversal compiled for
/// x86-64-v3). [`Bvh::build`] takes the widest the running CPU has, so one portable binary
/// uses what each host offers; both give the same answers to the bit, so the choice never
/// changes an image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NodeLanes {
    /// Two SSE tests of four boxes.
    Four,
    /// One AVX test of eight boxes.
    Eight,
}

impl NodeLanes {
    /// The widest node test the running CPU can run.
    pub fn widest() -> Self {
        #[cfg(target_arch = "x86_64")]
        if avx::available() {
            return Self::Eight;
        }
        Self::Four
    }
}

/// An eight-wide BVH over triangles with packets of four triangles for leaves, traversed
/// one ray at a time, a node's boxes tested four or eight at a time (Wald, Benthin and
/// Boulos, "Getting rid of packets", RT 2008), every hit decided by prism's watertight
/// triangle test.
pub struct Bvh {
    tree: Option<WideBvh>,
    triangles: usize,
    skipped: usize,
    lanes: NodeLanes,
}

impl Bvh {
    /// A BVH over `triangles`. Degenerate ones (non-finite vertices or zero area) can never
    /// be hit and are left out; [`Bvh::skipped`] counts them.
    pub fn build(triangles: &[[Vec3; 3]], quality: BvhQuality) -> Self {
        let usable =
            |t: &[Vec3; 3]| t.iter().all(|v| v.is_finite()) && triangle_normal(*t) != Vec3::ZERO;
        // The usable triangles and their indices, copied only when some are left out: the
        // copy was a tenth of a large scene's memory peak.
        let filtered: Option<(Vec<[Vec3; 3]>, Vec<u32>)> =
            (!triangles.iter().all(usable)).then(|| {
                (0u32..)
                    .zip(triangles)
                    .filter(|(_, t)| usable(t))
                    .map(|(i, t)| (*t, i))
                    .unzip()
            });
        let (vertices, original) = match &filtered {
            Some((kept, original)) => (kept.as_slice(), Some(original.as_slice())),
            None => (triangles, None),
        };
        let skipped = triangles.len() - vertices.len();
        let tree = (!vertices.is_empty()).then(|| {
            let bounds: Vec<Aabb> = vertices.iter().map(padded_bounds).collect();
            let preset = match quality {
                BvhQuality::Medium => BvhBuildParams::medium_build(),
                BvhQuality::Slow => BvhBuildParams::slow_build(),
            };
            // One triangle per binary leaf: the collapse makes the packets.
            let params = BvhBuildParams {
                max_prims_per_leaf: 1,
                ..preset
            };
            let binary = build_bvh2(&bounds, params, &mut Duration::default());
            drop(bounds);
            WideBvh::collapse(&Source {
                binary: &binary,
                vertices,
                original,
            })
        });
        Self {
            tree,
            triangles: vertices.len(),
            skipped,
            lanes: NodeLanes::widest(),
        }
    }

    /// The node test the traversals use.
    pub fn node_lanes(&self) -> NodeLanes {
        self.lanes
    }

    /// Uses the node test `lanes` where the running CPU has it, else keeps the present one;
    /// returns whether it switched (to compare or time the two).
    pub fn use_node_lanes(&mut self, lanes: NodeLanes) -> bool {
        if lanes == NodeLanes::Eight && NodeLanes::widest() != NodeLanes::Eight {
            return false;
        }
        self.lanes = lanes;
        true
    }

    /// Bytes held: nodes and leaf packets.
    pub fn memory_bytes(&self) -> usize {
        self.tree.as_ref().map_or(0, |t| {
            std::mem::size_of_val(t.nodes.as_slice()) + std::mem::size_of_val(t.packets.as_slice())
        })
    }

    /// Triangles left out as degenerate.
    pub fn skipped(&self) -> usize {
        self.skipped
    }

    /// Triangles in the BVH.
    pub fn len(&self) -> usize {
        self.triangles
    }

    /// Whether the BVH holds no triangle.
    pub fn is_empty(&self) -> bool {
        self.triangles == 0
    }

    /// The closest hit along `ray` with 0 < t < `ray.t_max`.
    pub fn intersect(&self, ray: &Ray) -> Option<SurfaceHit> {
        let tree = self.tree.as_ref()?;
        let watertight = WatertightRay::new(ray)?;
        let found = with_stack(tree, |stack| match self.lanes {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: `lanes` is `Eight` only where the CPU has AVX (`use_node_lanes`).
            #[allow(
                unsafe_code,
                reason = "code compiled for AVX2, entered where the CPU has it"
            )]
            NodeLanes::Eight => unsafe { tree.closest_avx(ray, &watertight, stack) },
            _ => tree.closest::<BoxRay>(ray, &watertight, stack),
        });
        found.map(|(triangle, hit, vertices)| SurfaceHit {
            triangle: triangle as usize,
            hit,
            vertices,
        })
    }

    /// Whether anything lies along `ray` with 0 < t < `ray.t_max` (shadow rays): traversal
    /// stops at the first hit found, whichever it is.
    pub fn occluded(&self, ray: &Ray) -> bool {
        let (Some(tree), Some(watertight)) = (self.tree.as_ref(), WatertightRay::new(ray)) else {
            return false;
        };
        with_stack(tree, |stack| match self.lanes {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: as in `intersect`.
            #[allow(
                unsafe_code,
                reason = "code compiled for AVX2, entered where the CPU has it"
            )]
            NodeLanes::Eight => unsafe { tree.any_avx(ray, &watertight, stack) },
            _ => tree.any::<BoxRay>(ray, &watertight, stack),
        })
    }
}

thread_local! {
    /// Each thread's traversal stack for trees deeper than an inline array serves: kept
    /// between traversals, because clearing a fresh one per ray (a memset of 256-512
    /// bytes) was a noticeable share of the bunny box's instructions. A traversal writes
    /// every entry before it reads it, so what earlier rays left there never matters.
    static STACK: RefCell<Vec<Pending>> = const { RefCell::new(Vec::new()) };
}

/// Runs a traversal with a stack deep enough for `tree`: a small array on the machine
/// stack for shallow trees (clearing 16 entries is a few stores), else the thread's
/// reused stack.
fn with_stack<R>(tree: &WideBvh, traverse: impl FnOnce(&mut [Pending]) -> R) -> R {
    let needed = stack_size(tree.depth);
    if needed <= 16 {
        return traverse(&mut [Pending::default(); 16]);
    }
    STACK.with(|stack| {
        let mut stack = stack.borrow_mut();
        if stack.len() < needed {
            stack.resize(needed, Pending::default());
        }
        traverse(&mut stack[..needed])
    })
}
