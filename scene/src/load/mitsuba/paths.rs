//! File names as the parser hands them to the caller's resolver: joined to the directory
//! of the file that names them, with `.` and `..` folded so that the include stack can
//! recognise a file met twice. Pure string work: this crate touches no files.

/// The directory part of a file name ("" for a bare name).
pub fn directory(file: &str) -> &str {
    match file.rfind(['/', '\\']) {
        Some(i) => &file[..i],
        None => "",
    }
}

/// Whether a name is absolute (a leading slash or backslash, or a drive letter).
pub fn is_absolute(name: &str) -> bool {
    let bytes = name.as_bytes();
    name.starts_with(['/', '\\'])
        || (bytes.len() >= 2 && bytes[0].is_ascii_alphabetic() && bytes[1] == b':')
}

/// `name` relative to `directory`, folded; an absolute name as it is (folded).
pub fn join(directory: &str, name: &str) -> String {
    if is_absolute(name) || directory.is_empty() {
        fold(name)
    } else {
        fold(&format!("{directory}/{name}"))
    }
}

/// Drops `.` components and folds `x/..`; a leading `..` stays.
fn fold(name: &str) -> String {
    let absolute = name.starts_with(['/', '\\']);
    let mut parts: Vec<&str> = Vec::new();
    for part in name.split(['/', '\\']) {
        match part {
            "" | "." => {}
            ".." if parts.last().is_some_and(|p| *p != "..") => {
                parts.pop();
            }
            _ => parts.push(part),
        }
    }
    let joined = parts.join("/");
    if absolute {
        format!("/{joined}")
    } else {
        joined
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joins_and_folds() {
        assert_eq!(directory("scenes/a.xml"), "scenes");
        assert_eq!(directory("a.xml"), "");
        assert_eq!(join("scenes", "inc/b.xml"), "scenes/inc/b.xml");
        assert_eq!(join("scenes/inc", "../a.xml"), "scenes/a.xml");
        assert_eq!(join("", "./a.xml"), "a.xml");
        assert_eq!(join("x", "/abs/a.xml"), "/abs/a.xml");
        assert_eq!(join("", "../a.xml"), "../a.xml");
    }
}
