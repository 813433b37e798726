//! Mitsuba's participating media (the "Media" and "Phase functions" plugin references):
//! `homogeneous` and `heterogeneous` as prism's media, their phase functions `isotropic`,
//! `hg` and `rayleigh`, where they are (a shape's `interior` and `exterior`, the sensor's
//! medium), and the `null` BSDF as a boundary that is no surface.
//!
//! A Mitsuba medium is an extinction sigma_t times `scale` and an albedo: sigma_s =
//! scale sigma_t albedo, sigma_a = scale sigma_t (1 - albedo) (`src/media/homogeneous.cpp`
//! and `heterogeneous.cpp`). A heterogeneous medium is where its sigma_t volume's box is:
//! a grid's values or a `constvolume`'s spectrum within it, nothing outside; its albedo
//! may vary too. Where media are follows Mitsuba's model, not prism's nesting: crossing a
//! shape's surface puts a path in the shape's `interior` or `exterior` (none: vacuum)
//! whatever it was in before, and the camera starts in the sensor's medium
//! ([`crate::medium::Media::with_sides`]).
//!
//! Mitsuba renders media with `volpath` and `volpathmis` only: its other integrators
//! ignore them, and so does prism then (with a warning), to render what Mitsuba renders.

use std::collections::HashMap;
use std::sync::Arc;

use prism_spectrum::Spectrum;
use prism_spectrum::spectra::DenselySampled;

use super::files::Files;
use super::parse::error;
use super::sensors::number;
use super::tree::{Class, Object, Value};
use super::volumes::{Volume, known, volume};
use crate::LoadError;
use crate::load::Upsampler;
use crate::materials::Material;
use crate::medium::{Albedo, Grid, MAX_ABS_G, Media, Medium, Phase, Sides};
use crate::textures::SceneSpectrum;

/// The integrators that render media in Mitsuba.
const VOLUMETRIC: [&str; 2] = ["volpath", "volpathmis"];

/// A Mitsuba scene's media, gathered as its shapes and sensor are read.
#[derive(Default)]
pub(crate) struct MediaBuilder {
    media: Vec<Medium>,
    /// Medium objects read so far (by address: references share one), by index.
    read: HashMap<usize, u32>,
    /// Per material, the media on its surfaces' sides.
    sides: Vec<Option<Sides>>,
    /// The sensor's medium.
    world: Option<u32>,
}

/// What reading a medium needs.
pub(crate) struct Reading<'a> {
    pub upsampler: &'a Upsampler,
    /// Where the files volumes name are found.
    pub files: Files<'a>,
    pub warnings: &'a mut Vec<String>,
}

impl MediaBuilder {
    /// The media on `shape`'s sides (its `interior` and `exterior`), if it has any.
    pub(crate) fn shape_sides(
        &mut self,
        shape: &Object,
        cx: &mut Reading,
    ) -> Result<Option<Sides>, LoadError> {
        let mut sides = Sides::default();
        let mut any = false;
        for child in shape.children_of(Class::Medium) {
            let slot = match child.name.as_deref() {
                Some("interior") => &mut sides.inside,
                Some("exterior") => &mut sides.outside,
                name => {
                    // Mitsuba reads only these two names on a shape.
                    cx.warnings.push(format!(
                        "{}: a shape's medium named '{}' is not read (interior and exterior are)",
                        child.object.at,
                        name.unwrap_or("")
                    ));
                    continue;
                }
            };
            if slot.is_some() {
                return Err(error(
                    &child.object.at,
                    "a shape has one interior and one exterior medium",
                ));
            }
            *slot = Some(self.medium(&child.object, cx)?);
            any = true;
        }
        Ok(any.then_some(sides))
    }

    /// Records that material `material` has `sides`.
    pub(crate) fn set_sides(&mut self, material: usize, sides: Option<Sides>) {
        if self.sides.len() <= material {
            self.sides.resize(material + 1, None);
        }
        self.sides[material] = sides;
    }

    /// Reads the medium `sensor` is in (any medium nested in it), where paths start.
    pub(crate) fn sensor(&mut self, sensor: &Object, cx: &mut Reading) -> Result<(), LoadError> {
        let mut media = sensor.children_of(Class::Medium);
        if let Some(m) = media.next() {
            if media.next().is_some() {
                return Err(error(&sensor.at, "a sensor is in one medium"));
            }
            self.world = Some(self.medium(&m.object, cx)?);
        }
        Ok(())
    }

    /// The scene's media for its integrator `integrator` (None: the scene has none, or
    /// the integrator ignores them, which a warning says).
    pub(crate) fn finish(
        self,
        integrator: Option<&Object>,
        warnings: &mut Vec<String>,
    ) -> Result<Option<Media>, LoadError> {
        if self.media.is_empty() {
            return Ok(None);
        }
        let kind = integrator.map(|i| nested(i).kind.as_str());
        if !kind.is_some_and(|k| VOLUMETRIC.contains(&k)) {
            warnings.push(format!(
                "integrator '{}' ignores participating media in Mitsuba, and prism's render does too (volpath and volpathmis render them)",
                kind.unwrap_or("path")
            ));
            return Ok(None);
        }
        Media::with_sides(self.media, self.sides, self.world)
            .map(Some)
            .map_err(LoadError::Scene)
    }

    /// The index of medium `m`, read on first use.
    fn medium(&mut self, m: &Arc<Object>, cx: &mut Reading) -> Result<u32, LoadError> {
        let key = Arc::as_ptr(m) as usize;
        if let Some(&i) = self.read.get(&key) {
            return Ok(i);
        }
        let medium = medium(m, cx)?;
        let index = u32::try_from(self.media.len()).expect("fewer media than u32 counts");
        self.media.push(medium);
        self.read.insert(key, index);
        Ok(index)
    }
}

/// The integrator a wrapper (`moment`, `aov`) runs, or `integrator` itself.
pub(crate) fn nested(integrator: &Object) -> &Object {
    match integrator.kind.as_str() {
        "moment" | "aov" => integrator
            .children_of(Class::Integrator)
            .next()
            .map_or(integrator, |c| nested(&c.object)),
        _ => integrator,
    }
}

/// Mitsuba's `null` BSDF on a medium's boundary: no surface, light crosses it unchanged
/// and into the medium the shape's sides say (prism's interface material). This is the
/// part of `null` media need; a `null` shape without media is the same interface.
pub(crate) fn null_boundary(bsdf: &Object) -> Result<Material, LoadError> {
    known(bsdf, &[])?;
    Ok(Material::Interface)
}

/// A `homogeneous` or `heterogeneous` medium.
fn medium(m: &Object, cx: &mut Reading) -> Result<Medium, LoadError> {
    let heterogeneous = match m.kind.as_str() {
        "homogeneous" => false,
        "heterogeneous" => true,
        other => {
            return Err(error(
                &m.at,
                format!("medium '{other}' is not read yet (homogeneous and heterogeneous are)"),
            ));
        }
    };
    let names = [
        "albedo",
        "sigma_t",
        "scale",
        "sample_emitters",
        "has_spectral_extinction",
    ];
    if let Some(p) = m
        .properties
        .iter()
        .find(|p| !names.contains(&p.name.as_str()))
    {
        return Err(error(
            &p.at,
            format!("{}: parameter '{}' is not read", m.kind, p.name),
        ));
    }
    if let Some(c) = m.children.iter().find(|c| {
        c.object.class != Class::Phase && !names.contains(&c.name.as_deref().unwrap_or(""))
    }) {
        return Err(error(
            &c.object.at,
            format!(
                "{}: nested {} '{}' ({}) is not read",
                m.kind,
                c.object.class.tag(),
                c.object.kind,
                c.name.as_deref().unwrap_or("unnamed")
            ),
        ));
    }
    for (name, what) in [
        (
            "sample_emitters",
            "sample_emitters false is not read: prism samples emitters from inside every medium (the same image; Mitsuba's flag only saves time)",
        ),
        (
            "has_spectral_extinction",
            "has_spectral_extinction false is not read: prism's tracer is right for any extinction, grey or not",
        ),
    ] {
        if let Some(p) = m.property(name) {
            match p.value {
                Value::Boolean(true) => {}
                Value::Boolean(false) => cx.warnings.push(format!("{}: {what}", p.at)),
                _ => return Err(error(&p.at, format!("'{name}' must be a boolean"))),
            }
        }
    }
    let scale = number(m, "scale")?.unwrap_or(1.0);
    if scale < 0.0 {
        return Err(error(&m.at, format!("scale {scale} must be at least 0")));
    }
    let phase = phase(m)?;
    let sigma_t = volume(m, "sigma_t", 1.0, cx.upsampler, cx.files, cx.warnings)?;
    let albedo = volume(m, "albedo", 0.75, cx.upsampler, cx.files, cx.warnings)?;
    let built = |e: String| error(&m.at, format!("{}: {e}", m.kind));
    // The extinction where the density is 1, and what makes it vary.
    let (extinction, density) = match sigma_t {
        Volume::Constant { value, min, max } => {
            if heterogeneous && matches!(value, SceneSpectrum::Rgb(_)) {
                cx.warnings.push(format!(
                    "{}: Mitsuba bounds this medium by its RGB extinction's mean over wavelengths, below the spectrum's peak, and its volpath is biased where the wavelengths it samples exceed that; prism's render is not (a spectrum or a number avoids the difference)",
                    m.at
                ));
            }
            let value = product(&value, &SceneSpectrum::Constant(scale), |t, s| t * s);
            // A heterogeneous medium is where its sigma_t's box is (Mitsuba clips its
            // paths to that box); a homogeneous one is everywhere.
            let density = heterogeneous
                .then(|| Grid::new(glam::UVec3::ONE, min, max, vec![1.0]))
                .transpose()
                .map_err(built)?
                .map(Volume::Grid);
            (value, density)
        }
        grid if heterogeneous => (SceneSpectrum::Constant(scale), Some(grid)),
        _ => {
            return Err(error(
                &m.at,
                "a homogeneous medium's sigma_t is one value, not a grid (heterogeneous reads grids)",
            ));
        }
    };
    let (sigma_s, sigma_a, varying) = match albedo {
        Volume::Constant { value, .. } => {
            let s = product(&extinction, &value, |t, a| t * a);
            let a = product(&extinction, &value, |t, a| t * (1.0 - a));
            (s, a, None)
        }
        Volume::Grid(g) => (
            extinction,
            SceneSpectrum::Constant(0.0),
            Some(Albedo::Grid(g)),
        ),
        Volume::Spectral(g) => (
            extinction,
            SceneSpectrum::Constant(0.0),
            Some(Albedo::Spectral(g)),
        ),
    };
    let mut medium = Medium::new(sigma_a, sigma_s, phase, None).map_err(|e| {
        error(
            &m.at,
            format!("{}: {e} (an albedo must be in [0, 1])", m.kind),
        )
    })?;
    match density {
        None => {}
        Some(Volume::Grid(g)) => medium = medium.with_density(g),
        Some(Volume::Spectral(g)) => medium = medium.with_spectral_density(g),
        Some(Volume::Constant { .. }) => unreachable!("a constant's density is a grid"),
    }
    if let Some(a) = varying {
        medium = medium.with_albedo(a);
    }
    Ok(medium)
}

/// `f(a, b)` per wavelength: a constant of constants, a scaled spectrum where one is a
/// constant factor, else tabulated at 1 nm over 300-830 nm.
fn product(a: &SceneSpectrum, b: &SceneSpectrum, f: impl Fn(f64, f64) -> f64) -> SceneSpectrum {
    match (a, b) {
        (SceneSpectrum::Constant(x), SceneSpectrum::Constant(y)) => {
            SceneSpectrum::Constant(f(*x, *y))
        }
        _ => {
            let values = (300..=830)
                .map(|nm| {
                    let nm = f64::from(nm);
                    f(a.evaluate(nm), b.evaluate(nm))
                })
                .collect();
            match DenselySampled::from_values(300.0, values) {
                Ok(d) => SceneSpectrum::Dense(Arc::new(d)),
                // Spectra are finite, so the table is; a constant 0 if not.
                Err(_) => SceneSpectrum::Constant(0.0),
            }
        }
    }
}

/// The medium's phase function (Mitsuba's default: isotropic).
fn phase(m: &Object) -> Result<Phase, LoadError> {
    let mut phases = m.children_of(Class::Phase);
    let Some(p) = phases.next() else {
        return Ok(Phase::HenyeyGreenstein { g: 0.0 });
    };
    if let Some(second) = phases.next() {
        return Err(error(&second.object.at, "a medium has one phase function"));
    }
    let p = &p.object;
    match p.kind.as_str() {
        "isotropic" => {
            known(p, &[])?;
            Ok(Phase::HenyeyGreenstein { g: 0.0 })
        }
        "hg" => {
            known(p, &["g"])?;
            // Mitsuba's default asymmetry is 0.8; its g > 0 scatters forward, as prism's.
            let g = number(p, "g")?.unwrap_or(0.8);
            if g.abs() >= 1.0 {
                return Err(error(&p.at, format!("hg: g {g} must be in (-1, 1)")));
            }
            Phase::henyey_greenstein(g).map_err(|e| {
                error(
                    &p.at,
                    format!("hg: {e}: prism's narrowest lobe is |g| = {MAX_ABS_G}"),
                )
            })
        }
        "rayleigh" => {
            known(p, &[])?;
            Ok(Phase::Rayleigh)
        }
        other => Err(error(
            &p.at,
            format!("phase '{other}' is not read yet (isotropic, hg and rayleigh are)"),
        )),
    }
}
