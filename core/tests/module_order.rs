//! The core's top-level modules form no import cycle: every module uses only modules before
//! it in [`ORDER`]. Read from the sources: each `core/src/<module>.rs` and every file under
//! `core/src/<module>/`, up to its `#[cfg(test)]` (unit tests may use anything), with plain `//`
//! comments removed and doc comments (`///`, `//!`) kept; a use is any `crate::<name>` naming a
//! top-level module, in code (`use`, `pub use`, paths in expressions) or in a doc link
//! (`[…](crate::x::…)`, `` [`crate::x`] ``). A module missing from [`ORDER`], or a use of a later
//! module, fails with the file that makes it. A second check: no module re-exports another
//! top-level module's items (`pub use crate::x::…` or `pub(crate) use crate::x::…` with x not the
//! module itself), so every item has one path, the one in its own module.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::collections::BTreeMap;
use std::path::Path;

/// The allowed order, lowest first: a module may use the modules before it.
#[rustfmt::skip]
const ORDER: &[&str] = &[
    "error", "geom", "toolpath", "outline", "material", "machine", "frame", "job", "path", "analysis", "plan",
    "warnings", "feed", "optimize", "quantity", "sweep", "engagement", "slot_levels", "corner", "pocket", "report", "nc",
    "part", "verify",
];

/// Production code of one file: up to the first `#[cfg(test)]`, plain `//` comments removed,
/// doc comments (`///`, `//!`) kept whole (their links name modules too).
fn production(text: &str) -> String {
    let body = text.split("#[cfg(test)]").next().unwrap_or("");
    body.lines()
        .map(|l| {
            let t = l.trim_start();
            if t.starts_with("///") || t.starts_with("//!") { l } else { l.split("//").next().unwrap_or("") }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The top-level modules whose items `code` re-exports (`pub use crate::x::…`,
/// `pub(crate) use crate::x::…`, `pub(super) use crate::x::…`).
fn re_exports(code: &str) -> Vec<String> {
    code.lines()
        .filter_map(|l| {
            let t = l.trim_start();
            let rest = t
                .strip_prefix("pub ")
                .or_else(|| t.strip_prefix("pub(crate) "))
                .or_else(|| t.strip_prefix("pub(super) "))?;
            let path = rest.strip_prefix("use crate::")?;
            Some(path.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect())
        })
        .collect()
}

/// Top-level module names after `crate::` in `code`.
fn uses(code: &str) -> Vec<String> {
    code.match_indices("crate::")
        .filter(|(i, _)| !code[..*i].ends_with(|c: char| c.is_alphanumeric() || c == '_'))
        .map(|(i, m)| code[i + m.len()..].chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect())
        .collect()
}

/// Files of each top-level module (not lib.rs; a module's `tests.rs` and `*_tests.rs` are test
/// code).
fn modules(src: &Path) -> BTreeMap<String, Vec<std::path::PathBuf>> {
    let mut out: BTreeMap<String, Vec<std::path::PathBuf>> = BTreeMap::new();
    for e in std::fs::read_dir(src).expect("core/src").flatten() {
        let p = e.path();
        let name = p.file_stem().and_then(|s| s.to_str()).unwrap_or("").to_string();
        if p.is_dir() {
            let mut stack = vec![p.clone()];
            while let Some(d) = stack.pop() {
                for f in std::fs::read_dir(&d).expect("module dir").flatten() {
                    let q = f.path();
                    if q.is_dir() {
                        stack.push(q);
                    } else if q.extension().is_some_and(|x| x == "rs")
                        && q.file_name()
                            .and_then(|n| n.to_str())
                            .is_some_and(|n| n != "tests.rs" && !n.ends_with("_tests.rs"))
                    {
                        out.entry(name.clone()).or_default().push(q);
                    }
                }
            }
        } else if p.extension().is_some_and(|x| x == "rs") && name != "lib" {
            out.entry(name).or_default().push(p);
        }
    }
    out
}

#[test]
fn core_modules_use_only_earlier_modules() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mods = modules(&src);
    let rank = |m: &str| ORDER.iter().position(|o| *o == m);
    let mut bad = Vec::new();
    for (m, files) in &mods {
        let Some(rm) = rank(m) else {
            bad.push(format!("module `{m}` is not in ORDER"));
            continue;
        };
        for f in files {
            let code = production(&std::fs::read_to_string(f).expect("read source"));
            for u in uses(&code) {
                if let Some(ru) = rank(&u)
                    && ru > rm
                {
                    bad.push(format!("{} uses crate::{u}, which comes after `{m}`", f.display()));
                }
            }
            for x in re_exports(&code) {
                if x != *m && rank(&x).is_some() {
                    bad.push(format!("{} re-exports items of crate::{x} (use them from `{x}`)", f.display()));
                }
            }
        }
    }
    bad.sort();
    bad.dedup();
    assert!(bad.is_empty(), "module order violated:\n{}", bad.join("\n"));
}

/// The scanner sees the uses it must see (a check of the check): a made-up file using a later
/// module, in both forms, and nothing in comments or after `#[cfg(test)]`.
#[test]
fn scanner_finds_uses_and_skips_comments_and_tests() {
    let code = production(
        "use crate::geom::P2;\nfn f() { crate::pocket::plan(); } // crate::nc\n#[cfg(test)]\nuse crate::corner;",
    );
    assert_eq!(uses(&code), vec!["geom".to_string(), "pocket".to_string()]);
    assert!(uses("mycrate::pocket").is_empty());
    // doc links count, plain comments do not
    let docs = production("//! See [`crate::nc::write`].\n/// [plan](crate::pocket::plan)\nfn g() {} // crate::feed");
    assert_eq!(uses(&docs), vec!["nc".to_string(), "pocket".to_string()]);
    // re-exports of another module's items are found, in every visibility
    let re = "pub use crate::engagement::KindMax;\n    pub(crate) use crate::geom::mirror::flip_y;\nuse crate::toolpath::Entry;\npub use super::x::Y;";
    assert_eq!(re_exports(re), vec!["engagement".to_string(), "geom".to_string()]);
}
