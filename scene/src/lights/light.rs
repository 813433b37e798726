//! Lights of a render-ready scene: emissive triangles, KHR punctual lights and a constant
//! environment, chosen in proportion to their power through an alias table, or, when
//! their spectra differ in narrow bands or the ultraviolet, to their power at the path's
//! wavelengths (`light_choice`).

use std::f32::consts::PI;
use std::sync::Arc;

use glam::{Vec2, Vec3};
use prism_sampling::distribution::{AliasTable, positive_finite};
use prism_sampling::warp::{
    cosine_hemisphere, spherical_triangle, spherical_triangle_solid_angle, uniform_cone,
    uniform_cone_pdf, uniform_disk_concentric, uniform_sphere, uniform_triangle,
};
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use super::light_choice::SpectralChoice;
use super::{EmissionCache, EnvironmentMap, SpotTexture};
use crate::geometry::{
    Ray, offset_ray_origin, triangle_area, triangle_normal, triangle_point_error,
};
use crate::textures::SceneSpectrum;

/// One light.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum Light {
    /// An emissive triangle with radiance `emission` (index into the scene's emission
    /// spectra), from its front face (the side its counter-clockwise winding faces) only
    /// unless `two_sided`.
    Triangle {
        /// Index of the triangle in the scene.
        triangle: u32,
        /// Index of its emission spectrum.
        emission: u32,
        /// Whether both faces emit.
        two_sided: bool,
    },
    /// A point light of radiant intensity `intensity` (W sr^-1 nm^-1).
    Point {
        /// Position.
        position: Vec3,
        /// Radiant intensity.
        intensity: SceneSpectrum,
    },
    /// A spot light: a point light whose intensity falls off between an inner and an
    /// outer cone as `falloff` says.
    Spot {
        /// Position.
        position: Vec3,
        /// Unit axis.
        direction: Vec3,
        /// cos of the inner cone angle.
        cos_inner: f32,
        /// cos of the outer cone angle.
        cos_outer: f32,
        /// Radiant intensity on the axis.
        intensity: SceneSpectrum,
        /// How the intensity falls off between the cones.
        falloff: SpotFalloff,
        /// A texture it projects, multiplying its intensity (None: none).
        texture: Option<Arc<SpotTexture>>,
    },
    /// A distant light travelling along `direction` with irradiance `irradiance`
    /// (W m^-2 nm^-1) on a surface facing it.
    Directional {
        /// Unit direction of travel.
        direction: Vec3,
        /// Irradiance.
        irradiance: SceneSpectrum,
    },
    /// Constant radiance from every direction at infinity.
    Environment {
        /// Radiance.
        radiance: SceneSpectrum,
    },
    /// Radiance from infinity that varies with direction: an environment image.
    EnvironmentMap {
        /// The image.
        map: Arc<EnvironmentMap>,
    },
}

impl Light {
    /// The spectrum that sets the light's colour (an environment image's mean); None for
    /// an emissive triangle, whose spectrum is the scene's emission spectrum it names.
    pub fn spectrum(&self) -> Option<&SceneSpectrum> {
        match self {
            Light::Point { intensity: s, .. }
            | Light::Spot { intensity: s, .. }
            | Light::Directional { irradiance: s, .. }
            | Light::Environment { radiance: s } => Some(s),
            Light::EnvironmentMap { map } => Some(map.mean()),
            Light::Triangle { .. } => None,
        }
    }
}

/// A light sample seen from a point.
#[derive(Debug, Clone, Copy)]
pub struct LightSample<const N: usize> {
    /// Unit direction from the point to the light.
    pub wi: Vec3,
    /// Distance to the light (infinite for distant lights).
    pub distance: f32,
    /// Incident radiance (for delta lights, the delta's weight: intensity / distance^2 or
    /// irradiance).
    pub radiance: SampledSpectrum<N>,
    /// Density of `wi` with respect to solid angle, times the light's selection
    /// probability; for delta lights the selection probability alone.
    pub pdf: f32,
    /// Whether the light is a delta in direction (BSDF sampling can never hit it).
    pub delta: bool,
    /// Which of the scene's lights it is (`world::Scene::light_polarization`).
    pub light: u32,
}

/// A light path's first ray, sampled from a light's emission.
#[derive(Debug, Clone, Copy)]
pub struct EmissionSample<const N: usize> {
    /// The ray leaving the light (offset from an emitting surface).
    pub ray: Ray,
    /// Emitted radiance (or intensity, or irradiance) times the cosine at the light, over
    /// the density of the ray (position and direction) and of choosing the light: the
    /// light path's initial throughput.
    pub beta: SampledSpectrum<N>,
    /// Which of the scene's lights it left (`world::Scene::light_polarization`).
    pub light: u32,
}

/// A remapped uniform number (f64 in [0, 1)) as an f32 in [0, 1): rounding to f32 could
/// reach 1.
pub(crate) fn unit_f32(u: f64) -> f32 {
    (u as f32).min(1.0 - f32::EPSILON / 2.0)
}

/// `local` (z up) turned so that its z is the unit `axis`.
fn around(axis: Vec3, local: Vec3) -> Vec3 {
    let (x, y) = axis.any_orthonormal_pair();
    local.x * x + local.y * y + local.z * axis
}

/// What sampling a triangle light reads of its geometry, computed once per light: the
/// normal, area and centroid, recomputed per light sample, were a measurable share of
/// the Cornell box's instructions.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct TriangleShape {
    pub(crate) vertices: [Vec3; 3],
    centroid: Vec3,
    /// (v1 - v0) x (v2 - v0): twice the area, along the normal.
    cross: Vec3,
    pub(crate) normal: Vec3,
    pub(crate) area: f32,
    /// Texture coordinates at the vertices, in the set its emissive texture reads (which
    /// is read at the point sampled).
    uvs: [Vec2; 3],
}

impl TriangleShape {
    fn new(v: [Vec3; 3], uvs: [Vec2; 3]) -> Self {
        Self {
            vertices: v,
            centroid: (v[0] + v[1] + v[2]) / 3.0,
            cross: (v[1] - v[0]).cross(v[2] - v[0]),
            normal: triangle_normal(v),
            area: triangle_area(v),
            uvs,
        }
    }

    /// The texture coordinates at barycentrics `b`.
    fn uv(&self, b: [f32; 3]) -> Vec2 {
        b[0] * self.uvs[0] + b[1] * self.uvs[1] + b[2] * self.uvs[2]
    }

    /// The texture coordinates at point `q` of the triangle's plane.
    fn uv_at(&self, q: Vec3) -> Vec2 {
        let [v0, v1, v2] = self.vertices;
        let area2 = self.cross.length_squared();
        let b1 = (q - v0).cross(v2 - v0).dot(self.cross) / area2;
        let b2 = (v1 - v0).cross(q - v0).dot(self.cross) / area2;
        let uv = self.uv([1.0 - b1 - b2, b1, b2]);
        if uv.is_finite() { uv } else { self.uvs[0] }
    }
}

/// The subtended solid angles (sr) over which a triangle light is sampled uniformly in
/// solid angle rather than by area (the start also bounds a cheap screening estimate, see
/// [`solid_angle_sampled`]). Area sampling's noise is the variation of cos / d^2 over the
/// triangle, which grows with the angle it subtends; the spherical construction (Arvo
/// 1995) removes it but costs inverse trigonometry per sample and a solid angle per
/// emitter hit. Measured on the Cornell box (instructions per path under callgrind,
/// relMSE against a converged render): from 3e-4 sr, pbrt-v4's bound, many more
/// instructions for a small gain in error; from 0.05 sr, few more for the same gain. The
/// effects stage's booth panels, close to what they light, lose a good share of their
/// error either way. Above 6.22 sr (nearly a hemisphere) the construction degenerates (*PBR*
/// 4th ed. §6.5.4).
const SOLID_ANGLE_SAMPLING: std::ops::RangeInclusive<f32> = 0.05..=6.22;

/// The solid angle triangle `shape` subtends from `p`, when light sampling from `p`
/// samples it by solid angle (else None: by area). `Scene::light_pdf` decides the same
/// way.
pub(crate) fn solid_angle_sampled(p: Vec3, shape: &TriangleShape) -> Option<f32> {
    // Screened first by the solid angle of a small patch of the triangle's area at its
    // centroid, A |cos| / d^2 (no normalizations, no arctangent): most samples from most
    // points are of far lights (measured: the exact angle for every decision was a
    // noticeable share of the Cornell box's instructions). Only what passes gets the exact angle.
    let to = shape.centroid - p;
    let d2 = to.length_squared();
    let patch = 0.5 * shape.cross.dot(to).abs() / (d2 * d2.sqrt());
    // NaN (p at the centroid) fails too.
    if patch.is_nan() || patch < *SOLID_ANGLE_SAMPLING.start() {
        return None;
    }
    let omega = spherical_triangle_solid_angle(p, shape.vertices);
    SOLID_ANGLE_SAMPLING.contains(&omega).then_some(omega)
}

/// How a spot light's intensity falls off from its inner cone (full) to its outer cone
/// (none).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum SpotFalloff {
    /// glTF's (KHR_lights_punctual): a squared linear ramp in cos.
    #[default]
    Smooth,
    /// Mitsuba 3's `spot` (`falloff_curve` in src/emitters/spot.cpp): linear in the angle
    /// from the axis, (outer - angle) / (outer - inner), and none at the outer angle itself.
    LinearAngle,
    /// Mitsuba 3's `projector` (src/emitters/projector.cpp): 1 / cos^3 inside the outer
    /// cone (the frustum's, which its [`SpotTexture`] clips), the inverse of a pinhole
    /// camera's importance, so that a constant image lights a plane facing it evenly.
    InverseCosCubed,
}

/// The falloff of a spot light at cos `cos` off its axis.
fn spot_falloff(cos: f32, cos_inner: f32, cos_outer: f32, falloff: SpotFalloff) -> f32 {
    match falloff {
        SpotFalloff::Smooth => smooth_falloff(cos, cos_inner, cos_outer),
        SpotFalloff::LinearAngle => {
            if cos >= cos_inner {
                1.0
            } else if cos > cos_outer {
                let (inner, outer) = (cos_inner.acos(), cos_outer.acos());
                ((outer - cos.clamp(-1.0, 1.0).acos()) / (outer - inner)).clamp(0.0, 1.0)
            } else {
                0.0
            }
        }
        SpotFalloff::InverseCosCubed if cos > cos_outer && cos > 0.0 => 1.0 / (cos * cos * cos),
        SpotFalloff::InverseCosCubed => 0.0,
    }
}

/// The glTF spot light falloff (KHR_lights_punctual): a squared linear ramp in cos between
/// the outer and inner cone.
/// The ramp's width is not floored at 1e-3 as the extension's sample code does (that
/// only guards a division by zero, and would dim every spot narrower than ~2.5 degrees
/// to a fraction of its intensity).
fn smooth_falloff(cos: f32, cos_inner: f32, cos_outer: f32) -> f32 {
    let width = cos_inner - cos_outer;
    if width <= 0.0 {
        return f32::from(u8::from(cos >= cos_outer));
    }
    let t = ((cos - cos_outer) / width).clamp(0.0, 1.0);
    t * t
}

/// Every light of a scene with the distribution that chooses among them.
#[derive(Debug, Clone)]
pub struct Lights {
    pub(crate) lights: Vec<Light>,
    /// None when there is no light with power.
    pub(crate) choice: Option<AliasTable>,
    /// The choice at a path's wavelengths, for next-event estimation in scenes whose
    /// lights differ in spectrum (None: by power).
    spectral: Option<SpectralChoice>,
    /// The light index of each triangle, u32::MAX where it does not emit.
    pub(crate) of_triangle: Vec<u32>,
    pub(crate) environment: Option<u32>,
    /// Per light: its triangle's shape (the default for other lights).
    shapes: Vec<TriangleShape>,
    /// Per light: the power `choice` is proportional to (0 where none).
    power: Vec<f64>,
}

/// Where light paths aim: light from infinity leaves a disk over `sphere` (centre,
/// radius) only, and light paths choose lights by the power that reaches it (see
/// `world::Scene::aim`).
#[derive(Debug, Clone)]
pub struct CausticTarget {
    pub(crate) sphere: (Vec3, f32),
    /// None when no light has power.
    pub(crate) choice: Option<AliasTable>,
}

impl Lights {
    /// The lights, chosen in proportion to `power` (which must match `lights`), or to
    /// `extent` times their spectra at a path's wavelengths (see `light_choice`).
    /// `uvs_of_set` gives the texture coordinates at the triangles' vertices in a set.
    pub(crate) fn new<'a>(
        lights: Vec<Light>,
        power: &[f64],
        extent: &[f64],
        emission: &[SceneSpectrum],
        triangles: &[[Vec3; 3]],
        uvs_of_set: impl Fn(usize) -> &'a [[Vec2; 3]],
    ) -> Self {
        let mut of_triangle = vec![u32::MAX; triangles.len()];
        let shapes = lights
            .iter()
            .map(|light| match light {
                Light::Triangle {
                    triangle,
                    emission: e,
                    ..
                } => {
                    let t = *triangle as usize;
                    let set = emission[*e as usize].tex_coord_set().unwrap_or(0);
                    let uvs = uvs_of_set(set).get(t).copied();
                    TriangleShape::new(triangles[t], uvs.unwrap_or_default())
                }
                _ => TriangleShape::default(),
            })
            .collect();
        let mut environment = None;
        for (i, light) in lights.iter().enumerate() {
            match light {
                Light::Triangle { triangle, .. } => of_triangle[*triangle as usize] = i as u32,
                Light::Environment { .. } | Light::EnvironmentMap { .. } => {
                    environment = Some(i as u32);
                }
                _ => {}
            }
        }
        let usable = power.iter().any(|&p| p > 0.0 && p.is_finite());
        let weights: Vec<f64> = power
            .iter()
            .map(|&p| if p.is_finite() && p > 0.0 { p } else { 0.0 })
            .collect();
        Self {
            spectral: SpectralChoice::new(&lights, extent, emission),
            lights,
            choice: if usable {
                AliasTable::new(&weights).ok()
            } else {
                None
            },
            of_triangle,
            environment,
            shapes,
            power: weights,
        }
    }

    /// Light paths aimed at `sphere`, in a scene of bounding radius `scene_radius`: light
    /// from infinity counts with the power that crosses the sphere's disk (its power over
    /// the scene's disk times the ratio of their areas), other lights with all of theirs.
    /// A faint sky beside a spot light then starts few light paths (a sky chosen by its
    /// power over the whole scene started a third of them in the prism scene, and traced
    /// half again as many rays for no less error).
    pub(crate) fn aimed(&self, sphere: (Vec3, f32), scene_radius: f32) -> CausticTarget {
        let share = f64::from((sphere.1 / scene_radius).min(1.0)).powi(2);
        let weights: Vec<f64> = self
            .lights
            .iter()
            .zip(&self.power)
            .map(|(light, &p)| match light {
                Light::Directional { .. }
                | Light::Environment { .. }
                | Light::EnvironmentMap { .. } => p * share,
                _ => p,
            })
            .collect();
        let usable = weights.iter().any(|&p| p > 0.0);
        CausticTarget {
            sphere,
            choice: if usable {
                AliasTable::new(&weights).ok()
            } else {
                None
            },
        }
    }

    /// The shape of light `i`'s triangle (meaningful for triangle lights only).
    pub(crate) fn shape(&self, i: u32) -> &TriangleShape {
        &self.shapes[i as usize]
    }

    /// The lights.
    pub fn all(&self) -> &[Light] {
        &self.lights
    }

    /// The probability of choosing light `i` by power (light paths start so; next-event
    /// estimation too unless the lights differ in spectrum: see [`Lights::pmf_at`]).
    pub fn pmf(&self, i: u32) -> f32 {
        self.choice
            .as_ref()
            .map_or(0.0, |c| c.pmf(i as usize) as f32)
    }

    /// The light of triangle `t`, if it emits.
    pub fn of_triangle(&self, t: u32) -> Option<u32> {
        self.of_triangle
            .get(t as usize)
            .copied()
            .filter(|&l| l != u32::MAX)
    }

    /// Whether a light path can start from some light: one with a chance of being chosen
    /// (a scene whose lights are all black has none).
    pub fn start_light_paths(&self) -> bool {
        (0..self.lights.len()).any(|i| self.pmf(i as u32) > 0.0)
    }

    /// The environment light's index, if the scene has one.
    pub fn environment(&self) -> Option<u32> {
        self.environment
    }

    /// Whether next-event estimation chooses lights by their spectra at the path's
    /// wavelengths (the scene's lights differ in spectrum).
    pub fn spectral_choice(&self) -> bool {
        self.spectral.is_some()
    }

    /// The probability that next-event estimation chooses light `i` for a path at
    /// `wavelengths` (`cache`: the path's emission cache).
    pub fn pmf_at<const N: usize>(
        &self,
        i: u32,
        wavelengths: &SampledWavelengths<N>,
        cache: &mut EmissionCache<N>,
    ) -> f32 {
        match &self.spectral {
            Some(spectral) => {
                let weights = spectral.weights(wavelengths, cache);
                spectral.pmf(i as usize, &weights)
            }
            None => self.pmf(i),
        }
    }

    /// A light chosen with `u_choice` in proportion to power, its probability, and what
    /// is left of `u_choice` (uniform in [0, 1) again, see
    /// [`AliasTable::sample_remapped`]).
    fn choose(&self, u_choice: f32) -> Option<(usize, f32, f32)> {
        let (index, pmf, rest) = self.choice.as_ref()?.sample_remapped(f64::from(u_choice));
        let pmf = pmf as f32;
        (pmf > 0.0).then_some((index, pmf, unit_f32(rest)))
    }

    /// Chooses a light with `u.x` and samples it from `p` with what is left of `u.x` and
    /// with `u.y`: one 2D sample for the choice and the point, so that its stratification
    /// spans all of a light made of several triangles (a quad's two halves). Measured on
    /// the Cornell box (several seeds, every other dimension unchanged): less error than a
    /// separate number for the choice, in each seed.
    pub(crate) fn sample<const N: usize>(
        &self,
        p: Vec3,
        mut u: Vec2,
        wavelengths: &SampledWavelengths<N>,
        emission: &[SceneSpectrum],
        cache: &mut EmissionCache<N>,
    ) -> Option<LightSample<N>> {
        let (index, pmf, rest) = match &self.spectral {
            Some(spectral) => {
                let weights = spectral.weights(wavelengths, cache);
                spectral.choose(u.x, &weights)?
            }
            None => self.choose(u.x)?,
        };
        u.x = rest;
        let sample = match &self.lights[index] {
            Light::Triangle {
                emission: e,
                two_sided,
                ..
            } => {
                let shape = &self.shapes[index];
                let (v, n) = (shape.vertices, shape.normal);
                // Behind a one-sided light's plane no point of it faces p: the facing
                // test below would reject any sample, so none is drawn (a Cornell box's
                // ceiling, above its light, never sees it).
                if !*two_sided && n.dot(p - v[0]) <= 0.0 {
                    return None;
                }
                // The emission's texture coordinates are found only if it varies.
                let textured = matches!(emission[*e as usize], SceneSpectrum::Texture(_));
                let (wi, distance, pdf, uv) = match solid_angle_sampled(p, shape) {
                    Some(omega) => {
                        // Uniform in the subtended solid angle; the point is where the
                        // direction meets the triangle's plane. A failure (a triangle
                        // degenerate as seen from p) is no sample: switching strategy
                        // here would break the density `Scene::light_pdf` reports.
                        let wi = spherical_triangle(p, v, u)?.direction;
                        let distance = n.dot(v[0] - p) / n.dot(wi);
                        let uv = if textured {
                            shape.uv_at(p + wi * distance)
                        } else {
                            Vec2::ZERO
                        };
                        (wi, distance, 1.0 / omega, uv)
                    }
                    None => {
                        let b = uniform_triangle(u);
                        let to = b[0] * v[0] + b[1] * v[1] + b[2] * v[2] - p;
                        let d2 = to.length_squared();
                        let distance = d2.sqrt();
                        let wi = to / distance;
                        let cos = n.dot(wi).abs();
                        (wi, distance, d2 / (cos * shape.area), shape.uv(b))
                    }
                };
                let cos = -n.dot(wi);
                let facing = cos > 0.0 || (*two_sided && cos < 0.0);
                let valid = positive_finite(distance) && pdf.is_finite();
                if !facing || !valid {
                    return None;
                }
                LightSample {
                    light: index as u32,
                    wi,
                    distance,
                    radiance: cache.get(emission, *e, wavelengths, &uv.into()),
                    pdf: pmf * pdf,
                    delta: false,
                }
            }
            Light::Point {
                position,
                intensity,
            } => {
                let to = *position - p;
                let d2 = to.length_squared();
                let distance = d2.sqrt();
                LightSample {
                    light: index as u32,
                    wi: to / distance,
                    distance,
                    radiance: intensity.at(wavelengths) * (1.0 / d2),
                    pdf: pmf,
                    delta: true,
                }
            }
            Light::Spot {
                position,
                direction,
                cos_inner,
                cos_outer,
                intensity,
                falloff,
                texture,
            } => {
                let to = *position - p;
                let d2 = to.length_squared();
                let distance = d2.sqrt();
                let wi = to / distance;
                let falloff = spot_falloff(-wi.dot(*direction), *cos_inner, *cos_outer, *falloff);
                let mut radiance = intensity.at(wavelengths) * (falloff / d2);
                if let Some(t) = texture
                    && falloff > 0.0
                {
                    radiance *= t.at(-wi, wavelengths);
                }
                LightSample {
                    light: index as u32,
                    wi,
                    distance,
                    radiance,
                    pdf: pmf,
                    delta: true,
                }
            }
            Light::Directional {
                direction,
                irradiance,
            } => LightSample {
                light: index as u32,
                wi: -*direction,
                distance: f32::INFINITY,
                radiance: irradiance.at(wavelengths),
                pdf: pmf,
                delta: true,
            },
            Light::Environment { radiance } => LightSample {
                light: index as u32,
                wi: uniform_sphere(u),
                distance: f32::INFINITY,
                radiance: radiance.at(wavelengths),
                pdf: pmf / (4.0 * PI),
                delta: false,
            },
            Light::EnvironmentMap { map } => {
                let white = cache.environment_white(map, wavelengths);
                let (wi, pdf, radiance) = map.sample(u, wavelengths, &white)?;
                LightSample {
                    light: index as u32,
                    wi,
                    distance: f32::INFINITY,
                    radiance,
                    pdf: pmf * pdf,
                    delta: false,
                }
            }
        };
        (positive_finite(sample.pdf) && sample.wi.is_finite()).then_some(sample)
    }
}

impl Lights {
    /// Chooses a light with `u_choice` and samples a ray leaving it: a position with `u_position`
    /// and a direction with `u_direction` (light tracing). The scene's bounding sphere
    /// `scene` (centre, radius) places the rays of light from infinity, which cross `aim`'s
    /// sphere (the scene's without one) and are chosen by `aim`'s power.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn sample_emission<const N: usize>(
        &self,
        u_choice: f32,
        u_position: Vec2,
        u_direction: Vec2,
        wavelengths: &SampledWavelengths<N>,
        emission: &[SceneSpectrum],
        scene: (Vec3, f32),
        aim: Option<&CausticTarget>,
    ) -> Option<EmissionSample<N>> {
        let (index, pmf, aim) = match aim {
            Some(a) => {
                let (index, pmf, _) = a.choice.as_ref()?.sample_remapped(f64::from(u_choice));
                (index, pmf as f32, a.sphere)
            }
            None => {
                let (index, pmf, _) = self.choose(u_choice)?;
                (index, pmf, scene)
            }
        };
        if pmf <= 0.0 {
            return None;
        }
        // Light from infinity: parallel rays along `travel` through a disk facing it that
        // covers the sphere `aim`, started outside the scene's bounding sphere (so that
        // everything between infinity and the aim can block them). With `rest` the
        // radiance (or irradiance) over the direction's density, the flux per ray is
        // `rest` times the disk's area.
        let distant = |travel: Vec3| {
            let (a, r) = aim;
            let d = uniform_disk_concentric(u_position) * r;
            let (x, y) = travel.any_orthonormal_pair();
            let back = a.distance(scene.0) + r + scene.1;
            (a - travel * back + d.x * x + d.y * y, PI * r * r)
        };
        let (ray, beta) = match &self.lights[index] {
            Light::Triangle {
                emission: e,
                two_sided,
                ..
            } => {
                // Uniform in area, cosine-weighted in direction on an emitting side:
                // Le cos / (pdf_area pdf_dir) = Le pi area (times 2 for a side chosen at
                // random).
                let shape = &self.shapes[index];
                let (v, n) = (shape.vertices, shape.normal);
                let b = uniform_triangle(u_position);
                let p = b[0] * v[0] + b[1] * v[1] + b[2] * v[2];
                let (u, side, sides) = if *two_sided {
                    if u_direction.x < 0.5 {
                        (Vec2::new(2.0 * u_direction.x, u_direction.y), n, 2.0)
                    } else {
                        (Vec2::new(2.0 * u_direction.x - 1.0, u_direction.y), -n, 2.0)
                    }
                } else {
                    (u_direction, n, 1.0)
                };
                let direction = around(side, cosine_hemisphere(u.min(Vec2::splat(0.999_999_9))));
                let origin = offset_ray_origin(p, triangle_point_error(v, b), n, direction);
                let scale = PI * shape.area * sides / pmf;
                (
                    Ray::new(origin, direction, f32::INFINITY),
                    emission[*e as usize].at_uv(shape.uv(b), wavelengths) * scale,
                )
            }
            Light::Point {
                position,
                intensity,
            } => (
                Ray::new(*position, uniform_sphere(u_direction), f32::INFINITY),
                intensity.at(wavelengths) * (4.0 * PI / pmf),
            ),
            Light::Spot {
                position,
                direction,
                cos_inner,
                cos_outer,
                intensity,
                falloff,
                texture,
            } => {
                let local = uniform_cone(u_direction, *cos_outer);
                let w = around(*direction, local);
                let falloff = spot_falloff(local.z, *cos_inner, *cos_outer, *falloff);
                let mut beta =
                    intensity.at(wavelengths) * (falloff / (uniform_cone_pdf(*cos_outer) * pmf));
                if let Some(t) = texture
                    && falloff > 0.0
                {
                    beta *= t.at(w, wavelengths);
                }
                (Ray::new(*position, w, f32::INFINITY), beta)
            }
            Light::Directional {
                direction,
                irradiance,
            } => {
                let (origin, area) = distant(*direction);
                (
                    Ray::new(origin, *direction, f32::INFINITY),
                    irradiance.at(wavelengths) * (area / pmf),
                )
            }
            // Towards the light at `wi`, radiance `radiance`, with density `pdf` (solid
            // angle): pbrt-v4's `ImageInfiniteLight::SampleLe` (*PBR* 4th ed. §12.5.2).
            Light::Environment { radiance } => {
                let wi = uniform_sphere(u_direction);
                let (origin, area) = distant(-wi);
                (
                    Ray::new(origin, -wi, f32::INFINITY),
                    radiance.at(wavelengths) * (4.0 * PI * area / pmf),
                )
            }
            Light::EnvironmentMap { map } => {
                let (wi, pdf, radiance) =
                    map.sample_emitted(u_direction, wavelengths, &map.white(wavelengths))?;
                let (origin, area) = distant(-wi);
                (
                    Ray::new(origin, -wi, f32::INFINITY),
                    radiance * (area / (pdf * pmf)),
                )
            }
        };
        (ray.direction.is_finite() && ray.origin.is_finite() && !beta.is_black()).then_some(
            EmissionSample {
                ray,
                beta,
                light: index as u32,
            },
        )
    }
}

/// A light's flux per unit of its spectrum: emitting area times pi for the emitters, the
/// solid angle for punctual lights, a disk of the scene's radius for distant ones. Its
/// flux at wavelength l is this times [`light_spectrum`] at l.
pub(crate) fn light_extent(light: &Light, triangles: &[[Vec3; 3]], scene_radius: f32) -> f64 {
    use std::f64::consts::PI as PI64;
    let disk = f64::from(PI * scene_radius * scene_radius);
    match light {
        Light::Triangle {
            triangle,
            two_sided,
            ..
        } => {
            let area = f64::from(triangle_area(triangles[*triangle as usize]));
            PI64 * area * if *two_sided { 2.0 } else { 1.0 }
        }
        Light::Point { .. } => 4.0 * PI64,
        Light::Spot {
            cos_inner,
            cos_outer,
            ..
        } => 2.0 * PI64 * (1.0 - 0.5 * f64::from(cos_inner + cos_outer)),
        Light::Directional { .. } => disk,
        Light::Environment { .. } | Light::EnvironmentMap { .. } => PI64 * disk,
    }
}

/// The part of a textured emitter's light that triangle light `light` gives off, relative
/// to its texture's mean colour (1 for every other light): its texels' mean luminance,
/// estimated at 64 stratified points of the triangle, over the whole texture's. A tenth of
/// the mean is kept for every triangle, so that a triangle whose light the estimate misses
/// is still chosen sometimes (light choice must never rule out a triangle that emits).
/// Chosen by this, the dark parts of a sign or a screen take few light samples.
/// `uvs_of_set` gives the texture coordinates at the triangles' vertices in a set.
pub(crate) fn texture_coverage<'a>(
    light: &Light,
    uvs_of_set: impl Fn(usize) -> &'a [[Vec2; 3]],
    emission: &[SceneSpectrum],
) -> f64 {
    let Light::Triangle {
        triangle,
        emission: e,
        ..
    } = light
    else {
        return 1.0;
    };
    let SceneSpectrum::Texture(texture) = &emission[*e as usize] else {
        return 1.0;
    };
    let Some(uv) = uvs_of_set(texture.set()).get(*triangle as usize) else {
        return 1.0;
    };
    let whole = texture.luminance(None);
    if whole <= 0.0 || whole.is_nan() {
        return 1.0;
    }
    const SIDE: u32 = 8;
    let sum: f64 = (0..SIDE * SIDE)
        .map(|k| {
            let u = Vec2::new((k % SIDE) as f32 + 0.5, (k / SIDE) as f32 + 0.5) / SIDE as f32;
            let b = uniform_triangle(u);
            texture.luminance(Some(b[0] * uv[0] + b[1] * uv[1] + b[2] * uv[2]))
        })
        .sum();
    0.1 + 0.9 * (sum / f64::from(SIDE * SIDE)) / whole
}

/// A light's spectrum (radiance, intensity or irradiance).
pub(crate) fn light_spectrum<'a>(
    light: &'a Light,
    emission: &'a [SceneSpectrum],
) -> &'a SceneSpectrum {
    match light {
        Light::Triangle { emission: e, .. } => &emission[*e as usize],
        Light::Point { intensity: s, .. }
        | Light::Spot { intensity: s, .. }
        | Light::Directional { irradiance: s, .. }
        | Light::Environment { radiance: s } => s,
        Light::EnvironmentMap { map } => map.mean(),
    }
}

#[cfg(test)]
mod tests {
    use super::{SpotFalloff, spot_falloff};

    /// Mitsuba's falloff is linear in the angle between beam and cutoff, full within the
    /// beam and none from the cutoff on; glTF's is a squared ramp in cos.
    #[test]
    fn spot_falloffs_are_mitsubas_and_gltfs() {
        let (beam, cutoff) = (15f32.to_radians(), 20f32.to_radians());
        let at = |deg: f32, f| spot_falloff(deg.to_radians().cos(), beam.cos(), cutoff.cos(), f);
        let linear = SpotFalloff::LinearAngle;
        assert_eq!(at(0.0, linear), 1.0);
        assert_eq!(at(15.0, linear), 1.0);
        assert!((at(17.5, linear) - 0.5).abs() < 1e-3);
        assert!((at(19.0, linear) - 0.2).abs() < 1e-3);
        assert_eq!(at(20.0, linear), 0.0);
        assert_eq!(at(40.0, linear), 0.0);
        let t: f32 = (17.5f32.to_radians().cos() - cutoff.cos()) / (beam.cos() - cutoff.cos());
        assert!((at(17.5, SpotFalloff::Smooth) - t * t).abs() < 1e-6);
        // A beam as wide as the cutoff: a hard edge.
        let hard =
            |deg: f32| spot_falloff(deg.to_radians().cos(), cutoff.cos(), cutoff.cos(), linear);
        assert_eq!(hard(19.9), 1.0);
        assert_eq!(hard(20.1), 0.0);
    }

    /// Mitsuba's projector: 1 / cos^3 inside its cone (a plane facing it at distance 1 is
    /// lit evenly: intensity / distance^2 times cos is constant), nothing outside.
    #[test]
    fn a_projectors_intensity_is_inverse_cos_cubed() {
        let outer = 60f32.to_radians().cos();
        let f = SpotFalloff::InverseCosCubed;
        assert_eq!(spot_falloff(1.0, outer, outer, f), 1.0);
        let c = 45f32.to_radians().cos();
        assert!((spot_falloff(c, outer, outer, f) - 1.0 / (c * c * c)).abs() < 1e-5);
        // On the plane z = 1 at angle theta: distance 1 / cos, incidence cos.
        let irradiance = spot_falloff(c, outer, outer, f) * c * c * c;
        assert!((irradiance - 1.0).abs() < 1e-5);
        assert_eq!(spot_falloff(61f32.to_radians().cos(), outer, outer, f), 0.0);
        assert_eq!(spot_falloff(-0.5, -0.9, -0.9, f), 0.0);
    }
}
