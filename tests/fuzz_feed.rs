//! Fuzz of the feeds written into NC programs: `export --variable-feed` with a target chip
//! thickness of 1e-6 mm in every dialect, random small targets, largest feeds and return
//! feeds, and job files whose `[machine]` table allows only a tiny feed. Each run either exits
//! 2 with a message naming one of the options it was given, or writes a program in which every
//! F word (read here from the text, comments removed) is a finite number > 0 — and which, for
//! LinuxCNC, `rs274` runs without a message. Fixed seeds: a failure names a case that can be
//! run again.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;
mod pocket_common;

use nc_common::interpret;
use pocket_common::{Rng, run};
use std::path::Path;

const DIALECTS: [(&str, &str); 4] = [("linuxcnc", "ngc"), ("fanuc", "nc"), ("grbl", "gcode"), ("sinumerik", "mpf")];

/// The program text without comments: `( … )` and, for Sinumerik, `;` to the end of the line.
fn code_of(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let mut depth = 0;
        for c in line.chars() {
            match c {
                '(' => depth += 1,
                ')' if depth > 0 => depth -= 1,
                ';' if depth == 0 => break,
                _ if depth == 0 => out.push(c),
                _ => {}
            }
        }
        out.push('\n');
    }
    out
}

/// Every F word of the program: (line number, the word's text, its value or None when the text
/// after F is not a number). An F is a word where it starts a word (after a line start, a space
/// or another word's digits) and is followed by a number or `=` and a number; an F followed by
/// a letter starts a keyword (Sinumerik's FFWON, FNORM…) and is not one.
fn f_words(text: &str) -> Vec<(usize, String, Option<f64>)> {
    let mut words = Vec::new();
    for (n, line) in code_of(text).lines().enumerate() {
        let b: Vec<char> = line.chars().collect();
        for i in 0..b.len() {
            if b[i] != 'F' {
                continue;
            }
            let starts = i == 0 || b[i - 1].is_whitespace() || b[i - 1].is_ascii_digit() || b[i - 1] == '.';
            let next = b.get(i + 1).copied().unwrap_or(' ');
            if !starts || next.is_ascii_alphabetic() || next == '_' {
                continue;
            }
            let mut j = i + 1;
            if next == '=' {
                j += 1;
            }
            let num: String =
                b[j..].iter().take_while(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E')).collect();
            let word: String = b[i..j + num.len()].iter().collect();
            words.push((n + 1, word, num.parse::<f64>().ok()));
        }
    }
    words
}

/// Check one export: a refusal must be exit 2 naming one of `names`; a program must have F
/// words, each finite and > 0, and (LinuxCNC) pass rs274. The failure, if any; Ok(true) for a
/// program, Ok(false) for a refusal.
fn check(label: &str, args: &[&str], file: &Path, dialect: &str, names: &[&str]) -> Result<bool, String> {
    let r = run(label, args);
    if r.code == 2 {
        let msg = r.stderr.trim();
        return if names.iter().any(|n| msg.contains(n)) {
            Ok(false)
        } else {
            Err(format!("refused without naming {names:?}: {msg}"))
        };
    }
    if r.code != 0 {
        return Err(format!("exit {}: {}", r.code, r.stderr.trim()));
    }
    let text = std::fs::read_to_string(file).map_err(|e| format!("{}: {e}", file.display()))?;
    let words = f_words(&text);
    if words.is_empty() {
        return Err("a program without an F word".into());
    }
    let bad: Vec<String> = words
        .iter()
        .filter(|(_, _, v)| !v.is_some_and(|v| v.is_finite() && v > 0.0))
        .map(|(n, w, _)| format!("line {n}: {w}"))
        .collect();
    if !bad.is_empty() {
        return Err(format!(
            "{} of {} F words zero, negative or not a number: {}",
            bad.len(),
            words.len(),
            bad.iter().take(4).cloned().collect::<Vec<_>>().join(", ")
        ));
    }
    if dialect == "linuxcnc" {
        interpret(file)?;
    }
    Ok(true)
}

/// Run the cases (label, arguments after `export`, dialect, the option names a refusal may
/// give), print each outcome and fail with every wrong one.
fn fuzz(name: &str, cases: Vec<(String, Vec<String>, &'static str, Vec<&'static str>)>) {
    let dir = tempfile::tempdir().expect("tempdir");
    let (mut written, mut refused, mut failed) = (0, 0, Vec::new());
    let start = std::time::Instant::now();
    for (k, (label, extra, dialect, names)) in cases.iter().enumerate() {
        let ext = DIALECTS.iter().find(|d| d.0 == *dialect).map_or("nc", |d| d.1);
        let file = dir.path().join(format!("{name}{k}.{ext}"));
        let mut args: Vec<&str> = vec!["export", "--dialect", dialect, "-o", file.to_str().expect("utf-8")];
        args.extend(extra.iter().map(String::as_str));
        let label = format!("{name} {k}: {label} ({dialect})");
        match check(&label, &args, &file, dialect, names) {
            Ok(true) => written += 1,
            Ok(false) => refused += 1,
            Err(msg) => {
                eprintln!("{label}: FAILED: {msg}");
                failed.push(format!("{label}: {msg}"));
            }
        }
    }
    eprintln!(
        "{name}: {} cases, {written} programs with positive feeds, {refused} refused by name, {} wrong, {:.1} s",
        cases.len(),
        failed.len(),
        start.elapsed().as_secs_f64()
    );
    assert!(failed.is_empty(), "{name}: {} of {} cases wrong:\n{}", failed.len(), cases.len(), failed.join("\n"));
}

/// `--variable-feed --target-hmax 1e-6` in each dialect, then random small targets (1e-9 to
/// 1e-2 mm, log-uniform), now and then with a small largest feed (`--max-feed`, 1e-9 to
/// 100 mm/min) or return feed (`--return-feed`), in random dialects.
#[test]
fn variable_feed_programs_never_carry_a_zero_feed() {
    let mut cases = Vec::new();
    for (dialect, _) in DIALECTS {
        let extra = ["--variable-feed", "--target-hmax", "1e-6"].map(String::from).to_vec();
        cases.push(("target-hmax 1e-6".to_string(), extra, dialect, vec!["target-hmax"]));
    }
    let mut rng = Rng::new(11);
    for _ in 0..16 {
        let dialect = DIALECTS[rng.below(4)].0;
        let h = rng.log_range(1e-9, 1e-2);
        let mut extra = vec!["--variable-feed".to_string(), "--target-hmax".into(), format!("{h:e}")];
        let mut names = vec!["target-hmax"];
        let mut label = format!("target-hmax {h:.3e}");
        if rng.unit() < 0.3 {
            let f = rng.log_range(1e-9, 100.0);
            extra.extend(["--max-feed".to_string(), format!("{f:e}")]);
            names.push("max-feed");
            label.push_str(&format!(", max-feed {f:.3e}"));
        }
        if rng.unit() < 0.3 {
            let f = rng.log_range(1e-9, 100.0);
            extra.extend(["--return-feed".to_string(), format!("{f:e}")]);
            names.push("return-feed");
            label.push_str(&format!(", return-feed {f:.3e}"));
        }
        cases.push((label, extra, dialect, names));
    }
    fuzz("variable feed", cases);
}

/// Job files (the paper's Table 1 job) with a `[machine]` table of the `vmc` preset's keys and
/// a largest X/Y feed of 1e-9 mm/min, then random tiny ones (1e-12 to 1 mm/min), exported with
/// and without `--variable-feed` in each dialect.
#[test]
fn a_machine_with_a_tiny_largest_feed_never_gets_a_zero_feed() {
    let dir = tempfile::tempdir().expect("tempdir");
    let base = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/paper-table1.toml")).expect("job");
    let mut rng = Rng::new(12);
    let mut cases = Vec::new();
    for k in 0..12 {
        let f = if k < 4 { 1e-9 } else { rng.log_range(1e-12, 1.0) };
        let (fx, fy) = if k % 3 == 2 { (f, 20_000.0) } else { (f, f) };
        let job = dir.path().join(format!("job{k}.toml"));
        let machine = format!(
            "\n[machine]\nname = \"tiny\"\nmax-feed-x = {fx:e}\nmax-feed-y = {fy:e}\nacceleration-x = 3000.0\n\
             acceleration-y = 3000.0\njerk-x = 50000.0\njerk-y = 50000.0\npath-tolerance = 0.01\nblock-time = 0.004\n"
        );
        std::fs::write(&job, format!("{base}{machine}")).expect("write job");
        let dialect = DIALECTS[k % 4].0;
        let mut extra = vec!["--job".to_string(), job.to_str().expect("utf-8").to_string()];
        let variable = k % 2 == 0 || k < 4;
        if variable {
            extra.push("--variable-feed".into());
        }
        let label =
            format!("machine max-feed-x {fx:e}, max-feed-y {fy:e}{}", if variable { ", variable feed" } else { "" });
        cases.push((label, extra, dialect, vec!["max-feed"]));
    }
    fuzz("machine", cases);
}

#[test]
fn f_words_are_read_from_code_only() {
    // the reader itself: comments skipped, keywords skipped, `F=` read, a bad number kept as None
    let text = "(feed F0 in a comment)\nG1 X1 F600.0\nFFWON\nG1 X2 F=12.5 ; F0\nG2X1F0.0\nG1 FX\n";
    let w: Vec<(usize, Option<f64>)> = f_words(text).into_iter().map(|(n, _, v)| (n, v)).collect();
    assert_eq!(w, vec![(2, Some(600.0)), (4, Some(12.5)), (5, Some(0.0))]);
}
