//! Steps 3 and 5 of the medial-axis planner (docs/pockets.md): circles along a guide, each
//! placed by the variable-circle bisection and joined by the common tangent or a G1
//! half-circle, the narrow stretches where ρ < r_min, and the way back along the axis.

use super::axis::Guide;
use super::circles::{Current, Planner, bisect, transition};
use super::{CLEARANCE_STEP_MM, SHORT_TURN_RAD};
use crate::error::Error;
use crate::geom::{Circle, P2, bisect_edge, rot90};
use crate::pocket::rings::link_is_inside;
use crate::toolpath::MoveKind;
use std::f64::consts::{PI, TAU};

impl Planner<'_> {
    /// Circles and axis moves along `guide` from the circle `start` to the guide's end.
    /// `placed` collects the circles (with their arc length) for the next restart. A circle
    /// the search finds inside the current circle's cleared disc cuts nothing: it is skipped
    /// and the search goes on from there (`from`). Returns the arc length where the tool stops.
    pub(super) fn chain(&mut self, guide: &Guide, start: Current, placed: &mut Vec<Current>) -> Result<f64, Error> {
        let (r, target, eps, r_min) = (self.r(), self.cs.target, self.cs.tolerance, self.cs.r_min());
        let end = guide.length();
        let mut cur = start;
        let mut from = cur.s;
        loop {
            let rho_cur = cur.offset_radius - r;
            // Search range: up to 2·R ahead, not past the first point where ρ < r_min.
            // Not past the next Voronoi vertex either: its circle touches three walls.
            let node = guide.node_s.iter().copied().find(|&n| n > from + 1e-6).unwrap_or(end);
            let reach = (from + 2.0 * cur.offset_radius).min(end).min(node);
            let zone_end = self.zone_end(guide, from, reach);
            let m = |s: f64| {
                let q = guide.at(s);
                let rho = self.rho(q).max(r_min);
                let circle = self.engagement(Circle::new(cur.center, cur.offset_radius), Circle::new(q, rho + r));
                if (rho - rho_cur).abs() >= (q - cur.center).norm() {
                    circle.max(self.transition_engagement(cur.center, rho_cur, q, rho))
                } else {
                    circle
                }
            };
            let next = if zone_end > from + 1e-6 {
                Some(bisect(from, zone_end, target, eps, m)).filter(|n| n.0 > from + 1e-6)
            } else {
                None
            };
            match next {
                Some((s, _)) if cur.covers(guide.at(s), self.rho(guide.at(s)).max(r_min) + r) => from = s,
                Some((s, v)) => {
                    let q = guide.at(s);
                    let rho = self.rho(q).max(r_min);
                    self.link(guide, &cur, rho_cur, s, q, rho);
                    self.push_circle(q, rho, Some(v), MoveKind::Circle)?;
                    cur = Current { s, center: q, offset_radius: rho + r, entry: Some(self.angle_of(q)) };
                    from = s;
                    placed.push(cur);
                }
                None if self.zone_start(guide, from, end).is_none()
                    && guide.walk(cur.s, end).iter().all(|&q| cur.covers(q, r)) =>
                {
                    // The tip move would run in the cleared disc (which is convex: so does the
                    // axis polyline between points that do).
                    self.finish(&cur, rho_cur);
                    self.b.line(cur.center, MoveKind::Link);
                    return Ok(cur.s);
                }
                None => {
                    // ρ < r_min ahead: finish the circle, go along the axis to where circles
                    // fit again (a neck) or to the guide's end (a corner tip), unless the tip
                    // is thinned by corner-point arcs.
                    let resume = self.zone_start(guide, cur.s, end);
                    if resume.is_none()
                        && let Some(stop) = self.thin_tip(guide, &cur, rho_cur, end)
                    {
                        return Ok(stop);
                    }
                    self.finish(&cur, rho_cur);
                    self.b.line(cur.center, MoveKind::Link);
                    match resume {
                        Some(s) => {
                            self.b.polyline(&guide.walk(cur.s, s), MoveKind::Straight);
                            let q = guide.at(s);
                            let rho = self.rho(q).max(r_min);
                            self.b.line(q - rot90(guide.dir(s)) * rho, MoveKind::Link);
                            let a0 = self.angle_of(q);
                            self.push_circle(q, rho, None, MoveKind::Circle)?;
                            cur = Current { s, center: q, offset_radius: rho + r, entry: Some(a0) };
                            from = s;
                            placed.push(cur);
                        }
                        None => {
                            self.b.polyline(&guide.walk(cur.s, end), MoveKind::Tip);
                            return Ok(end);
                        }
                    }
                }
            }
        }
    }
    /// Angle of the tool's position about `center`.
    pub(super) fn angle_of(&self, center: P2) -> f64 {
        let d = self.b.pos - center;
        d.y.atan2(d.x)
    }
    /// Complete the current circle (a full turn from its entry) if it has one.
    pub(super) fn finish(&mut self, cur: &Current, rho: f64) {
        if let Some(a) = cur.entry {
            self.b.arc(cur.center, rho, a, TAU, MoveKind::Circle);
        }
    }
    /// From the current circle to the next one (centre q, tool-centre radius ρ, at arc length s):
    /// the circle's turn up to the right common tangent, the tangent, ending at the next circle.
    pub(super) fn link(&mut self, guide: &Guide, cur: &Current, rho_cur: f64, s: f64, q: P2, rho: f64) {
        let d = q - cur.center;
        let dist = d.norm();
        let u = d / dist;
        let v = rot90(u);
        let sin_b = (rho - rho_cur) / dist;
        let (exit, entry, tangent_ok) = if sin_b.abs() < 1.0 {
            let nrm = v * (1.0 - sin_b * sin_b).sqrt() + u * sin_b;
            (cur.center - nrm * rho_cur, q - nrm * rho, true)
        } else {
            (cur.center - v * rho_cur, q - v * rho, false)
        };
        let inside = tangent_ok && link_is_inside(self.poly, exit, entry, self.r());
        if !inside && dist < rho_cur + rho {
            // One circle contains the other, or the tangent would come closer than r to a wall
            // (a reflex corner): the half-circle transition (G1, inside both circles' discs
            // when they overlap without containment, so in cut material).
            let (m, rt, a0) = transition(cur.center, rho_cur, q, rho);
            match cur.entry {
                Some(a) => self.b.arc(cur.center, rho_cur, a, TAU + (a0 - a).rem_euclid(TAU), MoveKind::Circle),
                None => {
                    self.b.line(cur.center, MoveKind::Link);
                    self.b.line(cur.center + P2::new(a0.cos(), a0.sin()) * rho_cur, MoveKind::Link);
                }
            }
            self.b.arc(m, rt, a0, PI, MoveKind::Link);
            return;
        }
        let exit_angle = (exit - cur.center).y.atan2((exit - cur.center).x);
        match cur.entry {
            Some(a) => {
                let delta = (exit_angle - a + SHORT_TURN_RAD).rem_euclid(TAU) - SHORT_TURN_RAD;
                let sweep = if tangent_ok && inside { TAU + delta } else { TAU };
                self.b.arc(cur.center, rho_cur, a, sweep, MoveKind::Circle);
            }
            None => {
                // Restarting from the centre of a circle cut before: out to its exit point.
                self.b.line(cur.center, MoveKind::Link);
                if tangent_ok && inside {
                    self.b.line(exit, MoveKind::Link);
                }
            }
        }
        if tangent_ok && inside {
            self.b.line(entry, MoveKind::Link);
        } else {
            // Along the axis, centre to centre, then out to the next circle.
            self.b.line(cur.center, MoveKind::Link);
            self.b.polyline(&guide.walk(cur.s, s), MoveKind::Link);
            self.b.line(q - v * rho, MoveKind::Link);
        }
    }
    /// The first arc length in (s0, s1] where ρ < r_min, or s1 if there is none. Sampled every
    /// [`CLEARANCE_STEP_MM`], the crossing refined by bisection.
    /// Samples where ρ is well above r_min are followed by as many as the clearance's slope
    /// (at most 1 along the guide) cannot bring below it; those are not computed.
    pub(super) fn zone_end(&self, guide: &Guide, s0: f64, s1: f64) -> f64 {
        let r_min = self.cs.r_min();
        let ok = |s: f64| self.rho(guide.at(s)) >= r_min;
        let n = ((s1 - s0) / CLEARANCE_STEP_MM).ceil().max(1.0) as usize;
        let at = |k: usize| s0 + (s1 - s0) * k as f64 / n as f64;
        let mut k = 1;
        while k <= n {
            let s = at(k);
            let above = self.rho(guide.at(s)) - r_min;
            if above < 0.0 {
                return bisect_edge(at(k - 1), s, 50, ok);
            }
            let same = (above - 1e-9 * (1.0 + above + r_min)) / ((s1 - s0) / n as f64);
            k += 1 + if same.is_finite() && same > 1.0 { same.ceil() as usize - 1 } else { 0 };
        }
        s1
    }
    /// The first arc length in (s0, s1] where ρ ≥ r_min again after a narrow stretch, if any.
    pub(super) fn zone_start(&self, guide: &Guide, s0: f64, s1: f64) -> Option<f64> {
        let r_min = self.cs.r_min();
        let ok = |s: f64| self.rho(guide.at(s)) >= r_min;
        let n = ((s1 - s0) / CLEARANCE_STEP_MM).ceil().max(1.0) as usize;
        let mut prev = s0;
        let mut left = false;
        for k in 1..=n {
            let s = s0 + (s1 - s0) * k as f64 / n as f64;
            let good = ok(s);
            if !good {
                left = true;
            } else if left {
                return Some(bisect_edge(s, prev, 50, ok));
            }
            prev = s;
        }
        None
    }
}
