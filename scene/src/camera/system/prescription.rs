//! Lens prescriptions in pbrt-v4's lens file format (`RealisticCamera`, *PBR* 4th ed.
//! §5.3): one interface per line from the object's side to the film's, four numbers in
//! millimetres: the surface's radius of curvature (positive: its centre towards the
//! film; 0: the aperture stop, a plane), the distance along the axis to the next
//! interface (for the last, to the film), the index of refraction of the medium behind it
//! (towards the film; 0 or 1 is air), and the interface's clear aperture diameter. `#`
//! starts a comment. prism reads an optional fifth column naming the medium's glass: a
//! glass of the scene format's catalogue (`bk7`, `sf11`, ...) or `ND:VD` (an index at the
//! d line and an Abbe number, by `KHR_materials_dispersion`'s model), which then replaces
//! the third column's single index by the glass's dispersion.

use prism_spectrum::optics::{Cauchy, named_glass};

use super::{Interface, LensSystem, Medium};

/// Parses a prescription. Every malformed line is an error naming its line number.
pub fn parse_prescription(text: &str) -> Result<LensSystem, String> {
    let mut interfaces = Vec::new();
    for (n, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let at = |e: String| format!("line {}: {e}", n + 1);
        let fields: Vec<&str> = line.split_whitespace().collect();
        if !(4..=5).contains(&fields.len()) {
            return Err(at(format!(
                "{} columns (radius, thickness, index, aperture diameter in mm, and optionally a glass)",
                fields.len()
            )));
        }
        let number = |i: usize, what: &str| -> Result<f64, String> {
            fields[i]
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| at(format!("{what} '{}' is not a finite number", fields[i])))
        };
        let radius = number(0, "radius")?;
        let thickness = number(1, "thickness")?;
        let index = number(2, "index")?;
        let diameter = number(3, "aperture diameter")?;
        if thickness < 0.0 {
            return Err(at(format!("thickness {thickness} is negative")));
        }
        if diameter <= 0.0 {
            return Err(at(format!("aperture diameter {diameter} must be > 0")));
        }
        if radius != 0.0 && radius.abs() < 0.5 * diameter {
            return Err(at(format!(
                "a surface of radius {radius} cannot be {diameter} wide"
            )));
        }
        let medium = match fields.get(4) {
            Some(glass) => glass_medium(glass).map_err(at)?,
            None if index == 0.0 || index == 1.0 => Medium::Air,
            None if index > 1.0 => Medium::Index(index),
            None => return Err(at(format!("index {index} (0 or 1 is air, glass > 1)"))),
        };
        if radius == 0.0 && !matches!(medium, Medium::Air) {
            return Err(at("the aperture stop (radius 0) must be in air".into()));
        }
        interfaces.push(Interface {
            radius,
            thickness,
            medium,
            aperture_radius: 0.5 * diameter,
        });
    }
    LensSystem::new(interfaces)
}

/// The medium a glass name or `ND:VD` names.
fn glass_medium(name: &str) -> Result<Medium, String> {
    if let Some((nd, vd)) = name.split_once(':') {
        let parse = |s: &str| s.parse::<f64>().ok().filter(|v| v.is_finite());
        let (Some(nd), Some(vd)) = (parse(nd), parse(vd)) else {
            return Err(format!(
                "glass '{name}' is not ND:VD (for example 1.5168:64.17)"
            ));
        };
        return Cauchy::from_abbe(nd, vd)
            .map(Medium::Cauchy)
            .map_err(|e| format!("glass '{name}': {e}"));
    }
    named_glass(name)
        .map(|g| Medium::Sellmeier(g.ior))
        .map_err(|e| format!("glass '{name}': {e}"))
}
