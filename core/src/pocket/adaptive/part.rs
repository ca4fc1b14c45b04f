//! The per-part driver of adaptive clearing: for each region of tool centres the core radius T,
//! then entry and spiral or growth from outside, corner and cusp passes and the finishing
//! contour; the shortest plan over the core fractions wins (docs/adaptive-clearing.md).

use super::MAX_PASSES;
use super::PocketSettings;
use super::corners::{CORNER_CHORD_REACH, Corner, convex_corners, corner_point_arcs};
use super::loops::{Builder, inscribed, link, start_near};
use super::open::{MIN_CORE_SHARE, OpenPocket, Seed, grown_rings};
use super::options::{AdaptiveOptions, concave_step};
use super::plan::{AdaptivePart, CornerPasses};
use super::spiral::spiral_and_rings;
use crate::error::{Error, Param};
use crate::geom::offset::{Region, largest};
use crate::geom::{P2, Polygon, Segment, p2};
use crate::toolpath::{Entry, MoveKind};
use std::f64::consts::PI;

/// Fractions of the inscribed radius the core radius T starts from (the shortest plan wins).
pub(super) const CORE_FRACTIONS: [f64; 5] = [1.0, 0.85, 0.7, 0.55, 0.4];

/// Entry, spiral, rings, corner passes down to `rho_fin` and (with a finishing stock) the
/// finishing pass of each region of tool centres of `work`, one part each: for each, the
/// shortest plan over the core fractions. Each region grows from its seed: outside the stock
/// where it reaches past an open edge of `open`, else a helix. Also the core of the ring
/// methods ([`crate::pocket::rings::plan_ring_pocket`], closed: `open` = `None`).
pub(crate) fn clear_regions(
    regions: &[Region],
    work: &Polygon,
    settings: &PocketSettings,
    options: &AdaptiveOptions,
    phi: f64,
    rho_fin: f64,
    open: Option<&OpenPocket>,
) -> Result<(Vec<AdaptivePart>, Builder), Error> {
    let router = open.map_or_else(Default::default, |o| {
        crate::pocket::route::RouterCache::pinned(&o.far_polygon, settings.tool_radius)
    });
    let mut b = Builder { segments: Vec::new(), kinds: Vec::new(), radii: Vec::new(), router, retracts: Vec::new() };
    let mut parts = Vec::new();
    for region in regions {
        // The core radius trades ring length against corner caps: plan with T starting at each
        // fraction of the inscribed radius and keep the shortest path (geometry only).
        let (mut inscribed_radius, k0) = inscribed(region);
        let seed = open.and_then(|o| o.seed_of(region)).unwrap_or(Seed::Helix);
        if let Seed::Outside { closed, .. } = &seed {
            inscribed_radius = inscribed(closed).0;
        }
        let mut best: Option<(f64, Builder, AdaptivePart)> = None;
        let mut last_err = None;
        let (mut radii, mut router) = (Vec::new(), std::mem::take(&mut b.router));
        for fraction in CORE_FRACTIONS {
            let (taken, routes) = (std::mem::take(&mut radii), std::mem::take(&mut router));
            let mut bb =
                Builder { segments: Vec::new(), kinds: Vec::new(), radii: taken, router: routes, retracts: Vec::new() };
            let planned = plan_part(
                region,
                (inscribed_radius, k0),
                work,
                settings,
                options,
                phi,
                rho_fin,
                fraction,
                &mut bb,
                &seed,
            );
            (radii, router) = (std::mem::take(&mut bb.radii), std::mem::take(&mut bb.router));
            match planned {
                Ok(part) => {
                    let len: f64 = bb.segments.iter().map(Segment::length).sum();
                    if best.as_ref().is_none_or(|(l, _, _)| len < *l) {
                        best = Some((len, bb, part));
                    }
                }
                Err(e) => last_err = Some(e),
            }
        }
        let Some((_, bb, part)) = best else {
            return Err(last_err.unwrap_or_else(|| Error::param(Param::Polygon, "no plan", "a pocket the tool fits")));
        };
        let first = b.segments.len();
        b.router = router;
        b.retracts.extend(bb.retracts.iter().map(|i| i + first));
        b.segments.extend(bb.segments);
        b.kinds.extend(bb.kinds);
        parts.push(AdaptivePart { first_segment: first, end_segment: b.segments.len(), ..part });
    }
    Ok((parts, b))
}

/// Entry, spiral, rings and corners of one region of tool centres; the finishing pass.
#[allow(clippy::too_many_arguments)]
pub(super) fn plan_part(
    region: &Region,
    (inscribed, k0): (f64, P2),
    polygon: &Polygon,
    settings: &PocketSettings,
    options: &AdaptiveOptions,
    phi: f64,
    rho_fin: f64,
    fraction: f64,
    b: &mut Builder,
    seed: &Seed<'_>,
) -> Result<AdaptivePart, Error> {
    let r = settings.tool_radius;
    // The least core radius: the helix radius; from outside a share of the inscribed radius.
    let r_h = match seed {
        Seed::Helix => crate::pocket::entry::helix_radius(options, r, inscribed)?,
        _ => MIN_CORE_SHARE * inscribed,
    };
    // Open: T is chosen on the closed pocket's region (the open one reaches far past the edges).
    let t_region = match seed {
        Seed::Outside { closed, .. } => closed,
        _ => region,
    };
    let area = t_region.area();
    let corners_all = convex_corners(&region.segments());
    let t_corners = match seed {
        Seed::Outside { .. } => convex_corners(&t_region.segments()),
        _ => Vec::new(),
    };
    let t_corners = if t_corners.is_empty() { &corners_all } else { &t_corners };
    let sf = options.finish_stock_mm;
    let cusps_all = crate::pocket::cusp::cusps(&region.segments(), polygon, r + sf, sf);
    let open_cusps;
    let t_cusps = match seed {
        Seed::Outside { .. } => {
            open_cusps = crate::pocket::cusp::cusps(&t_region.segments(), polygon, r + sf, sf);
            &open_cusps
        }
        _ => &cusps_all,
    };
    // Core radius T: the largest (from 0.995 × the inscribed radius, −10 % a step) whose
    // opening of the region leaves only the corner caps.
    let mut t = 0.995 * fraction * inscribed;
    let core = loop {
        if t < r_h {
            t = r_h;
        }
        let ks = t_region.offset(t);
        if ks.len() == 1
            && let Some(opened) = largest(ks[0].offset(-t))
        {
            let caps: f64 = t_corners.iter().map(|c| c.cap_area(t)).sum::<f64>()
                + t_cusps.iter().map(|c| c.cap_area(t)).sum::<f64>();
            // the corner passes start from the opening's arc of radius T: it must fit the walls
            let fits = t_corners.iter().all(|c| t <= c.len_in.min(c.len_out) * (0.5 * c.alpha).tan() + 1e-9)
                && t_cusps.iter().all(|c| t <= c.rho_max + 1e-9);
            if (fits && area - opened.area() <= caps + 1e-3 * area) || t <= r_h {
                break ks.into_iter().next();
            }
        }
        if t <= r_h {
            break None;
        }
        t *= 0.9;
    };
    let Some(core) = core else {
        return Err(Error::param(
            Param::Polygon,
            "a region whose core does not hold the helix",
            "a pocket whose tool-centre region is one piece at least the helix radius wide",
        ));
    };
    let (entry, trimmed, rings) = match seed {
        Seed::Helix => {
            let (helix, trimmed, rings) =
                spiral_and_rings(b, region, &core, (inscribed, k0), polygon, (r, t, r_h, phi), options);
            (Entry::Helix(helix), trimmed, rings)
        }
        Seed::Outside { stock, grow, .. } => {
            let grow_core = largest(grow.offset(t)).ok_or_else(|| {
                Error::param(Param::OpenEdges, "no core beyond the open edges", "open edges at least D long")
            })?;
            let (rings, at) = grown_rings(b, polygon, r, &grow_core, t, phi, k0, stock)?;
            (Entry::Outside { at }, None, rings)
        }
    };
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
    // Cusps (a neck's mouth): arcs tangent to both walls from T down to ρ_fin, each back on
    // its chord (inside its own disc: cleared) and along the incoming wall into the next.
    for c in &cusps_all {
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
    // Finishing contour: the opening of the final wall offset with radius ρ_fin + s_f, and at
    // every convex corner arc of it the arcs into the corner point.
    let mut corner_points = Vec::new();
    if sf > 0.0 {
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
        for (i, seg) in fin_loop.iter().enumerate() {
            b.push(*seg, MoveKind::Finish);
            let is_line = |sg: &Segment| matches!(sg, Segment::Line { .. });
            if let Segment::Arc { center, radius, start_angle, sweep } = *seg
                && sweep > 1e-9
                && (radius - (rho_fin + sf)).abs() < 1e-6
                && (radius - options.corner_tolerance_mm) * (1.0 / (0.5 * sweep).cos() - 1.0)
                    > options.corner_tolerance_mm
                && is_line(&fin_loop[(i + n - 1) % n])
                && is_line(&fin_loop[(i + 1) % n])
            {
                let corner = Corner::of_arc(center, radius, start_angle, sweep);
                let (before, point) =
                    (b.segments.len(), corner_point_arcs(b, &corner, radius, r, phi, options.corner_tolerance_mm));
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
    }
    Ok(AdaptivePart { entry, first_segment: 0, end_segment: 0, core_radius_mm: t, rings, corners, corner_points })
}
