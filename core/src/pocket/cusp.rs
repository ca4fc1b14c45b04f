//! Cusps of a region of tool centres: convex corners where at least one wall is an arc. An
//! inward offset of a polygon has arcs only about its reflex vertices (the region lies outside
//! the circle of radius R = r + s_f about the vertex), so a cusp is where such an arc meets a
//! line or another arc at an angle: the mouth of a neck narrower than the tool (two arcs), or a
//! reflex vertex near a wall. Adaptive clearing's rings round a cusp off with their radius T;
//! the cusp passes here thin it down to ρ_fin like the corner passes of a corner between two
//! lines ([`super::adaptive`], step 4), so that the finishing pass meets a concentric arc.
//!
//! **Geometry (DERIVED).** An arc of radius ρ tangent to both walls from inside the region is
//! centred at the matching vertex c(ρ) of the region offset inward by ρ: the intersection of
//! the walls' offsets (a line moved ρ along its inward normal, a circle about a reflex vertex
//! grown to R + ρ) nearest the cusp P. Its tangent points are c − ρ·n on a line and
//! V + (c − V)·R/(R + ρ) on a circle. Every point within ρ of c is at least R from each circle's
//! centre and on the inner side of each line, so the arc's disc — and its chord, the way back
//! — lies in the region. For two lines this is the corner arc of step 4.
//!
//! **Step (DERIVED as step 4's).** Consecutive arcs cut a crescent whose depth is largest on the
//! line through both centres: |c(ρ_k+1) − c(ρ_k)| − (ρ_k − ρ_k+1). Where the centres move
//! straight toward P (two lines, a symmetric neck) that is g(ρ_k) − g(ρ_k+1), g(ρ) = |c(ρ) − P| −
//! ρ the arc's distance from P (for two lines g = ρ(1/sin(α/2) − 1), step 4's). It is held to
//! the concave-cut step of ρ_k+1 ([`super::adaptive::concave_step`]); ρ_k+1 by bisection.

use super::adaptive::concave_step;
use crate::geom::{P2, Polygon, Segment, bisect_edge, cross, rot90};
use std::f64::consts::{PI, TAU};

/// Most passes into one cusp (bounds run time on hostile input).
const MAX_CUSP_PASSES: usize = 2_000;
/// Bisection steps for radii.
const BISECTION_STEPS: usize = 60;
/// Points per element when a cap's area is summed.
const CAP_POINTS: usize = 24;
/// Most walls followed from a cusp each way.
const MAX_CHAIN: usize = 4;

/// A wall of a region of tool centres next to a cusp.
#[derive(Clone, Copy, Debug)]
enum Wall {
    /// A line through `p` with unit inward normal `n` (the region on its left).
    Line { p: P2, n: P2 },
    /// The circle of radius `radius` about a reflex pocket vertex `v` (the region outside it).
    Circle { v: P2, radius: f64 },
}

impl Wall {
    /// The wall of a loop segment (counter-clockwise loop); `None` for an arc with the region
    /// inside it (inward offsets of a polygon have none).
    fn of(seg: &Segment) -> Option<Wall> {
        match *seg {
            Segment::Line { start, end } => Some(Wall::Line { p: start, n: rot90((end - start).normalize()) }),
            Segment::Arc { center, radius, sweep, .. } if sweep < 0.0 => Some(Wall::Circle { v: center, radius }),
            _ => None,
        }
    }

    /// The point where a circle about `c` of radius ρ touches the wall from inside.
    fn touch(&self, c: P2, rho: f64) -> P2 {
        match *self {
            Wall::Line { n, .. } => c - n * rho,
            Wall::Circle { v, radius } => v + (c - v) * (radius / (radius + rho)),
        }
    }

    /// Unit normal into the region at a point `q` of the wall.
    fn normal(&self, q: P2) -> P2 {
        match *self {
            Wall::Line { n, .. } => n,
            Wall::Circle { v, .. } => (q - v).normalize(),
        }
    }
}

/// Points where the offsets by ρ of two walls meet.
fn meet(a: Wall, b: Wall, rho: f64) -> Vec<P2> {
    let line_circle = |p: P2, n: P2, v: P2, big_r: f64| -> Vec<P2> {
        // points p + n·ρ + t·d with |· − v| = R + ρ
        let d = -rot90(n);
        let q = p + n * rho - v;
        let (bq, cq) = (q.dot(&d), q.norm_squared() - (big_r + rho).powi(2));
        let disc = bq * bq - cq;
        if disc < 0.0 {
            return Vec::new();
        }
        let s = disc.sqrt();
        vec![v + q + d * (-bq - s), v + q + d * (-bq + s)]
    };
    match (a, b) {
        (Wall::Line { p: p1, n: n1 }, Wall::Line { p: p2_, n: n2 }) => {
            let (d1, d2) = (-rot90(n1), -rot90(n2));
            let den = cross(d1, d2);
            if den.abs() < 1e-12 {
                return Vec::new();
            }
            let (q1, q2) = (p1 + n1 * rho, p2_ + n2 * rho);
            vec![q1 + d1 * (cross(q2 - q1, d2) / den)]
        }
        (Wall::Line { p, n }, Wall::Circle { v, radius }) | (Wall::Circle { v, radius }, Wall::Line { p, n }) => {
            line_circle(p, n, v, radius)
        }
        (Wall::Circle { v: v1, radius: r1 }, Wall::Circle { v: v2, radius: r2 }) => {
            let (ra, rb) = (r1 + rho, r2 + rho);
            let d = (v2 - v1).norm();
            if d < 1e-12 || d > ra + rb || d < (ra - rb).abs() {
                return Vec::new();
            }
            let x = (d * d + ra * ra - rb * rb) / (2.0 * d);
            let h = (ra * ra - x * x).max(0.0).sqrt();
            let u = (v2 - v1) / d;
            let m = v1 + u * x;
            vec![m + rot90(u) * h, m - rot90(u) * h]
        }
    }
}

/// A cusp of a counter-clockwise loop of tool centres.
#[derive(Clone, Debug)]
pub(crate) struct Cusp {
    /// The cusp P (mm).
    pub vertex: P2,
    /// The walls into the cusp: the segment ending at P, then those before it that join it
    /// tangentially (a larger arc touches them where it runs past the first).
    walls_in: Vec<(Wall, Segment)>,
    /// The walls out of it: the segment starting at P, then those after it joining tangentially.
    walls_out: Vec<(Wall, Segment)>,
    /// Interior angle between the walls' tangents at the cusp of the final wall (the region
    /// offset back outward by the finishing stock) (rad): reaching that point reads π − α.
    pub alpha: f64,
    /// Largest radius whose arc touches both walls on the loop and stays in the region (mm).
    pub rho_max: f64,
}

/// Whether `q` lies on the segment.
fn on(seg: &Segment, q: P2) -> bool {
    (super::adaptive::closest_on(seg, q).0 - q).norm() <= 1e-7 * (1.0 + q.norm())
}

/// The move along a wall from its point `from` to its point `to`.
fn along(w: Wall, from: P2, to: P2) -> Segment {
    match w {
        Wall::Line { .. } => Segment::Line { start: from, end: to },
        Wall::Circle { v, radius } => {
            let start_angle = (from.y - v.y).atan2(from.x - v.x);
            let sweep = ((to.y - v.y).atan2(to.x - v.x) - start_angle + PI).rem_euclid(TAU) - PI;
            Segment::Arc { center: v, radius, start_angle, sweep }
        }
    }
}

/// The moves along a chain of walls (each run in the loop's direction) from its point `from`
/// to its point `to`: down the chain's indices for the walls into a cusp, up for those out.
fn run(chain: &[(Wall, Segment)], from: P2, to: P2, into_cusp: bool) -> Vec<Segment> {
    let index = |q: P2| chain.iter().position(|(_, sg)| on(sg, q)).unwrap_or(0);
    let (i_from, i_to) = (index(from), index(to));
    let ks: Vec<usize> =
        if into_cusp { (i_to..=i_from.max(i_to)).rev().collect() } else { (i_from..=i_to.max(i_from)).collect() };
    ks.iter()
        .map(|&k| {
            let (w, sg) = chain[k];
            let start = if k == i_from { from } else { sg.start() };
            let end = if k == i_to { to } else { sg.end() };
            along(w, start, end)
        })
        .collect()
}

impl Cusp {
    /// Centre of the arc of radius ρ tangent to a wall in and a wall out, touching both on their
    /// segments (the one nearest the cusp), with the walls' indices. ρ < 0: the cusp of the
    /// first two walls offset outward by −ρ.
    fn touching(&self, rho: f64) -> Option<(P2, usize, usize)> {
        let mut best: Option<(f64, P2, usize, usize)> = None;
        for (i, (wa, sa)) in self.walls_in.iter().enumerate() {
            for (j, (wb, sb)) in self.walls_out.iter().enumerate() {
                if rho < 0.0 && i + j > 0 {
                    continue;
                }
                for c in meet(*wa, *wb, rho) {
                    let fits = rho < 0.0 || (on(sa, wa.touch(c, rho)) && on(sb, wb.touch(c, rho)));
                    let d = (c - self.vertex).norm();
                    if fits && best.is_none_or(|(bd, ..)| d < bd) {
                        best = Some((d, c, i, j));
                    }
                }
            }
        }
        best.map(|(_, c, i, j)| (c, i, j))
    }

    /// Tangent points on the incoming and outgoing walls and the arc of radius ρ between them
    /// (counter-clockwise).
    pub fn arc(&self, rho: f64) -> Option<(P2, P2, Segment)> {
        let (c, i, j) = self.touching(rho)?;
        let (a, e) = (self.walls_in[i].0.touch(c, rho), self.walls_out[j].0.touch(c, rho));
        let start_angle = (a.y - c.y).atan2(a.x - c.x);
        let sweep = ((e.y - c.y).atan2(e.x - c.x) - start_angle).rem_euclid(TAU);
        Some((a, e, Segment::Arc { center: c, radius: rho, start_angle, sweep }))
    }

    /// Deepest cut of the arc of radius ρ' after the arc of radius ρ: |c(ρ') − c(ρ)| − (ρ − ρ')
    /// (the farthest point of the new circle from the old one's centre, on the line through
    /// both centres; g(ρ) − g(ρ') where the centres move straight toward the cusp) (mm).
    pub fn depth(&self, rho: f64, next: f64) -> f64 {
        match (self.touching(rho), self.touching(next)) {
            (Some((c, ..)), Some((c_next, ..))) => (c_next - c).norm() - (rho - next),
            _ => f64::INFINITY,
        }
    }

    /// The moves along the incoming walls from their point `from` to their point `to`, nearer
    /// the cusp.
    pub fn along_wall(&self, from: P2, to: P2) -> Vec<Segment> {
        run(&self.walls_in, from, to, true)
    }

    /// Radii of the passes from ρ₀ down to ρ_fin: each crescent's depth on the axis within the
    /// concave-cut step of the new radius (module doc).
    pub fn radii(&self, rho0: f64, rho_fin: f64, r: f64, phi: f64) -> Vec<f64> {
        let mut out = Vec::new();
        let mut rho = rho0;
        while rho > rho_fin + 1e-6 && out.len() < MAX_CUSP_PASSES {
            let fits = |next: f64| self.depth(rho, next) <= concave_step(next, r, phi);
            let next = if fits(rho_fin) { rho_fin } else { bisect_edge(rho, rho_fin, BISECTION_STEPS, fits) };
            if rho - next < 1e-9 {
                break;
            }
            out.push(next);
            rho = next;
        }
        out
    }

    /// Area between the walls and the arc of radius ρ (the cap the arc leaves) (mm²).
    pub fn cap_area(&self, rho: f64) -> f64 {
        let Some((a, e, arc)) = self.arc(rho) else { return 0.0 };
        let mut pts: Vec<P2> = Vec::with_capacity(4 * CAP_POINTS);
        let walls =
            run(&self.walls_in, a, self.vertex, true).into_iter().chain(run(&self.walls_out, self.vertex, e, false));
        for sg in walls {
            pts.extend((0..CAP_POINTS).map(|i| sg.point(i as f64 / CAP_POINTS as f64)));
        }
        pts.extend((0..CAP_POINTS).map(|i| arc.point(1.0 - i as f64 / CAP_POINTS as f64)));
        let n = pts.len();
        0.5 * (0..n).map(|i| cross(pts[i], pts[(i + 1) % n])).sum::<f64>().abs()
    }
}

/// The cusps of a counter-clockwise loop of tool centres of `polygon` (the pocket offset by
/// `clearance` = r + s_f), with the finishing stock `sf`; `loop_segs` its segments.
pub(crate) fn cusps(loop_segs: &[Segment], polygon: &Polygon, clearance: f64, sf: f64) -> Vec<Cusp> {
    let n = loop_segs.len();
    let mut out = Vec::new();
    for i in 0..n {
        let (sa, sb) = (&loop_segs[i], &loop_segs[(i + 1) % n]);
        if matches!((sa, sb), (Segment::Line { .. }, Segment::Line { .. })) {
            continue;
        }
        let (Some(wa), Some(wb)) = (Wall::of(sa), Wall::of(sb)) else { continue };
        let p = sa.end();
        let (ta, tb) = (sa.eval(1.0).d1.normalize(), sb.eval(0.0).d1.normalize());
        if cross(ta, tb) < 1e-6 {
            continue; // smooth or reflex: no cusp
        }
        // the walls that continue them tangentially, up to MAX_CHAIN each way
        let tangent = |s1: &Segment, s2: &Segment| {
            let (t1, t2) = (s1.eval(1.0).d1.normalize(), s2.eval(0.0).d1.normalize());
            cross(t1, t2).abs() < 1e-6 && t1.dot(&t2) > 0.0
        };
        let mut walls_in = vec![(wa, *sa)];
        for k in 1..MAX_CHAIN.min(n) {
            let (prev, next) = (&loop_segs[(i + n - k) % n], &loop_segs[(i + n + 1 - k) % n]);
            let Some(w) = Wall::of(prev).filter(|_| tangent(prev, next)) else { break };
            walls_in.push((w, *prev));
        }
        let mut walls_out = vec![(wb, *sb)];
        for k in 2..MAX_CHAIN.min(n) + 1 {
            let (prev, next) = (&loop_segs[(i + k - 1) % n], &loop_segs[(i + k) % n]);
            let Some(w) = Wall::of(next).filter(|_| tangent(prev, next)) else { break };
            walls_out.push((w, *next));
        }
        let mut cusp = Cusp { vertex: p, walls_in, walls_out, alpha: 0.0, rho_max: 0.0 };
        // α at the final wall's cusp: the walls' normals there make π − α
        let q = cusp.touching(-sf).map_or(p, |(c, ..)| c);
        let (na, nb) = (wa.normal(wa.touch(q, -sf)), wb.normal(wb.touch(q, -sf)));
        cusp.alpha = PI - cross(na, nb).atan2(na.dot(&nb)).abs();
        cusp.rho_max = largest_radius(&cusp, loop_segs, polygon, clearance);
        out.push(cusp);
    }
    out
}

/// The largest radius (bisection) whose arc touches both walls on the loop and keeps the
/// clearance from the pocket's edges.
fn largest_radius(cusp: &Cusp, loop_segs: &[Segment], polygon: &Polygon, clearance: f64) -> f64 {
    let on_loop =
        |q: P2| loop_segs.iter().any(|sg| (super::adaptive::closest_on(sg, q).0 - q).norm() < 1e-6 * (1.0 + q.norm()));
    let ok = |rho: f64| {
        cusp.arc(rho).is_some_and(|(a, e, arc)| {
            on_loop(a)
                && on_loop(e)
                && (0..=8).all(|j| polygon.boundary_distance(arc.point(j as f64 / 8.0)) >= clearance - 1e-6)
        })
    };
    let ext = loop_segs.iter().map(|sg| (sg.start() - cusp.vertex).norm()).fold(0.0, f64::max);
    if ok(ext) { ext } else { bisect_edge(0.0, ext, BISECTION_STEPS, ok) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::p2;

    fn cusp(walls_in: Vec<(Wall, Segment)>, walls_out: Vec<(Wall, Segment)>, vertex: P2) -> Cusp {
        Cusp { vertex, walls_in, walls_out, alpha: 0.0, rho_max: 0.0 }
    }

    /// Two lines: the arc is step 4's corner arc (centre V + b·ρ/sin(α/2)), the depth of the
    /// next arc (ρ − ρ')(1/sin(α/2) − 1), and the cap T²(cot(α/2) − (π − α)/2).
    #[test]
    fn two_lines_give_the_corner_arc() {
        // 90° corner at the origin: incoming wall along +x into V, outgoing along +y
        let (sa, sb) = (
            Segment::Line { start: p2(-10.0, 0.0), end: p2(0.0, 0.0) },
            Segment::Line { start: p2(0.0, 0.0), end: p2(0.0, 10.0) },
        );
        let c = cusp(vec![(Wall::of(&sa).unwrap(), sa)], vec![(Wall::of(&sb).unwrap(), sb)], p2(0.0, 0.0));
        let (t_a, t_b, arc) = c.arc(2.0).unwrap();
        assert!((t_a - p2(-2.0, 0.0)).norm() < 1e-12 && (t_b - p2(0.0, 2.0)).norm() < 1e-12);
        let Segment::Arc { center, sweep, .. } = arc else { panic!("an arc") };
        assert!((center - p2(-2.0, 2.0)).norm() < 1e-12 && (sweep - 0.5 * PI).abs() < 1e-12);
        let k = 1.0 / (0.25 * PI).sin() - 1.0;
        assert!((c.depth(2.0, 1.5) - 0.5 * k).abs() < 1e-12);
        // the arc enters the sum as CAP_POINTS chords: each adds its circular segment
        // ρ²(θ − sin θ)/2, θ = (π/2)/CAP_POINTS, to the cap
        let theta = 0.5 * PI / CAP_POINTS as f64;
        let chords = CAP_POINTS as f64 * 2.0 * (theta - theta.sin());
        assert!((c.cap_area(2.0) - 4.0 * (1.0 - 0.25 * PI) - chords).abs() < 1e-9, "{}", c.cap_area(2.0));
        // past the walls' ends (10 mm) no arc touches both
        assert!(c.arc(10.5).is_none());
    }

    /// A neck's mouth: circles of radius R about (0, ∓a), the loop running up the mouth (region
    /// on its left, x < P): clockwise about (0, −a) into P = (−√(R² − a²), 0), then clockwise
    /// about (0, a). The arc of radius ρ is centred at (−√((R + ρ)² − a²), 0) and touches each
    /// circle on the line to its centre; the final wall's cusp (R − s_f) at (−√((R − s_f)² − a²), 0).
    #[test]
    fn neck_mouth_arcs_touch_both_circles() {
        let (big_r, a, rho): (f64, f64, f64) = (5.2, 4.0, 1.5);
        let h = (big_r * big_r - a * a).sqrt();
        let p = p2(-h, 0.0);
        let ang = |v: P2| (p.y - v.y).atan2(p.x - v.x);
        let (va, vb) = (p2(0.0, -a), p2(0.0, a));
        let sa = Segment::Arc { center: va, radius: big_r, start_angle: ang(va) + 0.8, sweep: -0.8 };
        let sb = Segment::Arc { center: vb, radius: big_r, start_angle: ang(vb), sweep: -0.8 };
        assert!((sa.end() - p).norm() < 1e-12);
        let c = cusp(vec![(Wall::of(&sa).unwrap(), sa)], vec![(Wall::of(&sb).unwrap(), sb)], p);
        let (t_a, t_b, arc) = c.arc(rho).unwrap();
        let Segment::Arc { center, .. } = arc else { panic!("an arc") };
        assert!((center - p2(-((big_r + rho).powi(2) - a * a).sqrt(), 0.0)).norm() < 1e-12, "{center:?}");
        for (t, v) in [(t_a, va), (t_b, vb)] {
            assert!(((t - v).norm() - big_r).abs() < 1e-12 && ((t - center).norm() - rho).abs() < 1e-12);
        }
        let sf = 0.2;
        let (q, ..) = c.touching(-sf).unwrap();
        assert!((q.x + ((big_r - sf).powi(2) - a * a).sqrt()).abs() < 1e-12);
        // the move along the incoming wall stays on its circle
        let along = c.along_wall(sa.start(), t_a);
        assert!(along.iter().all(|sg| (0..=4).all(|j| ((sg.point(j as f64 / 4.0) - va).norm() - big_r).abs() < 1e-9)));
    }

    /// A chain: a larger arc runs past the first wall onto the tangent one before it.
    #[test]
    fn larger_arcs_touch_the_tangent_wall_before() {
        // region x > 0 side... incoming: the line x = 5 running down to (5, 3), then clockwise
        // about (0, 3) (radius 5) into the cusp with the outgoing line y = 0 (region above)
        let v = p2(0.0, 3.0);
        let p = p2(4.0, 0.0); // |p − v| = 5
        let line_in = Segment::Line { start: p2(5.0, 20.0), end: p2(5.0, 3.0) };
        let arc_in = Segment::Arc { center: v, radius: 5.0, start_angle: 0.0, sweep: (p.y - v.y).atan2(p.x - v.x) };
        let out = Segment::Line { start: p, end: p2(30.0, 0.0) };
        let c = cusp(
            vec![(Wall::of(&arc_in).unwrap(), arc_in), (Wall::of(&line_in).unwrap(), line_in)],
            vec![(Wall::of(&out).unwrap(), out)],
            p,
        );
        // ρ = 4: the line pair's arc about (9, 4) touches x = 5 at (5, 4) (on the line) and keeps
        // |c − v| = √(81 + 1) > 5 + 4
        let (t_a, t_b, arc) = c.arc(4.0).unwrap();
        let Segment::Arc { center, .. } = arc else { panic!("an arc") };
        assert!((center - p2(9.0, 4.0)).norm() < 1e-12, "{center:?}");
        assert!((t_a - p2(5.0, 4.0)).norm() < 1e-12 && (t_b - p2(9.0, 0.0)).norm() < 1e-12);
        // the move from there to a small arc's touch point runs down the line, then on the circle
        let (t_small, ..) = c.arc(0.5).unwrap();
        let moves = c.along_wall(t_a, t_small);
        assert_eq!(moves.len(), 2);
        assert!((moves[0].end() - p2(5.0, 3.0)).norm() < 1e-12 && (moves[1].end() - t_small).norm() < 1e-12);
    }
}
