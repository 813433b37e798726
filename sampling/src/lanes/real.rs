//! Real numbers, one or lanes of them, and 3-vectors of them: what the warps a path samples
//! with are written over, so that one path and lanes of them (path reuse's gather, eight
//! first vertices at a time) run the same code.
//!
//! For `f32` every operation is the one glam and the standard library perform (the same
//! IEEE operations in the same order, libm's sine and arcsine), so code written over
//! [`Real`] computes, for one path, the values it computed before it was generic. For
//! [`Lanes`] the arithmetic is lane by lane the same; the transcendental functions are the
//! branch-free ones of [`super::trig`], within a few ulp of libm's, because libm's cannot
//! be vectorized. Branches become masks and selects.

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

use super::Lanes;
use super::trig;

/// An f32 or lanes of them.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// One truth value per lane.
    type Mask: Copy
        + BitAnd<Output = Self::Mask>
        + BitOr<Output = Self::Mask>
        + Not<Output = Self::Mask>;
    /// Every lane `x`.
    fn splat(x: f32) -> Self;
    /// Square root.
    fn sqrt(self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// As `f32::min` (a NaN operand gives the other).
    fn min(self, other: Self) -> Self;
    /// As `f32::max` (a NaN operand gives the other).
    fn max(self, other: Self) -> Self;
    /// self < other.
    fn lt(self, other: Self) -> Self::Mask;
    /// self <= other.
    fn le(self, other: Self) -> Self::Mask;
    /// self > other.
    fn gt(self, other: Self) -> Self::Mask;
    /// self != other (true for NaN).
    fn ne(self, other: Self) -> Self::Mask;
    /// Neither infinite nor NaN.
    fn is_finite(self) -> Self::Mask;
    /// `a` where `mask` holds, else `b`.
    fn select(mask: Self::Mask, a: Self, b: Self) -> Self;
    /// As `f32::signum`.
    fn signum(self) -> Self;
    /// (sin, cos).
    fn sin_cos(self) -> (Self, Self);
    /// asin of the argument clamped to at most 1 (the callers' arguments are >= 0).
    fn asin_min1(self) -> Self;
    /// atan2(self, x).
    fn atan2(self, x: Self) -> Self;
    /// Whether the mask holds in no lane.
    fn none(mask: Self::Mask) -> bool;
}

impl Real for f32 {
    type Mask = bool;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f32::abs(self)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        f32::min(self, other)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        f32::max(self, other)
    }
    #[inline(always)]
    fn lt(self, other: Self) -> bool {
        self < other
    }
    #[inline(always)]
    fn le(self, other: Self) -> bool {
        self <= other
    }
    #[inline(always)]
    fn gt(self, other: Self) -> bool {
        self > other
    }
    #[inline(always)]
    fn ne(self, other: Self) -> bool {
        self != other
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
    #[inline(always)]
    fn select(mask: bool, a: Self, b: Self) -> Self {
        if mask { a } else { b }
    }
    #[inline(always)]
    fn signum(self) -> Self {
        f32::signum(self)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        f32::sin_cos(self)
    }
    #[inline(always)]
    fn asin_min1(self) -> Self {
        self.min(1.0).asin()
    }
    #[inline(always)]
    fn atan2(self, x: Self) -> Self {
        f32::atan2(self, x)
    }
    #[inline(always)]
    fn none(mask: bool) -> bool {
        !mask
    }
}

/// Lanes of truth values, all bits set or none (what a vector comparison yields).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaneMask<const W: usize>(pub Lanes<u32, W>);

impl<const W: usize> LaneMask<W> {
    /// Lane `i` holds where `f(i)` is true.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> bool) -> Self {
        Self(Lanes::from_fn(|i| if f(i) { u32::MAX } else { 0 }))
    }

    /// Lane `i` as a bool.
    #[inline(always)]
    pub fn get(&self, i: usize) -> bool {
        self.0.0[i] != 0
    }
}

impl<const W: usize> BitAnd for LaneMask<W> {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, rhs: Self) -> Self {
        Self(self.0 & rhs.0)
    }
}

impl<const W: usize> BitOr for LaneMask<W> {
    type Output = Self;
    #[inline(always)]
    fn bitor(self, rhs: Self) -> Self {
        Self(self.0.zip(rhs.0, |a, b| a | b))
    }
}

impl<const W: usize> Not for LaneMask<W> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        Self(self.0.map(|a| !a))
    }
}

/// W reals in lanes. `EXACT` chooses libm's sine, arcsine and arctangent lane by lane (the
/// scalar path's values to the bit, for tests that a batch of paths is the scalar paths)
/// instead of the vectorizable ones of [`super::trig`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reals<const W: usize, const EXACT: bool = false>(pub Lanes<f32, W>);

impl<const W: usize, const EXACT: bool> Reals<W, EXACT> {
    /// Lane `i` is `f(i)`.
    #[inline(always)]
    pub fn from_fn(f: impl FnMut(usize) -> f32) -> Self {
        Self(Lanes::from_fn(f))
    }

    /// Lane by lane `f`.
    #[inline(always)]
    pub fn map(self, f: impl FnMut(f32) -> f32) -> Self {
        Self(self.0.map(f))
    }

    #[inline(always)]
    fn zip(self, other: Self, f: impl FnMut(f32, f32) -> f32) -> Self {
        Self(self.0.zip(other.0, f))
    }

    /// Lane `i`.
    #[inline(always)]
    pub fn lane(&self, i: usize) -> f32 {
        self.0.0[i]
    }
}

macro_rules! reals_op {
    ($trait:ident, $method:ident, $op:expr) => {
        impl<const W: usize, const EXACT: bool> $trait for Reals<W, EXACT> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, rhs: Self) -> Self {
                self.zip(rhs, $op)
            }
        }
    };
}

reals_op!(Add, add, |a, b| a + b);
reals_op!(Sub, sub, |a, b| a - b);
reals_op!(Mul, mul, |a, b| a * b);
reals_op!(Div, div, |a, b| a / b);

impl<const W: usize, const EXACT: bool> Neg for Reals<W, EXACT> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(|a| -a)
    }
}

impl<const W: usize, const EXACT: bool> Real for Reals<W, EXACT> {
    type Mask = LaneMask<W>;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        Self(Lanes::splat(x))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        self.map(f32::sqrt)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        self.map(f32::abs)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        self.zip(other, f32::min)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        self.zip(other, f32::max)
    }
    #[inline(always)]
    fn lt(self, other: Self) -> LaneMask<W> {
        LaneMask::from_fn(|i| self.lane(i) < other.lane(i))
    }
    #[inline(always)]
    fn le(self, other: Self) -> LaneMask<W> {
        LaneMask::from_fn(|i| self.lane(i) <= other.lane(i))
    }
    #[inline(always)]
    fn gt(self, other: Self) -> LaneMask<W> {
        LaneMask::from_fn(|i| self.lane(i) > other.lane(i))
    }
    #[inline(always)]
    fn ne(self, other: Self) -> LaneMask<W> {
        LaneMask::from_fn(|i| self.lane(i) != other.lane(i))
    }
    #[inline(always)]
    fn is_finite(self) -> LaneMask<W> {
        // |x| < inf is false for infinities and NaN alike, and is one comparison.
        LaneMask::from_fn(|i| self.lane(i).abs() < f32::INFINITY)
    }
    #[inline(always)]
    fn select(mask: LaneMask<W>, a: Self, b: Self) -> Self {
        Self::from_fn(|i| {
            let m = mask.0.0[i];
            f32::from_bits((a.lane(i).to_bits() & m) | (b.lane(i).to_bits() & !m))
        })
    }
    #[inline(always)]
    fn signum(self) -> Self {
        self.map(f32::signum)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        let both = self.0.map(if EXACT { f32::sin_cos } else { trig::sin_cos });
        (Self(both.map(|p| p.0)), Self(both.map(|p| p.1)))
    }
    #[inline(always)]
    fn asin_min1(self) -> Self {
        if EXACT {
            self.map(|x| x.min(1.0).asin())
        } else {
            self.map(trig::asin)
        }
    }
    #[inline(always)]
    fn atan2(self, x: Self) -> Self {
        self.zip(x, if EXACT { f32::atan2 } else { trig::atan2 })
    }
    #[inline(always)]
    fn none(mask: LaneMask<W>) -> bool {
        mask.0.0.iter().all(|&m| m == 0)
    }
}

/// A 3-vector of reals: one direction or point, or lanes of them (x, y, z each a lane
/// array). Its operations are glam's `Vec3`'s, in the same order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct V3<R> {
    /// The x components.
    pub x: R,
    /// The y components.
    pub y: R,
    /// The z components.
    pub z: R,
}

impl<R: Real> V3<R> {
    /// The vector (x, y, z).
    #[inline(always)]
    pub fn new(x: R, y: R, z: R) -> Self {
        Self { x, y, z }
    }

    /// Zero in every lane.
    #[inline(always)]
    pub fn zero() -> Self {
        Self::splat3(0.0, 0.0, 0.0)
    }

    /// Every lane (x, y, z).
    #[inline(always)]
    pub fn splat3(x: f32, y: f32, z: f32) -> Self {
        Self::new(R::splat(x), R::splat(y), R::splat(z))
    }

    /// Dot product.
    #[inline(always)]
    pub fn dot(self, o: Self) -> R {
        (self.x * o.x) + (self.y * o.y) + (self.z * o.z)
    }

    /// Cross product.
    #[inline(always)]
    pub fn cross(self, o: Self) -> Self {
        Self::new(
            self.y * o.z - o.y * self.z,
            self.z * o.x - o.z * self.x,
            self.x * o.y - o.x * self.y,
        )
    }

    /// Euclidean length.
    #[inline(always)]
    pub fn length(self) -> R {
        self.dot(self).sqrt()
    }

    /// Each component times `s`.
    #[inline(always)]
    pub fn scale(self, s: R) -> Self {
        Self::new(self.x * s, self.y * s, self.z * s)
    }

    /// The unit vector along `self` and where it exists (glam's `try_normalize`): not
    /// where the length is zero or not finite.
    #[inline(always)]
    pub fn try_normalize(self) -> (Self, R::Mask) {
        let rcp = R::splat(1.0) / self.length();
        let ok = rcp.is_finite() & rcp.gt(R::splat(0.0));
        (self.scale(rcp), ok)
    }

    /// The unit vector along `self`, or zero where there is none (glam's
    /// `normalize_or_zero`).
    #[inline(always)]
    pub fn normalize_or_zero(self) -> Self {
        let (unit, ok) = self.try_normalize();
        Self::select(ok, unit, Self::zero())
    }

    /// `a` where `mask` holds, else `b`.
    #[inline(always)]
    pub fn select(mask: R::Mask, a: Self, b: Self) -> Self {
        Self::new(
            R::select(mask, a.x, b.x),
            R::select(mask, a.y, b.y),
            R::select(mask, a.z, b.z),
        )
    }

    /// Whether the vector is zero (every component +-0).
    #[inline(always)]
    pub fn is_zero(self) -> R::Mask {
        let zero = R::splat(0.0);
        !(self.x.ne(zero) | self.y.ne(zero) | self.z.ne(zero))
    }
}

impl<R: Real> Add for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<R: Real> Sub for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<R: Real> Neg for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}

impl From<glam::Vec3> for V3<f32> {
    #[inline(always)]
    fn from(v: glam::Vec3) -> Self {
        Self::new(v.x, v.y, v.z)
    }
}

impl From<V3<f32>> for glam::Vec3 {
    #[inline(always)]
    fn from(v: V3<f32>) -> Self {
        glam::Vec3::new(v.x, v.y, v.z)
    }
}

impl<const W: usize, const EXACT: bool> V3<Reals<W, EXACT>> {
    /// Lane `i` as a glam vector.
    #[inline(always)]
    pub fn lane(&self, i: usize) -> glam::Vec3 {
        glam::Vec3::new(self.x.lane(i), self.y.lane(i), self.z.lane(i))
    }

    /// Lanes of `f(i)`.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> glam::Vec3) -> Self {
        let v: [glam::Vec3; W] = std::array::from_fn(&mut f);
        Self::new(
            Reals::from_fn(|i| v[i].x),
            Reals::from_fn(|i| v[i].y),
            Reals::from_fn(|i| v[i].z),
        )
    }
}
