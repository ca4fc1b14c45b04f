//! Rest machining end to end: the 60 × 40 rectangle cleared by D 16, then by D 6 with
//! `--rest-from 16`, against the full D 6 clearing; the three programs are read back through
//! LinuxCNC's `rs274` and measured on what they cut, not on the plans.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;
mod pocket_common;

use nc_common::{cut, interpret, length, motions, segments_of};
use pocket_common::{DEPTH, check_pocket_program, export, pocket_export};
use std::f64::consts::TAU;
use trochoplan_core::geom::{P2, Polygon, Segment, p2};

const RECT: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)];
/// a_e / D = 0.25 for both tools, the ratio of the CLI's defaults (D 10, a_e 2.5).
const STEP_OVER: &str = "1.5";

/// Distance from `q` to a line or arc.
fn distance(q: P2, s: &Segment) -> f64 {
    match *s {
        Segment::Line { start, end } => {
            let v = end - start;
            let vv = v.dot(&v);
            let t = if vv > 0.0 { ((q - start).dot(&v) / vv).clamp(0.0, 1.0) } else { 0.0 };
            (q - (start + v * t)).norm()
        }
        Segment::Arc { center, radius, start_angle, sweep } => {
            let v = q - center;
            let from = if sweep >= 0.0 { v.y.atan2(v.x) - start_angle } else { start_angle - v.y.atan2(v.x) };
            if from.rem_euclid(TAU) <= sweep.abs() {
                (v.norm() - radius).abs()
            } else {
                (q - s.start()).norm().min((q - s.end()).norm())
            }
        }
        Segment::Trochoid { .. } => panic!("no trochoid read back"),
    }
}

/// The cut at depth of a program, read back through rs274.
fn read_back(file: &std::path::Path) -> (Vec<Segment>, f64) {
    let c = cut(&motions(&interpret(file).expect("rs274")), DEPTH, 1e-4);
    (segments_of(&c), length(&c))
}

#[test]
fn rest_machining_after_d16_clears_the_corners_d6_reaches_in_a_fraction_of_the_length() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d16 = export(dir.path(), "d16.ngc", RECT, &["--tool-diameter", "16", "--step-over", STEP_OVER]);
    let full = export(dir.path(), "d6.ngc", RECT, &["--tool-diameter", "6", "--step-over", STEP_OVER]);
    let rest =
        export(dir.path(), "rest.ngc", RECT, &["--tool-diameter", "6", "--step-over", STEP_OVER, "--rest-from", "16"]);
    // the rest program passes rs274, retraces its plan and keeps r from the walls
    check_pocket_program("rest", &rest, RECT, 3.0, 0.005, 4);
    let (big_cut, _) = read_back(&d16.file);
    let (full_cut, full_len) = read_back(&full.file);
    let (rest_cut, rest_len) = read_back(&rest.file);
    eprintln!("at depth: full D 6 {full_len:.1} mm, rest {rest_len:.1} mm ({:.1} %)", 100.0 * rest_len / full_len);
    assert!(rest_len <= 0.3 * full_len, "rest {rest_len:.1} mm > 30 % of {full_len:.1} mm");
    // the JSON names the larger tool and the full clearing's length (the plan's; the read-back
    // length above is the program's, written to 4 decimals: within 0.1 %)
    assert_eq!(rest.json["rest_from_mm"].as_f64(), Some(16.0));
    let planned_full = rest.json["rest_full_length_mm"].as_f64().expect("rest_full_length_mm");
    assert!((planned_full - full_len).abs() <= 1e-3 * full_len, "{planned_full} vs {full_len}");
    // peaks over every move within the target + 1°, measured by the evaluator over the rest
    // stock (the plan's own measurement; read back below)
    let target = rest.json["target_deg"].as_f64().expect("target");
    let peak = rest.json["max_engagement_deg"].as_f64().expect("peak");
    assert!(peak <= target + 1.0, "peak {peak:.2}° > target {target:.2}° + 1°");
    // every corner cleared to what D 6 reaches: on a 0.05 mm grid over each 12 × 12 mm corner
    // square, a point the full D 6 clearing cuts (within 3 mm of its centre path) is cut by
    // D 16 (within 8 mm of its path) or by the rest path (within 3 mm), up to 1e-3 mm: the
    // sliver a dropped move may have cut, whose engagement read at most 1°, is at most
    // r·(1 − cos 1°) = 4.6e-4 mm thick, plus the program's rounding 0.5e-4·√2 mm
    let slack = 3.0 * (1.0 - 1f64.to_radians().cos()) + 0.5e-4 * 2f64.sqrt();
    assert!(slack < 1e-3);
    let near = |segs: &[Segment], q: P2, reach: f64| segs.iter().any(|s| distance(q, s) <= reach);
    let corners = [p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 40.0), p2(0.0, 40.0)];
    let (h, side) = (0.05, 12.0);
    let n = (side / h) as i32;
    for c in corners {
        let toward = p2(if c.x > 30.0 { -1.0 } else { 1.0 }, if c.y > 20.0 { -1.0 } else { 1.0 });
        // the paths near this corner only (every cut point in the square is within 8 mm of it)
        let close = |segs: &[Segment]| -> Vec<Segment> {
            let mid = c + toward * (0.5 * side);
            segs.iter().copied().filter(|s| distance(mid, s) <= 0.5 * side * 2f64.sqrt() + 8.0).collect()
        };
        let (big, full_c, rest_c) = (close(&big_cut), close(&full_cut), close(&rest_cut));
        let (mut reached, mut missed, mut left_by_big) = (0usize, 0usize, 0usize);
        for i in 0..n {
            for j in 0..n {
                let q = c + p2(toward.x * (i as f64 + 0.5) * h, toward.y * (j as f64 + 0.5) * h);
                if !near(&full_c, q, 3.0) {
                    continue;
                }
                reached += 1;
                if near(&big, q, 8.0) {
                    continue;
                }
                left_by_big += 1;
                if !near(&rest_c, q, 3.0 + slack) {
                    missed += 1;
                }
            }
        }
        eprintln!("corner {c:?}: {reached} points D 6 reaches, {left_by_big} of them left by D 16, {missed} missed");
        assert!(left_by_big > 0, "corner {c:?}: D 16 leaves material D 6 reaches");
        assert_eq!(missed, 0, "corner {c:?}: {missed} points D 6 reaches left uncut by the rest path");
    }
    // the read-back rest path over the rest stock: the pocket less D 16's read-back cut (as
    // the smaller tool's evaluator reads it, `swept_as`, whose cover is tested in the core)
    use trochoplan_core::engagement::{EvaluatorOptions, engagement_profile};
    let stock = Polygon::new(RECT.iter().map(|&(x, y)| p2(x, y)).collect()).expect("polygon");
    let before = trochoplan_core::pocket::rest::swept_as(&big_cut, 3.0, 8.0);
    let prof = engagement_profile(&stock, &before, &rest_cut, &EvaluatorOptions::new(3.0, 0.25)).expect("profile");
    // every run of the rest path starts in cleared stock (straight down): nothing is cut
    // before the tool moves; the peak within the target + 1° and the plan's within 0.5°
    // (the program's rounding, as in `nc_pocket_rs274`)
    let read = prof.max_angle().to_degrees();
    eprintln!("rest read back: peak {read:.2}° (plan {peak:.2}°, target {target:.2}°)");
    assert!(read <= target + 1.0 + 0.5, "read back {read:.2}° at {:?}", prof.max());
}

#[test]
fn rest_from_is_refused_by_name() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (label, extra) in [
        ("equal", vec!["--rest-from", "6"]),
        ("smaller", vec!["--rest-from", "4"]),
        ("nan", vec!["--rest-from", "NaN"]),
        ("method", vec!["--rest-from", "16", "--method", "plain"]),
    ] {
        let mut args = vec!["--tool-diameter", "6", "--step-over", STEP_OVER];
        args.extend(extra);
        // refused before any planning, naming the flag; no program written
        let e = pocket_export(dir.path(), &format!("{label}.ngc"), RECT, &args);
        assert!(e.is_none(), "{label}: accepted");
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_trochoplan"))
            .args(["pocket", "--polygon"])
            .arg(dir.path().join(format!("{label}.ngc.poly")))
            .args(&args)
            .output()
            .expect("run");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{label}: {err}");
        assert!(err.contains("rest-from"), "{label}: {err}");
        if label != "method" {
            assert!(err.contains("larger than the tool diameter 6 mm"), "{label}: {err}");
        } else {
            assert!(err.contains("--method adaptive"), "{label}: {err}");
        }
        assert!(!dir.path().join(format!("{label}.ngc")).exists(), "{label}: a program was written");
    }
}

/// In levels, a rest pass is measured on every level over the stock the larger tool left
/// there, not over the uncut pocket: the same path over the same stock, so each level's peak
/// is the plan's own `max_engagement_deg`.
#[test]
fn rest_machining_in_levels_is_measured_over_the_stock_the_larger_tool_left() {
    let dir = tempfile::tempdir().expect("tempdir");
    let args =
        ["--tool-diameter", "6", "--step-over", STEP_OVER, "--rest-from", "16", "--depth", "6", "--max-step-down", "3"];
    let rest = export(dir.path(), "rest-levels.ngc", RECT, &args);
    let peak = rest.json["max_engagement_deg"].as_f64().expect("peak");
    let levels = rest.json["levels"].as_array().expect("levels");
    assert_eq!(levels.len(), 2, "6 mm in levels of at most 3 mm");
    for l in levels {
        assert_eq!(l["max_engagement_deg"].as_f64(), Some(peak), "{l}");
    }
    assert_eq!(rest.json["levels_max_engagement_deg"].as_f64(), Some(peak));
}
