//! The sunny sky the environment and light-path tests share (each declares the `rgbe`
//! module this writes its file with).

use std::sync::Arc;

use glam::Vec2;
use prism_scene::load::environment_map;
use prism_scene::world::EnvironmentMap;

use crate::rgbe::rgbe_file;

/// A sky of radiance ~0.2 (0.2, 0.18, 0.25) with a sun of radiance 2000 about 2.4 texels
/// wide, high to the +x +z side of a 64 x 32 image.
pub fn sunny_sky() -> Arc<EnvironmentMap> {
    let (w, h) = (64u32, 32u32);
    let bytes = rgbe_file(w, h, |x, y| {
        let d = Vec2::new(x as f32 + 0.5 - 40.0, y as f32 + 0.5 - 9.0).length();
        if d < 1.2 {
            [2000.0; 3]
        } else {
            [0.2, 0.18, 0.25]
        }
    });
    environment_map(&bytes, 0.0, 1.0).unwrap()
}
