//! Table lookups of many colours at once.
//!
//! One lookup is a chain of dependent steps (channel, ratios, axis inverses, cells, loads,
//! weights) about a hundred cycles long, which leaves most of a core idle, and the axis
//! inverses are a large part of it (measured). On x86_64 a batch takes four
//! colours through the front of the chain in SSE2 lanes (clamp, largest channel, ratios,
//! axis inverses, cells), a quarter of the instructions per colour, then interpolates
//! each colour as [`CoefficientTable::lookup`] does. Every step is the same IEEE operation
//! on the same values as the single lookup, so the spectra are the same bits (tested).

use crate::model::SigmoidPolynomial;
use crate::table::CoefficientTable;

impl CoefficientTable {
    /// [`CoefficientTable::lookup`] of many colours: the same spectra, in order, faster
    /// per colour (for converting images, textures and lists).
    pub fn lookup_many(&self, rgb: &[[f64; 3]]) -> Vec<SigmoidPolynomial> {
        let mut out = Vec::with_capacity(rgb.len());
        #[cfg(target_arch = "x86_64")]
        {
            let mut groups = rgb.chunks_exact(4);
            for group in &mut groups {
                out.extend(self.lookup_four([group[0], group[1], group[2], group[3]]));
            }
            out.extend(groups.remainder().iter().map(|&c| self.lookup(c)));
        }
        #[cfg(not(target_arch = "x86_64"))]
        out.extend(rgb.iter().map(|&c| self.lookup(c)));
        out
    }

    /// Four lookups with the front of the chain in SSE2 lanes.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    #[allow(unsafe_code, reason = "SSE2 intrinsics, in the x86_64 baseline")]
    fn lookup_four(&self, rgb: [[f64; 3]; 4]) -> [SigmoidPolynomial; 4] {
        use std::arch::x86_64::*;

        use crate::table::BLACK;

        // SAFETY: SSE and SSE2 are part of the x86_64 baseline (always enabled); the
        // intrinsics compute on registers, and the stores write the 16 bytes of local
        // four-lane arrays.
        let (channel, unmultiply, black, ratios) = unsafe {
            let (zero, one) = (_mm_setzero_ps(), _mm_set1_ps(1.0));
            // f64 to f32, then the clamp: the same values as clamping first (rounding is
            // monotonic and 0 and 1 are exact). maxps returns its second operand for NaN,
            // so NaN components count as 0, as in the single lookup.
            let component = |k: usize| {
                let lanes = _mm_setr_ps(
                    rgb[0][k] as f32,
                    rgb[1][k] as f32,
                    rgb[2][k] as f32,
                    rgb[3][k] as f32,
                );
                _mm_min_ps(_mm_max_ps(lanes, zero), one)
            };
            let (r, g, b) = (component(0), component(1), component(2));
            // The single lookup's branches as masks: r if r >= g and r >= b, else g if
            // g >= b, else b; the others in cyclic order after it.
            let red = _mm_and_ps(_mm_cmpge_ps(r, g), _mm_cmpge_ps(r, b));
            let green = _mm_andnot_ps(red, _mm_cmpge_ps(g, b));
            let pick = |if_red, if_green, otherwise| {
                let rest = _mm_or_ps(_mm_and_ps(green, if_green), _mm_andnot_ps(green, otherwise));
                _mm_or_ps(_mm_and_ps(red, if_red), _mm_andnot_ps(red, rest))
            };
            let (z, first, second) = (pick(r, g, b), pick(g, b, r), pick(b, r, g));
            let channel = _mm_sub_epi32(
                _mm_set1_epi32(2),
                _mm_add_epi32(
                    _mm_and_si128(_mm_castps_si128(red), _mm_set1_epi32(2)),
                    _mm_and_si128(_mm_castps_si128(green), _mm_set1_epi32(1)),
                ),
            );
            // Black lanes go through as z = 1 and are replaced at the end.
            let black = _mm_cmpeq_ps(z, zero);
            let divisor = _mm_or_ps(_mm_and_ps(black, one), _mm_andnot_ps(black, z));
            let ratios = [_mm_div_ps(first, divisor), _mm_div_ps(second, divisor), z];
            let unmultiply = _mm_div_ps(one, _mm_sqrt_ps(divisor));
            let mut channel_out = [0i32; 4];
            let mut unmultiply_out = [0f32; 4];
            let mut black_out = [0i32; 4];
            _mm_storeu_si128(channel_out.as_mut_ptr().cast(), channel);
            _mm_storeu_ps(unmultiply_out.as_mut_ptr(), unmultiply);
            _mm_storeu_si128(black_out.as_mut_ptr().cast(), _mm_castps_si128(black));
            (channel_out, unmultiply_out, black_out, ratios)
        };
        // Through u32: a usize-to-f32 conversion takes a branch.
        let (last, scale) = (self.resolution - 2, (self.resolution - 1) as u32 as f32);
        let x = self.axes.ratio.cells_lanes(ratios[0], last, scale);
        let y = self.axes.ratio.cells_lanes(ratios[1], last, scale);
        let u = self.axes.brightness.cells_lanes(ratios[2], last, scale);
        std::array::from_fn(|k| {
            if black[k] != 0 {
                return BLACK;
            }
            let cells = [(x.0[k], x.1[k]), (y.0[k], y.1[k]), (u.0[k], u.1[k])];
            self.interpolate(channel[k] as usize, cells, unmultiply[k])
        })
    }
}
