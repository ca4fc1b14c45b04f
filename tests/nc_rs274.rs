//! End to end: `trochoplan export` writes LinuxCNC, Fanuc-style and GRBL programs, LinuxCNC's
//! standalone interpreter `rs274` (Debian package `linuxcnc-uspace`) runs them, and the
//! canonical motion it prints (STRAIGHT_TRAVERSE / STRAIGHT_FEED / ARC_FEED) must retrace
//! the planned path: zero interpreter errors, deviation within the tolerance plus rounding,
//! no wall gouge, path length within 0.1 % of the analysis (`nc_common::check_cut`).
//!
//! rs274 is run as `rs274 -g FILE OUTFILE </dev/null`: `-g` runs the whole file in batch mode;
//! it needs no display, INI file or tool table (T1 M6 / G43 H1 use its built-in table).
//! Fanuc's `%` tape marks and `O1000` program number are accepted by rs274 as they are, so the
//! harness passes every program unchanged. Set RS274=/path/to/rs274 to use another binary.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;

use nc_common::{Motion, check_cut, cut, interpret, motions, same_motion};
use std::path::{Path, PathBuf};
use std::process::Command;
use trochoplan_core::job::Direction;
use trochoplan_core::{Job, PathKind, Plan, plan};

/// (CLI flags, job): the paper's default job and every path type.
fn jobs() -> Vec<(Vec<&'static str>, Job)> {
    let d = Job::default();
    vec![
        (vec![], d.clone()),
        (vec!["--path", "circular-type"], Job { path: PathKind::CircularType, ..d.clone() }),
        (
            vec!["--path", "elliptical", "--aspect-ratio", "0.8"],
            Job { path: PathKind::Elliptical, aspect_ratio: 0.8, ..d.clone() },
        ),
        (
            vec!["--path", "elliptical", "--aspect-ratio", "1.2"],
            Job { path: PathKind::Elliptical, aspect_ratio: 1.2, ..d.clone() },
        ),
        (
            vec!["--path", "linear-elliptical", "--aspect-ratio", "0.6", "--linear-distance", "0.75"],
            Job { path: PathKind::LinearElliptical, aspect_ratio: 0.6, linear_distance: 0.75, ..d.clone() },
        ),
        // climb milling: every loop mirrored, counter-clockwise
        (vec!["--direction", "climb"], Job { direction: Direction::Climb, ..d.clone() }),
        (
            vec![
                "--path",
                "linear-elliptical",
                "--aspect-ratio",
                "0.6",
                "--linear-distance",
                "0.75",
                "--direction",
                "climb",
            ],
            Job {
                path: PathKind::LinearElliptical,
                aspect_ratio: 0.6,
                linear_distance: 0.75,
                direction: Direction::Climb,
                ..d
            },
        ),
    ]
}

fn export(dir: &Path, name: &str, job_flags: &[&str], nc_flags: &[&str]) -> PathBuf {
    let file = dir.join(name);
    let out = Command::new(env!("CARGO_BIN_EXE_trochoplan"))
        .arg("export")
        .args(job_flags)
        .args(nc_flags)
        .arg("-o")
        .arg(&file)
        .output()
        .expect("run trochoplan");
    assert!(
        out.status.success(),
        "trochoplan export {job_flags:?} {nc_flags:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    file
}

fn read_back(file: &Path) -> Vec<Motion> {
    motions(&interpret(file).unwrap_or_else(|e| panic!("{e}")))
}

fn check(label: &str, file: &Path, p: &Plan, tol: f64, decimals: i32) -> Vec<Motion> {
    let m = read_back(file);
    // rs274 prints 4 decimals: z is exact to that
    check_cut(label, &cut(&m, p.job.depth, 1e-4), p, tol, 10f64.powi(-decimals)).unwrap_or_else(|e| panic!("{e}"));
    m
}

#[test]
fn linuxcnc_fanuc_and_grbl_programs_pass_rs274_and_retrace_the_plan() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (k, (flags, job)) in jobs().into_iter().enumerate() {
        let p = plan(&job).expect("valid job");
        for (dialect, ext, decimals) in [("linuxcnc", "ngc", 4), ("fanuc", "nc", 3), ("grbl", "gcode", 3)] {
            let f = export(dir.path(), &format!("{k}.{ext}"), &flags, &["--dialect", dialect, "--coolant"]);
            check(&format!("{} {dialect}", job.path.name()), &f, &p, 0.005, decimals);
        }
        let f = export(dir.path(), &format!("{k}_chords.ngc"), &flags, &["--dialect", "linuxcnc", "--linear-segments"]);
        check(&format!("{} linuxcnc chords", job.path.name()), &f, &p, 0.005, 4);
        let f = export(dir.path(), &format!("{k}_tol.nc"), &flags, &["--dialect", "fanuc", "--tolerance", "0.02"]);
        check(&format!("{} fanuc 0.02 mm", job.path.name()), &f, &p, 0.02, 3);
    }
}

#[test]
fn linuxcnc_while_loop_moves_like_the_expanded_program() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (k, (flags, job)) in jobs().into_iter().enumerate() {
        let p = plan(&job).expect("valid job");
        for fast in [&[][..], &["--return-feed", "1800"][..]] {
            let nc: Vec<&str> = ["--dialect", "linuxcnc"].iter().chain(fast).copied().collect();
            let expanded = export(dir.path(), &format!("{k}.ngc"), &flags, &nc);
            let compact_flags: Vec<&str> = nc.iter().copied().chain(["--compact"]).collect();
            let compact = export(dir.path(), &format!("{k}_loop.ngc"), &flags, &compact_flags);
            let text = std::fs::read_to_string(&compact).expect("read");
            assert!(text.contains("o100 while") && text.contains("o100 endwhile"), "{text}");
            let me = check(&format!("{} expanded", job.path.name()), &expanded, &p, 0.005, 4);
            let mc = check(&format!("{} loop", job.path.name()), &compact, &p, 0.005, 4);
            // cycle-relative vs absolute rounding: one quantum, plus rs274's print rounding
            same_motion(&me, &mc, 1e-4 + 1e-4).unwrap_or_else(|e| panic!("{}: {e}", job.path.name()));
        }
    }
}

#[test]
fn the_harness_catches_interpreter_errors_and_wrong_motion() {
    let dir = tempfile::tempdir().expect("tempdir");
    // an interpreter error (LinuxCNC rejects a nested comment) is reported, not ignored
    let bad = dir.path().join("bad.ngc");
    std::fs::write(&bad, "G21 G90\nG1 X1 F100 (a (nested) comment)\nM30\n").expect("write");
    let err = interpret(&bad).expect_err("rs274 must reject it");
    assert!(err.contains("comment"), "{err}");

    // a program missing one block of one cycle is caught by the motion checks
    let job = Job { path: PathKind::Elliptical, aspect_ratio: 0.8, ..Job::default() };
    let p = plan(&job).expect("valid job");
    let good =
        export(dir.path(), "good.ngc", &["--path", "elliptical", "--aspect-ratio", "0.8"], &["--dialect", "linuxcnc"]);
    let text = std::fs::read_to_string(&good).expect("read");
    let lines: Vec<&str> = text.lines().collect();
    let arcs: Vec<usize> = (0..lines.len()).filter(|&i| lines[i].starts_with('X')).collect();
    let dropped = arcs[arcs.len() / 2];
    // one arc piece becomes a straight line to its end; the next block gets its G2 back
    let mut broken: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    broken[dropped] = format!("G1 {}", lines[dropped].split(" I").next().unwrap_or(""));
    assert!(lines[dropped + 1].starts_with('X'), "the next block is an arc too");
    broken[dropped + 1] = format!("G2 {}", lines[dropped + 1]);
    let broken_file = dir.path().join("broken.ngc");
    std::fs::write(&broken_file, broken.join("\n") + "\n").expect("write");
    let m = motions(&interpret(&broken_file).unwrap_or_else(|e| panic!("{e}")));
    let result = check_cut("broken", &cut(&m, p.job.depth, 1e-4), &p, 0.005, 1e-4);
    assert!(result.is_err(), "a chord in place of an arc must exceed the tolerance");
}

#[test]
fn hostile_titles_cannot_form_active_comments() {
    // LinuxCNC executes comments that begin with MSG, DEBUG, PRINT, LOG…, ABORT,
    // PROBEOPEN/PROBECLOSE (any case, after spaces): `ABORT,stop` would abort the program before
    // any motion, `LOGOPEN,/path` would open a file. The interpreter must run each program silently (any
    // message on stderr fails `interpret`) and create no file, and the program must still cut.
    let dir = tempfile::tempdir().expect("tempdir");
    let log = dir.path().join("controller.log");
    let logopen = format!("LOGOPEN,{}", log.display());
    let p = plan(&Job::default()).expect("valid job");
    for (k, title) in
        ["ABORT,stop", "  msg,hello operator", "DEBUG,#5220", "Print,x", logopen.as_str(), "logclose", "PROBEOPEN x"]
            .into_iter()
            .enumerate()
    {
        let f = export(dir.path(), &format!("title{k}.ngc"), &[], &["--dialect", "linuxcnc", "--title", title]);
        check(&format!("title {title:?}"), &f, &p, 0.005, 4);
        let first = std::fs::read_to_string(&f).expect("read").lines().next().unwrap_or("").to_string();
        assert!(first.starts_with("(- "), "{title:?} -> {first}");
    }
    assert!(!log.exists(), "the program opened a log file on the controller");
}

/// Variable feed in every dialect rs274 reads (and the LinuxCNC loop): the path is
/// retraced as with the programmed feed, and the feeds rs274 sets are the schedule's block feeds (the plunge at
/// the programmed feed aside), several of them, none above 3 × feed.
#[test]
fn variable_feed_programs_pass_rs274_with_the_scheduled_feeds() {
    use trochoplan_core::feed::{VariableFeed, schedule};
    let dir = tempfile::tempdir().expect("tempdir");
    for (k, (flags, job)) in jobs().into_iter().enumerate() {
        let p = plan(&job).expect("valid job");
        let sched = schedule(&p, &VariableFeed::default()).expect("schedule");
        let feeds: Vec<f64> = sched.blocks.iter().map(|b| b.feed_mm_per_min).collect();
        for (dialect, ext, decimals, extra) in [
            ("linuxcnc", "ngc", 4, &[][..]),
            ("fanuc", "nc", 3, &[][..]),
            ("grbl", "gcode", 3, &[][..]),
            ("linuxcnc", "ngc", 4, &["--compact"][..]),
        ] {
            let nc: Vec<&str> = ["--dialect", dialect, "--variable-feed"].iter().chain(extra).copied().collect();
            let f = export(dir.path(), &format!("{k}_vf{}.{ext}", extra.len()), &flags, &nc);
            let label = format!("{} {dialect}{extra:?} variable feed", job.path.name());
            check(&label, &f, &p, 0.005, decimals);
            let canon = interpret(&f).unwrap_or_else(|e| panic!("{e}"));
            let set: Vec<f64> = canon
                .lines()
                .filter_map(|l| l.split("SET_FEED_RATE(").nth(1))
                .filter_map(|r| r.trim_end_matches(')').trim().parse::<f64>().ok())
                // rs274 starts at F0 before the program sets one
                .filter(|&f| f > 0.0)
                .collect();
            let distinct: std::collections::BTreeSet<i64> = set.iter().map(|f| (f * 10.0).round() as i64).collect();
            assert!(distinct.len() >= 5, "{label}: feeds {distinct:?}");
            for f in &set {
                let scheduled = feeds.iter().any(|g| (g - f).abs() <= 0.05 + 1e-6 * g);
                assert!(scheduled || (f - job.feed).abs() < 1e-6, "{label}: F{f} not in the schedule");
                assert!(*f <= 3.0 * job.feed + 0.05, "{label}: F{f}");
            }
        }
    }
}
