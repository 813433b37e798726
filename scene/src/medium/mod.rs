//! Participating media: what fills a volume (fog, milk, smoke, a glowing gas), described
//! per wavelength, and how far light travels in it before it meets a particle.
//!
//! A medium is its absorption and scattering coefficients sigma_a and sigma_s (per unit
//! of scene length, m^-1 in a scene in metres), a phase function, and optionally an
//! emission coefficient (radiance added per unit length). Light crossing a distance d
//! keeps exp(-sigma_t d) of itself, sigma_t = sigma_a + sigma_s, at each wavelength.
//!
//! Where media are: a material may bound one (the medium inside its closed surface:
//! [`Media::inside`]), and the scene may be filled by one (fog: [`Media::world`]), which is
//! what a ray is in outside every boundary and where the camera starts. Mitsuba's scenes
//! place media the other way, by what each surface has on either side
//! ([`Media::with_sides`]).
//!
//! Distances are drawn by tracking against a majorant ([`track`]), the null-scattering
//! formulation of Miller, Georgiev and Jarosz (SIGGRAPH 2019), which the integrator's
//! volumetric path tracer builds on.

mod fluorescence;
mod grid;
mod phase;
mod spectral_grid;
pub mod track;
#[cfg(feature = "vdb")]
mod vdb;
mod vol;

pub use fluorescence::Fluorescence;
pub use grid::{Filter, Grid, Span, Stencil};
pub use phase::{MAX_ABS_G, Phase, PhaseSample};
pub use spectral_grid::SpectralGrid;
#[cfg(feature = "vdb")]
pub use vdb::read_vdb;
pub use vol::{VolFile, parse_vol, read_vol, write_vol};

use std::sync::Arc;

use prism_spectrum::spectra::planck_radiance;
use prism_spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};

use crate::textures::SceneSpectrum;

/// A participating medium: homogeneous, or its coefficients scaled by a density grid.
#[derive(Debug, Clone)]
pub struct Medium {
    sigma_a: SceneSpectrum,
    sigma_s: SceneSpectrum,
    phase: Phase,
    emission: Option<SceneSpectrum>,
    /// The density that scales sigma_a, sigma_s and the emission at each point.
    density: Density,
    /// Where the single-scattering albedo varies in space: sigma_s is that share of the
    /// extinction at each point, the rest absorbed (None: sigma_s's share everywhere).
    albedo: Option<Arc<Albedo>>,
    /// A fluorescent dye: its absorption joins sigma_a, and what it absorbs it re-emits at
    /// longer wavelengths (None: no dye).
    fluorescence: Option<Arc<Fluorescence>>,
    /// Temperatures in kelvin: where the medium absorbs, it also emits as a black body
    /// at the local temperature (Kirchhoff's law: sigma_a B_lambda(T)), a flame.
    temperature: Option<Arc<Grid>>,
    /// The least majorant of an emissive medium (per unit length): emission is gathered
    /// where tracking stops, so it must stop somewhere even where the medium barely
    /// absorbs or scatters.
    emissive_floor: f32,
}

/// What scales a medium's coefficients from point to point.
#[derive(Debug, Clone)]
enum Density {
    /// 1 everywhere: a homogeneous medium.
    Uniform,
    /// One number per voxel, alike at every wavelength.
    Grid(Arc<Grid>),
    /// A spectrum per voxel (Mitsuba's RGB grids).
    Spectral(Arc<SpectralGrid>),
}

/// A single-scattering albedo that varies in space (Mitsuba's `albedo` given as a
/// volume). Outside its box it keeps the value at the box's nearest face, as Mitsuba's
/// clamped grids do.
#[derive(Debug, Clone)]
pub enum Albedo {
    /// One number per voxel, alike at every wavelength.
    Grid(Grid),
    /// A spectrum per voxel.
    Spectral(SpectralGrid),
}

impl Albedo {
    /// The albedo at `p` for `wavelengths`.
    #[inline]
    fn at<const N: usize>(
        &self,
        p: glam::Vec3,
        wavelengths: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        match self {
            Albedo::Grid(g) => SampledSpectrum::splat(g.lookup_clamped(p)),
            Albedo::Spectral(g) => g.lookup_clamped(p, wavelengths),
        }
    }
}

/// The coefficients of a medium at a point, at a package's wavelengths.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MediumPoint<const N: usize> {
    /// Absorption coefficient per lane.
    pub sigma_a: SampledSpectrum<N>,
    /// Scattering coefficient per lane.
    pub sigma_s: SampledSpectrum<N>,
    /// Emission coefficient per lane (radiance per unit length), 0 where none.
    pub emission: SampledSpectrum<N>,
    /// Fluorescent in-scattering per lane: what light of every other wavelength adds to
    /// the lane's per unit length and unit radiance (0 without a dye). It does not
    /// attenuate: the dye's absorption is part of `sigma_a`.
    pub sigma_fo: SampledSpectrum<N>,
}

/// The least emissive floor: below it the collision estimator's variance is needlessly
/// high for no saving (one unit: a scene in metres collides once per metre).
const EMISSIVE_FLOOR: f64 = 1.0;

impl Medium {
    /// A homogeneous medium. The spectra must be finite and non-negative (the scene
    /// format's parser checks them; spectra from code are checked here over 360-830 nm).
    pub fn new(
        sigma_a: SceneSpectrum,
        sigma_s: SceneSpectrum,
        phase: Phase,
        emission: Option<SceneSpectrum>,
    ) -> Result<Self, String> {
        for (name, s) in [("sigma_a", Some(&sigma_a)), ("sigma_s", Some(&sigma_s))]
            .into_iter()
            .chain(std::iter::once(("emission", emission.as_ref())))
        {
            let Some(s) = s else { continue };
            for nm in (360..=830).step_by(5) {
                let v = s.evaluate(f64::from(nm));
                if !(v.is_finite() && v >= 0.0) {
                    return Err(format!(
                        "{name} is {v} at {nm} nm (must be finite and >= 0)"
                    ));
                }
            }
        }
        let mean_t = sigma_a.mean_visible() + sigma_s.mean_visible();
        let emissive_floor = if emission.is_some() {
            mean_t.max(EMISSIVE_FLOOR) as f32
        } else {
            0.0
        };
        Ok(Self {
            sigma_a,
            sigma_s,
            phase,
            emission,
            emissive_floor,
            density: Density::Uniform,
            albedo: None,
            temperature: None,
            fluorescence: None,
        })
    }

    /// The same medium with a fluorescent dye in it.
    pub fn with_fluorescence(mut self, fluorescence: Fluorescence) -> Self {
        self.fluorescence = Some(Arc::new(fluorescence));
        self
    }

    /// The fluorescent dye, if any.
    pub fn fluorescence(&self) -> Option<&Fluorescence> {
        self.fluorescence.as_deref()
    }

    /// The fluorescent dye, to change (the scene sets its guide).
    pub(crate) fn fluorescence_mut(&mut self) -> Option<&mut Fluorescence> {
        self.fluorescence.as_mut().map(Arc::make_mut)
    }

    /// The same medium glowing where it absorbs as a black body at `temperature`'s
    /// field (kelvin): emission sigma_a(lambda, p) B_lambda(T(p)) in W m^-2 sr^-1 nm^-1
    /// per unit length, added to any `emission` it has. Flames and explosions.
    pub fn with_temperature(mut self, temperature: Grid) -> Self {
        self.temperature = Some(Arc::new(temperature));
        self
    }

    /// The temperature grid, if the medium glows by its temperature.
    pub fn temperature(&self) -> Option<&Grid> {
        self.temperature.as_deref()
    }

    /// The same medium with its coefficients (and emission) scaled at each point by
    /// `density`'s field there: a heterogeneous medium, 0 outside the grid's box.
    pub fn with_density(mut self, density: Grid) -> Self {
        self.density = Density::Grid(Arc::new(density));
        self
    }

    /// The same medium with its coefficients (and emission) scaled at each point and
    /// wavelength by `density`'s spectrum there, 0 outside the grid's box: Mitsuba's
    /// extinction given as a grid of colours.
    pub fn with_spectral_density(mut self, density: SpectralGrid) -> Self {
        self.density = Density::Spectral(Arc::new(density));
        self
    }

    /// The same medium scattering `albedo`'s share of its extinction at each point (the
    /// rest absorbed), whatever sigma_a and sigma_s share it as: Mitsuba's `albedo` given
    /// as a volume. An albedo above 1 (a blend of Mitsuba's RGB grids can reach one)
    /// scatters more than the medium extinguishes, as in Mitsuba; sigma_a is then
    /// negative there, and sigma_a + sigma_s the extinction still.
    pub fn with_albedo(mut self, albedo: Albedo) -> Self {
        self.albedo = Some(Arc::new(albedo));
        self
    }

    /// The density grid, if the medium's density is one number per voxel.
    pub fn density(&self) -> Option<&Grid> {
        match &self.density {
            Density::Grid(g) => Some(g),
            _ => None,
        }
    }

    /// The density grid of spectra, if the medium's density is one.
    pub fn spectral_density(&self) -> Option<&SpectralGrid> {
        match &self.density {
            Density::Spectral(g) => Some(g),
            _ => None,
        }
    }

    /// The albedo that varies in space, if any.
    pub fn albedo(&self) -> Option<&Albedo> {
        self.albedo.as_deref()
    }

    /// The stretches of the ray `origin + t direction`, `t` in [0, `t_max`], over which
    /// the density is at most a bound, in order, each handed to `visit` until it returns
    /// false: the whole ray with bound 1 in a homogeneous medium, else the density grid's
    /// cells ([`Grid::spans`]); nothing outside a grid's box, where the density is 0.
    #[inline]
    pub fn spans(
        &self,
        origin: glam::Vec3,
        direction: glam::Vec3,
        t_max: f32,
        mut visit: impl FnMut(Span) -> bool,
    ) {
        match &self.density {
            Density::Uniform => {
                visit(Span {
                    t0: 0.0,
                    t1: t_max,
                    bound: 1.0,
                });
            }
            Density::Grid(g) => g.spans(origin, direction, t_max, visit),
            // A spectrum of the grid is at most its scale (a sigmoid is at most 1).
            Density::Spectral(g) => g.scales().spans(origin, direction, t_max, visit),
        }
    }

    /// The phase function.
    pub fn phase(&self) -> &Phase {
        &self.phase
    }

    /// The absorption coefficient.
    pub fn sigma_a(&self) -> &SceneSpectrum {
        &self.sigma_a
    }

    /// The scattering coefficient.
    pub fn sigma_s(&self) -> &SceneSpectrum {
        &self.sigma_s
    }

    /// The emission coefficient, if the medium glows.
    pub fn emission(&self) -> Option<&SceneSpectrum> {
        self.emission.as_ref()
    }

    /// One line saying what the medium is: its phase function, whether it is a grid, and
    /// what it adds (emission, heat, a dye).
    pub fn describe(&self) -> String {
        let phase = match self.phase {
            Phase::HenyeyGreenstein { g } => format!("Henyey-Greenstein g {g}"),
            Phase::Rayleigh => "Rayleigh".into(),
        };
        let grid =
            |r: glam::UVec3, what: &str| format!("{what}grid {}x{}x{}, {phase}", r.x, r.y, r.z);
        let mut parts = vec![match &self.density {
            Density::Uniform => format!("homogeneous, {phase}"),
            Density::Grid(g) => grid(g.resolution(), ""),
            Density::Spectral(g) => grid(g.scales().resolution(), "spectral "),
        }];
        if self.albedo.is_some() {
            parts.push("albedo varying".into());
        }
        if self.emission.is_some() {
            parts.push("emissive".into());
        }
        if self.temperature.is_some() {
            parts.push("glowing by temperature".into());
        }
        if self.fluorescence.is_some() {
            parts.push("fluorescent dye".into());
        }
        parts.join(", ")
    }

    /// Whether the medium emits light (an emission coefficient, or a temperature).
    pub fn emissive(&self) -> bool {
        self.emission.is_some() || self.temperature.is_some()
    }

    /// Whether light crosses the medium by a closed form: homogeneous, with a majorant
    /// that is its extinction (no emission to gather, no dye to re-emit), so that tracking
    /// meets only real collisions and the transmittance over a distance d is exactly
    /// exp(-sigma_t d) per lane ([`track::transmittance`]). Shadow rays use the closed
    /// form instead of ratio tracking's estimate, which in such a medium is all or nothing
    /// (a track-length estimator: a collision zeroes it).
    pub fn transmittance_in_closed_form(&self) -> bool {
        matches!(self.density, Density::Uniform)
            && self.emission.is_none()
            && self.fluorescence.is_none()
    }

    /// The extinction sigma_a + sigma_s per lane where the density is 1.
    pub fn extinction<const N: usize>(
        &self,
        wavelengths: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let point = self.at(wavelengths);
        point.sigma_a + point.sigma_s
    }

    /// The coefficients at `wavelengths` where the density is 1 (everywhere in a
    /// homogeneous medium).
    pub fn at<const N: usize>(&self, wavelengths: &SampledWavelengths<N>) -> MediumPoint<N> {
        let mut sigma_a = self.sigma_a.at(wavelengths);
        let mut sigma_fo = SampledSpectrum::splat(0.0);
        if let Some(dye) = &self.fluorescence {
            sigma_a += dye.absorption().at(wavelengths);
            sigma_fo = SampledSpectrum::from_fn(|i| dye.in_scattering(wavelengths.lambda(i)));
        }
        MediumPoint {
            sigma_a,
            sigma_s: self.sigma_s.at(wavelengths),
            emission: self
                .emission
                .as_ref()
                .map_or(SampledSpectrum::splat(0.0), |e| e.at(wavelengths)),
            sigma_fo,
        }
    }

    /// The coefficients at point `p` for `wavelengths`, `base` being [`Medium::at`]'s.
    #[inline]
    pub fn point<const N: usize>(
        &self,
        base: &MediumPoint<N>,
        p: glam::Vec3,
        wavelengths: &SampledWavelengths<N>,
    ) -> MediumPoint<N> {
        let mut point = match &self.density {
            Density::Uniform => *base,
            Density::Grid(grid) => {
                let d = grid.lookup(p);
                MediumPoint {
                    sigma_a: base.sigma_a * d,
                    sigma_s: base.sigma_s * d,
                    emission: base.emission * d,
                    sigma_fo: base.sigma_fo * d,
                }
            }
            Density::Spectral(grid) => {
                let d = grid.lookup(p, wavelengths);
                MediumPoint {
                    sigma_a: base.sigma_a * d,
                    sigma_s: base.sigma_s * d,
                    emission: base.emission * d,
                    sigma_fo: base.sigma_fo * d,
                }
            }
        };
        if let Some(albedo) = &self.albedo {
            let extinction = point.sigma_a + point.sigma_s;
            point.sigma_s = extinction * albedo.at(p, wavelengths);
            point.sigma_a = extinction - point.sigma_s;
        }
        if let Some(grid) = &self.temperature {
            let kelvin = f64::from(grid.lookup(p));
            if kelvin > 0.0 && !point.sigma_a.is_black() {
                // planck_radiance is per metre of wavelength: 1e-9 of it per nanometre.
                let b = SampledSpectrum::from_fn(|i| {
                    let nm = f64::from(wavelengths.lambda(i));
                    (planck_radiance(nm * 1e-9, kelvin) * 1e-9) as f32
                });
                point.emission += point.sigma_a * b;
            }
        }
        point
    }

    /// The majorant per lane where the density is at most `bound`, `base` being
    /// [`Medium::at`]'s: sigma_t times the bound, raised in a medium that glows to its
    /// emissive floor (times the bound) so that tracking stops where it emits.
    #[inline]
    pub fn majorant_over<const N: usize>(
        &self,
        base: &MediumPoint<N>,
        bound: f32,
    ) -> SampledSpectrum<N> {
        // A dye's in-scattering does not attenuate, but tracking must stop where it adds
        // light even where nothing absorbs or scatters: the majorant is at least it.
        let t = (base.sigma_a + base.sigma_s) * bound;
        let t = if self.fluorescence.is_some() {
            SampledSpectrum::from_fn(|i| t[i].max(base.sigma_fo[i] * bound))
        } else {
            t
        };
        if self.emission.is_some() {
            let floor = self.emissive_floor * bound;
            t.map(|s| s.max(floor))
        } else {
            t
        }
    }
}

/// The media of a scene and where they are.
#[derive(Debug, Clone, Default)]
pub struct Media {
    media: Vec<Medium>,
    /// Per material, the medium its closed surface holds (empty: none does).
    inside: Vec<Option<u32>>,
    /// The medium filling the world outside every boundary (fog), if any.
    world: Option<u32>,
    /// Mitsuba's model, where crossing a surface sets the medium rather than entering or
    /// leaving a nested volume: per material, the media either side of its surfaces
    /// (None: crossing them leaves the medium as it is). None: prism's nested volumes.
    sides: Option<Vec<Option<Sides>>>,
}

/// The media either side of a boundary where crossing it sets the medium (Mitsuba's
/// shapes' `interior` and `exterior`): against the surface's outward normal a path is in
/// `inside` after it, along it in `outside`; None is vacuum.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Sides {
    /// The medium behind the surface (its `interior`).
    pub inside: Option<u32>,
    /// The medium in front of it (its `exterior`).
    pub outside: Option<u32>,
}

impl Media {
    /// Media `media`, material `m`'s inside being `inside[m]` (the list may be shorter
    /// than the materials: the rest hold none), the world filled by `world`. Indices must
    /// name media in the list.
    pub fn new(
        media: Vec<Medium>,
        inside: Vec<Option<u32>>,
        world: Option<u32>,
    ) -> Result<Self, String> {
        let count = media.len();
        for (m, i) in inside.iter().enumerate() {
            if let Some(i) = i
                && *i as usize >= count
            {
                return Err(format!("material {m} holds medium {i}, of {count}"));
            }
        }
        if let Some(w) = world
            && w as usize >= count
        {
            return Err(format!("the world's medium {w} is not one of {count}"));
        }
        Ok(Self {
            media,
            inside,
            world,
            sides: None,
        })
    }

    /// Media placed as Mitsuba places them (its "volpath" integrator, and
    /// `SurfaceInteraction::target_medium`): a path starts in `world` (the sensor's
    /// medium) and crossing a surface of material `m` puts it in `sides[m]`'s medium on
    /// the side it goes to; crossing a material without sides (the list may be shorter
    /// than the materials) changes nothing. Unlike nested volumes, overlapping shapes
    /// leave a path in whatever the last surface it crossed says. Indices must name media
    /// in the list.
    pub fn with_sides(
        media: Vec<Medium>,
        sides: Vec<Option<Sides>>,
        world: Option<u32>,
    ) -> Result<Self, String> {
        let count = media.len();
        for (m, s) in sides.iter().enumerate() {
            for i in s.iter().flat_map(|s| [s.inside, s.outside]).flatten() {
                if i as usize >= count {
                    return Err(format!("material {m} borders medium {i}, of {count}"));
                }
            }
        }
        let mut media = Self::new(media, Vec::new(), world)?;
        media.sides = Some(sides);
        Ok(media)
    }

    /// Whether the scene has any medium.
    pub fn is_empty(&self) -> bool {
        self.media.is_empty()
    }

    /// The media.
    pub fn all(&self) -> &[Medium] {
        &self.media
    }

    /// The media, to change.
    pub(crate) fn all_mut(&mut self) -> &mut [Medium] {
        &mut self.media
    }

    /// Medium `i`.
    pub fn get(&self, i: u32) -> &Medium {
        &self.media[i as usize]
    }

    /// The medium material `material` holds inside, if any.
    pub fn inside(&self, material: u32) -> Option<u32> {
        self.inside.get(material as usize).copied().flatten()
    }

    /// Whether material `material` bounds a medium.
    pub fn bounds_medium(&self, material: u32) -> bool {
        self.inside(material).is_some()
    }

    /// Whether crossing a surface sets the medium (Mitsuba's model, [`Media::with_sides`])
    /// rather than entering or leaving a nested volume.
    pub fn crossing_sets(&self) -> bool {
        self.sides.is_some()
    }

    /// Where crossing sets the medium, the media either side of material `material`'s
    /// surfaces (None: crossing them changes nothing, or the volumes nest).
    pub fn sides(&self, material: u32) -> Option<Sides> {
        self.sides
            .as_ref()
            .and_then(|s| s.get(material as usize).copied().flatten())
    }

    /// The medium outside every boundary, if any.
    pub fn world(&self) -> Option<u32> {
        self.world
    }

    /// Whether a medium scatters or emits with a polarizing phase function (Rayleigh).
    pub fn has_rayleigh(&self) -> bool {
        self.media
            .iter()
            .any(|m| matches!(m.phase, Phase::Rayleigh))
    }
}
