//! Pocket programs end to end, shared by `nc_pocket_rs274.rs` and `fuzz.rs`: export a pocket
//! through the CLI (`pocket --export`), read the planned path from its JSON, read the program
//! back through LinuxCNC's `rs274` and check it against the plan and the walls.

#![allow(dead_code)]

use crate::nc_common::{Motion, budget, check_path_cut, cut, interpret, motions, sample};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
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

pub fn dist_to_edge(p: P2, a: P2, b: P2) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(&ab) / ab.dot(&ab)).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm()
}

/// Even–odd ray casting along +x.
pub fn inside(p: P2, poly: &[P2]) -> bool {
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

/// The checks of a pocket program: rs274 runs it silently, no rapid below the safe height but
/// the rapids at depth the plan makes through cleared stock (in the plane at depth, on the
/// planned path), the cut at depth retraces the planned path within tolerance + rounding, and
/// the tool centre stays `r` from every wall (up to the same budget).
pub fn check_pocket_program(label: &str, e: &Exported, polygon: &[(f64, f64)], r: f64, tol: f64, decimals: i32) {
    let canon = interpret(&e.file).unwrap_or_else(|err| panic!("{label}: {err}"));
    let q = 10f64.powi(-decimals);
    let all = motions(&canon);
    for m in &all {
        if let Motion::Rapid { start, end } = m {
            let at_depth = (start[2] + DEPTH).abs() < 1e-4 && (end[2] + DEPTH).abs() < 1e-4;
            if at_depth {
                continue;
            }
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

/// A run of the binary that takes longer than this is a hang (the bound of the fuzz tests).
pub const WATCHDOG: Duration = Duration::from_secs(10);

/// Exit code and output of one run of the binary.
pub struct Run {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

/// Run the binary with a watchdog: a run over [`WATCHDOG`] is killed and fails the test, a
/// crash (signal, panic message, exit code other than 0/1/2) fails it too.
pub fn run(label: &str, args: &[&str]) -> Run {
    let dir = tempfile::tempdir().expect("tempdir");
    let (out, err) = (dir.path().join("out"), dir.path().join("err"));
    let mut child = Command::new(env!("CARGO_BIN_EXE_trochoplan"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out).expect("stdout file"))
        .stderr(std::fs::File::create(&err).expect("stderr file"))
        .spawn()
        .expect("run trochoplan");
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().expect("wait") {
            break s;
        }
        if start.elapsed() > WATCHDOG {
            let _ = child.kill();
            panic!("{label}: ran over {WATCHDOG:?}: trochoplan {args:?}");
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let r = Run {
        code: status.code().unwrap_or_else(|| panic!("{label}: killed by a signal: trochoplan {args:?}")),
        stdout: std::fs::read_to_string(out).expect("stdout"),
        stderr: std::fs::read_to_string(err).expect("stderr"),
    };
    assert!(!r.stderr.contains("panicked"), "{label}: panic: {}", r.stderr);
    assert!((0..=2).contains(&r.code), "{label}: exit {}: {}", r.code, r.stderr);
    r
}

// ---- exact clearance of every move below the stock top ----

/// An XY arc of a motion: centre, radius (the mean of the written start and end radii),
/// start angle and signed sweep, and `spread`, half the difference of the two radii (a
/// controller runs such an arc as a spiral that stays within `spread` of the mean circle).
struct Arc2 {
    c: P2,
    radius: f64,
    a0: f64,
    sweep: f64,
    spread: f64,
}

impl Arc2 {
    fn of(start: [f64; 3], end: [f64; 3], c: P2, turns: i32) -> Arc2 {
        let tau = std::f64::consts::TAU;
        let (vs, ve) = (p2(start[0], start[1]) - c, p2(end[0], end[1]) - c);
        let (a0, a1) = (vs.y.atan2(vs.x), ve.y.atan2(ve.x));
        let mut sweep = if turns > 0 { (a1 - a0).rem_euclid(tau) } else { -(a0 - a1).rem_euclid(tau) };
        if sweep.abs() < 1e-9 {
            sweep = tau * f64::from(turns.signum());
        }
        sweep += tau * f64::from(turns.abs() - 1) * f64::from(turns.signum());
        Arc2 { c, radius: 0.5 * (vs.norm() + ve.norm()), a0, sweep, spread: 0.5 * (vs.norm() - ve.norm()).abs() }
    }
    /// Whether the direction `theta` from the centre lies on the arc.
    fn covers(&self, theta: f64) -> bool {
        let tau = std::f64::consts::TAU;
        if self.sweep.abs() >= tau {
            return true;
        }
        if self.sweep >= 0.0 {
            (theta - self.a0).rem_euclid(tau) <= self.sweep
        } else {
            (self.a0 - theta).rem_euclid(tau) <= -self.sweep
        }
    }
    fn at(&self, theta: f64) -> P2 {
        self.c + p2(theta.cos(), theta.sin()) * self.radius
    }
    /// Exact distance from `p` to the arc (mean circle).
    fn point_distance(&self, p: P2) -> f64 {
        let v = p - self.c;
        if v.norm() > 0.0 && self.covers(v.y.atan2(v.x)) {
            (v.norm() - self.radius).abs()
        } else if v.norm() == 0.0 {
            self.radius
        } else {
            (p - self.at(self.a0)).norm().min((p - self.at(self.a0 + self.sweep)).norm())
        }
    }
    /// Exact distance from the segment a–b to the arc (mean circle). The minimum of the
    /// distance between a segment and an arc is at an end of either (end point to the other
    /// curve), at a point where they cross (0), or where the arc's radius through the foot of
    /// the centre on the segment's line meets the arc (the line's distance minus the radius).
    fn segment_distance(&self, a: P2, b: P2) -> f64 {
        let mut d = self
            .point_distance(a)
            .min(self.point_distance(b))
            .min(dist_to_edge(self.at(self.a0), a, b))
            .min(dist_to_edge(self.at(self.a0 + self.sweep), a, b));
        let len = (b - a).norm();
        if len == 0.0 {
            return d;
        }
        let u = (b - a) / len;
        let t = (self.c - a).dot(&u);
        let foot = a + u * t;
        let h = (self.c - foot).norm();
        if h >= self.radius {
            let n = foot - self.c;
            if (0.0..=len).contains(&t) && (h == 0.0 || self.covers(n.y.atan2(n.x))) {
                d = d.min(h - self.radius);
            }
        } else {
            let s = (self.radius * self.radius - h * h).sqrt();
            for tt in [t - s, t + s] {
                let q = a + u * tt - self.c;
                if (0.0..=len).contains(&tt) && self.covers(q.y.atan2(q.x)) {
                    return 0.0;
                }
            }
        }
        d
    }
}

fn orient(a: P2, b: P2, c: P2) -> f64 {
    (b - a).perp(&(c - a))
}

/// Exact distance between the segments p–q and a–b: 0 where they cross, else the least
/// distance of an end point from the other segment.
pub fn segment_segment_distance(p: P2, q: P2, a: P2, b: P2) -> f64 {
    let (o1, o2, o3, o4) = (orient(p, q, a), orient(p, q, b), orient(a, b, p), orient(a, b, q));
    if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
        return 0.0;
    }
    dist_to_edge(p, a, b).min(dist_to_edge(q, a, b)).min(dist_to_edge(a, p, q)).min(dist_to_edge(b, p, q))
}

/// Exact XY distance between what the tool centre sweeps in one motion and the edge a–b (an
/// arc less its spiral spread; a straight move of any kind as its XY segment).
pub fn motion_edge_distance(m: &Motion, a: P2, b: P2) -> f64 {
    let xy = |p: [f64; 3]| p2(p[0], p[1]);
    match *m {
        Motion::Arc { start, end, center, turns } => {
            let arc = Arc2::of(start, end, center, turns);
            arc.segment_distance(a, b) - arc.spread
        }
        _ => segment_segment_distance(xy(m.start()), xy(m.end()), a, b),
    }
}

/// The region the tool centre's disc may cover below the stock top: the pocket, and for each
/// open edge the half-strip it sweeps along its outward normal (the planner's own model: the
/// stock is the polygon, beyond an open edge is air). Its boundary as segments: the closed
/// edges and the strips' side rays (cut at 10 m), split where they cross or touch one another
/// or an open edge, keeping the pieces with the region on one side only (an edge or a ray
/// with the region on both sides, e.g. a closed edge beside an open one at a reflex corner,
/// has no material behind it).
pub struct Walls {
    poly: Vec<P2>,
    /// Open edges as (start, direction, length, outward normal).
    strips: Vec<(P2, P2, f64, P2)>,
    /// Pieces of the region's boundary: every one has material on one side.
    pub pieces: Vec<(P2, P2)>,
}

impl Walls {
    pub fn new(polygon: &[(f64, f64)], open: &[usize]) -> Walls {
        let poly: Vec<P2> = polygon.iter().map(|&(x, y)| p2(x, y)).collect();
        let n = poly.len();
        let area2: f64 = (0..n).map(|i| poly[i].perp(&poly[(i + 1) % n])).sum();
        let edge = |i: usize| (poly[i], poly[(i + 1) % n]);
        let strips: Vec<(P2, P2, f64, P2)> = open
            .iter()
            .map(|&i| {
                let (a, b) = edge(i);
                let u = (b - a) / (b - a).norm();
                // outward: right of the edge for a counter-clockwise polygon
                let out = if area2 > 0.0 { p2(u.y, -u.x) } else { p2(-u.y, u.x) };
                (a, u, (b - a).norm(), out)
            })
            .collect();
        let mut curves: Vec<(P2, P2)> = (0..n).filter(|i| !open.contains(i)).map(edge).collect();
        for &(a, u, len, out) in &strips {
            curves.push((a, a + out * 1e4));
            curves.push((a + u * len, a + u * len + out * 1e4));
        }
        let cutters: Vec<(P2, P2)> = curves.iter().copied().chain(open.iter().map(|&i| edge(i))).collect();
        let mut w = Walls { poly, strips, pieces: Vec::new() };
        for &(p, q) in &curves {
            let d = q - p;
            let mut ts = vec![0.0, 1.0];
            for &(a, b) in &cutters {
                let e = b - a;
                let den = d.perp(&e);
                if den.abs() > 1e-12 {
                    let t = (a - p).perp(&e) / den;
                    let s = (a - p).perp(&d) / den;
                    if (0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&s) {
                        ts.push(t);
                    }
                }
                for c in [a, b] {
                    let t = (c - p).dot(&d) / d.dot(&d);
                    if (0.0..=1.0).contains(&t) && (p + d * t - c).norm() < 1e-9 {
                        ts.push(t);
                    }
                }
            }
            ts.sort_by(f64::total_cmp);
            for t in ts.windows(2) {
                let (s, e) = (p + d * t[0], p + d * t[1]);
                if (e - s).norm() < 1e-9 {
                    continue;
                }
                let m = (s + e) * 0.5;
                let nrm = p2(-(e - s).y, (e - s).x) / (e - s).norm() * 1e-6;
                if w.contains(m + nrm) != w.contains(m - nrm) {
                    w.pieces.push((s, e));
                }
            }
        }
        w
    }

    /// Whether `q` is in the pocket, on an open edge or beyond it.
    pub fn contains(&self, q: P2) -> bool {
        inside(q, &self.poly)
            || self.strips.iter().any(|&(a, u, len, out)| {
                // on the open edge itself or beyond it (1 nm: a point on the edge counts)
                (q - a).dot(&out) >= -1e-9 && (-1e-9..=len + 1e-9).contains(&(q - a).dot(&u))
            })
    }
}

/// The wall check of every move below the stock top: no move below Z0, of any kind, brings
/// the tool centre closer than r − `slack` to material ([`Walls`]: the closed edges, and the
/// sides of the air beyond the open edges). `polygon` as written in the polygon file; `open`
/// the indices of its open edges (edge i from vertex i to i + 1). A move is below the stock top
/// when either end is below Z0 (−1e-6 for the printed rounding). Its distance from each wall
/// piece is computed exactly (segment to segment, arc to segment); its start must lie inside
/// the region: a continuous move that keeps more than 0 from every piece then never leaves
/// it. A rapid below Z0 is a retract straight up, a descent straight down where the tool's
/// whole disc is off the stock (outside the polygon, r − `slack` from it), or a move in the
/// plane at one height (a rapid at depth through cleared stock, wall-checked like any move;
/// that it cuts nothing is checked by the evaluator in the acceptance tests): anything else is
/// reported. Returns a description of the offending moves (at most 3), or nothing.
pub fn below_top_violations(all: &[Motion], polygon: &[(f64, f64)], open: &[usize], r: f64, slack: f64) -> Vec<String> {
    let walls = Walls::new(polygon, open);
    let v: Vec<P2> = polygon.iter().map(|&(x, y)| p2(x, y)).collect();
    let allowed = r - slack;
    let mut bad = Vec::new();
    for (k, m) in all.iter().enumerate() {
        let (s, e) = (m.start(), m.end());
        if s[2].min(e[2]) >= -1e-6 {
            continue;
        }
        let ps = p2(s[0], s[1]);
        let pe = p2(e[0], e[1]);
        if let Motion::Rapid { .. } = m {
            let vertical = (ps - pe).norm() < 1e-9;
            let up = e[2] > s[2];
            let off_stock = !inside(ps, &v) && trochoplan_core::geom::loop_distance(ps, &v) >= allowed;
            let level = (e[2] - s[2]).abs() < 1e-9 && !vertical;
            if !(level || vertical && (up || off_stock)) {
                bad.push(format!("motion {k}: rapid below Z0 {m:?}"));
            }
        }
        if !walls.contains(ps) {
            bad.push(format!("motion {k}: starts in the material at Z {:.4}: {m:?}", s[2]));
        }
        for &(a, b) in &walls.pieces {
            let d = motion_edge_distance(m, a, b);
            #[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN fails
            if !(d >= allowed) {
                bad.push(format!(
                    "motion {k} ({}) at Z {:.4}..{:.4}: tool centre {d:.4} mm from the wall {:?}-{:?} < r - {slack} = {allowed:.4}: {m:?}",
                    kind(m),
                    s[2],
                    e[2],
                    (a.x, a.y),
                    (b.x, b.y)
                ));
                break;
            }
        }
        if bad.len() >= 3 {
            break;
        }
    }
    bad
}

fn kind(m: &Motion) -> &'static str {
    match m {
        Motion::Rapid { .. } => "G0",
        Motion::Line { .. } => "G1",
        Motion::Arc { .. } => "G2/G3",
    }
}
