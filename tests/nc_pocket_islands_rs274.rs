//! Pockets with islands end to end: `trochoplan pocket --polygon FILE` with the islands as the
//! loops after the boundary, `--export` a LinuxCNC program read back through `rs274`. The
//! acceptance pocket: 80 × 60 with a Ø20 round boss (centre (25, 30)) and a 15 × 30
//! rectangular island (x 50..65, y 15..45), D 10, depth 4, the defaults otherwise (a_e 2.5:
//! target 60°). Checked here from the JSON and the program alone: the peak over every move
//! ≤ 60° and ≤ the target + 1°, the 95th percentile ≤ the target, the program retraces the
//! planned moves, no rapid below the safe height but on the planned path at depth, and every
//! point of the cut keeps the tool centre inside the boundary, outside both islands and at
//! least r − 0.005 mm from every wall and island edge (distances computed here from the
//! polygon file). Then the bad inputs: each is refused naming what is wrong.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod islands_common;
#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;
mod pocket_common;

use islands_common::{boss, least_clearance, loop_distance, rect, run};
use nc_common::{Motion, check_path_cut, cut, interpret, motions, sample};
use std::path::Path;
use trochoplan_core::geom::{P2, Segment, p2};

/// Tool radius (D 10), depth and safe height of the program (mm).
const R: f64 = 5.0;
const DEPTH: f64 = 4.0;
const SAFE_Z: f64 = 5.0;

/// The boss's vertices as a drawing's export gives them, rounded to 1e-6 mm: the pocket is the
/// same to the eye, but the planner's choices (the helix's place between the two equal gaps
/// above and below the boss, the order of the runs) differ, so the checks see another plan.
fn rounded(v: &[P2]) -> Vec<P2> {
    v.iter().map(|p| p2((p.x * 1e6).round() / 1e6, (p.y * 1e6).round() / 1e6)).collect()
}

#[test]
fn a_pocket_with_a_boss_and_a_rectangular_island_passes_rs274_within_the_target_and_off_the_islands() {
    let dir = tempfile::tempdir().expect("tempdir");
    let boundary = rect(0.0, 0.0, 80.0, 60.0);
    for (label, boss) in [("exact", boss()), ("rounded", rounded(&boss()))] {
        check_islands_program(dir.path(), label, &boundary, &[boss, rect(50.0, 15.0, 65.0, 45.0)]);
    }
}

/// A 10 × 10 island in the middle of the 60 × 40 rectangle: the growth goes round it through
/// the necks above and below (4.6 mm of tool centres each) and closes on its far side, with
/// stock between its arms and the island until it is reached (a jump there reads 180°).
#[test]
fn an_island_in_the_middle_is_cleared_round_within_the_target() {
    let dir = tempfile::tempdir().expect("tempdir");
    check_islands_program(dir.path(), "middle", &rect(0.0, 0.0, 60.0, 40.0), &[rect(25.0, 15.0, 35.0, 25.0)]);
}

/// The acceptance checks (module docs) of the pocket `boundary` with `islands`.
fn check_islands_program(dir: &Path, label: &str, boundary: &[P2], islands: &[Vec<P2>]) {
    let boundary = boundary.to_vec();
    let loops: Vec<Vec<P2>> = std::iter::once(boundary.clone()).chain(islands.iter().cloned()).collect();
    let nc = dir.join(format!("{label}.ngc"));
    let (ok, stdout, stderr) =
        run(dir, label, &loops, &["--depth", "4", "--export", nc.to_str().expect("utf-8"), "--dialect", "linuxcnc"]);
    assert!(ok, "{label}: {stderr}");
    let json: serde_json::Value = serde_json::from_str(&stdout).expect("json");
    assert_eq!(json["islands"].as_u64(), Some(islands.len() as u64), "{}", json["islands"]);
    for (k, island) in islands.iter().enumerate() {
        assert_eq!(json["island_polygons"][k].as_array().map(Vec::len), Some(island.len()));
    }
    assert_eq!(json["method"], "adaptive");
    // the target of a_e = 2.5, D = 10: the straight cut's arccos(1 − 2.5/5) = 60° (above the
    // 50° cap of the area-rate default, so the straight cut's)
    let target = json["target_deg"].as_f64().expect("target");
    assert!((target - 60.0).abs() < 1e-9, "{target}");
    let peak = json["max_engagement_deg"].as_f64().expect("peak");
    let p95 = json["p95_engagement_deg"].as_f64().expect("p95");
    // (the rings on straight walls and the corner-point arcs are planned to the target itself:
    // the evaluator reads them to within 1e-3°)
    assert!(peak <= 60.0 + 1e-3 && peak <= target + 1.0, "{label}: peak {peak}");
    assert!(p95 <= target, "{label}: p95 {p95}");
    // every kind of move, entries included, within the target + 1°
    for row in json["by_kind"].as_array().expect("by_kind") {
        assert!(row["max_engagement_deg"].as_f64().is_some_and(|m| m <= target + 1.0), "{row}");
    }
    // the program: rs274 runs it; no rapid below the safe height but at depth on the path
    let canon = interpret(&nc).unwrap_or_else(|e| panic!("rs274: {e}"));
    let all = motions(&canon);
    for m in &all {
        if let Motion::Rapid { start, end } = m {
            if (start[2] + DEPTH).abs() < 1e-4 && (end[2] + DEPTH).abs() < 1e-4 {
                continue;
            }
            assert!(start[2] >= SAFE_Z - 1e-4 || end[2] >= SAFE_Z - 1e-4, "rapid below safe Z: {m:?}");
            assert!(end[2] >= SAFE_Z - 1e-4 || (end[0] == start[0] && end[1] == start[1]), "{m:?}");
        }
    }
    let c = cut(&all, DEPTH, 1e-4);
    let planned: Vec<Segment> = serde_json::from_value(json["segments"].clone()).expect("segments");
    check_path_cut(label, &c, &planned, 0.005, 1e-4).unwrap_or_else(|e| panic!("{e}"));
    // every point of the cut, every 0.02 mm: inside the boundary, outside the islands, at least
    // r − 0.005 mm from every wall and island edge
    let least = least_clearance(&sample(&c, 0.02), &boundary, islands).unwrap_or_else(|e| panic!("{label}: {e}"));
    assert!(least >= R - 0.005, "{label}: the tool centre comes {least:.6} mm from a wall or island (r = {R})");
    // the islands are gone round: the cut comes within r + the finishing stock + 0.01 mm of each
    for island in islands {
        let near = sample(&c, 0.5).iter().map(|&p| loop_distance(p, island)).fold(f64::INFINITY, f64::min);
        assert!(near <= R + 0.01, "nearest pass {near} mm from an island: not finished round it");
    }
}

#[test]
fn bad_islands_are_refused_by_name() {
    let dir = tempfile::tempdir().expect("tempdir");
    let boundary = rect(0.0, 0.0, 80.0, 60.0);
    // (from a file, the reader refuses loops that touch or cross, naming both loops; the
    // request's `islands` are checked by the planner: its unit tests)
    for (name, loops, what) in [
        (
            "touching",
            vec![boundary.clone(), rect(0.0, 10.0, 20.0, 20.0)],
            "loop 1 (lines 1-4) and loop 2 (lines 6-9) cross or touch",
        ),
        (
            "crossing",
            vec![boundary.clone(), rect(-5.0, 10.0, 20.0, 20.0)],
            "loop 1 (lines 1-4) and loop 2 (lines 6-9) cross or touch",
        ),
        (
            "overlapping",
            vec![boundary.clone(), rect(10.0, 10.0, 30.0, 30.0), rect(20.0, 20.0, 40.0, 40.0)],
            "loop 2 (lines 6-9) and loop 3 (lines 11-14) cross or touch",
        ),
        ("separate pockets", vec![boundary.clone(), rect(100.0, 10.0, 120.0, 20.0)], "separate pockets"),
        (
            "nested",
            vec![boundary.clone(), rect(10.0, 10.0, 50.0, 50.0), rect(20.0, 20.0, 30.0, 30.0)],
            "a loop lies inside an island",
        ),
    ] {
        let (ok, _, stderr) = run(dir.path(), &name.replace(' ', "_"), &loops, &[]);
        assert!(!ok, "{name}: accepted");
        assert!(stderr.contains(what), "{name}: {stderr}");
    }
    // the other methods refuse islands, naming the method and adaptive clearing
    let loops = [boundary, rect(30.0, 20.0, 50.0, 40.0)];
    for method in ["plain", "variable", "isometric", "medial-axis", "slot"] {
        let (ok, _, stderr) = run(dir.path(), method, &loops, &["--method", method]);
        assert!(!ok, "{method}: accepted");
        assert!(
            stderr.contains("islands") && stderr.contains(&format!("--method {method}")) && stderr.contains("adaptive"),
            "{method}: {stderr}"
        );
    }
}
