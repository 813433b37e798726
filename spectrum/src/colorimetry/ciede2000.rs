use super::Lab;

/// Components beyond this magnitude are clamped before CIEDE2000 is evaluated, so that
/// squares and sums cannot overflow: real colours have |L*|, |a*|, |b*| < 1000.
const COMPONENT_LIMIT: f64 = 1e100;

/// The CIEDE2000 colour difference (CIE 142-2001) with parametric factors
/// kL = kC = kH = 1, implemented after Sharma, Wu and Dalal, "The CIEDE2000 color-difference
/// formula: implementation notes, supplementary test data, and mathematical observations",
/// Color Res. Appl. 30(1), 21-30, 2005, equations (2)-(22).
///
/// Exactly symmetric (the arguments are put in a canonical order first) and finite for all
/// finite inputs: achromatic colours (C' = 0) take hue 0 as the paper prescribes, the hue
/// mean and difference follow its discontinuity rules, components with magnitude above
/// 1e100 are clamped, and NaN components are treated as 0.
///
/// ```
/// use prism_spectrum::colorimetry::{ciede2000, Lab};
///
/// // The first pair of Sharma, Wu and Dalal's Table 1.
/// let first = Lab { l: 50.0, a: 2.6772, b: -79.7751 };
/// let second = Lab { l: 50.0, a: 0.0, b: -82.7485 };
/// assert!((ciede2000(first, second) - 2.0425).abs() < 1e-4);
/// assert_eq!(ciede2000(first, second), ciede2000(second, first));
/// ```
pub fn ciede2000(first: Lab, second: Lab) -> f64 {
    let sanitize = |lab: Lab| {
        let c = |v: f64| {
            if v.is_nan() {
                0.0
            } else {
                v.clamp(-COMPONENT_LIMIT, COMPONENT_LIMIT)
            }
        };
        Lab::new(c(lab.l), c(lab.a), c(lab.b))
    };
    let (p, q) = (sanitize(first), sanitize(second));
    let key = |lab: &Lab| (lab.l, lab.a, lab.b);
    let (lab1, lab2) = if key(&p) <= key(&q) { (p, q) } else { (q, p) };

    // (2)-(6): a' rescaled by G, C', h'.
    let c_bar = 0.5 * (lab1.chroma() + lab2.chroma());
    // 0.5 (1 - sqrt(C^7 / (C^7 + 25^7))) written as a ratio that cannot overflow.
    let g = 0.5 * (1.0 - (1.0 / (1.0 + (25.0 / c_bar).powi(7))).sqrt());
    let prime = |lab: Lab| {
        let a = (1.0 + g) * lab.a;
        let c = a.hypot(lab.b);
        let h = if c == 0.0 {
            0.0
        } else {
            lab.b.atan2(a).to_degrees().rem_euclid(360.0)
        };
        (c, h)
    };
    let (c1, h1) = prime(lab1);
    let (c2, h2) = prime(lab2);

    // (8)-(10): differences.
    let dl = lab2.l - lab1.l;
    let dc = c2 - c1;
    let dh_angle = if c1 * c2 == 0.0 {
        0.0
    } else if (h2 - h1).abs() <= 180.0 {
        h2 - h1
    } else if h2 - h1 > 180.0 {
        h2 - h1 - 360.0
    } else {
        h2 - h1 + 360.0
    };
    let dh = 2.0 * (c1 * c2).sqrt() * (0.5 * dh_angle).to_radians().sin();

    // (12)-(22): weights.
    let l_bar = 0.5 * (lab1.l + lab2.l);
    let c_bar_prime = 0.5 * (c1 + c2);
    let h_bar = if c1 * c2 == 0.0 {
        h1 + h2
    } else if (h1 - h2).abs() <= 180.0 {
        0.5 * (h1 + h2)
    } else if h1 + h2 < 360.0 {
        0.5 * (h1 + h2 + 360.0)
    } else {
        0.5 * (h1 + h2 - 360.0)
    };
    let t = 1.0 - 0.17 * (h_bar - 30.0).to_radians().cos()
        + 0.24 * (2.0 * h_bar).to_radians().cos()
        + 0.32 * (3.0 * h_bar + 6.0).to_radians().cos()
        - 0.20 * (4.0 * h_bar - 63.0).to_radians().cos();
    let d_theta = 30.0 * (-((h_bar - 275.0) / 25.0).powi(2)).exp();
    let r_c = 2.0 * (1.0 / (1.0 + (25.0 / c_bar_prime).powi(7))).sqrt();
    // S_L = 1 + 0.015 (L - 50)^2 / sqrt(20 + (L - 50)^2), arranged to avoid inf / inf.
    let d50 = (l_bar - 50.0).abs();
    let s_l = 1.0 + 0.015 * d50 / (20.0 / (d50 * d50) + 1.0).sqrt();
    let s_c = 1.0 + 0.045 * c_bar_prime;
    let s_h = 1.0 + 0.015 * c_bar_prime * t;
    let r_t = -(2.0 * d_theta).to_radians().sin() * r_c;

    let (tl, tc, th) = (dl / s_l, dc / s_c, dh / s_h);
    (tl * tl + tc * tc + th * th + r_t * tc * th)
        .max(0.0)
        .sqrt()
}
