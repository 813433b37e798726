//! Mitsuba's `shapegroup` and `instance` ("Shapes" plugin reference): a group's shapes
//! are read once, in the group's own space, and each instance places a copy of them by
//! its `to_world` (points by it, normals by its inverse transpose, as Mitsuba's
//! `Instance::compute_surface_interaction` transforms a hit). Each shape keeps the BSDF
//! the group gives it: Mitsuba cannot give an instance a material of its own either.
//!
//! prism's BVH holds triangles, so an instance is its group's triangles copied and
//! moved; the scene's total is held to the limit glTF's node instancing has.
//! What Mitsuba refuses inside a group is refused here too (`render/shapegroup.cpp`):
//! nested groups and instances, and emitters.

use std::collections::HashMap;
use std::sync::Arc;

use super::files::Files;
use super::parse::error;
use super::shape_mesh::ShapeMesh;
use super::shapes::{shape_mesh, transform};
use super::tree::{Class, Object};
use crate::LoadError;

/// The groups read so far: each group's shapes with their meshes in the group's space.
#[derive(Default)]
pub(crate) struct Groups {
    read: HashMap<usize, Vec<(Arc<Object>, ShapeMesh)>>,
}

impl Groups {
    /// The shapes `instance` places, each with its mesh moved by the instance's
    /// `to_world`. `already` is the number of triangles the scene has so far.
    pub(crate) fn place(
        &mut self,
        instance: &Object,
        already: usize,
        files: &Files,
        warnings: &mut Vec<String>,
    ) -> Result<Vec<(Arc<Object>, ShapeMesh)>, LoadError> {
        let mut groups = instance.children_of(Class::Shape);
        let group = match (groups.next(), groups.next()) {
            (Some(g), None) if g.object.kind == "shapegroup" => g.object.clone(),
            (Some(g), None) => {
                return Err(error(
                    &instance.at,
                    format!("an instance places a shapegroup, not a '{}'", g.object.kind),
                ));
            }
            (None, _) => {
                return Err(error(
                    &instance.at,
                    "an instance needs a reference to a shapegroup",
                ));
            }
            (Some(_), Some(_)) => {
                return Err(error(&instance.at, "an instance places one shapegroup"));
            }
        };
        let key = Arc::as_ptr(&group) as usize;
        let members = match self.read.entry(key) {
            std::collections::hash_map::Entry::Occupied(e) => e.into_mut(),
            std::collections::hash_map::Entry::Vacant(e) => {
                e.insert(members(&group, files, warnings)?)
            }
        };
        let triangles: usize = members.iter().map(|(_, m)| m.triangles.len()).sum();
        let limit = crate::load::instancing::MAX_INSTANCED;
        if (already as u64).saturating_add(triangles as u64) > limit {
            return Err(error(
                &instance.at,
                format!("this instance brings the scene past prism's limit of {limit} triangles"),
            ));
        }
        let to_world = transform(instance, "to_world")?;
        members
            .iter()
            .map(|(shape, mesh)| {
                mesh.transformed(&to_world)
                    .map(|m| (shape.clone(), m))
                    .map_err(|e| error(&instance.at, e))
            })
            .collect()
    }
}

/// Checks a `shapegroup` as Mitsuba does when it is defined, instanced or not.
pub(crate) fn check_group(group: &Object) -> Result<(), LoadError> {
    for child in &group.children {
        let shape = &child.object;
        if shape.class != Class::Shape {
            return Err(error(
                &shape.at,
                format!(
                    "a shapegroup holds shapes, not a {} '{}'",
                    shape.class.tag(),
                    shape.kind
                ),
            ));
        }
        match shape.kind.as_str() {
            "shapegroup" => return Err(error(&shape.at, "shapegroups do not nest")),
            "instance" => return Err(error(&shape.at, "a shapegroup cannot hold an instance")),
            _ => {}
        }
        if shape.children_of(Class::Emitter).next().is_some() {
            return Err(error(
                &shape.at,
                "a shape in a shapegroup cannot emit (Mitsuba does not instance emitters)",
            ));
        }
    }
    Ok(())
}

/// The shapes of `group` with their meshes in the group's space.
fn members(
    group: &Object,
    files: &Files,
    warnings: &mut Vec<String>,
) -> Result<Vec<(Arc<Object>, ShapeMesh)>, LoadError> {
    check_group(group)?;
    group
        .children
        .iter()
        .map(|c| Ok((c.object.clone(), shape_mesh(&c.object, files, warnings)?)))
        .collect()
}
