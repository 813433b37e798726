//! Reading Mitsuba 3 (and 2.x) XML scene files into a tree of plugin objects with typed
//! properties: the structural layer only. What the plugins mean (turning a `diffuse`
//! BSDF or a `perspective` sensor into prism's scene) is the caller's work; this module
//! gives it a resolved tree to read instead of XML.
//!
//! The format is Mitsuba's "Scene file format"
//! (<https://mitsuba.readthedocs.io/en/latest/src/key_topics/scene_format.html>), with the
//! details of its reader (`src/core/xml.cpp` of mitsuba-renderer/mitsuba3) where the page
//! is silent. What is read:
//!
//! - objects: `<scene version="x.y.z">` at the root, then `shape`, `bsdf`, `emitter`,
//!   `sensor`, `film`, `sampler`, `integrator`, `texture`, `medium`, `phase`, `rfilter`,
//!   `volume`, and `spectrum` / `rgb` with a `type` (a plugin object, e.g. a blackbody),
//!   nested in any order, each with `type`, optional `id` and `name`;
//! - properties `float`, `integer`, `boolean`, `string`, `point` and `vector` (`value="x,
//!   y, z"` or `x`/`y`/`z`), `rgb` (three numbers, or one for grey), `spectrum` (a
//!   constant, `wavelength:value` pairs, or a `filename=` `.spd` file), and `transform`
//!   with `translate`, `rotate` (axis `x y z` or `value`, `angle` in degrees), `scale`,
//!   `matrix` (16 or 9 numbers, row-major) and `lookat` (`origin`, `target`, `up`),
//!   composed in document order, each operation multiplying from the left;
//! - `<ref id>` / `<ref name id>` to an object defined anywhere in the scene (Mitsuba
//!   resolves references after reading), `<alias id as>`;
//! - `<default name value>` parameters, overridden by the caller's `-D` definitions, and
//!   `$name` substitution in every attribute value;
//! - `<include filename>` (the included `<scene>`'s children spliced in place, up to 16
//!   deep, cycles reported) and `<path value>` search directories.
//!
//! Not read: the camelCase parameter names of 0.x scenes are not upgraded (a warning
//! says so), and nothing checks that a plugin or a parameter exists: an unknown `type`
//! is the converter's to report. Every error names the file and line, in one line; no
//! input makes the parser panic. This crate reads no files: includes and `.spd` files go
//! through the caller's resolver.

mod parse;
mod paths;
mod resolve;
mod tree;
mod values;

// What the plugins mean: the tree turned into prism's loaded geometry, one file per
// plugin family (Mitsuba's folders: shapes, bsdfs, emitters, sensors).
mod bitmaps;
mod bsdfs;
mod conductors;
mod emitters;
mod files;
mod instances;
mod media;
mod mesh_attribute;
mod primitives;
mod principled;
mod scene;
mod sensors;
mod shape_mesh;
mod shapes;
mod spectra;
mod textures;
mod unread;
mod volumes;
mod wrappers;

#[cfg(test)]
mod emitters_tests;
#[cfg(test)]
mod media_tests;
#[cfg(test)]
mod scene_tests;
#[cfg(test)]
mod sensors_tests;
#[cfg(test)]
mod shapes_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod textures_tests;

pub use parse::MAX_INCLUDE_DEPTH;
pub use scene::{MitsubaScene, load};
pub use sensors::{Film, PixelFilter};
pub use tree::{Child, Class, Location, Object, Property, Read, SpectrumValue, Value};

use crate::LoadError;

/// Options of a parse.
pub struct ParseOptions<'a> {
    /// `-D name=value` definitions, which override the file's `<default>`s.
    pub defines: &'a [(String, String)],
    /// Reads a file the scene names (includes, `.spd` spectra), given the name joined to
    /// the directory of the file that names it (or to a `<path>` directory).
    pub resolve: &'a dyn Fn(&str) -> std::io::Result<Vec<u8>>,
}

/// A parsed scene.
#[derive(Debug, Clone)]
pub struct Parsed {
    /// The root `<scene>` object.
    pub scene: Object,
    /// Warnings, one line each, starting with `file:line:`.
    pub warnings: Vec<String>,
    /// The `<path>` directories, the latest first, then the scene file's directory: where
    /// the files plugins name (meshes, images) are looked for before the directory of the
    /// (included) file naming them, as Mitsuba's file resolver looks.
    pub search: Vec<String>,
}

/// Parses the text of a Mitsuba scene file. `file` is the name errors and warnings give
/// and the directory includes are relative to.
///
/// # Errors
///
/// [`LoadError::Mitsuba`] naming `file:line` and the problem: malformed XML, an unknown
/// tag, a missing attribute, a bad number, an undefined `$name`, an unknown reference, a
/// duplicate id, an include that cannot be read, that includes itself, or that nests
/// deeper than [`MAX_INCLUDE_DEPTH`].
pub fn parse(text: &str, file: &str, options: &ParseOptions) -> Result<Parsed, LoadError> {
    parse::parse(text, file, options)
}
