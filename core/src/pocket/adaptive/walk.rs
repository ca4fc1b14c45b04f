//! Links to the start of a ring's run that stay in what is cleared (step 3 of
//! docs/adaptive-clearing.md): the shortest path that keeps the tool off the walls
//! ([`crate::pocket::route`]) knows the walls, not the stock still standing, and may cross the
//! band the run is about to cut (a link into a run at the far end of an arm cut that band
//! backwards, at more than the target).
//!
//! **Rule (DERIVED).** A run of ring j starts where ring j leaves ring j − 1, on ring j − 1
//! (`safe`), and everything inside ring j − 1 is cleared: its tool centres cut every ring up to
//! it, a concave-cut step apart, so a tool centre inside the loop has its whole disc in cut
//! material but for the cusps between passes; so is one within a step of a run cut outside
//! ring j − 1 (a place cleared past it, a run of ring j cut before: their bands are swept by
//! runs a step apart, [`Cleared`]). The router's path is kept where every point of it
//! is cleared so. Otherwise the tool goes by the
//! router to the point of `safe` nearest it (through what the last runs cleared: it ends a run
//! on the ring before, or at another place's run, whose band is cut), then along `safe`, the
//! shorter way, to the run's start: on a path already cut, where the tool's disc only touches
//! the stock. A run that starts off the ring before (a ring that grew all round) is entered
//! from the ring on a shallow slant along its own direction ([`LEAD_IN_RUN`]).

use super::loops::{Builder, closest_on, link, split};
use crate::geom::loop_contains;
use crate::geom::{P2, Polygon, Segment};
use crate::toolpath::MoveKind;
use std::collections::HashMap;

/// How near `safe` a point of a link counts as on it (mm): the run starts lie within 1 µm of
/// the previous ring ([`crate::pocket::runs::new_runs`]), the chords of its arcs within 0.1 µm.
pub(crate) const ON_LOOP_MM: f64 = 2e-3;

/// Spacing of the points of a link checked against `safe` (mm).
const CHECK_MM: f64 = 0.25;

/// Length of the lead-in onto a run that starts off the ring before it (a ring that grew all
/// round starts where it comes nearest that ring, a gap g outside it, the two nearly parallel
/// there), in units of g: the tool leaves the ring 8·g before its point nearest the start and
/// goes straight to the start, so the cut deepens from nothing to g at a slant of 1/8 (7°) to
/// the ring's own direction instead of across it.
const LEAD_IN_RUN: f64 = 8.0;

/// The runs cut so far, as points every half step in cells of a step: a tool centre within a
/// step of a run that lies outside the ring before (a place cleared past that ring, or a run
/// of the same ring cut earlier) lies in the band those runs cleared, the rings a step apart
/// (between that ring and the run, or between two runs); the band the next run cuts has no
/// run outside the ring before within a step.
#[derive(Default)]
pub(crate) struct Cleared {
    /// A tool centre this near the ring before (mm) grazes the stock outside it by at most
    /// this depth: cut 2·arccos(1 − g/r) wide at most, a quarter of the target
    /// ([`crate::pocket::runs::entry_gap`]); the router keeps r from the walls where the rings
    /// keep r + s_f, so its links graze the finishing stock by up to s_f at reflex corners.
    graze: f64,
    /// The finishing stock s_f (mm): a tool centre nearer the walls than r + s_f and within s_f
    /// of the ring before (which runs along the wall there, r + s_f off it) cuts into the
    /// finishing stock only, a layer s_f ≤ a_e deep: within the step-over's straight engagement.
    finish: f64,
    /// The pocket and the tool radius, for that wall distance.
    walls: Option<(Polygon, f64)>,
    radius: f64,
    cells: HashMap<(i64, i64), Vec<P2>>,
}

impl Cleared {
    /// Nothing cut yet, for rings `step` apart, grazing the ring before by `graze` at most and
    /// the finishing stock `finish` of `polygon` for a tool of radius `r`.
    pub(crate) fn new(step: f64, graze: f64, (polygon, r, finish): (&Polygon, f64, f64)) -> Cleared {
        Cleared { graze, finish, walls: Some((polygon.clone(), r)), radius: step, cells: HashMap::new() }
    }

    /// Whether `p` cuts only into the finishing stock along a wall beside `ring` (see `finish`).
    fn in_finish_stock(&self, p: P2, ring: &[Segment]) -> bool {
        let Some((polygon, r)) = &self.walls else { return false };
        self.finish > 0.0
            && polygon.boundary_distance(p) < r + self.finish
            && ring.iter().any(|sg| (closest_on(sg, p).0 - p).norm() <= self.finish + ON_LOOP_MM)
    }

    fn cell(&self, p: P2) -> (i64, i64) {
        ((p.x / self.radius).floor() as i64, (p.y / self.radius).floor() as i64)
    }

    /// Record the run segment `sg` as cut.
    pub(crate) fn add(&mut self, sg: &Segment) {
        if self.radius.is_nan() || self.radius <= 0.0 {
            return;
        }
        let n = (sg.length() / (0.5 * self.radius)).ceil().max(1.0) as usize;
        for k in 0..=n {
            let p = sg.point(k as f64 / n as f64);
            let c = self.cell(p);
            self.cells.entry(c).or_default().push(p);
        }
    }

    /// Whether a recorded point within a step of `p` passes `keep`.
    fn near(&self, p: P2, keep: impl Fn(P2) -> bool) -> bool {
        if self.radius.is_nan() || self.radius <= 0.0 {
            return false;
        }
        let (i, j) = self.cell(p);
        (-1..=1).any(|di| {
            (-1..=1).any(|dj| {
                self.cells
                    .get(&(i + di, j + dj))
                    .is_some_and(|v| v.iter().any(|&q| (q - p).norm() <= self.radius && keep(q)))
            })
        })
    }
}

/// A ring to stay within: its loops, their chords, its segments, and what else is cleared.
type Within<'a> = (&'a [&'a [Segment]], &'a [Vec<P2>], &'a [Segment], &'a Cleared);

/// The closed loops of a ring given as consecutive segments (several pieces one after the
/// other: a new loop where a segment does not start at the previous one's end).
fn loops(ring: &[Segment]) -> Vec<&[Segment]> {
    let mut out = Vec::new();
    let mut start = 0;
    for i in 1..=ring.len() {
        if i == ring.len() || (ring[i].start() - ring[i - 1].end()).norm() > 1e-6 {
            out.push(&ring[start..i]);
            start = i;
        }
    }
    out
}

/// A polygon through a loop's segments: lines by their ends, arcs by chords whose sagitta is
/// at most 0.1 µm (well within [`ON_LOOP_MM`]).
fn chords(lp: &[Segment]) -> Vec<P2> {
    let mut pts = Vec::new();
    for sg in lp {
        let n = match *sg {
            Segment::Arc { radius, sweep, .. } => {
                let half = (1.0 - 1e-4 / radius.max(1e-4)).clamp(-1.0, 1.0).acos();
                (sweep.abs() / (2.0 * half.max(1e-6))).ceil().clamp(1.0, 4096.0) as usize
            }
            _ => 1,
        };
        pts.extend((0..n).map(|k| sg.point(k as f64 / n as f64)));
    }
    pts
}

/// Whether `p` lies inside one of `polys` (the loops' chords) or within `near` of `ring`.
fn in_ring(p: P2, polys: &[Vec<P2>], ring: &[Segment], near: f64) -> bool {
    polys.iter().any(|v| loop_contains(v, p)) || ring.iter().any(|sg| (closest_on(sg, p).0 - p).norm() <= near)
}

/// Whether the tool centre `p` lies in cleared material: inside the ring before (`polys`,
/// `ring`), or in the band of runs cut outside it ([`Cleared`]).
fn within(p: P2, polys: &[Vec<P2>], ring: &[Segment], cleared: &Cleared) -> bool {
    in_ring(p, polys, ring, cleared.graze.max(ON_LOOP_MM))
        || cleared.in_finish_stock(p, ring)
        || cleared.near(p, |q| !in_ring(q, polys, ring, ON_LOOP_MM))
}

/// `sg` run backwards.
pub(super) fn reversed(sg: &Segment) -> Segment {
    match *sg {
        Segment::Line { start, end } => Segment::Line { start: end, end: start },
        Segment::Arc { center, radius, start_angle, sweep } => {
            Segment::Arc { center, radius, start_angle: start_angle + sweep, sweep: -sweep }
        }
        other => other,
    }
}

/// The point of `lp` nearest `q`: its segment and local parameter.
fn nearest(lp: &[Segment], q: P2) -> (usize, f64, f64) {
    lp.iter()
        .enumerate()
        .map(|(i, sg)| {
            let (p, t) = closest_on(sg, q);
            (i, t, (p - q).norm())
        })
        .min_by(|a, c| a.2.total_cmp(&c.2))
        .unwrap_or((0, 0.0, f64::INFINITY))
}

/// The path along the closed loop `lp` from (segment i, parameter s) to (j, t), forward
/// (the loop's own sense) or backward, whichever is shorter.
fn along(lp: &[Segment], (i, s): (usize, f64), (j, t): (usize, f64)) -> Vec<Segment> {
    let n = lp.len();
    let mut fwd = Vec::new();
    if i == j && t >= s {
        fwd.push(split(&split(&lp[i], t).0, if t > 0.0 { s / t } else { 0.0 }).1);
    } else {
        fwd.push(split(&lp[i], s).1);
        let mut k = (i + 1) % n;
        while k != j {
            fwd.push(lp[k]);
            k = (k + 1) % n;
        }
        fwd.push(split(&lp[j], t).0);
    }
    let mut bwd = Vec::new();
    if i == j && t <= s {
        bwd.push(reversed(&split(&split(&lp[i], s).0, if s > 0.0 { t / s } else { 0.0 }).1));
    } else {
        bwd.push(reversed(&split(&lp[i], s).0));
        let mut k = (i + n - 1) % n;
        while k != j {
            bwd.push(reversed(&lp[k]));
            k = (k + n - 1) % n;
        }
        bwd.push(reversed(&split(&lp[j], t).1));
    }
    let len = |v: &[Segment]| v.iter().map(Segment::length).sum::<f64>();
    let way = if len(&fwd) <= len(&bwd) { fwd } else { bwd };
    way.into_iter().filter(|sg| sg.length() > 1e-9).collect()
}

/// Whether every point of the polyline `pts` (every [`CHECK_MM`]) lies within `safe`.
fn inside_all(pts: &[P2], polys: &[Vec<P2>], safe: &[Segment], cleared: &Cleared) -> bool {
    pts.windows(2).all(|w| {
        let n = ((w[1] - w[0]).norm() / CHECK_MM).ceil().max(1.0) as usize;
        (0..=n).all(|k| within(w[0] + (w[1] - w[0]) * (k as f64 / n as f64), polys, safe, cleared))
    })
}

/// A link from the tool's position to `to`, a run's start on the ring before it, `safe`, the
/// run leaving it in the direction `dir` (module docs); with no `safe` ring, the router's path.
pub(crate) fn link_within(
    b: &mut Builder,
    polygon: &Polygon,
    r: f64,
    (safe, cleared): (&[Segment], &Cleared),
    to: P2,
    dir: P2,
) {
    if safe.is_empty() {
        return link(b, polygon, r, to);
    }
    let rings = loops(safe);
    let polys: Vec<Vec<P2>> = rings.iter().map(|lp| chords(lp)).collect();
    let gap = rings.iter().map(|lp| nearest(lp, to).2).fold(f64::INFINITY, f64::min);
    if gap <= cleared.graze.max(ON_LOOP_MM) {
        return reach(b, polygon, r, (&rings, &polys, safe, cleared), to);
    }
    // off the ring (a ring that grew all round, started where it comes nearest the ring
    // before): along that ring to LEAD_IN_RUN·g before its point nearest the start, then
    // straight on at a slant of 1/LEAD_IN_RUN
    let _ = dir;
    let Some(lp) = rings.iter().min_by(|a, c| nearest(a, to).2.total_cmp(&nearest(c, to).2)) else {
        return link(b, polygon, r, to);
    };
    let (j, t, _) = nearest(lp, to);
    let (jb, tb) = before(lp, (j, t), LEAD_IN_RUN * gap);
    let lead = lp[jb].point(tb);
    // (a pocket with islands: not where the slant would pass an island)
    if !b.router.get(polygon, r).keeps_off_islands(lead, to) {
        return reach(b, polygon, r, (&rings, &polys, safe, cleared), to);
    }
    reach(b, polygon, r, (&rings, &polys, safe, cleared), lead);
    b.line(to, MoveKind::Link);
}

/// The point `back` mm before (segment j, parameter t) along the closed loop `lp` (lines and
/// arcs: their parameter is proportional to length), at most half the loop back.
fn before(lp: &[Segment], (mut j, mut t): (usize, f64), back: f64) -> (usize, f64) {
    let total: f64 = lp.iter().map(Segment::length).sum();
    let mut left = back.min(0.5 * total);
    for _ in 0..=lp.len() {
        let len = lp[j].length();
        if len * t >= left {
            return (j, t - left / len.max(1e-12));
        }
        left -= len * t;
        (j, t) = ((j + lp.len() - 1) % lp.len(), 1.0);
    }
    (j, t)
}

/// The tool's way to `to` within the rings `safe` (its loops and their chords): the router's
/// path where it stays within, else onto the loop nearest `to` and along it (module docs).
fn reach(b: &mut Builder, polygon: &Polygon, r: f64, (rings, polys, safe, cleared): Within<'_>, to: P2) {
    let from = b.at();
    if let Some(pts) = b.router.get(polygon, r).route(from, to)
        && inside_all(&pts, polys, safe, cleared)
    {
        pts.iter().skip(1).for_each(|&p| b.line(p, MoveKind::Link));
        return;
    }
    let Some(lp) = rings.iter().min_by(|a, c| nearest(a, to).2.total_cmp(&nearest(c, to).2)) else {
        return link(b, polygon, r, to);
    };
    let (j, t, _) = nearest(lp, to);
    let (i, s, _) = nearest(lp, from);
    let onto = lp[i].point(s);
    link(b, polygon, r, onto);
    if (b.at() - onto).norm() > 1e-9 {
        // no path onto the loop: the router's own link (a retract where it has none)
        return link(b, polygon, r, to);
    }
    for sg in along(lp, (i, s), (j, t)) {
        b.push(sg, MoveKind::Link);
    }
    b.line(to, MoveKind::Link);
}
