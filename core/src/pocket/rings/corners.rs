//! The corner strategy of every ring (docs/pockets.md): each convex corner of a ring replaced
//! by the `corner` command's variable or isometric circles (Wu et al. 2016) and their
//! corner-point arcs, where the corner scenario's preconditions hold and the circles stay in
//! the pocket.

use super::{RingCorner, Tagged, piece_is_inside};
use crate::corner::{Corner, CornerMethod, CornerScenario, CornerSettings, plan_corner, strategy::CornerPointArcs};
use crate::error::Error;
use crate::geom::{P2, Polygon, Segment};
use crate::pocket::PocketSettings;
use crate::toolpath::MoveKind;

/// Adapter from a ring to [`plan_corner`] (see the module docs): every convex line–line corner
/// of the closed CCW loop `ring` gets the corner trochoids of `method`, spliced in
/// place of the incoming line. Returns the new loop, the number of corners done and the number
/// of convex corners left plain because the corner scenario's preconditions failed.
pub fn ring_with_corner_trochoids(
    polygon: &Polygon,
    ring: &[Segment],
    settings: PocketSettings,
    method: CornerMethod,
) -> Result<(Vec<Segment>, usize, usize), Error> {
    let (tagged, done, skipped, _) = corner_ring(polygon, ring, settings, method, None, settings.tool_radius)?;
    Ok((tagged.into_iter().map(|(s, _)| s).collect(), done, skipped))
}

/// [`ring_with_corner_trochoids`] with each segment tagged: [`MoveKind::Corner`] for the
/// strategy's pieces (its circles and links), [`MoveKind::CornerPoint`] for its corner-point
/// arcs and their moves, [`MoveKind::Ring`] for the ring's own. With a corner tolerance δ
/// (docs/corners.md) each strategy ends with the corner-point arcs of
/// [`crate::corner::plan_corner`] instead of Wu et al.'s move into U0: its last arc ends on the
/// outgoing ring line, δ·cot α past U0 (tangent to it), and the next ring segment starts there
/// (for the last corner, the loop's first segment: the loop stays closed). Returns also the
/// corners that got arcs.
pub(super) fn corner_ring(
    polygon: &Polygon,
    ring: &[Segment],
    settings: PocketSettings,
    method: CornerMethod,
    corner_tolerance: Option<f64>,
    clearance: f64,
) -> Result<(Tagged, usize, usize, Vec<RingCorner>), Error> {
    let (r, ae) = (settings.tool_radius, settings.step_over);
    let base =
        CornerSettings { feed_mm_per_min: settings.feed_mm_per_min, corner_tolerance, ..CornerSettings::new(r, ae)? };
    let n = ring.len();
    // the piece at each convex line–line vertex i (between ring[i] and ring[i + 1]), or why not
    let mut pieces: Vec<Option<Piece>> = Vec::with_capacity(n);
    let mut convex = vec![false; n];
    for i in 0..n {
        let (seg, next) = (ring[i], ring[(i + 1) % n]);
        let (Segment::Line { start: a, end: u0 }, Segment::Line { end: c, .. }) = (seg, next) else {
            pieces.push(None);
            continue;
        };
        let (u, v) = (u0 - a, c - u0);
        // straight or reflex (concave-of-pocket) vertex, or one that deepens the cut by no more
        // than the corner tolerance δ: a_e·(1/sin(α/2) − 1) on the bisector, α = π − the turn
        let turn = crate::geom::cross(u, v).atan2(u.dot(&v));
        let delta = corner_tolerance.unwrap_or(crate::corner::point::DEFAULT_CORNER_TOLERANCE_MM);
        if crate::geom::cross(u, v) <= 1e-9 * u.norm() * v.norm() || ae * (1.0 / (0.5 * turn).cos() - 1.0) <= delta {
            pieces.push(None);
            continue;
        }
        convex[i] = true;
        pieces.push(corner_piece(a, u0, c, base, method).filter(|p| piece_is_inside(polygon, &p.path, clearance)));
    }
    // Each segment starts where the piece before it ended. A piece whose first move would
    // not run forward from there is dropped (its corner stays plain), which may move the start
    // of the segment after it: repeat until nothing changes (drops only, so this ends).
    let start_of =
        |pieces: &[Option<Piece>], i: usize| pieces[(i + n - 1) % n].as_ref().map_or(ring[i].start(), |p| p.end);
    loop {
        let mut dropped = false;
        for i in 0..n {
            let from = start_of(&pieces, i);
            if let Some(p) = &pieces[i]
                && !p.starts_after(from)
            {
                pieces[i] = None;
                dropped = true;
            }
        }
        if !dropped {
            break;
        }
    }
    let mut out = Vec::with_capacity(n);
    let (mut done, mut skipped, mut points) = (0, 0, Vec::new());
    for i in 0..n {
        let from = start_of(&pieces, i);
        match &pieces[i] {
            Some(p) => {
                let mut path = p.path.clone();
                if let Some(Segment::Line { start, .. }) = path.first_mut() {
                    *start = from;
                }
                out.extend(path.into_iter().zip(p.kinds.iter().copied()));
                if let Some(arcs) = &p.arcs {
                    points.push((ring[i].end(), p.angle, arcs.clone()));
                }
                done += 1;
            }
            None => {
                let seg = match ring[i] {
                    Segment::Line { end, .. } => Segment::Line { start: from, end },
                    other => other,
                };
                out.push((seg, MoveKind::Ring));
                skipped += usize::from(convex[i]);
            }
        }
    }
    Ok((out, done, skipped, points))
}

/// A corner strategy's path in place of the incoming ring line (see [`corner_piece`]).
pub(super) struct Piece {
    pub(super) path: Vec<Segment>,
    pub(super) kinds: Vec<MoveKind>,
    /// Where it ends: U0, or on the outgoing line past it (after corner-point arcs).
    pub(super) end: P2,
    /// Interior angle of the corner (rad) and its corner-point arcs, if any.
    pub(super) angle: f64,
    pub(super) arcs: Option<CornerPointArcs>,
}

impl Piece {
    /// Whether its first move (along the incoming line) can start at `from` instead: `from`
    /// on that line before the move's end.
    pub(super) fn starts_after(&self, from: P2) -> bool {
        let Some(Segment::Line { start, end }) = self.path.first() else { return false };
        let len = (end - start).norm();
        let dir = (end - start) / len;
        crate::geom::cross(dir, from - start).abs() < 1e-6 && (from - start).dot(&dir) < len - 1e-9
    }
}

/// The strategy's path from `a` (start of the incoming ring line) to the corner vertex `u0`,
/// or with corner-point arcs to the end of the last arc on the outgoing line u0→`c` (between
/// them), or `None` where the corner scenario does not apply.
pub(super) fn corner_piece(a: P2, u0: P2, c: P2, base: CornerSettings, method: CornerMethod) -> Option<Piece> {
    let r = base.tool_radius;
    let at_vertex = Corner::new(u0, u0 - a, c - u0).ok()?;
    let (alpha, b) = (at_vertex.half_angle, at_vertex.bisector);
    let apex = u0 - b * (r / alpha.sin());
    let corner = Corner::new(apex, at_vertex.dir_in, at_vertex.dir_out).ok()?;
    // Wall length from the apex: the ring line's length plus the foot of U0 on the wall, r/tan α.
    let edge_length = (u0 - a).norm().min((c - u0).norm()) + r / alpha.tan();
    let sc = CornerScenario::new(corner, CornerSettings { edge_length, ..base }).ok()?;
    let plan = plan_corner(&sc, method).ok()?;
    let (mut path, mut kinds) = (plan.toolpath.segments(), plan.toolpath.kinds());
    path.pop(); // the V leg: the next ring segment
    kinds.pop();
    let kinds = kinds.into_iter().map(|k| if k == MoveKind::CornerPoint { k } else { MoveKind::Corner }).collect();
    let first = path.first_mut()?;
    let Segment::Line { end: e, .. } = *first else { return None };
    // The strategy's first move must end on the incoming line, between a and u0.
    let (dir, len) = ((u0 - a) / (u0 - a).norm(), (u0 - a).norm());
    let t = (e - a).dot(&dir);
    if !(t >= 0.0 && t <= len && crate::geom::cross(dir, e - a).abs() < 1e-6) {
        return None;
    }
    *first = Segment::Line { start: a, end: e };
    // It ends at U0, or after corner-point arcs on the outgoing line short of its end.
    let end = path.last().map(Segment::end)?;
    let (out_dir, out_len) = ((c - u0) / (c - u0).norm(), (c - u0).norm());
    let along = (end - u0).dot(&out_dir);
    if (end - u0).norm() > 1e-6 && !(crate::geom::cross(out_dir, end - u0).abs() < 1e-6 && along < out_len - 1e-6) {
        return None;
    }
    Some(Piece { path, kinds, end, angle: 2.0 * alpha, arcs: plan.corner_point })
}
