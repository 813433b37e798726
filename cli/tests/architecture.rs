//! The workspace's dependency graph is the DAG that ARCHITECTURE.md states. This reads
//! every member's manifest and fails on any prism-to-prism edge not in the allowed set,
//! so a new edge has to be argued for in ARCHITECTURE.md and here at once.

use std::collections::BTreeSet;

const ALLOWED: &[(&str, &[&str])] = &[
    ("spectrum", &[]),
    ("sampling", &[]),
    ("upsample", &["prism-spectrum"]),
    (
        "scene",
        &["prism-spectrum", "prism-upsample", "prism-sampling"],
    ),
    (
        "integrator",
        &["prism-scene", "prism-spectrum", "prism-sampling"],
    ),
    (
        "cli",
        &[
            "prism-spectrum",
            "prism-upsample",
            "prism-sampling",
            "prism-scene",
            "prism-integrator",
        ],
    ),
    // A dependent of every library crate, using their public API only (tests).
    (
        "examples/downstream",
        &[
            "prism-spectrum",
            "prism-upsample",
            "prism-sampling",
            "prism-scene",
            "prism-integrator",
        ],
    ),
    (
        "benches",
        &[
            "prism-spectrum",
            "prism-upsample",
            "prism-sampling",
            "prism-scene",
            "prism-integrator",
        ],
    ),
];

/// The `prism-*` names in the `[dependencies]` table of a manifest (dev-dependencies of a
/// test are not part of the library graph).
fn prism_dependencies(manifest: &str) -> BTreeSet<String> {
    let mut in_dependencies = false;
    let mut found = BTreeSet::new();
    for line in manifest.lines().map(str::trim) {
        if line.starts_with('[') {
            in_dependencies = line == "[dependencies]";
            continue;
        }
        let name = line.split(['.', '=', ' ']).next();
        if let (true, Some(name)) = (in_dependencies, name.filter(|n| n.starts_with("prism-"))) {
            found.insert(name.to_string());
        }
    }
    found
}

#[test]
fn crate_dependencies_follow_the_documented_dag() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let workspace = std::fs::read_to_string(format!("{root}/Cargo.toml")).unwrap();
    for (folder, allowed) in ALLOWED {
        assert!(
            workspace.contains(&format!("\"{folder}\"")),
            "{folder} is a workspace member"
        );
        let manifest = std::fs::read_to_string(format!("{root}/{folder}/Cargo.toml")).unwrap();
        let allowed: BTreeSet<String> = allowed.iter().map(|s| s.to_string()).collect();
        let actual = prism_dependencies(&manifest);
        let forbidden: Vec<_> = actual.difference(&allowed).collect();
        assert!(
            forbidden.is_empty(),
            "{folder} depends on {forbidden:?}, which ARCHITECTURE.md forbids"
        );
    }
    // The integrator never sees RGB.
    let integrator = std::fs::read_to_string(format!("{root}/integrator/Cargo.toml")).unwrap();
    assert!(!prism_dependencies(&integrator).contains("prism-upsample"));
}
