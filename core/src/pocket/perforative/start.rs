//! Step 2 of the medial-axis planner (docs/pockets.md): a part's entry at its axis point of
//! largest clearance (helix, else ramp) and the concentric circles out of the bore, each the
//! largest within the target.

use super::axis::{AxisGraph, Guide};
use super::circles::{Current, Planner, bisect, transition_along};
use crate::engagement::engagement_profile;
use crate::error::Error;
use crate::geom::{Circle, P2, Segment};
use crate::pocket::adaptive::AdaptiveOptions;
use crate::pocket::entry::entry_at;
use crate::toolpath::{Entry, MoveKind};
use std::f64::consts::{PI, TAU};

impl Planner<'_> {
    /// One connected part: entry at the root (helix, else ramp), concentric clearing out of
    /// the helix bore, then every leaf. Returns the entry.
    pub(super) fn part(&mut self, g: &AxisGraph, root: usize, options: &AdaptiveOptions) -> Result<Entry, Error> {
        let center = g.nodes[root];
        let rho_root = self.rho(center);
        let way_in = entry_at(self.poly, self.r(), options, center, rho_root, 0.0)?;
        let bore = way_in.at_depth();
        self.b.pos = bore.start();
        self.b.segments.push(bore);
        self.b.kinds.push(MoveKind::Entry);
        self.b.pos = bore.end();
        let mut cur = match way_in {
            Entry::Helix(h) => {
                self.push_circle(center, h.radius, None, MoveKind::Entry)?;
                let entry = self.spiral(center, h.radius, h.start_angle, rho_root, None)?;
                Current { s: 0.0, center, offset_radius: rho_root.max(h.radius) + self.r(), entry }
            }
            // The ramp cleared its line, a slot of width D through the root: back to the root
            // along it, then concentric circles grow out of the slot, each measured.
            Entry::Ramp(ramp) => {
                self.b.line(center, MoveKind::Link);
                let d = ramp.end - ramp.start;
                let cut = vec![way_in.bore()];
                match self.spiral(center, 0.0, d.y.atan2(d.x), rho_root, Some(cut))? {
                    Some(entry) => Current { s: 0.0, center, offset_radius: rho_root + self.r(), entry: Some(entry) },
                    None => Current { s: 0.0, center, offset_radius: self.r(), entry: None },
                }
            }
            // (open sides are adaptive clearing's only: `--open-edges` errors for this method)
            // (open sides are adaptive clearing's only; a descent into cleared stock is not a way in)
            Entry::Outside { .. } | Entry::Down { .. } => {
                Current { s: 0.0, center, offset_radius: self.r(), entry: None }
            }
        };
        let walks = g.leaf_walks(root);
        let mut prev: Option<(Vec<usize>, Guide, Vec<Current>, f64)> = None;
        for walk in walks {
            let guide = g.guide(&walk);
            // Circles of the previous walk on the shared prefix; the chain restarts at the last.
            let mut placed = vec![cur];
            if let Some((pw, pg, pc, stop)) = &prev {
                let common = walk.iter().zip(pw).take_while(|(a, b)| a == b).count();
                let s_lca = guide.node_s[common - 1];
                placed = pc.iter().copied().filter(|c| c.s <= s_lca + 1e-9).collect();
                let restart = placed[placed.len() - 1];
                let back = pg.walk(*stop, restart.s);
                self.b.polyline(&back, MoveKind::Return);
                cur = Current { entry: None, ..restart };
            }
            let stop = self.chain(&guide, cur, &mut placed)?;
            prev = Some((walk, guide, placed, stop));
        }
        Ok(way_in)
    }
    /// Concentric circles about the helix centre `c`, from the helix circle (tool-centre radius
    /// `rho0`, the tool at angle `theta0` on it) up to tool-centre radius `rho_max`. Returns
    /// the entry angle of the last circle (`None` if none was cut).
    ///
    /// After a ramp (`cut`: what it cleared; `rho0` = 0, the tool at `c`) the two-circle
    /// model does not hold: it counts the whole disc outside the tool as material, and reads
    /// π/2 + arcsin(ρ/2r) ≥ 90° for any first circle (a plunge hole, module docs), where the
    /// ramp's slot has cleared most of it. Each candidate radius is then measured instead: the
    /// evaluator over its half-circle and circle, with the ramp's line and the spiral so far
    /// as cut, in the same bisection.
    pub(super) fn spiral(
        &mut self,
        c: P2,
        rho0: f64,
        theta0: f64,
        rho_max: f64,
        mut cut: Option<Vec<Segment>>,
    ) -> Result<Option<f64>, Error> {
        let (r, target, eps, r_min) = (self.r(), self.cs.target, self.cs.tolerance, self.cs.r_min());
        if rho_max <= rho0 + 1e-9 {
            return Ok(None);
        }
        let (mut prev_rho, mut theta) = (rho0, theta0);
        loop {
            // Next radius: the largest in (ρ, ρ_max] within the target (bisection).
            let prev_c = Circle::new(c, prev_rho + r);
            let e = P2::new(theta.cos(), theta.sin());
            let m = |x: f64| match &cut {
                None => {
                    self.engagement(prev_c, Circle::new(c, x + r)).max(self.transition_engagement(c, prev_rho, c, x))
                }
                Some(before) => {
                    let (mid, rt, _) = transition_along(c, prev_rho, c, x, e);
                    let moves = [
                        Segment::Arc { center: mid, radius: rt, start_angle: theta, sweep: PI },
                        Segment::Arc { center: c, radius: x, start_angle: theta + PI, sweep: TAU },
                    ];
                    engagement_profile(self.poly, before, &moves, &self.opts).map_or(PI, |p| p.max_angle())
                }
            };
            let mut next = bisect(prev_rho, rho_max, target, eps, m);
            if next.0 <= prev_rho + 1e-6 {
                let x = (prev_rho + r_min).min(rho_max);
                next = (x, m(x));
            }
            let rho = next.0;
            let first = self.b.segments.len();
            let (mid, rt, _) = transition_along(c, prev_rho, c, rho, e);
            self.b.arc(mid, rt, theta, PI, MoveKind::Spiral);
            theta += PI;
            self.push_circle(c, rho, Some(next.1), MoveKind::Spiral)?;
            if rho >= rho_max - 1e-9 {
                return Ok(Some(theta)); // its full turn is cut by the chain (`link`, `finish`)
            }
            self.b.arc(c, rho, theta, TAU, MoveKind::Spiral);
            if let Some(before) = &mut cut {
                before.extend_from_slice(&self.b.segments[first..]);
            }
            prev_rho = rho;
        }
    }
}
