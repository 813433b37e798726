//! The files plugins name (images, meshes), found as Mitsuba's file resolver finds them:
//! in the scene's `<path>` directories, the latest first, then next to the file that
//! names them.

use super::parse::error;
use super::paths;
use super::tree::Location;
use crate::LoadError;

/// Where named files are looked for, and how they are read.
#[derive(Clone, Copy)]
pub(crate) struct Files<'a> {
    /// Reads a file by name (the caller's resolver).
    pub resolve: &'a dyn Fn(&str) -> std::io::Result<Vec<u8>>,
    /// The `<path>` directories, the latest first.
    pub search: &'a [String],
}

impl Files<'_> {
    /// The bytes of `name`, named at `at`: the first candidate that reads. An error
    /// names the file and the last reason.
    pub fn read(&self, name: &str, at: &Location) -> Result<Vec<u8>, LoadError> {
        let mut candidates: Vec<String> = Vec::new();
        if paths::is_absolute(name) {
            candidates.push(paths::join("", name));
        } else {
            candidates.extend(self.search.iter().map(|dir| paths::join(dir, name)));
            candidates.push(paths::join(paths::directory(&at.file), name));
        }
        let mut last = None;
        for candidate in &candidates {
            match (self.resolve)(candidate) {
                Ok(bytes) => return Ok(bytes),
                Err(e) => last = Some((candidate, e)),
            }
        }
        Err(match last {
            Some((candidate, e)) => error(at, format!("cannot read \"{candidate}\": {e}")),
            None => error(at, format!("cannot read \"{name}\"")),
        })
    }
}
