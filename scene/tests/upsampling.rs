//! The upsampling modes a load can use: exact fits, table lookups, refined lookups.

use prism_scene::load::{LoadOptions, LoadedGeometry, Upsampling, load_scene};
use prism_spectrum::Spectrum;

fn cornell(upsampling: Upsampling) -> LoadedGeometry {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let bytes = std::fs::read(dir.join("cornell-box.gltf")).unwrap();
    load_scene(
        &bytes,
        &move |uri| std::fs::read(dir.join(uri)),
        &LoadOptions::default().upsampling(upsampling),
    )
    .unwrap()
}

#[test]
fn table_and_refined_lookups_approach_the_exact_fit() {
    let exact = cornell(Upsampling::Exact);
    let table = cornell(Upsampling::Table(16));
    let refined = cornell(Upsampling::Refined(16));
    // The red wall: coloured, so a table lookup differs from the fit, slightly; a refining
    // step brings it closer.
    let red = |g: &LoadedGeometry| {
        g.materials
            .iter()
            .find(|m| m.name == "red")
            .unwrap()
            .base_color
            .clone()
    };
    let (e, t, r) = (red(&exact), red(&table), red(&refined));
    let distance = |a: &dyn Spectrum, b: &dyn Spectrum| {
        (400..=700)
            .step_by(10)
            .map(|nm| (a.evaluate(f64::from(nm)) - b.evaluate(f64::from(nm))).abs())
            .fold(0.0, f64::max)
    };
    let (dt, dr) = (distance(&t, &e), distance(&r, &e));
    assert!(dt > 0.0 && dt < 0.05, "table lookup differs by {dt}");
    assert!(dr <= dt, "refined {dr} vs table {dt}");
    // Emission goes through the same mode and stays close.
    let light = |g: &LoadedGeometry| g.materials[0].emission.clone().unwrap();
    let (le, lt) = (light(&exact), light(&table));
    assert!((le.evaluate(550.0) - lt.evaluate(550.0)).abs() < 0.02 * le.evaluate(550.0));
}

#[test]
fn mode_names() {
    for mode in [
        Upsampling::Exact,
        Upsampling::Table(64),
        Upsampling::Refined(32),
    ] {
        assert_eq!(Upsampling::from_name(&mode.name()).unwrap(), mode);
    }
    for bad in ["table", "table17", "refined", "fast", ""] {
        assert!(
            Upsampling::from_name(bad)
                .unwrap_err()
                .to_string()
                .contains("table16"),
            "{bad}"
        );
    }
}

fn vertex_colors(options: &LoadOptions) -> Result<LoadedGeometry, prism_scene::load::LoadError> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/assets");
    let bytes = std::fs::read(dir.join("vertex-colors.gltf")).unwrap();
    load_scene(&bytes, &move |uri| std::fs::read(dir.join(uri)), options)
}

#[test]
fn tables_come_from_the_caller_else_the_crate_and_are_never_fitted_when_one_is_there() {
    use prism_spectrum::color::RgbSpaceId;
    use prism_upsample::{CoefficientTable, FitContext};
    use std::sync::Arc;

    let shipped = CoefficientTable::shipped(RgbSpaceId::Srgb).unwrap();
    let loaded = vertex_colors(&LoadOptions::default()).unwrap();
    assert!(Arc::ptr_eq(loaded.color_table.as_ref().unwrap(), &shipped));

    let srgb = RgbSpaceId::Srgb;
    let context = FitContext::new(srgb.space(), &srgb.illuminant()).unwrap();
    let (mine, _) = CoefficientTable::fit(&context, 8, &|_| {}).unwrap();
    let mine = Arc::new(mine);
    let loaded = vertex_colors(&LoadOptions::default().table(Some(mine.clone()))).unwrap();
    assert!(Arc::ptr_eq(loaded.color_table.as_ref().unwrap(), &mine));

    // A table of another resolution than the mode names, or of another space, is refused.
    let wrong_size = LoadOptions::default()
        .table(Some(mine.clone()))
        .upsampling(Upsampling::Table(16));
    let message = vertex_colors(&wrong_size).unwrap_err().to_string();
    assert!(
        message.contains("8^3") && message.contains("table16"),
        "{message}"
    );
    let p3 = RgbSpaceId::DisplayP3;
    let p3_context = FitContext::new(p3.space(), &p3.illuminant()).unwrap();
    let (other, _) = CoefficientTable::fit(&p3_context, 4, &|_| {}).unwrap();
    let message = vertex_colors(&LoadOptions::default().table(Some(Arc::new(other))))
        .unwrap_err()
        .to_string();
    assert!(message.contains("not linear sRGB"), "{message}");
}
