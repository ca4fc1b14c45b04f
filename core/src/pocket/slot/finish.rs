//! The finishing contour after the trochoidal slot (as adaptive clearing's, docs/adaptive-clearing.md):
//! the tool-centre region offset by r, its convex corners rounded to ρ_fin + s_f so that each
//! corner arc removes the stock s_f within the target, entered on a quarter-circle lead-in from
//! cleared material; at every rounded convex corner the arcs into the corner point
//! ([`corner_point_radii`]), down to the corner tolerance δ. A corner is where the tangents at
//! the rounding arc's ends meet; its sides are walls offset by r or arcs r about a reflex vertex
//! of the pocket (the tips of the region where a branch of the centre line runs between a
//! wall and a reflex corner, as at the junction of a T: rounded, they would stay uncut).

use crate::corner::point::corner_point_radii;
use crate::error::{Error, Param};
use crate::geom::offset::{Region, largest};
use crate::geom::{P2, Polygon, Segment, p2, rot90};
use crate::pocket::CornerPoint;
use crate::pocket::adaptive::{Builder, link, start_near};
use crate::toolpath::MoveKind;
use std::f64::consts::PI;

/// Most arcs into one corner point (bounds the work on hostile input).
const MAX_CORNER_ARCS: usize = 20_000;
/// Pieces each corner-point arc is cut into (its bisector and quarter points measured).
const CORNER_POINT_PIECES: usize = 4;

/// What the finishing pass needs: the pocket, the tool-centre region at r + s_f, the tool
/// radius, the stock, the corner radius ρ_fin, the target φ and the corner tolerance δ.
pub(super) struct Finish<'a> {
    pub(super) polygon: &'a Polygon,
    pub(super) region: &'a Region,
    pub(super) r: f64,
    pub(super) sf: f64,
    pub(super) rho_fin: f64,
    pub(super) phi: f64,
    pub(super) delta: f64,
}

/// Append the finishing pass to `b`; the corner points it reaches.
pub(super) fn finishing_pass(b: &mut Builder, f: &Finish<'_>) -> Result<Vec<CornerPoint>, Error> {
    let (polygon, r, sf, rho_fin) = (f.polygon, f.r, f.sf, f.rho_fin);
    let inner = largest(f.region.offset(rho_fin)).ok_or_else(|| {
        Error::param(Param::Polygon, "no finishing contour", "a pocket wider than the tool plus the stock")
    })?;
    let fin = largest(inner.offset(-(rho_fin + sf)))
        .ok_or_else(|| Error::param(Param::Polygon, "no finishing contour", "a pocket wider than the tool"))?;
    let loop_segs = fin.segments();
    // Lead-in: a quarter circle of radius max(s_f, r/2) tangent to the straight wall nearest
    // the tool, starting in cleared material; where none keeps off the walls, straight on.
    let lead = sf.max(0.5 * r);
    let here = b.at();
    let lead_in = |(mid, dir): (P2, P2)| {
        let (center, start_angle) = (mid + rot90(dir) * lead, (-dir.y).atan2(-dir.x));
        (mid, Segment::Arc { center, radius: lead, start_angle, sweep: 0.5 * PI })
    };
    let clear = |(_, arc): &(P2, Segment)| crate::pocket::guard::keeps_off_walls(polygon, arc, r);
    let chosen = loop_segs
        .iter()
        .filter_map(|sg| match *sg {
            Segment::Line { start, end } if (end - start).norm() >= 2.0 * lead => Some((start, end)),
            _ => None,
        })
        .map(|(a, c)| {
            let (len, dir) = ((c - a).norm(), (c - a).normalize());
            lead_in((a + dir * (here - a).dot(&dir).clamp(lead, len - 1e-3), dir))
        })
        .filter(clear)
        .min_by(|x, y| (x.0 - here).norm().total_cmp(&(y.0 - here).norm()));
    let mid = match chosen {
        Some((mid, arc)) => {
            link(b, polygon, r, arc.start());
            b.push(arc, MoveKind::Finish);
            mid
        }
        None => {
            let mid = loop_segs[0].start();
            link(b, polygon, r, mid);
            mid
        }
    };
    let fin_loop = start_near(&loop_segs, mid);
    let n = fin_loop.len();
    let mut corner_points = Vec::new();
    // a side of a corner: a line, or an arc turning the other way (the offset of a reflex vertex
    // of the pocket, r about it), which turns away from its tangent at the corner, so that no
    // tool position between the tangents comes nearer than r to that vertex. The tool-centre
    // region ends in such corners where a branch of the centre line runs between a wall and
    // a reflex vertex (a junction of arms): the rounded corner leaves its tip uncut.
    let side = |sg: &Segment| match *sg {
        Segment::Line { .. } => true,
        Segment::Arc { sweep, .. } => sweep < 0.0,
        _ => false,
    };
    for (i, seg) in fin_loop.iter().enumerate() {
        b.push(*seg, MoveKind::Finish);
        if let Segment::Arc { center, radius, start_angle, sweep } = *seg
            && sweep > 1e-9
            && (radius - (rho_fin + sf)).abs() < 1e-6
            && (radius - f.delta) * (1.0 / (0.5 * sweep).cos() - 1.0) > f.delta
            && side(&fin_loop[(i + n - 1) % n])
            && side(&fin_loop[(i + 1) % n])
        {
            let before = b.segments.len();
            let point = corner_point_arcs(b, center, radius, start_angle, sweep, f);
            if b.segments[before..].iter().all(|sg| crate::pocket::guard::keeps_off_walls(polygon, sg, r)) {
                corner_points.push(point);
            } else {
                b.segments.truncate(before);
                b.kinds.truncate(before);
            }
        }
    }
    Ok(corner_points)
}

/// The arcs into the corner point of the corner whose walls are the tangents at the ends of the
/// counter-clockwise finishing arc (centre, radius ρ₀, start angle, sweep π − α), the tool at
/// its end: back on the arc's chord (cleared) to wall A, then per arc along wall A to its
/// tangent point, the arc, and back on its chord; after the last (radius δ) along wall B to
/// the finishing arc's end. Every move is [`MoveKind::CornerPoint`].
fn corner_point_arcs(
    b: &mut Builder,
    center: P2,
    rho0: f64,
    start_angle: f64,
    sweep: f64,
    f: &Finish<'_>,
) -> CornerPoint {
    let alpha = PI - sweep;
    let half = 0.5 * alpha;
    let dir = |a: f64| p2(a.cos(), a.sin());
    let vertex = center + dir(start_angle + 0.5 * sweep) * (rho0 / half.sin());
    let (d_in, d_out) = (rot90(dir(start_angle)), rot90(dir(start_angle + sweep)));
    let arc = |rho: f64| {
        let l = rho / half.tan();
        let bis = (d_out - d_in).normalize();
        let c = vertex + bis * (rho / half.sin());
        let a = vertex - d_in * l;
        let e = vertex + d_out * l;
        (a, e, c, (a.y - c.y).atan2(a.x - c.x))
    };
    let k = 1.0 / half.sin() - 1.0;
    let (a0, e0, _, _) = arc(rho0);
    b.line(a0, MoveKind::CornerPoint);
    let (mut rho, mut arcs, mut deepest) = (rho0, 0, 0.0_f64);
    for next in corner_point_radii(rho0, alpha, f.r, f.phi, f.delta, MAX_CORNER_ARCS) {
        let (a, _, c, start) = arc(next);
        b.line(a, MoveKind::CornerPoint);
        let piece = sweep / CORNER_POINT_PIECES as f64;
        for j in 0..CORNER_POINT_PIECES {
            let seg = Segment::Arc { center: c, radius: next, start_angle: start + piece * j as f64, sweep: piece };
            b.push(seg, MoveKind::CornerPoint);
        }
        if next > f.delta * (1.0 + 1e-9) {
            b.line(a, MoveKind::CornerPoint);
        }
        deepest = deepest.max((rho - next) * k);
        rho = next;
        arcs += 1;
    }
    b.line(e0, MoveKind::CornerPoint);
    CornerPoint {
        vertex,
        angle_rad: alpha,
        arcs,
        last_radius_mm: rho,
        residual_mm: rho * k,
        max_radial_depth_mm: deepest,
        max_engagement_rad: 0.0,
        at: vertex,
    }
}
