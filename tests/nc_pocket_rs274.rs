//! End to end for whole pockets (issue #5): `trochoplan pocket --export` writes LinuxCNC,
//! Fanuc-style and GRBL programs of a rectangle and an L-shaped pocket, plain and with
//! variable corner circles; LinuxCNC's standalone interpreter `rs274` runs them. The checks are
//! those of the slot and corner programs (harness in `core/tests/nc_common`): zero interpreter
//! errors, the feed moves at depth retrace the rings and feed links the command printed in its
//! JSON within the tolerance plus rounding, their length within 0.1 %. Plus the pocket's wall
//! check: every point of the cut keeps the tool centre inside the polygon and at least the tool
//! radius from every edge (up to the same budget), computed here from the polygon file alone;
//! and no rapid move below the safe height.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;

use nc_common::{DUMBBELL, Motion, budget, check_path_cut, cut, interpret, motions, sample};
use std::path::{Path, PathBuf};
use std::process::Command;
use trochoplan_core::geom::{P2, Segment, p2};

/// Tool radius (the `pocket` default D = 10 mm), depth and safe Z (the defaults) in mm.
const R: f64 = 5.0;
const DEPTH: f64 = 6.0;
const SAFE_Z: f64 = 5.0;

const RECT: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)];
/// An L: 100 × 90 minus the 60 × 50 block at the top right, arms 40 wide; one reflex vertex
/// at (40, 40).
const L_SHAPE: &[(f64, f64)] = &[(0.0, 0.0), (100.0, 0.0), (100.0, 40.0), (40.0, 40.0), (40.0, 90.0), (0.0, 90.0)];

const DIALECTS: [(&str, &str, i32); 3] = [("linuxcnc", "ngc", 4), ("fanuc", "nc", 3), ("grbl", "gcode", 3)];

struct Exported {
    file: PathBuf,
    /// Rings and feed links in machining order, as the command printed them.
    feed_path: Vec<Segment>,
    json: serde_json::Value,
}

fn export(dir: &Path, name: &str, polygon: &[(f64, f64)], args: &[&str]) -> Exported {
    let poly_file = dir.join(format!("{name}.poly"));
    let text: String = polygon.iter().map(|(x, y)| format!("{x},{y}\n")).collect();
    std::fs::write(&poly_file, text).expect("write polygon");
    let file = dir.join(name);
    let mut all: Vec<&str> = vec!["pocket", "--spacing", "1", "--polygon"];
    all.push(poly_file.to_str().expect("utf-8"));
    all.push("--export");
    all.push(file.to_str().expect("utf-8"));
    all.extend_from_slice(args);
    let out = Command::new(env!("CARGO_BIN_EXE_trochoplan")).args(&all).output().expect("run trochoplan");
    assert!(out.status.success(), "trochoplan {all:?}: {}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    assert!(json["nc_export"]["blocks"].as_u64().is_some_and(|b| b > 20), "{}", json["nc_export"]);
    if let Some(segs) = json.get("segments") {
        // medial-axis: the whole path, with jumps only where the program retracts
        let feed_path: Vec<Segment> = serde_json::from_value(segs.clone()).expect("segments");
        return Exported { file, feed_path, json };
    }
    let rings = json["rings"].as_array().expect("rings");
    let links = json["links"].as_array().expect("links");
    assert_eq!(links.len() + 1, rings.len(), "{name}: one link between consecutive rings");
    let mut feed_path = Vec::new();
    for (i, ring) in rings.iter().enumerate() {
        let segs: Vec<Segment> = serde_json::from_value(ring["segments"].clone()).expect("segments");
        feed_path.extend(segs);
        if let Some(l) = links.get(i)
            && l["kind"] == "feed"
        {
            let pt = |v: &serde_json::Value| p2(v[0].as_f64().expect("x"), v[1].as_f64().expect("y"));
            feed_path.push(Segment::Line { start: pt(&l["from"]), end: pt(&l["to"]) });
        }
    }
    Exported { file, feed_path, json }
}

fn dist_to_edge(p: P2, a: P2, b: P2) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(&ab) / ab.dot(&ab)).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm()
}

/// Even–odd ray casting along +x.
fn inside(p: P2, poly: &[P2]) -> bool {
    let mut c = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) {
            c = !c;
        }
    }
    c
}

/// Smallest signed clearance of the cut from the pocket walls: distance to the nearest edge,
/// negative outside the polygon.
fn wall_clearance(cut: &[Motion], polygon: &[(f64, f64)]) -> f64 {
    let poly: Vec<P2> = polygon.iter().map(|&(x, y)| p2(x, y)).collect();
    sample(cut, 0.02)
        .iter()
        .map(|&p| {
            let d = (0..poly.len())
                .map(|i| dist_to_edge(p, poly[i], poly[(i + 1) % poly.len()]))
                .fold(f64::INFINITY, f64::min);
            if inside(p, &poly) { d } else { -d }
        })
        .fold(f64::INFINITY, f64::min)
}

fn check(label: &str, e: &Exported, polygon: &[(f64, f64)], tol: f64, decimals: i32) {
    let canon = interpret(&e.file).unwrap_or_else(|err| panic!("{label}: {err}"));
    let q = 10f64.powi(-decimals);
    let all = motions(&canon);
    for m in &all {
        if let Motion::Rapid { start, end } = m {
            assert!(start[2] >= SAFE_Z - 1e-4 || end[2] >= SAFE_Z - 1e-4, "{label}: rapid below safe Z: {m:?}");
            assert!(end[2] >= SAFE_Z - 1e-4 || (end[0] == start[0] && end[1] == start[1]), "{label}: {m:?}");
        }
    }
    let c = cut(&all, DEPTH, 1e-4);
    check_path_cut(label, &c, &e.feed_path, tol, q).unwrap_or_else(|err| panic!("{err}"));
    let clearance = wall_clearance(&c, polygon);
    let allowed = R - budget(tol, q);
    assert!(clearance >= allowed, "{label}: tool centre {clearance:.6} mm from a wall < r - budget = {allowed:.6} mm");
}

#[test]
fn pocket_programs_pass_rs274_and_stay_inside_the_offset() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (shape, polygon) in [("rect", RECT), ("l", L_SHAPE)] {
        for method in ["plain", "variable"] {
            for (dialect, ext, decimals) in DIALECTS {
                let label = format!("{shape} {method} {dialect}");
                let e = export(
                    dir.path(),
                    &format!("{shape}_{method}.{ext}"),
                    polygon,
                    &["--method", method, "--dialect", dialect, "--coolant"],
                );
                check(&label, &e, polygon, 0.005, decimals);
                if method == "variable" {
                    assert!(e.json["trochoid_corners"].as_u64().is_some_and(|n| n > 0), "{label}: {}", e.json);
                }
            }
        }
    }
}

#[test]
fn rectangle_pocket_program_is_one_connected_cut() {
    // 60 × 40, D = 10, a_e = 2.5 (the defaults): rings at d = 5 + 2.5k while d ≤ 20 (the
    // innermost, d = 20, is the segment from (20, 20) to (40, 20) walked there and back):
    // k = 0..6, seven rings, perimeters 2(60 − 2d) + 2(40 − 2d) = 200 − 8d = 160, 140, …, 40;
    // total 7·(160 + 40)/2 = 700 mm. Each ring is entered at the middle of a long side, so each
    // link is a step of a_e = 2.5 mm outward: six feed links, 15 mm, no retract.
    let dir = tempfile::tempdir().expect("tempdir");
    let e = export(dir.path(), "rect.ngc", RECT, &["--dialect", "linuxcnc", "--linear-segments"]);
    assert!((e.json["path_length_mm"].as_f64().expect("len") - 700.0).abs() < 1e-9, "{}", e.json["path_length_mm"]);
    assert!((e.json["link_length_mm"].as_f64().expect("links") - 15.0).abs() < 1e-9, "{}", e.json["link_length_mm"]);
    let text = std::fs::read_to_string(&e.file).expect("read");
    // one plunge, one final retract: the approach's G0 Z and the end's
    assert_eq!(text.matches("G0 Z").count() + text.matches("\nZ5.0000").count(), 2, "{text}");
    check("rect plain linuxcnc chords", &e, RECT, 0.005, 4);
}

#[test]
fn retract_links_pass_rs274_and_the_cut_skips_them() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (dialect, ext, decimals) in DIALECTS {
        let e =
            export(dir.path(), &format!("dumbbell.{ext}"), DUMBBELL, &["--method", "variable", "--dialect", dialect]);
        let links = e.json["links"].as_array().expect("links");
        let retracts = links.iter().filter(|l| l["kind"] == "retract").count();
        assert!(retracts >= 1 && retracts < links.len(), "{dialect}: {links:?}");
        let text = std::fs::read_to_string(&e.file).expect("read");
        // every retract link is one more plunge: the approach's, one per retract
        let plunges = text.lines().filter(|l| l.contains("Z-6.000")).count();
        assert_eq!(plunges, 1 + retracts, "{dialect}:\n{text}");
        check(&format!("dumbbell variable {dialect}"), &e, DUMBBELL, 0.005, decimals);
    }
}

#[test]
fn medial_axis_pocket_programs_pass_rs274_and_stay_inside_the_offset() {
    // Perforative trochoids along the medial axis (`--method medial-axis`): rectangle, L and the
    // dumbbell with D = 18, whose 16 mm neck splits it into two parts (one retract between).
    let dir = tempfile::tempdir().expect("tempdir");
    for (dialect, ext, decimals) in DIALECTS {
        for (shape, polygon) in [("rect", RECT), ("l", L_SHAPE)] {
            let e = export(
                dir.path(),
                &format!("{shape}_ma.{ext}"),
                polygon,
                &["--method", "medial-axis", "--dialect", dialect],
            );
            assert_eq!(e.json["parts"], 1, "{shape}");
            check(&format!("{shape} medial-axis {dialect}"), &e, polygon, 0.005, decimals);
        }
    }
    let e = export(
        dir.path(),
        "dumbbell_ma.ngc",
        DUMBBELL,
        &["--method", "medial-axis", "--tool-diameter", "18", "--step-over", "3", "--dialect", "linuxcnc"],
    );
    assert_eq!(e.json["parts"], 2);
    let text = std::fs::read_to_string(&e.file).expect("read");
    assert_eq!(text.lines().filter(|l| l.contains("Z-6.000")).count(), 2, "one plunge per part");
    let canon = interpret(&e.file).unwrap_or_else(|err| panic!("dumbbell D18: {err}"));
    let c = cut(&motions(&canon), DEPTH, 1e-4);
    check_path_cut("dumbbell D18", &c, &e.feed_path, 0.005, 1e-4).unwrap_or_else(|err| panic!("{err}"));
    assert!(wall_clearance(&c, DUMBBELL) >= 9.0 - budget(0.005, 1e-4));
}

/// A random simple polygon: star-shaped about the origin (vertices at increasing angles, each
/// at its own radius), so it never crosses itself; reflex vertices wherever a radius dips.
fn star_polygon(seed: u64, n: usize) -> Vec<(f64, f64)> {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = move || {
        // xorshift64*: deterministic, good enough for test shapes
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        (s.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * (k as f64 + 0.8 * next()) / n as f64;
            let r = 30.0 + 40.0 * next();
            (100.0 + r * a.cos(), 200.0 + r * a.sin())
        })
        .collect()
}

#[test]
fn random_medial_axis_pockets_retrace_their_plan_and_never_gouge() {
    // Issue #13: near-full circles of medial-axis pockets were written with a moved centre (up
    // to 4.59 mm off the plan, closer than r to a wall in 10 of 31 random pockets). Random
    // simple polygons, random tool and step-over, Fanuc (3 decimals, where it showed) and
    // LinuxCNC: the program read back by rs274 must retrace the plan within tolerance +
    // rounding and keep the tool centre r from every wall.
    let dir = tempfile::tempdir().expect("tempdir");
    for seed in 1..=8u64 {
        let n = 7 + (seed as usize * 5) % 9;
        let polygon = star_polygon(seed, n);
        let d = 6.0 + (seed as f64 * 1.37) % 6.0;
        let a_e = 0.12 * d + (seed as f64 * 0.71) % (0.2 * d);
        let (d_s, a_e_s) = (format!("{d}"), format!("{a_e}"));
        for (dialect, ext, decimals) in [DIALECTS[0], DIALECTS[1]] {
            let label = format!("seed {seed} ({n} vertices, D {d:.3}, a_e {a_e:.3}) {dialect}");
            let args =
                ["--method", "medial-axis", "--tool-diameter", &d_s, "--step-over", &a_e_s, "--dialect", dialect];
            let e = export(dir.path(), &format!("star{seed}.{ext}"), &polygon, &args);
            let canon = interpret(&e.file).unwrap_or_else(|err| panic!("{label}: {err}"));
            let q = 10f64.powi(-decimals);
            let c = cut(&motions(&canon), DEPTH, 1e-4);
            check_path_cut(&label, &c, &e.feed_path, 0.005, q).unwrap_or_else(|err| panic!("{err}"));
            let clearance = wall_clearance(&c, &polygon);
            let allowed = 0.5 * d - budget(0.005, q);
            assert!(clearance >= allowed, "{label}: tool centre {clearance:.6} mm from a wall < r - budget = {allowed:.6}");
        }
    }
}
