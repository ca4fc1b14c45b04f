//! The circles of the medial-axis planner and what places them (docs/pockets.md): the
//! variable-circle bisection of Wu et al. 2016 (eqs. 23–24), the G1 half-circle between nested
//! circles, the path builder and the two-circle engagement of a candidate.

use super::{AxisCircle, COVER_TOL_MM, MAX_BISECTION, MAX_CIRCLES};
use crate::corner::CornerSettings;
use crate::engagement::{EvaluatorOptions, Turn, TwoCircle};
use crate::error::Error;
use crate::geom::medial::Walls;
use crate::geom::{Circle, P2, Polygon, Segment, golden_min};
use crate::pocket::CornerPoint;
use crate::toolpath::MoveKind;
use std::f64::consts::PI;

/// The variable-circle bisection on (lo, hi] for a metric m with m(lo) = 0 (the same circle): hi if
/// m(hi) ≤ a*; else the first x with m(x) ∈ (a*, a* + ε]; after 60 steps the last x found
/// under a* (or lo). Returns (x, m(x)).
pub(super) fn bisect(mut lo: f64, mut hi: f64, target: f64, eps: f64, m: impl Fn(f64) -> f64) -> (f64, f64) {
    let at_hi = m(hi);
    if at_hi <= target {
        return (hi, at_hi);
    }
    let mut best = (lo, 0.0);
    for _ in 0..MAX_BISECTION {
        let x = 0.5 * (lo + hi);
        let v = m(x);
        if v > target && v <= target + eps {
            return (x, v);
        }
        if v <= target {
            lo = x;
            best = (x, v);
        } else {
            hi = x;
        }
    }
    best
}

/// The G1 half-circle from the tool-centre circle (c1, ρ1) to (c2, ρ2) when one contains the
/// other (|ρ2 − ρ1| ≥ |c2 − c1|; concentric circles included): with u the unit vector from c1
/// to c2 (any if they coincide), it starts at A = c1 + ρ1·u, where circle 1 runs along
/// rot90(u), and ends at B = c2 − ρ2·u, where circle 2 runs along −rot90(u); A and B lie on
/// one line along u, so the half-circle on AB (counter-clockwise from A) is tangent to both.
/// Returns its centre, radius and start angle (its sweep is π).
pub(super) fn transition(c1: P2, rho1: f64, c2: P2, rho2: f64) -> (P2, f64, f64) {
    let d = c2 - c1;
    transition_along(c1, rho1, c2, rho2, if d.norm() > 1e-12 { d / d.norm() } else { P2::new(1.0, 0.0) })
}

/// [`transition`] with the direction u given (for concentric circles).
pub(super) fn transition_along(c1: P2, rho1: f64, c2: P2, rho2: f64, u: P2) -> (P2, f64, f64) {
    let (a, b) = (c1 + u * rho1, c2 - u * rho2);
    ((a + b) / 2.0, (a - b).norm() / 2.0, u.y.atan2(u.x))
}

/// The path under construction.
pub(super) struct Builder {
    pub(super) segments: Vec<Segment>,
    pub(super) kinds: Vec<MoveKind>,
    pub(super) pos: P2,
}

impl Builder {
    pub(super) fn line(&mut self, to: P2, kind: MoveKind) {
        if (to - self.pos).norm() > 1e-9 {
            self.segments.push(Segment::Line { start: self.pos, end: to });
            self.kinds.push(kind);
        }
        self.pos = to;
    }

    pub(super) fn arc(&mut self, center: P2, radius: f64, start_angle: f64, sweep: f64, kind: MoveKind) {
        if radius > 0.0 && sweep.abs() > 1e-12 {
            self.segments.push(Segment::Arc { center, radius, start_angle, sweep });
            self.kinds.push(kind);
        }
        self.pos = center + P2::new((start_angle + sweep).cos(), (start_angle + sweep).sin()) * radius;
    }

    pub(super) fn polyline(&mut self, pts: &[P2], kind: MoveKind) {
        for &p in pts {
            self.line(p, kind);
        }
    }
}

/// The circle the chain continues from: its arc length on the guide, offset radius, and the
/// angle at which the tool entered its tool-centre circle (`None`: the tool is at its centre or
/// the circle is already cut).
#[derive(Clone, Copy, Debug)]
pub(super) struct Current {
    pub(super) s: f64,
    pub(super) center: P2,
    pub(super) offset_radius: f64,
    pub(super) entry: Option<f64>,
}

impl Current {
    /// Whether the disc of radius `radius` about `q` lies in this circle's cleared disc (up to
    /// [`COVER_TOL_MM`]).
    pub(super) fn covers(&self, q: P2, radius: f64) -> bool {
        (q - self.center).norm() + radius <= self.offset_radius + COVER_TOL_MM
    }
}

pub(super) struct Planner<'a> {
    pub(super) poly: &'a Polygon,
    pub(super) walls: &'a Walls,
    pub(super) cs: CornerSettings,
    /// Corner tolerance δ of the corner-point arcs (mm, `--corner-tolerance`).
    pub(super) corner_tolerance: f64,
    /// The evaluator's options for the spiral out of a ramp's slot.
    pub(super) opts: EvaluatorOptions,
    pub(super) b: Builder,
    pub(super) circles: Vec<AxisCircle>,
    /// The tips thinned by corner-point arcs, with the range of their segments.
    pub(super) corner_points: Vec<(CornerPoint, std::ops::Range<usize>)>,
}

impl Planner<'_> {
    pub(super) fn r(&self) -> f64 {
        self.cs.tool_radius
    }
    pub(super) fn rho(&self, q: P2) -> f64 {
        self.walls.clearance(q) - self.r()
    }
    pub(super) fn engagement(&self, prev: Circle, cur: Circle) -> f64 {
        TwoCircle { previous: prev, current: cur, tool_radius: self.r(), turn: Turn::Ccw }.max_engagement().angle
    }
    /// Largest two-circle engagement along the half-circle transition from the circle
    /// (c1, ρ1) to (c2, ρ2) of [`Planner::transition`], after the first circle was cut: the
    /// half-circle is a piece of a circle, so the model applies to it over its half turn
    /// (scanned every 0.5°, refined by golden section).
    pub(super) fn transition_engagement(&self, c1: P2, rho1: f64, c2: P2, rho2: f64) -> f64 {
        let (m, rt, a0) = transition(c1, rho1, c2, rho2);
        let model = TwoCircle {
            previous: Circle::new(c1, rho1 + self.r()),
            current: Circle::new(m, rt + self.r()),
            tool_radius: self.r(),
            turn: Turn::Ccw,
        };
        let f = |phi: f64| model.engagement_at(phi).angle;
        let n = 360;
        let (mut best, mut at) = (0.0, a0);
        for i in 0..=n {
            let phi = a0 + PI * i as f64 / n as f64;
            if f(phi) > best {
                (best, at) = (f(phi), phi);
            }
        }
        let h = PI / n as f64;
        let (lo, hi) = ((at - h).max(a0), (at + h).min(a0 + PI));
        best.max(-golden_min(lo, hi, 1e-9, |p| -f(p)).1)
    }
    pub(super) fn push_circle(
        &mut self,
        center: P2,
        rho: f64,
        predicted: Option<f64>,
        kind: MoveKind,
    ) -> Result<(), Error> {
        self.circles.push(AxisCircle {
            tool_circle: Circle::new(center, rho),
            offset_radius: rho + self.r(),
            predicted_max_rad: predicted,
            kind,
        });
        if self.circles.len() > MAX_CIRCLES {
            return Err(Error::geometry("circles", self.circles.len(), format!("at most {MAX_CIRCLES} per pocket")));
        }
        Ok(())
    }
}
