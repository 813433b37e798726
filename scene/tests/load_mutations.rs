//! Malformed scenes are errors, never panics: the repository's scenes with random values
//! replaced (indices, counts, offsets, factors, spectral descriptions; extreme numbers,
//! wrong types, missing entries) and random words of their binary buffers overwritten
//! (non-finite, huge and subnormal coordinates) either load into a scene or fail with an
//! error. Mutating the scenes this way found two panics in the gltf crate's reader and
//! validation and one in the BVH build, which these cases keep found.

use prism_scene::load::load_geometry;
use prism_scene::world::{Scene, SceneOptions};
use proptest::prelude::*;
use serde_json::{Value, json};

fn scenes_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

/// Every value's path in `doc` (object keys and array indices), root excluded.
fn paths(doc: &Value) -> Vec<Vec<PathStep>> {
    fn walk(v: &Value, at: &mut Vec<PathStep>, out: &mut Vec<Vec<PathStep>>) {
        match v {
            Value::Object(map) => {
                for (k, x) in map {
                    at.push(PathStep::Key(k.clone()));
                    out.push(at.clone());
                    walk(x, at, out);
                    at.pop();
                }
            }
            Value::Array(items) => {
                for (i, x) in items.iter().enumerate() {
                    at.push(PathStep::Index(i));
                    out.push(at.clone());
                    walk(x, at, out);
                    at.pop();
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(doc, &mut Vec::new(), &mut out);
    out
}

#[derive(Debug, Clone)]
enum PathStep {
    Key(String),
    Index(usize),
}

fn at<'a>(doc: &'a mut Value, path: &[PathStep]) -> Option<&'a mut Value> {
    path.iter().try_fold(doc, |v, step| match step {
        PathStep::Key(k) => v.get_mut(k.as_str()),
        PathStep::Index(i) => v.get_mut(*i),
    })
}

/// Replacement values: indices just past the ends, huge and tiny numbers, wrong types.
fn replacement() -> impl Strategy<Value = Value> {
    prop_oneof![
        (0u64..40).prop_map(|i| json!(i)),
        prop::sample::select(vec![
            json!(0),
            json!(-1),
            json!(4294967295u64),
            json!(1u64 << 62),
            json!(0.0),
            json!(-0.0),
            json!(1e-45),
            json!(1e-39),
            json!(3e38),
            json!(-3e38),
            json!(1e300),
            json!(0.5),
            json!(""),
            json!("blackbody:0"),
            json!("gaussian:550:0"),
            json!("csv:missing.csv"),
            json!([]),
            json!([[700, 1], [400, 2]]),
            json!({}),
            json!(null),
        ]),
    ]
}

/// A 32-bit word for the binary buffer: extreme and non-finite floats, huge indices.
fn word() -> impl Strategy<Value = u32> {
    prop_oneof![
        prop::sample::select(vec![
            f32::NAN.to_bits(),
            f32::INFINITY.to_bits(),
            3e38f32.to_bits(),
            (-3e38f32).to_bits(),
            1e-40f32.to_bits(),
            0,
            u32::MAX,
            1 << 31,
        ]),
        any::<u32>(),
    ]
}

fn load_and_build(doc: &Value, bin: Vec<u8>) {
    let text = serde_json::to_vec(doc).unwrap();
    if let Ok(loaded) = load_geometry(&text, &move |_| Ok(bin.clone()), None) {
        let _ = Scene::from_loaded(loaded, &SceneOptions::default());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1024))]
    #[test]
    fn mutated_scenes_load_or_fail_cleanly(
        spectral in any::<bool>(),
        edits in prop::collection::vec((any::<prop::sample::Index>(), replacement()), 1..4),
        deletions in prop::collection::vec(any::<prop::sample::Index>(), 0..2),
        words in prop::collection::vec((any::<prop::sample::Index>(), word()), 0..6),
    ) {
        let name = if spectral { "cornell-spectral.gltf" } else { "cornell-box.gltf" };
        let dir = scenes_dir();
        let mut doc: Value =
            serde_json::from_slice(&std::fs::read(dir.join(name)).unwrap()).unwrap();
        let mut bin = std::fs::read(dir.join("cornell-box.bin")).unwrap();
        let all = paths(&doc);
        for (index, value) in edits {
            if let Some(slot) = at(&mut doc, &all[index.index(all.len())]) {
                *slot = value;
            }
        }
        for index in deletions {
            let path = &all[index.index(all.len())];
            let (last, parent) = path.split_last().unwrap();
            if let (PathStep::Key(k), Some(Value::Object(map))) = (last, at(&mut doc, parent)) {
                map.remove(k);
            }
        }
        for (index, w) in words {
            let i = index.index(bin.len() / 4) * 4;
            bin[i..i + 4].copy_from_slice(&w.to_le_bytes());
        }
        load_and_build(&doc, bin);
    }
}
