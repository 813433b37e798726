//! The parser against scenes written here: a Cornell-box-like scene read whole, each
//! feature, each error (one line, with file:line), and arbitrary input (no panic).

use std::collections::HashMap;
use std::sync::Arc;

use proptest::prelude::*;

use super::*;

type Files = HashMap<String, String>;

fn parse_with(text: &str, files: &Files, defines: &[(&str, &str)]) -> Result<Parsed, LoadError> {
    let defines: Vec<(String, String)> = defines
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    let resolve = |name: &str| {
        files
            .get(name)
            .map(|t| t.as_bytes().to_vec())
            .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::NotFound, "no such file"))
    };
    parse(
        text,
        "scenes/main.xml",
        &ParseOptions {
            defines: &defines,
            resolve: &resolve,
        },
    )
}

fn ok(text: &str) -> Parsed {
    parse_with(text, &Files::new(), &[]).unwrap_or_else(|e| panic!("{e}"))
}

/// The error's text, checked to be one line starting with `file:line: `.
fn err_with(text: &str, files: &Files, defines: &[(&str, &str)], at: &str) -> String {
    let e = match parse_with(text, files, defines) {
        Ok(_) => panic!("parsed, expected an error at {at}: {text}"),
        Err(e) => e,
    };
    assert!(matches!(e, LoadError::Mitsuba { .. }), "{e:?}");
    let message = e.to_string();
    assert!(!message.contains('\n'), "{message}");
    assert!(
        message.starts_with(&format!("{at}: ")),
        "{message} (expected at {at})"
    );
    message
}

fn err(text: &str, at: &str) -> String {
    err_with(text, &Files::new(), &[], at)
}

fn value<'a>(object: &'a Object, name: &str) -> &'a Value {
    &object
        .property(name)
        .unwrap_or_else(|| panic!("no property {name}"))
        .value
}

fn matrix(object: &Object, name: &str) -> [[f64; 4]; 4] {
    match value(object, name) {
        Value::Transform(m) => *m,
        other => panic!("{other:?}"),
    }
}

fn apply(m: &[[f64; 4]; 4], p: [f64; 4]) -> [f64; 3] {
    let row = |i: usize| (0..4).map(|k| m[i][k] * p[k]).sum::<f64>();
    [row(0), row(1), row(2)]
}

fn assert_close(a: [f64; 3], b: [f64; 3]) {
    assert!(
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9),
        "{a:?} != {b:?}"
    );
}

const CORNELL: &str = r#"<?xml version="1.0" encoding="utf-8"?>
<!-- A Cornell box, more or less -->
<scene version="3.0.0">
    <default name="spp" value="64"/>
    <default name="res" value="256"/>
    <integrator type="path">
        <integer name="max_depth" value="8"/>
    </integrator>
    <sensor type="perspective">
        <float name="fov" value="39.3077"/>
        <transform name="to_world">
            <lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="$spp"/>
        </sampler>
        <film type="hdrfilm">
            <integer name="width" value="$res"/>
            <integer name="height" value="$res"/>
            <rfilter type="gaussian"/>
        </film>
    </sensor>
    <bsdf type="diffuse" id="white">
        <rgb name="reflectance" value="0.885809, 0.698859, 0.666422"/>
    </bsdf>
    <bsdf type="diffuse" id="red">
        <rgb name="reflectance" value="0.570068 0.0430135 0.0443706"/>
    </bsdf>
    <shape type="rectangle" id="floor">
        <transform name="to_world">
            <translate x="1" y="2" z="3"/>
            <rotate y="1" angle="90"/>
        </transform>
        <ref id="white"/>
    </shape>
    <shape type="rectangle">
        <ref name="bsdf" id="red"/>
        <boolean name="flip_normals" value="true"/>
    </shape>
    <shape type="rectangle">
        <ref id="white"/>
        <emitter type="area">
            <rgb name="radiance" value="18.387, 13.9873, 6.75357"/>
        </emitter>
    </shape>
    <shape type="sphere">
        <point name="center" value="0.1, 0.2, 0.3"/>
        <float name="radius" value=" 1e-1 "/>
        <bsdf type="dielectric">
            <string name="int_ior" value="bk7"/>
        </bsdf>
    </shape>
</scene>
"#;

#[test]
fn cornell_box_tree() {
    let parsed = ok(CORNELL);
    assert!(parsed.warnings.is_empty(), "{:?}", parsed.warnings);
    let scene = &parsed.scene;
    assert_eq!(scene.class, Class::Scene);
    assert_eq!(scene.kind, "scene");
    assert_eq!(scene.at.line, 3);
    let classes: Vec<Class> = scene.children.iter().map(|c| c.object.class).collect();
    assert_eq!(
        classes,
        [
            Class::Integrator,
            Class::Sensor,
            Class::Bsdf,
            Class::Bsdf,
            Class::Shape,
            Class::Shape,
            Class::Shape,
            Class::Shape
        ]
    );

    let sensor = &scene.children[1].object;
    assert_eq!(sensor.kind, "perspective");
    assert_eq!(value(sensor, "fov"), &Value::Float(39.3077));
    let sampler = sensor.children_of(Class::Sampler).next().unwrap();
    assert_eq!(value(&sampler.object, "sample_count"), &Value::Integer(64));
    let film = &sensor.children_of(Class::Film).next().unwrap().object;
    assert_eq!(value(film, "width"), &Value::Integer(256));
    assert_eq!(film.children[0].object.class, Class::Rfilter);
    assert_eq!(
        film.at,
        Location {
            file: "scenes/main.xml".into(),
            line: 17
        }
    );

    // References share the object defined once.
    let white = &scene.children[2].object;
    assert_eq!(white.id.as_deref(), Some("white"));
    let floor = &scene.children[4].object;
    assert_eq!(floor.id.as_deref(), Some("floor"));
    assert!(Arc::ptr_eq(&floor.children[0].object, white));
    assert_eq!(floor.children[0].name, None);
    let third = &scene.children[6].object;
    assert!(Arc::ptr_eq(&third.children[0].object, white));
    assert_eq!(third.children[1].object.class, Class::Emitter);
    assert_eq!(
        value(&third.children[1].object, "radiance"),
        &Value::Rgb([18.387, 13.9873, 6.75357])
    );
    let second = &scene.children[5].object;
    assert_eq!(second.children[0].name.as_deref(), Some("bsdf"));
    assert_eq!(second.children[0].object.id.as_deref(), Some("red"));
    assert_eq!(value(second, "flip_normals"), &Value::Boolean(true));
    let red = &scene.children[3].object;
    assert_eq!(
        value(red, "reflectance"),
        &Value::Rgb([0.570068, 0.0430135, 0.0443706])
    );
    let sphere = &scene.children[7].object;
    assert_eq!(value(sphere, "center"), &Value::Point([0.1, 0.2, 0.3]));
    assert_eq!(value(sphere, "radius"), &Value::Float(0.1));
    assert_eq!(
        value(&sphere.children[0].object, "int_ior"),
        &Value::String("bk7".into())
    );
}

#[test]
fn transforms_compose_each_operation_from_the_left() {
    let parsed = ok(CORNELL);
    let floor = &parsed.scene.children[4].object;
    let m = matrix(floor, "to_world");
    // Translate by (1, 2, 3), then rotate 90 degrees about +y: M = R * T. R takes
    // (x, y, z) to (z, y, -x), so the origin goes to R(1, 2, 3) = (3, 2, -1).
    assert_close(apply(&m, [0.0, 0.0, 0.0, 1.0]), [3.0, 2.0, -1.0]);
    // A direction ignores the translation: +x goes to -z.
    assert_close(apply(&m, [1.0, 0.0, 0.0, 0.0]), [0.0, 0.0, -1.0]);
    let expected = [
        [0.0, 0.0, 1.0, 3.0],
        [0.0, 1.0, 0.0, 2.0],
        [-1.0, 0.0, 0.0, -1.0],
        [0.0, 0.0, 0.0, 1.0],
    ];
    for (row, want) in m.iter().zip(expected) {
        assert_close([row[0], row[1], row[2]], [want[0], want[1], want[2]]);
        assert!((row[3] - want[3]).abs() < 1e-9, "{m:?}");
    }

    // The other order: rotate first, then translate: the origin stays at (1, 2, 3).
    let parsed = ok(r#"<scene version="3.0.0"><shape type="cube">
        <transform name="to_world">
            <rotate value="0 1 0" angle="90"/>
            <scale value="2"/>
            <translate value="1, 2, 3"/>
        </transform></shape></scene>"#);
    let m = matrix(&parsed.scene.children[0].object, "to_world");
    assert_close(apply(&m, [0.0, 0.0, 0.0, 1.0]), [1.0, 2.0, 3.0]);
    // +x: rotated to -z, scaled by 2, then moved: (1, 2, 3) + (0, 0, -2).
    assert_close(apply(&m, [1.0, 0.0, 0.0, 1.0]), [1.0, 2.0, 1.0]);
}

#[test]
fn lookat_camera_looks_along_local_z() {
    let parsed = ok(CORNELL);
    let m = matrix(&parsed.scene.children[1].object, "to_world");
    // Mitsuba's look_at: columns left, up, dir, origin.
    assert_close(apply(&m, [0.0, 0.0, 0.0, 1.0]), [0.0, 0.0, 5.0]);
    assert_close(apply(&m, [0.0, 0.0, 1.0, 0.0]), [0.0, 0.0, -1.0]);
    assert_close(apply(&m, [0.0, 1.0, 0.0, 0.0]), [0.0, 1.0, 0.0]);
    // left = up x dir = (0, 1, 0) x (0, 0, -1) = (-1, 0, 0).
    assert_close(apply(&m, [1.0, 0.0, 0.0, 0.0]), [-1.0, 0.0, 0.0]);
}

#[test]
fn matrix_is_row_major_and_three_by_three_fills_in() {
    let parsed = ok(r#"<scene version="3.0.0"><shape type="cube">
        <transform name="a"><matrix value="1 0 0 7  0 1 0 8  0 0 1 9  0 0 0 1"/></transform>
        <transform name="b"><matrix value="0 -1 0, 1 0 0, 0 0 1"/></transform>
        </shape></scene>"#);
    let shape = &parsed.scene.children[0].object;
    assert_close(
        apply(&matrix(shape, "a"), [0.0, 0.0, 0.0, 1.0]),
        [7.0, 8.0, 9.0],
    );
    let b = matrix(shape, "b");
    assert_close(apply(&b, [1.0, 0.0, 0.0, 1.0]), [0.0, 1.0, 0.0]);
    assert_eq!(b[3], [0.0, 0.0, 0.0, 1.0]);
}

#[test]
fn defines_override_defaults_and_substitute_everywhere() {
    let text = r#"<scene version="3.0.0">
        <default name="material" value="diffuse"/>
        <default name="r" value="0.5"/>
        <default name="rr" value="0.25"/>
        <bsdf type="$material" id="m_$material">
            <rgb name="reflectance" value="$r, $rr, $r"/>
        </bsdf>
    </scene>"#;
    let parsed = ok(text);
    let bsdf = &parsed.scene.children[0].object;
    assert_eq!(bsdf.kind, "diffuse");
    assert_eq!(bsdf.id.as_deref(), Some("m_diffuse"));
    // `$rr` is the longer name, not `$r` followed by "r".
    assert_eq!(value(bsdf, "reflectance"), &Value::Rgb([0.5, 0.25, 0.5]));

    let parsed = parse_with(
        text,
        &Files::new(),
        &[("material", "conductor"), ("r", "1")],
    )
    .unwrap();
    let bsdf = &parsed.scene.children[0].object;
    assert_eq!(bsdf.kind, "conductor");
    assert_eq!(value(bsdf, "reflectance"), &Value::Rgb([1.0, 0.25, 1.0]));
}

#[test]
fn includes_splice_scene_children_in_place() {
    let mut files = Files::new();
    files.insert(
        "scenes/parts/materials.xml".into(),
        r#"<scene version="3.0.0">
            <bsdf type="diffuse" id="grey"/>
            <include filename="more.xml"/>
        </scene>"#
            .into(),
    );
    files.insert(
        "scenes/parts/more.xml".into(),
        r#"<bsdf type="conductor" id="metal"/>"#.into(),
    );
    let text = r#"<scene version="3.0.0">
        <shape type="sphere"/>
        <include filename="parts/materials.xml"/>
        <shape type="cube"><ref id="metal"/><ref id="grey"/></shape>
    </scene>"#;
    let parsed = parse_with(text, &files, &[]).unwrap();
    let kinds: Vec<&str> = parsed
        .scene
        .children
        .iter()
        .map(|c| c.object.kind.as_str())
        .collect();
    assert_eq!(kinds, ["sphere", "diffuse", "conductor", "cube"]);
    let grey = &parsed.scene.children[1].object;
    assert_eq!(
        grey.at,
        Location {
            file: "scenes/parts/materials.xml".into(),
            line: 2
        }
    );
    let cube = &parsed.scene.children[3].object;
    assert!(Arc::ptr_eq(&cube.children[1].object, grey));
    assert_eq!(cube.children[0].object.id.as_deref(), Some("metal"));
}

#[test]
fn path_adds_a_search_directory() {
    let mut files = Files::new();
    files.insert(
        "scenes/lib/glass.xml".into(),
        r#"<bsdf type="dielectric"/>"#.into(),
    );
    let parsed = parse_with(
        r#"<scene version="3.0.0"><path value="lib"/><include filename="glass.xml"/></scene>"#,
        &files,
        &[],
    )
    .unwrap();
    assert_eq!(parsed.scene.children[0].object.kind, "dielectric");
}

#[test]
fn references_may_come_before_the_definition() {
    let parsed = ok(r#"<scene version="3.0.0">
        <shape type="sphere"><ref name="bsdf" id="later"/></shape>
        <bsdf type="diffuse" id="later"/>
        <alias id="later" as="other"/>
        <shape type="cube"><ref id="other"/></shape>
    </scene>"#);
    let sphere = &parsed.scene.children[0].object;
    assert_eq!(sphere.children[0].object.kind, "diffuse");
    let cube = &parsed.scene.children[2].object;
    assert!(Arc::ptr_eq(
        &cube.children[0].object,
        &sphere.children[0].object
    ));
}

#[test]
fn spectrum_forms() {
    let mut files = Files::new();
    files.insert(
        "scenes/data/gold.spd".into(),
        "# gold\n400 0.1\n500 0.2\n\n600 0.9\n".into(),
    );
    let parsed = parse_with(
        r#"<scene version="3.0.0"><bsdf type="conductor">
            <spectrum name="a" value="0.5"/>
            <spectrum name="b" value="400:0.1, 500:0.2"/>
            <spectrum name="c" filename="data/gold.spd"/>
            <spectrum name="d" type="blackbody"><float name="temperature" value="6500"/></spectrum>
            <rgb name="e" value="0.25"/>
        </bsdf></scene>"#,
        &files,
        &[],
    )
    .unwrap();
    let bsdf = &parsed.scene.children[0].object;
    assert_eq!(
        value(bsdf, "a"),
        &Value::Spectrum(SpectrumValue::Constant(0.5))
    );
    assert_eq!(
        value(bsdf, "b"),
        &Value::Spectrum(SpectrumValue::Samples(vec![(400.0, 0.1), (500.0, 0.2)]))
    );
    assert_eq!(
        value(bsdf, "c"),
        &Value::Spectrum(SpectrumValue::Samples(vec![
            (400.0, 0.1),
            (500.0, 0.2),
            (600.0, 0.9)
        ]))
    );
    let d = bsdf.child("d").unwrap();
    assert_eq!(d.object.class, Class::Spectrum);
    assert_eq!(d.object.kind, "blackbody");
    assert_eq!(value(&d.object, "temperature"), &Value::Float(6500.0));
    assert_eq!(value(bsdf, "e"), &Value::Rgb([0.25; 3]));
}

#[test]
fn old_versions_warn_new_ones_do_not() {
    assert!(ok(r#"<scene version="2.1.0"/>"#).warnings.is_empty());
    let parsed = ok("<scene version=\"0.6.0\">\n<shape type=\"sphere\"/></scene>");
    assert_eq!(parsed.warnings.len(), 1);
    assert!(
        parsed.warnings[0].starts_with("scenes/main.xml:1: "),
        "{:?}",
        parsed.warnings
    );
}

#[test]
fn include_cycle_is_reported_with_the_chain() {
    let mut files = Files::new();
    files.insert(
        "scenes/a.xml".into(),
        "<scene version=\"3.0.0\">\n<include filename=\"b.xml\"/></scene>".into(),
    );
    files.insert(
        "scenes/b.xml".into(),
        "<scene version=\"3.0.0\">\n\n<include filename=\"a.xml\"/></scene>".into(),
    );
    let text = "<scene version=\"3.0.0\">\n<include filename=\"a.xml\"/></scene>";
    let message = err_with(text, &files, &[], "scenes/b.xml:3");
    assert!(
        message.ends_with(
            "include cycle: scenes/main.xml -> scenes/a.xml -> scenes/b.xml -> scenes/a.xml"
        ),
        "{message}"
    );
}

#[test]
fn include_depth_is_limited() {
    let mut files = Files::new();
    for i in 0..40 {
        files.insert(
            format!("scenes/d{i}.xml"),
            format!(
                "<scene version=\"3.0.0\"><include filename=\"d{}.xml\"/></scene>",
                i + 1
            ),
        );
    }
    let message = err_with(
        r#"<scene version="3.0.0"><include filename="d0.xml"/></scene>"#,
        &files,
        &[],
        "scenes/d15.xml:1",
    );
    assert!(message.contains("deeper than 16"), "{message}");
}

#[test]
fn every_error_names_file_and_line() {
    let head = "<scene version=\"3.0.0\">\n";
    let at2 = "scenes/main.xml:2";
    let cases: &[(&str, &str, &str)] = &[
        (
            "<scene version=\"3.0.0\">\n<shape type=\"x\">\n</scene>",
            "scenes/main.xml:3",
            "malformed XML",
        ),
        ("<shape type=\"x\"/>", "scenes/main.xml:1", "root element"),
        ("<scene>\n</scene>", "scenes/main.xml:1", "missing version"),
        (
            "<scene version=\"three\"/>",
            "scenes/main.xml:1",
            "version number",
        ),
        ("<blob/>", at2, "unexpected tag <blob>"),
        (
            "<color name=\"a\" value=\"1\"/>",
            at2,
            "unexpected tag <color>",
        ),
        ("<shape id=\"s\"/>", at2, "missing attribute \"type\""),
        (
            "<shape type=\"a\"><float value=\"1\"/></shape>",
            at2,
            "missing attribute \"name\"",
        ),
        (
            "<shape type=\"a\"><float name=\"f\"/></shape>",
            at2,
            "missing attribute \"value\"",
        ),
        (
            "<shape type=\"a\"><float name=\"f\" value=\"abc\"/></shape>",
            at2,
            "abc",
        ),
        (
            "<shape type=\"a\"><integer name=\"f\" value=\"1.5\"/></shape>",
            at2,
            "integer",
        ),
        (
            "<shape type=\"a\"><boolean name=\"f\" value=\"yes\"/></shape>",
            at2,
            "boolean",
        ),
        (
            "<shape type=\"a\"><point name=\"p\" value=\"1 2\"/></shape>",
            at2,
            "1 or 3",
        ),
        (
            "<shape type=\"a\"><rgb name=\"p\" value=\"1 2 x\"/></shape>",
            at2,
            "\"x\"",
        ),
        (
            "<shape type=\"a\"><spectrum name=\"s\" value=\"400:1, 300:2\"/></shape>",
            at2,
            "increasing",
        ),
        (
            "<shape type=\"a\"><spectrum name=\"s\" filename=\"none.spd\"/></shape>",
            at2,
            "scenes/none.spd",
        ),
        ("<shape type=\"$nope\"/>", at2, "$nope"),
        (
            "<shape type=\"a\"><ref id=\"missing\"/></shape>",
            at2,
            "unknown object \"missing\"",
        ),
        (
            "<bsdf type=\"a\" id=\"x\"/>\n<bsdf type=\"b\" id=\"x\"/>",
            "scenes/main.xml:3",
            "duplicate id \"x\" (previous was at scenes/main.xml:2)",
        ),
        (
            "<bsdf type=\"a\" id=\"x\"><bsdf type=\"b\" id=\"x\"/></bsdf>",
            at2,
            "duplicate id",
        ),
        (
            "<bsdf type=\"a\" id=\"x\"><ref id=\"x\"/></bsdf>",
            at2,
            "cycle",
        ),
        (
            "<include filename=\"missing.xml\"/>",
            at2,
            "scenes/missing.xml",
        ),
        (
            "<shape type=\"a\"><translate x=\"1\"/></shape>",
            at2,
            "only occur in a <transform>",
        ),
        (
            "<shape type=\"a\"><transform name=\"t\"><float name=\"f\" value=\"1\"/></transform></shape>",
            at2,
            "transform operations",
        ),
        (
            "<shape type=\"a\"><transform name=\"t\"><rotate x=\"1\"/></transform></shape>",
            at2,
            "\"angle\"",
        ),
        (
            "<shape type=\"a\"><transform name=\"t\"><rotate angle=\"3\"/></transform></shape>",
            at2,
            "axis is zero",
        ),
        (
            "<shape type=\"a\"><transform name=\"t\"><matrix value=\"1 2 3\"/></transform></shape>",
            at2,
            "16 or 9",
        ),
        (
            "<shape type=\"a\"><transform name=\"t\"><lookat origin=\"0 0 0\" target=\"0 0 0\"/></transform></shape>",
            at2,
            "lookat",
        ),
        (
            "<shape type=\"a\" colour=\"red\"/>",
            at2,
            "unexpected attribute \"colour\"",
        ),
        (
            "<shape type=\"a\"><float name=\"f\" value=\"1\"><float name=\"g\" value=\"1\"/></float></shape>",
            at2,
            "cannot occur as a child",
        ),
        ("<shape type=\"a\">text</shape>", at2, "unexpected text"),
        (
            "<shape type=\"a\"><path value=\"x\"/></shape>",
            at2,
            "<path>",
        ),
        ("<bsdf type=\"a\"><scene/></bsdf>", at2, "only be the root"),
    ];
    for (body, at, needle) in cases {
        let text = if body.starts_with("<scene") || body.starts_with("<shape type=\"x\"/>") {
            body.to_string()
        } else {
            format!("{head}{body}\n</scene>")
        };
        let message = err(&text, at);
        assert!(
            message.contains(needle),
            "{message} (expected \"{needle}\")"
        );
    }
}

const VALID: &str = r#"<scene version="3.0.0">
<default name="x" value="1"/>
<bsdf type="diffuse" id="b"><rgb name="reflectance" value="0.5, $x, 0.5"/></bsdf>
<shape type="obj"><string name="filename" value="a.obj"/><ref id="b"/>
<transform name="to_world"><translate value="1 2 3"/><rotate y="1" angle="45"/><lookat origin="0,0,1" target="0,0,0"/></transform></shape>
<include filename="inc.xml"/>
<emitter type="point"><spectrum name="intensity" value="400:1 500:2"/></emitter>
</scene>"#;

fn files_for_fuzz() -> Files {
    let mut files = Files::new();
    files.insert(
        "scenes/inc.xml".into(),
        r#"<scene version="3.0.0"><bsdf type="x" id="y"/></scene>"#.into(),
    );
    files
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn arbitrary_text_never_panics(text in ".{0,300}") {
        let _ = parse_with(&text, &files_for_fuzz(), &[]);
    }

    #[test]
    fn mutated_scenes_never_panic(
        edits in proptest::collection::vec((0usize..VALID.len(), 0usize..8, "[<>/=\"$:,. a-z0-9#-]{0,4}"), 1..6)
    ) {
        let mut text = VALID.to_string();
        for (at, cut, insert) in edits {
            let mut start = at.min(text.len());
            while !text.is_char_boundary(start) {
                start -= 1;
            }
            let mut end = (start + cut).min(text.len());
            while !text.is_char_boundary(end) {
                end -= 1;
            }
            text.replace_range(start..end, &insert);
        }
        let _ = parse_with(&text, &files_for_fuzz(), &[("x", "$x")]);
    }
}

#[test]
fn the_valid_fuzz_seed_parses() {
    let parsed = parse_with(VALID, &files_for_fuzz(), &[]).unwrap();
    assert_eq!(parsed.scene.children.len(), 4);
}

#[test]
fn deep_nesting_is_an_error_not_a_stack_overflow() {
    let depth = 5000;
    let text = format!(
        "<scene version=\"3.0.0\">{}{}</scene>",
        "<bsdf type=\"a\">".repeat(depth),
        "</bsdf>".repeat(depth)
    );
    let message = err(&text, "scenes/main.xml:1");
    assert!(message.contains("nested deeper"), "{message}");
    // Just inside the limit parses.
    let depth = 190;
    let text = format!(
        "<scene version=\"3.0.0\">{}{}</scene>",
        "<bsdf type=\"a\">".repeat(depth),
        "</bsdf>".repeat(depth)
    );
    ok(&text);
}
