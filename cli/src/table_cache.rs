//! Where default coefficient tables come from: fitted on first use for the colour space
//! that needs one and kept in a cache directory, so a fresh clone works offline, a build
//! fits nothing, tests stay fast, and only spaces actually used are ever fitted.
//!
//! The cache is `$PRISM_CACHE_DIR`, else `$XDG_CACHE_HOME/prism`, else `$HOME/.cache/prism`;
//! tables live in `tables/<space>-<resolution>-v<format>.bin`. A cached file that does not
//! load, or belongs to another space, is refitted and replaced; if the cache cannot be
//! written the table is used from memory with a one-line warning.

use std::io::IsTerminal;
use std::path::PathBuf;

use prism_spectrum::color::RgbSpaceId;
use prism_upsample::{CoefficientTable, FORMAT_VERSION, FitContext};

/// The default resolution: the accuracy targets hold at 64^3 (docs/upsample-accuracy.md).
pub const DEFAULT_RESOLUTION: usize = 64;

/// The cache directory, from the environment.
pub fn cache_dir() -> Option<PathBuf> {
    let from = |key: &str| {
        std::env::var_os(key)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
    };
    from("PRISM_CACHE_DIR")
        .or_else(|| from("XDG_CACHE_HOME").map(|p| p.join("prism")))
        .or_else(|| from("HOME").map(|p| p.join(".cache").join("prism")))
}

/// The default table for `id`, from the cache or freshly fitted (and cached).
pub fn default_table(id: RgbSpaceId, context: &FitContext) -> Result<CoefficientTable, String> {
    let file = cache_dir().map(|d| {
        d.join("tables").join(format!(
            "{}-{DEFAULT_RESOLUTION}-v{FORMAT_VERSION}.bin",
            id.name()
        ))
    });
    if let Some(path) = &file
        && let Ok(bytes) = std::fs::read(path)
    {
        match CoefficientTable::from_bytes(&bytes) {
            Ok(table) if table.space().matches(context) => return Ok(table),
            Ok(_) => eprintln!(
                "prism: warning: '{}' is for another colour space; refitting",
                path.display()
            ),
            Err(e) => eprintln!("prism: warning: '{}': {e}; refitting", path.display()),
        }
    }
    if std::io::stderr().is_terminal() {
        eprintln!(
            "prism: fitting the {DEFAULT_RESOLUTION}^3 {} table (first use; cached afterwards)",
            id.name()
        );
    }
    let (table, _) =
        CoefficientTable::fit(context, DEFAULT_RESOLUTION, &|_| {}).map_err(|e| e.to_string())?;
    let saved = file.as_ref().map(|path| {
        let dir = path.parent().unwrap_or(path.as_path());
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create '{}': {e}", dir.display()))
            .and_then(|()| crate::output::write_atomically(path, &table.to_bytes()))
    });
    match saved {
        Some(Err(e)) => eprintln!("prism: warning: {e}; using the table from memory"),
        None => eprintln!(
            "prism: warning: no cache directory (set PRISM_CACHE_DIR); using the table from memory"
        ),
        Some(Ok(())) => {}
    }
    Ok(table)
}
