use super::WavelengthDistribution;

/// The largest package size supported (the C in 1, 2, 4, 8, 16).
pub const MAX_PACKAGE_SIZE: usize = 16;

/// How the `C` wavelengths of a package are chosen from the hero distribution p.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PackageScheme {
    /// Wilkie et al. 2014: the hero lambda_H ~ p and the others by rotation in wavelength,
    /// lambda_j = ((lambda_H - min + j / C (max - min)) mod (max - min)) + min, combined by
    /// the balance heuristic over the package (the seed lecture's "HWS").
    HeroRotation,
    /// Every lane distributed by p (the seed lecture's "let's pick each wavelength
    /// according to p"): lambda_j = P^-1((u + j / C) mod 1), with lane 0 the hero, combined
    /// by the balance heuristic over the package. Rotation in primary sample space makes
    /// the package the same set whichever lane is the hero, which is what the balance
    /// heuristic needs.
    StratifiedBalance,
    /// The lanes of `StratifiedBalance`, each weighted by its own marginal density p(lambda_j)
    /// without MIS (pbrt-v4's `SampleVisible`). Only for paths whose sampling does not
    /// depend on wavelength.
    StratifiedIndependent,
}

/// The wavelengths a path carries, with their densities.
///
/// `pdf` is the per-lane density for the estimator `(1/C) sum_j L(lambda_j) / pdf_j`: for
/// the balance schemes it is `(1/C) sum_k p(lambda_k)` in every lane (so the estimator is
/// `sum_j L(lambda_j) / sum_k p(lambda_k)`), for `StratifiedIndependent` it is
/// `p(lambda_j)`. A lane with `pdf` 0 is terminated and contributes nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WavelengthPackage<const N: usize> {
    /// Wavelengths, nm; lane 0 is the hero.
    pub lambda: [f32; N],
    /// p(lambda_j): each lane's density under the hero distribution, per nm.
    pub hero_pdf: [f32; N],
    /// The estimator density per lane (see the type's documentation), per nm.
    pub pdf: [f32; N],
    terminated: bool,
}

impl<const N: usize> WavelengthPackage<N> {
    /// Draws a package from `distribution` with one uniform number `u` (clamped into
    /// [0, 1)) by `scheme`.
    pub fn sample(distribution: &WavelengthDistribution, u: f64, scheme: PackageScheme) -> Self {
        const { assert!(N >= 1 && N <= MAX_PACKAGE_SIZE, "package size must be 1..=16") };
        let range = distribution.range();
        let (lo, width) = (f64::from(range.min()), f64::from(range.width()));
        let u = crate::distribution::clamp_unit(u);
        let lambda_f64: [f64; N] = match scheme {
            PackageScheme::HeroRotation => {
                let hero = distribution.sample(u);
                std::array::from_fn(|j| {
                    let shifted = (hero - lo + j as f64 / N as f64 * width).rem_euclid(width);
                    lo + shifted
                })
            }
            PackageScheme::StratifiedBalance | PackageScheme::StratifiedIndependent => {
                std::array::from_fn(|j| distribution.sample((u + j as f64 / N as f64).fract()))
            }
        };
        let hero_pdf_f64 = lambda_f64.map(|l| distribution.pdf(l));
        let lambda = lambda_f64.map(|l| range.clamp(l as f32));
        let hero_pdf = hero_pdf_f64.map(|p| p as f32);
        let pdf = match scheme {
            PackageScheme::HeroRotation | PackageScheme::StratifiedBalance => {
                let mean = hero_pdf_f64.iter().sum::<f64>() / N as f64;
                [mean as f32; N]
            }
            PackageScheme::StratifiedIndependent => hero_pdf,
        };
        Self {
            lambda,
            hero_pdf,
            pdf,
            terminated: false,
        }
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
        self.pdf[0] = self.hero_pdf[0] / N as f32;
    }

    /// The balance-heuristic estimator density of every lane when path sampling depends
    /// on wavelength: `(1/C) sum_k p(lambda_k) q_k`, with `q_k` the density of the sampled
    /// path given lambda_k (the seed lecture's HWS MIS). After secondary termination it is
    /// `p(lambda_0) q_0 / C` for the hero and 0 elsewhere.
    pub fn balance_pdf(&self, path_pdf: &[f32; N]) -> [f32; N] {
        if self.terminated {
            let mut pdf = [0.0; N];
            pdf[0] = self.hero_pdf[0] * path_pdf[0] / N as f32;
            return pdf;
        }
        let sum: f64 = (0..N).map(|k| f64::from(self.hero_pdf[k]) * f64::from(path_pdf[k])).sum();
        [(sum / N as f64) as f32; N]
    }
}

/// Spectral MIS weights over a package: w_j = p(lambda_j) q_j / sum_k p(lambda_k) q_k, with
/// p the hero density and q_j the density of the path given lambda_j. Non-finite or negative
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
