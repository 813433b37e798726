//! What prism ignores, said: after a scene is read, every parameter of a shape, emitter,
//! sensor, film, sampler, reconstruction filter or integrator that no reader asked for is
//! one warning line with its file and line. Mitsuba does the same for properties its
//! plugins do not query. BSDFs, textures, media, phases and volumes refuse an unknown
//! parameter outright, so they are not walked here.

use std::collections::HashSet;

use super::tree::{Class, Object};

/// One warning per unread parameter of `scene`'s objects, in file order.
pub(crate) fn unread_parameters(scene: &Object) -> Vec<String> {
    let mut warnings = Vec::new();
    let mut visited = HashSet::new();
    for child in &scene.children {
        walk(&child.object, &mut visited, &mut warnings);
    }
    warnings
}

fn walk(object: &Object, visited: &mut HashSet<*const Object>, warnings: &mut Vec<String>) {
    let walked = matches!(
        object.class,
        Class::Shape
            | Class::Emitter
            | Class::Sensor
            | Class::Film
            | Class::Sampler
            | Class::Rfilter
            | Class::Integrator
    );
    // A shared object (a reference) is said once.
    if !walked || !visited.insert(object as *const Object) {
        return;
    }
    for p in object.unread() {
        warnings.push(format!(
            "{}: {} '{}': parameter '{}' is not read; prism ignores it",
            p.at,
            object.class.tag(),
            object.kind,
            p.name
        ));
    }
    for child in &object.children {
        walk(&child.object, visited, warnings);
    }
}
