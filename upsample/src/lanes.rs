//! Four f32 lanes for the table lookup's interpolation.
//!
//! A table node is 16 bytes (three coefficients and a zero), so one vector operation does
//! the work of three scalar ones. LLVM does not find this on its own: the fourth lane is
//! dead, and its SLP vectorizer scalarized the three live ones (measured: 75 scalar
//! loads, multiplies and adds per lookup). On x86_64 the lanes are therefore SSE
//! registers, which every x86_64 processor has; elsewhere they are plain arrays, which
//! compute the same values lane by lane.

#[cfg(target_arch = "x86_64")]
mod imp {
    #![allow(
        unsafe_code,
        reason = "SSE intrinsics; sound because SSE is in the x86_64 baseline"
    )]

    use std::arch::x86_64::{
        __m128, _mm_add_ps, _mm_loadu_ps, _mm_mul_ps, _mm_set1_ps, _mm_storeu_ps, _mm_sub_ps,
    };

    /// Four f32 lanes in one SSE register.
    #[derive(Clone, Copy)]
    pub(crate) struct F32x4(__m128);

    // SAFETY (every block below): the intrinsics need SSE, which every x86_64 target has
    // (it is part of the architecture's baseline, so `target_feature = "sse"` is always
    // on); the unaligned load and store touch exactly the 16 bytes of a `[f32; 4]`
    // reference.
    impl F32x4 {
        #[inline(always)]
        pub(crate) fn load(values: &[f32; 4]) -> Self {
            Self(unsafe { _mm_loadu_ps(values.as_ptr()) })
        }

        #[inline(always)]
        pub(crate) fn splat(value: f32) -> Self {
            Self(unsafe { _mm_set1_ps(value) })
        }

        #[inline(always)]
        pub(crate) fn to_array(self) -> [f32; 4] {
            let mut out = [0.0; 4];
            unsafe { _mm_storeu_ps(out.as_mut_ptr(), self.0) };
            out
        }

        #[inline(always)]
        pub(crate) fn add(self, other: Self) -> Self {
            Self(unsafe { _mm_add_ps(self.0, other.0) })
        }

        #[inline(always)]
        pub(crate) fn sub(self, other: Self) -> Self {
            Self(unsafe { _mm_sub_ps(self.0, other.0) })
        }

        #[inline(always)]
        pub(crate) fn mul(self, other: Self) -> Self {
            Self(unsafe { _mm_mul_ps(self.0, other.0) })
        }
    }
}

#[cfg(not(target_arch = "x86_64"))]
mod imp {
    /// Four f32 lanes as an array.
    #[derive(Clone, Copy)]
    pub(crate) struct F32x4([f32; 4]);

    impl F32x4 {
        #[inline(always)]
        pub(crate) fn load(values: &[f32; 4]) -> Self {
            Self(*values)
        }

        #[inline(always)]
        pub(crate) fn splat(value: f32) -> Self {
            Self([value; 4])
        }

        #[inline(always)]
        pub(crate) fn to_array(self) -> [f32; 4] {
            self.0
        }

        #[inline(always)]
        pub(crate) fn add(self, other: Self) -> Self {
            Self(std::array::from_fn(|k| self.0[k] + other.0[k]))
        }

        #[inline(always)]
        pub(crate) fn sub(self, other: Self) -> Self {
            Self(std::array::from_fn(|k| self.0[k] - other.0[k]))
        }

        #[inline(always)]
        pub(crate) fn mul(self, other: Self) -> Self {
            Self(std::array::from_fn(|k| self.0[k] * other.0[k]))
        }
    }
}

pub(crate) use imp::F32x4;

#[cfg(test)]
mod tests {
    use super::F32x4;

    /// Lane-wise arithmetic is IEEE single precision in every lane, the same values as
    /// scalar f32 code.
    #[test]
    fn lanes_compute_like_scalars() {
        let (a, b) = ([1.5f32, -2.0, 1e-30, 3.0], [0.25f32, 4.0, 1e30, -0.0]);
        let (va, vb) = (F32x4::load(&a), F32x4::load(&b));
        let expect =
            |f: fn(f32, f32) -> f32| -> [f32; 4] { std::array::from_fn(|k| f(a[k], b[k])) };
        assert_eq!(va.add(vb).to_array(), expect(|x, y| x + y));
        assert_eq!(va.sub(vb).to_array(), expect(|x, y| x - y));
        assert_eq!(va.mul(vb).to_array(), expect(|x, y| x * y));
        assert_eq!(F32x4::splat(0.1).to_array(), [0.1; 4]);
    }
}
