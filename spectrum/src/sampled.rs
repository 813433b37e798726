//! Spectra sampled at a package of wavelengths: what a path carries.
//!
//! [`SampledWavelengths`] holds the wavelengths and the probability density with which
//! each was chosen; [`SampledSpectrum`] holds one value per wavelength. A sampled spectrum
//! has no colour on its own: it becomes XYZ only through
//! [`SampledSpectrum::to_xyz`], which needs the wavelengths and their densities
//! (pbrt-v4, Pharr, Jakob and Humphreys, *Physically Based Rendering*, 4th ed., §4.5.4).

use std::ops::{Add, AddAssign, Div, DivAssign, Index, IndexMut, Mul, MulAssign, Sub, SubAssign};

use crate::colorimetry::{Observer, Xyz};
use crate::error::SpectrumError;

/// `N` wavelengths (nm) and the density (per nm) with which each was sampled.
///
/// A lane with density 0 is a terminated lane: it contributes nothing to colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampledWavelengths<const N: usize> {
    lambda: [f32; N],
    pdf: [f32; N],
}

impl<const N: usize> SampledWavelengths<N> {
    /// Wavelengths (finite, > 0, nm) and their densities (finite, >= 0, per nm).
    pub fn new(lambda: [f32; N], pdf: [f32; N]) -> Result<Self, SpectrumError> {
        // Every path makes packages: accept on the bits, all lanes without early exits,
        // and search for the culprit (the definition below) only when that fails
        // (measured: the searching form alone was a noticeable share of the default
        // scene's instructions). A finite l > 0 is 1..=0x7f7f_ffff; a finite p >= 0 is
        // 0..=0x7f7f_ffff or -0.
        let mut invalid = false;
        for (l, p) in lambda.iter().zip(&pdf) {
            let p = p.to_bits();
            invalid |= l.to_bits().wrapping_sub(1) >= 0x7f7f_ffff;
            invalid |= p >= 0x7f80_0000 && p != 0x8000_0000;
        }
        let valid = !invalid;
        if valid {
            return Ok(Self { lambda, pdf });
        }
        if let Some(&l) = lambda.iter().find(|l| !(l.is_finite() && **l > 0.0)) {
            return Err(SpectrumError::InvalidValue {
                what: "sampled wavelength (nm)",
                value: f64::from(l),
                expected: "a finite number > 0",
            });
        }
        if let Some(&p) = pdf.iter().find(|p| !(p.is_finite() && **p >= 0.0)) {
            return Err(SpectrumError::InvalidValue {
                what: "wavelength density",
                value: f64::from(p),
                expected: "a finite number >= 0",
            });
        }
        Ok(Self { lambda, pdf })
    }

    /// The wavelength of lane `i`, nm.
    pub fn lambda(&self, i: usize) -> f32 {
        self.lambda[i]
    }

    /// The sampling density of lane `i`, per nm.
    pub fn pdf(&self, i: usize) -> f32 {
        self.pdf[i]
    }

    /// All wavelengths.
    pub fn lambdas(&self) -> &[f32; N] {
        &self.lambda
    }

    /// All densities.
    pub fn pdfs(&self) -> &[f32; N] {
        &self.pdf
    }
}

/// An f64 value as the f32 a sampled spectrum or an image holds: NaN becomes 0 and
/// magnitudes beyond f32's range saturate at `f32::MAX`, where `as f32` would round them to
/// infinity (a constant radiance of 1e300 is finite in f64 and infinite in f32).
pub fn saturating_f32(x: f64) -> f32 {
    if x.is_nan() {
        0.0
    } else {
        x.clamp(-f64::from(f32::MAX), f64::from(f32::MAX)) as f32
    }
}

/// One value per wavelength lane, with lane-wise arithmetic.
///
/// Division by zero yields 0 rather than inf or NaN: in light transport a zero denominator
/// (a zero pdf, a black albedo) always means "this lane carries nothing".
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampledSpectrum<const N: usize>(pub [f32; N]);

impl<const N: usize> SampledSpectrum<N> {
    /// Every lane equal to `value`.
    pub fn splat(value: f32) -> Self {
        Self([value; N])
    }

    /// Lane `i` is `f(i)`.
    pub fn from_fn(f: impl FnMut(usize) -> f32) -> Self {
        Self(std::array::from_fn(f))
    }

    /// Whether every lane is exactly zero.
    pub fn is_black(&self) -> bool {
        self.0.iter().all(|&v| v == 0.0)
    }

    /// Whether every lane is finite.
    pub fn is_finite(&self) -> bool {
        self.0.iter().all(|v| v.is_finite())
    }

    /// The largest lane.
    pub fn max_value(&self) -> f32 {
        self.0.iter().copied().fold(f32::NEG_INFINITY, f32::max)
    }

    /// The mean of the lanes.
    pub fn average(&self) -> f32 {
        self.0.iter().sum::<f32>() / N as f32
    }

    /// Lane-wise `f`.
    pub fn map(&self, f: impl Fn(f32) -> f32) -> Self {
        Self(self.0.map(f))
    }

    /// Monte Carlo estimate of the CIE XYZ tristimulus values of the spectrum whose
    /// samples these are: `(1/N) sum_i cmf(lambda_i) S_i / p(lambda_i)`. Lanes with
    /// zero density (terminated) contribute nothing. The result is in the same units as
    /// [`crate::colorimetry::emission_xyz`] (value times nm), so its expectation is the
    /// exact integral.
    pub fn to_xyz(&self, wavelengths: &SampledWavelengths<N>, observer: Observer) -> Xyz {
        let mut xyz = [0.0f64; 3];
        for i in 0..N {
            let pdf = wavelengths.pdf(i);
            if pdf > 0.0 {
                let cmf = observer.cmf(f64::from(wavelengths.lambda(i)));
                let weight = f64::from(self.0[i]) / f64::from(pdf);
                for (acc, c) in xyz.iter_mut().zip(cmf) {
                    *acc += c * weight;
                }
            }
        }
        let n = N as f64;
        Xyz::new(xyz[0] / n, xyz[1] / n, xyz[2] / n)
    }
}

impl<const N: usize> Default for SampledSpectrum<N> {
    fn default() -> Self {
        Self::splat(0.0)
    }
}

impl<const N: usize> Index<usize> for SampledSpectrum<N> {
    type Output = f32;
    fn index(&self, i: usize) -> &f32 {
        &self.0[i]
    }
}

impl<const N: usize> IndexMut<usize> for SampledSpectrum<N> {
    fn index_mut(&mut self, i: usize) -> &mut f32 {
        &mut self.0[i]
    }
}

fn safe_div(a: f32, b: f32) -> f32 {
    if b == 0.0 { 0.0 } else { a / b }
}

macro_rules! lanewise {
    ($trait:ident, $method:ident, $assign_trait:ident, $assign:ident, $op:expr) => {
        impl<const N: usize> $trait for SampledSpectrum<N> {
            type Output = Self;
            fn $method(self, rhs: Self) -> Self {
                Self(std::array::from_fn(|i| $op(self.0[i], rhs.0[i])))
            }
        }
        impl<const N: usize> $trait<f32> for SampledSpectrum<N> {
            type Output = Self;
            fn $method(self, rhs: f32) -> Self {
                Self(self.0.map(|a| $op(a, rhs)))
            }
        }
        impl<const N: usize> $assign_trait for SampledSpectrum<N> {
            fn $assign(&mut self, rhs: Self) {
                *self = $trait::$method(*self, rhs);
            }
        }
        impl<const N: usize> $assign_trait<f32> for SampledSpectrum<N> {
            fn $assign(&mut self, rhs: f32) {
                *self = $trait::$method(*self, rhs);
            }
        }
    };
}

lanewise!(Add, add, AddAssign, add_assign, |a: f32, b: f32| a + b);
lanewise!(Sub, sub, SubAssign, sub_assign, |a: f32, b: f32| a - b);
lanewise!(Mul, mul, MulAssign, mul_assign, |a: f32, b: f32| a * b);
lanewise!(Div, div, DivAssign, div_assign, safe_div);

impl<const N: usize> Mul<SampledSpectrum<N>> for f32 {
    type Output = SampledSpectrum<N>;
    fn mul(self, rhs: SampledSpectrum<N>) -> SampledSpectrum<N> {
        rhs * self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn division_by_zero_lane_is_zero() {
        let a = SampledSpectrum([1.0, 2.0, 3.0, 4.0]);
        let b = SampledSpectrum([0.0, 2.0, 0.0, 8.0]);
        assert_eq!((a / b).0, [0.0, 1.0, 0.0, 0.5]);
        assert_eq!((a / 0.0).0, [0.0; 4]);
    }

    #[test]
    fn terminated_lanes_add_no_colour() {
        let wl = SampledWavelengths::new([550.0, 600.0], [0.01, 0.0]).unwrap();
        let s = SampledSpectrum([1.0, 1000.0]);
        let only_first = SampledSpectrum([1.0, 0.0]);
        assert_eq!(
            s.to_xyz(&wl, Observer::Cie1931),
            only_first.to_xyz(&wl, Observer::Cie1931)
        );
    }

    #[test]
    fn invalid_wavelengths_are_rejected() {
        assert!(SampledWavelengths::new([f32::NAN], [1.0]).is_err());
        assert!(SampledWavelengths::new([500.0], [-1.0]).is_err());
        assert!(SampledWavelengths::new([0.0], [1.0]).is_err());
    }

    #[test]
    fn saturating_f32_is_finite_and_exact_in_range() {
        let max = f64::from(f32::MAX);
        for (x, stored) in [
            (f64::NAN, 0.0),
            (f64::INFINITY, f32::MAX),
            (f64::NEG_INFINITY, -f32::MAX),
            (f64::MAX, f32::MAX),
            (-f64::MAX, -f32::MAX),
            (max * (1.0 + 1e-9), f32::MAX),
            (max, f32::MAX),
            (1.0, 1.0),
            (-0.0, -0.0),
            (1e-320, 0.0),
            (f64::from(f32::from_bits(1)), f32::from_bits(1)),
        ] {
            assert_eq!(saturating_f32(x).to_bits(), stored.to_bits(), "{x}");
        }
    }
}
