//! Mipmaps: a texture's image halved level by level (2 x 2 box filter in linear values,
//! stored 8-bit in the texture's own encoding), so that a lookup whose footprint covers
//! many texels reads their average instead of one of them (*PBR* 4th ed. §10.4.3). Built
//! on a texture's first minified lookup; textures never seen from afar never build one.

use std::sync::Arc;

use super::texture::Encoding;

/// One level of a pyramid: `width` x `height` texels, rows from the top.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Level {
    pub width: u32,
    pub height: u32,
    pub texels: Arc<Vec<[u8; 3]>>,
}

/// The levels below `base`, each half the size of the one above (rounded up; odd edges
/// average what they have), down to 1 x 1.
pub(crate) fn pyramid(base: &Level, encoding: Encoding) -> Vec<Level> {
    let decode = encoding.table();
    let mut levels: Vec<Level> = Vec::new();
    let mut above = base.clone();
    while above.width > 1 || above.height > 1 {
        let (w, h) = (above.width.div_ceil(2), above.height.div_ceil(2));
        let mut texels = Vec::with_capacity(w as usize * h as usize);
        for y in 0..h {
            for x in 0..w {
                let mut sum = [0.0f32; 3];
                let mut n = 0.0f32;
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let (sx, sy) = (2 * x + dx, 2 * y + dy);
                    if sx < above.width && sy < above.height {
                        let t = above.texels[(sy * above.width + sx) as usize];
                        for k in 0..3 {
                            sum[k] += decode[usize::from(t[k])];
                        }
                        n += 1.0;
                    }
                }
                texels.push(sum.map(|s| encode(s / n, encoding)));
            }
        }
        let level = Level {
            width: w,
            height: h,
            texels: Arc::new(texels),
        };
        levels.push(level.clone());
        above = level;
    }
    levels
}

/// A linear value in [0, 1] as the nearest byte of `encoding`.
fn encode(v: f32, encoding: Encoding) -> u8 {
    let v = f64::from(v.clamp(0.0, 1.0));
    let e = match encoding {
        Encoding::Linear => v,
        Encoding::Srgb => prism_spectrum::color::TransferFunction::Srgb.encode(v),
    };
    (e * 255.0).round() as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_average_in_linear_values_down_to_one_texel() {
        // 3 x 2: black and white columns; sRGB 255 and 0 average to linear 0.5.
        let base = Level {
            width: 3,
            height: 2,
            texels: Arc::new(vec![[0; 3], [255; 3], [0; 3], [0; 3], [255; 3], [0; 3]]),
        };
        let levels = pyramid(&base, Encoding::Srgb);
        assert_eq!(
            levels
                .iter()
                .map(|l| (l.width, l.height))
                .collect::<Vec<_>>(),
            vec![(2, 1), (1, 1)]
        );
        // The first texel averages black and white: linear 0.5 is sRGB byte 188.
        assert_eq!(levels[0].texels[0], [188; 3]);
        // The odd column averages only itself.
        assert_eq!(levels[0].texels[1], [0; 3]);
        let linear = pyramid(&base, Encoding::Linear);
        assert_eq!(linear[0].texels[0], [128; 3]);
    }
}
