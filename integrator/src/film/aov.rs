//! Feature buffers (AOVs, "arbitrary output variables"): what a denoiser and a compositor
//! read beside the radiance. Each is an average over a pixel's camera samples, on the same
//! film (same filter, sample ranges, merges and checkpoints) as the radiance:
//!
//! - `albedo`: the reflectance of the first surface that is not a delta (mirror, smooth
//!   glass), times what the delta vertices before it pass (the directional albedo, by one
//!   BSDF sample per camera sample), in the output RGB space: a white reflectance of 0.8
//!   is RGB 0.8. Each of X, Y, Z is the sample's estimate over its estimate of a white's
//!   at the same wavelengths (a ratio estimator: exact for greys in every sample, within
//!   a fraction of a percent for colours). As Open Image Denoise asks of its albedo input (its documentation,
//!   "Albedo"), so that what is seen in a mirror or through glass keeps its edges.
//! - `normal`: that surface's shading normal, world space, 0 where nothing was met.
//! - `depth`: the distance from the camera to the first surface seen (media boundaries are
//!   not seen), averaged over the samples that met one (0 where none did).
//! - `position`: that surface point, world space, averaged likewise.
//! - `material_id`: 1 + the index of that surface's material in the scene's list, 0 for
//!   nothing; the lowest-numbered sample's, so that merged ranges agree with one render.
//! - `variance`: the variance of each pixel's mean (R, G, B): its expected squared error.
//!   prism's samples are scrambled Sobol points (randomized quasi-Monte Carlo), whose
//!   means err less than the spread of their samples says, by a factor of the integrand.
//!   So a film that records the variance splits its samples
//!   into two independently scrambled sequences (`Replicas`: even and odd samples),
//!   sums the second's colours apart, and estimates the variance of the pixel from the
//!   two means' difference, without bias: n_a n_b / n^2 (A - B)^2. The radiance is then
//!   the mean of two sequences of n / 2 points rather than one of n, another image of the
//!   same expectation with more error (docs/trade-offs.md, "Feature buffers and the
//!   variance buffer").
//!
//! The features are traced by a pass of their own (`trace`), one camera ray per sample
//! with the radiance's film point, lens point, time and wavelengths, followed through
//! delta vertices: it is independent of the tracer (paths, lanes, media), splitting and
//! path reuse, and a render that asks for no AOV never runs it.

use std::fmt;
use std::str::FromStr;

/// One feature buffer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Aov {
    /// `albedo.R`, `albedo.G`, `albedo.B`.
    Albedo,
    /// `normal.X`, `normal.Y`, `normal.Z`.
    Normal,
    /// `depth.Z`.
    Depth,
    /// `position.X`, `position.Y`, `position.Z`.
    Position,
    /// `material_id.ID`.
    MaterialId,
    /// `variance.R`, `variance.G`, `variance.B`.
    Variance,
}

impl Aov {
    /// Every AOV, in the order they are listed and written.
    pub const ALL: [Aov; 6] = [
        Aov::Albedo,
        Aov::Normal,
        Aov::Depth,
        Aov::Position,
        Aov::MaterialId,
        Aov::Variance,
    ];

    /// The name `--aov` takes and the EXR layer's.
    pub fn name(self) -> &'static str {
        match self {
            Aov::Albedo => "albedo",
            Aov::Normal => "normal",
            Aov::Depth => "depth",
            Aov::Position => "position",
            Aov::MaterialId => "material_id",
            Aov::Variance => "variance",
        }
    }

    fn bit(self) -> u8 {
        1 << (self as u8)
    }
}

/// A set of AOVs (empty: none, the default).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct Aovs(u8);

impl Aovs {
    /// No AOV.
    pub const NONE: Aovs = Aovs(0);

    /// This set with `aov` in it.
    #[must_use]
    pub fn with(self, aov: Aov) -> Self {
        Aovs(self.0 | aov.bit())
    }

    /// Whether `aov` is asked for.
    pub fn has(self, aov: Aov) -> bool {
        self.0 & aov.bit() != 0
    }

    /// Whether none is.
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The AOVs in the set, in [`Aov::ALL`]'s order.
    pub fn iter(self) -> impl Iterator<Item = Aov> {
        Aov::ALL.into_iter().filter(move |a| self.has(*a))
    }

    /// The bytes per pixel a film's sums of these AOVs take.
    pub fn bytes_per_pixel(self) -> u64 {
        let hits = self.has(Aov::Depth) || self.has(Aov::Position);
        let floats: u64 = self
            .iter()
            .map(|a| match a {
                Aov::Albedo | Aov::Normal | Aov::Position => 3,
                Aov::Depth => 1,
                Aov::MaterialId => 2,
                Aov::Variance => 6,
            })
            .sum::<u64>()
            + u64::from(hits);
        floats * 8
    }

    /// Whether the set needs the feature pass (everything but the variance, which the
    /// radiance's own samples give).
    pub(crate) fn traced(self) -> bool {
        self.iter().any(|a| a != Aov::Variance)
    }
}

impl fmt::Display for Aovs {
    /// The names, joined by commas (as [`Aovs::from_str`] reads them).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = self.iter().map(Aov::name).collect();
        f.write_str(&names.join(","))
    }
}

impl FromStr for Aovs {
    type Err = String;

    /// Names joined by commas (`albedo,normal`), any order, repeats allowed; `all` for
    /// every one; an empty string for none.
    fn from_str(s: &str) -> Result<Self, String> {
        let mut set = Aovs::NONE;
        for name in s.split(',').map(str::trim).filter(|n| !n.is_empty()) {
            if name == "all" {
                set = Aov::ALL.into_iter().fold(set, Aovs::with);
                continue;
            }
            let aov = Aov::ALL
                .into_iter()
                .find(|a| a.name() == name)
                .ok_or_else(|| {
                    let names: Vec<&str> = Aov::ALL.iter().map(|a| a.name()).collect();
                    format!("unknown AOV '{name}' (valid: {}, all)", names.join(", "))
                })?;
            set = set.with(aov);
        }
        Ok(set)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        let all: Aovs = "all".parse().unwrap();
        assert_eq!(all.iter().count(), 6);
        assert_eq!(all.to_string().parse::<Aovs>().unwrap(), all);
        let two: Aovs = " normal ,albedo,normal".parse().unwrap();
        assert_eq!(two.to_string(), "albedo,normal");
        assert!(two.traced());
        assert!(!"variance".parse::<Aovs>().unwrap().traced());
        assert!("".parse::<Aovs>().unwrap().is_empty());
        let err = "albedo,speed".parse::<Aovs>().unwrap_err();
        assert!(
            err.contains("'speed'") && err.contains("material_id"),
            "{err}"
        );
    }
}
