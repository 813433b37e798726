//! Materials of a render-ready scene and the BSDF each becomes at a hit.

use std::sync::Arc;

use glam::Vec3;
use prism_sampling::wavelength::ReradiationSampler;
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use super::{Layers, SurfaceFrame};
use crate::bsdf::{
    Bsdf, CoatingAlbedo, Diffuse, Distribution, Ggx, MetallicRoughness, Microfacet, Plastic,
    PlasticCoating, RoughConductor, RoughDielectric, Sheet, SheetElement, ThinDielectric,
    TransportMode,
};
use crate::textures::{RgbTexture, SceneSpectrum, TexCoords};

/// A surface's material, with spectral parameters not yet sampled.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum Material {
    /// Lambertian reflection.
    Diffuse {
        /// Reflectance in [0, 1].
        reflectance: SceneSpectrum,
    },
    /// The glTF metallic-roughness BSDF ([`MetallicRoughness`]).
    MetallicRoughness {
        /// Base colour (reflectance).
        base: SceneSpectrum,
        /// Metallic factor in [0, 1].
        metallic: f32,
        /// Perceptual roughness in [0, 1].
        roughness: f32,
        /// glTF's metallic-roughness texture, linear, with the factors folded into its own
        /// (1, roughness, metallic): at a hit its green channel is the roughness and its
        /// blue the metallic, replacing the two numbers above (None: they hold everywhere).
        texture: Option<Arc<RgbTexture>>,
        /// The coating's albedo table for its index.
        coating: Arc<CoatingAlbedo>,
        /// A thin film over it (`KHR_materials_iridescence`), if any.
        iridescence: Option<Arc<super::IridescenceDesc>>,
        /// The other glTF extensions on it (specular, anisotropy, clear coat, sheen), if
        /// any.
        layers: Option<Arc<Layers>>,
    },
    /// A dielectric interface (glass), smooth when `roughness` is 0. The index is inside
    /// over outside, per wavelength when dispersive.
    Dielectric {
        /// Index of refraction of the inside.
        ior: SceneSpectrum,
        /// Perceptual roughness; alpha = roughness^2.
        roughness: f32,
        /// Absorption coefficient of the inside, per unit of scene length (Beer-Lambert:
        /// light crossing a distance d keeps exp(-sigma d)); None: clear.
        absorption: Option<SceneSpectrum>,
    },
    /// A conductor (metal) with complex index eta + i k relative to the outside, smooth
    /// when `roughness` is 0.
    Conductor {
        /// Real part of the index.
        eta: SceneSpectrum,
        /// Extinction coefficient.
        k: SceneSpectrum,
        /// Perceptual roughness; alpha = roughness^2.
        roughness: f32,
    },
    /// A dielectric interface with a microfacet distribution chosen by the scene
    /// (Mitsuba's `roughdielectric` with its default Beckmann distribution, or with
    /// anisotropic roughness); isotropic GGX is [`Material::Dielectric`]. The index is
    /// inside over outside.
    MicrofacetDielectric {
        /// Index of refraction of the inside.
        ior: SceneSpectrum,
        /// The distribution, alpha_x along the surface's tangent (dp/du).
        distribution: Distribution,
    },
    /// A conductor with a microfacet distribution chosen by the scene (Mitsuba's
    /// `roughconductor` with Beckmann or anisotropic roughness).
    MicrofacetConductor {
        /// Real part of the index.
        eta: SceneSpectrum,
        /// Extinction coefficient.
        k: SceneSpectrum,
        /// The distribution, alpha_x along the surface's tangent (dp/du).
        distribution: Distribution,
    },
    /// A thin dielectric sheet, smooth: light reflects with the slab's summed reflectance
    /// or passes straight through (Mitsuba's `thindielectric`, [`crate::bsdf::ThinDielectric`]).
    ThinDielectric {
        /// Index of the sheet over the outside.
        ior: SceneSpectrum,
    },
    /// Mitsuba's `roughplastic` as Mitsuba models it ([`crate::bsdf::RoughPlastic`]): a
    /// Lambertian substrate under a rough coating that loses the light single scattering
    /// loses.
    RoughPlastic {
        /// The substrate's reflectance in [0, 1].
        reflectance: SceneSpectrum,
        /// Whether the substrate's inner bounces darken its colour (Mitsuba's
        /// `nonlinear`).
        nonlinear: bool,
        /// The coating: its distribution, index and tables.
        coating: Arc<crate::bsdf::RoughPlasticCoating>,
    },
    /// A weighted mix of two materials' BSDFs (Mitsuba's `blendbsdf`,
    /// [`crate::bsdf::Blend`]): f = (1 - w) f_first + w f_second.
    Blend {
        /// The second's weight in [0, 1], a number or a texture.
        weight: Arc<crate::textures::FloatTexture>,
        /// The material weighed by 1 - w.
        first: Box<Material>,
        /// The material weighed by w.
        second: Box<Material>,
    },
    /// A Lambertian substrate under a smooth or rough dielectric coating, as Mitsuba's
    /// `plastic` and `roughplastic` ([`Plastic`]).
    Plastic {
        /// The substrate's reflectance in [0, 1].
        reflectance: SceneSpectrum,
        /// Whether the substrate's inner bounces darken its colour (Mitsuba's
        /// `nonlinear`); by default the colour is kept.
        nonlinear: bool,
        /// The coating: its index, roughness and transmittance table.
        coating: Arc<PlasticCoating>,
    },
    /// A Lambertian surface that re-radiates (fluorescence): light arriving at one
    /// wavelength leaves at another. The elastic part (`reflectance`, light leaving at the
    /// wavelength it came in at) is kept exact; the inelastic part is a discretized
    /// re-radiation matrix without its diagonal ([`crate::bsdf::fluorescence_matrix`]).
    Fluorescent {
        /// Elastic (ordinary) reflectance in [0, 1].
        reflectance: SceneSpectrum,
        /// The inelastic re-radiation and its sampler.
        reradiation: Arc<ReradiationSampler>,
    },
    /// A thin ideal linear polarizer (a filter sheet): light crosses it unbent, the part
    /// polarized along `axis` passing with `transmittance`, the rest absorbed.
    Polarizer {
        /// The transmission axis (world space), projected onto the sheet and across the
        /// light's direction.
        axis: Vec3,
        /// The fraction of light polarized along the axis that passes, in [0, 1].
        transmittance: SceneSpectrum,
    },
    /// A thin linear retarder (a wave plate): light crosses it unbent, the component
    /// polarized across `axis` delayed by `retardance` waves.
    Retarder {
        /// The fast axis (world space), projected like a polarizer's.
        axis: Vec3,
        /// The delay in waves (0.25: a quarter-wave plate) per wavelength.
        retardance: SceneSpectrum,
    },
    /// Mitsuba's `principled` (Burley's principled BSDF as Mitsuba defines it).
    Principled(Arc<super::PrincipledDesc>),
    /// Mitsuba's `principledthin` (its thin-sheet form).
    PrincipledThin(Arc<super::PrincipledThinDesc>),
    /// The boundary of a medium that light crosses unchanged (no reflection, no bending):
    /// what is inside it is the medium's, not a surface's. The volumetric path tracer
    /// passes through it; anything else sees an ideal clear sheet.
    Interface,
}

impl Material {
    /// The glass share of a glTF material, if it has one beyond clear thick glass.
    fn transmission(&self) -> Option<&super::TransmissionDesc> {
        match self {
            Material::MetallicRoughness {
                layers: Some(l), ..
            } => l.transmission.as_ref(),
            _ => None,
        }
    }

    /// The diffuse transmission of a glTF material, if any.
    fn diffuse_transmission(&self) -> Option<&super::DiffuseTransmissionDesc> {
        match self {
            Material::MetallicRoughness {
                layers: Some(l), ..
            } => l.diffuse_transmission.as_ref(),
            _ => None,
        }
    }

    /// Whether light can cross it (glass, whole or in part, or diffuse transmission).
    pub fn transmissive(&self) -> bool {
        matches!(
            self,
            Material::Dielectric { .. }
                | Material::MicrofacetDielectric { .. }
                | Material::ThinDielectric { .. }
                | Material::Polarizer { .. }
                | Material::Retarder { .. }
                | Material::Interface
        ) || self.transmission().is_some()
            || self.either(Material::transmissive)
            || self.diffuse_transmission().is_some()
            || matches!(self, Material::Principled(d) if d.transmissive())
            || matches!(self, Material::PrincipledThin(d) if d.transmissive())
    }

    /// Whether the index of refraction varies with wavelength (dispersion) where light
    /// refracts through it.
    pub fn dispersive(&self) -> bool {
        let varies = |ior: &SceneSpectrum| !matches!(ior, SceneSpectrum::Constant(_));
        match self {
            Material::Dielectric { ior, .. } | Material::MicrofacetDielectric { ior, .. } => {
                varies(ior)
            }
            Material::Blend { .. } => self.either(Material::dispersive),
            _ => self
                .transmission()
                .is_some_and(|t| !t.thin && varies(&t.ior)),
        }
    }

    /// The absorption coefficient inside, if the material bounds an absorbing volume.
    pub fn absorption(&self) -> Option<&SceneSpectrum> {
        match self {
            Material::Dielectric { absorption, .. } => absorption.as_ref(),
            Material::Blend { first, second, .. } => {
                first.absorption().or_else(|| second.absorption())
            }
            _ => self
                .transmission()
                .and_then(|t| t.absorption.as_ref())
                .or_else(|| self.diffuse_transmission()?.absorption.as_ref()),
        }
    }

    /// Whether a sampled lobe can be a Dirac delta here (smooth glass or metal): paths
    /// through it form caustics that only light paths find.
    pub fn specular(&self) -> bool {
        match self {
            Material::Dielectric { roughness, .. } | Material::Conductor { roughness, .. } => {
                Ggx::new(roughness * roughness, roughness * roughness).effectively_smooth()
            }
            Material::MicrofacetDielectric { distribution, .. }
            | Material::MicrofacetConductor { distribution, .. } => {
                distribution.effectively_smooth()
            }
            Material::Polarizer { .. }
            | Material::Retarder { .. }
            | Material::ThinDielectric { .. } => true,
            Material::Blend { .. } => self.either(Material::specular),
            Material::MetallicRoughness {
                roughness, texture, ..
            } if self.transmission().is_some() => {
                texture.is_some()
                    || Ggx::new(roughness * roughness, roughness * roughness).effectively_smooth()
            }
            _ => false,
        }
    }

    /// Whether its BSDF can be narrow at a hit ([`Bsdf::is_narrow`] with `alpha`): smooth
    /// or slightly rough glass or metal, the polarizing sheets.
    pub fn narrow(&self, alpha: f32) -> bool {
        let below = |roughness: f32| roughness * roughness <= alpha;
        match self {
            Material::Dielectric { roughness, .. } | Material::Conductor { roughness, .. } => {
                below(*roughness)
            }
            Material::MicrofacetDielectric { distribution, .. }
            | Material::MicrofacetConductor { distribution, .. } => {
                distribution.max_alpha() <= alpha
            }
            Material::Blend { first, second, .. } => first.narrow(alpha) && second.narrow(alpha),
            Material::MetallicRoughness {
                roughness, texture, ..
            } if self.transmission().is_some() => texture.is_some() || below(*roughness),
            _ => self.specular(),
        }
    }

    /// Whether light leaving it can be focused ([`Material::narrow`] with `alpha`, or a
    /// delta lobe of any kind: a smooth plastic's coating too): every surface at which a
    /// light path's first bounce can count as a caustic's.
    pub fn focuses(&self, alpha: f32) -> bool {
        match self {
            Material::Plastic { coating, .. } => coating.distribution().effectively_smooth(),
            Material::Blend { first, second, .. } => first.focuses(alpha) || second.focuses(alpha),
            _ => self.narrow(alpha),
        }
    }

    /// Whether its reflectance or metallic-roughness parameters come from textures (what
    /// footprint filtering applies to).
    pub fn textured(&self) -> bool {
        let textured = |s: &SceneSpectrum| matches!(s, SceneSpectrum::Texture(_));
        match self {
            Material::Diffuse { reflectance }
            | Material::Fluorescent { reflectance, .. }
            | Material::Plastic { reflectance, .. }
            | Material::RoughPlastic { reflectance, .. } => textured(reflectance),
            Material::MetallicRoughness {
                base,
                texture,
                iridescence,
                layers,
                ..
            } => {
                textured(base)
                    || texture.is_some()
                    || iridescence.as_ref().is_some_and(|i| i.textured())
                    || layers.as_ref().is_some_and(|l| l.textured())
            }
            Material::Principled(d) => d.textured(),
            Material::PrincipledThin(d) => d.textured(),
            Material::Blend { weight, .. } => {
                weight.constant().is_none() || self.either(Material::textured)
            }
            _ => false,
        }
    }

    /// Whether its BSDF needs the surface's tangent frame at a hit
    /// ([`Material::bsdf_oriented`]).
    pub fn oriented(&self) -> bool {
        match self {
            Material::MetallicRoughness {
                layers: Some(l), ..
            } => l.oriented(),
            Material::Polarizer { .. } | Material::Retarder { .. } => true,
            Material::Principled(d) => d.anisotropic(),
            Material::PrincipledThin(d) => d.anisotropic(),
            Material::Blend { .. } => self.either(Material::oriented),
            _ => false,
        }
    }

    /// Whether either material of a blend has `property` (false for other materials).
    fn either(&self, property: impl Fn(&Material) -> bool) -> bool {
        match self {
            Material::Blend { first, second, .. } => property(first) || property(second),
            _ => false,
        }
    }

    /// Whether it is a polarizing element (a polarizer or a retarder), whose effect only
    /// polarized renders show.
    pub fn polarizing_element(&self) -> bool {
        matches!(self, Material::Polarizer { .. } | Material::Retarder { .. })
    }

    /// Whether it is an interface (a medium's boundary light crosses unchanged).
    pub fn interface(&self) -> bool {
        matches!(self, Material::Interface)
    }

    /// Whether a medium can be inside it: an interface, or a boundary light crosses (a
    /// dielectric, glTF glass that is not thin-walled, or a diffusely transmitting skin).
    pub fn can_hold_medium(&self) -> bool {
        match self {
            Material::Interface
            | Material::Dielectric { .. }
            | Material::MicrofacetDielectric { .. } => true,
            Material::Blend { .. } => self.either(Material::can_hold_medium),
            _ => {
                self.transmission().is_some_and(|t| !t.thin)
                    || self.diffuse_transmission().is_some()
            }
        }
    }

    /// Whether the material re-radiates (fluorescence).
    pub fn fluorescent(&self) -> bool {
        matches!(self, Material::Fluorescent { .. })
    }

    /// The BSDF at a hit with texture coordinates `at`, its parameters sampled at
    /// `wavelengths`. For a fluorescent
    /// material this is its elastic part only: the integrator handles the change of
    /// wavelength itself (it must also change the wavelengths the path carries on with).
    pub fn bsdf<const N: usize>(
        &self,
        at: impl Into<TexCoords>,
        wavelengths: &SampledWavelengths<N>,
    ) -> Bsdf<'_, N> {
        self.bsdf_for(at, wavelengths, TransportMode::Radiance)
    }

    /// [`Material::bsdf`] for paths carrying `mode`: light paths transport importance,
    /// which refraction does not scale by 1 / eta^2.
    pub fn bsdf_for<const N: usize>(
        &self,
        at: impl Into<TexCoords>,
        wavelengths: &SampledWavelengths<N>,
        mode: TransportMode,
    ) -> Bsdf<'_, N> {
        self.bsdf_tinted(at, wavelengths, mode, None)
    }

    /// [`Material::bsdf_for`] with the base colour's reflectance (diffuse, metallic-
    /// roughness and fluorescent materials' reflectance) multiplied by `tint` (a vertex
    /// colour's spectrum), if any.
    pub fn bsdf_tinted<const N: usize>(
        &self,
        at: impl Into<TexCoords>,
        wavelengths: &SampledWavelengths<N>,
        mode: TransportMode,
        tint: Option<SampledSpectrum<N>>,
    ) -> Bsdf<'_, N> {
        self.bsdf_at(&at.into(), wavelengths, mode, tint)
    }

    /// [`Material::bsdf_tinted`] with textures filtered over the footprints of `at`
    /// (mipmapping; `-inf`: unfiltered texels).
    #[inline(always)]
    pub fn bsdf_at<const N: usize>(
        &self,
        at: &TexCoords,
        wavelengths: &SampledWavelengths<N>,
        mode: TransportMode,
        tint: Option<SampledSpectrum<N>>,
    ) -> Bsdf<'_, N> {
        self.bsdf_oriented(at, wavelengths, mode, tint, None)
    }

    /// [`Material::bsdf_at`] on a surface oriented by `frame` (what anisotropy and a
    /// coat's normal texture are read in; without it they are isotropic and follow the
    /// base).
    #[inline(always)]
    pub fn bsdf_oriented<const N: usize>(
        &self,
        at: &TexCoords,
        wavelengths: &SampledWavelengths<N>,
        mode: TransportMode,
        tint: Option<SampledSpectrum<N>>,
        frame: Option<&SurfaceFrame>,
    ) -> Bsdf<'_, N> {
        let base = |s: &SceneSpectrum| match tint {
            Some(t) => s.at_uv(*at, wavelengths) * t,
            None => s.at_uv(*at, wavelengths),
        };
        match self {
            Material::Diffuse { reflectance } => Bsdf::Diffuse(Diffuse::new(base(reflectance))),
            Material::Plastic {
                reflectance,
                nonlinear,
                coating,
            } => Bsdf::Plastic(Plastic::new(base(reflectance), coating, *nonlinear)),
            Material::RoughPlastic {
                reflectance,
                nonlinear,
                coating,
            } => Bsdf::RoughPlastic(crate::bsdf::RoughPlastic::new(
                base(reflectance),
                coating,
                *nonlinear,
            )),
            Material::MetallicRoughness {
                base: base_colour,
                metallic,
                roughness,
                texture,
                coating,
                iridescence,
                layers,
            } => {
                let (metallic, roughness) = match texture {
                    Some(t) => {
                        let [_, roughness, metallic] = t.sample_at(at);
                        (metallic, roughness)
                    }
                    None => (*metallic, *roughness),
                };
                let colour = base(base_colour);
                let bsdf = MetallicRoughness::new(colour, metallic, roughness, coating);
                if layers.is_none() && iridescence.is_none() {
                    return Bsdf::MetallicRoughness(bsdf);
                }
                super::layers::extended_bsdf(
                    bsdf,
                    super::layers::HitParameters {
                        layers: layers.as_deref(),
                        iridescence: iridescence.as_deref(),
                        at,
                        frame,
                        mode,
                        base: colour,
                        metallic,
                        roughness,
                    },
                    wavelengths,
                )
            }
            Material::Dielectric { ior, roughness, .. } => {
                let alpha = roughness * roughness;
                let eta = ior.at(wavelengths).0.map(|e| e.max(1e-3));
                Bsdf::Dielectric(RoughDielectric {
                    distribution: Ggx::new(alpha, alpha),
                    eta,
                    mode,
                })
            }
            Material::Conductor { eta, k, roughness } => {
                let alpha = roughness * roughness;
                Bsdf::Conductor(RoughConductor {
                    distribution: Ggx::new(alpha, alpha),
                    eta: eta.at(wavelengths),
                    k: k.at(wavelengths),
                })
            }
            Material::MicrofacetDielectric { ior, distribution } => {
                Bsdf::MicrofacetDielectric(RoughDielectric {
                    distribution: *distribution,
                    eta: ior.at(wavelengths).0.map(|e| e.max(1e-3)),
                    mode,
                })
            }
            Material::MicrofacetConductor {
                eta,
                k,
                distribution,
            } => Bsdf::MicrofacetConductor(RoughConductor {
                distribution: *distribution,
                eta: eta.at(wavelengths),
                k: k.at(wavelengths),
            }),
            Material::ThinDielectric { ior } => Bsdf::ThinDielectric(ThinDielectric {
                distribution: Ggx::new(0.0, 0.0),
                eta: ior.at(wavelengths).0,
            }),
            Material::Fluorescent { reflectance, .. } => {
                Bsdf::Diffuse(Diffuse::new(base(reflectance)))
            }
            Material::Blend {
                weight,
                first,
                second,
            } => {
                let w = weight.value(at.uv[0]);
                Bsdf::Blend(Box::new(crate::bsdf::Blend {
                    first: first.bsdf_oriented(at, wavelengths, mode, tint, frame),
                    second: second.bsdf_oriented(at, wavelengths, mode, tint, frame),
                    weight: if w.is_nan() { 0.0 } else { w.clamp(0.0, 1.0) },
                }))
            }
            Material::Polarizer {
                axis,
                transmittance,
            } => Bsdf::Sheet(Sheet {
                element: SheetElement::Polarizer,
                axis: local_axis(*axis, frame),
                transmittance: transmittance
                    .at(wavelengths)
                    .map(|t| 0.5 * t.clamp(0.0, 1.0)),
            }),
            Material::Retarder { axis, retardance } => {
                let waves = retardance.at(wavelengths);
                Bsdf::Sheet(Sheet {
                    element: SheetElement::Retarder(std::array::from_fn(|i| {
                        std::f32::consts::TAU * waves[i]
                    })),
                    axis: local_axis(*axis, frame),
                    transmittance: SampledSpectrum::splat(1.0),
                })
            }
            Material::Principled(d) => d.bsdf(at, wavelengths, mode, tint, frame),
            Material::PrincipledThin(d) => d.bsdf(at, wavelengths, tint, frame),
            // A clear sheet: a retarder that delays nothing.
            Material::Interface => Bsdf::Sheet(Sheet {
                element: SheetElement::Retarder([0.0; N]),
                axis: glam::Vec3::X,
                transmittance: SampledSpectrum::splat(1.0),
            }),
        }
    }
}

/// A sheet's world axis in the local shading frame (read as local without a frame).
fn local_axis(axis: Vec3, frame: Option<&SurfaceFrame>) -> Vec3 {
    match frame {
        Some(f) => f.frame.to_local(axis),
        None => axis,
    }
}
