//! The ring pocket (docs/pockets.md): an adaptive-clearing core out to ring k_c, then the rings
//! with their corner strategies from there out to the wall, measured in one profile.

use super::Level;
use super::corners::corner_ring;
use super::links::{Assembled, assemble, nearest_on, start_on_longest_line};
use super::report::ring_reports;
use super::{CorneredRing, RING_SLACK_MM, RingCorner, RingPlan, ring_levels};
use crate::corner::CornerMethod;
use crate::error::{Error, Param};
use crate::geom::offset::Region;
use crate::geom::{P2, Polygon, Segment};
use crate::pocket::PocketSettings;
use crate::pocket::adaptive::{AdaptiveOptions, AdaptivePart, Builder, clear_regions, fin_radius, inscribed};
use crate::pocket::entry::{entry_at, helix_radius};
use crate::pocket::path::PocketPath;
use crate::toolpath::Entry;
use crate::toolpath::{MoveKind, Toolpath};

/// The core of [`plan_ring_pocket`]: adaptive clearing of the regions (inward offsets of the
/// pocket), with its finishing pass (`--finish-stock`, which keeps the spiral's stadium off the
/// region's boundary) and corner points; its parts, moves, and the regions' boundary loops.
pub(super) type Core = (Vec<AdaptivePart>, Builder, Vec<Vec<Segment>>);

pub(super) fn adaptive_core(
    polygon: &Polygon,
    settings: &PocketSettings,
    options: &AdaptiveOptions,
    phi: f64,
    outline: &Region,
    d: f64,
) -> Result<Core, Error> {
    let (r, sf) = (settings.tool_radius, options.finish_stock_mm);
    // as adaptive clearing: the regions keep the finishing stock from the final wall, ring d
    let regions = outline.offset(d + sf);
    if regions.is_empty() {
        return Err(Error::param(Param::Polygon, "no region", "a pocket the tool fits"));
    }
    let rho_fin = if sf > 0.0 { fin_radius(sf, r, phi) } else { 0.1 * r };
    let (parts, b) = clear_regions(&regions, polygon, settings, options, phi, rho_fin, (None, false))?;
    Ok((parts, b, outline.offset(d).iter().map(Region::segments).collect()))
}

/// The rings of [`plan_ring_pocket`] from the core outward, each with its tagged segments
/// (starting after its longest line, ending with it), the corners done and left plain, and
/// the helix centre of its region.
pub(super) struct Candidate {
    pub(super) level: usize,
    pub(super) offset: f64,
    pub(super) segments: Vec<(Segment, MoveKind)>,
    pub(super) corners: (usize, usize),
    /// Its corners with corner-point arcs.
    pub(super) points: Vec<RingCorner>,
    pub(super) hub: P2,
    /// The loop inside it that was cut before it: the previous ring, or the boundary of the
    /// region the core cleared.
    pub(super) inner: Vec<Segment>,
}

/// Contour-parallel rings without a plunge or a full slot (docs/pockets.md):
/// 1. **Core.** The rings run from level k_c − 1 out to level 0 (the wall). The region inside
///    ring k_c is cleared by adaptive clearing ([`crate::pocket::adaptive`]: helix at its point of
///    largest clearance, spiral out of the bore, rings along its core, corner passes, the
///    finishing pass of `--finish-stock` along ring k_c and its corner points), every move
///    within the target: no full slot. k_c is
///    the deepest level whose region still holds a helix of 0.25·D, and not deeper than the
///    first level with a convex corner where the strategy does not apply (its walls too short
///    for the circles, or the circles too near a wall): those corners are the core's. Where
///    adaptive clearing cannot take that region (a neck its core does not pass), the next
///    level out, down to the wall ring, then the levels further in (where the region splits
///    into lobes, each its own part); rings between keep the corners left plain, counted. So every
///    ring of variable/isometric has its strategy at every convex corner. Plain rings take the
///    levels of variable circles and keep plain corners (the papers' baseline, above the
///    target on purpose). Where even level 0 does not hold the helix, the tool ramps down
///    along the longest line through the point of largest clearance ([`crate::pocket::entry`]) and
///    every level is a ring.
/// 2. **Links.** Into each ring on a [`diagonal_link`](super::links::diagonal_link): a chord through the cleared inside,
///    then a diagonal of angle atan(a_e/L) into the ring's band along its longest line (φ* + θ
///    at most); otherwise the shortest path on which the tool keeps r from the walls
///    ([`crate::pocket::route`]), or a retract.
///
/// Everything at depth is measured in one profile by the evaluator, the entries' bores counted
/// as cut; each ring's and link's maximum comes from that profile.
pub fn plan_ring_pocket(
    polygon: &Polygon,
    settings: PocketSettings,
    method: CornerMethod,
    options: &AdaptiveOptions,
) -> Result<RingPlan, Error> {
    settings.validate()?;
    let core_options = *options;
    core_options.validate(&settings)?;
    if method == CornerMethod::MedialAxis {
        return Err(Error::param(Param::Method, method.name(), "plain, variable or isometric for pocket rings"));
    }
    let (r, ae) = (settings.tool_radius, settings.step_over);
    let levels = ring_levels(polygon, r, ae)?;
    let phi = options.target_rad(&settings)?;
    let outline = Region::polygon(polygon.vertices());
    // Every ring with its corners; k_c from the helix and the corners.
    let delta = Some(core_options.corner_tolerance_mm);
    let rings = cornered_rings(polygon, settings, method, delta, &levels)?;
    let sf = core_options.finish_stock_mm;
    let holds_helix = |k: usize| {
        let regions = outline.offset(levels[k].1 + sf);
        !regions.is_empty() && regions.iter().all(|g| helix_radius(&core_options, r, inscribed(g).0).is_ok())
    };
    let deepest = (0..levels.len()).rev().find(|&k| holds_helix(k));
    // Plain rings take the levels of variable circles (the same core and rings, only the
    // corners differ), so the two compare like for like.
    let first_plain = if method == CornerMethod::Plain {
        let mut first = None;
        'levels: for (k, (_, d, loops)) in levels.iter().enumerate() {
            for plain in loops {
                if corner_ring(polygon, plain, settings, CornerMethod::Variable, delta, *d - RING_SLACK_MM)?.2 > 0 {
                    first = Some(k);
                    break 'levels;
                }
            }
        }
        first
    } else {
        rings.iter().position(|l| l.iter().any(|(_, (_, skipped), _)| *skipped > 0))
    };
    let ctx =
        RingContext { polygon, settings, method, options: &core_options, phi, outline: &outline, levels: &levels };
    let (core, entries, kc, inner_loops, hubs) = ring_core(&ctx, deepest, first_plain)?;
    let candidates = ring_candidates(&levels, &rings, kc, inner_loops, &hubs, r);
    let a = assemble(polygon, r, ae, core, &candidates);
    let toolpath = Toolpath::at_depth(&a.segments, &a.kinds, -options.depth_mm, entries, a.retract_before.clone());
    let path = PocketPath::measured(polygon, settings, toolpath, options.depth_mm)?;
    let (out_rings, links, corner_points) = ring_reports(&a, &candidates, &path);
    let path_length_mm: f64 = out_rings.iter().map(|g| g.length_mm).sum();
    Ok(RingPlan {
        max_engagement_rad: path.measurement.max_engagement_rad,
        path,
        method,
        rings: out_rings,
        path_length_mm,
        trochoid_corners: candidates.iter().map(|c| c.corners.0).sum(),
        plain_corners: candidates.iter().map(|c| c.corners.1).sum(),
        links,
        corner_points,
    })
}

/// Every ring of every level with its corner strategy (plain rings keep their corners): its
/// tagged segments, the corners done and left plain, and the corners with corner-point arcs.
fn cornered_rings(
    polygon: &Polygon,
    settings: PocketSettings,
    method: CornerMethod,
    delta: Option<f64>,
    levels: &[Level],
) -> Result<Vec<Vec<CorneredRing>>, Error> {
    let mut rings: Vec<Vec<CorneredRing>> = Vec::with_capacity(levels.len());
    for (_, d, loops) in levels {
        let mut level = Vec::with_capacity(loops.len());
        for plain in loops {
            level.push(if method == CornerMethod::Plain {
                (plain.iter().map(|s| (*s, MoveKind::Ring)).collect(), (0, 0), Vec::new())
            } else {
                let (segs, done, skipped, points) =
                    corner_ring(polygon, plain, settings, method, delta, *d - RING_SLACK_MM)?;
                (segs, (done, skipped), points)
            });
        }
        rings.push(level);
    }
    Ok(rings)
}

/// What choosing the core of a ring pocket needs.
struct RingContext<'a> {
    polygon: &'a Polygon,
    settings: PocketSettings,
    method: CornerMethod,
    options: &'a AdaptiveOptions,
    phi: f64,
    outline: &'a Region,
    levels: &'a [Level],
}

/// The core's moves and entries, k_c, the loops of the regions it cleared and their hubs.
type RingCore = (Assembled, Vec<Entry>, usize, Vec<Vec<Segment>>, Vec<P2>);

/// The core of the ring pocket (step 1 of [`plan_ring_pocket`]): adaptive clearing of the
/// region inside ring k_c, tried from the wanted level `min(deepest, first_plain)` out to the
/// wall, then inward; without a helix anywhere the medial-axis plan (variable, isometric) or
/// a ramp in each region with every level a ring (plain).
fn ring_core(ctx: &RingContext<'_>, deepest: Option<usize>, first_plain: Option<usize>) -> Result<RingCore, Error> {
    let RingContext { polygon, settings, method, options, phi, outline, levels } = *ctx;
    let (core_options, r) = (*options, settings.tool_radius);
    let mut core = Assembled {
        segments: Vec::new(),
        kinds: Vec::new(),
        retract_before: Vec::new(),
        rings: Vec::new(),
        links: Vec::new(),
    };
    let mut entries = Vec::new();
    let mut last_err = None;
    // (k_c, the regions' loops, their hubs)
    let (kc, inner_loops, hubs) = match deepest {
        Some(deepest) => {
            // From the wanted level outward to the wall, then inward (where a level splits
            // into lobes that adaptive clearing takes one by one): the first it can clear.
            let wanted = deepest.min(first_plain.unwrap_or(usize::MAX));
            let mut tries = (0..=wanted).rev().chain(wanted + 1..=deepest);
            loop {
                let Some(kc) = tries.next() else { break Err(()) };
                match adaptive_core(polygon, &settings, &core_options, phi, outline, levels[kc].1) {
                    Ok((parts, b, loops)) => {
                        for (i, part) in parts.iter().enumerate() {
                            if i > 0 {
                                core.retract_before.push(part.first_segment);
                            }
                            entries.push(part.entry);
                        }
                        core.retract_before.extend(b.retracts.iter().copied());
                        core.retract_before.sort_unstable();
                        core.segments = b.segments;
                        core.kinds = b.kinds;
                        let hubs = parts.iter().map(|p| p.entry.center()).collect::<Vec<_>>();
                        break Ok((kc, loops, hubs));
                    }
                    Err(e) => last_err = Some(e),
                }
            }
            .map_err(|()| {
                last_err.take().unwrap_or_else(|| Error::param(Param::Polygon, "no core", "a pocket the tool fits"))
            })?
        }
        None if method != CornerMethod::Plain => {
            // No helix anywhere, so no adaptive core, and the corner strategies do not fit these
            // narrow rings either, so that region is cleared another way: the
            // medial-axis clearing of the whole pocket (ramp entry, circles out of its slot,
            // corner-point arcs) is the core, and no ring is left outside it.
            let m = crate::pocket::perforative::plan_perforative(polygon, settings, &core_options)?;
            let path = m.path.toolpath;
            core.segments = path.segments();
            core.kinds = path.kinds();
            core.retract_before = path.retract_before;
            entries = path.entries;
            (0, Vec::new(), Vec::new())
        }
        None => {
            // No helix anywhere: a ramp in each region of tool centres, every level a ring.
            let mut hubs = Vec::new();
            for region in outline.offset(r) {
                if !core.segments.is_empty() {
                    core.retract_before.push(core.segments.len());
                }
                let (ins, k0) = inscribed(&region);
                let e = entry_at(polygon, r, options, k0, ins, 0.0)?;
                entries.push(e);
                core.segments.push(e.at_depth());
                core.kinds.push(MoveKind::Entry);
                hubs.push(k0);
            }
            (levels.len(), Vec::new(), hubs)
        }
    };
    Ok((core, entries, kc, inner_loops, hubs))
}

/// The rings from level k_c − 1 out (step 2 of [`plan_ring_pocket`]), each after the loop
/// inside it: the nearest loop of the level below, or of the core's regions.
fn ring_candidates(
    levels: &[Level],
    rings: &[Vec<CorneredRing>],
    kc: usize,
    inner_loops: Vec<Vec<Segment>>,
    hubs: &[P2],
    r: f64,
) -> Vec<Candidate> {
    let mut candidates: Vec<Candidate> = Vec::new();
    let mut inside: Vec<Vec<Segment>> = inner_loops;
    for k in (0..kc).rev() {
        let mut next = Vec::new();
        for (plain, (segs, corners, points)) in levels[k].2.iter().zip(&rings[k]) {
            let p = plain[0].start();
            let inner = inside
                .iter()
                .min_by(|a, b| (nearest_on(a, p) - p).norm().total_cmp(&(nearest_on(b, p) - p).norm()))
                .cloned()
                .unwrap_or_default();
            let hub = hubs.iter().copied().min_by(|a, b| (a - p).norm().total_cmp(&(b - p).norm())).unwrap_or(p);
            let segments = start_on_longest_line(segs.clone(), r);
            next.push(segments.iter().map(|(s, _)| *s).collect());
            candidates.push(Candidate {
                level: k,
                offset: levels[k].1,
                segments,
                corners: *corners,
                points: points.clone(),
                hub,
                inner,
            });
        }
        inside = next;
    }
    candidates
}
