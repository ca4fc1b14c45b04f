//! End to end for slots in several levels: `trochoplan export --max-step-down … [--closed]`
//! in every dialect rs274 reads (LinuxCNC, Fanuc-style ISO, GRBL), read back through LinuxCNC's
//! `rs274` (harness of `nc_rs274.rs`), and checked from the motion read back alone:
//!
//! - the closed 60 × 10 keyway 12 mm deep, D 8, in 3 levels of 4 mm: no plunge into stock
//!   (every descent below the stock top or below what has been cut is a helical arc inside the
//!   slot; every straight descent ends in air or above the floor already cut, inside the slot),
//!   the tool centre r from both end walls, each level retracing the planned moves, and the
//!   engagement over every move read back (the evaluator over the stock around the slot, with
//!   what the helix bored as cut) at most the steady-state cycle's engagement + 1°;
//! - the open slot in 3 levels: every descent outside the stock, each level retracing the
//!   planned path.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;

use nc_common::{Motion, check_cut, check_path_cut, cut, interpret, motions, sample, segments_of};
use std::path::{Path, PathBuf};
use std::process::Command;
use trochoplan_core::engagement::{EvaluatorOptions, Stock, measure};
use trochoplan_core::geom::{Polygon, Segment, p2};
use trochoplan_core::path::closed::ClosedSlot;
use trochoplan_core::toolpath::{Move, MoveKind, Toolpath};
use trochoplan_core::{Job, plan};

const KEYWAY: [&str; 12] = [
    "--slot-width",
    "10",
    "--slot-length",
    "60",
    "--depth",
    "12",
    "--tool-diameter",
    "8",
    "--max-step-down",
    "4",
    "--closed",
    "--dialect",
];

const DIALECTS: [(&str, &str, i32); 3] = [("linuxcnc", "ngc", 4), ("fanuc", "nc", 3), ("grbl", "gcode", 3)];

fn run(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_trochoplan")).args(args).output().expect("run trochoplan")
}

fn export(dir: &Path, name: &str, args: &[&str]) -> PathBuf {
    let file = dir.join(name);
    let mut all = vec!["export"];
    all.extend_from_slice(args);
    let out = Command::new(env!("CARGO_BIN_EXE_trochoplan")).args(&all).arg("-o").arg(&file).output().expect("run");
    assert!(out.status.success(), "export {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    file
}

fn keyway_job() -> Job {
    Job {
        slot_width: 10.0,
        slot_length: 60.0,
        depth: 12.0,
        tool_diameter: 8.0,
        max_step_down: Some(4.0),
        closed: true,
        ..Job::default()
    }
}

/// Whether the motion moves down (by more than the rounding).
fn descends(m: &Motion, q: f64) -> bool {
    m.end()[2] < m.start()[2] - q
}

#[test]
fn the_closed_keyway_in_three_levels_never_plunges_and_stays_within_the_target() {
    let dir = tempfile::tempdir().expect("tempdir");
    let job = keyway_job();
    let (r, a, l) = (4.0, 1.0, 60.0);
    // The target: the steady-state cycle's engagement of `analyze` (the tooth series against the
    // previous cycle's edge, independent of the evaluator used below).
    let analyze: Vec<&str> = ["analyze"].into_iter().chain(KEYWAY[..11].iter().copied()).collect();
    let out = run(&analyze);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let target = json["engagement_max_deg"].as_f64().expect("target");
    assert_eq!(json["level_count"], 3);
    assert_eq!(json["slot_ends"], "closed");
    assert!(json["levels_engagement_peak_deg"].as_f64().expect("peak") <= target + 1.0, "{json}");
    let planned: Vec<Segment> =
        ClosedSlot::for_job(&job.validate().expect("valid")).moves().iter().map(|m| m.0).collect();
    // the stock: the slot with D of material around it, beyond both ends too
    let stock = Polygon::new(vec![p2(-13.0, -8.0), p2(13.0, -8.0), p2(13.0, 68.0), p2(-13.0, 68.0)]).expect("stock");
    for (dialect, ext, decimals) in DIALECTS {
        let q = 10f64.powi(-decimals) + 1e-4;
        let mut args = KEYWAY.to_vec();
        args.push(dialect);
        let file = export(dir.path(), &format!("keyway.{ext}"), &args);
        let all = motions(&interpret(&file).unwrap_or_else(|e| panic!("{e}")));
        // No plunge: the floor cut so far (the lowest feed move; the whole slot is cut to it
        // before the next level's descent) bounds every straight descent; below it only the
        // helix descends, inside the slot, at most 0.1·D a turn (half a turn a block).
        let mut floor = 0.0f64;
        let mut helix_arcs = 0;
        for m in &all {
            let (s, e) = (m.start(), m.end());
            let inside = |x: f64, y: f64| x.abs() <= a + q && y >= r - q && y <= l - r + q;
            if descends(m, q) {
                match m {
                    Motion::Arc { .. } => {
                        assert!(inside(s[0], s[1]) && inside(e[0], e[1]), "{dialect}: helix off the slot {m:?}");
                        assert!(s[2] - e[2] <= 0.5 * 0.8 + q, "{dialect}: half a helix turn drops {}", s[2] - e[2]);
                        helix_arcs += 1;
                    }
                    _ => {
                        assert!(
                            e[2] >= floor - q,
                            "{dialect}: straight descent to Z{} below the cut floor {floor}",
                            e[2]
                        );
                        assert!(e[2] >= -q || inside(e[0], e[1]), "{dialect}: straight descent into stock {m:?}");
                    }
                }
            }
            if !matches!(m, Motion::Rapid { .. }) {
                floor = floor.min(e[2]);
            }
            // every feed move below the top keeps the tool centre in the slot: r from both ends
            if !matches!(m, Motion::Rapid { .. }) && e[2] < -q {
                for pt in sample(&[*m], 0.05) {
                    assert!(inside(pt.x, pt.y), "{dialect}: tool centre at ({}, {}) beyond the slot", pt.x, pt.y);
                }
            }
        }
        assert!(helix_arcs >= 3, "{dialect}: a helix per level");
        // every level: its moves retrace the plan; the engagement over every move read back
        let opts = EvaluatorOptions::new(r, 0.08);
        for (k, z) in [4.0, 8.0, 12.0].into_iter().enumerate() {
            let level = cut(&all, z, 1e-4);
            check_path_cut(&format!("{dialect} level {}", k + 1), &level, &planned, 0.005, 10f64.powi(-decimals))
                .unwrap_or_else(|e| panic!("{e}"));
            // what the helix of this level bored: its arcs ending between the level above and this one
            let bore: Vec<Segment> = all
                .iter()
                .filter(|m| matches!(m, Motion::Arc { .. }) && descends(m, q))
                .filter(|m| m.end()[2] < -(z - 4.0) + q && m.end()[2] > -z - q)
                .flat_map(|m| segments_of(&[*m]))
                .collect();
            assert!(!bore.is_empty(), "{dialect} level {}: helix", k + 1);
            let segs = segments_of(&level);
            let moves = segs
                .iter()
                .map(|&segment| Move {
                    segment,
                    z_start_mm: -z,
                    z_end_mm: -z,
                    kind: MoveKind::Cut,
                    feed_mm_per_min: None,
                })
                .collect();
            let tp = Toolpath { moves, entries: Vec::new(), retract_before: Vec::new() };
            let m = measure(&tp, Stock { polygon: &stock, precut: &bore, islands: &[] }, &opts).expect("measure");
            let peak = m.max_engagement_rad.to_degrees();
            assert!(peak <= target + 1.0, "{dialect} level {}: {peak}° > {target}° + 1°", k + 1);
        }
    }
}

#[test]
fn the_open_slot_in_levels_enters_every_level_outside_the_stock() {
    let dir = tempfile::tempdir().expect("tempdir");
    let job = Job { max_step_down: Some(2.5), ..Job::default() };
    let p = plan(&Job { max_step_down: None, ..job.clone() }).expect("plan");
    for (dialect, ext, decimals) in DIALECTS {
        let q = 10f64.powi(-decimals) + 1e-4;
        let file = export(dir.path(), &format!("open.{ext}"), &["--max-step-down", "2.5", "--dialect", dialect]);
        let all = motions(&interpret(&file).unwrap_or_else(|e| panic!("{e}")));
        // 6 mm in ⌈6 / 2.5⌉ = 3 levels of 2 mm, each the whole planned path
        for z in [2.0, 4.0, 6.0] {
            check_cut(&format!("{dialect} Z-{z}"), &cut(&all, z, 1e-4), &p, 0.005, 10f64.powi(-decimals))
                .unwrap_or_else(|e| panic!("{e}"));
        }
        assert!(cut(&all, 2.5, 1e-4).is_empty(), "{dialect}: equal levels, not 2.5 mm");
        let descents: Vec<&Motion> = all.iter().filter(|m| descends(m, q) && m.end()[2] < -q).collect();
        assert_eq!(descents.len(), 3, "{dialect}");
        for m in descents {
            // straight down beside the open end: the tool's disc (r = 5) off the stock y ≥ 0
            assert!(!matches!(m, Motion::Arc { .. }) && m.end()[1] + 5.0 < 0.0, "{dialect}: {m:?}");
        }
    }
}

#[test]
fn bad_levels_and_closed_slots_are_refused_naming_the_flag() {
    for (args, flag) in [
        (&["--max-step-down", "0"][..], "max-step-down"),
        (&["--max-step-down", "-2"][..], "max-step-down"),
        (&["--max-step-down", "NaN"][..], "max-step-down"),
        (&["--closed", "--slot-length", "8"][..], "slot-length"),
        (&["--closed", "--slot-width", "10.4", "--step", "0.5"][..], "slot-width"),
    ] {
        for cmd in ["analyze", "export"] {
            let mut all = vec![cmd];
            all.extend_from_slice(args);
            if cmd == "export" {
                all.extend_from_slice(&["--dialect", "linuxcnc", "-o", "/dev/null"]);
            }
            let out = run(&all);
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(!out.status.success() && err.contains(flag) && err.contains("must be"), "{all:?}: {err}");
        }
    }
}
