//! The moves of a part being built, and what every step of adaptive clearing uses on loops of
//! lines and arcs: closest points, splitting, restarting a loop, links through cleared
//! material ([`super::crate::pocket::route`]) and the inscribed circle of a region.

use crate::geom::offset::{Region, largest};
use crate::geom::{P2, Polygon, Segment, p2};
use crate::toolpath::MoveKind;
use std::f64::consts::TAU;

/// Bisection steps for the inscribed radius.
pub(super) const INSCRIBED_STEPS: usize = 48;

/// The closest point of a line or arc to `q`, and its local parameter.
pub(crate) fn closest_on(seg: &Segment, q: P2) -> (P2, f64) {
    match *seg {
        Segment::Line { start, end } => {
            let d = end - start;
            let t = if d.norm_squared() > 0.0 { ((q - start).dot(&d) / d.norm_squared()).clamp(0.0, 1.0) } else { 0.0 };
            (start + d * t, t)
        }
        Segment::Arc { start_angle, sweep, center, .. } => {
            let v = q - center;
            let ang = v.y.atan2(v.x);
            let rel =
                if sweep >= 0.0 { (ang - start_angle).rem_euclid(TAU) } else { (start_angle - ang).rem_euclid(TAU) };
            let t = if rel <= sweep.abs() {
                rel / sweep.abs()
            } else if (q - seg.start()).norm() <= (q - seg.end()).norm() {
                0.0
            } else {
                1.0
            };
            (seg.point(t), t)
        }
        Segment::Trochoid { .. } => (seg.start(), 0.0),
    }
}

/// The two pieces of a segment split at local parameter t ([`Segment::part`]).
pub(crate) fn split(seg: &Segment, t: f64) -> (Segment, Segment) {
    (seg.part(0.0, t), seg.part(t, 1.0))
}

/// The closed loop re-started at its point nearest `q`.
pub(crate) fn start_near(lp: &[Segment], q: P2) -> Vec<Segment> {
    let (mut best, mut bt, mut bd) = (0, 0.0, f64::INFINITY);
    for (i, s) in lp.iter().enumerate() {
        let (p, t) = closest_on(s, q);
        if (p - q).norm() < bd {
            (best, bt, bd) = (i, t, (p - q).norm());
        }
    }
    let (head, tail) = split(&lp[best], bt);
    let mut out = Vec::with_capacity(lp.len() + 1);
    if tail.length() > 1e-9 {
        out.push(tail);
    }
    out.extend_from_slice(&lp[best + 1..]);
    out.extend_from_slice(&lp[..best]);
    if head.length() > 1e-9 {
        out.push(head);
    }
    out
}

/// The moves of one part being built (`Builder::default()`: none yet).
#[derive(Default)]
pub(crate) struct Builder {
    pub(crate) segments: Vec<Segment>,
    pub(crate) kinds: Vec<MoveKind>,
    /// Corner-point radii already derived, by (α, ρ₀): the finishing pass is the same for every
    /// core fraction, so each sequence is computed once per region.
    pub(crate) radii: Vec<(f64, f64, Vec<f64>)>,
    /// The links' router (kept across the core fractions) and the moves reached by a retract.
    pub(crate) router: crate::pocket::route::RouterCache,
    pub(crate) retracts: Vec<usize>,
}

impl Builder {
    pub(crate) fn push(&mut self, seg: Segment, kind: MoveKind) {
        if seg.length() > 1e-9 {
            self.segments.push(seg);
            self.kinds.push(kind);
        }
    }

    pub(crate) fn at(&self) -> P2 {
        self.segments.last().map_or(P2::zeros(), Segment::end)
    }

    pub(crate) fn line(&mut self, to: P2, kind: MoveKind) {
        let from = self.at();
        self.push(Segment::Line { start: from, end: to }, kind);
    }
}

/// A link through cleared material from the current position to `to`: the shortest path on
/// which the tool keeps r from the walls ([`crate::pocket::route`]); a retract where there is none.
pub(crate) fn link(b: &mut Builder, polygon: &Polygon, r: f64, to: P2) {
    let from = b.at();
    match b.router.get(polygon, r).route(from, to) {
        Some(pts) => pts.iter().skip(1).for_each(|&p| b.line(p, MoveKind::Link)),
        None => b.retracts.push(b.segments.len()),
    }
}

/// The radius of the largest circle in the region, by bisection on inward offsets, and its
/// centre (the middle of the last offset that does not vanish).
pub(crate) fn inscribed(region: &Region) -> (f64, P2) {
    let ext = region.extents();
    let (mut lo, mut hi) = (0.0, ext.map_or(1.0, |(a, b)| 0.5 * (b.x - a.x).min(b.y - a.y)) + 1e-9);
    let mut centre = region.vertices().first().copied().unwrap_or_else(P2::zeros);
    for _ in 0..INSCRIBED_STEPS {
        let mid = 0.5 * (lo + hi);
        match largest(region.offset(mid)) {
            Some(o) => {
                lo = mid;
                if let Some((a, b)) = o.extents() {
                    centre = p2(0.5 * (a.x + b.x), 0.5 * (a.y + b.y));
                }
            }
            None => hi = mid,
        }
    }
    (lo, centre)
}
