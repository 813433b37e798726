//! Which medium a path is in: the world's (fog, or vacuum), and on top of it the medium of
//! each volume boundary it has entered and not yet left, so that a medium inside a glass
//! inside fog is left for the fog again. In scenes whose surfaces say what lies on either
//! side (Mitsuba's, `Media::with_sides`) there is no nesting: crossing a surface sets the
//! medium, and the stack keeps one entry.

use glam::Vec3;
use prism_scene::world::{Hit, Scene};

/// Nested boundaries deeper than this replace the innermost (a path inside eight
/// volumes at once is already a malformed scene's: overlapping closed surfaces).
const DEPTH: usize = 8;

/// The media a path is inside, innermost last; `None` entries are volumes of vacuum
/// (a dielectric without a medium).
#[derive(Debug, Clone, Copy)]
pub(crate) struct MediumStack {
    entries: [Option<u32>; DEPTH],
    /// Entries in use; the first is the world's and is never left.
    len: usize,
}

impl MediumStack {
    /// A path starting outside every boundary, in the world's medium (if any).
    pub(crate) fn new(world: Option<u32>) -> Self {
        let mut entries = [None; DEPTH];
        entries[0] = world;
        Self { entries, len: 1 }
    }

    /// The media around the camera: the world's, and those of the closed volumes the
    /// camera is inside (underwater, in a fog box), found by a probe ray from the camera's
    /// position that notes each volume it leaves without having entered it. One position
    /// serves the whole render (an orthographic camera's rays start apart: a volume that
    /// encloses some of them and not others is not found this way). A scene without media
    /// has none.
    pub(crate) fn around_camera(scene: &Scene) -> Self {
        let mut stack = Self::new(scene.media().world());
        // Where surfaces set the medium, the camera's is the one the scene gives it (the
        // world's: Mitsuba's sensor medium), as Mitsuba starts its paths.
        if scene.media().is_empty() || scene.media().crossing_sets() {
            return stack;
        }
        let origin = scene
            .camera()
            .generate_ray(glam::Vec2::splat(0.5), 1.0)
            .origin;
        // An arbitrary direction, off the axes that modelled boxes are aligned with.
        let direction = Vec3::new(0.267, 0.862, 0.431).normalize();
        let mut ray = prism_scene::geometry::Ray::new(origin, direction, f32::INFINITY);
        let mut entered: Vec<u32> = Vec::new();
        let mut enclosing: Vec<Option<u32>> = Vec::new();
        for _ in 0..1024 {
            let Some(hit) = scene.intersect(&ray) else {
                break;
            };
            if scene.bounds_volume(&hit) {
                let material = scene.material_index(&hit);
                if direction.dot(hit.normal) < 0.0 {
                    entered.push(material);
                } else if entered.last() == Some(&material) {
                    entered.pop();
                } else {
                    enclosing.push(scene.medium_inside(&hit));
                }
            }
            ray = hit.spawn(direction);
        }
        // Outermost first.
        for medium in enclosing.into_iter().rev() {
            if stack.len < DEPTH {
                stack.len += 1;
            }
            stack.entries[stack.len - 1] = medium;
        }
        stack
    }

    /// The medium the path is in now.
    #[inline]
    pub(crate) fn current(&self) -> Option<u32> {
        self.entries[self.len - 1]
    }

    /// Crosses the volume boundary `hit` (where [`Scene::bounds_volume`]) towards unit
    /// `direction`: against the outward geometric normal it enters the boundary's
    /// medium, along it it leaves the innermost one; where the surface says what lies on
    /// the side the path goes to ([`Scene::medium_beyond`]), that is the medium.
    #[inline]
    pub(crate) fn cross(&mut self, scene: &Scene, hit: &Hit, direction: Vec3) {
        if let Some(beyond) = scene.medium_beyond(hit, direction) {
            self.entries[self.len - 1] = beyond;
        } else if scene.media().crossing_sets() {
            // A surface with nothing on its sides changes nothing.
        } else if direction.dot(hit.normal) < 0.0 {
            let inside = scene.medium_inside(hit);
            if self.len < DEPTH {
                self.len += 1;
            }
            self.entries[self.len - 1] = inside;
        } else if self.len > 1 {
            self.len -= 1;
        }
    }

    /// The media a path is in after scattering at `hit` from `incoming` to `outgoing`
    /// (unit directions of travel): crossed where the path goes on through a volume's
    /// boundary ([`Scene::bounds_volume`]), the same where it turns back.
    #[inline]
    pub(crate) fn after(&self, scene: &Scene, hit: &Hit, incoming: Vec3, outgoing: Vec3) -> Self {
        let mut next = *self;
        if incoming.dot(hit.normal) * outgoing.dot(hit.normal) > 0.0 && scene.bounds_volume(hit) {
            next.cross(scene, hit, outgoing);
        }
        next
    }
}
