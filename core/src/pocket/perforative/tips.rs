//! Step 4 of the medial-axis planner (docs/pockets.md): where the chain ends in a corner of
//! the tool-centre region, corner-point arcs (radii from [`crate::corner::point`]) instead of
//! the straight tip into the corner point.

use super::MAX_CORNER_ARCS;
use super::axis::Guide;
use super::circles::{Current, Planner};
use crate::corner::point::corner_point_radii;
use crate::geom::medial::WallFeature;
use crate::geom::{P2, Segment, bisect_edge};
use crate::pocket::CornerPoint;
use crate::toolpath::MoveKind;
use std::f64::consts::{PI, TAU};

impl Planner<'_> {
    /// The way into the end of a guide, where the tool-centre region C (the pocket offset
    /// by r) has a corner U0 (Rc = r) between two wall features: two edges (a convex corner
    /// of the pocket), two reflex vertices (the mouth of a neck narrower than the tool) or an
    /// edge and a reflex vertex. Instead of the straight tip into U0, which reads π − α at U0
    /// for the corner angle α of C there ([`super::adaptive::corner_point_bound_rad`]; at a
    /// neck mouth of width w, C's boundary arcs meet at α = π − 2·asin(w/D), so 2·asin(w/D)),
    /// corner-point arcs as in `trochoplan corner`: the arc of tool-centre radius ρ is
    /// centred at the axis point o(ρ) with clearance r + ρ (the matching vertex of C offset
    /// inward by ρ), so it touches both features' tool-centre boundaries (the lines at r from
    /// the edges, the circles of radius r about the vertices), and runs counter-clockwise
    /// between the two touching points through the side of U0. The radii come from
    /// [`corner_point_radii`] with C's angle at U0, from the last circle's ρ (which touches
    /// both features: it left the cap that derivation models) down to the corner tolerance δ;
    /// exact for two edges, for a vertex C is narrower than that wedge (its boundary is an
    /// arc bulging inward), and the evaluator measures every move. Per arc: along the first
    /// feature's boundary to its touching point (a line, or an arc of radius r about the
    /// vertex), the arc, back on its chord (within ρ of o, so at least r from the walls); after
    /// the last, back to its centre on the axis. What is left is the sliver within reach of
    /// U0 only: |o_n − U0| − δ on the axis (`residual_mm`; for two edges δ(1/sin(α/2) − 1)).
    /// Returns the arc length of the last centre on the guide (where the tool stops), or
    /// `None` where the arcs do not apply (no two features at U0, or the last circle does not
    /// touch both) and the straight tip is cut.
    pub(super) fn thin_tip(&mut self, guide: &Guide, cur: &Current, rho_cur: f64, end: f64) -> Option<f64> {
        let (r, delta) = (self.r(), self.corner_tolerance);
        let tol = 1e-6 * (1.0 + r);
        let u0 = guide.at(end);
        let [f1, f2] = self.walls.nearest_features(u0, tol)[..] else { return None };
        let touches = |f: WallFeature, o: P2, rho: f64| (f.distance(o) - (rho + r)).abs() <= 1e3 * tol;
        if !(touches(f1, cur.center, rho_cur) && touches(f2, cur.center, rho_cur)) {
            return None;
        }
        let (n1, n2) = ((u0 - f1.nearest(u0)).normalize(), (u0 - f2.nearest(u0)).normalize());
        let alpha = PI - n1.dot(&n2).clamp(-1.0, 1.0).acos();
        let radii = corner_point_radii(rho_cur, alpha, r, self.cs.target, delta, MAX_CORNER_ARCS);
        // Each arc's centre on the guide (Rc falls towards U0), checked to touch both features.
        let mut arcs = Vec::with_capacity(radii.len());
        for &rho in &radii {
            let s = bisect_edge(cur.s, end, 60, |s| self.rho(guide.at(s)) >= rho);
            let o = guide.at(s);
            if !(touches(f1, o, rho) && touches(f2, o, rho)) {
                return None;
            }
            arcs.push((s, o, rho));
        }
        let (&(_, o1, _), &(s_last, o_last, rho_last)) = (arcs.first()?, arcs.last()?);
        let toward = |f: WallFeature, o: P2| (f.nearest(o) - o).normalize();
        let angle = |v: P2| v.y.atan2(v.x);
        // Counter-clockwise from the first feature to the second through the side of U0.
        let sweep12 = (angle(toward(f2, o1)) - angle(toward(f1, o1))).rem_euclid(TAU);
        let (f_in, f_out) =
            if (angle(u0 - o1) - angle(toward(f1, o1))).rem_euclid(TAU) < sweep12 { (f1, f2) } else { (f2, f1) };
        // every arc keeps r from every wall, exactly (its centre's clearance comes from a
        // bisection): else the straight tip
        let arc_of = |o: P2, rho: f64| {
            let (a, e) = (o + toward(f_in, o) * rho, o + toward(f_out, o) * rho);
            Segment::Arc {
                center: o,
                radius: rho,
                start_angle: angle(a - o),
                sweep: (angle(e - o) - angle(a - o)).rem_euclid(TAU),
            }
        };
        if !arcs.iter().all(|&(_, o, rho)| crate::pocket::guard::keeps_off_walls(self.poly, &arc_of(o, rho), r)) {
            return None;
        }
        let at0 = cur.center + toward(f_in, cur.center) * rho_cur;
        let (undo, pos) = (self.b.segments.len(), self.b.pos);
        match cur.entry {
            // the circle's full turn, then on to its touching point on the first feature (no
            // further where the turn ends there: a rounding error must not add a turn)
            Some(a) => {
                let on = (angle(at0 - cur.center) - a + 1e-6).rem_euclid(TAU) - 1e-6;
                self.b.arc(cur.center, rho_cur, a, TAU + on.max(0.0), MoveKind::Circle)
            }
            None => {
                self.b.line(cur.center, MoveKind::Link);
                self.b.line(at0, MoveKind::Link);
            }
        }
        let first = self.b.segments.len();
        // material left on the axis before U0, and the deepest cut of one arc there
        let (mut left, mut deepest) = ((cur.center - u0).norm() - rho_cur, 0.0_f64);
        for (i, &(_, o, rho)) in arcs.iter().enumerate() {
            let (a, e) = (o + toward(f_in, o) * rho, o + toward(f_out, o) * rho);
            self.along(f_in, a);
            let sweep = (angle(e - o) - angle(a - o)).rem_euclid(TAU);
            self.b.arc(o, rho, angle(a - o), sweep, MoveKind::CornerPoint);
            if i + 1 < arcs.len() {
                self.b.line(a, MoveKind::CornerPoint);
            }
            let now = (o - u0).norm() - rho;
            deepest = deepest.max(left - now);
            left = now;
        }
        self.b.line(o_last, MoveKind::CornerPoint);
        let point = CornerPoint {
            vertex: u0,
            angle_rad: alpha,
            arcs: arcs.len(),
            last_radius_mm: rho_last,
            residual_mm: left,
            max_radial_depth_mm: deepest,
            max_engagement_rad: 0.0,
            at: u0,
        };
        // the moves along the features and back keep r from every wall too, else the tip
        if !self.b.segments[undo..].iter().all(|sg| crate::pocket::guard::keeps_off_walls(self.poly, sg, r)) {
            self.b.segments.truncate(undo);
            self.b.kinds.truncate(undo);
            self.b.pos = pos;
            return None;
        }
        self.corner_points.push((point, first..self.b.segments.len()));
        Some(s_last)
    }
    /// Along a feature's tool-centre boundary to `to`: a line along an edge, the arc of radius
    /// r about a vertex (the shorter way).
    pub(super) fn along(&mut self, f: WallFeature, to: P2) {
        match f {
            WallFeature::Edge(..) => self.b.line(to, MoveKind::CornerPoint),
            WallFeature::Vertex(v) => {
                let (a, b) = (self.b.pos - v, to - v);
                let a0 = a.y.atan2(a.x);
                let sweep = (b.y.atan2(b.x) - a0 + PI).rem_euclid(TAU) - PI;
                if sweep.abs() * a.norm() > 1e-9 {
                    self.b.arc(v, a.norm(), a0, sweep, MoveKind::CornerPoint);
                }
                self.b.pos = to;
            }
        }
    }
}
