//! From the parser's flat list of objects, whose references are ids, to the tree of
//! [`Object`]s whose references are the objects themselves. Mitsuba resolves references
//! after the whole file is read (`instantiate_node` in src/core/xml.cpp), so a `<ref>`
//! may name an object defined later or nested elsewhere; a reference to an unknown id, or
//! a circle of references, is an error. Each object is built once and shared through an
//! [`Arc`] by every reference to it. The walk keeps its own stack: a long chain of
//! references cannot overflow the thread's.

use std::collections::HashMap;
use std::sync::Arc;

use super::parse::error;
use super::tree::{Child, Class, Location, Object, Property};
use crate::LoadError;

/// An object as the parser reads it.
#[derive(Debug)]
pub struct RawObject {
    pub class: Class,
    pub kind: String,
    pub id: Option<String>,
    pub properties: Vec<Property>,
    pub children: Vec<RawChild>,
    pub at: Location,
}

impl RawObject {
    pub fn new(class: Class, kind: String, id: Option<String>, at: Location) -> RawObject {
        RawObject {
            class,
            kind,
            id,
            properties: Vec::new(),
            children: Vec::new(),
            at,
        }
    }
}

/// A child as the parser reads it.
#[derive(Debug)]
pub struct RawChild {
    pub name: Option<String>,
    pub target: Target,
}

/// What a child is.
#[derive(Debug)]
pub enum Target {
    /// An object nested in place: its index in the arena.
    Index(usize),
    /// A `<ref>`.
    Id { id: String, at: Location },
}

/// The objects read so far and their ids.
#[derive(Debug, Default)]
pub struct Arena {
    objects: Vec<RawObject>,
    /// id -> (index, where the id was defined), for objects pushed and aliases.
    ids: HashMap<String, (usize, Location)>,
    /// Every id declared so far (objects still being read included), for duplicates.
    declared: HashMap<String, Location>,
}

impl Arena {
    /// Declares an id where its tag starts; the earlier place when it is declared twice.
    pub fn declare(&mut self, id: &str, at: &Location) -> Result<(), Location> {
        match self.declared.get(id) {
            Some(previous) => Err(previous.clone()),
            None => {
                self.declared.insert(id.to_string(), at.clone());
                Ok(())
            }
        }
    }

    /// Adds a finished object; returns its index.
    pub fn push(&mut self, object: RawObject) -> usize {
        let index = self.objects.len();
        if let Some(id) = &object.id {
            self.ids.insert(id.clone(), (index, object.at.clone()));
        }
        self.objects.push(object);
        index
    }

    /// `<alias id="id" as="alias">`; false when `id` is not defined yet.
    pub fn alias(&mut self, id: &str, alias: &str, at: Location) -> bool {
        if let Some((index, _)) = self.ids.get(id) {
            let index = *index;
            self.ids.insert(alias.to_string(), (index, at));
            true
        } else {
            false
        }
    }

    /// Resolves every reference and builds the scene's tree.
    pub fn finish(mut self, scene: RawObject) -> Result<Object, LoadError> {
        let root = self.push(scene);
        // Each object's children as arena indices, unknown ids reported.
        let mut edges: Vec<Vec<(usize, Option<Location>)>> = Vec::with_capacity(self.objects.len());
        for object in &self.objects {
            let mut list = Vec::with_capacity(object.children.len());
            for child in &object.children {
                list.push(match &child.target {
                    Target::Index(i) => (*i, None),
                    Target::Id { id, at } => match self.ids.get(id) {
                        Some((i, _)) => (*i, Some(at.clone())),
                        None => {
                            return Err(error(at, format!("reference to unknown object \"{id}\"")));
                        }
                    },
                });
            }
            edges.push(list);
        }
        let mut built: Vec<Option<Arc<Object>>> = vec![None; self.objects.len()];
        let mut on_stack = vec![false; self.objects.len()];
        let mut stack: Vec<(usize, usize)> = vec![(root, 0)];
        if let Some(flag) = on_stack.get_mut(root) {
            *flag = true;
        }
        while let Some(top) = stack.last_mut() {
            let (node, next) = *top;
            let node_edges = edges.get(node).map(Vec::as_slice).unwrap_or(&[]);
            if let Some((dep, via)) = node_edges.get(next) {
                top.1 += 1;
                let dep = *dep;
                if built.get(dep).is_some_and(Option::is_some) {
                    continue;
                }
                if on_stack.get(dep).copied().unwrap_or(false) {
                    let at = via.clone().unwrap_or_else(|| self.objects[node].at.clone());
                    let id = self.objects[dep].id.clone().unwrap_or_default();
                    return Err(error(
                        &at,
                        format!("reference cycle: \"{id}\" refers back to itself"),
                    ));
                }
                on_stack[dep] = true;
                stack.push((dep, 0));
                continue;
            }
            // Every child is built: build this object.
            stack.pop();
            on_stack[node] = false;
            let raw = &mut self.objects[node];
            let mut children = Vec::with_capacity(raw.children.len());
            for (child, (dep, _)) in raw.children.drain(..).zip(node_edges) {
                if let Some(Some(object)) = built.get(*dep) {
                    children.push(Child {
                        name: child.name,
                        object: Arc::clone(object),
                    });
                }
            }
            built[node] = Some(Arc::new(Object {
                class: raw.class,
                kind: std::mem::take(&mut raw.kind),
                id: raw.id.take(),
                properties: std::mem::take(&mut raw.properties),
                children,
                at: raw.at.clone(),
            }));
        }
        let scene = built
            .get_mut(root)
            .and_then(Option::take)
            .ok_or_else(|| error(&self.objects[root].at, "the scene could not be built"))?;
        drop(built);
        Ok(Arc::try_unwrap(scene).unwrap_or_else(|shared| (*shared).clone()))
    }
}
