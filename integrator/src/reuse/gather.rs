//! A tile's gathering: per second vertex x2_k, its connection to every first vertex x1_m
//! of the tile, the first vertices eight at a time in SIMD lanes.
//!
//! The geometry of a connection (direction, distance, local direction, Lambertian
//! density, the Jacobian to area measure, whether the pair can connect) is written once
//! over [`Real`] ([`connect`]): for one `f32` it is the formula a single pair needs, in
//! lanes the same IEEE operations lane by lane (no transcendental function is involved),
//! so every lane's values are the scalar ones to the bit (`tests` below). The tile's
//! paths are all at the same point of their work here, so the lanes are full. What stays
//! per pair: the shadow ray (traversal per ray), the BSDF's value where the pair
//! connects, and the sums, in the scalar order.

use std::f32::consts::PI;

use glam::Vec3;
use prism_sampling::distribution::positive_finite;
use prism_sampling::lanes::real::{Real, Reals, V3};
use prism_scene::world::{Bsdf, Departure, Scene};
use prism_spectrum::SampledSpectrum;

use super::tile_pixel::TilePixel;
use crate::transport::reuse_record::{FirstVertex, SecondVertex};

/// First vertices per group of lanes.
const LANES: usize = 8;

type Lane8 = Reals<LANES>;

/// The geometry of connecting first vertices (one, or lanes of them) to a second vertex.
pub(crate) struct Connection<R: Real> {
    /// Unit direction from the first vertex to the second, world space.
    pub direction: V3<R>,
    pub distance: R,
    /// `direction` in the first vertex's shading frame.
    pub wi: V3<R>,
    /// The Lambertian density of `wi` (solid angle) given the camera ray's `wo`.
    pub pdf: R,
    /// |cos theta| at the second vertex over the squared distance: solid angle to area.
    pub jacobian: R,
    /// Whether the pair can connect: a positive finite distance, the first vertex on the
    /// side of the second whose reflected light it estimates, a positive finite Jacobian.
    pub ok: R::Mask,
}

/// Where first vertices are: point, shading frame (x, y, z) and the z of the camera
/// ray's direction in it (the side the Lambertian BSDF reflects on).
pub(crate) struct FirstVertices<R> {
    pub p: V3<R>,
    pub frame: [V3<R>; 3],
    pub wo_z: R,
}

impl FirstVertices<f32> {
    /// One first vertex.
    fn of<const N: usize>(first: &FirstVertex<'_, N>) -> Self {
        Self {
            p: first.hit.p.into(),
            frame: [
                first.frame.x.into(),
                first.frame.y.into(),
                first.frame.z.into(),
            ],
            wo_z: first.wo.z,
        }
    }
}

impl Connection<Lane8> {
    /// Lane `i`'s connection.
    fn lane(&self, i: usize) -> Connection<f32> {
        let v3 = |v: &V3<Lane8>| V3::new(v.x.lane(i), v.y.lane(i), v.z.lane(i));
        Connection {
            direction: v3(&self.direction),
            distance: self.distance.lane(i),
            wi: v3(&self.wi),
            pdf: self.pdf.lane(i),
            jacobian: self.jacobian.lane(i),
            ok: self.ok.get(i),
        }
    }
}

fn splat<R: Real>(v: Vec3) -> V3<R> {
    V3::splat3(v.x, v.y, v.z)
}

fn positive_finite_lanes<R: Real>(x: R) -> R::Mask {
    x.gt(R::splat(0.0)) & x.is_finite()
}

/// The connections of `firsts` to `second`: for `f32`, the operations of the scalar
/// formulas (glam's `Vec3` ones, in its order); for lanes, the same per lane.
#[inline(always)]
pub(crate) fn connect<R: Real>(firsts: &FirstVertices<R>, second: &SecondVertex) -> Connection<R> {
    let zero = R::splat(0.0);
    let x2 = splat::<R>(second.p);
    let to = x2 - firsts.p;
    let distance = to.length();
    // x1_m must lie on the side of x2_k whose reflected light S_k is.
    let away = (firsts.p - x2).dot(splat(second.shading_normal)).gt(zero);
    let on_side = if second.side { away } else { !away };
    let direction = V3::new(to.x / distance, to.y / distance, to.z / distance);
    let [x, y, z] = &firsts.frame;
    let wi = V3::new(direction.dot(*x), direction.dot(*y), direction.dot(*z));
    // `prism_scene::bsdf::Diffuse::pdf`: cosine-weighted on `wo`'s side.
    let same_side = (firsts.wo_z * wi.z).gt(zero);
    let pdf = R::select(same_side, wi.z.abs().max(zero) / R::splat(PI), zero);
    let jacobian = splat::<R>(second.normal).dot(direction).abs() / (distance * distance);
    let ok = positive_finite_lanes(distance) & on_side & positive_finite_lanes(jacobian);
    Connection {
        direction,
        distance,
        wi,
        pdf,
        jacobian,
        ok,
    }
}

/// What a first vertex's connections need besides the lanes' geometry.
struct Start {
    /// Where its shadow rays leave.
    departure: Departure,
    /// Whether its BSDF is Lambertian, whose density the lanes compute (any other is asked
    /// per pair).
    lambertian: bool,
}

/// The buffers of a tile's gathering, kept from tile to tile.
pub(super) struct Gathering<const N: usize> {
    /// The first vertices, eight to a group.
    groups: Vec<FirstVertices<Lane8>>,
    /// Per pixel, what its first vertex's connections need besides the lanes.
    starts: Vec<Option<Start>>,
    connections: Vec<Connection<Lane8>>,
    density: Vec<f32>,
    light: Vec<SampledSpectrum<N>>,
    gathered: Vec<SampledSpectrum<N>>,
}

impl<const N: usize> Gathering<N> {
    pub(super) fn new() -> Self {
        Self {
            groups: Vec::new(),
            starts: Vec::new(),
            connections: Vec::new(),
            density: Vec::new(),
            light: Vec::new(),
            gathered: Vec::new(),
        }
    }

    /// Per pixel of a tile, the light its first vertex gathers from the tile's second
    /// vertices (its own included); adds the shadow rays it traces to the pixels' counts.
    // The first vertex's index m is compared with k and indexes five arrays.
    #[allow(clippy::needless_range_loop)]
    pub(super) fn gather(
        &mut self,
        scene: &Scene,
        pixels: &mut [TilePixel<'_, N>],
    ) -> &[SampledSpectrum<N>] {
        let n = pixels.len();
        let black = SampledSpectrum::<N>::splat(0.0);
        self.gathered.clear();
        self.gathered.resize(n, black);
        self.density.clear();
        self.density.resize(n, 0.0);
        self.light.clear();
        self.light.resize(n, black);
        // A tile with fewer pixels than lanes connects them one pair at a time.
        let lanes = n >= LANES;
        self.set_first_vertices(pixels, lanes);
        // Per second vertex k: each first vertex's area density of it, and what it would add.
        for k in 0..n {
            let Some(second) = &pixels[k].record.second else {
                continue;
            };
            let reflected = pixels[k].record.reflected;
            self.connections.clear();
            if lanes {
                self.connections
                    .extend(self.groups.iter().map(|group| connect(group, second)));
            }
            let mut total = 0.0f32;
            for m in 0..n {
                self.density[m] = 0.0;
                let Some(first) = &pixels[m].record.first else {
                    continue;
                };
                let (direction, distance, wi, pdf, jacobian) = if m == k {
                    let direction = first.frame.to_world(first.wi);
                    let distance = second.distance;
                    let jacobian = second.normal.dot(direction).abs() / (distance * distance);
                    (direction, distance, first.wi, first.pdf, jacobian)
                } else {
                    let connection = if lanes {
                        self.connections[m / LANES].lane(m % LANES)
                    } else {
                        connect(&FirstVertices::of(first), second)
                    };
                    if !connection.ok {
                        continue;
                    }
                    let wi = Vec3::from(connection.wi);
                    let lambertian = self.starts[m].as_ref().is_some_and(|s| s.lambertian);
                    let pdf = if lambertian {
                        connection.pdf
                    } else {
                        first.bsdf.pdf(first.wo, wi)
                    };
                    let direction = Vec3::from(connection.direction);
                    (direction, connection.distance, wi, pdf, connection.jacobian)
                };
                if !positive_finite(pdf) || !positive_finite(jacobian) {
                    continue;
                }
                if m != k {
                    pixels[m].result.rays += 1;
                    pixels[m].result.connections += 1;
                    let Some(start) = &self.starts[m] else {
                        continue;
                    };
                    if scene.occluded(&start.departure.ray_to(direction, distance)) {
                        continue;
                    }
                }
                self.density[m] = pdf * jacobian;
                total += self.density[m];
                self.light[m] = first.bsdf.f(first.wo, wi) * (wi.z.abs() * jacobian) * reflected;
            }
            if !positive_finite(total) {
                continue;
            }
            for m in 0..n {
                if self.density[m] > 0.0 {
                    self.gathered[m] += self.light[m] * (1.0 / total);
                }
            }
        }
        &self.gathered
    }

    /// Lays the pixels' first vertices out in groups of lanes (a pixel without one: zeros,
    /// which its `record.first` being None excludes) and notes what else each needs.
    fn set_first_vertices(&mut self, pixels: &[TilePixel<'_, N>], lanes: bool) {
        self.starts.clear();
        self.starts.extend(pixels.iter().map(|pixel| {
            let first = pixel.record.first.as_ref()?;
            Some(Start {
                departure: first.hit.departure(),
                lambertian: matches!(first.bsdf, Bsdf::Diffuse(_)),
            })
        }));
        self.groups.clear();
        if !lanes {
            return;
        }
        for chunk in pixels.chunks(LANES) {
            let mut p = [[0.0f32; LANES]; 3];
            let mut frame = [[[0.0f32; LANES]; 3]; 3];
            let mut wo_z = [0.0f32; LANES];
            for (i, pixel) in chunk.iter().enumerate() {
                let Some(first) = &pixel.record.first else {
                    continue;
                };
                for axis in 0..3 {
                    p[axis][i] = first.hit.p[axis];
                    for (row, v) in [first.frame.x, first.frame.y, first.frame.z]
                        .iter()
                        .enumerate()
                    {
                        frame[row][axis][i] = v[axis];
                    }
                }
                wo_z[i] = first.wo.z;
            }
            let lanes = |a: [f32; LANES]| Lane8::from_fn(|i| a[i]);
            let v3 = |a: [[f32; LANES]; 3]| V3::new(lanes(a[0]), lanes(a[1]), lanes(a[2]));
            self.groups.push(FirstVertices {
                p: v3(p),
                frame: frame.map(v3),
                wo_z: lanes(wo_z),
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_scene::bsdf::Diffuse;
    use prism_scene::geometry::Frame;
    use proptest::prelude::*;

    /// What the gather computed per pair before it ran in lanes: glam's operations and the
    /// scene's Lambertian density. Returns None where the pair cannot connect.
    fn scalar(
        p: Vec3,
        frame: &Frame,
        wo: Vec3,
        second: &SecondVertex,
    ) -> Option<(Vec3, f32, Vec3, f32, f32)> {
        let to = second.p - p;
        let distance = to.length();
        if !positive_finite(distance)
            || ((p - second.p).dot(second.shading_normal) > 0.0) != second.side
        {
            return None;
        }
        let direction = to / distance;
        let wi = frame.to_local(direction);
        let pdf = Diffuse::<4>::new(SampledSpectrum::splat(0.5)).pdf(wo, wi);
        let jacobian = second.normal.dot(direction).abs() / (distance * distance);
        positive_finite(jacobian).then_some((direction, distance, wi, pdf, jacobian))
    }

    fn component() -> impl Strategy<Value = f32> {
        prop_oneof![
            Just(0.0f32),
            Just(-0.0f32),
            Just(1e-30f32),
            Just(1e30f32),
            Just(f32::INFINITY),
            Just(f32::NAN),
            -2.0..2.0f32,
            -1e4..1e4f32,
        ]
    }

    fn point() -> impl Strategy<Value = Vec3> {
        prop_oneof![
            4 => prop::array::uniform3(-2.0..2.0f32).prop_map(Vec3::from_array),
            1 => prop::array::uniform3(component()).prop_map(Vec3::from_array),
        ]
    }

    fn unit() -> impl Strategy<Value = Vec3> {
        point().prop_map(|v| v.normalize_or(Vec3::Z))
    }

    fn bits(v: Vec3) -> [u32; 3] {
        v.to_array().map(f32::to_bits)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]
        /// Eight first vertices in lanes connect to a second vertex with the values the
        /// scalar formulas give each, to the bit, and the same verdicts; the f32 instance
        /// of `connect` too.
        #[test]
        fn lanes_connect_as_the_scalar_formulas(
            firsts in prop::collection::vec((point(), unit(), point()), LANES),
            x2 in point(),
            normal in unit(),
            shading_normal in unit(),
            side: bool,
        ) {
            let second = SecondVertex { p: x2, normal, shading_normal, side, distance: 1.0 };
            let frames: Vec<Frame> = firsts.iter().map(|(_, n, _)| Frame::from_normal(*n)).collect();
            let group = FirstVertices {
                p: V3::from_fn(|i| firsts[i].0),
                frame: [
                    V3::from_fn(|i| frames[i].x),
                    V3::from_fn(|i| frames[i].y),
                    V3::from_fn(|i| frames[i].z),
                ],
                wo_z: Lane8::from_fn(|i| frames[i].to_local(firsts[i].2).z),
            };
            let lanes = connect(&group, &second);
            for (i, (p, _, wo_world)) in firsts.iter().enumerate() {
                let wo = frames[i].to_local(*wo_world);
                let one = FirstVertices {
                    p: (*p).into(),
                    frame: [frames[i].x.into(), frames[i].y.into(), frames[i].z.into()],
                    wo_z: wo.z,
                };
                let single = connect(&one, &second);
                let lane = lanes.lane(i);
                match scalar(*p, &frames[i], wo, &second) {
                    None => {
                        prop_assert!(!lane.ok);
                        prop_assert!(!single.ok);
                    }
                    Some((direction, distance, wi, pdf, jacobian)) => {
                        for c in [&lane, &single] {
                            prop_assert!(c.ok);
                            prop_assert_eq!(bits(Vec3::from(c.direction)), bits(direction));
                            prop_assert_eq!(c.distance.to_bits(), distance.to_bits());
                            prop_assert_eq!(bits(Vec3::from(c.wi)), bits(wi));
                            prop_assert_eq!(c.pdf.to_bits(), pdf.to_bits());
                            prop_assert_eq!(c.jacobian.to_bits(), jacobian.to_bits());
                        }
                    }
                }
            }
        }
    }
}
