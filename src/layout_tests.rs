//! The app crate's layout, checked: the two front ends share `src/shared/` and never name each
//! other's modules (see docs/architecture.md, "The app crate").
//!
//! Every `.rs` file under `src/` belongs to one side: the command line (`cli.rs` and the
//! command files it includes), the window (`app/`, `panels/`, `worker.rs`), the shared modules
//! (`shared/`) or the root (`main.rs`, this file). A file may name (as `crate::NAME`, as
//! `super::NAME` from a top-level module, or as a `#[path]` include) only the top-level modules
//! of its own side and the shared ones.

use std::path::{Path, PathBuf};

/// A side of the crate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Side {
    Cli,
    Gui,
    Shared,
    Root,
}

/// Files of the command line directly under `src/` (its command files under `src/cli/` too).
const CLI_FILES: [&str; 3] = ["cli.rs", "export.rs", "optimize_cmd.rs"];

/// The side of the file at `rel` (relative to `src/`, `/`-separated); `None`: unclassified.
fn side_of(rel: &str) -> Option<Side> {
    if CLI_FILES.contains(&rel) || rel.starts_with("cli/") {
        return Some(Side::Cli);
    }
    if rel == "worker.rs" || rel.starts_with("app/") || rel.starts_with("panels/") {
        return Some(Side::Gui);
    }
    if rel.starts_with("shared/") {
        return Some(Side::Shared);
    }
    ["main.rs", "layout_tests.rs"].contains(&rel).then_some(Side::Root)
}

/// The side of the top-level module `name` (a module declared in `main.rs`).
fn side_of_module(name: &str) -> Option<Side> {
    match name {
        "cli" => Some(Side::Cli),
        "app" | "worker" => Some(Side::Gui),
        "shared" => Some(Side::Shared),
        _ => None,
    }
}

/// May a file of `from` name a module or file of `to`?
fn allowed(from: Side, to: Side) -> bool {
    from == Side::Root || to == Side::Shared || from == to
}

/// The identifiers following `prefix` in `text` (e.g. `crate::` → `cli` in `crate::cli::X`).
fn names_after<'a>(text: &'a str, prefix: &str) -> Vec<&'a str> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find(prefix) {
        let before_ok = i == 0 || !rest[..i].ends_with(|c: char| c.is_alphanumeric() || c == '_' || c == ':');
        rest = &rest[i + prefix.len()..];
        let end = rest.find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(rest.len());
        if before_ok && end > 0 {
            out.push(&rest[..end]);
        }
    }
    out
}

/// What the file `rel` of side `side` with `text` names across the sides: one message per
/// offending reference.
fn violations(rel: &str, side: Side, text: &str) -> Vec<String> {
    let top_level = matches!(rel, "cli.rs" | "worker.rs" | "app/mod.rs" | "shared/mod.rs");
    let mut names: Vec<&str> = names_after(text, "crate::");
    if top_level {
        names.extend(names_after(text, "super::"));
    }
    let mut out: Vec<String> = names
        .into_iter()
        .filter_map(|n| side_of_module(n).filter(|&to| !allowed(side, to)).map(|to| (n, to)))
        .map(|(n, to)| format!("{rel} ({side:?}) names `{n}` ({to:?})"))
        .collect();
    let dir = Path::new(rel).parent().unwrap_or(Path::new(""));
    for target in path_includes(text) {
        let included = normalise(&dir.join(target));
        match side_of(&included) {
            Some(to) if allowed(side, to) => {}
            to => out.push(format!("{rel} ({side:?}) includes {included} ({to:?})")),
        }
    }
    out
}

/// The file names of the `#[path = "…"]` attributes in `text`.
fn path_includes(text: &str) -> Vec<&str> {
    text.lines().filter_map(|l| l.trim().strip_prefix("#[path = \"")).filter_map(|l| l.split('"').next()).collect()
}

/// `p` with `..` resolved, `/`-separated.
fn normalise(p: &Path) -> String {
    let mut parts: Vec<String> = Vec::new();
    for c in p.components() {
        match c {
            std::path::Component::ParentDir => {
                parts.pop();
            }
            std::path::Component::Normal(s) => parts.push(s.to_string_lossy().into_owned()),
            _ => {}
        }
    }
    parts.join("/")
}

/// Every `.rs` file under `dir`, relative to `root`.
fn rust_files(root: &Path, dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(root, &p, out);
        } else if p.extension().is_some_and(|x| x == "rs")
            && let Ok(rel) = p.strip_prefix(root)
        {
            out.push(rel.to_owned());
        }
    }
}

#[test]
fn front_ends_import_only_shared_modules() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &src, &mut files);
    assert!(files.len() > 20, "the sources were found: {files:?}");
    let mut problems = Vec::new();
    let mut sides = [0usize; 4];
    for rel in &files {
        let rel = rel.to_string_lossy().replace('\\', "/");
        let Some(side) = side_of(&rel) else {
            problems.push(format!("{rel}: not on a side (add it to `side_of`)"));
            continue;
        };
        sides[side as usize] += 1;
        let text = std::fs::read_to_string(src.join(&rel)).unwrap_or_default();
        problems.extend(violations(&rel, side, &text));
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    assert!(sides.iter().all(|&n| n > 0), "files per side (cli, gui, shared, root): {sides:?}");
}

/// The check finds what it must: a window file naming the CLI (by path, by `super::` from a
/// top-level module, by `#[path]`), a CLI file naming the window, a shared file naming either.
#[test]
fn the_layout_check_flags_each_kind_of_crossing() {
    assert_eq!(violations("panels/x.rs", Side::Gui, "use crate::cli::JobArgs;").len(), 1);
    assert_eq!(violations("app/mod.rs", Side::Gui, "use super::cli::core_names;").len(), 1);
    assert_eq!(violations("panels/x.rs", Side::Gui, "#[path = \"../export.rs\"]\nmod e;").len(), 1);
    assert_eq!(violations("export.rs", Side::Cli, "/// see [`crate::app::App`]\nuse crate::worker::Worker;").len(), 2);
    assert_eq!(violations("shared/nc.rs", Side::Shared, "use crate::cli::X; use crate::app::Y;").len(), 2);
    // what is allowed
    assert!(violations("panels/x.rs", Side::Gui, "use crate::shared::nc::NcChoices; use crate::worker::W;").is_empty());
    assert!(
        violations("cli.rs", Side::Cli, "#[path = \"export.rs\"]\nmod export;\nuse super::shared::files;").is_empty()
    );
    assert!(violations("panels/x.rs", Side::Gui, "use super::export::ExportCache; // panels::export").is_empty());
    assert!(violations("cli/pocket.rs", Side::Cli, "use my_crate::cli::X;").is_empty());
}
