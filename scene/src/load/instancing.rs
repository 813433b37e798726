//! How much a scene's node graph instances, counted before anything is instanced.
//!
//! glTF nodes may be shared: a node listed as the child of two parents is instanced under
//! each. Forty levels of nodes that each list one child twice make a file of a few
//! kilobytes instance a mesh 2^40 times, and loading it would allocate until the process
//! dies. Counting first, with every node's subtree counted once and reused by each parent,
//! costs one pass over the nodes, so such a file is an error before any allocation.

use super::LoadError;

/// The most triangles, primitives, punctual lights and cameras a scene may instance:
/// triangles are indexed by u32 throughout (the BVH's packets mark leaves with the top
/// bit), and far fewer already exceed any machine's memory.
pub(super) const MAX_INSTANCED: u64 = (1 << 31) - 1;

/// Checks what `scene` instances: the sum over its root nodes of each subtree's
/// triangles, primitives, punctual lights and cameras, each shared subtree counted once
/// per use. Errors when that exceeds [`MAX_INSTANCED`], or when a node is its own ancestor.
pub(super) fn check(document: &gltf::Document, scene: &gltf::Scene) -> Result<(), LoadError> {
    let nodes: Vec<gltf::Node> = document.nodes().collect();
    let mut subtree: Vec<Option<u64>> = vec![None; nodes.len()];
    let mut open = vec![false; nodes.len()];
    let mut total = 0u64;
    for root in scene.nodes() {
        // Depth-first, children before parents, without recursion: chains of nodes may be
        // longer than the machine stack is deep.
        let mut stack = vec![(root.index(), false)];
        while let Some((n, children_done)) = stack.pop() {
            if subtree[n].is_some() {
                continue;
            }
            if children_done {
                let own = own_weight(&nodes[n]);
                let sum = nodes[n].children().fold(own, |s, c| {
                    s.saturating_add(subtree[c.index()].unwrap_or(0))
                });
                subtree[n] = Some(sum);
                open[n] = false;
                continue;
            }
            // A node is open while its descendants are on the stack; one of them naming it
            // as a child is a cycle, caught below before the child is pushed.
            open[n] = true;
            stack.push((n, true));
            for child in nodes[n].children() {
                if open[child.index()] {
                    return Err(LoadError::Scene(format!(
                        "node {} is its own ancestor (the node hierarchy has a cycle)",
                        child.index()
                    )));
                }
                if subtree[child.index()].is_none() {
                    stack.push((child.index(), false));
                }
            }
        }
        total = total.saturating_add(subtree[root.index()].unwrap_or(0));
    }
    if total > MAX_INSTANCED {
        return Err(LoadError::Scene(format!(
            "the scene instances {} triangles, primitives, lights and cameras (a node shared \
             by several parents counts under each), more than prism's limit of {}",
            if total == u64::MAX {
                "more than 2^64".to_string()
            } else {
                total.to_string()
            },
            MAX_INSTANCED
        )));
    }
    Ok(())
}

/// What one node instances itself: its mesh's primitives and their triangles (from the
/// accessors' declared counts; reading them is `add_primitive`'s), a light, a camera.
fn own_weight(node: &gltf::Node) -> u64 {
    let triangles = |p: &gltf::Primitive| {
        let vertices = p
            .indices()
            .or_else(|| p.get(&gltf::Semantic::Positions))
            .map_or(0, |a| a.count() as u64);
        vertices / 3
    };
    let mesh = node.mesh().map_or(0, |m| {
        m.primitives()
            .fold(0u64, |s, p| s.saturating_add(1 + triangles(&p)))
    });
    mesh + u64::from(node.light().is_some()) + u64::from(node.camera().is_some())
}
