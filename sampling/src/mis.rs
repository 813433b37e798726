//! Multiple importance sampling heuristics (E. Veach, *Robust Monte Carlo Methods for
//! Light Transport Simulation*, PhD thesis, Stanford 1997, §9.2).

use crate::lanes::real::Real;

/// The balance heuristic weight of technique f (`nf` samples of density `f_pdf`) against
/// technique g: nf f / (nf f + ng g). An infinite `f_pdf` (a delta) gets weight 1;
/// both densities zero gives 0.
///
/// ```
/// use prism_sampling::mis::balance_heuristic;
///
/// // One light sample and one BSDF sample: the weights of the two sum to 1.
/// let (light, bsdf) = (balance_heuristic(1, 2.0, 1, 6.0), balance_heuristic(1, 6.0, 1, 2.0));
/// assert_eq!((light, bsdf), (0.25, 0.75));
/// assert_eq!(balance_heuristic(1, f32::INFINITY, 1, 6.0), 1.0);
/// ```
pub fn balance_heuristic(nf: u32, f_pdf: f32, ng: u32, g_pdf: f32) -> f32 {
    weight_of(nf as f32 * f_pdf, ng as f32 * g_pdf)
}

/// The power heuristic with exponent 2: (nf f)^2 / ((nf f)^2 + (ng g)^2). Overflow of the
/// squares is handled by scaling; an infinite `f_pdf` gets weight 1.
pub fn power_heuristic(nf: u32, f_pdf: f32, ng: u32, g_pdf: f32) -> f32 {
    power_heuristic_of(nf as f32 * f_pdf, ng as f32 * g_pdf)
}

/// [`power_heuristic`] of one sample's densities `f` and `g` (each already times its
/// sample count), or of lanes of them: the same operations, branches as selects, so that
/// a path and a batch of paths in lanes weigh alike to the bit.
#[inline(always)]
pub fn power_heuristic_of<R: Real>(f: R, g: R) -> R {
    let (zero, one) = (R::splat(0.0), R::splat(1.0));
    // Squares of values above ~1.8e19 overflow f32: divide both by the larger first.
    let scale = f.max(g);
    let (fs, gs) = (f / scale, g / scale);
    let w = weight_of(fs * fs, gs * gs);
    let dead = scale.ne(scale) | scale.le(zero);
    R::select(is_infinite(f), one, R::select(dead, zero, w))
}

/// +-infinity (not NaN).
#[inline(always)]
fn is_infinite<R: Real>(x: R) -> R::Mask {
    x.abs().gt(R::splat(f32::MAX))
}

/// [`weight`] over [`Real`].
#[inline(always)]
fn weight_of<R: Real>(f: R, g: R) -> R {
    let (zero, one) = (R::splat(0.0), R::splat(1.0));
    let sum = f + g;
    let usable = sum.gt(zero) & f.is_finite();
    let w = R::select(usable, (f / sum).max(zero).min(one), zero);
    R::select(is_infinite(f), one, R::select(is_infinite(g), zero, w))
}
