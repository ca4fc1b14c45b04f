//! Pockets in several depths end to end: `trochoplan pocket --depth 12 --max-step-down 4` of
//! the pocket with islands (80 × 60, a Ø20 round boss about (25, 30), a 15 × 30 island x 50..65,
//! y 15..45), D 10, the defaults otherwise (a_e 2.5: target 60°), `--export` a LinuxCNC program
//! read back through `rs274`. Checked from the JSON and the program alone: three levels of
//! 4 mm (⌈12/4⌉ = 3) with floors at −4, −8, −12; every level's peak ≤ 60° and ≤ the
//! target + 1°, its p95 ≤ the target; every move in the plane below the stock top at one of the three
//! floors, each floor retracing the planned moves; no plunge into stock: every straight descent
//! below the stock top goes down where the tool has been at least as deep before, every
//! helix or ramp starts 0.5 mm above the floor of the level above it (only the level's new
//! depth is helixed); no rapid below the safe height but those; every point of the cut at
//! least r − 0.005 mm from every wall and island edge (computed here from the polygon file).
//! Then the bad step-downs, each refused naming `max-step-down` and its range.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod islands_common;
#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;
mod pocket_common;

use islands_common::{acceptance_loops, floor_clearances, run};
use nc_common::{Motion, interpret, motions, sample};
use trochoplan_core::geom::{P2, Segment, p2};

/// Tool radius (D 10), safe height of the program (mm), the floors (12 mm in levels of at most
/// 4 mm: ⌈12/4⌉ = 3 levels of 12/3 = 4 mm) and the height above the floor above where each
/// level's helix starts.
const R: f64 = 5.0;
const SAFE_Z: f64 = 5.0;
const FLOORS: [f64; 3] = [-4.0, -8.0, -12.0];
const HELIX_ABOVE: f64 = 0.5;
const Z_TOL: f64 = 1e-4;

fn xy(p: [f64; 3]) -> P2 {
    p2(p[0], p[1])
}

#[test]
fn a_pocket_with_islands_in_three_levels_passes_rs274_level_by_level() {
    let dir = tempfile::tempdir().expect("tempdir");
    let loops = acceptance_loops();
    let nc = dir.path().join("levels.ngc");
    let args = ["--depth", "12", "--max-step-down", "4", "--export", nc.to_str().expect("utf-8")];
    let (ok, stdout, stderr) = run(dir.path(), "levels", &loops, &args);
    assert!(ok, "{stderr}");
    let json: serde_json::Value = serde_json::from_str(&stdout).expect("json");
    assert_eq!(json["method"], "adaptive");
    // the straight cut's arccos(1 − 2.5/5) = 60°
    let target = json["target_deg"].as_f64().expect("target");
    assert!((target - 60.0).abs() < 1e-9, "{target}");
    let levels = json["levels"].as_array().expect("levels");
    assert_eq!(levels.len(), 3);
    for (k, level) in levels.iter().enumerate() {
        let top = if k == 0 { 0.0 } else { FLOORS[k - 1] };
        assert_eq!(level["z_mm"].as_f64(), Some(FLOORS[k]), "{level}");
        assert!(level["top_mm"].as_f64().is_some_and(|t| (t - top).abs() < 1e-12), "{level}");
        assert!(level["axial_depth_mm"].as_f64().is_some_and(|a| (a - 4.0).abs() < 1e-12), "{level}");
        let peak = level["max_engagement_deg"].as_f64().expect("peak");
        let p95 = level["p95_engagement_deg"].as_f64().expect("p95");
        // (the passes along the walls are planned to the target itself: the evaluator reads
        // them to within 1e-3°)
        assert!(peak <= 60.0 + 1e-3 && peak <= target + 1.0, "level {k}: peak {peak}");
        assert!(p95 <= target, "level {k}: p95 {p95}");
    }
    let canon = interpret(&nc).unwrap_or_else(|e| panic!("rs274: {e}"));
    let all = motions(&canon);
    // every move in the plane below the stock top lies at one of the floors; each floor
    // retraces the planned moves, and keeps off the walls and islands
    let planned: Vec<Segment> = serde_json::from_value(json["segments"].clone()).expect("segments");
    for (f, least) in FLOORS.iter().zip(floor_clearances(&all, &FLOORS, Z_TOL, &planned, &loops)) {
        assert!(least >= R - 0.005, "Z{f}: the tool centre comes {least:.6} mm from a wall or island (r = {R})");
    }
    check_no_plunge(&all);
}

/// No descent into stock (module docs): straight descents below the stock top only where the
/// tool has been at least as deep before (points of the earlier moves every 0.05 mm, within
/// 0.05 mm); helices and ramps (descending moves that go sideways) from 0.5 mm above the floor
/// of the level above, down to their level's floor; other rapids on a floor, at or above the
/// safe height, or straight down to above the stock top.
fn check_no_plunge(all: &[Motion]) {
    let mut descents = 0;
    let mut k = 0;
    while k < all.len() {
        let m = &all[k];
        let (s, e) = (m.start(), m.end());
        let descends = e[2] < s[2] - Z_TOL && e[2] < -Z_TOL;
        let sideways = (xy(e) - xy(s)).norm() > 1e-6 || matches!(m, Motion::Arc { .. });
        if descends && sideways {
            // a helix or ramp: the run of descending moves from here
            let start_z = s[2];
            let mut j = k;
            while j + 1 < all.len() && all[j + 1].end()[2] < all[j + 1].start()[2] - Z_TOL {
                j += 1;
            }
            let end_z = all[j].end()[2];
            let level = FLOORS.iter().position(|f| (f - end_z).abs() <= Z_TOL);
            let level = level.unwrap_or_else(|| panic!("a helix from Z{start_z} ends at Z{end_z}, no floor"));
            let above = if level == 0 { 0.0 } else { FLOORS[level - 1] };
            assert!(
                (start_z - (above + HELIX_ABOVE)).abs() <= Z_TOL,
                "the helix to Z{end_z} starts at Z{start_z}, not 0.5 mm above Z{above}"
            );
            descents += 1;
            k = j + 1;
            continue;
        }
        if descends {
            // straight down (rapid or feed): into a hole the tool has cut at least as deep
            let (at, z) = (xy(e), e[2]);
            let been = all[..k]
                .iter()
                .filter(|p| p.start()[2].max(p.end()[2]) <= z + Z_TOL)
                .any(|p| sample(std::slice::from_ref(p), 0.05).iter().any(|q| (q - at).norm() <= 0.05));
            assert!(been, "straight down to Z{z} at ({}, {}) into uncut stock: {m:?}", at.x, at.y);
            descents += 1;
        } else if let Motion::Rapid { .. } = m {
            let on_floor = FLOORS.iter().any(|f| (s[2] - f).abs() <= Z_TOL && (e[2] - f).abs() <= Z_TOL);
            // on a floor through cleared stock, at the safe height, up, or straight down above the stock
            let vertical_above = !sideways && e[2] >= -Z_TOL;
            assert!(
                on_floor || s[2].min(e[2]) >= SAFE_Z - Z_TOL || e[2] > s[2] || vertical_above,
                "a rapid below the safe height: {m:?}"
            );
        }
        k += 1;
    }
    // at least one descent per level
    assert!(descents >= 3, "{descents} descents");
}

#[test]
fn bad_step_downs_are_refused_by_name() {
    let dir = tempfile::tempdir().expect("tempdir");
    let loops = acceptance_loops();
    for (m, range) in [
        ("0", "> 0 and ≤ the depth 12 mm"),
        ("-1", "> 0 and ≤ the depth 12 mm"),
        ("NaN", "> 0 and ≤ the depth 12 mm"),
        ("inf", "> 0 and ≤ the depth 12 mm"),
        ("12.5", "> 0 and ≤ the depth 12 mm"),
        // at most 100 levels: depth / 100 = 0.12 mm is the least
        ("0.1", "from depth / 100 = 0.12 mm to the depth 12 mm"),
    ] {
        let nc = dir.path().join(format!("bad{m}.ngc"));
        let args = ["--depth", "12", "--max-step-down", m, "--export", nc.to_str().expect("utf-8")];
        let (ok, _, stderr) = run(dir.path(), "bad", &loops, &args);
        assert!(!ok, "{m}: accepted");
        assert!(stderr.contains("max-step-down") && stderr.contains(range), "{m}: {stderr}");
        assert!(!nc.exists(), "{m}: a program was written");
    }
}

/// `--floor-stock 0.5` leaves 0.5 mm on the floor: 12 − 0.5 = 11.5 mm in levels of at most
/// 4 mm is ⌈11.5/4⌉ = 3 levels of 11.5/3 mm, the lowest at Z −11.5; no Z word of the program
/// goes below it (read from the program's text). Bad floor stocks name `floor-stock` and the
/// range; no program is written.
#[test]
fn floor_stock_raises_the_lowest_level() {
    let dir = tempfile::tempdir().expect("tempdir");
    let loops = vec![islands_common::rect(0.0, 0.0, 60.0, 40.0)];
    let nc = dir.path().join("floor.ngc");
    let args =
        ["--depth", "12", "--max-step-down", "4", "--floor-stock", "0.5", "--export", nc.to_str().expect("utf-8")];
    let (ok, stdout, stderr) = run(dir.path(), "floor", &loops, &args);
    assert!(ok, "{stderr}");
    let json: serde_json::Value = serde_json::from_str(&stdout).expect("json");
    assert_eq!(json["floor_stock_mm"].as_f64(), Some(0.5));
    let z: Vec<f64> =
        json["levels"].as_array().expect("levels").iter().map(|l| l["z_mm"].as_f64().expect("z")).collect();
    let each = 11.5 / 3.0;
    assert_eq!(z.len(), 3);
    for (k, zk) in z.iter().enumerate() {
        assert!((zk + each * (k + 1) as f64).abs() < 1e-9, "{z:?}");
    }
    let text = std::fs::read_to_string(&nc).expect("program");
    let lowest = text
        .split_whitespace()
        .filter_map(|w| w.strip_prefix('Z').and_then(|v| v.parse::<f64>().ok()))
        .fold(f64::INFINITY, f64::min);
    assert!((lowest + 11.5).abs() < 1e-4, "lowest Z {lowest}");
    for s in ["-0.1", "12", "NaN", "13"] {
        let bad = dir.path().join("bad.ngc");
        let args = ["--depth", "12", "--floor-stock", s, "--export", bad.to_str().expect("utf-8")];
        let (ok, _, stderr) = run(dir.path(), "floor_bad", &loops, &args);
        assert!(!ok, "{s}: accepted");
        assert!(stderr.contains("floor-stock") && stderr.contains("≥ 0 and < the depth 12 mm"), "{s}: {stderr}");
        assert!(!bad.exists(), "{s}: a program was written");
    }
}
