//! The README, ARCHITECTURE.md and everything in `docs/` as a user meets them: every
//! `prism` command in their `sh` blocks runs and writes what it names (renders made
//! small: 12 x 8 pixels, 2 samples per pixel unless the command renders sample ranges); a
//! block with any other command says why it is not run (`# not run by the tests: ...`);
//! every relative link leads to a file that exists, and to a heading of it where it names
//! one; and no document names a round of work.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The documents: the README, ARCHITECTURE.md and every Markdown file under `docs/`.
fn documents() -> Vec<PathBuf> {
    fn markdown_under(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                markdown_under(&path, out);
            } else if path.extension().is_some_and(|e| e == "md") {
                out.push(path);
            }
        }
    }
    let mut pages = Vec::new();
    markdown_under(&root().join("docs"), &mut pages);
    pages.sort();
    pages.insert(0, root().join("ARCHITECTURE.md"));
    pages.insert(0, root().join("README.md"));
    pages
}

/// The marker of a block whose commands the tests do not run, followed by the reason.
const NOT_RUN: &str = "# not run by the tests: ";

/// The lines of a document's fenced blocks tagged `lang`, block by block.
fn blocks(text: &str, lang: &str) -> Vec<Vec<String>> {
    let (mut out, mut current): (Vec<Vec<String>>, Option<Vec<String>>) = (Vec::new(), None);
    for line in text.lines() {
        match (&mut current, line.trim_start()) {
            (None, l) if l == format!("```{lang}") => current = Some(Vec::new()),
            (Some(_), "```") => out.push(current.take().unwrap()),
            (Some(lines), _) => lines.push(line.to_string()),
            _ => {}
        }
    }
    out
}

/// A command's arguments made small and pointed at `dir` for what it writes (and reads of
/// what an earlier command wrote).
fn small(args: &[&str], dir: &Path) -> Vec<String> {
    // Only renders get a small sample count; ranges and other commands keep what they say.
    let keeps_spp = args.contains(&"--sample-range") || args.first() != Some(&"render");
    let mut out: Vec<String> = Vec::new();
    let mut i = 0;
    while i < args.len() {
        let (arg, value) = (args[i], args.get(i + 1).copied());
        match (arg, value) {
            ("--width", Some(_)) | ("--height", Some(_)) => i += 2,
            ("--spp", Some(_)) if !keeps_spp => i += 2,
            ("-o" | "--polarization-png", Some(v)) => {
                out.push(arg.to_string());
                out.push(dir.join(v).to_string_lossy().into_owned());
                i += 2;
            }
            _ => {
                out.push(if dir.join(arg).exists() {
                    dir.join(arg).to_string_lossy().into_owned()
                } else {
                    arg.to_string()
                });
                i += 1;
            }
        }
    }
    if out.first().is_some_and(|c| c == "render") {
        out.extend(["--width", "12", "--height", "8", "-q"].map(String::from));
        if !keeps_spp {
            out.extend(["--spp", "2"].map(String::from));
        }
    }
    out
}

#[test]
fn every_command_in_the_guide_runs() {
    let mut ran = 0;
    for document in documents() {
        let text = std::fs::read_to_string(&document).unwrap();
        let dir = common::temp_dir("guide");
        for block in blocks(&text, "sh") {
            if let Some(marker) = block.iter().find(|l| l.trim().starts_with(NOT_RUN)) {
                assert!(
                    marker.trim().len() > NOT_RUN.len() + 10,
                    "{}: a block not run says why",
                    document.display()
                );
                continue;
            }
            let prompted = block.iter().any(|l| l.trim_start().starts_with("$ "));
            for line in block {
                let line = line.trim();
                if line.is_empty() || line.starts_with('#') {
                    continue;
                }
                // In a block with prompts, the lines without one are output.
                let line = match (prompted, line.strip_prefix("$ ")) {
                    (true, None) => continue,
                    (true, Some(command)) => command,
                    (false, _) => line,
                };
                let command = line.split(" #").next().unwrap().trim();
                let Some(rest) = command.strip_prefix("prism ") else {
                    panic!(
                        "{}: `{command}` is not a prism command: run it in a test or mark its block `{NOT_RUN}<why>`",
                        document.display()
                    );
                };
                let args: Vec<&str> = rest.split_whitespace().collect();
                // The denoiser is a library of its own (pip install pyoidn): without
                // PRISM_OIDN its commands are left out, unless the run requires them (CI).
                let denoises = args.contains(&"--denoise") || args.first() == Some(&"denoise");
                if denoises
                    && std::env::var_os("PRISM_OIDN").is_none()
                    && std::env::var_os("PRISM_REQUIRE_OIDN").is_none()
                {
                    continue;
                }
                let args = small(&args, &dir);
                let out = Command::new(env!("CARGO_BIN_EXE_prism"))
                    .args(&args)
                    .current_dir(root())
                    .output()
                    .unwrap();
                assert!(
                    out.status.success(),
                    "{}: `{command}` failed: {}",
                    document.display(),
                    String::from_utf8_lossy(&out.stderr)
                );
                for (i, a) in args.iter().enumerate() {
                    if a == "-o" {
                        assert!(
                            Path::new(&args[i + 1]).exists(),
                            "{}: `{command}` wrote no {}",
                            document.display(),
                            args[i + 1]
                        );
                    }
                }
                ran += 1;
            }
        }
    }
    assert!(ran >= 20, "only {ran} commands found");
}

/// Documents say what is true now; rounds of work belong to git and the issues.
#[test]
fn no_document_names_a_round_of_work() {
    for document in documents() {
        let text = std::fs::read_to_string(&document).unwrap().to_lowercase();
        for (n, line) in text.lines().enumerate() {
            let named = line.contains("this session")
                || line.contains("last session")
                || line
                    .match_indices("session ")
                    .any(|(i, _)| line[i + 8..].starts_with(|c: char| c.is_ascii_digit()));
            assert!(!named, "{}:{}: {line}", document.display(), n + 1);
        }
    }
}

/// GitHub's anchor for a heading: lower case, punctuation other than '-' and '_' dropped,
/// spaces as '-'.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == '-' || *c == '_' || *c == ' ')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

fn anchors(text: &str) -> Vec<String> {
    let mut fenced = false;
    text.lines()
        .filter(|l| {
            if l.trim_start().starts_with("```") {
                fenced = !fenced;
            }
            !fenced
        })
        .filter_map(|l| l.strip_prefix('#'))
        .map(|l| anchor(l.trim_start_matches('#')))
        .collect()
}

#[test]
fn every_link_in_the_guide_resolves() {
    let link = |text: &str| -> Vec<String> {
        let mut out = Vec::new();
        let mut rest = text;
        while let Some(i) = rest.find("](") {
            let after = &rest[i + 2..];
            let end = after.find(')').unwrap_or(after.len());
            out.push(after[..end].to_string());
            rest = &after[end..];
        }
        out
    };
    let mut checked = 0;
    for document in documents() {
        let text = std::fs::read_to_string(&document).unwrap();
        for target in link(&text) {
            if target.starts_with("http") {
                continue;
            }
            let (file, heading) = match target.split_once('#') {
                Some((f, h)) => (f, Some(h)),
                None => (target.as_str(), None),
            };
            let path = if file.is_empty() {
                document.clone()
            } else {
                document.parent().unwrap().join(file)
            };
            assert!(
                path.exists(),
                "{}: the link to {target} leads nowhere",
                document.display()
            );
            if let Some(h) = heading {
                let text = std::fs::read_to_string(&path).unwrap();
                assert!(
                    anchors(&text).iter().any(|a| a == h),
                    "{}: {} has no heading #{h}",
                    document.display(),
                    path.display()
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 30, "only {checked} links found");
}
