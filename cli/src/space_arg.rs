//! `--space` for upsampling: a named RGB colour space, or a user-defined one given by its
//! primaries and the illuminant whose white it uses.

use prism_spectrum::color::{RgbColorSpace, RgbSpaceId, TransferFunction};
use prism_spectrum::colorimetry::{Chromaticity, Observer, WhitePoint, emission_xyz};
use prism_spectrum::spectra::{NAMED_SPECTRUM_FORMS, NamedSpectrum};

/// The forms `--space` accepts, for errors (the names from [`RgbSpaceId::ALL`]).
fn space_forms() -> String {
    format!(
        "a name ({}) or primaries 'XR,YR,XG,YG,XB,YB@ILLUMINANT' (chromaticities of red, \
         green and blue; ILLUMINANT a named spectrum, default illuminant:D65)",
        RgbSpaceId::ALL.map(RgbSpaceId::name).join(", ")
    )
}

/// The colour space colours are fitted for, and the illuminant they are seen under.
pub struct SpaceChoice {
    /// The named space, if it is one (default tables exist only for those).
    pub id: Option<RgbSpaceId>,
    /// What to call it in output and in table files.
    pub name: String,
    pub space: RgbColorSpace,
    pub illuminant: Box<dyn prism_spectrum::Spectrum>,
}

/// Parses a named space or `XR,YR,XG,YG,XB,YB[@ILLUMINANT]`.
pub fn parse_space(text: &str) -> Result<SpaceChoice, String> {
    if !text.contains(',') {
        let id = RgbSpaceId::from_name(text).map_err(|e| e.to_string())?;
        return Ok(SpaceChoice {
            id: Some(id),
            name: id.name().to_string(),
            space: id.space().clone(),
            illuminant: Box::new(id.illuminant()),
        });
    }
    let malformed = |why: &str| format!("--space '{text}': {why} (expected {})", space_forms());
    let (primaries, illuminant) = text.split_once('@').unwrap_or((text, "illuminant:D65"));
    let numbers = primaries
        .split(',')
        .map(|p| p.trim().parse::<f64>())
        .collect::<Result<Vec<_>, _>>()
        .map_err(|_| malformed("the primaries must be six numbers"))?;
    let [xr, yr, xg, yg, xb, yb]: [f64; 6] = numbers
        .try_into()
        .map_err(|_| malformed("the primaries must be six numbers"))?;
    let illuminant = NamedSpectrum::parse(illuminant).map_err(|e| {
        format!("--space '{text}': the illuminant: {e} (named spectra: {NAMED_SPECTRUM_FORMS})")
    })?;
    let white = WhitePoint::from_xyz(emission_xyz(&illuminant, Observer::Cie1931))
        .map_err(|e| format!("--space '{text}': the illuminant has no white point: {e}"))?;
    let primaries = [(xr, yr), (xg, yg), (xb, yb)].map(|(x, y)| Chromaticity::new(x, y));
    let space = RgbColorSpace::new("custom", primaries, white.xy(), TransferFunction::Linear)
        .map_err(|e| format!("--space '{text}': {e}"))?;
    Ok(SpaceChoice {
        id: None,
        name: "custom".into(),
        space,
        illuminant: Box::new(illuminant),
    })
}
