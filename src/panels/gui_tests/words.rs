//! The window's words and the CLI's help: no label, tooltip or value names a code item (a
//! snake_case identifier, a path into the code with `::`, a source file) or a document outside
//! the program (the project's specification and its sections), and no value is shown as NaN.
//!
//! The rule ([`code_names`]): a word of lowercase letters and digits joined by underscores
//! (`a_str`, `power_max_w`) is a code name unless it is one of the papers' symbols written as the
//! papers write them ([`PAPER_SYMBOLS`]); symbols with a capital (F_R, W_l, K_c) are never code
//! names. `::`, `§`, the name of the workplace's domain specification, its shared folder, `docs/` and a `.rs` file are code or outside
//! documents wherever they stand; the window shows no backquotes (code markup). In `--help`, flag
//! names (`--max-step-down`), the `analyze` report's keys and backquoted text (what the user types
//! or reads literally: `-`, a report's key) are the program's own vocabulary and allowed.

use super::*;
use egui_kittest::kittest::{By, NodeT};

/// The papers' symbols with an underscore and no capital, as Wagih et al. (2023) and the
/// trochoidal-milling literature write them: chip thickness, aspect ratio, feed per tooth,
/// axial and radial depth of cut, feed rate, cycle and cooling time.
const PAPER_SYMBOLS: [&str; 9] = ["h_max", "r_e", "f_z", "a_p", "a_e", "f_r", "t_cycle", "t_cooling", "t_hmax"];

/// Text that is code or names a document outside the program wherever it stands.
const NEVER: [&str; 6] = ["::", "§", concat!("domain", "-", "spec"), concat!("..", "/", "shared"), "docs/", ".rs"];

/// The code names and outside documents in `text`; `allowed(word)`: words the context allows.
pub(super) fn code_names(text: &str, allowed: &dyn Fn(&str) -> bool) -> Vec<String> {
    let mut found: Vec<String> = NEVER.iter().filter(|n| text.contains(**n)).map(|n| (*n).to_owned()).collect();
    for word in text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '-')) {
        if allowed(word) {
            continue;
        }
        let word = word.trim_matches('-');
        let parts: Vec<&str> = word.split('_').collect();
        let snake = parts.len() >= 2
            && parts.iter().all(|p| !p.is_empty() && p.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit()));
        if snake && !PAPER_SYMBOLS.contains(&word) {
            found.push(word.to_owned());
        }
    }
    found
}

#[test]
fn the_rule_finds_code_names_and_allows_the_papers_symbols() {
    let none = |_: &str| false;
    assert_eq!(code_names("Straight engagement a_str (°)", &none), ["a_str"]);
    assert_eq!(code_names("Chip (Plan::chip_outline)", &none), ["::", "chip_outline"]);
    let spec = concat!("domain", "-", "spec");
    assert_eq!(code_names(&format!("see {spec} §1.1"), &none), ["§", spec]);
    assert!(code_names("h_max, r_e, f_z, a_p, W_l, F_R,max = 12 N", &none).is_empty());
    assert!(code_names("--max-step-down 4 mm", &none).is_empty(), "kebab-case is not snake_case");
    assert_eq!(code_names("power_max_w", &none), ["power_max_w"]);
    assert!(code_names("power_max_w", &|w: &str| w == "power_max_w").is_empty());
}

/// Every text of the window's accessibility tree: labels, values and descriptions (the
/// tooltips), with the node's role.
pub(super) fn texts(h: &Harness<'_, App>) -> Vec<String> {
    h.query_all(By::new().predicate(|_| true))
        .flat_map(|n| {
            let a = n.accesskit_node();
            [a.label(), a.value(), a.description()]
        })
        .flatten()
        .collect()
}

#[test]
fn no_tab_shows_a_code_name_an_outside_document_or_nan() {
    let mut h = harness();
    // pinned variants (Compare's table and every plot's overlays), PI without a value among them
    h.get_by_label(Tab::Compare.spec().label).click();
    h.run();
    h.get_by_label("Pin the paper's set").click();
    h.run();
    let mut bad = Vec::new();
    for spec in &crate::app::tabs::TABS {
        h.get_by_label(spec.label).click();
        h.run();
        // the tab's background work (Sweep, Pocket) finishes, its results shown
        let t0 = Instant::now();
        while (h.state().pocket.pending() || h.state().planner.pending()) && t0.elapsed().as_secs() < 120 {
            std::thread::sleep(std::time::Duration::from_millis(20));
            h.step();
        }
        h.run();
        for text in texts(&h) {
            let mut found = code_names(&text, &|_| false);
            // backquotes, code markup, are shown as they are: none in the window
            if text.contains('`') {
                found.push("`".to_owned());
            }
            if !found.is_empty() {
                bad.push(format!("{}: {found:?} in {text:?}", spec.label));
            }
            if text.contains("NaN") || text.contains("inf ") {
                bad.push(format!("{}: no value shown as a number in {text:?}", spec.label));
            }
        }
    }
    bad.sort();
    bad.dedup();
    assert!(bad.is_empty(), "{} texts:\n{}", bad.len(), bad.join("\n"));
}

#[test]
fn no_help_text_names_a_code_item_or_an_outside_document() {
    let keys: Vec<&str> = trochoplan_core::quantity::METRICS.iter().map(|m| m.key).collect();
    let allowed = |w: &str| w.starts_with("--") || keys.contains(&w);
    let mut bad = Vec::new();
    // the subcommands, from the program's own help
    let text = |args: &[&str]| String::from_utf8_lossy(&command_line(args).stdout).into_owned();
    let top = text(&["--help"]);
    let commands: Vec<String> = top
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next().map(str::to_owned))
        .filter(|c| c != "help")
        .collect();
    assert!(commands.len() > 5 && commands.iter().any(|c| c == "export"), "{commands:?}");
    let helps = std::iter::once(("trochoplan".to_owned(), top.clone()))
        .chain(commands.iter().map(|c| (c.clone(), text(&[c.as_str(), "--help"]))));
    for (command, text) in helps {
        for line in text.lines() {
            // backquoted: what the user types or reads literally (`-`, a report's key `time_real_s`)
            let unquoted: String = line.split('`').step_by(2).collect::<Vec<_>>().join(" ");
            let found = code_names(&unquoted, &allowed);
            if !found.is_empty() {
                bad.push(format!("{command}: {found:?} in {line:?}"));
            }
        }
    }
    assert!(bad.is_empty(), "{} lines:\n{}", bad.len(), bad.join("\n"));
}
