//! Steps 5 and 6 of adaptive clearing (docs/adaptive-clearing.md): the finishing contour — the
//! opening of the final wall offset with radius ρ_fin + s_f, entered on a quarter-circle lead-in —
//! and at each of its convex corner arcs the arcs into the corner point (a corner between two
//! lines, or between a line or arc and an arc about a reflex vertex of the pocket).

use super::corners::{Corner, corner_point_arcs};
use super::loops::{Builder, link, start_near};
use super::part::PartContext;
use crate::error::{Error, Param};
use crate::geom::offset::largest;
use crate::geom::{P2, Segment, p2};
use crate::pocket::CornerPoint;
use crate::toolpath::MoveKind;
use std::f64::consts::PI;

/// The finishing pass of a part (with a finishing stock s_f > 0) and its corner points.
pub(super) fn finishing_pass(b: &mut Builder, p: &PartContext<'_>) -> Result<Vec<CornerPoint>, Error> {
    let (region, polygon, options, r, phi, rho_fin) = (p.region, p.polygon, p.options, p.r, p.phi, p.rho_fin);
    let sf = options.finish_stock_mm;
    // Finishing contour: the opening of the final wall offset with radius ρ_fin + s_f, and at
    // every convex corner arc of it the arcs into the corner point.
    let mut corner_points = Vec::new();
    let inner = largest(region.offset(rho_fin)).ok_or_else(|| {
        Error::param(Param::Polygon, "no finishing contour", "a pocket wider than the tool plus the stock")
    })?;
    let fin = largest(inner.offset(-(rho_fin + sf)))
        .ok_or_else(|| Error::param(Param::Polygon, "no finishing contour", "a pocket wider than the tool"))?;
    // Start on the straight wall nearest the tool (at its point nearest the tool, at least
    // ρ_l from the wall's start; the longest wall's middle where no wall is 2ρ_l long),
    // entered on a quarter circle of radius ρ_l = max(s_f, r/2) tangent to it (the stock
    // grows from 0 to s_f under a convex arc); the lead-in starts ρ_l from the wall, in
    // cleared material.
    let loop_segs = fin.segments();
    let lead = sf.max(0.5 * r);
    let here = b.at();
    let lines: Vec<(P2, P2)> = loop_segs
        .iter()
        .filter_map(|sg| match *sg {
            Segment::Line { start, end } => Some((start, end)),
            _ => None,
        })
        .collect();
    // (a lead-in whose quarter circle would come within r of another wall is not taken;
    // where none is clear, the link goes straight to the wall point)
    let lead_in = |(mid, dir): (P2, P2)| {
        let (center, start_angle) = (mid + crate::geom::rot90(dir) * lead, (-dir.y).atan2(-dir.x));
        (mid, Segment::Arc { center, radius: lead, start_angle, sweep: 0.5 * PI })
    };
    let clear = |(_, arc): &(P2, Segment)| crate::pocket::guard::keeps_off_walls(polygon, arc, r);
    let nearest = lines
        .iter()
        .filter(|(a, c)| (c - a).norm() >= 2.0 * lead)
        .map(|&(a, c)| {
            let (len, dir) = ((c - a).norm(), (c - a).normalize());
            lead_in((a + dir * (here - a).dot(&dir).clamp(lead, len - 1e-3), dir))
        })
        .filter(clear)
        .min_by(|x, y| (x.0 - here).norm().total_cmp(&(y.0 - here).norm()));
    let longest = lead_in(
        lines
            .iter()
            .max_by(|a, c| (a.1 - a.0).norm().total_cmp(&(c.1 - c.0).norm()))
            .map_or((loop_segs[0].start(), p2(1.0, 0.0)), |(a, c)| ((a + c) * 0.5, (c - a).normalize())),
    );
    let (mid, arc) = nearest.unwrap_or(longest);
    let arc = Some(arc).filter(|a| clear(&(mid, *a)));
    link(b, polygon, r, arc.map_or(mid, |a| a.start()));
    arc.into_iter().for_each(|a| b.push(a, MoveKind::Finish));
    let fin_loop = start_near(&loop_segs, mid);
    let n = fin_loop.len();
    // a side of a corner: a line, or an arc turning the other way (the offset of a reflex vertex
    // of the pocket, r about it), which turns away from its tangent at the corner, so that no
    // tool position between the tangents comes nearer than r to that vertex. The tool-centre
    // region ends in such corners where it runs between a wall and a reflex vertex (the mouth
    // of an arm narrower than the tool plus the stock): the rounded corner leaves its tip uncut.
    // There the corner's walls are the tangents at the sides' points nearest the region's tip
    // ([`Corner::of_sides`]) and the arcs end at radius s_f about the tip: the pass then comes
    // s_f from every point of the region, as along its walls.
    let side = |sg: &Segment| match *sg {
        Segment::Line { .. } => true,
        Segment::Arc { sweep, .. } => sweep < 0.0,
        Segment::Trochoid { .. } => false,
    };
    for (i, seg) in fin_loop.iter().enumerate() {
        b.push(*seg, MoveKind::Finish);
        if let Segment::Arc { center, radius, start_angle, sweep } = *seg
            && sweep > 1e-9
            && (radius - (rho_fin + sf)).abs() < 1e-6
            && (radius - options.corner_tolerance_mm) * (1.0 / (0.5 * sweep).cos() - 1.0) > options.corner_tolerance_mm
            && side(&fin_loop[(i + n - 1) % n])
            && side(&fin_loop[(i + 1) % n])
        {
            let (prev, next) = (&fin_loop[(i + n - 1) % n], &fin_loop[(i + 1) % n]);
            let lines = matches!((prev, next), (Segment::Line { .. }, Segment::Line { .. }));
            let corner = Corner::of_sides(prev, seg, next, sf)
                .unwrap_or_else(|| Corner::of_arc(center, radius, start_angle, sweep));
            // with an arc side, down to the arc of radius s_f about the region's tip
            let least = if lines { options.corner_tolerance_mm } else { sf.max(options.corner_tolerance_mm) };
            let (before, point) = (b.segments.len(), corner_point_arcs(b, &corner, radius, r, phi, least));
            // back to the finishing arc's end (where a side is an arc, the corner's wall is not
            // that side's tangent at the arc's end)
            b.line(seg.end(), MoveKind::CornerPoint);
            // not where they would come within r of a wall whose offset the loop has lost
            // (a short edge between the corner's walls, farther than r + s_f from the region)
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
