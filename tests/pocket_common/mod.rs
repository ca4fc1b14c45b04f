//! Pocket programs end to end, shared by `nc_pocket_rs274.rs` and `fuzz.rs`: export a pocket
//! through the CLI (`pocket --export`), read the planned path from its JSON, read the program
//! back through LinuxCNC's `rs274` and check it against the plan and the walls.

#![allow(dead_code)]

use crate::nc_common::{Motion, budget, check_path_cut, cut, interpret, motions, sample};
use std::path::{Path, PathBuf};
use std::process::Command;
use trochoplan_core::geom::{P2, Segment, p2};

/// Depth and safe Z of the `pocket` command's defaults (mm).
pub const DEPTH: f64 = 6.0;
pub const SAFE_Z: f64 = 5.0;

pub struct Exported {
    pub file: PathBuf,
    /// Rings and feed links in machining order, as the command printed them.
    pub feed_path: Vec<Segment>,
    pub json: serde_json::Value,
}

/// `pocket --export` of `polygon` with `args`; the program and the planned feed path from the
/// JSON. Panics on any failure.
pub fn export(dir: &Path, name: &str, polygon: &[(f64, f64)], args: &[&str]) -> Exported {
    pocket_export(dir, name, polygon, args).unwrap_or_else(|| panic!("{name}: rejected"))
}

/// Like [`export`], but a pocket the command rejects (exit 2, a message naming a parameter or
/// the polygon) gives `None`; any other failure panics.
pub fn pocket_export(dir: &Path, name: &str, polygon: &[(f64, f64)], args: &[&str]) -> Option<Exported> {
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
    let stderr = String::from_utf8_lossy(&out.stderr);
    if out.status.code() == Some(2) && stderr.contains("invalid") && !stderr.contains("panicked") {
        return None;
    }
    assert!(out.status.success(), "trochoplan {all:?}: {stderr}");
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    assert!(json["nc_export"]["blocks"].as_u64().is_some_and(|b| b > 20), "{}", json["nc_export"]);
    if let Some(segs) = json.get("segments") {
        // medial-axis: the whole path, with jumps only where the program retracts
        let feed_path: Vec<Segment> = serde_json::from_value(segs.clone()).expect("segments");
        return Some(Exported { file, feed_path, json });
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
    Some(Exported { file, feed_path, json })
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
pub fn wall_clearance(cut: &[Motion], polygon: &[(f64, f64)]) -> f64 {
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

/// The checks of a pocket program: rs274 runs it silently, no rapid below the safe height, the
/// cut at depth retraces the planned feed path within tolerance + rounding, and the tool centre
/// stays `r` from every wall (up to the same budget).
pub fn check_pocket_program(label: &str, e: &Exported, polygon: &[(f64, f64)], r: f64, tol: f64, decimals: i32) {
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
    let allowed = r - budget(tol, q);
    assert!(clearance >= allowed, "{label}: tool centre {clearance:.6} mm from a wall < r - budget = {allowed:.6} mm");
}

/// A small deterministic generator (xorshift64*) for test inputs: a failing case can be run again.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// Log-uniform in [lo, hi): every order of magnitude equally often.
    pub fn log_range(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.unit()).exp()
    }
    /// Uniform in 0..n.
    pub fn below(&mut self, n: usize) -> usize {
        ((self.unit() * n as f64) as usize).min(n.saturating_sub(1))
    }
}

/// A random simple polygon: star-shaped about (100, 200) (vertices at increasing angles, each at
/// its own radius), so it never crosses itself; reflex vertices wherever a radius dips.
pub fn star_polygon(seed: u64, n: usize) -> Vec<(f64, f64)> {
    let mut rng = Rng::new(seed);
    (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * (k as f64 + 0.8 * rng.unit()) / n as f64;
            let r = 30.0 + 40.0 * rng.unit();
            (100.0 + r * a.cos(), 200.0 + r * a.sin())
        })
        .collect()
}
