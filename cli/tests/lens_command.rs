//! `prism lens`: first-order properties of the repository's prescriptions, as a table and
//! as the JSON the independent checks read, and one-line errors.

mod common;

use common::{assert_one_line_errors, prism_ok};

fn lens(name: &str) -> String {
    format!("{}/../scenes/lenses/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn json(file: &str, extra: &[&str]) -> serde_json::Value {
    let path = lens(file);
    let run = prism_ok(&[&["lens", path.as_str(), "--json"], extra]);
    serde_json::from_slice(&run.stdout).unwrap()
}

#[test]
fn the_singlet_and_the_achromat_as_their_designs_say() {
    let singlet = json("singlet.dat", &[]);
    let waves = singlet["wavelengths"].as_array().unwrap();
    assert_eq!(waves.len(), 3);
    let efl = singlet["efl_mm"].as_array().unwrap();
    let d = efl[1].as_f64().unwrap();
    assert!((d - 97.41).abs() < 0.01, "{d}");
    // Blue focuses nearer than red.
    let bfd = singlet["bfd_mm"].as_array().unwrap();
    assert!(bfd[0].as_f64().unwrap() < bfd[2].as_f64().unwrap());
    let achromat = json("achromat.dat", &["--wavelengths", "486.1327,656.2725"]);
    let (s, a) = (
        singlet["longitudinal_chromatic_aberration_mm"]
            .as_f64()
            .unwrap(),
        achromat["longitudinal_chromatic_aberration_mm"]
            .as_f64()
            .unwrap(),
    );
    assert!(a * 10.0 < s, "achromat {a} mm, singlet {s} mm");
    let table = prism_ok(&[&["lens", lens("singlet.dat").as_str()]]);
    let text = String::from_utf8_lossy(&table.stdout);
    assert!(text.contains("EFL mm") && text.contains("587.56"), "{text}");
}

#[test]
fn bad_lens_files_are_one_line_errors() {
    let dir = common::temp_dir("lens-command");
    let bad = dir.join("bad.dat");
    std::fs::write(&bad, "100 4 1.5 30 bk7\n-100 nope 1 30\n").unwrap();
    let (bad, singlet) = (bad.to_str().unwrap().to_string(), lens("singlet.dat"));
    assert_one_line_errors(&[
        (&["lens", bad.as_str()], "line 2: thickness 'nope'"),
        (&["lens", "missing.dat"], "cannot read"),
        (
            &["lens", singlet.as_str(), "--wavelengths", "5,550"],
            "5 nm",
        ),
    ]);
}
