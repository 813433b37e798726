//! Mueller matrices of the elements a polarized renderer needs.

use glam::{Mat4, Vec4};

use super::{FresnelAmplitudes, Stokes};

/// A Mueller matrix: the linear map of Stokes vectors an optical element applies (see the
/// module documentation for the frames it assumes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mueller(Mat4);

impl Mueller {
    /// Leaves light as it is.
    pub const IDENTITY: Mueller = Mueller(Mat4::IDENTITY);

    /// The matrix with these rows.
    pub fn from_rows(rows: [[f32; 4]; 4]) -> Self {
        Self(Mat4::from_cols_array_2d(&rows).transpose())
    }

    /// The rows.
    pub fn rows(&self) -> [[f32; 4]; 4] {
        self.0.transpose().to_cols_array_2d()
    }

    /// The element whose matrix is `m` (glam's, column by column).
    pub fn from_matrix(m: Mat4) -> Self {
        Self(m)
    }

    /// The matrix itself (columns as glam stores them; `matrix() * stokes.0` applies it).
    pub fn matrix(&self) -> Mat4 {
        self.0
    }

    /// The element applied to `stokes`.
    pub fn apply(&self, stokes: Stokes) -> Stokes {
        Stokes(self.0 * stokes.0)
    }

    /// This element after `first` (light meets `first`, then `self`).
    pub fn after(&self, first: &Mueller) -> Mueller {
        Mueller(self.0 * first.0)
    }

    /// Every entry times `s`.
    pub fn scaled(&self, s: f32) -> Mueller {
        Mueller(self.0 * s)
    }

    /// A depolarizer that keeps the fraction `value` of the intensity: diffuse reflection.
    pub fn depolarizer(value: f32) -> Self {
        Self::from_rows([[value, 0.0, 0.0, 0.0], [0.0; 4], [0.0; 4], [0.0; 4]])
    }

    /// The rotation of the reference frame by `theta` radians about the direction of
    /// travel (x towards y): what a Stokes vector's components become when its basis
    /// vector turns by `theta`.
    pub fn rotator(theta: f32) -> Self {
        let (s, c) = (2.0 * theta).sin_cos();
        Self::from_rows([
            [1.0, 0.0, 0.0, 0.0],
            [0.0, c, s, 0.0],
            [0.0, -s, c, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ])
    }

    /// `element` turned by `theta` about the direction of travel (its axis at `theta` from
    /// x): rotator(-theta) element rotator(theta).
    pub fn rotated(theta: f32, element: &Mueller) -> Self {
        Self::rotator(-theta).after(&element.after(&Self::rotator(theta)))
    }

    /// An ideal linear polarizer transmitting along x, scaled by `value` (1: ideal).
    pub fn linear_polarizer(value: f32) -> Self {
        let a = 0.5 * value;
        Self::from_rows([[a, a, 0.0, 0.0], [a, a, 0.0, 0.0], [0.0; 4], [0.0; 4]])
    }

    /// A linear retarder with its fast axis along x delaying y by `phase` radians (pi/2: a
    /// quarter-wave plate, pi: a half-wave plate).
    pub fn linear_retarder(phase: f32) -> Self {
        let (s, c) = phase.sin_cos();
        Self::from_rows([
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, c, s],
            [0.0, 0.0, -s, c],
        ])
    }

    /// A diattenuator transmitting the fractions `x` and `y` of the intensity polarized
    /// along x and y.
    pub fn diattenuator(x: f32, y: f32) -> Self {
        let (a, b, c) = (0.5 * (x + y), 0.5 * (x - y), (x * y).max(0.0).sqrt());
        Self::from_rows([
            [a, b, 0.0, 0.0],
            [b, a, 0.0, 0.0],
            [0.0, 0.0, c, 0.0],
            [0.0, 0.0, 0.0, c],
        ])
    }

    /// Specular reflection at an interface with Fresnel amplitudes `r` (s and p), in the
    /// s-p frame: intensities R_s = |r_s|^2 and R_p = |r_p|^2 and the retardance
    /// delta = arg(r_p) - arg(r_s) that turns linear into elliptical light (metals, and
    /// dielectrics beyond the critical angle). The sign of delta is the one that makes S3
    /// agree with Mitsuba 3 (its amplitudes are the complex conjugates of Born and Wolf's,
    /// the other sign convention of the time dependence; intensities do not depend on it).
    pub fn reflection(r: &FresnelAmplitudes) -> Self {
        let (rs, rp) = (r.s.norm_sqr(), r.p.norm_sqr());
        let product = r.p * r.s.conj();
        let (cos, sin) = match product.norm() {
            n if n > 0.0 && n.is_finite() => (product.re / n, product.im / n),
            _ => (1.0, 0.0),
        };
        Self::from_interface(rs, rp, cos, sin)
    }

    /// Specular transmission through a dielectric interface with amplitudes `t` (the
    /// fractions of power T_s and T_p crossing; no phase shift below the critical angle),
    /// in the s-p frame. The radiance scaling 1 / eta^2 is the BSDF's, not this matrix's.
    pub fn transmission(t: &FresnelAmplitudes) -> Self {
        let (ts, tp) = (t.transmitted_s, t.transmitted_p);
        Self::from_interface(ts, tp, 1.0, 0.0)
    }

    /// The matrix of an interface (Collett, p. 14), f64 in, f32 out, non-finite input as
    /// an absorber.
    fn from_interface(s: f64, p: f64, cos: f64, sin: f64) -> Self {
        let (a, b, c) = (0.5 * (s + p), 0.5 * (s - p), (s * p).max(0.0).sqrt());
        let rows = [
            [a, b, 0.0, 0.0],
            [b, a, 0.0, 0.0],
            [0.0, 0.0, c * cos, c * sin],
            [0.0, 0.0, -c * sin, c * cos],
        ];
        if rows.iter().flatten().all(|v| v.is_finite()) {
            Self::from_rows(rows.map(|r| r.map(|v| v as f32)))
        } else {
            Self::from_rows([[0.0; 4]; 4])
        }
    }

    /// Whether every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.0.is_finite()
    }

    /// The first column: what the element does to unpolarized light of intensity 1.
    pub fn unpolarized_response(&self) -> Vec4 {
        self.0.col(0)
    }
}
