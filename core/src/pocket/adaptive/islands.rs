//! Adaptive clearing round islands (docs/pockets.md, "Islands"): each region of tool centres —
//! the boundary offset inward by r + s_f less the islands offset outward by r + s_f
//! ([`centre_regions`]), split into parts where a neck between island and wall (or between
//! two islands) is narrower than the tool — is one part with its own helix.
//!
//! **Rings (DERIVED like step 3 of [`super`]).** The core K = C ⊖ T of the part (its outer
//! loop offset inward by T, its holes outward by T) must be one piece: T starts at the helix
//! radius r_h and shrinks by 10 % until it is (at least [`MIN_CORE_SHARE`]·r). The rings are
//! ∂(G_j ⊕ T) with G₀ the disc about the helix centre k0 of radius r_h − T (ring 0 is then the
//! helix's circle) and G_j+1 = K ∩ (G_j ⊕ a), a the concave-cut step of radius T: geodesic
//! growth in K, which goes round the islands, never through them. Each ring lies within a of
//! the one before and its convex arcs have radius ≥ T, so a pass cuts at most the concave-cut
//! step of radius T: within the target φ. Where G_j holds an island's hole of K whole (the
//! growth closed round it), the ring also has the loop round that island r + s_f off it,
//! clockwise (climb); before that, the rings run along the island where G_j meets its hole.
//! Each ring is cut only where it adds to the one before ([`crate::pocket::runs`]).
//!
//! **Corners and finish.** The convex corners of the part's outer loop get the corner passes
//! of step 4, the outer loop the finishing contour of step 5; then each island the part goes
//! round gets its own finishing loop, r off it, clockwise, reached by a link straight onto it
//! (it cuts the finishing stock s_f: a straight cut of depth s_f).
//!
//! Every link — between runs, to the corners and the finishing loops — is routed round the
//! islands ([`crate::pocket::route::Router::with_islands`]); the plan's last check measures
//! every move against the walls and the islands ([`crate::pocket::guard`]).

use super::corners::{convex_corners, corner_passes, cusp_passes};
use super::finish::finishing_pass;
use super::loops::{Builder, closest_on, link, start_near};
use super::open::Seed;
use super::options::{AdaptiveOptions, concave_step};
use super::part::PartContext;
use super::plan::AdaptivePart;
use super::walk::reversed;
use super::{MAX_PASSES, PocketSettings};
use crate::error::{Error, Param, num};
use crate::geom::offset::{BoolOp, Region, largest};
use crate::geom::{P2, Polygon, Segment, p2};
use crate::pocket::islands::{HoledRegion, centre_regions, subtract};
use crate::pocket::route::RouterCache;
use crate::pocket::runs::{entered_runs, entry_gap};
use crate::toolpath::{Entry, Helix, MoveKind};
use std::f64::consts::{PI, TAU};

/// The least core radius round islands, as a share of the tool radius: a core that needs a
/// smaller one to stay one piece (a neck just wider than the tool) is refused by name.
pub(super) const MIN_CORE_SHARE: f64 = 0.2;

/// Bisection steps of the inscribed radius.
const INSCRIBED_STEPS: usize = 40;

/// The core of `region` at radius `t`: its outer loop offset inward by t less its holes offset
/// outward by t; the pieces of area above 1e-6 mm².
fn core_of(region: &HoledRegion, t: f64) -> Vec<HoledRegion> {
    let mut pieces: Vec<HoledRegion> =
        region.outer.offset(t).into_iter().map(|outer| HoledRegion { outer, holes: Vec::new() }).collect();
    for h in &region.holes {
        if let Some(zone) = largest(h.offset(-t)) {
            pieces = subtract(pieces, &zone);
        }
    }
    pieces.retain(|p| p.outer.area() > 1e-6);
    pieces
}

/// A point inside the region `piece`: the middle of its bounding box where that lies inside,
/// else its first vertex.
fn point_in(piece: &HoledRegion) -> P2 {
    let first = piece.outer.vertices().first().copied().unwrap_or_else(P2::zeros);
    match piece.outer.extents() {
        Some((a, b)) => {
            let m = p2(0.5 * (a.x + b.x), 0.5 * (a.y + b.y));
            if piece.contains(m) { m } else { first }
        }
        None => first,
    }
}

/// The radius of the largest circle in `region` (holes included) by bisection on its cores,
/// and a centre: a point of the last core that does not vanish.
fn inscribed(region: &HoledRegion) -> (f64, P2) {
    let ext = region.outer.extents();
    let (mut lo, mut hi) = (0.0, ext.map_or(1.0, |(a, b)| 0.5 * (b.x - a.x).min(b.y - a.y)) + 1e-9);
    let mut centre = point_in(region);
    for _ in 0..INSCRIBED_STEPS {
        let mid = 0.5 * (lo + hi);
        let core = core_of(region, mid);
        match core.iter().max_by(|a, b| a.outer.area().total_cmp(&b.outer.area())) {
            Some(piece) => {
                lo = mid;
                centre = point_in(piece);
            }
            None => hi = mid,
        }
    }
    (lo, centre)
}

/// Adaptive clearing of `work` round `islands` (both as planned: mirrored already for
/// conventional milling): one part per region of tool centres (module docs).
pub(super) fn clear_round_islands(
    work: &Polygon,
    islands: &[Polygon],
    settings: &PocketSettings,
    options: &AdaptiveOptions,
    (phi, rho_fin): (f64, f64),
) -> Result<(Vec<AdaptivePart>, Builder), Error> {
    let r = settings.tool_radius;
    let rs = r + options.finish_stock_mm;
    let regions = centre_regions(work, islands, rs);
    if regions.is_empty() {
        return Err(Error::param(
            Param::Islands,
            "no room for the tool between the islands and the walls",
            format!("room for a tool of D = {} mm plus the finishing stock beside the islands", num(2.0 * r)),
        ));
    }
    let mut b = Builder { router: RouterCache::with_islands(islands), ..Builder::default() };
    let mut parts = Vec::new();
    for region in &regions {
        // (a retract before each part but the first: [`super::plan::measure`])
        let first = b.segments.len();
        let part = clear_part(&mut b, region, (work, islands), settings, options, (phi, rho_fin))?;
        parts.push(AdaptivePart { first_segment: first, end_segment: b.segments.len(), ..part });
    }
    Ok((parts, b))
}

/// One part: helix, rings round the islands, corner passes, finishing contour and the
/// islands' finishing loops (module docs).
fn clear_part(
    b: &mut Builder,
    region: &HoledRegion,
    (work, islands): (&Polygon, &[Polygon]),
    settings: &PocketSettings,
    options: &AdaptiveOptions,
    (phi, rho_fin): (f64, f64),
) -> Result<AdaptivePart, Error> {
    let r = settings.tool_radius;
    let sf = options.finish_stock_mm;
    let (inscribed_radius, k0) = inscribed(region);
    let r_h = crate::pocket::entry::helix_radius(options, r, inscribed_radius)?;
    // T: the largest radius from r_h down whose core is one piece
    let mut t = r_h;
    let core = loop {
        let mut pieces = core_of(region, t);
        if pieces.len() == 1 {
            break pieces.remove(0);
        }
        t *= 0.9;
        if t < MIN_CORE_SHARE * r {
            return Err(Error::param(
                Param::Islands,
                format!("a neck round an island about {} mm wider than the tool", num(2.0 * t / 0.9)),
                format!(
                    "islands at least D + 2 × the finishing stock + {} mm from the walls and from each other, \
                     or near enough that the tool does not pass (each side then its own part)",
                    num(2.0 * MIN_CORE_SHARE * r)
                ),
            ));
        }
    };
    let step = concave_step(t, r, phi);
    let helix =
        Helix { center: k0, radius: r_h, start_angle: 0.0, sense: 1.0, ramp_rad: options.ramp_deg.to_radians() };
    b.push(helix.circle(), MoveKind::Entry);
    // the spiral out of the bore to the largest circle about k0 in the region, then that circle
    let walls: Vec<Segment> =
        region.outer.segments().into_iter().chain(region.holes.iter().flat_map(Region::segments)).collect();
    let clearance = walls.iter().map(|sg| (closest_on(sg, k0).0 - k0).norm()).fold(f64::INFINITY, f64::min);
    let q_f = (0.995 * clearance).max(r_h);
    let ring0 = spiral(b, k0, (r_h, q_f), (r, phi));
    // the rings: geodesic growth in the core from the spiral's disc
    let s0 = (q_f - t).max(1e-3);
    let grow = |g: &[HoledRegion]| -> Vec<HoledRegion> { grown_by(g, &core, step) };
    let ring_of = |g: &[HoledRegion]| -> Vec<Vec<Segment>> { ring_loops(g, t) };
    let first = largest(core.outer.boolean(&Region::disc(k0, s0), BoolOp::And).into_iter().map(Region::ccw).collect());
    let mut grown: Vec<HoledRegion> = first.map(|outer| HoledRegion { outer, holes: Vec::new() }).into_iter().collect();
    let mut area: f64 = grown.iter().map(net_area).sum();
    let least_growth = 1e-6 * core.outer.area().max(1.0);
    let mut rings: Vec<Vec<Vec<Segment>>> = vec![vec![ring0]];
    while rings.len() < MAX_PASSES {
        let next = grow(&grown);
        let next_area: f64 = next.iter().map(net_area).sum();
        if next_area <= area + least_growth {
            break;
        }
        (grown, area) = (next, next_area);
        rings.push(ring_of(&grown));
    }
    // the last ring: the opening of the region with radius T (the whole core grown; where the
    // growth reached it already, it adds nothing and has no runs)
    rings.push(ring_of(std::slice::from_ref(&core)));
    let gap = entry_gap(r, phi);
    let flat = |loops: &[Vec<Segment>]| loops.iter().flatten().copied().collect::<Vec<Segment>>();
    let (mut ring_runs, mut safe): (Vec<Vec<Vec<Segment>>>, Vec<Vec<Segment>>) = (Vec::new(), Vec::new());
    for pair in rings.windows(2) {
        let prev = flat(&pair[0]);
        let runs: Vec<Vec<Segment>> = pair[1].iter().flat_map(|lp| entered_runs(lp, &prev, gap)).collect();
        if !runs.is_empty() {
            ring_runs.push(runs);
            safe.push(prev);
        }
    }
    let count = ring_runs.len();
    crate::pocket::runs::cut_runs(b, work, r, ring_runs, (&safe, step, gap, sf));
    // corners and cusps of the outer loop, its finishing contour
    let seed = Seed::Helix;
    let p = PartContext {
        region: &region.outer,
        inscribed: inscribed_radius,
        k0,
        polygon: work,
        options,
        r,
        phi,
        rho_fin,
        seed: &seed,
        arms: false,
    };
    let corners_all = convex_corners(&region.outer.segments());
    let mut corners = corner_passes(b, &p, &corners_all, t, None);
    let cusps_all = crate::pocket::cusp::cusps(&region.outer.segments(), work, r + sf, sf);
    corners.extend(cusp_passes(b, &p, &cusps_all, t));
    let corner_points = if sf > 0.0 {
        let points = finishing_pass(b, &p)?;
        for island in islands {
            let inside = island.vertices().first().is_some_and(|&v| region.holes.iter().any(|h| h.contains(v)));
            if inside && let Some(lp) = largest(Region::polygon(island.vertices()).offset(-r)) {
                let around: Vec<Segment> = lp.segments().iter().rev().map(reversed).collect();
                let from = start_near(&around, b.at());
                if let Some(first) = from.first() {
                    link(b, work, r, first.start());
                    from.iter().for_each(|sg| b.push(*sg, MoveKind::Finish));
                }
            }
        }
        points
    } else {
        Vec::new()
    };
    Ok(AdaptivePart {
        entry: Entry::Helix(helix),
        first_segment: 0,
        end_segment: 0,
        core_radius_mm: t,
        rings: count,
        corners,
        corner_points,
    })
}

/// The spiral out of the helix bore about `k0` (the tool at radius `q0` on the +x side): half
/// turns, each from radius q_i on one side to q_i+1 on the other (centre offset (q_i − q_i+1)/2:
/// G1), q_i+1 = q_i + half the concave-cut step of q_i (a revolution steps the concave-cut step:
/// within φ), up to `q_f`; then once round the circle of radius `q_f`, which is returned (ring 0
/// of the rings).
fn spiral(b: &mut Builder, k0: P2, (q0, q_f): (f64, f64), (r, phi): (f64, f64)) -> Vec<Segment> {
    let (mut q, mut e) = (q0, p2(1.0, 0.0));
    let mut halves = 0;
    while q < q_f - 1e-9 && halves < MAX_PASSES {
        let next = (q + 0.5 * concave_step(q, r, phi)).min(q_f);
        let center = k0 + e * (0.5 * (q - next));
        b.push(
            Segment::Arc { center, radius: 0.5 * (q + next), start_angle: e.y.atan2(e.x), sweep: PI },
            MoveKind::Spiral,
        );
        (q, e, halves) = (next, -e, halves + 1);
    }
    let circle = Segment::Arc { center: k0, radius: q, start_angle: e.y.atan2(e.x), sweep: TAU };
    b.push(circle, MoveKind::Spiral);
    vec![circle]
}

/// The area of a region less its holes (mm²).
fn net_area(g: &HoledRegion) -> f64 {
    g.outer.area() - g.holes.iter().map(Region::area).sum::<f64>()
}

/// G_j+1 = K ∩ (G_j ⊕ a) for the sets `g` (each an outer loop with holes: islands' holes of the
/// core and what the growth has not reached round them), the core `core` and the step `a`:
/// each outer loop offset outward (the loops it closes round become holes), each hole inward,
/// pieces that overlap united (their holes kept), cut to the core's outer loop, less the
/// core's holes.
fn grown_by(g: &[HoledRegion], core: &HoledRegion, a: f64) -> Vec<HoledRegion> {
    let mut merged: Vec<HoledRegion> = Vec::new();
    for piece in g {
        let offs = piece.outer.offset(-a);
        let Some(k) = (0..offs.len()).max_by(|&x, &y| offs[x].area().total_cmp(&offs[y].area())) else { continue };
        let mut holes: Vec<Region> = offs.iter().enumerate().filter(|&(j, _)| j != k).map(|(_, o)| o.clone()).collect();
        holes.extend(piece.holes.iter().flat_map(|h| h.offset(a)));
        let mut grown = HoledRegion { outer: offs[k].clone(), holes };
        while let Some(i) = merged.iter().position(|q| !q.outer.boolean(&grown.outer, BoolOp::And).is_empty()) {
            let q = merged.swap_remove(i);
            let Some(u) = largest(q.outer.boolean(&grown.outer, BoolOp::Or)) else { break };
            let mut holes = q.holes;
            holes.append(&mut grown.holes);
            grown = HoledRegion { outer: u.ccw(), holes };
        }
        merged.push(grown);
    }
    let mut out: Vec<HoledRegion> = Vec::new();
    for m in merged {
        for outer in core.outer.boolean(&m.outer, BoolOp::And).into_iter().map(Region::ccw).filter(|p| p.area() > 1e-9)
        {
            let holes: Vec<Region> = m
                .holes
                .iter()
                .filter(|h| h.area() > 1e-9 && h.vertices().first().is_some_and(|&v| outer.contains(v)))
                .cloned()
                .collect();
            out.push(HoledRegion { outer, holes });
        }
    }
    core.holes.iter().fold(out, subtract)
}

/// The ring ∂(G ⊕ T) of the sets `g` as loops: each outer loop offset outward by T
/// (counter-clockwise; a loop it closes round, clockwise) and each hole offset inward by T
/// (clockwise: round the island or what is not cut yet, climb).
fn ring_loops(g: &[HoledRegion], t: f64) -> Vec<Vec<Segment>> {
    let cw = |o: &Region| -> Vec<Segment> { o.segments().iter().rev().map(reversed).collect() };
    let mut loops: Vec<Vec<Segment>> = Vec::new();
    for p in g {
        let offs = p.outer.offset(-t);
        let outer = (0..offs.len()).max_by(|&a, &b| offs[a].area().total_cmp(&offs[b].area()));
        for (k, o) in offs.iter().enumerate() {
            loops.push(if Some(k) == outer { o.segments() } else { cw(o) });
        }
        for h in &p.holes {
            loops.extend(h.offset(t).iter().map(cw));
        }
    }
    loops
}
