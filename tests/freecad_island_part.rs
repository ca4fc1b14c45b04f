//! FreeCAD's Adaptive beside ours on the pocket with islands: 80 × 60 with a Ø20 round boss
//! about (25, 30) and a 15 × 30 rectangular island (x 50..65, y 15..45), D 10, 12 mm deep in
//! three levels of 4 mm. FreeCAD's program is `tests/data/freecad/islands.ngc`, written by
//! FreeCAD 0.20.2's own Adaptive operation run headless (`scripts/freecad-adaptive.py`: StepOver
//! 25 %, StepDown 4, 600 mm/min); ours is `trochoplan pocket --polygon
//! tests/data/freecad/islands.txt --depth 12 --max-step-down 4 --machine vmc --export` (a_e 2.5:
//! target 60°, 600 mm/min).
//!
//! Both programs are measured by the same tools: LinuxCNC's `rs274` reads each back (no error;
//! every move in the plane below the stock top at one of the floors −4, −8, −12; the closest
//! approach of the tool centre to the wall and to each island, computed here from the outline
//! file), and `trochoplan verify PROGRAM --stock islands.txt --part islands.txt
//! --gouge-tolerance 0.005 --machine vmc --moves CSV` measures every move (engagement, h_max,
//! real time) over the stock less its islands, and reports every move whose tool reaches past
//! the wall or into an island by more than 0.005 mm as a `gouge` (the tolerance is the
//! acceptance's: no move closer than r − 0.005 mm to the wall or either island).
//!
//! The entries: verify measures a descending move at its lowest point and the band above it as
//! still full where the helix's last turn did not pass, so the closing circle of each helix
//! reads the sloped bottom of the last turn as a wide cut (137–138° on both programs). "Away
//! from the entries" leaves out the descending moves and the moves at a floor from one turning
//! point of a helix to another (the closing circle).
//!
//! Asserted: both programs pass `rs274` with their floors at −4, −8, −12; verify's peak is the
//! largest engagement of its per-move CSV; ours keeps at least r − 0.005 mm from the wall and
//! both islands, and comes no closer than FreeCAD's program; verify reports a gouge of a loop
//! (wall, boss, island) exactly where the tool centre comes closer than r − 0.005 mm to it over
//! `rs274`'s output, its deepest gouge of that loop r less that closest approach (to 0.001 mm):
//! FreeCAD's program gouges the boss and the island, ours has no problem at all; away from the entries our peak is
//! within the target + 1° and below FreeCAD's; our 95th percentile is within the target and
//! below FreeCAD's. The real times are printed beside each other, not compared by an assertion.
//!
//! Prints the table of docs/freecad-comparison.md:
//! `cargo test --release --test freecad_island_part -- --nocapture`.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod islands_common;
#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;
mod pocket_common;

use islands_common::{acceptance_loops, loop_distance, loops_text};
use nc_common::{Motion, interpret, motions, sample};
use pocket_common::inside;
use std::path::{Path, PathBuf};
use std::process::Command;
use trochoplan_core::geom::{P2, p2};

/// Tool radius (D 10, mm).
const R: f64 = 5.0;
/// The floors of the three levels (12 mm in levels of 4 mm).
const FLOORS: [f64; 3] = [-4.0, -8.0, -12.0];
/// Our target engagement (degrees): the straight cut's arccos(1 − 2.5/5) = 60°.
const TARGET_DEG: f64 = 60.0;
/// Heights closer than this are one (mm).
const Z_TOL: f64 = 1e-4;
/// verify's gouge tolerance (mm): the acceptance's "no move closer than r − 0.005 mm to the
/// wall or either island".
const GOUGE_TOL: f64 = 0.005;

fn data() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/freecad")).to_path_buf()
}

fn xy(p: [f64; 3]) -> P2 {
    p2(p[0], p[1])
}

/// What is measured of one program.
struct Measured {
    /// Largest engagement over every feed move in the plane below the stock top (verify).
    peak: f64,
    /// The same without the entries (module docs).
    peak_away: f64,
    /// verify's 95th percentile.
    p95: f64,
    /// verify's largest h_max at the feed the machine reaches (mm).
    h_max: f64,
    /// verify's real time on `vmc` (s).
    time: f64,
    /// Feed length in the plane at each floor (mm), rapids at each floor (count, mm).
    at_floor: Vec<(f64, usize, f64)>,
    /// Retracts from below the stock top to above it.
    retracts: usize,
    /// Closest approach of the tool centre to the wall, the boss, the rectangular island (mm).
    closest: [f64; 3],
    /// verify's problems, by kind.
    problems: Vec<String>,
    /// verify's deepest gouge (mm) of the wall, the boss, the rectangular island (0: none),
    /// each gouge given to the loop nearest the tool centre at its place.
    gouge: [f64; 3],
    /// How many moves verify finds gouging.
    gouge_moves: u64,
}

/// `trochoplan ARGS`: stdout, failing the test on an error.
fn trochoplan(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_trochoplan")).args(args).output().expect("run trochoplan");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && !stderr.contains("panicked"), "trochoplan {args:?}: {stderr}");
    String::from_utf8(out.stdout).expect("utf-8")
}

/// The columns of verify's per-move CSV that are read here.
struct Row {
    kind: String,
    from: [f64; 3],
    to: [f64; 3],
    engagement: f64,
}

fn rows(csv: &str) -> Vec<Row> {
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().expect("header").split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name}"));
    let (kind, x0, eng) = (col("kind"), col("x0"), col("engagement_deg"));
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let v = |i: usize| f[i].parse::<f64>().unwrap_or_else(|e| panic!("{l}: {e}"));
            Row {
                kind: f[kind].to_string(),
                from: [v(x0), v(x0 + 1), v(x0 + 2)],
                to: [v(x0 + 3), v(x0 + 4), v(x0 + 5)],
                engagement: v(eng),
            }
        })
        .collect()
}

fn measure(label: &str, program: &Path, outline: &Path, dir: &Path) -> Measured {
    let loops = acceptance_loops();
    // rs274: every move in the plane below the top at a floor; lengths per floor; clearance
    let canon = interpret(program).unwrap_or_else(|e| panic!("{label}: {e}"));
    let all = motions(&canon);
    let lowest = all.iter().map(|m| m.end()[2]).fold(f64::INFINITY, f64::min);
    assert!((lowest - FLOORS[2]).abs() <= Z_TOL, "{label}: lowest Z {lowest}");
    let mut at_floor = vec![(0.0, 0, 0.0); FLOORS.len()];
    let mut retracts = 0;
    for m in &all {
        let (s, e) = (m.start(), m.end());
        if (s[2] - e[2]).abs() <= Z_TOL && s[2] < -Z_TOL {
            let k = FLOORS.iter().position(|f| (s[2] - f).abs() <= Z_TOL);
            let k = k.unwrap_or_else(|| panic!("{label}: a move at Z{}: {m:?}", s[2]));
            let len = nc_common::length(std::slice::from_ref(m));
            match m {
                Motion::Rapid { .. } => {
                    at_floor[k].1 += 1;
                    at_floor[k].2 += len;
                }
                _ => at_floor[k].0 += len,
            }
        }
        if s[2] < -Z_TOL && e[2] > 0.0 {
            retracts += 1;
        }
    }
    for (k, f) in at_floor.iter().enumerate() {
        assert!(f.0 > 0.0, "{label}: nothing cut at Z{}", FLOORS[k]);
    }
    let below: Vec<Motion> = all
        .iter()
        .filter(|m| m.start()[2].min(m.end()[2]) < -Z_TOL && (xy(m.end()) - xy(m.start())).norm() > 1e-9)
        .copied()
        .collect();
    let mut closest = [f64::INFINITY; 3];
    for p in sample(&below, 0.02) {
        assert!(inside(p, &loops[0]), "{label}: ({}, {}) outside the pocket", p.x, p.y);
        for (k, l) in loops.iter().enumerate() {
            assert!(k == 0 || !inside(p, l), "{label}: ({}, {}) inside island {k}", p.x, p.y);
            closest[k] = closest[k].min(loop_distance(p, l));
        }
    }
    // verify, with the per-move CSV
    let csv = dir.join(format!("{label}.csv"));
    let text = trochoplan(&[
        "verify",
        program.to_str().expect("utf-8"),
        "--stock",
        outline.to_str().expect("utf-8"),
        "--part",
        outline.to_str().expect("utf-8"),
        "--gouge-tolerance",
        &GOUGE_TOL.to_string(),
        "--machine",
        "vmc",
        "--moves",
        csv.to_str().expect("utf-8"),
    ]);
    let json: serde_json::Value = serde_json::from_str(&text).expect("json");
    let num = |k: &str| json[k].as_f64().unwrap_or_else(|| panic!("{label}: no {k}"));
    let rows = rows(&std::fs::read_to_string(&csv).expect("moves csv"));
    // the summary's moves: feed moves in the plane below the stock top
    let plane = |r: &&Row| r.kind == "feed" && (r.from[2] - r.to[2]).abs() <= Z_TOL && r.from[2] < -Z_TOL;
    let peak_csv = rows.iter().filter(plane).map(|r| r.engagement).fold(0.0, f64::max);
    // (the CSV has 3 decimals)
    assert!((peak_csv - num("max_engagement_deg")).abs() < 1e-3, "{label}: {peak_csv} vs the JSON's");
    // the helices' turning points: the ends of descending moves that go sideways
    let turning: Vec<P2> = rows
        .iter()
        .filter(|r| r.to[2] < r.from[2] - Z_TOL && (xy(r.to) - xy(r.from)).norm() > 1e-6)
        .map(|r| xy(r.to))
        .collect();
    let on_turning = |p: [f64; 3]| turning.iter().any(|t| (xy(p) - *t).norm() <= 1e-3);
    let peak_away = rows
        .iter()
        .filter(plane)
        .filter(|r| !(on_turning(r.from) && on_turning(r.to)))
        .map(|r| r.engagement)
        .fold(0.0, f64::max);
    let list = json["problems"].as_array().expect("problems");
    let problems = json["problem_moves"]
        .as_object()
        .expect("problem_moves")
        .iter()
        .map(|(kind, n)| format!("{kind} ×{n}"))
        .collect();
    let mut gouge = [0.0f64; 3];
    for p in list.iter().filter(|p| p["kind"] == "gouge") {
        let at = p2(p["x"].as_f64().expect("x"), p["y"].as_f64().expect("y"));
        let k = (0..loops.len())
            .min_by(|&a, &b| loop_distance(at, &loops[a]).total_cmp(&loop_distance(at, &loops[b])))
            .expect("loops");
        gouge[k] = gouge[k].max(p["value"].as_f64().expect("value"));
    }
    let gouge_moves = json["problem_moves"]["gouge"].as_u64().unwrap_or(0);
    Measured {
        peak: num("max_engagement_deg"),
        peak_away,
        p95: num("p95_engagement_deg"),
        h_max: num("h_max_mm"),
        time: num("time_real_s"),
        at_floor,
        retracts,
        closest,
        problems,
        gouge,
        gouge_moves,
    }
}

#[test]
fn freecad_adaptive_and_ours_on_the_pocket_with_islands() {
    let outline = data().join("islands.txt");
    // the committed outline is the pocket of the acceptance tests
    let loops = acceptance_loops();
    assert_eq!(std::fs::read_to_string(&outline).expect("outline"), loops_text(&loops));
    let dir = tempfile::tempdir().expect("tempdir");
    // FreeCAD's program, copied (rs274 writes beside it)
    let freecad = dir.path().join("freecad.ngc");
    std::fs::copy(data().join("islands.ngc"), &freecad).expect("copy");
    let ours = dir.path().join("ours.ngc");
    let text = trochoplan(&[
        "pocket",
        "--polygon",
        outline.to_str().expect("utf-8"),
        "--depth",
        "12",
        "--max-step-down",
        "4",
        "--machine",
        "vmc",
        "--export",
        ours.to_str().expect("utf-8"),
    ]);
    let json: serde_json::Value = serde_json::from_str(&text).expect("json");
    assert!(json["target_deg"].as_f64().is_some_and(|t| (t - TARGET_DEG).abs() < 1e-9), "{}", json["target_deg"]);
    let f = measure("freecad", &freecad, &outline, dir.path());
    let o = measure("ours", &ours, &outline, dir.path());

    println!(
        "| program | peak (every move) | peak away from the entries | p95 | h_max | real time (vmc) | \
         at each floor: feed length | rapids at each floor | retracts | closest: wall | boss | island | \
         verify's deepest gouge: wall | boss | island | gouging moves |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (name, m) in [("FreeCAD", &f), ("ours", &o)] {
        println!(
            "| {name} | {:.2}° | {:.2}° | {:.2}° | {:.4} mm | {:.1} s | {} | {} | {} | {:.4} | {:.4} | {:.4} | \
             {:.4} | {:.4} | {:.4} | {} |",
            m.peak,
            m.peak_away,
            m.p95,
            m.h_max,
            m.time,
            m.at_floor.iter().map(|a| format!("{:.1}", a.0)).collect::<Vec<_>>().join(" / "),
            m.at_floor.iter().map(|a| format!("{}, {:.1} mm", a.1, a.2)).collect::<Vec<_>>().join(" / "),
            m.retracts,
            m.closest[0],
            m.closest[1],
            m.closest[2],
            m.gouge[0],
            m.gouge[1],
            m.gouge[2],
            m.gouge_moves,
        );
    }
    println!("time ours / FreeCAD: {:.3}", o.time / f.time);
    println!("problems: FreeCAD {:?}; ours {:?}", f.problems, o.problems);

    // verify's gouges agree with rs274's closest approaches: a gouge of a loop exactly where the
    // tool centre comes closer than r − the tolerance, as deep as r less that approach
    for (name, m) in [("FreeCAD", &f), ("ours", &o)] {
        for k in 0..3 {
            let depth = R - m.closest[k];
            if depth > GOUGE_TOL {
                assert!((m.gouge[k] - depth).abs() <= 1e-3, "{name}, loop {k}: gouge {} vs rs274 {depth}", m.gouge[k]);
            } else {
                assert!(m.gouge[k] == 0.0, "{name}, loop {k}: gouge {} where rs274 reads {depth}", m.gouge[k]);
            }
        }
    }
    // FreeCAD's program cuts into the boss and the island; ours has no problem at all
    assert!(f.gouge[1] > GOUGE_TOL && f.gouge[2] > GOUGE_TOL, "FreeCAD's gouges: {:?}", f.gouge);
    assert!(o.problems.is_empty(), "ours: {:?}", o.problems);
    // ours keeps off the wall and both islands; FreeCAD's comes closer
    let (least_o, least_f) = (
        o.closest.iter().copied().fold(f64::INFINITY, f64::min),
        f.closest.iter().copied().fold(f64::INFINITY, f64::min),
    );
    assert!(least_o >= R - 0.005, "ours comes {least_o} mm from a wall or island");
    assert!(least_o >= least_f, "ours {least_o} mm, FreeCAD {least_f} mm");
    // away from the entries, ours within the target + 1° and below FreeCAD's
    assert!(o.peak_away <= TARGET_DEG + 1.0, "ours: peak away from the entries {}", o.peak_away);
    assert!(o.peak_away < f.peak_away, "peak away from the entries: ours {}, FreeCAD {}", o.peak_away, f.peak_away);
    assert!(o.p95 <= TARGET_DEG && o.p95 < f.p95, "p95: ours {}, FreeCAD {}", o.p95, f.p95);
}
