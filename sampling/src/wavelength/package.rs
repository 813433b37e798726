use super::WavelengthDistribution;
use crate::distribution::density_f32;

/// The largest package size supported (packages of C = 1, 2, 4, 8 or 16 wavelengths).
pub const MAX_PACKAGE_SIZE: usize = 16;

/// How the `C` wavelengths of a package are chosen from the hero distribution p, and how
/// they are combined.
///
/// Both schemes use the balance heuristic over the C "techniques" *lane m is the hero*.
/// Technique m gives lane j's point (x, lambda_j) the density p_m(lambda_j) q(x | lambda_m),
/// where q is the density of the path given a wavelength and p_m(lambda_j) the density of
/// lambda_j when lane m is the hero; which p_m that is depends on the scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PackageScheme {
    /// Wilkie et al. 2014 (hero wavelength spectral sampling): lambda_H ~ p and the other lanes by
    /// rotation in wavelength, lambda_j = ((lambda_H - min + j / C (max - min)) mod
    /// (max - min)) + min. Rotation preserves measure, so p_m(lambda_j) = p(lambda_m) and
    /// the estimator is sum_j L_j / sum_k p(lambda_k) q_k: every lane's density is
    /// `(1/C) sum_k p(lambda_k) q_k`.
    HeroRotation,
    /// Every lane distributed by p (pick each wavelength according to p, but still use
    /// only one as the hero): lambda_j = P^-1((u + j / C) mod 1), lane 0
    /// the hero. Rotation in primary sample space gives every lane the marginal density p,
    /// so p_m(lambda_j) = p(lambda_j) and the estimator is
    /// sum_j L_j / (p(lambda_j) sum_k q_k): lane j's density is `p(lambda_j) (1/C) sum_k q_k`,
    /// which for wavelength-independent paths is simply p(lambda_j) (pbrt-v4's
    /// `SampleVisible`).
    Stratified,
}

/// The wavelengths a path carries, with their densities.
///
/// `pdf` is the per-lane density for the estimator `(1/C) sum_j L(lambda_j) / pdf_j` when
/// path sampling does not depend on wavelength (see [`PackageScheme`]); when it does, use
/// [`WavelengthPackage::balance_pdf`]. A lane with `pdf` 0 is terminated and contributes
/// nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WavelengthPackage<const N: usize> {
    /// Wavelengths, nm; lane 0 is the hero.
    pub lambda: [f32; N],
    /// p(lambda_j): each lane's density under the hero distribution, per nm.
    pub hero_pdf: [f32; N],
    /// The estimator density per lane (see the type's documentation), per nm.
    pub pdf: [f32; N],
    scheme: PackageScheme,
    terminated: bool,
}

impl<const N: usize> WavelengthPackage<N> {
    /// Draws a package from `distribution` with one uniform number `u` (clamped into
    /// [0, 1)) by `scheme`.
    pub fn sample(distribution: &WavelengthDistribution, u: f64, scheme: PackageScheme) -> Self {
        const {
            assert!(
                N >= 1 && N <= MAX_PACKAGE_SIZE,
                "package size must be 1..=16"
            )
        };
        let range = distribution.range();
        let (lo, width) = (f64::from(range.min()), f64::from(range.width()));
        let u = crate::distribution::clamp_unit(u);
        let lambda_f64: [f64; N] = match scheme {
            PackageScheme::HeroRotation => {
                let hero = distribution.sample(u);
                // Lane 0 is the hero itself: wrapping it would turn lambda_max into lambda_min.
                std::array::from_fn(|j| {
                    if j == 0 {
                        return hero;
                    }
                    // hero - lo + offset lies in [0, 2 width): one subtraction wraps it, and
                    // exactly (Sterbenz), as rem_euclid would, without a libm fmod per lane.
                    let shifted = hero - lo + j as f64 / N as f64 * width;
                    lo + if shifted >= width {
                        shifted - width
                    } else {
                        shifted
                    }
                })
            }
            PackageScheme::Stratified => {
                std::array::from_fn(|j| distribution.sample((u + j as f64 / N as f64).fract()))
            }
        };
        // The renderer uses the f32 wavelength, so its density is evaluated there; if
        // rounding to f32 crossed into a zero-density bin, step back one ulp towards the
        // sampled f64 value.
        let mut lambda = lambda_f64.map(|l| range.clamp(l as f32));
        let mut hero_pdf = distribution.pdf_lanes(&lambda);
        for j in 0..N {
            if hero_pdf[j] == 0.0 {
                let l = lambda_f64[j];
                let narrow = lambda[j];
                lambda[j] = range.clamp(if f64::from(narrow) > l {
                    narrow.next_down()
                } else {
                    narrow.next_up()
                });
                hero_pdf[j] = density_f32(distribution.pdf(f64::from(lambda[j])));
            }
        }
        let mut package = Self {
            lambda,
            hero_pdf,
            pdf: hero_pdf,
            scheme,
            terminated: false,
        };
        package.pdf = package.balance_pdf(&[1.0; N]);
        package
    }

    /// The hero wavelength, nm.
    pub fn hero(&self) -> f32 {
        self.lambda[0]
    }

    /// Whether the secondary lanes were terminated.
    pub fn secondary_terminated(&self) -> bool {
        self.terminated
    }

    /// Ends the secondary lanes at a wavelength-dependent delta event (dispersive
    /// refraction), where only the hero's direction was sampled and the others' densities
    /// are zero. Afterwards the package estimates with the hero alone:
    /// `(1/C) L(lambda_0) / pdf_0` with `pdf_0 = p(lambda_0) / C` equals
    /// `L(lambda_0) / p(lambda_0)`, unbiased because lambda_0 ~ p; every secondary lane gets
    /// density 0 and so contributes nothing. Idempotent: an explicit flag records the
    /// termination, so the hero's density is rescaled exactly once (inferring termination
    /// from zero densities is the bug pbrt-v4's check invites when a lane's density is 0
    /// for another reason).
    pub fn terminate_secondary(&mut self) {
        if self.terminated {
            return;
        }
        self.terminated = true;
        self.pdf = [0.0; N];
        self.pdf[0] = density_f32(f64::from(self.hero_pdf[0]) / N as f64);
    }

    /// The scheme that drew the package.
    pub fn scheme(&self) -> PackageScheme {
        self.scheme
    }

    /// The balance-heuristic estimator density per lane when path sampling depends on
    /// wavelength, `path_pdf[k]` = q_k the density of the sampled path given lambda_k
    /// (Wilkie et al. 2014, §4: hero wavelength MIS): `(1/C) sum_k p(lambda_k) q_k` for `HeroRotation`,
    /// `p(lambda_j) (1/C) sum_k q_k` for `Stratified`. After secondary termination only
    /// the hero remains, with `p(lambda_0) q_0 / C`.
    pub fn balance_pdf(&self, path_pdf: &[f32; N]) -> [f32; N] {
        let q = |k: usize| f64::from(path_pdf[k]);
        if self.terminated {
            let mut pdf = [0.0; N];
            pdf[0] = density_f32(f64::from(self.hero_pdf[0]) * q(0) / N as f64);
            return pdf;
        }
        match self.scheme {
            PackageScheme::HeroRotation => {
                let sum: f64 = (0..N).map(|k| f64::from(self.hero_pdf[k]) * q(k)).sum();
                [density_f32(sum / N as f64); N]
            }
            PackageScheme::Stratified => {
                let mean_q = (0..N).map(q).sum::<f64>() / N as f64;
                std::array::from_fn(|j| density_f32(f64::from(self.hero_pdf[j]) * mean_q))
            }
        }
    }

    /// The balance-heuristic weight of each lane's own technique, so that the estimator is
    /// `sum_j w_j L_j / (p(lambda_j) q_j)`: [`spectral_mis_weights`] for `HeroRotation`,
    /// `q_j / sum_k q_k` for `Stratified`. They sum to 1 (0 everywhere if every q is 0).
    pub fn mis_weights(&self, path_pdf: &[f32; N]) -> [f32; N] {
        match self.scheme {
            PackageScheme::HeroRotation => spectral_mis_weights(&self.hero_pdf, path_pdf),
            PackageScheme::Stratified => spectral_mis_weights(&[1.0; N], path_pdf),
        }
    }
}

/// Spectral MIS weights over a rotation package (Wilkie et al.
/// 2014, §4): w_j = p(lambda_j) q_j / sum_k p(lambda_k) q_k, with p the hero density and q_j
/// the density of the path given lambda_j. Non-finite or negative
/// inputs count as 0; if every product is 0 the weights are 0.
pub fn spectral_mis_weights<const N: usize>(hero_pdf: &[f32; N], path_pdf: &[f32; N]) -> [f32; N] {
    let product = |j: usize| {
        let v = f64::from(hero_pdf[j]) * f64::from(path_pdf[j]);
        if v.is_finite() && v > 0.0 { v } else { 0.0 }
    };
    let sum: f64 = (0..N).map(product).sum();
    if !(sum > 0.0 && sum.is_finite()) {
        return [0.0; N];
    }
    std::array::from_fn(|j| (product(j) / sum) as f32)
}
