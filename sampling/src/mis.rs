//! Multiple importance sampling heuristics (E. Veach, *Robust Monte Carlo Methods for
//! Light Transport Simulation*, PhD thesis, Stanford 1997, §9.2).

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
    weight(nf as f32 * f_pdf, ng as f32 * g_pdf)
}

/// The power heuristic with exponent 2: (nf f)^2 / ((nf f)^2 + (ng g)^2). Overflow of the
/// squares is handled by scaling; an infinite `f_pdf` gets weight 1.
pub fn power_heuristic(nf: u32, f_pdf: f32, ng: u32, g_pdf: f32) -> f32 {
    let (f, g) = (nf as f32 * f_pdf, ng as f32 * g_pdf);
    if f.is_infinite() {
        return 1.0;
    }
    // Squares of values above ~1.8e19 overflow f32: divide both by the larger first.
    let scale = f.max(g);
    if scale.is_nan() || scale <= 0.0 {
        return 0.0;
    }
    let (f, g) = (f / scale, g / scale);
    weight(f * f, g * g)
}

fn weight(f: f32, g: f32) -> f32 {
    if f.is_infinite() {
        return 1.0;
    }
    if g.is_infinite() {
        return 0.0;
    }
    let sum = f + g;
    if sum > 0.0 && f.is_finite() {
        (f / sum).clamp(0.0, 1.0)
    } else {
        0.0
    }
}
