//! Lanes: W values handled as one. Path reuse's gather (the integrator's
//! `reuse/gather.rs`) connects eight first vertices of a tile at a time in them, through
//! [`real::Real`]; the Lambertian sampling, shading frames and Russian roulette the path
//! tracer runs for one `f32` are written once over the same trait, so that they serve
//! lanes as well; and `SobolLanes` draws W consecutive samples at once over [`Word`].
//!
//! A `Lanes<T, W>` is a plain aligned array whose operations are lane-by-lane loops that
//! the compiler turns into SIMD instructions where the target has them; every operation
//! is, lane for lane, the scalar operation of the same name, so code written over
//! [`Word`] (or [`real::Real`]) computes bit-identical values for one `u32` (or `f32`)
//! and for lanes of them. [`native_width`] is the width the running CPU handles in one register.

pub mod real;
pub mod trig;
mod word;

pub use word::Word;

use std::ops::{Add, BitAnd, BitXor, Mul, Shl, Shr, Sub};

/// `W` values of `T`, one per lane, aligned for the widest vector registers.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub struct Lanes<T, const W: usize>(pub [T; W]);

impl<T: Copy, const W: usize> Lanes<T, W> {
    /// Every lane `value`.
    #[inline]
    pub fn splat(value: T) -> Self {
        Self([value; W])
    }

    /// Lane `i` is `f(i)`.
    #[inline]
    pub fn from_fn(f: impl FnMut(usize) -> T) -> Self {
        Self(std::array::from_fn(f))
    }

    /// Lane by lane `f`.
    #[inline]
    pub fn map<U: Copy>(self, mut f: impl FnMut(T) -> U) -> Lanes<U, W> {
        Lanes(std::array::from_fn(|i| f(self.0[i])))
    }

    /// Lane by lane `f` of `self` and `other`.
    #[inline]
    pub fn zip<U: Copy, V: Copy>(
        self,
        other: Lanes<U, W>,
        mut f: impl FnMut(T, U) -> V,
    ) -> Lanes<V, W> {
        Lanes(std::array::from_fn(|i| f(self.0[i], other.0[i])))
    }
}

macro_rules! lane_op {
    ($trait:ident, $method:ident, $t:ty, $op:expr) => {
        impl<const W: usize> $trait for Lanes<$t, W> {
            type Output = Self;
            #[inline]
            fn $method(self, rhs: Self) -> Self {
                self.zip(rhs, $op)
            }
        }
    };
}

lane_op!(Add, add, f32, |a, b| a + b);
lane_op!(Sub, sub, f32, |a, b| a - b);
lane_op!(Mul, mul, f32, |a, b| a * b);
lane_op!(Add, add, u32, u32::wrapping_add);
lane_op!(Sub, sub, u32, u32::wrapping_sub);
lane_op!(Mul, mul, u32, u32::wrapping_mul);
lane_op!(BitXor, bitxor, u32, |a, b| a ^ b);
lane_op!(BitAnd, bitand, u32, |a, b| a & b);

impl<const W: usize> Shr<u32> for Lanes<u32, W> {
    type Output = Self;
    #[inline]
    fn shr(self, bits: u32) -> Self {
        self.map(|a| a >> bits)
    }
}

impl<const W: usize> Shl<u32> for Lanes<u32, W> {
    type Output = Self;
    #[inline]
    fn shl(self, bits: u32) -> Self {
        self.map(|a| a << bits)
    }
}

impl<const W: usize> Lanes<f32, W> {
    /// Lane by lane minimum (as `f32::min`).
    #[inline]
    pub fn min(self, other: Self) -> Self {
        self.zip(other, f32::min)
    }

    /// Lane by lane maximum (as `f32::max`).
    #[inline]
    pub fn max(self, other: Self) -> Self {
        self.zip(other, f32::max)
    }
}

/// The widest lanes of 32-bit values the running CPU handles in one register: 16 with
/// AVX-512, 8 with AVX2, else 4 (SSE2, NEON), as Dr.Jit chooses its LLVM backend's width.
/// A portable build asks at run time, so one binary uses what each host has.
pub fn native_width() -> usize {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx512f") {
            return 16;
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            return 8;
        }
    }
    4
}
