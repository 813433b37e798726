//! The node test eight lanes wide, for CPUs with AVX: one slab test for all eight children
//! of a node where SSE needs two, and the traversals compiled for the x86-64-v3 level
//! (AVX2, BMI, LZCNT, FMA) around it, chosen at run time ([`super::NodeLanes`]).
//!
//! The test performs [`super::traverse::BoxRay`]'s IEEE operations lane for lane: the same
//! subtraction and product per plane, `maxps`/`minps` (which return the second operand
//! where one is NaN) with the same operands in the same order, and the same comparison, so
//! its mask and entry distances are equal to the bit (`scene/tests/node_lanes.rs` compares
//! the traversals' answers).
//! Rust never fuses a product and a sum unasked, so enabling FMA does not change a result.
#![allow(
    unsafe_code,
    reason = "AVX intrinsics, and code compiled for AVX2 entered only where the CPU has it"
)]

use std::arch::x86_64::{
    __m256, _CMP_LE_OS, _mm256_cmp_ps, _mm256_load_ps, _mm256_max_ps, _mm256_min_ps,
    _mm256_movemask_ps, _mm256_mul_ps, _mm256_set1_ps, _mm256_setzero_ps, _mm256_storeu_ps,
    _mm256_sub_ps,
};

use glam::Vec3;

use super::traverse::{NodeTest, Pending, exit_widening, slab_inverse, slab_planes};
use super::wide::{Node, WIDTH, WideBvh};
use crate::geometry::Ray;
use crate::geometry::triangle::{TriangleHit, WatertightRay};

/// Whether the running CPU has what [`WideBvh::closest_avx`] is compiled for.
pub(super) fn available() -> bool {
    std::arch::is_x86_feature_detected!("avx2")
        && std::arch::is_x86_feature_detected!("bmi1")
        && std::arch::is_x86_feature_detected!("bmi2")
        && std::arch::is_x86_feature_detected!("lzcnt")
        && std::arch::is_x86_feature_detected!("fma")
}

/// The slab test eight lanes wide: the ray's set-up.
pub(super) struct BoxRay8 {
    origin: [__m256; 3],
    inverse: [__m256; 3],
    near: [usize; 3],
    far: [usize; 3],
}

impl NodeTest for BoxRay8 {
    #[inline(always)]
    fn new(ray: &Ray) -> Self {
        let inverse = slab_inverse(ray);
        let (near, far) = slab_planes(inverse);
        // SAFETY: only reached from the traversals compiled with AVX, which run only where
        // `available` found it.
        unsafe {
            Self {
                origin: ray.origin.to_array().map(|o| _mm256_set1_ps(o)),
                inverse: inverse.map(|i| _mm256_set1_ps(i)),
                near,
                far,
            }
        }
    }

    #[inline(always)]
    fn enter(&self, node: &Node, t_max: f32) -> (u32, [f32; WIDTH]) {
        // SAFETY: as in `new`; each plane's eight values are 32 contiguous bytes of a node
        // aligned to 32 (`Node` is `repr(C, align(32))`, and a plane is 32 bytes).
        unsafe {
            let t_enter = _mm256_max_ps(
                _mm256_max_ps(
                    self.slab(node, self.near[0], 0),
                    self.slab(node, self.near[1], 1),
                ),
                _mm256_max_ps(self.slab(node, self.near[2], 2), _mm256_setzero_ps()),
            );
            let t_exit = _mm256_min_ps(
                _mm256_min_ps(
                    self.slab(node, self.far[0], 0),
                    self.slab(node, self.far[1], 1),
                ),
                _mm256_min_ps(self.slab(node, self.far[2], 2), _mm256_set1_ps(t_max)),
            );
            let widened = _mm256_mul_ps(t_exit, _mm256_set1_ps(exit_widening()));
            let mask = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OS>(t_enter, widened)) as u32;
            let mut entries = [0.0; WIDTH];
            _mm256_storeu_ps(entries.as_mut_ptr(), t_enter);
            (mask, entries)
        }
    }
}

// Helpers are always-inlined functions, not closures: a closure is compiled without the
// AVX of the function it is written in, and its intrinsics can then stay calls (a trial
// that tested leaf packets in pairs, eight lanes wide, with closures ran much slower).
impl BoxRay8 {
    /// Where the ray crosses plane `plane` (of axis `axis`) of the node's eight boxes.
    #[inline(always)]
    unsafe fn slab(&self, node: &Node, plane: usize, axis: usize) -> __m256 {
        // SAFETY: a plane's eight values are 32 contiguous bytes of a node aligned to 32.
        unsafe {
            let bounds = _mm256_load_ps(node.bounds[plane].as_ptr().cast::<f32>());
            _mm256_mul_ps(_mm256_sub_ps(bounds, self.origin[axis]), self.inverse[axis])
        }
    }
}

impl WideBvh {
    /// [`WideBvh::closest`] with the eight-lane node test.
    ///
    /// # Safety
    /// The CPU must have what [`available`] checks.
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,fma")]
    pub(super) unsafe fn closest_avx(
        &self,
        ray: &Ray,
        watertight: &WatertightRay,
        stack: &mut [Pending],
    ) -> Option<(u32, TriangleHit, [Vec3; 3])> {
        self.closest::<BoxRay8>(ray, watertight, stack)
    }

    /// [`WideBvh::any`] with the eight-lane node test.
    ///
    /// # Safety
    /// The CPU must have what [`available`] checks.
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,fma")]
    pub(super) unsafe fn any_avx(
        &self,
        ray: &Ray,
        watertight: &WatertightRay,
        stack: &mut [Pending],
    ) -> bool {
        self.any::<BoxRay8>(ray, watertight, stack)
    }
}
