use glam::{Vec2, Vec3};
use prism_sampling::distribution::positive_finite;
use prism_sampling::warp::{cosine_hemisphere, cosine_hemisphere_pdf};
use prism_spectrum::SampledSpectrum;

use super::coating_albedo::CoatingAlbedo;
use super::microfacet::Ggx;
use super::thin_film::{ThinFilm, conductor_index_from_reflectance};
use super::{BsdfSample, fresnel_dielectric, same_hemisphere};

/// The specular lobes of a [`MetallicRoughness`] at one pair of directions
/// ([`MetallicRoughness::specular_parts`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpecularParts<const N: usize> {
    /// The microfacet normal (local frame, +z side).
    pub half: Vec3,
    /// What the dielectric coating reflects, per lane (its share of f).
    pub coating: SampledSpectrum<N>,
    /// What the metal reflects, per lane (its share of f).
    pub metal: SampledSpectrum<N>,
}

/// `KHR_materials_iridescence` at one hit: a thin film over the dielectric and the metal
/// alike, whose Fresnel reflectance (solved per wavelength, [`ThinFilm`]) replaces the
/// bare surface's in proportion `factor`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Iridescence<const N: usize> {
    /// glTF's `iridescenceFactor` (times its texture), in [0, 1].
    pub factor: f32,
    /// The film (glTF's `iridescenceIor` and the thickness at the hit).
    pub film: ThinFilm,
    /// The path's wavelengths (nm), lane by lane: the film's colour depends on them.
    pub lambdas: [f32; N],
    /// The film's index per lane where it is a measured spectrum (`film.ior` otherwise).
    pub iors: Option<[f32; N]>,
}

impl<const N: usize> Iridescence<N> {
    /// The film lane `lane` sees.
    pub fn film_at(&self, lane: usize) -> ThinFilm {
        match &self.iors {
            Some(iors) => ThinFilm {
                ior: iors[lane],
                ..self.film
            },
            None => self.film,
        }
    }
}

/// `KHR_materials_specular` at one hit: the strength (`specularFactor`, times its texture)
/// and colour (`specularColorFactor` times its texture, upsampled) of the dielectric
/// base's reflection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Specular<const N: usize> {
    /// The weight, F90 of the extension: the reflectance at grazing incidence.
    pub weight: f32,
    /// The colour per lane, multiplying the reflectance at normal incidence.
    pub color: SampledSpectrum<N>,
}

/// `KHR_materials_diffuse_transmission` at one hit: the share of the diffuse base that
/// leaves through the other side, and its colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiffuseTransmission<const N: usize> {
    /// `diffuseTransmissionFactor` (times its texture), in [0, 1].
    pub factor: f32,
    /// `diffuseTransmissionColorFactor` (times its texture) per lane, in [0, 1].
    pub color: SampledSpectrum<N>,
}

/// The specular extension's Fresnel per lane, as the extension defines its end points and
/// the exact dielectric Fresnel term shapes the curve between them:
/// F(cos) = F0' + (F90 - F0') (F_exact(cos) - F0) / (1 - F0), with F0' = min(F0 c, 1) F90
/// (F0: the exact term at normal incidence). Affine in the exact term, so the coating's
/// albedo follows exactly from the tabulated ones (E and the mirror's E_1).
#[derive(Debug, Clone, Copy)]
struct SpecularLanes<const N: usize> {
    weight: f32,
    f0: [f32; N],
}

/// Gauss-Legendre nodes and weights on [0, 1] (16 points): the average over mu of the
/// filmed albedo, which oscillates with the film's phase.
const GAUSS_16: [(f32, f32); 8] = [
    (0.989_400_9, 0.027_152_46),
    (0.944_575, 0.062_253_52),
    (0.865_631_2, 0.095_158_51),
    (0.755_404_4, 0.124_628_97),
    (0.617_876_2, 0.149_595_99),
    (0.458_016_8, 0.169_156_52),
    (0.281_603_6, 0.182_603_42),
    (0.095_012_5, 0.189_450_6),
];

/// The glTF metallic-roughness material (glTF 2.0 specification, Appendix B) as a
/// physically based, energy-conserving BSDF:
///
/// - dielectric: a GGX coating reflecting with the exact dielectric Fresnel term
///   (index `eta`, 1.5 by default) over a diffuse base whose lobe is
///   `base (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg))`, E the coating's directional
///   albedo ([`CoatingAlbedo`]). With a white base the total albedo is
///   E(mu_o) + (1 - E(mu_o)) = 1 exactly (up to the table's accuracy), and the form is
///   reciprocal (Kulla and Conty 2017).
/// - metal: GGX reflection with Schlick's Fresnel, F0 = base colour, as glTF defines it.
/// - blended by `metallic`: f = (1 - m) f_dielectric + m f_metal.
///
/// Roughness is glTF's perceptual roughness; alpha = roughness^2.
///
/// With [`Iridescence`], a thin film lies on both: the Fresnel term of the coating and of
/// the metal (at the microfacet normal) becomes a mix of the bare one and the film's, per
/// wavelength, as `KHR_materials_iridescence` defines it (the metal's complex index from
/// its base colour, [`conductor_index_from_reflectance`]). The diffuse base keeps what the
/// filmed coating does not reflect, in the same albedo-scaling form with the coating's
/// albedo E replaced by the filmed coating's, estimated per lane as
/// E_film(mu) = E(mu) F_film(mu) / F(mu) (exact for a smooth coating, and equal to E
/// where the film is absent) and its average by quadrature: reciprocal. Measured by the
/// furnace test, a white base under the films glTF files describe (index up to 2, 100 to
/// 400 nm) reflects 1 within 2%; under a thick high-index film (2.4, 600 nm) on a rough
/// coating, whose reflectance oscillates across the lobe, within 8% either way.
///
/// The extensions' state lives behind one allocation, made only for a material that has
/// them: the plain material stays small, so that every BSDF of a scene without them is
/// cheap to build and move (measured: inline, it made the Cornell box's paths take more
/// instructions).
#[derive(Debug, Clone)]
pub struct MetallicRoughness<'a, const N: usize> {
    base: SampledSpectrum<N>,
    metallic: f32,
    distribution: Ggx,
    /// The roughness the albedo tables are read at (the isotropic alpha, or the
    /// root-mean-square of an anisotropic pair).
    table_alpha: f32,
    coating: &'a CoatingAlbedo,
    extended: Option<Box<Extended<N>>>,
}

/// What the glTF extensions add to a [`MetallicRoughness`] at one hit.
#[derive(Debug, Clone)]
struct Extended<const N: usize> {
    /// cos and sin of the angle from the local frame's x to the anisotropy direction.
    rotation: Option<Vec2>,
    iridescence: Option<Iridescence<N>>,
    specular: Option<SpecularLanes<N>>,
    diffuse_transmission: Option<DiffuseTransmission<N>>,
    /// 1 - the coating's average albedo per lane, once a film or the specular extension
    /// makes it differ from the table's.
    kept_average: [f32; N],
}

impl<'a, const N: usize> MetallicRoughness<'a, N> {
    /// The material at one hit. `base` and `metallic` are clamped into [0, 1]; `coating`
    /// must be the albedo table for the material's index (glTF default 1.5).
    pub fn new(
        base: SampledSpectrum<N>,
        metallic: f32,
        roughness: f32,
        coating: &'a CoatingAlbedo,
    ) -> Self {
        let unit = |v: f32| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        let roughness = unit(roughness);
        let alpha = roughness * roughness;
        let distribution = Ggx::new(alpha, alpha);
        Self {
            base: base.map(unit),
            metallic: unit(metallic),
            distribution,
            table_alpha: distribution.alpha_x,
            coating,
            extended: None,
        }
    }

    /// The extensions' state, created on first use.
    fn extend(mut self, change: impl FnOnce(&mut Extended<N>)) -> Self {
        let kept = 1.0 - self.coating.average(self.table_alpha);
        let extended = self.extended.get_or_insert_with(|| {
            Box::new(Extended {
                rotation: None,
                iridescence: None,
                specular: None,
                diffuse_transmission: None,
                kept_average: [kept; N],
            })
        });
        change(extended);
        self
    }

    fn rotation(&self) -> Option<Vec2> {
        self.extended.as_ref()?.rotation
    }

    fn iridescence(&self) -> Option<&Iridescence<N>> {
        self.extended.as_ref()?.iridescence.as_ref()
    }

    fn specular(&self) -> Option<&SpecularLanes<N>> {
        self.extended.as_ref()?.specular.as_ref()
    }

    fn diffuse_transmission(&self) -> Option<&DiffuseTransmission<N>> {
        self.extended.as_ref()?.diffuse_transmission.as_ref()
    }

    /// 1 - the coating's average albedo in lane `lane`.
    fn kept(&self, lane: usize) -> f32 {
        match &self.extended {
            Some(e) => e.kept_average[lane],
            None => 1.0 - self.coating.average(self.table_alpha),
        }
    }

    /// The same material with `KHR_materials_specular`'s strength and colour on the
    /// dielectric base (the metal is not affected, as the extension says).
    pub fn with_specular(self, specular: Specular<N>) -> Self {
        let unit = |v: f32| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        let weight = unit(specular.weight);
        let f0 = fresnel_dielectric(1.0, self.coating.eta());
        let lanes = SpecularLanes {
            weight,
            f0: std::array::from_fn(|i| {
                let c = specular.color[i];
                let c = if c.is_nan() { 0.0 } else { c.max(0.0) };
                (f0 * c).min(1.0) * weight
            }),
        };
        self.extend(|e| e.specular = Some(lanes)).with_averages()
    }

    /// The same material with `KHR_materials_diffuse_transmission`: a share `factor` of
    /// its diffuse base leaves through the other side, coloured, as Lambertian
    /// transmission (the coating above it on both sides, in the same albedo-scaling form as
    /// the reflection: a white base with a white transmission colour reflects and
    /// transmits everything between them).
    pub fn with_diffuse_transmission(self, transmission: DiffuseTransmission<N>) -> Self {
        let unit = |v: f32| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        let factor = unit(transmission.factor);
        if factor == 0.0 {
            return self;
        }
        self.extend(|e| {
            e.diffuse_transmission = Some(DiffuseTransmission {
                factor,
                color: transmission.color.map(unit),
            })
        })
    }

    /// The share of the diffuse base that is transmitted.
    fn transmitted_share(&self) -> f32 {
        self.diffuse_transmission().map_or(0.0, |d| d.factor)
    }

    /// The diffuse base's transmission lobe for directions on opposite sides.
    fn f_transmitted(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        let Some(dt) = self.diffuse_transmission() else {
            return SampledSpectrum::splat(0.0);
        };
        let (mu_o, mu_i) = (wo.z.abs(), wi.z.abs());
        let weight = (1.0 - self.metallic) * dt.factor / std::f32::consts::PI;
        SampledSpectrum::from_fn(|i| {
            weight
                * dt.color[i]
                * (1.0 - self.coat_albedo(mu_o, i))
                * (1.0 - self.coat_albedo(mu_i, i))
                / self.kept(i)
        })
    }

    /// The same material made anisotropic (`KHR_materials_anisotropy`): `strength` in
    /// [0, 1] stretches the roughness along `direction` (a unit vector in the local
    /// frame's xy plane) to alpha_t = mix(alpha, 1, strength^2), keeping alpha across it.
    pub fn with_anisotropy(self, strength: f32, direction: Vec2) -> Self {
        let strength = if strength.is_nan() {
            0.0
        } else {
            strength.clamp(0.0, 1.0)
        };
        let Some(direction) = direction.try_normalize() else {
            return self;
        };
        if strength == 0.0 {
            return self;
        }
        let alpha = self.distribution.alpha_y;
        let along = alpha + (1.0 - alpha) * strength * strength;
        let table_alpha = ((along * along + alpha * alpha) / 2.0).sqrt();
        Self {
            distribution: Ggx::new(along, alpha),
            table_alpha,
            ..self
        }
        .extend(|e| e.rotation = Some(direction))
        .with_averages()
    }

    /// The same material under a thin film (`factor` clamped into [0, 1]; 0 leaves it
    /// bare).
    pub fn with_iridescence(self, iridescence: Iridescence<N>) -> Self {
        let factor = if iridescence.factor.is_nan() {
            0.0
        } else {
            iridescence.factor.clamp(0.0, 1.0)
        };
        if factor == 0.0 {
            return match self.extended {
                Some(_) => self.extend(|e| e.iridescence = None).with_averages(),
                None => self,
            };
        }
        self.extend(|e| {
            e.iridescence = Some(Iridescence {
                factor,
                ..iridescence
            })
        })
        .with_averages()
    }

    /// Recomputes what the diffuse base keeps on average per lane after a film or the
    /// specular extension changed the coating: E_avg + 2 int (E' - E) mu dmu by
    /// quadrature under a film (whose reflectance oscillates with angle), exactly from
    /// the tables otherwise.
    fn with_averages(self) -> Self {
        let alpha = self.table_alpha;
        let base_average = self.coating.average(alpha);
        let kept_average = std::array::from_fn(|i| {
            let average = if self.iridescence().is_some() {
                let mut correction = 0.0;
                for (x, w) in GAUSS_16 {
                    for mu in [0.5 * (1.0 + x), 0.5 * (1.0 - x)] {
                        let e = self.coating.albedo(mu, alpha);
                        correction += w * (self.coat_albedo(mu, i) - e) * mu;
                    }
                }
                base_average + correction
            } else if let Some(spec) = self.specular() {
                spec.albedo(
                    base_average,
                    self.coating.mirror_average(alpha),
                    fresnel_dielectric(1.0, self.coating.eta()),
                    i,
                )
            } else {
                base_average
            };
            1.0 - average.clamp(0.0, 0.999)
        });
        self.extend(|e| e.kept_average = kept_average)
    }

    /// The coating's reflectance at cos `cos` (of the microfacet normal) in lane `lane`,
    /// given the bare dielectric's there: the film mixed in by its factor, and the
    /// specular extension's remapping as a ratio to the bare term.
    fn coat_fresnel(&self, cos: f32, bare: f32, lane: usize) -> f32 {
        let eta = self.coating.eta();
        let mut f = bare;
        if let Some(film) = self.iridescence() {
            let filmed = film
                .film_at(lane)
                .reflectance(cos, film.lambdas[lane], 1.0, eta, 0.0);
            f += film.factor * (filmed - bare);
        }
        if let Some(spec) = self.specular() {
            let remapped = spec.fresnel(bare, fresnel_dielectric(1.0, eta), lane);
            f = if bare > 1e-6 {
                f * remapped / bare
            } else {
                remapped
            };
        }
        f.clamp(0.0, 1.0)
    }

    /// The coating's directional albedo at `mu` in lane `lane`: the table's; exact under
    /// the specular extension alone; under a film estimated as E F'(mu) / F(mu) (exact
    /// for a smooth coating, and equal to E where the film is absent). (Averaging the
    /// ratio over the microfacet angles a rough coating reflects through did not bring the
    /// furnace closer to 1: measured, and left out.)
    fn coat_albedo(&self, mu: f32, lane: usize) -> f32 {
        let alpha = self.table_alpha;
        let e = self.coating.albedo(mu, alpha);
        if self.iridescence().is_some() {
            let bare = fresnel_dielectric(mu, self.coating.eta());
            (e * self.coat_fresnel(mu, bare, lane) / bare.max(1e-6)).clamp(0.0, 0.999)
        } else if let Some(spec) = self.specular() {
            let f0 = fresnel_dielectric(1.0, self.coating.eta());
            spec.albedo(e, self.coating.mirror_albedo(mu, alpha), f0, lane)
                .clamp(0.0, 0.999)
        } else {
            e
        }
    }

    /// The probability of sampling the microfacet reflection lobe rather than the diffuse
    /// base: the metal's share plus the coating's albedo (the lanes' mean where it
    /// varies).
    fn specular_probability(&self, mu_o: f32) -> f32 {
        let coating = if self.iridescence().is_none() && self.specular().is_none() {
            self.coating.albedo(mu_o, self.table_alpha)
        } else {
            (0..N).map(|i| self.coat_albedo(mu_o, i)).sum::<f32>() / N as f32
        };
        self.metallic + (1.0 - self.metallic) * coating
    }

    /// A local direction in the anisotropy's frame (x along its direction), and back.
    fn aligned(&self, w: Vec3) -> Vec3 {
        match self.rotation() {
            Some(r) => Vec3::new(r.x * w.x + r.y * w.y, r.x * w.y - r.y * w.x, w.z),
            None => w,
        }
    }

    fn unaligned(&self, w: Vec3) -> Vec3 {
        match self.rotation() {
            Some(r) => Vec3::new(r.x * w.x - r.y * w.y, r.y * w.x + r.x * w.y, w.z),
            None => w,
        }
    }

    /// f(wo, wi); reflection only (0 across the surface).
    pub fn f(&self, wo: Vec3, wi: Vec3) -> SampledSpectrum<N> {
        let (wo, wi) = (self.aligned(wo), self.aligned(wi));
        if !same_hemisphere(wo, wi) {
            if wo.z * wi.z < 0.0 {
                return self.f_transmitted(wo, wi);
            }
            return SampledSpectrum::splat(0.0);
        }
        let (mu_o, mu_i) = (wo.z.abs(), wi.z.abs());
        let Some(wm) = (wo + wi).try_normalize() else {
            return SampledSpectrum::splat(0.0);
        };
        let wm = if wm.z < 0.0 { -wm } else { wm };
        let d = &self.distribution;
        let microfacet = d.d(wm) * d.g(wo, wi) / (4.0 * mu_o * mu_i);
        // At grazing angles of a near-smooth lobe the quotient over- or underflows.
        let microfacet = if microfacet.is_finite() {
            microfacet
        } else {
            0.0
        };
        let cos_h = wo.dot(wm).abs();
        let eta = self.coating.eta();
        let bare = fresnel_dielectric(cos_h, eta);
        let schlick = (1.0 - cos_h).powi(5);
        let m = self.metallic;
        if self.iridescence().is_none()
            && self.specular().is_none()
            && self.diffuse_transmission().is_none()
        {
            let alpha = self.table_alpha;
            let diffuse_weight = (1.0 - self.coating.albedo(mu_o, alpha))
                * (1.0 - self.coating.albedo(mu_i, alpha))
                / (std::f32::consts::PI * (1.0 - self.coating.average(alpha)));
            return SampledSpectrum::from_fn(|i| {
                let dielectric = microfacet * bare + self.base[i] * diffuse_weight;
                let metal = microfacet * (self.base[i] + (1.0 - self.base[i]) * schlick);
                (1.0 - m) * dielectric + m * metal
            });
        }
        SampledSpectrum::from_fn(|i| {
            let coated = self.coat_fresnel(cos_h, bare, i);
            let diffuse = (1.0 - self.coat_albedo(mu_o, i)) * (1.0 - self.coat_albedo(mu_i, i))
                / (std::f32::consts::PI * self.kept(i));
            let reflected = self.base[i] * (1.0 - self.transmitted_share());
            let dielectric = microfacet * coated + reflected * diffuse;
            let metal = if m > 0.0 {
                microfacet * self.metal_fresnel(cos_h, schlick, i)
            } else {
                0.0
            };
            (1.0 - m) * dielectric + m * metal
        })
    }

    /// The metal's reflectance at cos `cos_h` (of the microfacet normal; `schlick` =
    /// (1 - cos_h)^5) in lane `lane`: Schlick's from the base colour, the film mixed in.
    fn metal_fresnel(&self, cos_h: f32, schlick: f32, lane: usize) -> f32 {
        let f0 = self.base[lane];
        let bare_metal = f0 + (1.0 - f0) * schlick;
        match self.iridescence() {
            Some(film) => {
                let (eta_m, k_m) = conductor_index_from_reflectance(f0);
                let filmed =
                    film.film_at(lane)
                        .reflectance(cos_h, film.lambdas[lane], 1.0, eta_m, k_m);
                bare_metal + film.factor * (filmed - bare_metal)
            }
            None => bare_metal,
        }
    }

    /// The two specular lobes of f(wo, wi), apart, for directions on one side: what the
    /// dielectric coating reflects and what the metal reflects (the diffuse base is the
    /// rest of f), with their microfacet normal. Polarized renders give each its own
    /// Fresnel Mueller matrix. None across the surface.
    pub fn specular_parts(&self, wo: Vec3, wi: Vec3) -> Option<SpecularParts<N>> {
        let (wo, wi) = (self.aligned(wo), self.aligned(wi));
        if !same_hemisphere(wo, wi) {
            return None;
        }
        let wm = (wo + wi).try_normalize()?;
        let wm = if wm.z < 0.0 { -wm } else { wm };
        let d = &self.distribution;
        let microfacet = d.d(wm) * d.g(wo, wi) / (4.0 * wo.z.abs() * wi.z.abs());
        let microfacet = if microfacet.is_finite() {
            microfacet
        } else {
            0.0
        };
        let cos_h = wo.dot(wm).abs();
        let bare = fresnel_dielectric(cos_h, self.coating.eta());
        let schlick = (1.0 - cos_h).powi(5);
        let m = self.metallic;
        Some(SpecularParts {
            half: self.unaligned(wm),
            coating: SampledSpectrum::from_fn(|i| {
                (1.0 - m) * microfacet * self.coat_fresnel(cos_h, bare, i)
            }),
            metal: SampledSpectrum::from_fn(|i| {
                m * microfacet * self.metal_fresnel(cos_h, schlick, i)
            }),
        })
    }

    /// The coating's index of refraction (glTF's `ior`).
    pub fn coating_ior(&self) -> f32 {
        self.coating.eta()
    }

    /// The base colour per lane: the metal's reflectance at normal incidence.
    pub fn base_color(&self) -> &SampledSpectrum<N> {
        &self.base
    }

    /// The iridescent film over the surface, if any.
    pub fn film(&self) -> Option<&Iridescence<N>> {
        self.iridescence()
    }

    /// The density of [`MetallicRoughness::sample`] returning `wi`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let (wo, wi) = (self.aligned(wo), self.aligned(wi));
        if !same_hemisphere(wo, wi) {
            if wo.z * wi.z < 0.0 && self.diffuse_transmission().is_some() {
                let q = self.specular_probability(wo.z.abs());
                let diffuse = cosine_hemisphere_pdf(Vec3::new(wi.x, wi.y, wi.z.abs()));
                return (1.0 - q) * self.transmitted_share() * diffuse;
            }
            return 0.0;
        }
        let Some(wm) = (wo + wi).try_normalize() else {
            return 0.0;
        };
        let wm = if wm.z * wo.z < 0.0 { -wm } else { wm };
        let specular = self.distribution.d_visible(wo, wm) / (4.0 * wo.dot(wm).abs());
        let diffuse = cosine_hemisphere_pdf(Vec3::new(wi.x, wi.y, wi.z.abs()));
        let q = self.specular_probability(wo.z.abs());
        if self.diffuse_transmission().is_some() {
            return q * specular + (1.0 - q) * (1.0 - self.transmitted_share()) * diffuse;
        }
        q * specular + (1.0 - q) * diffuse
    }

    /// Chooses the reflection lobe (visible normals) or the diffuse base (cosine) with
    /// `uc`, returning the mixture density.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<N>> {
        if wo.z == 0.0 || !wo.is_finite() {
            return None;
        }
        let wo_aligned = self.aligned(wo);
        let q = self.specular_probability(wo.z.abs());
        let wi = if uc < q {
            let wm = self.distribution.sample_visible_normal(wo_aligned, u);
            let wi = self.unaligned(2.0 * wo_aligned.dot(wm) * wm - wo_aligned);
            if !same_hemisphere(wo, wi) {
                return None;
            }
            wi
        } else {
            let w = cosine_hemisphere(u);
            // Through the surface with the transmitted share's probability.
            let through = (uc - q) / (1.0 - q) < self.transmitted_share();
            if (wo.z < 0.0) != through {
                Vec3::new(w.x, w.y, -w.z)
            } else {
                w
            }
        };
        if wi.z * wo.z == 0.0 || (!same_hemisphere(wo, wi) && self.diffuse_transmission().is_none())
        {
            return None;
        }
        let pdf = self.pdf(wo, wi);
        if !positive_finite(pdf) {
            return None;
        }
        Some(BsdfSample::smooth(wi, self.f(wo, wi), [pdf; N]))
    }
}

impl<const N: usize> SpecularLanes<N> {
    /// The remapped reflectance in lane `lane` where the exact term is `exact` (`f0`: the
    /// exact term at normal incidence).
    fn fresnel(&self, exact: f32, f0: f32, lane: usize) -> f32 {
        let shape = if f0 < 1.0 - 1e-4 {
            ((exact - f0) / (1.0 - f0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        self.f0[lane] + (self.weight - self.f0[lane]) * shape
    }

    /// The albedo of the remapped lobe from the exact lobe's `e` and the mirror's `e1`:
    /// F0' E_1 + (F90 - F0') (E - F0 E_1) / (1 - F0).
    fn albedo(&self, e: f32, e1: f32, f0: f32, lane: usize) -> f32 {
        let shaped = if f0 < 1.0 - 1e-4 {
            ((e - f0 * e1) / (1.0 - f0)).max(0.0)
        } else {
            0.0
        };
        self.f0[lane] * e1 + (self.weight - self.f0[lane]) * shaped
    }
}
