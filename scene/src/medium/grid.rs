//! A scalar field on a regular grid of voxels (a smoke's density, a flame's temperature),
//! looked up trilinearly, and the coarse grid of its maxima that tracking steps through.
//!
//! Values sit at voxel centres and are blended trilinearly (or taken from the nearest
//! voxel: [`Filter`]), clamped to the nearest voxel at the grid's faces, and the field is 0
//! outside its box (as Mitsuba 3's `gridvolume` with clamped wrapping inside the box a
//! heterogeneous medium clips to); [`Grid::lookup_clamped`] extends the faces' values
//! outwards instead, as Mitsuba's clamped wrapping does everywhere. The majorant grid follows pbrt-v4
//! (*PBR* 4th ed. §11.4.3, `MajorantGrid`): a coarse grid over the same box whose every
//! cell bounds the field over the cell, so that tracking through a wisp of smoke in a big
//! box draws distances against the wisp's own density, not the densest voxel's.

use glam::{UVec3, Vec3};

/// The most cells a majorant grid has along an axis.
const MAJORANT_RESOLUTION: u32 = 16;

/// How a grid blends its voxels between their centres (Mitsuba's `filter_type`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Filter {
    /// Trilinear between the eight nearest voxel centres.
    #[default]
    Trilinear,
    /// The value of the voxel the point is in.
    Nearest,
}

/// A scalar field on a regular grid over an axis-aligned box.
#[derive(Debug, Clone)]
pub struct Grid {
    resolution: UVec3,
    min: Vec3,
    max: Vec3,
    /// Values, x fastest then y then z.
    values: Vec<f32>,
    majorants: Majorants,
    filter: Filter,
}

/// The voxels that blend into the field at a point and their weights (which sum to 1):
/// eight for trilinear filtering, one (the rest weightless) for the nearest voxel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stencil {
    /// Indices into the voxels, x fastest then y then z.
    pub voxels: [u32; 8],
    /// Each voxel's weight.
    pub weights: [f32; 8],
}

/// The maxima of a grid's field over the cells of a coarse grid on the same box.
#[derive(Debug, Clone)]
struct Majorants {
    resolution: UVec3,
    values: Vec<f32>,
}

/// A stretch of a ray (ray parameters `t0` to `t1`) over which the field is at most
/// `bound`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span {
    /// Where it starts.
    pub t0: f32,
    /// Where it ends.
    pub t1: f32,
    /// The field's bound over it.
    pub bound: f32,
}

impl Grid {
    /// A grid of `resolution` voxels (each at least 1) over the box `min`-`max` (min < max
    /// on every axis, finite), its values x fastest: they must be finite and >= 0, and as
    /// many as the voxels.
    pub fn new(resolution: UVec3, min: Vec3, max: Vec3, values: Vec<f32>) -> Result<Self, String> {
        if resolution.min_element() == 0 {
            return Err(format!("a grid of {resolution} voxels is empty"));
        }
        let count = resolution.x as u64 * resolution.y as u64 * resolution.z as u64;
        if count != values.len() as u64 {
            return Err(format!(
                "{} values for a grid of {} x {} x {} voxels",
                values.len(),
                resolution.x,
                resolution.y,
                resolution.z
            ));
        }
        if !min.is_finite() || !max.is_finite() || !min.cmplt(max).all() {
            return Err(format!(
                "the grid's box {min} - {max} is empty or not finite"
            ));
        }
        if let Some((i, v)) = values
            .iter()
            .enumerate()
            .find(|(_, v)| !(v.is_finite() && **v >= 0.0))
        {
            return Err(format!("voxel {i} is {v} (values must be finite and >= 0)"));
        }
        let mut grid = Self {
            resolution,
            min,
            max,
            values,
            majorants: Majorants {
                resolution: UVec3::ONE,
                values: vec![0.0],
            },
            filter: Filter::Trilinear,
        };
        grid.majorants = grid.build_majorants(MAJORANT_RESOLUTION);
        Ok(grid)
    }

    /// The same grid with a majorant grid of at most `cells` per axis (at least 1): one
    /// cell is the single global majorant that tracking without the coarse grid would
    /// draw against, for measuring what the coarse grid saves.
    pub fn with_majorant_cells(mut self, cells: u32) -> Self {
        self.majorants = self.build_majorants(cells.max(1));
        self
    }

    /// The same grid blending its voxels by `filter`. The majorant grid bounds both
    /// filters (each cell's maximum spans every voxel either can reach from it).
    pub fn with_filter(mut self, filter: Filter) -> Self {
        self.filter = filter;
        self
    }

    /// How the grid blends its voxels.
    pub fn filter(&self) -> Filter {
        self.filter
    }

    /// The box the field is defined on.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        (self.min, self.max)
    }

    /// The voxels along each axis.
    pub fn resolution(&self) -> UVec3 {
        self.resolution
    }

    /// The largest value.
    pub fn max_value(&self) -> f32 {
        self.majorants.values.iter().copied().fold(0.0, f32::max)
    }

    /// Multiplies every value by `factor` (finite, >= 0).
    pub fn scaled(mut self, factor: f32) -> Result<Self, String> {
        if !(factor.is_finite() && factor >= 0.0) {
            return Err(format!("scale {factor} must be finite and >= 0"));
        }
        for v in self
            .values
            .iter_mut()
            .chain(self.majorants.values.iter_mut())
        {
            *v *= factor;
            if !v.is_finite() {
                return Err(format!("scale {factor} overflows a voxel"));
            }
        }
        Ok(self)
    }

    /// The same values over another box.
    pub fn placed(mut self, min: Vec3, max: Vec3) -> Result<Self, String> {
        if !min.is_finite() || !max.is_finite() || !min.cmplt(max).all() {
            return Err(format!("the box {min} - {max} is empty or not finite"));
        }
        (self.min, self.max) = (min, max);
        Ok(self)
    }

    /// Voxel `index` (x fastest then y then z), as [`Stencil::voxels`] names it.
    #[inline]
    pub(crate) fn value(&self, index: u32) -> f32 {
        self.values[index as usize]
    }

    #[inline]
    fn voxel(&self, x: u32, y: u32, z: u32) -> f32 {
        let r = self.resolution;
        self.values[((z * r.y + y) * r.x + x) as usize]
    }

    /// The field at `p`: blended by the grid's filter, 0 outside the box (and for a point
    /// that is not finite).
    #[inline]
    pub fn lookup(&self, p: Vec3) -> f32 {
        let unit = (p - self.min) / (self.max - self.min);
        if !(unit.cmpge(Vec3::ZERO).all() && unit.cmple(Vec3::ONE).all()) {
            return 0.0;
        }
        self.at_unit(unit)
    }

    /// The field at `p` with `p` clamped into the box: outside it, the value at the
    /// nearest point of the box's faces (Mitsuba's clamped wrapping; a point that is not
    /// finite reads the box's lowest corner).
    #[inline]
    pub fn lookup_clamped(&self, p: Vec3) -> f32 {
        self.at_unit(self.clamped_unit(p))
    }

    /// `p` in the box's unit cube, clamped into it (NaN to 0).
    #[inline]
    pub(crate) fn clamped_unit(&self, p: Vec3) -> Vec3 {
        let unit = (p - self.min) / (self.max - self.min);
        // f32::max returns the other operand for NaN.
        unit.max(Vec3::ZERO).min(Vec3::ONE)
    }

    /// `p` in the box's unit cube, if it is in the box (None for a point that is not
    /// finite).
    #[inline]
    pub(crate) fn unit_inside(&self, p: Vec3) -> Option<Vec3> {
        let unit = (p - self.min) / (self.max - self.min);
        (unit.cmpge(Vec3::ZERO).all() && unit.cmple(Vec3::ONE).all()).then_some(unit)
    }

    /// The field at `unit`, a point of the box's unit cube.
    #[inline]
    fn at_unit(&self, unit: Vec3) -> f32 {
        if self.filter == Filter::Nearest {
            let i = self.nearest(unit);
            return self.voxel(i.x, i.y, i.z);
        }
        let r = self.resolution.as_vec3();
        let s = (unit * r - 0.5).clamp(Vec3::ZERO, r - 1.0);
        let base = s.floor();
        let f = s - base;
        let i0 = base.as_uvec3();
        let i1 = (i0 + 1).min(self.resolution - 1);
        let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
        let x00 = lerp(
            self.voxel(i0.x, i0.y, i0.z),
            self.voxel(i1.x, i0.y, i0.z),
            f.x,
        );
        let x10 = lerp(
            self.voxel(i0.x, i1.y, i0.z),
            self.voxel(i1.x, i1.y, i0.z),
            f.x,
        );
        let x01 = lerp(
            self.voxel(i0.x, i0.y, i1.z),
            self.voxel(i1.x, i0.y, i1.z),
            f.x,
        );
        let x11 = lerp(
            self.voxel(i0.x, i1.y, i1.z),
            self.voxel(i1.x, i1.y, i1.z),
            f.x,
        );
        lerp(lerp(x00, x10, f.y), lerp(x01, x11, f.y), f.z)
    }

    /// The voxel `unit` is in.
    #[inline]
    fn nearest(&self, unit: Vec3) -> UVec3 {
        (unit * self.resolution.as_vec3())
            .floor()
            .max(Vec3::ZERO)
            .as_uvec3()
            .min(self.resolution - 1)
    }

    /// The voxels and weights the grid's filter blends at `unit` (a point of the box's
    /// unit cube), as [`Grid::lookup`] blends them: for grids that hold more than one
    /// number per voxel beside this one (spectra: `SpectralGrid`).
    #[inline]
    pub fn stencil(&self, unit: Vec3) -> Stencil {
        let r = self.resolution;
        let index = |v: UVec3| (v.z * r.y + v.y) * r.x + v.x;
        if self.filter == Filter::Nearest {
            let mut weights = [0.0; 8];
            weights[0] = 1.0;
            return Stencil {
                voxels: [index(self.nearest(unit)); 8],
                weights,
            };
        }
        let rf = r.as_vec3();
        let s = (unit * rf - 0.5).clamp(Vec3::ZERO, rf - 1.0);
        let base = s.floor();
        let f = s - base;
        let i0 = base.as_uvec3();
        let i1 = (i0 + 1).min(r - 1);
        let mut voxels = [0; 8];
        let mut weights = [0.0; 8];
        for k in 0..8 {
            let pick = |bit: usize, lo: u32, hi: u32, t: f32| {
                if k >> bit & 1 == 1 {
                    (hi, t)
                } else {
                    (lo, 1.0 - t)
                }
            };
            let (x, wx) = pick(0, i0.x, i1.x, f.x);
            let (y, wy) = pick(1, i0.y, i1.y, f.y);
            let (z, wz) = pick(2, i0.z, i1.z, f.z);
            voxels[k] = index(UVec3::new(x, y, z));
            weights[k] = wx * wy * wz;
        }
        Stencil { voxels, weights }
    }

    /// The coarse grid of maxima: each cell the largest voxel whose trilinear reach (the
    /// voxels either side of every point of the cell) touches it.
    fn build_majorants(&self, cells: u32) -> Majorants {
        let resolution = self.resolution.min(UVec3::splat(cells));
        let mut values = Vec::with_capacity(resolution.element_product() as usize);
        let r = self.resolution.as_vec3();
        for cz in 0..resolution.z {
            for cy in 0..resolution.y {
                for cx in 0..resolution.x {
                    let c = UVec3::new(cx, cy, cz).as_vec3();
                    let lo = c / resolution.as_vec3() * r - 0.5;
                    let hi = (c + 1.0) / resolution.as_vec3() * r - 0.5;
                    let i0 = lo
                        .floor()
                        .max(Vec3::ZERO)
                        .as_uvec3()
                        .min(self.resolution - 1);
                    let i1 = hi
                        .ceil()
                        .max(Vec3::ZERO)
                        .as_uvec3()
                        .min(self.resolution - 1);
                    let mut m = 0.0f32;
                    for z in i0.z..=i1.z {
                        for y in i0.y..=i1.y {
                            for x in i0.x..=i1.x {
                                m = m.max(self.voxel(x, y, z));
                            }
                        }
                    }
                    values.push(m);
                }
            }
        }
        Majorants { resolution, values }
    }

    /// The spans of the ray `origin + t direction`, `t` in [0, `t_max`], over which the
    /// majorant grid bounds the field, in order, each handed to `visit` until it returns
    /// false (3D DDA, Amanatides and Woo 1987, as pbrt-v4's `DDAMajorantIterator`). Parts
    /// of the ray outside the box are not visited (the field is 0 there).
    pub fn spans(
        &self,
        origin: Vec3,
        direction: Vec3,
        t_max: f32,
        mut visit: impl FnMut(Span) -> bool,
    ) {
        let extent = self.max - self.min;
        // The ray in the box's unit cube.
        let o = (origin - self.min) / extent;
        let d = direction / extent;
        let (mut t0, mut t1) = (0.0f32, t_max);
        for axis in 0..3 {
            if d[axis] == 0.0 {
                if !(0.0..=1.0).contains(&o[axis]) {
                    return;
                }
                continue;
            }
            let inv = 1.0 / d[axis];
            let (mut near, mut far) = (-o[axis] * inv, (1.0 - o[axis]) * inv);
            if near > far {
                std::mem::swap(&mut near, &mut far);
            }
            t0 = t0.max(near);
            t1 = t1.min(far);
        }
        if t0.is_nan() || t1.is_nan() || t0 >= t1 {
            return;
        }
        let res = self.majorants.resolution;
        let resf = res.as_vec3();
        let start = (o + d * t0) * resf;
        let mut cell = [0i32; 3];
        let mut next = [0.0f32; 3];
        let mut delta = [0.0f32; 3];
        let mut step = [0i32; 3];
        let mut end = [0i32; 3];
        for axis in 0..3 {
            cell[axis] = (start[axis].floor() as i32).clamp(0, res[axis] as i32 - 1);
            let speed = d[axis] * resf[axis];
            if speed > 0.0 {
                next[axis] = t0 + (cell[axis] as f32 + 1.0 - start[axis]) / speed;
                delta[axis] = 1.0 / speed;
                step[axis] = 1;
                end[axis] = res[axis] as i32;
            } else if speed < 0.0 {
                next[axis] = t0 + (cell[axis] as f32 - start[axis]) / speed;
                delta[axis] = -1.0 / speed;
                step[axis] = -1;
                end[axis] = -1;
            } else {
                next[axis] = f32::INFINITY;
                delta[axis] = f32::INFINITY;
                step[axis] = 0;
                end[axis] = i32::MIN;
            }
        }
        let mut t = t0;
        // A cell at most once per axis step: the DDA ends within the sum of the sides.
        for _ in 0..(res.x + res.y + res.z + 3) {
            let index =
                ((cell[2] as u32 * res.y + cell[1] as u32) * res.x + cell[0] as u32) as usize;
            let bound = self.majorants.values[index];
            let axis = if next[0] < next[1] {
                if next[0] < next[2] { 0 } else { 2 }
            } else if next[1] < next[2] {
                1
            } else {
                2
            };
            let exit = next[axis].min(t1);
            if exit > t
                && !visit(Span {
                    t0: t,
                    t1: exit,
                    bound,
                })
            {
                return;
            }
            if next[axis] >= t1 {
                return;
            }
            t = exit;
            cell[axis] += step[axis];
            if cell[axis] == end[axis] {
                return;
            }
            next[axis] += delta[axis];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp() -> Grid {
        // 4 x 3 x 2 voxels over [0, 4] x [0, 3] x [0, 2]: value = x index.
        let values = (0..24).map(|i| (i % 4) as f32).collect();
        Grid::new(
            UVec3::new(4, 3, 2),
            Vec3::ZERO,
            Vec3::new(4.0, 3.0, 2.0),
            values,
        )
        .unwrap()
    }

    #[test]
    fn lookup_is_trilinear_between_voxel_centres() {
        let g = ramp();
        assert_eq!(g.lookup(Vec3::new(0.5, 1.5, 1.0)), 0.0);
        assert_eq!(g.lookup(Vec3::new(1.5, 0.5, 0.5)), 1.0);
        assert!((g.lookup(Vec3::new(2.25, 1.0, 1.0)) - 1.75).abs() < 1e-6);
        // Clamped to the edge voxel inside the box, 0 outside it.
        assert_eq!(g.lookup(Vec3::new(3.9, 1.0, 1.0)), 3.0);
        assert_eq!(g.lookup(Vec3::new(0.1, 1.0, 1.0)), 0.0);
        assert_eq!(g.lookup(Vec3::new(4.1, 1.0, 1.0)), 0.0);
        assert_eq!(g.lookup(Vec3::NAN), 0.0);
    }

    #[test]
    fn bad_grids_are_errors() {
        let v = |n| vec![1.0; n];
        assert!(Grid::new(UVec3::new(0, 1, 1), Vec3::ZERO, Vec3::ONE, v(0)).is_err());
        assert!(Grid::new(UVec3::new(2, 1, 1), Vec3::ZERO, Vec3::ONE, v(1)).is_err());
        assert!(Grid::new(UVec3::ONE, Vec3::ONE, Vec3::ZERO, v(1)).is_err());
        assert!(Grid::new(UVec3::ONE, Vec3::ZERO, Vec3::ONE, vec![f32::NAN]).is_err());
        assert!(Grid::new(UVec3::ONE, Vec3::ZERO, Vec3::ONE, vec![-1.0]).is_err());
        assert!(ramp().scaled(f32::INFINITY).is_err());
    }

    /// The spans cover the ray's part inside the box, in order and without gaps, and each
    /// bounds the field at every point of it.
    #[test]
    fn spans_cover_the_box_and_bound_the_field() {
        let mut values = vec![0.0; 40 * 40 * 40];
        // A wisp: one dense voxel and a faint neighbourhood.
        values[(20 * 40 + 20) * 40 + 20] = 9.0;
        values[(20 * 40 + 20) * 40 + 21] = 0.5;
        let g = Grid::new(
            UVec3::splat(40),
            Vec3::splat(-1.0),
            Vec3::splat(1.0),
            values,
        )
        .unwrap();
        let mut u = 0.37f32;
        for k in 0..200 {
            u = (u * 997.0 + 0.123).fract();
            let origin = Vec3::new(-2.0 + u, (k as f32 * 0.013).sin(), -1.5 + 0.01 * k as f32);
            let direction = (Vec3::new(1.0, 0.3 * u - 0.1, 0.7) + 0.01 * k as f32).normalize();
            let mut spans = vec![];
            g.spans(origin, direction, 10.0, |s| {
                spans.push(s);
                true
            });
            for w in spans.windows(2) {
                assert!((w[0].t1 - w[1].t0).abs() < 1e-5, "{w:?}");
            }
            for s in &spans {
                for j in 0..16 {
                    let t = s.t0 + (s.t1 - s.t0) * (j as f32 + 0.5) / 16.0;
                    let v = g.lookup(origin + direction * t);
                    assert!(v <= s.bound + 1e-6, "{v} > {s:?}");
                }
            }
            // Every point of the ray inside the box is in some span.
            for j in 0..200 {
                let t = 10.0 * (j as f32 + 0.5) / 200.0;
                let p = origin + direction * t;
                let inside = p.cmpgt(Vec3::splat(-1.0 + 1e-4)).all()
                    && p.cmplt(Vec3::splat(1.0 - 1e-4)).all();
                if inside {
                    assert!(
                        spans.iter().any(|s| s.t0 - 1e-5 <= t && t <= s.t1 + 1e-5),
                        "t {t} uncovered"
                    );
                }
            }
        }
        // Most of the box's majorant cells are empty: a wisp costs what the wisp holds.
        let empty = g.majorants.values.iter().filter(|v| **v == 0.0).count();
        assert!(empty > g.majorants.values.len() * 9 / 10, "{empty}");
    }
}
