//! No pocket shape breaks the engagement target: random simple polygons — rectangles with
//! notches and tabs, L, T, U and plus shapes, necks, acute and reflex corners, star-ish
//! outlines, outlines with short edges — drawn by a fixed-seed generator, each planned with the
//! default pocket (adaptive clearing, default target) through [`pocket::plan`], for a tool of
//! D = 10 mm and of D = 6 mm. Each plan must either
//!
//! (a) keep the peak of its own measurement (every move at depth: entries, spiral, rings,
//!     links, corner passes, finish, corner points) within the target + 1°, keep every tool
//!     position at least r − 0.005 mm from the walls (checked here, independently of the
//!     planner: every move sampled every 0.05 mm, distance to the polygon's edges) and leave
//!     nothing the tool could reach uncut (an independent raster check, [`uncut_area`]); or
//! (b) be refused with an error that names its reason — never a panic, never NaN.
//!
//! The shapes are drawn in units of the tool diameter, so both tools fit in parts of them and
//! not in others (necks, notches and arms from 0.3·D to 2.5·D wide).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod rng_common;

use rng_common::Rng;
use std::collections::HashMap;
use std::f64::consts::{PI, TAU};
use std::panic::{AssertUnwindSafe, catch_unwind};
use trochoplan_core::geom::{P2, Polygon, Segment, p2};
use trochoplan_core::pocket::{self, PocketPlan, PocketRequest, PocketStrategy};

/// Rectangle [x0, x1] × [y0, y1], counter-clockwise from (x0, y0).
fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<P2> {
    vec![p2(x0, y0), p2(x1, y0), p2(x1, y1), p2(x0, y1)]
}

/// A W × H rectangle (in D) with a notch in its bottom side: a slot out of the pocket
/// (`out`) or a tab of wall into it, `w` wide and `d` deep, at `x` from the left.
fn rect_notch(rng: &mut Rng) -> Vec<P2> {
    let (w, h) = (rng.f(3.0, 5.5), rng.f(2.2, 4.0));
    let nw = rng.f(0.3, 2.0);
    let x = rng.f(0.3, w - nw - 0.3);
    let out = rng.n(2) == 0;
    let d = if out { rng.f(0.3, 1.5) } else { rng.f(0.3, 0.45 * h) };
    let y = if out { -d } else { d };
    vec![p2(0.0, 0.0), p2(x, 0.0), p2(x, y), p2(x + nw, y), p2(x + nw, 0.0), p2(w, 0.0), p2(w, h), p2(0.0, h)]
}

/// An L: arms `a` and `b` wide, `la` and `lb` long.
fn l_shape(rng: &mut Rng) -> Vec<P2> {
    let (a, b) = (rng.f(0.9, 2.5), rng.f(0.9, 2.5));
    let (la, lb) = (rng.f(b + 1.0, 5.0), rng.f(a + 1.0, 5.0));
    vec![p2(0.0, 0.0), p2(la, 0.0), p2(la, a), p2(b, a), p2(b, lb), p2(0.0, lb)]
}

/// A T: a bar `t` thick and `w` wide on a stem `s` wide and `l` long.
fn t_shape(rng: &mut Rng) -> Vec<P2> {
    let (w, t) = (rng.f(3.0, 5.5), rng.f(0.9, 2.2));
    let s = rng.f(0.9, 2.2).min(w - 0.6);
    let l = rng.f(1.0, 3.0);
    let x = rng.f(0.3, w - s - 0.3);
    vec![p2(x, 0.0), p2(x + s, 0.0), p2(x + s, l), p2(w, l), p2(w, l + t), p2(0.0, l + t), p2(0.0, l), p2(x, l)]
}

/// A U: two arms `a`, `b` wide on a base `t` thick, the notch between them `g` wide.
fn u_shape(rng: &mut Rng) -> Vec<P2> {
    let (a, b, g) = (rng.f(0.9, 2.5), rng.f(0.9, 2.5), rng.f(0.4, 3.0));
    let (t, h) = (rng.f(0.9, 2.2), rng.f(3.0, 5.0));
    let w = a + g + b;
    vec![p2(0.0, 0.0), p2(w, 0.0), p2(w, h), p2(a + g, h), p2(a + g, t), p2(a, t), p2(a, h), p2(0.0, h)]
}

/// A plus: arms `a` wide reaching `l` beyond a square hub.
fn plus(rng: &mut Rng) -> Vec<P2> {
    let a = rng.f(1.0, 2.2);
    let l: Vec<f64> = (0..4).map(|_| rng.f(0.5, 2.0)).collect();
    let (x0, x1) = (-0.5 * a, 0.5 * a);
    vec![
        p2(x0, x0 - l[0]),
        p2(x1, x0 - l[0]),
        p2(x1, x0),
        p2(x1 + l[1], x0),
        p2(x1 + l[1], x1),
        p2(x1, x1),
        p2(x1, x1 + l[2]),
        p2(x0, x1 + l[2]),
        p2(x0, x1),
        p2(x0 - l[3], x1),
        p2(x0 - l[3], x0),
        p2(x0, x0),
    ]
}

/// Two rectangles joined by a neck `n` wide (below, about and above D) and `l` long.
fn neck(rng: &mut Rng) -> Vec<P2> {
    let (w1, h1, w2, h2) = (rng.f(1.8, 3.0), rng.f(1.8, 3.0), rng.f(1.8, 3.0), rng.f(1.8, 3.0));
    let n = rng.f(0.7, 1.6).min(h1.min(h2) - 0.4);
    let l = rng.f(0.2, 1.5);
    let (y1, y2) = (rng.f(0.2, h1 - n - 0.2), rng.f(0.2, h2 - n - 0.2));
    // left box [0, w1] × [0, h1], neck from x = w1 to w1 + l at y1..y1 + n, right box shifted so
    // that the neck enters it at y2
    let dy = y1 - y2;
    let x2 = w1 + l;
    vec![
        p2(0.0, 0.0),
        p2(w1, 0.0),
        p2(w1, y1),
        p2(x2, y1),
        p2(x2, dy),
        p2(x2 + w2, dy),
        p2(x2 + w2, dy + h2),
        p2(x2, dy + h2),
        p2(x2, y1 + n),
        p2(w1, y1 + n),
        p2(w1, h1),
        p2(0.0, h1),
    ]
}

/// A star-ish outline: 5 to 10 points on alternating outer and inner radii (acute tips,
/// reflex valleys), angles jittered. Simple: star-shaped about the origin.
fn star(rng: &mut Rng) -> Vec<P2> {
    let n = 5 + rng.n(6);
    let (outer, inner) = (rng.f(2.2, 3.5), rng.f(1.1, 2.0));
    (0..2 * n)
        .map(|k| {
            let a = (k as f64 + rng.f(-0.25, 0.25)) * PI / n as f64;
            let rad = if k % 2 == 0 { outer * rng.f(0.85, 1.0) } else { inner * rng.f(0.8, 1.0) };
            p2(a.cos(), a.sin()) * rad
        })
        .collect()
}

/// A random star-shaped polygon about the origin: 6 to 14 vertices at radii 1.2 to 3.2
/// (acute and reflex corners of every angle).
fn blob(rng: &mut Rng) -> Vec<P2> {
    let n = 6 + rng.n(9);
    let mut angles: Vec<f64> = (0..n).map(|k| (k as f64 + rng.f(0.1, 0.9)) * TAU / n as f64).collect();
    angles.sort_by(f64::total_cmp);
    angles.iter().map(|&a| p2(a.cos(), a.sin()) * rng.f(1.2, 3.2)).collect()
}

/// A triangle with one acute corner of 20° to 50° and the others as they come.
fn acute(rng: &mut Rng) -> Vec<P2> {
    let alpha = rng.f(20.0, 50.0).to_radians();
    let (l1, l2) = (rng.f(3.5, 6.0), rng.f(3.5, 6.0));
    vec![p2(0.0, 0.0), p2(l1, 0.0), p2(l2 * alpha.cos(), l2 * alpha.sin())]
}

/// A rectangle or an L with short edges: every convex corner chamfered by 0.01·D to 0.4·D
/// (some of them left sharp), and one side cut into a shallow zig-zag of short edges.
fn short_edges(rng: &mut Rng) -> Vec<P2> {
    let base = if rng.n(2) == 0 { rect(0.0, 0.0, rng.f(3.0, 5.0), rng.f(2.2, 4.0)) } else { l_shape(rng) };
    let n = base.len();
    let mut out = Vec::new();
    for i in 0..n {
        let (prev, v, next) = (base[(i + n - 1) % n], base[i], base[(i + 1) % n]);
        let convex = (v - prev).perp(&(next - v)) > 0.0;
        if convex && rng.n(3) > 0 {
            let c = rng.f(0.01, 0.4);
            out.push(v + (prev - v).normalize() * c);
            out.push(v + (next - v).normalize() * c);
        } else {
            out.push(v);
        }
        if i == 0 {
            // the first side, zig-zagged inward by up to 0.08·D over pieces 0.05·D to 0.3·D
            let len = (next - v).norm();
            let (dir, inward) = ((next - v) / len, (next - v).normalize());
            let inward = p2(-inward.y, inward.x);
            let mut s = 0.6;
            while s < len - 0.6 {
                out.push(v + dir * s + inward * rng.f(0.0, 0.08));
                s += rng.f(0.05, 0.3);
            }
        }
    }
    out
}

/// One random shape (in units of D), its family's name.
fn shape(rng: &mut Rng, k: usize) -> (&'static str, Vec<P2>) {
    match k % 10 {
        0 => ("rect-notch", rect_notch(rng)),
        1 => ("L", l_shape(rng)),
        2 => ("T", t_shape(rng)),
        3 => ("U", u_shape(rng)),
        4 => ("plus", plus(rng)),
        5 => ("neck", neck(rng)),
        6 => ("star", star(rng)),
        7 => ("blob", blob(rng)),
        8 => ("acute", acute(rng)),
        _ => ("short-edges", short_edges(rng)),
    }
}

/// The shape scaled to the tool (`d` mm per unit), turned by a random angle and moved: a
/// valid polygon, or `None` where the drawing is not simple.
fn placed(rng: &mut Rng, unit: &[P2], d: f64) -> Option<Polygon> {
    let (s, c) = rng.f(0.0, TAU).sin_cos();
    let o = p2(rng.f(-50.0, 50.0), rng.f(-50.0, 50.0));
    Polygon::new(unit.iter().map(|v| o + p2(c * v.x - s * v.y, s * v.x + c * v.y) * d).collect()).ok()
}

/// Distance from `p` to the segment ab.
fn seg_dist(p: P2, a: P2, b: P2) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm()
}

/// Distance from `p` to the polygon's edges, computed here (not the crate's).
fn wall_dist(p: P2, v: &[P2]) -> f64 {
    (0..v.len()).map(|i| seg_dist(p, v[i], v[(i + 1) % v.len()])).fold(f64::INFINITY, f64::min)
}

/// Even-odd containment, computed here.
fn inside(p: P2, v: &[P2]) -> bool {
    let mut c = false;
    for i in 0..v.len() {
        let (a, b) = (v[i], v[(i + 1) % v.len()]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            c = !c;
        }
    }
    c
}

/// Points along `seg` at most `h` apart, both ends included.
fn dense(seg: &Segment, h: f64) -> Vec<P2> {
    let n = (seg.length() / h).ceil().max(1.0) as usize;
    (0..=n).map(|i| seg.point(i as f64 / n as f64)).collect()
}

/// Sampling step along the moves for the wall and the uncut checks (mm).
const SAMPLE_MM: f64 = 0.05;
/// Least wall distance of a tool position: r less this (mm), the brief's bound.
const WALL_SLACK_MM: f64 = 0.005;

/// The tool positions nearer the wall than r − [`WALL_SLACK_MM`], or outside the pocket:
/// (move index, point, distance) of the worst.
fn wall_violation(segments: &[Segment], v: &[P2], r: f64) -> Option<(usize, P2, f64)> {
    let mut worst: Option<(usize, P2, f64)> = None;
    for (i, seg) in segments.iter().enumerate() {
        for p in dense(seg, SAMPLE_MM) {
            let d = if inside(p, v) { wall_dist(p, v) } else { -wall_dist(p, v) };
            if d < r - WALL_SLACK_MM && worst.is_none_or(|w| d < w.2) {
                worst = Some((i, p, d));
            }
        }
    }
    worst
}

/// Area (mm²) of the pocket the tool could reach but no move came near: raster cells of side
/// `h` whose centre lies within r of a cell of the tool-centre region C = {inside, wall
/// distance ≥ r + s_f} (the disc of radius r about a point of C), and farther than
/// r + s_f + `tol` from every sampled tool position (moves and entry bores). A point within r
/// of C is within r of C's boundary or inside C, so the discs are stamped about C's boundary
/// cells only. Returns the area and the worst cell's centre.
fn uncut_area(v: &[P2], cut: &[P2], r: f64, sf: f64, h: f64, tol: f64) -> (f64, Option<P2>) {
    let (mut lo, mut hi) = (p2(f64::INFINITY, f64::INFINITY), p2(f64::NEG_INFINITY, f64::NEG_INFINITY));
    for p in v {
        lo = p2(lo.x.min(p.x), lo.y.min(p.y));
        hi = p2(hi.x.max(p.x), hi.y.max(p.y));
    }
    let (nx, ny) = (((hi.x - lo.x) / h).ceil() as usize + 1, ((hi.y - lo.y) / h).ceil() as usize + 1);
    let at = |i: usize, j: usize| lo + p2((i as f64 + 0.5) * h, (j as f64 + 0.5) * h);
    let mut pocket = vec![false; nx * ny];
    let mut region = vec![false; nx * ny];
    for j in 0..ny {
        for i in 0..nx {
            let p = at(i, j);
            if inside(p, v) {
                pocket[j * nx + i] = true;
                region[j * nx + i] = wall_dist(p, v) >= r + sf;
            }
        }
    }
    let mut reach = region.clone();
    let k = (r / h).ceil() as isize;
    for j in 0..ny {
        for i in 0..nx {
            let id = j * nx + i;
            let edge = region[id]
                && [(-1isize, 0isize), (1, 0), (0, -1), (0, 1)].iter().any(|&(di, dj)| {
                    let (a, b) = (i as isize + di, j as isize + dj);
                    a < 0 || b < 0 || a >= nx as isize || b >= ny as isize || !region[b as usize * nx + a as usize]
                });
            if !edge {
                continue;
            }
            for dj in -k..=k {
                for di in -k..=k {
                    let (a, b) = (i as isize + di, j as isize + dj);
                    if a < 0 || b < 0 || a >= nx as isize || b >= ny as isize {
                        continue;
                    }
                    if ((di * di + dj * dj) as f64) * h * h <= r * r {
                        reach[b as usize * nx + a as usize] = true;
                    }
                }
            }
        }
    }
    // the cut positions in bins of the covering radius
    let big = r + sf + tol;
    let mut bins: HashMap<(i64, i64), Vec<P2>> = HashMap::new();
    for &p in cut {
        bins.entry(((p.x / big).floor() as i64, (p.y / big).floor() as i64)).or_default().push(p);
    }
    let covered = |p: P2| {
        let (bx, by) = ((p.x / big).floor() as i64, (p.y / big).floor() as i64);
        (-1..=1).any(|dx| {
            (-1..=1).any(|dy| bins.get(&(bx + dx, by + dy)).is_some_and(|b| b.iter().any(|q| (q - p).norm() <= big)))
        })
    };
    let mut area = 0.0;
    let mut worst = None;
    for j in 0..ny {
        for i in 0..nx {
            let id = j * nx + i;
            if pocket[id] && reach[id] && !covered(at(i, j)) {
                area += h * h;
                worst = Some(at(i, j));
            }
        }
    }
    (area, worst)
}

/// The step-over for a tool of diameter `d`: 1.527 mm scaled with D (the acceptance step-over
/// of D = 10, whose default target is the 50° cap; the cap holds for the same a_e/D).
fn step_over(d: f64) -> f64 {
    1.527 * d / 10.0
}

/// Peak allowance over the target (rad): the brief's 1°.
const PEAK_SLACK_DEG: f64 = 1.0;

/// Uncut area allowed (mm²): the raster's own error along the reach boundary is absorbed by
/// `tol` = one cell diagonal on the covering radius; what remains is a few stray cells.
const UNCUT_AREA_MM2: f64 = 0.5;

enum Outcome {
    Planned { peak_deg: f64, target_deg: f64, uncut_mm2: f64, secs: f64 },
    Refused(String),
}

/// Plan one pocket and check it; `Err` says what broke.
fn check(polygon: &Polygon, d: f64) -> Result<Outcome, String> {
    let req = PocketRequest {
        polygon: polygon.clone(),
        tool_diameter_mm: d,
        step_over_mm: step_over(d),
        strategy: PocketStrategy::Adaptive,
        ..PocketRequest::default()
    };
    let t0 = std::time::Instant::now();
    let planned = catch_unwind(AssertUnwindSafe(|| pocket::plan(&req)));
    let secs = t0.elapsed().as_secs_f64();
    let plan = match planned {
        Err(e) => {
            let what = e.downcast_ref::<String>().cloned().or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()));
            return Err(format!("panic: {}", what.unwrap_or_default()));
        }
        Ok(Err(e)) => {
            let msg = e.to_string();
            if e.subject().is_none() || !msg.contains("must be") || msg.contains("NaN") {
                return Err(format!("refused without a named reason: {msg}"));
            }
            return Ok(Outcome::Refused(msg));
        }
        // the default method: adaptive clearing, or the trochoidal slot where no helix fits
        Ok(Ok(PocketPlan::Adaptive(p))) => (p.path, p.target_rad, p.options.finish_stock_mm),
        Ok(Ok(PocketPlan::Slot(p))) => (p.path, p.target_rad, p.options.finish_stock_mm),
        Ok(Ok(other)) => return Err(format!("planned with {:?}", other.strategy())),
    };
    let (path, target_rad, sf) = plan;
    let r = 0.5 * d;
    let m = &path.measurement;
    let segs = path.segments();
    let finite = |p: P2| p.x.is_finite() && p.y.is_finite();
    if !(m.max_engagement_rad.is_finite() && m.length_at_depth_mm.is_finite())
        || segs.iter().any(|s| !finite(s.start()) || !finite(s.end()) || !s.length().is_finite())
    {
        return Err("NaN in the plan".into());
    }
    let (peak, target) = (m.max_engagement_rad.to_degrees(), target_rad.to_degrees());
    let mut faults = Vec::new();
    if peak > target + PEAK_SLACK_DEG {
        let kinds: Vec<String> = m
            .maxima
            .iter()
            .filter(|k| k.max_rad.to_degrees() > target + PEAK_SLACK_DEG)
            .map(|k| format!("{:?} {:.1}° at ({:.2}, {:.2})", k.kind, k.max_rad.to_degrees(), k.at.x, k.at.y))
            .collect();
        faults.push(format!("peak {peak:.2}° > target {target:.1}° + 1°: {}", kinds.join(", ")));
    }
    let v = polygon.vertices();
    if let Some((i, p, dist)) = wall_violation(&segs, v, r) {
        faults.push(format!(
            "move #{} ({:?}) at ({:.3}, {:.3}) is {dist:.4} mm from the wall",
            i + 1,
            path.kinds()[i],
            p.x,
            p.y
        ));
    }
    let mut cut: Vec<P2> = segs.iter().flat_map(|s| dense(s, SAMPLE_MM)).collect();
    for b in path.toolpath.bores() {
        cut.extend(dense(&b, SAMPLE_MM));
    }
    let h = 0.025 * d;
    let (uncut, worst) = uncut_area(v, &cut, r, sf, h, h * 2f64.sqrt());
    if uncut > UNCUT_AREA_MM2 {
        faults.push(format!("{uncut:.2} mm² reachable but uncut, e.g. at {worst:?}"));
    }
    if faults.is_empty() {
        Ok(Outcome::Planned { peak_deg: peak, target_deg: target, uncut_mm2: uncut, secs })
    } else {
        Err(faults.join("; "))
    }
}

fn vertices_text(p: &Polygon) -> String {
    let v: Vec<String> = p.vertices().iter().map(|q| format!("({:.4}, {:.4})", q.x, q.y)).collect();
    v.join(", ")
}

/// Polygons per run; every fourth is planned with D = 6, the others with D = 10.
const CASES: usize = 48;

/// Cases of the fixed-seed run that still break a rule, each with what it breaks: the test
/// fails when another case breaks a rule, and when one of these no longer does (then it leaves
/// this list). Cases 4, 26 and 27 (a corner pass of an acute corner, the links of two rings'
/// runs, above the target) are refused by name.
const OPEN: [usize; 0] = [];

#[test]
fn random_pockets_keep_the_target_and_the_walls_or_are_refused_by_name() {
    let mut rng = Rng(0x5EED_2026);
    let (mut planned, mut refused, mut failed) = (0, Vec::new(), Vec::new());
    let mut k = 0;
    let mut case = 0;
    while case < CASES {
        let d = if case % 4 == 3 { 6.0 } else { 10.0 };
        let (family, unit) = shape(&mut rng, k);
        k += 1;
        let Some(polygon) = placed(&mut rng, &unit, d) else { continue };
        case += 1;
        let name = format!("#{case} {family} D{d}");
        match check(&polygon, d) {
            Ok(Outcome::Planned { peak_deg, target_deg, uncut_mm2, secs }) => {
                planned += 1;
                println!(
                    "{name}: peak {peak_deg:.2}° (target {target_deg:.1}°), uncut {uncut_mm2:.3} mm², {secs:.2} s"
                );
            }
            Ok(Outcome::Refused(msg)) => {
                println!("{name}: refused: {msg}");
                refused.push(format!("{name}: {msg}"));
            }
            Err(fault) => {
                println!("{name}: FAILED: {fault}\n  polygon: [{}]", vertices_text(&polygon));
                failed.push((case, format!("{name}: {fault}")));
            }
        }
    }
    println!("planned within the target {planned}, refused {}, failed {}", refused.len(), failed.len());
    let new: Vec<&String> = failed.iter().filter(|(c, _)| !OPEN.contains(c)).map(|(_, m)| m).collect();
    assert!(new.is_empty(), "{} of {CASES} pockets broke a rule:\n{new:#?}", new.len());
    let fixed: Vec<usize> = OPEN.iter().copied().filter(|c| failed.iter().all(|(f, _)| f != c)).collect();
    assert!(fixed.is_empty(), "cases {fixed:?} keep every rule now: take them off OPEN");
}

fn poly(v: &[(f64, f64)]) -> Polygon {
    Polygon::new(v.iter().map(|&(x, y)| p2(x, y)).collect()).unwrap()
}

/// The pocket plans within the target, off the walls, and leaves nothing reachable uncut.
fn assert_planned(v: &[(f64, f64)], d: f64) {
    match check(&poly(v), d) {
        Ok(Outcome::Planned { .. }) => {}
        Ok(Outcome::Refused(msg)) => panic!("refused: {msg}"),
        Err(fault) => panic!("{fault}"),
    }
}

/// An L whose short arm (11 mm wide: the tool centre has 0.35 mm either side) is narrower
/// than the helix's core (r_h = 3.75 mm): the opening of the core left the arm to the corner
/// passes, which crossed it full width (180°). The rings now grow into the arm with a finer
/// core radius.
#[test]
fn l_with_an_arm_narrower_than_the_helix_core() {
    let l = [
        (-46.6494, -25.2374),
        (-4.0217, -32.4792),
        (-0.3665, -10.9636),
        (-32.0498, -5.5810),
        (-29.1763, 11.3331),
        (-40.1207, 13.1924),
    ];
    assert_planned(&l, 10.0);
}

/// A T whose stem is narrower than the helix's core (it read 180° on the links and corner
/// passes into the stem).
#[test]
fn t_with_a_stem_narrower_than_the_helix_core() {
    let t = [
        (-27.3212, -29.4449),
        (-42.3119, -36.7518),
        (-35.3650, -51.0040),
        (-40.7653, -53.6362),
        (-33.8062, -67.9134),
        (10.8965, -46.1240),
        (3.9374, -31.8468),
        (-20.3742, -43.6970),
    ];
    assert_planned(&t, 10.0);
}

/// A U for D = 6 whose arms are narrower than the helix's core (180°).
#[test]
fn u_with_arms_narrower_than_the_helix_core() {
    let u = [
        (36.0238, 34.1986),
        (52.5472, 2.6761),
        (70.2433, 11.9520),
        (66.7060, 18.7003),
        (59.3743, 14.8572),
        (52.7623, 27.4712),
        (60.0941, 31.3143),
        (53.7200, 43.4745),
    ];
    assert_planned(&u, 6.0);
}

/// Two boxes joined by a neck through which the core of the helix's radius does not pass, for
/// D = 6: the second box was reached by links across uncut stock (97.7°).
#[test]
fn boxes_joined_by_a_neck_narrower_than_the_helix_core() {
    let neck = [
        (37.9134, 44.7981),
        (46.6647, 55.6015),
        (45.2955, 56.7106),
        (47.6623, 59.6323),
        (50.0083, 57.7319),
        (59.2906, 69.1907),
        (46.6793, 79.4065),
        (37.3971, 67.9477),
        (42.7151, 63.6398),
        (40.3483, 60.7180),
        (34.0558, 65.8153),
        (25.3045, 55.0119),
    ];
    assert_planned(&neck, 6.0);
}

/// A rectangle with a slot out of one side, narrower than the helix's core (180°).
#[test]
fn rectangle_with_a_slot_narrower_than_the_helix_core() {
    let slot = [
        (-17.3024, -6.5290),
        (-17.0561, -10.6326),
        (-27.8191, -11.2786),
        (-27.0867, -23.4814),
        (-16.3237, -22.8355),
        (-14.1022, -59.8508),
        (12.1988, -58.2723),
        (8.9985, -4.9505),
    ];
    assert_planned(&slot, 10.0);
}

/// An L for D = 6 whose long arm (6.31 mm wide) is narrower than D plus twice the finishing
/// stock: the tool-centre region ends in a tip at the arm's mouth, between a wall and a reflex
/// vertex; the finishing pass rounded that corner (a line and an arc) and left a sliver of the
/// arm (2.72 mm²). The corner points now reach into it.
#[test]
fn l_whose_long_arm_is_narrower_than_the_tool_and_the_stock() {
    let l = [
        (-8.6586, -3.0605),
        (-13.9472, -25.4467),
        (-7.8048, -26.8978),
        (-4.8912, -14.5646),
        (10.2828, -18.1493),
        (12.6577, -8.0964),
    ];
    assert_planned(&l, 6.0);
}
