//! Real time of FreeCAD's Adaptive programs and of our default pockets on the same machine
//! model: for each of the six outlines in `tests/data/freecad/` (README there), FreeCAD's
//! LinuxCNC program and the program of `trochoplan pocket --polygon P --step-over 1.527
//! --export P.ngc` (D 10, 600 mm/min, depth 6, LinuxCNC) are read back into tool paths
//! (`nc::read_toolpath`) and timed on the `vmc` preset by `machine::program_time`.
//!
//! Checks against bounds computed here from the moves alone: the time at feed is at least the
//! feed moves' 3D length at their programmed feed, the rapids' time at least their length at
//! the machine's rapid rate, the vertical moves' at least their length at the fastest rate they
//! may run; the lengths FreeCAD's programs have at depth (cut and rapid) are the README's,
//! measured there on LinuxCNC's `rs274` output; our program read back is timed like the plan's
//! own tool path (`machine::toolpath_time`). Prints the table of docs/freecad-comparison.md:
//! `cargo test --release --test freecad_time -- --nocapture`.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::Path;
use std::process::Command;
use trochoplan_core::machine::{Machine, ProgramTime, program_time};
use trochoplan_core::nc::{Dialect, read_toolpath};
use trochoplan_core::toolpath::{Move, MoveKind};

/// The pockets, with FreeCAD's lengths from the README of `tests/data/freecad/` (mm, one
/// decimal): the feed moves in the plane below the stock top (Cutting + entry + helix, 3D) and
/// the rapids at depth (LinkClear).
const POCKETS: [(&str, f64, f64); 6] = [
    ("rect", 1670.1 + 5.3 + 94.3, 616.4),
    ("L", 1780.5 + 5.3 + 94.3, 959.6),
    ("dumbbell", 1107.7 + 10.6 + 188.5, 207.6),
    ("u-channel", 2441.3 + 5.3 + 94.3, 1370.8),
    ("pentagon-notch", 1983.6 + 5.3 + 94.3, 778.8),
    ("narrow", 1627.6 + 3.5 + 89.5, 798.0),
];

/// Depth of both programs (mm).
const DEPTH: f64 = 6.0;
/// Programmed feed of both (mm/min).
const FEED: f64 = 600.0;

fn data() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/freecad"))
}

fn len3(m: &Move) -> f64 {
    m.segment.length().hypot(m.z_end_mm - m.z_start_mm)
}

/// Whether a move is at the depth (both ends).
fn at_depth(m: &Move) -> bool {
    (m.z_start_mm + DEPTH).abs() < 1e-6 && (m.z_end_mm + DEPTH).abs() < 1e-6
}

/// Lower bounds of the time of `moves` from their lengths alone (s): feed moves with motion in
/// the plane at their programmed feed, rapids at the rapid rate, moves along Z at the larger
/// of the feed and the rapid rate.
fn bounds(moves: &[Move], m: &Machine) -> (f64, f64, f64) {
    let rapid = m.rapid_mm_per_min();
    let (mut feed, mut fast, mut vertical) = (0.0, 0.0, 0.0);
    for mv in moves {
        let l = len3(mv);
        let f = mv.feed_mm_per_min.unwrap_or(FEED);
        if mv.segment.length() <= 1e-9 {
            vertical += l / f.max(rapid) * 60.0;
        } else if mv.kind == MoveKind::Rapid {
            fast += l / rapid * 60.0;
        } else {
            feed += l / f * 60.0;
        }
    }
    (feed, fast, vertical)
}

fn check(label: &str, moves: &[Move], t: &ProgramTime, m: &Machine) {
    let (feed, rapid, vertical) = bounds(moves, m);
    assert!(t.feed_s >= feed * (1.0 - 1e-9), "{label}: at feed {} s < {feed} s", t.feed_s);
    assert!(t.rapid_s >= rapid * (1.0 - 1e-9), "{label}: rapids {} s < {rapid} s", t.rapid_s);
    assert!(t.vertical_s >= vertical * (1.0 - 1e-9), "{label}: vertical {} s < {vertical} s", t.vertical_s);
    assert!((t.total_s - (t.feed_s + t.rapid_s + t.vertical_s)).abs() < 1e-9, "{label}: {t:?}");
    // at 600 mm/min (10 mm/s) the `vmc` ramps last v/a + a/J = 0.063 s: the feed moves run at
    // their feed but for the stops and the blends of sharp polyline corners
    assert!(t.feed_s < 1.5 * feed, "{label}: at feed {} s against {feed} s programmed", t.feed_s);
}

#[test]
fn freecad_and_our_pockets_timed_by_one_model() {
    let vmc = Machine::preset("vmc").unwrap();
    let dir = tempfile::tempdir().unwrap();
    let mut rows = Vec::new();
    for (name, fc_cut, fc_links) in POCKETS {
        // FreeCAD's program as it posts it
        let text = std::fs::read_to_string(data().join(format!("{name}.ngc"))).unwrap();
        let fc = read_toolpath(&text, Dialect::LinuxCnc).unwrap();
        let tf = program_time(&fc.moves, &vmc, FEED).unwrap();
        check(&format!("FreeCAD {name}"), &fc.moves, &tf, &vmc);
        // its lengths are the README's (rs274 output, one decimal each)
        let cut: f64 = fc
            .moves
            .iter()
            .filter(|m| m.kind != MoveKind::Rapid && m.segment.length() > 1e-9 && m.z_start_mm.max(m.z_end_mm) <= 0.0)
            .map(len3)
            .sum();
        let links: f64 =
            fc.moves.iter().filter(|m| m.kind == MoveKind::Rapid && at_depth(m)).map(|m| m.segment.length()).sum();
        assert!((cut - fc_cut).abs() < 0.3, "{name}: feed below the top {cut} vs {fc_cut}");
        assert!((links - fc_links).abs() < 0.2, "{name}: links at depth {links} vs {fc_links}");

        // our default pocket, exported by the command line
        let polygon = data().join(format!("{name}.txt"));
        let ngc = dir.path().join(format!("{name}.ngc"));
        let out = Command::new(env!("CARGO_BIN_EXE_trochoplan"))
            .args(["pocket", "--polygon"])
            .arg(&polygon)
            .args(["--step-over", "1.527", "--machine", "vmc", "--export"])
            .arg(&ngc)
            .output()
            .unwrap();
        assert!(out.status.success(), "{name}: {}", String::from_utf8_lossy(&out.stderr));
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let ours = read_toolpath(&std::fs::read_to_string(&ngc).unwrap(), Dialect::LinuxCnc).unwrap();
        let to = program_time(&ours.moves, &vmc, FEED).unwrap();
        check(&format!("ours {name}"), &ours.moves, &to, &vmc);
        // the plan's own tool path, timed by the command (`time_real_s`), agrees with its
        // program read back within 0.1 % (the program's biarcs and rounding)
        let planned = json["time_real_s"].as_f64().unwrap();
        assert!(
            (planned - to.total_s).abs() < 1e-3 * to.total_s,
            "{name}: planned {planned} vs read back {}",
            to.total_s
        );
        rows.push((name, tf, to));
    }
    println!(
        "| pocket | FreeCAD: time | at feed | rapids | Z moves | length at feed | rapid length | ours: time | at feed | rapids | Z moves | length at feed | rapid length | ours / FreeCAD |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (name, f, o) in rows {
        println!(
            "| {name} | {:.1} s | {:.1} s | {:.1} s | {:.1} s | {:.0} mm | {:.0} mm | {:.1} s | {:.1} s | {:.1} s | {:.1} s | {:.0} mm | {:.0} mm | {:.2} |",
            f.total_s,
            f.feed_s,
            f.rapid_s,
            f.vertical_s,
            f.feed_length_mm,
            f.rapid_length_mm,
            o.total_s,
            o.feed_s,
            o.rapid_s,
            o.vertical_s,
            o.feed_length_mm,
            o.rapid_length_mm,
            o.total_s / f.total_s
        );
    }
}
