//! Numbers that vary over a surface as Mitsuba 3's textures give them where a plugin asks
//! for one number (`Texture::eval_1`): a mask's opacity, a bump map's height. A bitmap
//! gives its value (three channels: their luminance), a checkerboard one of two numbers.

use glam::{Affine2, Vec2};

use super::Texels;
use super::pattern::same_halves;

/// A number per point of a surface (by its first texture coordinate set).
#[derive(Debug, Clone, PartialEq)]
pub enum FloatTexture {
    /// The same everywhere.
    Constant(f32),
    /// A bitmap's value, or its luminance.
    Texels(Texels),
    /// Mitsuba's `checkerboard` read as one number.
    Checkerboard {
        /// Where u and v fall in different halves of their unit interval.
        color0: Box<FloatTexture>,
        /// Elsewhere.
        color1: Box<FloatTexture>,
        /// Texture coordinates to the checkerboard's.
        to_uv: Affine2,
    },
}

impl FloatTexture {
    /// The value at `uv` (finite).
    pub fn value(&self, uv: Vec2) -> f32 {
        match self {
            FloatTexture::Constant(v) => *v,
            FloatTexture::Texels(t) => t.scalar(uv),
            // Mitsuba's `eval_1` picks color0 where the halves differ: the opposite of its
            // `eval` (src/textures/checkerboard.cpp), kept so that numbers land where
            // Mitsuba puts them.
            FloatTexture::Checkerboard {
                color0,
                color1,
                to_uv,
            } => {
                if same_halves(*to_uv, uv) {
                    color1.value(uv)
                } else {
                    color0.value(uv)
                }
            }
        }
    }

    /// The gradient of the value in (u, v) at `uv` where it has one (a bitmap's; zero
    /// elsewhere).
    pub fn gradient(&self, uv: Vec2) -> Vec2 {
        match self {
            FloatTexture::Texels(t) => t.gradient(uv),
            _ => Vec2::ZERO,
        }
    }

    /// Whether it is the same everywhere.
    pub fn constant(&self) -> Option<f32> {
        match self {
            FloatTexture::Constant(v) => Some(*v),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checkerboard_numbers_fall_where_mitsuba_puts_them() {
        let board = FloatTexture::Checkerboard {
            color0: Box::new(FloatTexture::Constant(0.05)),
            color1: Box::new(FloatTexture::Constant(0.3)),
            to_uv: Affine2::IDENTITY,
        };
        assert_eq!(board.value(Vec2::new(0.25, 0.25)), 0.3);
        assert_eq!(board.value(Vec2::new(0.75, 0.25)), 0.05);
        assert_eq!(board.gradient(Vec2::ZERO), Vec2::ZERO);
        assert_eq!(board.constant(), None);
    }
}
