//! End-to-end tests of `prism info`.

mod common;

use common::{assert_one_line_errors, prism};

#[test]
fn describes_the_canonical_scenes() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes");
    let out = prism(&["info", &format!("{dir}/cornell-bunny.gltf")]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("triangles      69463"), "{text}");
    assert!(
        text.contains("area lights    1 instances, 2 triangles"),
        "{text}"
    );
    assert!(text.contains("cameras        camera"), "{text}");
    let out = prism(&["info", &format!("{dir}/cornell-box.gltf")]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("materials      4"));
}

#[test]
fn bad_scenes_are_one_clear_line() {
    let readme = concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md");
    let bunny = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-bunny.gltf");
    assert_one_line_errors(&[
        (&["info", "/no/such/scene.gltf"], "cannot read"),
        (&["info", readme], "invalid glTF"),
        (&["info", bunny, "--scene-index", "7"], "no scene 7"),
        (&["info"], "required"),
    ]);
}
