//! What a camera path records for path reuse (`crate::reuse`): its first vertex where it
//! can share, its second vertex where it reflects alike in every direction, and the light
//! it gathered before and beyond the second vertex. The path tracers fill it; reuse's
//! tiles read it.

use glam::Vec3;
use prism_scene::bsdf::BsdfSample;
use prism_scene::geometry::{Frame, Ray};
use prism_scene::world::{Bsdf, Hit, Material};

/// A path's first vertex, recorded when it can share ([`shares_first`]): the technique
/// that can reach other pixels' second vertices.
pub(crate) struct FirstVertex<'s, const N: usize> {
    pub hit: Hit,
    pub frame: Frame,
    /// The direction the camera ray arrived from, local.
    pub wo: Vec3,
    pub bsdf: Bsdf<'s, N>,
    /// The direction sampled (local) and its density.
    pub wi: Vec3,
    pub pdf: f32,
}

impl<'s, const N: usize> FirstVertex<'s, N> {
    /// The first vertex `hit` (of `material`, with `bsdf` in `frame`, seen from `wo`) whose
    /// bounce `sample` drew with density `pdf`, where it is one that can reach other
    /// pixels' second vertices: a material that [`shares_first`], sampled neither as a
    /// delta nor per wavelength. None elsewhere.
    #[inline(always)]
    pub(crate) fn recorded(
        material: &Material,
        hit: Hit,
        frame: Frame,
        wo: Vec3,
        bsdf: &Bsdf<'s, N>,
        sample: &BsdfSample<N>,
        pdf: f32,
    ) -> Option<Self> {
        let shares = !sample.delta && !sample.wavelength_dependent && shares_first(material);
        shares.then(|| Self {
            hit,
            frame,
            wo,
            bsdf: bsdf.clone(),
            wi: sample.wi,
            pdf,
        })
    }
}

/// Whether a first vertex of `material` gathers its tile's second vertices: Lambertian
/// ones, and plastics under a rough coating, whose substrate's wide lobe overlaps its
/// neighbours' (the plastic box reaches equal error sooner: docs/trade-offs.md, "Path
/// reuse across tiles of pixels"). Every bounce drawn
/// there must be one that can be shared (a pixel that drew a delta would not gather, and
/// its light reflected by the lobe it did not draw would be lost): a smooth coating's
/// mirror is a delta. Conductors and glass are left out: the glossy box's copper (GGX alpha
/// 0.15) and aluminium (0.3) lowered its error less than they added to the time, their
/// lobes too narrow for most pairs (docs/trade-offs.md, "Tried and not kept"); a narrow one
/// ([`crate::transport::light_path::CAUSTIC_ALPHA`]) would also mix paths whose caustics
/// light paths carry with paths whose they do not.
fn shares_first(material: &Material) -> bool {
    match material {
        Material::Diffuse { .. } => true,
        Material::Plastic { coating, .. } => !coating.distribution().effectively_smooth(),
        _ => false,
    }
}

/// A path's second vertex, recorded when it reflects alike in every direction.
pub(crate) struct SecondVertex {
    pub p: Vec3,
    /// The geometric normal (the area density's cosine) and the shading normal (whose side
    /// the reflected light is).
    pub normal: Vec3,
    pub shading_normal: Vec3,
    /// Whether the first vertex lies on the shading normal's side.
    pub side: bool,
    /// Distance from the first vertex.
    pub distance: f32,
}

impl SecondVertex {
    /// The second vertex `hit`, which `ray` (from the first vertex) found, seen from the
    /// direction `wo_world` back along it.
    #[inline(always)]
    pub(crate) fn at(hit: &Hit, ray: &Ray, wo_world: Vec3) -> Self {
        Self {
            p: hit.p,
            normal: hit.normal,
            shading_normal: hit.shading_normal,
            side: wo_world.dot(hit.shading_normal) > 0.0,
            distance: hit.t * ray.direction.length(),
        }
    }
}

/// What a path leaves for its tile: its first and second vertices, the light it
/// gathered before the second vertex (`own`) and what the second vertex reflects
/// (`reflected`, per unit of throughput there).
pub(crate) struct ReuseRecord<'s, const N: usize, R> {
    pub first: Option<FirstVertex<'s, N>>,
    pub second: Option<SecondVertex>,
    pub own: R,
    pub reflected: R,
}

impl<'s, const N: usize, R: Clone> ReuseRecord<'s, N, R> {
    /// An empty record whose radiances are `black`.
    pub(crate) fn new(black: R) -> Self {
        Self {
            first: None,
            second: None,
            own: black.clone(),
            reflected: black,
        }
    }
}
