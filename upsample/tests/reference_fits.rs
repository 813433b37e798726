//! prism's exact fits against an independent fitter: scipy's MINPACK Levenberg-Marquardt
//! on colour-science's colorimetry (`tools/reference_fits.py`,
//! `fixtures/reference_fits.json`). The objective's optimum is unique for reachable
//! colours, so the two fitted spectra must agree; coefficients are compared through the
//! spectra because nearly flat directions of the objective let coefficients differ more
//! than the colours they make.

use prism_spectrum::Spectrum;
use prism_spectrum::color::RgbSpaceId;
use prism_upsample::{FitContext, SigmoidPolynomial};

#[test]
fn fits_agree_with_an_independent_fitter() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/reference_fits.json"
    );
    let fixture: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let context =
        FitContext::new(RgbSpaceId::Srgb.space(), &RgbSpaceId::Srgb.illuminant()).unwrap();
    let fits = fixture["fits"].as_array().unwrap();
    assert_eq!(fits.len(), 40);
    let mut worst: f64 = 0.0;
    for entry in fits {
        let v = |key: &str| -> Vec<f64> {
            entry[key]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        };
        let rgb = v("rgb");
        let reference = SigmoidPolynomial {
            coefficients: v("coefficients_nm").try_into().unwrap(),
        };
        let ours = context.fit([rgb[0], rgb[1], rgb[2]], [0.0; 3]).spectrum;
        for l in (360..=830).map(f64::from) {
            let d = (ours.evaluate(l) - reference.evaluate(l)).abs();
            worst = worst.max(d);
            // Measured agreement is ~2e-8; 1e-6 leaves room for platform rounding only.
            assert!(
                d < 1e-6,
                "{rgb:?} at {l} nm: ours {} vs reference {}",
                ours.evaluate(l),
                reference.evaluate(l)
            );
        }
    }
    eprintln!("largest reflectance difference to the independent fitter: {worst:.2e}");
}
