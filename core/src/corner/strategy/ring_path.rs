//! The ring path around a corner's circles (docs/corners.md): the U leg, the circles linked by
//! lines along U, the corner-point arcs ([`crate::corner::point`]) instead of the straight move
//! into U0, and the V leg.

use super::{CornerCircle, CornerPointArcs, CornerScenario, MAX_CIRCLES};
use crate::corner::geometry::Corner;
use crate::corner::point::corner_point_radii;
use crate::geom::{P2, Segment};
use crate::toolpath::MoveKind;
use std::f64::consts::{PI, TAU};

/// The way into the corner point after the last wall-tangent circle (tool-centre radius
/// `rho_last`, the tool at `at`, its tangent point on U), then along V to `end` if given.
/// With a corner tolerance δ: the corner-point arcs of [`corner_point_radii`] — per arc a move
/// along U to its tangent point, the arc (counter-clockwise through π − 2α) to its tangent
/// point on V and, but after the last, back on its chord (between the arc and the last circle,
/// cut) — so the tool never reaches U0 and the corner is cut to radius r + δ. Without: Wu et
/// al.'s straight move into U0. The last move (along V) is not part of the way in. Returns
/// the arcs, if any.
pub(super) fn into_corner_point(
    moves: &mut Moves,
    sc: &CornerScenario,
    rho_last: f64,
    at: P2,
    end: Option<P2>,
) -> Option<CornerPointArcs> {
    let s = sc.settings;
    let Some(delta) = s.corner_tolerance else {
        moves.push(Segment::Line { start: at, end: sc.corner_point }, MoveKind::Tip);
        if let Some(e) = end {
            moves.push(Segment::Line { start: sc.corner_point, end: e }, MoveKind::Ring);
        }
        return None;
    };
    let (corner, r) = (&sc.corner, s.tool_radius);
    let (n_in, n_out, alpha) = (corner.normal_in(), corner.normal_out(), corner.half_angle);
    let radii = corner_point_radii(rho_last, 2.0 * alpha, r, s.target, delta, MAX_CIRCLES);
    let k = 1.0 / alpha.sin() - 1.0;
    let (mut here, mut rho, mut deepest) = (at, rho_last, 0.0_f64);
    for (i, &next) in radii.iter().enumerate() {
        let o = corner.on_bisector(corner.t_for_radius(next + r));
        let (a, e) = (o - n_in * next, o - n_out * next);
        if (a - here).norm() > 1e-12 {
            moves.push(Segment::Line { start: here, end: a }, MoveKind::CornerPoint);
        }
        let dir = a - o;
        let arc = Segment::Arc { center: o, radius: next, start_angle: dir.y.atan2(dir.x), sweep: PI - 2.0 * alpha };
        moves.push(arc, MoveKind::CornerPoint);
        here = if i + 1 < radii.len() {
            moves.push(Segment::Line { start: e, end: a }, MoveKind::CornerPoint);
            a
        } else {
            e
        };
        deepest = deepest.max((rho - next) * k);
        rho = next;
    }
    if let Some(e) = end {
        moves.push(Segment::Line { start: here, end: e }, MoveKind::Ring);
    }
    Some(CornerPointArcs { residual_mm: rho * k, max_radial_depth_mm: deepest, radii_mm: radii })
}

/// The ring piece up to the corner's way in: U leg to the first circle's tangent point on U (or
/// to `leg_end` and back along U to it), then [`circles_along_u`].
pub(super) fn ring_path(sc: &CornerScenario, circles: &[CornerCircle], leg_end: Option<P2>) -> (Moves, P2) {
    let mut moves = Moves::default();
    let first = circles
        .first()
        .map_or(sc.corner_point, |c| c.tool_circle.center - sc.corner.normal_in() * c.tool_circle.radius);
    let at = match leg_end {
        Some(x) => {
            moves.push(Segment::Line { start: sc.ring_start, end: x }, MoveKind::Ring);
            x
        }
        None => {
            moves.push(Segment::Line { start: sc.ring_start, end: first }, MoveKind::Ring);
            first
        }
    };
    let at = circles_along_u(&mut moves, &sc.corner, circles, at);
    (moves, at)
}

/// Each circle once round (CCW) from its tangent point on U, linked by straight moves along U
/// from `at`; returns where the tool ends (the last circle's tangent point).
pub(super) fn circles_along_u(moves: &mut Moves, corner: &Corner, circles: &[CornerCircle], mut at: P2) -> P2 {
    let n_in = corner.normal_in();
    for c in circles {
        let (o, rho) = (c.tool_circle.center, c.tool_circle.radius);
        let tangent = o - n_in * rho; // point of the tool circle on U
        if (tangent - at).norm() > 1e-12 {
            moves.push(Segment::Line { start: at, end: tangent }, MoveKind::Link);
        }
        let dir = tangent - o;
        moves.push(
            Segment::Arc { center: o, radius: rho, start_angle: dir.y.atan2(dir.x), sweep: TAU },
            MoveKind::Circle,
        );
        at = tangent;
    }
    at
}

/// A corner path under construction: the moves and what each does.
#[derive(Default)]
pub(super) struct Moves {
    pub(super) path: Vec<Segment>,
    pub(super) kinds: Vec<MoveKind>,
}

impl Moves {
    pub(super) fn push(&mut self, seg: Segment, kind: MoveKind) {
        self.path.push(seg);
        self.kinds.push(kind);
    }
}
