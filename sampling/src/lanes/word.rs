//! 32-bit words, one or lanes of them: what hashing and scrambling are written over, so
//! that a scalar stream and a lane stream run the same code.

use super::Lanes;

/// A 32-bit word, or lanes of them, with wrapping arithmetic.
pub trait Word: Copy {
    /// Every lane `x`.
    fn splat(x: u32) -> Self;
    /// Wrapping sum.
    fn add(self, other: Self) -> Self;
    /// Wrapping product.
    fn mul(self, other: Self) -> Self;
    /// Exclusive or.
    fn xor(self, other: Self) -> Self;
    /// Each lane's bits in reverse order.
    fn reverse_bits(self) -> Self;
}

impl Word for u32 {
    #[inline]
    fn splat(x: u32) -> Self {
        x
    }
    #[inline]
    fn add(self, other: Self) -> Self {
        self.wrapping_add(other)
    }
    #[inline]
    fn mul(self, other: Self) -> Self {
        self.wrapping_mul(other)
    }
    #[inline]
    fn xor(self, other: Self) -> Self {
        self ^ other
    }
    #[inline]
    fn reverse_bits(self) -> Self {
        u32::reverse_bits(self)
    }
}

impl<const W: usize> Word for Lanes<u32, W> {
    #[inline]
    fn splat(x: u32) -> Self {
        Lanes::splat(x)
    }
    #[inline]
    fn add(self, other: Self) -> Self {
        self + other
    }
    #[inline]
    fn mul(self, other: Self) -> Self {
        self * other
    }
    #[inline]
    fn xor(self, other: Self) -> Self {
        self ^ other
    }
    #[inline]
    fn reverse_bits(self) -> Self {
        self.map(u32::reverse_bits)
    }
}
