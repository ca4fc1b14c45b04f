//! End to end for the program's frame: every program the CLI writes (slot `export`, `corner
//! --export`, `pocket --export`) with tool 7, work offset G55, clearance 25 mm and inch units
//! passes LinuxCNC's `rs274` (LinuxCNC, Fanuc-style and GRBL), which must report the inch units,
//! G55, tool 7 and the clearance; the motion it prints, converted to mm, agrees move by move
//! with the core's back-plot of the same text (which reads G20 and converts), and follows the
//! plan (slot) or the metric program of the same command (corner, pocket) within the rounding
//! of both. Sinumerik programs (G700) are not read by rs274: their back-plot is compared with
//! the back-plot of the metric Sinumerik program.
//!
//! rs274's built-in tool table has no tool 7: it is run with a two-line table (`-t`).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;

use nc_common::{Motion, check_cut, cut, length, motions, ordered_deviation, sample};
use std::path::{Path, PathBuf};
use std::process::Command;
use trochoplan_core::geom::P2;
use trochoplan_core::nc::{Dialect, backplot, read_toolpath};
use trochoplan_core::toolpath::MoveKind;
use trochoplan_core::{Job, plan};

const MM_PER_INCH: f64 = 25.4;
/// The flags under test (the acceptance).
const FRAME: [&str; 8] = ["--tool-number", "7", "--work-offset", "G55", "--clearance", "25", "--units", "inch"];
/// Coordinate quanta (mm): an inch program writes 4 decimals of inch on Fanuc, GRBL and
/// Sinumerik (0.00254 mm), 5 on LinuxCNC; rs274 prints 4 decimals whatever the units, so
/// 0.0001 inch is the quantum of every motion read back through it.
const Q_INCH_MM: f64 = 1e-4 * MM_PER_INCH;
const Q_MM: f64 = 1e-3;
/// rs274's print rounds the written value by at most half its last digit: 0.00005 inch.
const PRINT_MM: f64 = 0.5 * Q_INCH_MM;
/// Cut depth of every program here (the default job's a_p, `corner`/`pocket --depth`), mm.
const DEPTH: f64 = 6.0;

fn cli(args: &[&str]) {
    let out = Command::new(env!("CARGO_BIN_EXE_trochoplan")).args(args).output().expect("run trochoplan");
    assert!(out.status.success(), "trochoplan {args:?}: {}", String::from_utf8_lossy(&out.stderr));
}

/// Write the program of `command` (`export`, `corner` or `pocket`) for `dialect`, with the
/// frame flags when `inch`; returns its file.
fn program(dir: &Path, command: &str, dialect: &str, inch: bool, polygon: &Path) -> PathBuf {
    let file = dir.join(format!("{command}_{dialect}_{}.nc", if inch { "inch" } else { "mm" }));
    let f = file.to_str().expect("utf-8");
    let mut args: Vec<&str> = vec![command, "--dialect", dialect];
    match command {
        "export" => args.extend(["-o", f]),
        "corner" => args.extend(["--spacing", "1", "--export", f]),
        _ => args.extend(["--polygon", polygon.to_str().expect("utf-8"), "--spacing", "1", "--export", f]),
    }
    if inch {
        args.extend(FRAME);
    }
    cli(&args);
    file
}

/// rs274 on `file` with a tool table holding tools 1 and 7; its canonical output.
fn rs274_with_tools(file: &Path) -> String {
    nc_common::rs274_with_tools(file, "T1 P1 D10.0 Z0 ;tool 1\nT7 P7 D10.0 Z0 ;tool 7\n")
}

/// Motions in inch scaled to mm.
fn to_mm(m: &[Motion]) -> Vec<Motion> {
    let s = |p: [f64; 3]| p.map(|v| v * MM_PER_INCH);
    m.iter()
        .map(|m| match *m {
            Motion::Rapid { start, end } => Motion::Rapid { start: s(start), end: s(end) },
            Motion::Line { start, end } => Motion::Line { start: s(start), end: s(end) },
            Motion::Arc { start, end, center, turns } => {
                Motion::Arc { start: s(start), end: s(end), center: center * MM_PER_INCH, turns }
            }
        })
        .collect()
}

/// The back-plot of `text` agrees with rs274's motions (mm) move by move: the same kind (rapid
/// or feed) and end points within rs274's print rounding. rs274 starts at the origin, so its
/// first two moves (up to the clearance, then to the path start) start where the back-plot
/// knows no position yet and have no move there.
fn backplot_agrees(label: &str, text: &str, dialect: Dialect, rs: &[Motion]) {
    let bp = read_toolpath(text, dialect).unwrap_or_else(|e| panic!("{label}: {e}"));
    assert_eq!(rs.len(), bp.moves.len() + 2, "{label}: rs274 and back-plot move counts");
    for (k, (r, b)) in rs[2..].iter().zip(&bp.moves).enumerate() {
        let rapid = matches!(r, Motion::Rapid { .. });
        assert_eq!(rapid, b.kind == MoveKind::Rapid, "{label}: move {k}: {r:?} vs {b:?}");
        // an arc's segment ends at its start radius; the written end is where the next move
        // starts (the last move is the final retract, a line)
        let end = bp.moves.get(k + 1).map_or(b.segment.end(), |n| n.segment.start());
        let e = r.end();
        let d = [(e[0] - end.x).abs(), (e[1] - end.y).abs(), (e[2] - b.z_end_mm).abs()];
        assert!(d.iter().all(|&d| d <= PRINT_MM + 1e-9), "{label}: move {k} ends {e:?} vs {end:?} z {}", b.z_end_mm);
    }
}

/// What rs274 says about the frame: inch units, G55 (work offset 2), tool 7 where the dialect
/// calls tools, and the first move up to the 25 mm clearance (within the written rounding,
/// half a quantum, plus rs274's print rounding: one inch quantum at most).
fn frame_is_read(label: &str, canon: &str, dialect: &str, rs: &[Motion]) {
    assert!(canon.contains("USE_LENGTH_UNITS(CANON_UNITS_INCHES)"), "{label}: no inch units");
    assert!(canon.contains("SET_G5X_OFFSET(2,"), "{label}: G55 not selected");
    if dialect != "grbl" {
        assert!(canon.contains("SELECT_TOOL(7)"), "{label}: tool 7 not selected");
    }
    let z = rs[0].end()[2];
    assert!((z - 25.0).abs() <= Q_INCH_MM, "{label}: first move to Z {z} mm, not the clearance 25 mm");
}

fn rectangle(dir: &Path) -> PathBuf {
    let f = dir.join("rect.txt");
    std::fs::write(&f, "0,0\n60,0\n60,40\n0,40\n").expect("polygon");
    f
}

#[test]
fn inch_programs_with_tool_7_g55_and_25_mm_clearance_pass_rs274_and_agree_with_the_backplot() {
    let dir = tempfile::tempdir().expect("tempdir");
    let polygon = rectangle(dir.path());
    let slot = plan(&Job::default()).expect("default job");
    for command in ["export", "corner", "pocket"] {
        for (dialect, d) in [("linuxcnc", Dialect::LinuxCnc), ("fanuc", Dialect::Fanuc), ("grbl", Dialect::Grbl)] {
            let label = format!("{command} {dialect} inch");
            let file = program(dir.path(), command, dialect, true, &polygon);
            let text = std::fs::read_to_string(&file).expect("read");
            let canon = rs274_with_tools(&file);
            let rs = to_mm(&motions(&canon));
            frame_is_read(&label, &canon, dialect, &rs);
            backplot_agrees(&label, &text, d, &rs);
            // read back like a metric program: the cut at depth follows the plan (slot) or the
            // metric program's cut (corner, pocket) within the rounding of both
            let c = cut(&rs, DEPTH, PRINT_MM + 1e-9);
            if command == "export" {
                check_cut(&label, &c, &slot, 0.005, Q_INCH_MM).unwrap_or_else(|e| panic!("{e}"));
            } else {
                let metric = program(dir.path(), command, dialect, false, &polygon);
                let m = motions(&nc_common::interpret(&metric).unwrap_or_else(|e| panic!("{e}")));
                same_cut(&label, &c, &cut(&m, DEPTH, 1e-4));
            }
        }
    }
}

/// Largest distance between two back-plot polylines, both ways, matched in order.
fn polyline_distance(a: &[P2], b: &[P2]) -> f64 {
    ordered_deviation(a, b, 400).max(ordered_deviation(b, a, 400))
}

/// Two programs of the same plan in different units cut the same: their cuts (sampled every
/// 0.02 mm) within the rounding of both (each within 3 quanta of the plan, see
/// `nc_common::budget`) plus the sampling's chords (1 µm on the back-plot's own chords, up to
/// 1.5 µm where a 0.005 mm corner arc is one chord: 2 µm), and the same length within 0.1 %.
fn same_cut(label: &str, inch: &[Motion], metric: &[Motion]) {
    let allowed = 3.0 * (Q_INCH_MM + Q_MM) + 2e-3;
    let d = polyline_distance(&sample(inch, 0.02), &sample(metric, 0.02));
    assert!(d <= allowed, "{label}: {d} mm from the metric program's cut (> {allowed})");
    let (a, b) = (length(inch), length(metric));
    assert!((a - b).abs() <= 1e-3 * b, "{label}: length {a} vs metric {b} mm");
}

#[test]
fn sinumerik_inch_programs_backplot_as_their_metric_programs() {
    let dir = tempfile::tempdir().expect("tempdir");
    let polygon = rectangle(dir.path());
    for command in ["export", "corner", "pocket"] {
        let read = |inch: bool| {
            let f = program(dir.path(), command, "sinumerik", inch, &polygon);
            std::fs::read_to_string(f).expect("read")
        };
        let (inch, metric) = (read(true), read(false));
        assert!(inch.contains("G700") && inch.contains("\nG55\n") && inch.contains("\nT7 D1\n"), "{inch}");
        let pts = |t: &str| backplot(t, Dialect::Sinumerik, 1e-3).unwrap_or_else(|e| panic!("{command}: {e}"));
        let (a, b) = (pts(&inch), pts(&metric));
        // both within half a quantum of the same planned points, plus the chords' 1 µm sagitta
        let allowed = 3.0 * (Q_INCH_MM + Q_MM) + 2e-3;
        let d = polyline_distance(&a, &b);
        assert!(d <= allowed, "{command}: inch back-plot {d} mm from the metric one (> {allowed})");
        // and the clearance: 25 mm = 0.9843 inch
        assert!(inch.contains("G0 Z0.9843\n"), "{command}: {inch}");
    }
}
