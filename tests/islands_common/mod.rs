//! The pocket with islands of the end-to-end tests, shared by `nc_pocket_islands_rs274.rs`
//! and `nc_pocket_levels_rs274.rs`: its loops (80 × 60 with a Ø20 round boss about (25, 30) and
//! a 15 × 30 rectangular island x 50..65, y 15..45), the point-list text, the command, and the
//! plain geometry the checks compute from the polygon file (distances, inside).

#![allow(dead_code)]

use std::path::Path;
use std::process::Command;
use trochoplan_core::geom::{P2, p2};

/// The boss: a 128-gon inscribed in the circle of radius 10 about (25, 30) (its chords lie
/// within 10·(1 − cos(π/128)) = 0.003 mm of the circle).
pub fn boss() -> Vec<P2> {
    (0..128)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 128.0;
            p2(25.0 + 10.0 * a.cos(), 30.0 + 10.0 * a.sin())
        })
        .collect()
}

pub fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<P2> {
    vec![p2(x0, y0), p2(x1, y0), p2(x1, y1), p2(x0, y1)]
}

/// The acceptance pocket's loops: the 80 × 60 boundary, the boss, the rectangular island.
pub fn acceptance_loops() -> Vec<Vec<P2>> {
    vec![rect(0.0, 0.0, 80.0, 60.0), boss(), rect(50.0, 15.0, 65.0, 45.0)]
}

/// The point-list text of the loops, separated by empty lines.
pub fn loops_text(loops: &[Vec<P2>]) -> String {
    loops
        .iter()
        .map(|l| l.iter().map(|p| format!("{},{}\n", p.x, p.y)).collect::<String>())
        .collect::<Vec<_>>()
        .join("\n")
}

/// `trochoplan pocket --polygon` of `loops` with `args`: the exit status, stdout and stderr.
pub fn run(dir: &Path, name: &str, loops: &[Vec<P2>], args: &[&str]) -> (bool, String, String) {
    let file = dir.join(format!("{name}.txt"));
    std::fs::write(&file, loops_text(loops)).expect("write polygon");
    let mut all = vec!["pocket", "--polygon", file.to_str().expect("utf-8")];
    all.extend_from_slice(args);
    let out = Command::new(env!("CARGO_BIN_EXE_trochoplan")).args(&all).output().expect("run trochoplan");
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr));
    assert!(!stderr.contains("panicked"), "{stderr}");
    (out.status.success(), stdout, stderr.into_owned())
}

// the distance to an edge and the even–odd test of the pocket tests (the crate includes
// `pocket_common` beside this module)
use crate::pocket_common::{dist_to_edge as edge_distance, inside};

/// The least distance from `p` to an edge of `poly`.
pub fn loop_distance(p: P2, poly: &[P2]) -> f64 {
    (0..poly.len()).map(|i| edge_distance(p, poly[i], poly[(i + 1) % poly.len()])).fold(f64::INFINITY, f64::min)
}

/// Every point of `points` inside `boundary`, outside each of `islands`; the least distance
/// of them to a wall or island edge.
pub fn least_clearance(points: &[P2], boundary: &[P2], islands: &[Vec<P2>]) -> Result<f64, String> {
    let mut least: f64 = f64::INFINITY;
    for &p in points {
        if !inside(p, boundary) {
            return Err(format!("({}, {}) outside the pocket", p.x, p.y));
        }
        if islands.iter().any(|i| inside(p, i)) {
            return Err(format!("({}, {}) inside an island", p.x, p.y));
        }
        let d = islands.iter().map(|i| loop_distance(p, i)).fold(loop_distance(p, boundary), f64::min);
        least = least.min(d);
    }
    Ok(least)
}

/// The program's motions `all` read back at the floors `floors` (Z, within `z_tol`): every move
/// in the plane below the stock top lies at one of them, each floor's cut retraces `planned`
/// (within 0.005 mm, q = 1e-4 mm), and the tool centre's least distance from the walls and
/// islands of `loops` (boundary first) at each floor, points every 0.02 mm, is returned in the
/// order of `floors`.
pub fn floor_clearances(
    all: &[crate::nc_common::Motion],
    floors: &[f64],
    z_tol: f64,
    planned: &[trochoplan_core::geom::Segment],
    loops: &[Vec<P2>],
) -> Vec<f64> {
    use crate::nc_common::{check_path_cut, cut, sample};
    for m in all {
        let (s, e) = (m.start(), m.end());
        if (s[2] - e[2]).abs() <= z_tol && s[2] < -z_tol {
            assert!(floors.iter().any(|f| (s[2] - f).abs() <= z_tol), "a move at Z{}: {m:?}", s[2]);
        }
    }
    let (boundary, islands) = (&loops[0], &loops[1..]);
    floors
        .iter()
        .map(|&f| {
            let c = cut(all, -f, z_tol);
            check_path_cut(&format!("Z{f}"), &c, planned, 0.005, 1e-4).unwrap_or_else(|e| panic!("{e}"));
            least_clearance(&sample(&c, 0.02), boundary, islands).unwrap_or_else(|e| panic!("Z{f}: {e}"))
        })
        .collect()
}
