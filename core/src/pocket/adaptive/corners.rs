//! Step 4 and 6 of adaptive clearing (docs/adaptive-clearing.md): the convex corners of a
//! tool-centre loop, the thinning arcs tangent to both walls, and the arcs into a corner point
//! after the finishing arc ([`crate::corner::point`]).

use super::MAX_PASSES;
use super::loops::{Builder, link};
use super::options::concave_step;
use super::part::PartContext;
use super::plan::CornerPasses;
use crate::corner::point::corner_point_radii;
use crate::geom::{P2, Segment, cross, p2, rot90};
use crate::pocket::CornerPoint;
use crate::pocket::cusp::Cusp;
use crate::toolpath::MoveKind;
use std::f64::consts::PI;

/// How far along wall A, from one corner arc's start toward the next one's, the straight move
/// from the previous arc's end reaches (the rest is run along the wall into the arc).
pub(super) const CORNER_CHORD_REACH: f64 = 0.9;

/// A convex corner of a tool-centre loop between two lines.
pub(super) struct Corner {
    pub(super) vertex: P2,
    pub(super) d_in: P2,
    pub(super) d_out: P2,
    pub(super) alpha: f64,
    pub(super) len_in: f64,
    pub(super) len_out: f64,
}

/// The loop with consecutive collinear lines joined (offsets keep the vertices where other
/// edges' offsets ended), so that a corner's walls are whole.
pub(super) fn merged(lp: &[Segment]) -> Vec<Segment> {
    let mut out: Vec<Segment> = Vec::with_capacity(lp.len());
    for seg in lp {
        if let (Some(Segment::Line { start, end }), Segment::Line { end: e2, .. }) = (out.last().copied(), *seg)
            && cross((end - start).normalize(), (e2 - end).normalize()).abs() < 1e-9
            && (end - start).dot(&(e2 - end)) > 0.0
        {
            *out.last_mut().unwrap_or(&mut Segment::Line { start, end }) = Segment::Line { start, end: e2 };
            continue;
        }
        out.push(*seg);
    }
    if out.len() > 2
        && let (Segment::Line { start: s0, end: e0 }, Segment::Line { start: sl, end: el }) =
            (out[0], out[out.len() - 1])
        && cross((el - sl).normalize(), (e0 - s0).normalize()).abs() < 1e-9
        && (el - sl).dot(&(e0 - s0)) > 0.0
    {
        out[0] = Segment::Line { start: sl, end: e0 };
        out.pop();
    }
    out
}

pub(super) fn convex_corners(lp: &[Segment]) -> Vec<Corner> {
    let lp = merged(lp);
    let n = lp.len();
    let mut out = Vec::new();
    for i in 0..n {
        let (a, b) = (&lp[i], &lp[(i + 1) % n]);
        let (Segment::Line { start: a0, end: v }, Segment::Line { end: b1, .. }) = (*a, *b) else { continue };
        let (d_in, d_out) = ((v - a0).normalize(), (b1 - v).normalize());
        let turn = cross(d_in, d_out).atan2(d_in.dot(&d_out));
        if turn > 1e-6 {
            out.push(Corner {
                vertex: v,
                d_in,
                d_out,
                alpha: PI - turn,
                len_in: (v - a0).norm(),
                len_out: (b1 - v).norm(),
            });
        }
    }
    out
}

impl Corner {
    /// Tangent points on the incoming and outgoing walls and the arc of radius ρ.
    pub(super) fn arc(&self, rho: f64) -> (P2, P2, Segment) {
        let half = 0.5 * self.alpha;
        let l = rho / half.tan();
        let b = (self.d_out - self.d_in).normalize();
        let center = self.vertex + b * (rho / half.sin());
        let a = self.vertex - self.d_in * l;
        let e = self.vertex + self.d_out * l;
        let start_angle = (a.y - center.y).atan2(a.x - center.x);
        (a, e, Segment::Arc { center, radius: rho, start_angle, sweep: PI - self.alpha })
    }

    /// The corner whose walls are the tangents at the ends of a counter-clockwise arc of radius
    /// ρ (centre, start angle, sweep π − α): V lies ρ/sin(α/2) from the centre on the arc's
    /// middle radius. The walls' lengths are the arc's tangent lengths ρ/tan(α/2).
    pub(super) fn of_arc(center: P2, rho: f64, start_angle: f64, sweep: f64) -> Corner {
        let alpha = PI - sweep;
        let half = 0.5 * alpha;
        let dir = |a: f64| p2(a.cos(), a.sin());
        let mid = dir(start_angle + 0.5 * sweep);
        let l = rho / half.tan();
        Corner {
            vertex: center + mid * (rho / half.sin()),
            d_in: crate::geom::rot90(dir(start_angle)),
            d_out: crate::geom::rot90(dir(start_angle + sweep)),
            alpha,
            len_in: l,
            len_out: l,
        }
    }

    /// The corner of a counter-clockwise finishing arc (centre, radius ρ, start angle, sweep)
    /// between the loop's segments `prev` and `next`, each a line or an arc about a reflex
    /// vertex of the pocket run clockwise (the loop outside it). Between two lines: the corner
    /// of the tangents at the arc's ends ([`Corner::of_arc`]). With an arc side, that tangent
    /// would cut the corner short of the region's tip: the corner's walls are then the tangents
    /// at the points of the sides nearest the tip T of the region the loop is the offset of by
    /// s_f (`sf`), T where the sides moved inward by s_f meet (nearest the arc's middle), so that
    /// T lies s_f from both walls as in a corner between two lines and the corner points pass
    /// s_f from it. A line side is its own tangent; a circle of radius ρ_c about c touches the
    /// wall through c + ρ_c·(T − c)/|T − c| normal to T − c. `None` where the sides do not meet
    /// or do not make a convex corner.
    pub(super) fn of_sides(prev: &Segment, arc: &Segment, next: &Segment, sf: f64) -> Option<Corner> {
        let Segment::Arc { center, radius, start_angle, sweep } = *arc else { return None };
        let side = |sg: &Segment| match *sg {
            Segment::Line { start, end } if (end - start).norm() > 0.0 => {
                Some(Side::Line(start, (end - start).normalize()))
            }
            Segment::Arc { center, radius, sweep, .. } if sweep < 0.0 => Some(Side::Circle(center, radius)),
            _ => None,
        };
        let (a, b) = (side(prev)?, side(next)?);
        if let (Side::Line(..), Side::Line(..)) = (a, b) {
            return Some(Corner::of_arc(center, radius, start_angle, sweep));
        }
        let mid = arc.point(0.5);
        let tip = a
            .meet(b, sf)
            .into_iter()
            .filter(|q| q.x.is_finite() && q.y.is_finite())
            .min_by(|p, q| (p - mid).norm().total_cmp(&(q - mid).norm()))?;
        let ((p_in, d_in), (p_out, d_out)) = (a.tangent(tip), b.tangent(tip));
        let den = cross(d_in, d_out);
        let turn = den.atan2(d_in.dot(&d_out));
        if turn <= 1e-6 || den.abs() < 1e-12 {
            return None;
        }
        let vertex = p_in + d_in * (cross(p_out - p_in, d_out) / den);
        let alpha = PI - turn;
        let l = radius / (0.5 * alpha).tan();
        Some(Corner { vertex, d_in, d_out, alpha, len_in: l, len_out: l })
    }

    /// Cap area between the corner and its arc of radius ρ.
    pub(super) fn cap_area(&self, rho: f64) -> f64 {
        let half = 0.5 * self.alpha;
        rho * rho * (1.0 / half.tan() - (PI - self.alpha) / 2.0)
    }
}

/// Pieces each corner-point arc is cut into, so that the evaluator measures it at its
/// bisector and quarter points (the arcs are shorter than the sampling spacing).
pub(super) const CORNER_POINT_PIECES: usize = 4;

/// The arcs into a corner point after the finishing arc of radius ρ₀ (the tool at its end, on
/// wall B): back on that arc's chord (cleared) to wall A, then per arc: along wall A to its
/// tangent point, the arc (radius from [`next_corner_point_radius`]), and back on its chord;
/// after the last (radius δ) along wall B to the finishing arc's end. Every move is
/// [`MoveKind::CornerPoint`], measured like the rest.
pub(super) fn corner_point_arcs(b: &mut Builder, c: &Corner, rho0: f64, r: f64, phi: f64, delta: f64) -> CornerPoint {
    let (a0, e0, _) = c.arc(rho0);
    let k = 1.0 / (0.5 * c.alpha).sin() - 1.0;
    let (mut rho, mut arcs, mut deepest) = (rho0, 0, 0.0_f64);
    b.line(a0, MoveKind::CornerPoint);
    let known = b.radii.iter().position(|(alpha, r0, _)| *alpha == c.alpha && *r0 == rho0);
    let radii = match known {
        Some(i) => b.radii[i].2.clone(),
        None => {
            let radii = corner_point_radii(rho0, c.alpha, r, phi, delta, MAX_PASSES);
            b.radii.push((c.alpha, rho0, radii.clone()));
            radii
        }
    };
    for next in radii {
        let (a, _, arc) = c.arc(next);
        b.line(a, MoveKind::CornerPoint);
        if let Segment::Arc { center, radius, start_angle, sweep } = arc {
            let piece = sweep / CORNER_POINT_PIECES as f64;
            for j in 0..CORNER_POINT_PIECES {
                let start_angle = start_angle + piece * j as f64;
                b.push(Segment::Arc { center, radius, start_angle, sweep: piece }, MoveKind::CornerPoint);
            }
        }
        if next > delta * (1.0 + 1e-9) {
            b.line(a, MoveKind::CornerPoint);
        }
        deepest = deepest.max((rho - next) * k);
        rho = next;
        arcs += 1;
    }
    b.line(e0, MoveKind::CornerPoint);
    CornerPoint {
        vertex: c.vertex,
        angle_rad: c.alpha,
        arcs,
        last_radius_mm: rho,
        residual_mm: rho * k,
        max_radial_depth_mm: deepest,
        max_engagement_rad: 0.0,
        at: c.vertex,
    }
}

/// Step 4: the thinning passes into every convex corner `corners_all` of the part's region, from
/// radius T (Δ/k more at the end whose half-circle ring 0 left, `trimmed`) down to ρ_fin, each
/// removing at most the concave-cut step on the bisector; from the corner nearest the tool, in
/// the loop's order.
pub(super) fn corner_passes(
    b: &mut Builder,
    p: &PartContext<'_>,
    corners_all: &[Corner],
    t: f64,
    trimmed: Option<(P2, P2, f64)>,
) -> Vec<CornerPasses> {
    let (polygon, options, r, phi, rho_fin) = (p.polygon, p.options, p.r, p.phi, p.rho_fin);
    // Corners: the caps between the opening (radius T) and ρ_fin.
    // The first corner pass's radius: T, or Δ/k more at the end whose half-circle ring 0 left.
    let first_radius = |c: &Corner| {
        let k = 1.0 / (0.5 * c.alpha).sin() - 1.0;
        let extra = match trimmed {
            Some((end, other, delta)) if (c.vertex - end).norm() < (c.vertex - other).norm() => delta / k,
            _ => 0.0,
        };
        (t + extra).min(c.len_in.min(c.len_out) * (0.5 * c.alpha).tan())
    };
    // From the corner whose first pass starts nearest the tool, in the loop's order.
    let here = b.at();
    let first = (0..corners_all.len())
        .min_by(|&i, &j| {
            let d = |c: &Corner| (c.arc(first_radius(c)).0 - here).norm();
            d(&corners_all[i]).total_cmp(&d(&corners_all[j]))
        })
        .unwrap_or(0);
    let mut corners = Vec::new();
    for c in corners_all[first..].iter().chain(&corners_all[..first]) {
        let k = 1.0 / (0.5 * c.alpha).sin() - 1.0;
        let mut rho = first_radius(c);
        // (a corner that leaves no more than the corner tolerance on its bisector has no passes)
        if rho <= rho_fin + 1e-6 || (rho - rho_fin) * k <= options.corner_tolerance_mm {
            continue;
        }
        let (a0, _, _) = c.arc(rho);
        link(b, polygon, r, a0);
        let mut passes = 0;
        let mut deepest: f64 = 0.0;
        while rho > rho_fin + 1e-6 && passes < MAX_PASSES {
            // Fixed point: the step allowed at the new radius.
            let mut next = rho - concave_step(rho, r, phi) / k;
            next = (rho - concave_step(next.max(rho_fin), r, phi) / k).max(rho_fin);
            // After the first: from the previous arc's end on wall B straight to wall A, short
            // of this arc's start by a tenth of the gap between the two arcs' tangent points,
            // then along wall A into the arc (entered tangentially, as the step rule assumes).
            let (a, _, arc) = c.arc(next);
            if passes > 0 {
                let (a_prev, _, _) = c.arc(rho);
                b.line(a_prev + (a - a_prev) * CORNER_CHORD_REACH, MoveKind::Link);
            }
            b.line(a, MoveKind::Corner);
            b.push(arc, MoveKind::Corner);
            deepest = deepest.max((rho - next) * k);
            rho = next;
            passes += 1;
        }
        corners.push(CornerPasses {
            vertex: c.vertex,
            angle_rad: c.alpha,
            passes,
            last_radius_mm: rho,
            max_radial_depth_mm: deepest,
            max_engagement_rad: 0.0,
            at: c.vertex,
        });
    }
    corners
}

/// Step 4 at the cusps (a neck's mouth): arcs tangent to both walls from T down to ρ_fin
/// ([`crate::pocket::cusp`]), each back on its chord and along the incoming wall into the next.
pub(super) fn cusp_passes(b: &mut Builder, p: &PartContext<'_>, cusps_all: &[Cusp], t: f64) -> Vec<CornerPasses> {
    let (polygon, r, phi, rho_fin) = (p.polygon, p.r, p.phi, p.rho_fin);
    let mut corners = Vec::new();
    // Cusps (a neck's mouth): arcs tangent to both walls from T down to ρ_fin, each back on
    // its chord (inside its own disc: cleared) and along the incoming wall into the next.
    for c in cusps_all {
        let rho0 = t.min(c.rho_max);
        let radii = c.radii(rho0, rho_fin, r, phi);
        let (Some((a0, _, _)), false) = (c.arc(rho0), radii.is_empty()) else { continue };
        link(b, polygon, r, a0);
        let (mut rho_prev, mut a_prev, mut deepest) = (rho0, a0, 0.0_f64);
        for &rho in &radii {
            let Some((a, _, arc)) = c.arc(rho) else { break };
            b.line(a_prev, MoveKind::Link);
            for sg in c.along_wall(a_prev, a) {
                b.push(sg, MoveKind::Corner);
            }
            b.push(arc, MoveKind::Corner);
            deepest = deepest.max(c.depth(rho_prev, rho));
            (rho_prev, a_prev) = (rho, a);
        }
        corners.push(CornerPasses {
            vertex: c.vertex,
            angle_rad: c.alpha,
            passes: radii.len(),
            last_radius_mm: rho_prev,
            max_radial_depth_mm: deepest,
            max_engagement_rad: 0.0,
            at: c.vertex,
        });
    }
    corners
}

/// A side of a finishing corner: a line through a point with its unit direction (the region on
/// its left), or a circle about a reflex vertex of the pocket with its radius (the region
/// outside it, run clockwise).
#[derive(Clone, Copy)]
enum Side {
    Line(P2, P2),
    Circle(P2, f64),
}

impl Side {
    /// The points where the two sides, each moved into the region by `d`, meet.
    fn meet(self, other: Side, d: f64) -> Vec<P2> {
        let line_circle = |p: P2, u: P2, c: P2, rho: f64| -> Vec<P2> {
            // p' + s·u with |p' + s·u − c| = ρ: s² + 2s·u·w + |w|² − ρ² = 0, w = p' − c
            let w = p + rot90(u) * d - c;
            let (h, q) = (u.dot(&w), w.norm_squared() - (rho + d).powi(2));
            let disc = h * h - q;
            if disc < 0.0 {
                return Vec::new();
            }
            [-h - disc.sqrt(), -h + disc.sqrt()].iter().map(|s| c + w + u * *s).collect()
        };
        match (self, other) {
            (Side::Line(p, u), Side::Circle(c, rho)) | (Side::Circle(c, rho), Side::Line(p, u)) => {
                line_circle(p, u, c, rho)
            }
            (Side::Circle(c1, r1), Side::Circle(c2, r2)) => {
                let (ra, rb, dist) = (r1 + d, r2 + d, (c2 - c1).norm());
                if dist < 1e-12 || dist > ra + rb || dist < (ra - rb).abs() {
                    return Vec::new();
                }
                let x = (dist * dist + ra * ra - rb * rb) / (2.0 * dist);
                let (u, h) = ((c2 - c1) / dist, (ra * ra - x * x).max(0.0).sqrt());
                vec![c1 + u * x + rot90(u) * h, c1 + u * x - rot90(u) * h]
            }
            (Side::Line(p1, u1), Side::Line(p2_, u2)) => {
                let den = cross(u1, u2);
                if den.abs() < 1e-12 {
                    return Vec::new();
                }
                let (q1, q2) = (p1 + rot90(u1) * d, p2_ + rot90(u2) * d);
                vec![q1 + u1 * (cross(q2 - q1, u2) / den)]
            }
        }
    }

    /// The wall through the side's point nearest `tip`, tangent to it, in the loop's direction:
    /// a point and a unit direction.
    fn tangent(self, tip: P2) -> (P2, P2) {
        match self {
            Side::Line(p, u) => (p, u),
            Side::Circle(c, rho) => {
                let n = (tip - c).normalize();
                (c + n * rho, -rot90(n))
            }
        }
    }
}
