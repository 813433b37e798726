//! Thin-film interference, solved exactly per wavelength: the reflectance of a film of
//! index n1 and thickness d between an outside medium n0 and a base n2 (a dielectric, or a
//! conductor with complex index eta + i k) is the Airy summation of the film's multiple
//! reflections (Born and Wolf, *Principles of Optics*, 7th ed., §1.6.4 and §7.6.1):
//!
//! r = (r01 + r12 e^{2i delta}) / (1 + r01 r12 e^{2i delta}), delta = 2 pi n1 d cos(theta1) / lambda,
//!
//! with the Fresnel amplitude coefficients r_ij of each interface for s and p polarization
//! (complex at a conductor, which carries the phase shift on reflection; the interfaces'
//! phase of pi where the index rises is in their sign), and the reflectance
//! R = (|r_s|^2 + |r_p|^2) / 2 for unpolarized light. This is what
//! `KHR_materials_iridescence` describes; its sample implementation approximates it in RGB
//! (Belcour and Barla 2017), while a renderer that knows the wavelength needs no
//! approximation. Checked against the `tmm` package (scene/tools/thin_film_fixtures.py).

use num_complex::Complex64;

/// A thin dielectric film.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThinFilm {
    /// The film's index of refraction (glTF's `iridescenceIor`, default 1.3).
    pub ior: f32,
    /// Its thickness in nanometres.
    pub thickness_nm: f32,
}

impl ThinFilm {
    /// The unpolarized reflectance of the film over a base of complex index
    /// `base_eta` + i `base_k` (k = 0: a dielectric), seen from a medium of index
    /// `outside` at cos(theta) `cos_i` (its absolute value), for light of vacuum wavelength
    /// `lambda_nm`. In [0, 1] for every input; a thickness of 0 (or below) is the bare
    /// base.
    pub fn reflectance(
        &self,
        cos_i: f32,
        lambda_nm: f32,
        outside: f32,
        base_eta: f32,
        base_k: f32,
    ) -> f32 {
        let (rs, rp) = self.amplitudes(cos_i, lambda_nm, outside, base_eta, base_k);
        let r = 0.5 * (rs.norm_sqr() + rp.norm_sqr());
        if r.is_finite() {
            r.clamp(0.0, 1.0) as f32
        } else {
            1.0
        }
    }

    /// The complex amplitude reflection coefficients (r_s, r_p) of the film and its base,
    /// with the same arguments as [`ThinFilm::reflectance`] (which is their mean
    /// intensity): the phases a polarized renderer needs (an iridescent film retards s
    /// against p, so it turns linear light elliptical).
    pub fn amplitudes(
        &self,
        cos_i: f32,
        lambda_nm: f32,
        outside: f32,
        base_eta: f32,
        base_k: f32,
    ) -> (Complex64, Complex64) {
        let finite_or = |v: f32, fallback: f32| if v.is_finite() { v } else { fallback };
        let cos0 = f64::from(finite_or(cos_i.abs(), 1.0).min(1.0));
        let n0 = f64::from(finite_or(outside, 1.0).max(1e-3));
        let n1 = Complex64::from(f64::from(finite_or(self.ior, 1.0).max(1e-3)));
        let n2 = Complex64::new(
            f64::from(finite_or(base_eta, 1.0).max(1e-3)),
            f64::from(finite_or(base_k, 0.0).max(0.0)),
        );
        let d = f64::from(finite_or(self.thickness_nm, 0.0).max(0.0));
        let lambda = f64::from(finite_or(lambda_nm, 550.0).max(1.0));
        let n0c = Complex64::from(n0);
        // Snell's invariant n sin(theta), the same in every layer.
        let n_sin = n0 * (1.0 - cos0 * cos0).max(0.0).sqrt();
        let cos1 = forward_cos(n1, n_sin);
        let cos2 = forward_cos(n2, n_sin);
        let cos0 = Complex64::from(cos0);
        let phase = (Complex64::i() * 4.0 * std::f64::consts::PI * n1 * cos1 * d / lambda).exp();
        let airy = |r01: Complex64, r12: Complex64| {
            let r = (r01 + r12 * phase) / (1.0 + r01 * r12 * phase);
            if r.re.is_finite() && r.im.is_finite() {
                r
            } else {
                Complex64::from(1.0)
            }
        };
        (
            airy(r_s(n0c, cos0, n1, cos1), r_s(n1, cos1, n2, cos2)),
            airy(r_p(n0c, cos0, n1, cos1), r_p(n1, cos1, n2, cos2)),
        )
    }
}

/// cos(theta) in a layer of index `n` for Snell's invariant `n_sin`, on the branch of a
/// wave travelling forward (into the layer, decaying where it is evanescent or absorbed:
/// Im(n cos) >= 0, as the transfer-matrix method chooses).
fn forward_cos(n: Complex64, n_sin: f64) -> Complex64 {
    let s = n_sin / n;
    let cos = (1.0 - s * s).sqrt();
    let ncos = n * cos;
    let forward = if ncos.im.abs() > 1e-12 * ncos.norm() {
        ncos.im > 0.0
    } else {
        ncos.re > 0.0
    };
    if forward { cos } else { -cos }
}

/// The s-polarized amplitude reflection coefficient from medium i into medium j.
fn r_s(ni: Complex64, cos_i: Complex64, nj: Complex64, cos_j: Complex64) -> Complex64 {
    (ni * cos_i - nj * cos_j) / (ni * cos_i + nj * cos_j)
}

/// The p-polarized amplitude reflection coefficient from medium i into medium j.
fn r_p(ni: Complex64, cos_i: Complex64, nj: Complex64, cos_j: Complex64) -> Complex64 {
    (nj * cos_i - ni * cos_j) / (nj * cos_i + ni * cos_j)
}

/// A conductor's complex index (eta, k) whose normal-incidence reflectance in air is `f0`
/// (in [0, 1)): the artist-friendly metallic Fresnel of Gulbrandsen (JCGT 3(4), 2014) with
/// the edge tint equal to 1, the most metal-like index with that reflectance:
/// eta = (1 - r) / (1 + r), k = 2 sqrt(r) / (1 + r). glTF describes a metal by its base
/// colour alone; this gives a film over it the phase shifts of a metal rather than of a
/// dielectric.
pub fn conductor_index_from_reflectance(f0: f32) -> (f32, f32) {
    let r = if f0.is_finite() {
        f0.clamp(0.0, 0.9999)
    } else {
        0.0
    };
    ((1.0 - r) / (1.0 + r), 2.0 * r.sqrt() / (1.0 + r))
}
