//! Stock to leave and a floor pass end to end: `trochoplan pocket --depth 12 --max-step-down 4
//! --floor-stock 0.5 --floor-pass --stock-to-leave 0.5` of the pocket with islands (80 × 60, a
//! Ø20 round boss about (25, 30), a 15 × 30 island x 50..65, y 15..45), D 10, the defaults
//! otherwise (a_e 2.5: target 60°), `--export` a LinuxCNC program read back through `rs274`.
//!
//! Checked from the JSON and the program alone: 12 − 0.5 = 11.5 mm in levels of at most 4 mm
//! is ⌈11.5/4⌉ = 3 levels of 11.5/3 mm, then the floor pass from −11.5 to −12 (axial 0.5 mm);
//! every level's peak ≤ the target + 1°, its p95 ≤ the target; the top-level lengths and time
//! the sums of the levels'; every move in the plane below the stock top at one of the four
//! floors, each floor retracing the planned moves; every helix or ramp starting 0.5 mm above
//! the floor of the level above (the floor pass from Z −11); every point of the cut at least
//! r + 0.5 − 0.005 mm from every wall and island edge and, the finishing loop running along
//! them, within 0.01 mm of r + 0.5 (computed here from the polygon file). Then the bad values,
//! each refused by name.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod islands_common;
#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;
mod pocket_common;

use islands_common::{acceptance_loops, floor_clearances, least_clearance, run};
use nc_common::{Motion, cut, interpret, motions, sample};
use trochoplan_core::geom::{P2, Segment, p2};

/// Tool radius (D 10), the stock to leave and the floor stock (mm); the floors: 11.5 mm in
/// ⌈11.5/4⌉ = 3 levels of 11.5/3, then the floor pass at the full 12 mm.
const R: f64 = 5.0;
const STOCK: f64 = 0.5;
const FLOORS: [f64; 4] = [-11.5 / 3.0, -23.0 / 3.0, -11.5, -12.0];
const HELIX_ABOVE: f64 = 0.5;
const Z_TOL: f64 = 1e-4;

fn xy(p: [f64; 3]) -> P2 {
    p2(p[0], p[1])
}

fn num(v: &serde_json::Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} in {v}"))
}

#[test]
fn stock_to_leave_and_a_floor_pass_on_the_island_part_pass_rs274() {
    let dir = tempfile::tempdir().expect("tempdir");
    let loops = acceptance_loops();
    let nc = dir.path().join("stock.ngc");
    let args = [
        "--depth",
        "12",
        "--max-step-down",
        "4",
        "--floor-stock",
        "0.5",
        "--floor-pass",
        "--stock-to-leave",
        "0.5",
        "--export",
        nc.to_str().expect("utf-8"),
    ];
    let (ok, stdout, stderr) = run(dir.path(), "stock", &loops, &args);
    assert!(ok, "{stderr}");
    let json: serde_json::Value = serde_json::from_str(&stdout).expect("json");
    assert_eq!(json["stock_to_leave_mm"].as_f64(), Some(STOCK));
    // the straight cut's arccos(1 − 2.5/5) = 60°
    let target = num(&json, "target_deg");
    assert!((target - 60.0).abs() < 1e-9, "{target}");
    let levels = json["levels"].as_array().expect("levels");
    assert_eq!(levels.len(), 4);
    let (mut length, mut time, mut links) = (0.0, 0.0, 0.0);
    for (k, level) in levels.iter().enumerate() {
        let top = if k == 0 { 0.0 } else { FLOORS[k - 1] };
        assert!((num(level, "z_mm") - FLOORS[k]).abs() < 1e-9, "{level}");
        assert!((num(level, "top_mm") - top).abs() < 1e-9, "{level}");
        assert!((num(level, "axial_depth_mm") - (top - FLOORS[k])).abs() < 1e-9, "{level}");
        assert_eq!(level["floor_pass"].as_bool(), Some(k == 3), "{level}");
        let (peak, p95) = (num(level, "max_engagement_deg"), num(level, "p95_engagement_deg"));
        assert!(peak <= target + 1.0, "level {k}: peak {peak}");
        assert!(p95 <= target, "level {k}: p95 {p95}");
        length += num(level, "length_at_depth_mm");
        time += num(level, "time_s");
        links += num(level, "link_length_mm");
    }
    // the whole program's, not one level's
    for (key, sum) in [("length_at_depth_mm", length), ("time_s", time), ("link_length_mm", links)] {
        assert!((num(&json, key) - sum).abs() <= 1e-9 * sum, "{key}: {} vs {sum}", json[key]);
    }
    let text = std::fs::read_to_string(&nc).expect("program");
    assert!(text.contains("3 levels of 3.833 mm and a floor pass of 0.500 mm"), "the header names the floor pass");
    let canon = interpret(&nc).unwrap_or_else(|e| panic!("rs274: {e}"));
    let all = motions(&canon);
    let planned: Vec<Segment> = serde_json::from_value(json["segments"].clone()).expect("segments");
    for (f, least) in FLOORS.iter().zip(floor_clearances(&all, &FLOORS, Z_TOL, &planned, &loops)) {
        assert!(
            (R + STOCK - 0.005..=R + STOCK + 0.01).contains(&least),
            "Z{f}: the tool centre comes {least:.6} mm from a wall or island (r + stock = {})",
            R + STOCK
        );
    }
    check_entries(&all);
}

/// Every helix or ramp (a run of descending moves that go sideways) starts 0.5 mm above the
/// floor of the level above its own floor and ends on a floor; one at least per level.
fn check_entries(all: &[Motion]) {
    let mut per_level = [0usize; 4];
    let mut k = 0;
    while k < all.len() {
        let (s, e) = (all[k].start(), all[k].end());
        let descends = e[2] < s[2] - Z_TOL && e[2] < -Z_TOL;
        let sideways = (xy(e) - xy(s)).norm() > 1e-6 || matches!(all[k], Motion::Arc { .. });
        if !(descends && sideways) {
            k += 1;
            continue;
        }
        let mut j = k;
        while j + 1 < all.len() && all[j + 1].end()[2] < all[j + 1].start()[2] - Z_TOL {
            j += 1;
        }
        let end_z = all[j].end()[2];
        let level = FLOORS.iter().position(|f| (f - end_z).abs() <= Z_TOL);
        let level = level.unwrap_or_else(|| panic!("a helix from Z{} ends at Z{end_z}, no floor", s[2]));
        let above = if level == 0 { 0.0 } else { FLOORS[level - 1] };
        assert!((s[2] - (above + HELIX_ABOVE)).abs() <= Z_TOL, "the helix to Z{end_z} starts at Z{}", s[2]);
        per_level[level] += 1;
        k = j + 1;
    }
    assert!(per_level.iter().all(|&n| n >= 1), "{per_level:?}");
}

#[test]
fn bad_stock_and_floor_pass_are_refused_by_name() {
    let dir = tempfile::tempdir().expect("tempdir");
    let loops = acceptance_loops();
    for (flags, names) in [
        (vec!["--stock-to-leave", "-0.1"], vec!["stock-to-leave", "≥ 0"]),
        (vec!["--stock-to-leave", "NaN"], vec!["stock-to-leave", "≥ 0"]),
        // r + 8 = 13 mm: the walls and islands 15 mm apart leave the tool no room
        (vec!["--stock-to-leave", "8"], vec!["stock-to-leave", "must not be empty"]),
        (vec!["--floor-pass"], vec!["floor-pass", "--floor-stock"]),
        (vec!["--floor-pass", "--floor-stock", "0"], vec!["floor-pass", "--floor-stock F > 0"]),
        (vec!["--floor-pass", "--floor-stock", "5", "--max-step-down", "4"], vec!["floor-pass", "--max-step-down 4"]),
    ] {
        let nc = dir.path().join("bad.ngc");
        let mut args = vec!["--depth", "12", "--export", nc.to_str().expect("utf-8")];
        args.extend_from_slice(&flags);
        let (ok, _, stderr) = run(dir.path(), "bad", &loops, &args);
        assert!(!ok, "{flags:?}: accepted");
        assert!(names.iter().all(|n| stderr.contains(n)), "{flags:?}: {stderr}");
        assert!(!nc.exists(), "{flags:?}: a program was written");
    }
}

/// A job's pocket operation takes `stock-to-leave`: the 60 × 40 rectangle with a D 6 tool
/// (tool 2), 3 mm deep, 0.5 mm to leave; its program passes `rs274` and every point of its cut
/// at Z −3 lies r + 0.5 − 0.005 mm or more from the walls (3.5 mm, within 0.01 mm of it along
/// the finishing loop). `floor-pass = true` without a `floor-stock` is refused naming both;
/// with `floor-stock = 0.5` and `max-step-down = 1.5` the operation cuts its levels to
/// 3 − 0.5 = 2.5 mm (two of 1.25 mm) and then the floor pass at 3 mm, each floor with cuts on it.
#[test]
fn a_job_pocket_leaves_its_stock_and_takes_a_floor_pass_with_a_floor_stock() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let rect = vec![islands_common::rect(0.0, 0.0, 60.0, 40.0)];
    std::fs::write(d.join("rect.txt"), islands_common::loops_text(&rect)).expect("write");
    let job = |extra: &str| {
        format!(
            "[[tool]]\nnumber = 2\ndiameter = 6.0\nteeth = 3\nrpm = 4000.0\nfeed = 500.0\n\n\
             [[operation]]\nkind = \"pocket\"\ntool = 2\noutline = \"rect.txt\"\ndepth = 3.0\n\
             step-over = 1.5\nspacing = 1.0\nconstant-feed = true\n{extra}\n"
        )
    };
    let run_job = |name: &str, extra: &str| {
        let file = d.join(format!("{name}.toml"));
        std::fs::write(&file, job(extra)).expect("write");
        let nc = d.join(format!("{name}.ngc"));
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_trochoplan"))
            .args(["job", file.to_str().expect("utf-8"), "--export", nc.to_str().expect("utf-8")])
            .output()
            .expect("run trochoplan");
        (out.status.success(), String::from_utf8_lossy(&out.stderr).into_owned(), nc)
    };
    let (ok, stderr, nc) = run_job("stock", "stock-to-leave = 0.5");
    assert!(ok, "{stderr}");
    let canon = nc_common::rs274_with_tools(&nc, "T2 P2 D6.0 Z0 ;tool 2\n");
    let c = cut(&motions(&canon), 3.0, Z_TOL);
    let least = least_clearance(&sample(&c, 0.02), &rect[0], &[]).unwrap_or_else(|e| panic!("{e}"));
    assert!((3.5 - 0.005..=3.5 + 0.01).contains(&least), "{least}");
    let (ok, stderr, nc) = run_job("pass", "floor-pass = true");
    assert!(!ok && stderr.contains("floor-pass") && stderr.contains("--floor-stock"), "{stderr}");
    assert!(!nc.exists());
    let (ok, stderr, nc) = run_job("levels", "max-step-down = 1.5\nfloor-stock = 0.5\nfloor-pass = true");
    assert!(ok, "{stderr}");
    let m = motions(&nc_common::rs274_with_tools(&nc, "T2 P2 D6.0 Z0 ;tool 2\n"));
    for depth in [1.25, 2.5, 3.0] {
        assert!(!cut(&m, depth, Z_TOL).is_empty(), "no cut at Z -{depth}");
    }
    let lowest = m.iter().flat_map(|s| [s.start()[2], s.end()[2]]).fold(f64::INFINITY, f64::min);
    assert!((lowest + 3.0).abs() < Z_TOL, "{lowest}");
}
