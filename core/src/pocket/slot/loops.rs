//! The trochoid's loops along one run of the centre line: each loop a half circle about a point
//! of the axis, radius the local half-width of the tool-centre region (the wall clearance
//! less r + s_f), cut counter-clockwise (climb with M3) from the right side over the front to
//! the left side, then a straight link across the back to the next loop's right side. The
//! back half of a circle would run in material the loop before has cut, so it is left out
//! (the link is 2a long instead of πa). The step to the next loop is the largest whose
//! two-circle engagement (Wu et al. 2016; [`TwoCircle`]) stays within the planned angle.

use crate::engagement::{Turn, TwoCircle};
use crate::geom::{Circle, P2, bisect_edge};

/// The least step between two loops (mm), so that a run ends where the model would ask for an
/// ever smaller step.
pub(super) const MIN_STEP_MM: f64 = 0.01;
/// Bisection steps of the loop step.
const STEP_BISECTION: usize = 16;

/// One loop: its centre on the axis, its radius, and the direction of the run there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Loop {
    pub(super) center: P2,
    pub(super) radius: f64,
    pub(super) dir: P2,
}

impl Loop {
    /// The right side of the loop (where its arc starts).
    pub(super) fn right(&self) -> P2 {
        self.center + crate::geom::p2(self.dir.y, -self.dir.x) * self.radius
    }

    /// The loop's front arc, counter-clockwise from the right side over the front to the left
    /// side: radius `flat` × a about the point `√(flat² − 1)·a` behind the centre (a half
    /// circle for `flat` = 1): its centre, radius, start angle and sweep.
    pub(super) fn arc(&self, flat: f64) -> (P2, f64, f64, f64) {
        let back = self.radius * (flat * flat - 1.0).max(0.0).sqrt();
        let c = self.center - self.dir * back;
        let n = self.right() - c;
        (c, flat * self.radius, n.y.atan2(n.x), 2.0 * self.radius.atan2(back))
    }
}

/// What is cut about a point before a loop: the point, the radius cut about it, and the radius
/// a of the loop that cut it.
pub(super) type Cut = (P2, f64, f64);

/// Point and unit direction at arc length `s` along the polyline `line`.
fn at(line: &[P2], s: f64) -> (P2, P2) {
    let mut left = s;
    let mut dir = crate::geom::p2(1.0, 0.0);
    for w in line.windows(2) {
        let l = (w[1] - w[0]).norm();
        if l <= 1e-12 {
            continue;
        }
        dir = (w[1] - w[0]) / l;
        if left <= l {
            return (w[0] + dir * left, dir);
        }
        left -= l;
    }
    (line[line.len() - 1], dir)
}

/// Whether the largest two-circle engagement of a loop of radius `a` about `c` after the
/// circle `prev` (centre, radius of what it cut) was cut, tool radius `r`, is within `phi`.
fn within(prev: (P2, f64), c: P2, a: f64, r: f64, phi: f64) -> bool {
    let tc = TwoCircle {
        previous: Circle { center: prev.0, radius: prev.1 },
        current: Circle { center: c, radius: a + r },
        tool_radius: r,
        turn: Turn::Ccw,
    };
    !tc.exceeds(phi)
}

/// The loops along `line` after the cut circle `start` (its centre, the radius it cut, and the
/// radius a of the loop that cut it), and the same of the last loop: the first at the largest step within `phi`, and so on, the last at the end of the
/// line. `radius` gives the loop radius at an axis point; where it is larger than the loop
/// before by more than a concentric circle may grow within `phi`, the loop is that much smaller. Err(()) when more than `max_loops`.
pub(super) fn loops_along(
    line: &[P2],
    start: Cut,
    radius: &dyn Fn(P2) -> f64,
    (r, phi, flat): (f64, f64, f64),
    max_loops: usize,
) -> Result<(Vec<Loop>, Cut), ()> {
    let mut prev = (start.0, start.1);
    let total: f64 = line.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
    let mut out = Vec::new();
    let mut s = 0.0;
    let mut last_step: f64 = 0.0;
    // the radius the last loop cut about its own centre (for the growth cap), and its arc's
    let (mut prev_r, mut prev_a) = (start.2 + r, start.2);
    while s < total - 1e-9 {
        // a loop grows by at most what a concentric circle may within φ (ρ with
        // (a + r)² = ρ² + r² + 2ρr·cos φ), less a tenth for the step
        let rp = prev_r;
        let grown = -r * phi.cos() + (r * r * phi.cos().powi(2) - r * r + rp * rp).max(0.0).sqrt();
        let cap = (rp - r) + 0.9 * (grown - (rp - r)).max(0.0);
        let size = |c: P2| radius(c).min(cap);
        // the model's circles: the front arcs' (their centres behind the loops' by √(k² − 1)·a)
        let fits = |step: f64| {
            let (c, dir) = at(line, s + step);
            let a = size(c);
            let lp = Loop { center: c, radius: a, dir };
            let (fc, fr, _, _) = lp.arc(if a > prev_a + 1e-9 { 1.0 } else { flat });
            within(prev, fc, fr, r, phi)
        };
        let left = total - s;
        // bracketed near the step before (3 × it, where that is short of the end): the bisection
        // then ends within a 2⁻¹⁶ share of the bracket, below 0.1 µm for the steps of a loop
        let near = 3.0 * last_step;
        let step = if fits(left) {
            left
        } else if last_step > 0.0 && near < left {
            if fits(near) {
                bisect_edge(near, left, STEP_BISECTION, fits)
            } else {
                bisect_edge(0.0, near, STEP_BISECTION, fits)
            }
        } else {
            bisect_edge(0.0, left, STEP_BISECTION, fits)
        }
        .max(MIN_STEP_MM.min(left));
        last_step = step;
        s += step;
        let (center, dir) = at(line, s);
        let a = size(center);
        let lp = Loop { center, radius: a, dir };
        let (fc, fr, _, _) = lp.arc(if a > prev_a + 1e-9 { 1.0 } else { flat });
        out.push(lp);
        prev = (fc, fr + r);
        (prev_r, prev_a) = (a + r, a);
        if out.len() > max_loops {
            return Err(());
        }
    }
    Ok((out, (prev.0, prev.1, prev_a)))
}
