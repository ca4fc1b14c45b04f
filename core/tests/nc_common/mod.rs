//! Test-side helpers shared by `core/tests/nc_*.rs` and the top-level `tests/nc_rs274.rs` and
//! `tests/nc_corner_rs274.rs`:
//! motions read back from a program (by our Sinumerik/ISO evaluator or by LinuxCNC's rs274),
//! and the checks against the plan. Independent of the emitter: they only use the exact
//! planned segments (`SlotPath::segments`) and plain geometry.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
#![allow(dead_code)]

use std::path::Path;
use std::process::{Command, Stdio};
use trochoplan_core::geom::{P2, Segment, p2};
use trochoplan_core::{Job, PathKind, Plan, plan};

/// One move of the tool centre as a controller executes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Motion {
    /// G0 / STRAIGHT_TRAVERSE.
    Rapid { start: [f64; 3], end: [f64; 3] },
    /// G1 / STRAIGHT_FEED.
    Line { start: [f64; 3], end: [f64; 3] },
    /// G2/G3 / ARC_FEED in the XY plane: `turns` > 0 counter-clockwise, < 0 clockwise, |turns|
    /// = 1 up to one full turn (start = end: a full circle). Radius may change linearly
    /// with the angle (a controller's "spiral" when the written radii differ slightly).
    Arc { start: [f64; 3], end: [f64; 3], center: P2, turns: i32 },
}

impl Motion {
    pub fn start(&self) -> [f64; 3] {
        match *self {
            Motion::Rapid { start, .. } | Motion::Line { start, .. } | Motion::Arc { start, .. } => start,
        }
    }
    pub fn end(&self) -> [f64; 3] {
        match *self {
            Motion::Rapid { end, .. } | Motion::Line { end, .. } | Motion::Arc { end, .. } => end,
        }
    }
}

fn xy(p: [f64; 3]) -> P2 {
    p2(p[0], p[1])
}

/// Signed sweep (rad) and start/end radius of an arc motion.
fn arc_sweep(start: P2, end: P2, center: P2, turns: i32) -> (f64, f64, f64, f64) {
    let (vs, ve) = (start - center, end - center);
    let a0 = vs.y.atan2(vs.x);
    let a1 = ve.y.atan2(ve.x);
    let tau = std::f64::consts::TAU;
    let mut sweep = if turns > 0 { (a1 - a0).rem_euclid(tau) } else { -(a0 - a1).rem_euclid(tau) };
    if sweep.abs() < 1e-9 {
        sweep = tau * turns.signum() as f64;
    }
    sweep += tau * (turns.abs() - 1) as f64 * turns.signum() as f64;
    (a0, sweep, vs.norm(), ve.norm())
}

/// A cut as exact segments (XY): lines, and arcs about their written centre with the mean of
/// their start and end radii (they differ by the written rounding only), for the evaluator.
pub fn segments_of(cut: &[Motion]) -> Vec<Segment> {
    cut.iter()
        .map(|m| match *m {
            Motion::Arc { start, end, center, turns } => {
                let (start_angle, sweep, r0, r1) = arc_sweep(xy(start), xy(end), center, turns);
                Segment::Arc { center, radius: 0.5 * (r0 + r1), start_angle, sweep }
            }
            _ => Segment::Line { start: xy(m.start()), end: xy(m.end()) },
        })
        .collect()
}

/// The moves at cutting depth (z = −depth within `z_tol`), in program order: the cut. Rapids
/// at depth (a pocket's moves through cleared stock) are part of it: they follow the planned
/// path like the feed moves; whether they may be there is each caller's check.
pub fn cut(motions: &[Motion], depth: f64, z_tol: f64) -> Vec<Motion> {
    motions
        .iter()
        .copied()
        .filter(|m| (m.start()[2] + depth).abs() <= z_tol && (m.end()[2] + depth).abs() <= z_tol)
        .filter(|m| (xy(m.end()) - xy(m.start())).norm() > 0.0 || matches!(m, Motion::Arc { .. }))
        .collect()
}

/// XY length of the cut.
pub fn length(cut: &[Motion]) -> f64 {
    cut.iter()
        .map(|m| match *m {
            Motion::Arc { start, end, center, turns } => {
                let (_, sweep, r0, r1) = arc_sweep(xy(start), xy(end), center, turns);
                0.5 * (r0 + r1) * sweep.abs()
            }
            _ => (xy(m.end()) - xy(m.start())).norm(),
        })
        .sum()
}

/// Points along the cut, at most `h` apart.
pub fn sample(cut: &[Motion], h: f64) -> Vec<P2> {
    let mut pts = Vec::new();
    for m in cut {
        match *m {
            Motion::Arc { start, end, center, turns } => {
                let (a0, sweep, r0, r1) = arc_sweep(xy(start), xy(end), center, turns);
                let n = ((0.5 * (r0 + r1) * sweep.abs() / h).ceil() as usize).max(1);
                for i in 0..=n {
                    let f = i as f64 / n as f64;
                    let (a, r) = (a0 + sweep * f, r0 + (r1 - r0) * f);
                    pts.push(center + p2(a.cos(), a.sin()) * r);
                }
            }
            _ => {
                let (s, e) = (xy(m.start()), xy(m.end()));
                let n = (((e - s).norm() / h).ceil() as usize).max(1);
                pts.extend((0..=n).map(|i| s + (e - s) * (i as f64 / n as f64)));
            }
        }
    }
    pts
}

/// Points along the planned path (exact segments), spaced at most `h` in arc length.
pub fn planned_samples(plan: &Plan, h: f64) -> Vec<P2> {
    segment_samples(plan.path.segments(), h)
}

/// Points along exact segments, spaced at most `h` in arc length.
pub fn segment_samples(segments: impl IntoIterator<Item = Segment>, h: f64) -> Vec<P2> {
    let mut pts = Vec::new();
    for seg in segments {
        let n = ((seg.length() / h).ceil() as usize).max(1);
        pts.extend(seg.sample(n));
    }
    pts
}

/// Distance from `p` to the chord `a`–`b` (plain arithmetic: this is the hot loop of the
/// checks and runs unoptimised in tests).
fn dist_to_chord(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> f64 {
    let (abx, aby) = (b[0] - a[0], b[1] - a[1]);
    let (apx, apy) = (p[0] - a[0], p[1] - a[1]);
    let l2 = abx * abx + aby * aby;
    let t = if l2 > 0.0 { ((apx * abx + apy * aby) / l2).clamp(0.0, 1.0) } else { 0.0 };
    let (dx, dy) = (apx - abx * t, apy - aby * t);
    (dx * dx + dy * dy).sqrt()
}

/// Chord distances closer than this (mm) count as equal when the ordered match moves its
/// cursor: more than the rounding that makes two written copies of one line differ (≤ √2·q,
/// q ≤ 1e-3 mm), less than the smallest budget (`budget(0.005, 1e-4)` = 0.0055 mm). The
/// cursor then lags the nearest chord by at most this much of path on a line (a chord or two
/// on a curve), far inside the 0.4 mm window; the deviation counted is unchanged.
const TIE_MM: f64 = 0.005;

/// Largest distance of the points `a` from the polyline `b`, matching in order: a cursor
/// walks forward along `b` and each point of `a` is measured against the next `window`
/// chords only. The loops of a trochoidal path overlap their neighbours, so an unordered
/// nearest-point search would hide a skipped or repeated cycle; this one does not.
pub fn ordered_deviation(a: &[P2], b: &[P2], window: usize) -> f64 {
    let b: Vec<[f64; 2]> = b.iter().map(|p| [p.x, p.y]).collect();
    if b.len() < 2 {
        return f64::INFINITY;
    }
    let mut cursor = 0usize;
    let mut worst: f64 = 0.0;
    let mut d = Vec::with_capacity(window);
    for p in a {
        let p = [p.x, p.y];
        let end = (cursor + window).min(b.len() - 1);
        d.clear();
        d.extend((cursor..end).map(|j| dist_to_chord(b[j], b[j + 1], p)));
        let best = d.iter().copied().fold(f64::INFINITY, f64::min);
        // The cursor moves to the first chord as close as the best within TIE_MM: where the
        // path retraces itself (a corner path reversing along the line it came on), chords
        // behind and ahead of the turn are equally close, and the later one would skip the
        // turn. The deviation counted is `best` either way.
        if let Some(k) = d.iter().position(|&x| x <= best + TIE_MM) {
            cursor += k;
        }
        worst = worst.max(best);
    }
    // the walk must have reached the end of b, or part of b was never matched
    if cursor + window < b.len() - 1 { f64::INFINITY } else { worst }
}

/// [`ordered_deviation`] with the window ahead of the cursor at least `reach` mm of `b`'s
/// chords long (and at least `window` chords): the same walk where `b` is sampled densely.
pub fn ordered_deviation_within(a: &[P2], b: &[P2], window: usize, reach: f64) -> f64 {
    if b.len() < 2 {
        return f64::INFINITY;
    }
    // cumulative chord length of b
    let mut acc = Vec::with_capacity(b.len());
    let mut total = 0.0;
    acc.push(0.0);
    for w in b.windows(2) {
        total += (w[1] - w[0]).norm();
        acc.push(total);
    }
    let end_of = |cursor: usize| {
        let by_len = acc.partition_point(|&l| l < acc[cursor] + reach);
        (cursor + window).max(by_len).min(b.len() - 1)
    };
    let mut cursor = 0usize;
    let mut worst: f64 = 0.0;
    for p in a {
        let end = end_of(cursor);
        let d: Vec<f64> =
            (cursor..end).map(|j| dist_to_chord([b[j].x, b[j].y], [b[j + 1].x, b[j + 1].y], [p.x, p.y])).collect();
        let best = d.iter().copied().fold(f64::INFINITY, f64::min);
        if let Some(k) = d.iter().position(|&x| x <= best + TIE_MM) {
            cursor += k;
        }
        worst = worst.max(best);
    }
    // the walk must have reached the end of b, or part of b was never matched
    if end_of(cursor) < b.len() - 1 { f64::INFINITY } else { worst }
}

/// Two-sided ordered deviation between a cut and the planned path.
pub fn deviation_from_plan(cut: &[Motion], plan: &Plan) -> f64 {
    deviation_from_segments(cut, plan.path.segments())
}

/// Two-sided ordered deviation between a cut and any planned path given as exact segments
/// in machining order (a pocket corner, for instance). Both are split where they jump (a
/// retract between two pieces of a pocket): the pieces are compared in order, one to one, so a
/// jump can never be matched against a cut that runs along it; a different number of pieces is
/// a structural mismatch (infinite deviation).
pub fn deviation_from_segments(cut: &[Motion], segments: impl IntoIterator<Item = Segment>) -> f64 {
    const H: f64 = 0.02;
    let mut planned: Vec<Vec<Segment>> = Vec::new();
    for seg in segments {
        match planned.last_mut() {
            Some(piece) if piece.last().is_some_and(|l: &Segment| (seg.start() - l.end()).norm() <= 1e-6) => {
                piece.push(seg)
            }
            _ => planned.push(vec![seg]),
        }
    }
    let mut moves: Vec<Vec<Motion>> = Vec::new();
    for m in cut {
        match moves.last_mut() {
            Some(piece) if piece.last().is_some_and(|l: &Motion| xy(l.end()) == xy(m.start())) => piece.push(*m),
            _ => moves.push(vec![*m]),
        }
    }
    if planned.len() != moves.len() {
        return f64::INFINITY;
    }
    // both are sampled at ≤ H, so the match moves a sample or two per step; 0.4 mm of path
    // ahead is far more than that and than any deviation we accept
    // (as path length: where segments are shorter than H, e.g. a pocket's corner arcs of
    // 0.005 mm radius, two samples each, more chords than 0.4/H)
    let window = (0.4 / H) as usize;
    planned.into_iter().zip(&moves).fold(0.0, |worst: f64, (segs, piece)| {
        let prog = sample(piece, H);
        let plan = segment_samples(segs, H);
        worst
            .max(ordered_deviation_within(&prog, &plan, window, 0.4))
            .max(ordered_deviation_within(&plan, &prog, window, 0.4))
    })
}

/// Allowed distance from the planned path: the fit tolerance, plus rounding to the quantum q
/// (end points ≤ q/√2; the written centre ≤ q/√2 off, which moves the arc by as much; start
/// and end radii differ ≤ q√2, which the controller spreads as a spiral): < 3q; plus 2e-4 mm
/// for rs274's 4-decimal print (≤ 7.1e-5) and the chords of the sampled plan (h²/8ρ ≤ 1e-4
/// for h = 0.02 mm and ρ ≥ 0.5 mm).
pub fn budget(tol: f64, q: f64) -> f64 {
    tol + 3.0 * q + 2e-4
}

/// Every check of a slot cut read back from a program (docs/nc-export.md): it follows the plan within
/// `budget`, never leaves |x| ≤ (B − D)/2 by more than the rounding, and has the analysis'
/// path length within 0.1 %. Returns a description of the first failure.
pub fn check_cut(label: &str, cut: &[Motion], plan: &Plan, tol: f64, q: f64) -> Result<(), String> {
    if cut.is_empty() {
        return Err(format!("{label}: no cutting moves"));
    }
    check_deviation(label, deviation_from_plan(cut, plan), tol, q)?;
    let a = plan.job.trochoidal_radius();
    let max_x = sample(cut, 0.02).iter().map(|p| p.x.abs()).fold(0.0, f64::max);
    let band = a + 3.0 * q + 1e-4;
    if max_x > band {
        return Err(format!("{label}: |x| reaches {max_x:.6} mm > (B - D)/2 + rounding = {band:.6} mm (wall gouge)"));
    }
    check_length(label, length(cut), plan.metrics.path_length_mm)
}

/// The checks of [`check_cut`] that apply to any planned path given as exact segments: it
/// follows the segments within `budget` and has their length within 0.1 %. (The wall band is
/// the caller's: it depends on what the path machines.)
pub fn check_path_cut(label: &str, cut: &[Motion], segments: &[Segment], tol: f64, q: f64) -> Result<(), String> {
    if cut.is_empty() {
        return Err(format!("{label}: no cutting moves"));
    }
    check_deviation(label, deviation_from_segments(cut, segments.iter().copied()), tol, q)?;
    check_length(label, length(cut), segments.iter().map(Segment::length).sum())
}

fn check_deviation(label: &str, dev: f64, tol: f64, q: f64) -> Result<(), String> {
    let allowed = budget(tol, q);
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // deliberately NaN-safe: NaN fails the check
    if !(dev <= allowed) {
        // written so that a NaN deviation fails too
        return Err(format!("{label}: deviation from the planned path {dev:.6} mm > {allowed:.6} mm"));
    }
    Ok(())
}

fn check_length(label: &str, len: f64, want: f64) -> Result<(), String> {
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN fails
    if !((len - want).abs() <= 1e-3 * want) {
        return Err(format!("{label}: path length {len:.4} mm vs analysis {want:.4} mm (> 0.1 %)"));
    }
    Ok(())
}

/// Point halfway along an arc motion (by angle; radius interpolated as the controller does).
fn arc_midpoint(start: [f64; 3], end: [f64; 3], center: P2, turns: i32) -> P2 {
    let (a0, sweep, r0, r1) = arc_sweep(xy(start), xy(end), center, turns);
    let a = a0 + 0.5 * sweep;
    center + p2(a.cos(), a.sin()) * (0.5 * (r0 + r1))
}

/// Motions of two programs agree block by block within `tol`: same kind and direction, end
/// points and arc midpoints within `tol` (not the centres: for a shallow arc a centre moves
/// far along the normal when an end point moves by a rounding step, while the arc does not).
pub fn same_motion(a: &[Motion], b: &[Motion], tol: f64) -> Result<(), String> {
    if a.len() != b.len() {
        return Err(format!("{} vs {} motions", a.len(), b.len()));
    }
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        let close = |p: [f64; 3], q: [f64; 3]| (0..3).all(|i| (p[i] - q[i]).abs() <= tol);
        let ok = match (*x, *y) {
            (
                Motion::Arc { start: s0, end: e0, center: c0, turns: t0 },
                Motion::Arc { start: s1, end: e1, center: c1, turns: t1 },
            ) => t0 == t1 && (arc_midpoint(s0, e0, c0, t0) - arc_midpoint(s1, e1, c1, t1)).norm() <= 2.0 * tol,
            (Motion::Line { .. }, Motion::Line { .. }) | (Motion::Rapid { .. }, Motion::Rapid { .. }) => true,
            _ => false,
        };
        if !ok || !close(x.end(), y.end()) {
            return Err(format!("motion {k}: {x:?} vs {y:?}"));
        }
    }
    Ok(())
}

/// The test job of each path type: Table 1 conditions; r_e = 0.8 for the elliptical path,
/// r_e = 0.6 with d = 0.75 mm for the linear-elliptical one.
pub fn job(path: PathKind) -> Plan {
    let (r_e, d) = match path {
        PathKind::Elliptical => (0.8, 0.0),
        PathKind::LinearElliptical => (0.6, 0.75),
        _ => (1.0, 0.0),
    };
    plan(&Job { path, aspect_ratio: r_e, linear_distance: d, ..Job::default() }).expect("valid")
}

// ---- LinuxCNC's standalone interpreter rs274 (used by the top-level tests/nc_*rs274.rs) ----

/// The rs274 binary: $RS274, or `rs274` on the PATH.
pub fn rs274() -> String {
    std::env::var("RS274").unwrap_or_else(|_| "rs274".to_string())
}

/// Run rs274 on `file`; the canonical calls it printed, or the interpreter's error.
pub fn interpret(file: &Path) -> Result<String, String> {
    let out = file.with_extension("canon");
    // rs274 creates and maps $HOME/.tool.mmap with O_TRUNC: runs in parallel (test threads)
    // sharing one HOME truncate each other's mapping and die with SIGBUS. One HOME per run.
    let home = file.with_extension("home");
    std::fs::create_dir_all(&home).unwrap_or_else(|e| panic!("{}: {e}", home.display()));
    let run = Command::new(rs274())
        .arg("-g")
        .arg(file)
        .arg(&out)
        .env("HOME", &home)
        .stdin(Stdio::null())
        .output()
        .unwrap_or_else(|e| {
            panic!(
                "cannot run `{}` ({e}). These tests need LinuxCNC's standalone G-code interpreter: \
                 apt-get install -y --no-install-recommends linuxcnc-uspace (Debian bookworm), \
                 or set RS274 to its path",
                rs274()
            )
        });
    let stderr = String::from_utf8_lossy(&run.stderr);
    // rs274 prints "executing" on stderr; anything else there is an interpreter message
    let messages: Vec<&str> = stderr.lines().filter(|l| l.trim() != "executing" && !l.trim().is_empty()).collect();
    if !run.status.success() || !messages.is_empty() {
        return Err(format!("rs274 {} on {}: {}", run.status, file.display(), messages.join(" | ")));
    }
    std::fs::read_to_string(&out).map_err(|e| format!("{}: {e}", out.display()))
}

/// rs274 on `file` with the tool table `table` (its lines, e.g. "T7 P7 D10.0 Z0 ;tool 7"):
/// rs274's built-in table has tools 1 to 3 only. Its canonical calls; a failed run or any
/// message of the interpreter fails the test.
pub fn rs274_with_tools(file: &Path, table: &str) -> String {
    let home = file.with_extension("home");
    std::fs::create_dir_all(&home).expect("home");
    let tbl = home.join("tools.tbl");
    std::fs::write(&tbl, table).expect("tool table");
    let canon = file.with_extension("canon");
    let run = Command::new(rs274())
        .arg("-t")
        .arg(&tbl)
        .arg("-g")
        .arg(file)
        .arg(&canon)
        .env("HOME", &home)
        .stdin(Stdio::null())
        .output()
        .expect("run rs274 (apt-get install linuxcnc-uspace, or set RS274)");
    let stderr = String::from_utf8_lossy(&run.stderr);
    let messages: Vec<&str> = stderr.lines().filter(|l| l.trim() != "executing" && !l.trim().is_empty()).collect();
    assert!(run.status.success() && messages.is_empty(), "rs274 on {}: {}", file.display(), messages.join(" | "));
    std::fs::read_to_string(&canon).expect("canon")
}

/// The motions in rs274's canonical output, from (0, 0, 0).
pub fn motions(canon: &str) -> Vec<Motion> {
    let mut pos = [0.0f64; 3];
    let mut out = Vec::new();
    for line in canon.lines() {
        let Some((name, rest)) = line.split_once('(') else { continue };
        let name = name.split_whitespace().last().unwrap_or("");
        let args: Vec<f64> = rest.trim_end_matches(')').split(',').filter_map(|a| a.trim().parse().ok()).collect();
        let m = match name {
            "STRAIGHT_TRAVERSE" => Motion::Rapid { start: pos, end: [args[0], args[1], args[2]] },
            "STRAIGHT_FEED" => Motion::Line { start: pos, end: [args[0], args[1], args[2]] },
            // ARC_FEED(first_end, second_end, first_axis, second_axis, rotation, axis_end_point, …)
            "ARC_FEED" => Motion::Arc {
                start: pos,
                end: [args[0], args[1], args[5]],
                center: p2(args[2], args[3]),
                turns: args[4] as i32,
            },
            _ => continue,
        };
        pos = m.end();
        out.push(m);
    }
    out
}

/// Two 40 × 40 lobes joined by a 20 × 16 neck: inner rings split into one loop per lobe, and
/// links from lobe to lobe cannot be straight feed moves (they would slot across the uncut
/// neck or pass its corners closer than r): retracts.
pub const DUMBBELL: &[(f64, f64)] = &[
    (0.0, 0.0),
    (40.0, 0.0),
    (40.0, 12.0),
    (60.0, 12.0),
    (60.0, 0.0),
    (100.0, 0.0),
    (100.0, 40.0),
    (60.0, 40.0),
    (60.0, 28.0),
    (40.0, 28.0),
    (40.0, 40.0),
    (0.0, 40.0),
];

/// Two 30 × 30 lobes joined by a 10 mm long neck 8 mm wide: narrower than D = 10, so the tool
/// cannot pass it (the neck's mouths get cusp passes, docs/adaptive-clearing.md).
pub const DUMBBELL_8: &[(f64, f64)] = &[
    (0.0, 0.0),
    (30.0, 0.0),
    (30.0, 11.0),
    (40.0, 11.0),
    (40.0, 0.0),
    (70.0, 0.0),
    (70.0, 30.0),
    (40.0, 30.0),
    (40.0, 19.0),
    (30.0, 19.0),
    (30.0, 30.0),
    (0.0, 30.0),
];

/// A comb: a 100 × 15 base with five prongs up to y = 50 and four wall teeth between them
/// (x 20–28, 40–48, 60–68, 80–88): a straight link from one prong to another crosses a tooth.
pub const COMB: &[(f64, f64)] = &[
    (0.0, 0.0),
    (100.0, 0.0),
    (100.0, 50.0),
    (88.0, 50.0),
    (88.0, 15.0),
    (80.0, 15.0),
    (80.0, 50.0),
    (68.0, 50.0),
    (68.0, 15.0),
    (60.0, 15.0),
    (60.0, 50.0),
    (48.0, 50.0),
    (48.0, 15.0),
    (40.0, 15.0),
    (40.0, 50.0),
    (28.0, 50.0),
    (28.0, 15.0),
    (20.0, 15.0),
    (20.0, 50.0),
    (0.0, 50.0),
];

/// An 80 × 50 U channel: a 30 wide, 30 deep notch from the middle of the top edge, two reflex
/// corners at (25, 20) and (55, 20).
pub const U_CHANNEL: &[(f64, f64)] =
    &[(0.0, 0.0), (80.0, 0.0), (80.0, 50.0), (55.0, 50.0), (55.0, 20.0), (25.0, 20.0), (25.0, 50.0), (0.0, 50.0)];

/// A 60 × 60 L with 25 mm arms, its reflex corner at (25, 25).
pub const L_60X60: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 25.0), (25.0, 25.0), (25.0, 60.0), (0.0, 60.0)];
