//! Polygonal pocket cleared by contour-parallel rings (Wu et al. 2016 §4:
//! the plain contour-parallel path whose corners the strategies replace; docs/pockets.md).
//!
//! Conventions as in [`crate::corner`]: mm, counter-clockwise pocket boundary, tool-centre rings walked
//! counter-clockwise (pocket material on the left: climb milling with M3).
//!
//! Rings: ring `k` is the inward offset of the pocket boundary by `d_k = r + k·a_e`
//! (`k = 0, 1, …`) while that offset is non-empty. Offsetting is done by `cavalier_contours`
//! (J. Buckmccready, MIT/Apache-2.0) through [`crate::geom::offset`], here on a polygon that
//! [`Polygon::new`] has validated (≥ 3 finite vertices, no degenerate edges, simple, CCW) and
//! with a finite positive offset, so the library's preconditions hold (it can panic on
//! degenerate input; nothing is caught here). Its output keeps arcs exact as bulges; they are
//! converted to [`Segment::Arc`] (`sweep = 4·atan(bulge)`, cavalier_contours' bulge
//! definition). Note: an *inward* offset of a convex pocket corner stays sharp; arcs appear at
//! reflex (concave-of-pocket) vertices, with radius `d_k`.
//!
//! Measurement: each ring is measured by the independent evaluator ([`engagement_profile`])
//! over the pocket polygon as stock, after every ring machined before it. Rings are machined
//! from the innermost outward (the usual contour-parallel order starting in the middle), so
//! the innermost ring is a full slot (180°) and each further ring cuts a band of `a_e`.
//! Links between rings ([`Link`], one from the end of each ring to the entry of the next in
//! machining order) are kept apart from the rings: not in `path_length_mm` nor `time_s`
//! (they are in `link_length_mm`), and measured on their own (`Link::max_engagement_rad`).
//!
//! Link choice: a straight feed move (G1) when both
//! 1. the tool centre on the whole segment keeps at least the tool radius from every pocket
//!    edge — checked exactly, segment against edge ([`link_is_inside`]) — so the tool cannot
//!    gouge a wall, and
//! 2. the link cuts no more than a radial step of one step-over does: its engagement, measured
//!    by the evaluator over the material left by the rings and links before it, is at most
//!    `2·arccos(1 − a_e/r)` (capped at 180°) + [`LINK_ENGAGEMENT_SLACK_RAD`]. Derived: moving
//!    straight towards a band whose edge is a_e beyond the last ring, the tool ends with the
//!    band's chord in its front, at distance r − a_e from the centre, i.e. the arc
//!    2·arccos((r − a_e)/r). A link cannot be shown to run in cleared material only — it ends
//!    on the next ring, a_e outside the last one — so this bound is the honest criterion.
//!
//! Otherwise a retract to safe Z, a rapid and a plunge at the next entry
//! ([`LinkKind::Retract`]): e.g. a link that would slot across uncut material between two
//! lobes of a pocket, or one that would pass a reflex corner closer than r. The plunge lands
//! at the entry of the next ring, where the ring itself cuts next. The material a feed link
//! removes is not credited to the rings after it (their measurement is unchanged: conservative).
//! The first position of each ring (the entry, where the evaluator has no swept path behind
//! the tool yet) is reported apart from the ring's running maximum.
//!
//! Corner strategies (variable / isometric circles, [`crate::corner::strategy`]) are applied at every
//! convex line–line corner of every ring that has a previous (inner) ring, through a small
//! adapter ([`ring_with_corner_trochoids`]): the strategy's corner scenario assumes the current
//! ring is the walls offset by r and the previous ring the walls offset by r + a_e with a sharp
//! corner. For ring k (offset r + k·a_e) those walls are the polygon offset by k·a_e, whose
//! corner apex is `U0 − (r / sin α) b̂` (U0 the ring's corner vertex); the previous ring k + 1,
//! machined before it (inside-out order), is exactly the sharp r + a_e offset of those walls
//! near the corner. The strategy's path from its ring start to U0 is spliced into the ring in
//! place of the incoming line. Corners where the scenario's preconditions fail (walls too short
//! for the circles, the circles' entry not on the incoming line, arcs next to the corner) stay
//! plain and are counted in `RingPlan::plain_corners`, and so do corners whose circles would
//! take the tool centre closer than r to any pocket edge (a corner's circles only know its two
//! walls: in an L-shaped pocket the first circles of the corner opposite the reflex vertex grow
//! along the bisector into the notch). That check ([`piece_is_inside`]) is exact for lines and
//! treats every arc as its full circle (sufficient, so it may leave a corner plain that would
//! fit). The innermost ring (a full slot, no previous ring) stays plain. The engagement of the
//! result is measured by the evaluator like the plain rings.

use super::PocketSettings;
use super::adaptive::{
    AdaptiveOptions, AdaptivePart, Builder, CornerPoint, clear_regions, closest_on, fin_radius, inscribed,
};
use super::entry::{entry_at, helix_radius};
use super::path::PocketPath;
use super::route::Router;
use crate::corner::{Corner, CornerMethod, CornerScenario, CornerSettings, plan_corner, strategy::CornerPointArcs};
use crate::engagement::{EvaluatorOptions, engagement_profile, sample_owners};
use crate::error::{Error, Param};
use crate::geom::offset::Region;
use crate::geom::{P2, Polygon, Segment, p2};
use crate::toolpath::MoveKind;
use crate::toolpath::Toolpath;
use serde::{Deserialize, Serialize};

/// Upper bound on the number of offset levels (keeps run time bounded for tiny step-overs).
const MAX_LEVELS: usize = 10_000;
/// Offset loops shorter than this are dropped as numerical slivers (mm).
const MIN_RING_LENGTH: f64 = 1e-6;

/// Rounding allowance of the link engagement bound (rad): far above the evaluator's
/// refinement (~1e-8 rad), far below any engagement difference that matters (0.006°).
pub const LINK_ENGAGEMENT_SLACK_RAD: f64 = 1e-4;

/// Rounding allowance (mm) of "the strategy keeps the ring's offset from every wall": the
/// ring's own lines are at exactly that offset, up to the offsetting's rounding (~1e-12 mm).
const RING_SLACK_MM: f64 = 1e-6;

/// One closed tool-centre ring.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Ring {
    /// Offset level k (0 = the ring next to the wall).
    pub level: usize,
    /// Inward offset of the pocket boundary, d = r + k·a_e (mm).
    pub offset_mm: f64,
    /// Closed counter-clockwise loop of lines and arcs.
    pub segments: Vec<Segment>,
    /// Length (mm).
    pub length_mm: f64,
    /// Largest engagement after the entry position, measured by the evaluator (rad).
    pub max_engagement_rad: f64,
    /// Where it occurs (mm).
    pub max_engagement_at: P2,
    /// Engagement at the entry position (rad; the tool has no swept path behind it there).
    pub entry_engagement_rad: f64,
}

/// A pocket planned as contour-parallel rings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RingPlan {
    /// The pocket, the settings, the tool path and its measurement. [`plan_ring_pocket`]: every
    /// move at depth in machining order — entries' flat moves, the core cleared out of the
    /// helix bore, links and rings — the entry of each region of tool centres (helix, or ramp
    /// where no helix fits), the moves reached by retract, rapid and feed down (into material
    /// the path has cleared); links are every [`MoveKind::Link`] move at depth, the core's
    /// included. [`plan_rings`]: the rings and their feed links, a retract before each retract
    /// link, no entries (it plunges); its time counts the rings only.
    pub path: PocketPath,
    /// Corner strategy at the ring corners (plain, variable or isometric).
    pub method: CornerMethod,
    /// Rings in machining order (innermost first).
    pub rings: Vec<Ring>,
    /// Total ring length (mm), links excluded.
    pub path_length_mm: f64,
    /// Largest engagement (rad): [`plan_ring_pocket`] over every move at depth (the
    /// measurement's); [`plan_rings`] the largest running engagement over all rings, entries
    /// excluded.
    pub max_engagement_rad: f64,
    /// Ring corners where the strategy's circles were spliced in.
    pub trochoid_corners: usize,
    /// Convex ring corners left plain (strategy preconditions not met; innermost ring excluded).
    pub plain_corners: usize,
    /// `links[i]` joins the end of `rings[i]` to the entry of `rings[i + 1]`.
    pub links: Vec<Link>,
    /// [`plan_ring_pocket`]: the ring corners whose strategy ends with corner-point arcs
    /// (docs/corners.md), each with its arcs and the peak over them and their moves (the
    /// core's own corner points are not in this list; they are in the measurement's maxima).
    #[serde(default)]
    pub corner_points: Vec<CornerPoint>,
}

/// How the tool gets from one ring to the next.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LinkKind {
    /// A straight feed move at depth, inside the pocket offset by the tool radius.
    Feed,
    /// Retract to safe Z, rapid above the next entry, plunge (the straight move would come
    /// closer than the tool radius to a pocket edge).
    Retract,
}

/// A move from the end of one ring to the entry of the next.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Link {
    pub kind: LinkKind,
    pub from: P2,
    pub to: P2,
    /// XY length (mm).
    pub length_mm: f64,
    /// Largest engagement along a feed link over the material left before it, by the
    /// evaluator (rad); 0 for a retract link (not cut at depth).
    pub max_engagement_rad: f64,
}

/// Whether every point of the segment `a`–`b` is inside `polygon` at a distance of at least
/// `r` from its boundary (up to `1e-9` mm of rounding): `a` inside and the distance from the
/// segment to every edge ≥ r (a segment crossing an edge has distance 0 from it).
pub fn link_is_inside(polygon: &Polygon, a: P2, b: P2, r: f64) -> bool {
    let v = polygon.vertices();
    let n = v.len();
    polygon.contains(a) && (0..n).all(|i| crate::geom::segment_segment_distance(a, b, v[i], v[(i + 1) % n]) >= r - 1e-9)
}

/// Whether the tool centre on `piece` keeps at least `r` from every edge of `polygon` and stays
/// inside it: lines exactly ([`link_is_inside`]); an arc (centre c, radius ρ) by its full
/// circle, which keeps r from an edge iff the edge's distance from c is ≥ ρ + r (then the edge
/// is outside the disc and its distance from the circle is that minus ρ), with c inside.
pub fn piece_is_inside(polygon: &Polygon, piece: &[Segment], r: f64) -> bool {
    let v = polygon.vertices();
    let n = v.len();
    piece.iter().all(|seg| match *seg {
        Segment::Line { start, end } => link_is_inside(polygon, start, end, r),
        Segment::Arc { center, radius, .. } => {
            polygon.contains(center)
                && (0..n)
                    .all(|i| crate::geom::point_segment_distance(center, v[i], v[(i + 1) % n]) >= radius + r - 1e-9)
        }
        _ => false,
    })
}

/// The inward offset loops of a validated polygon at distance `d` (> 0, finite), as closed
/// counter-clockwise segment loops. Empty when the offset vanishes.
pub fn inward_offset(polygon: &Polygon, d: f64) -> Result<Vec<Vec<Segment>>, Error> {
    if !(d.is_finite() && d > 0.0) {
        return Err(Error::geometry("offset", d, "a finite number > 0 mm"));
    }
    // Counter-clockwise boundary: positive offset is to the left, i.e. inward.
    let mut loops = Vec::new();
    for off in Region::polygon(polygon.vertices()).offset_loops(d) {
        let segs = off.segments();
        let len: f64 = segs.iter().map(Segment::length).sum();
        if len > MIN_RING_LENGTH && segs.iter().all(|s| s.length().is_finite()) {
            loops.push(segs);
        }
    }
    Ok(loops)
}

/// An offset level: k, its offset d = r + k·a_e, its loops.
type Level = (usize, f64, Vec<Vec<Segment>>);
/// A loop whose segments carry what they do.
type Tagged = Vec<(Segment, MoveKind)>;

/// The offset levels of a pocket: level k is the inward offset by d = r + k·a_e, its loops,
/// while it is non-empty. Errors: the tool does not fit (`tool diameter`), too many levels.
fn ring_levels(polygon: &Polygon, r: f64, ae: f64) -> Result<Vec<Level>, Error> {
    let mut levels: Vec<Level> = Vec::new();
    for k in 0..MAX_LEVELS {
        let d = r + k as f64 * ae;
        let loops = inward_offset(polygon, d)?;
        if loops.is_empty() {
            break;
        }
        levels.push((k, d, loops));
    }
    if levels.is_empty() {
        return Err(Error::param(
            Param::ToolDiameter,
            2.0 * r,
            "small enough to fit in the pocket (the inward offset of the polygon by the tool radius is empty)",
        ));
    }
    if levels.len() == MAX_LEVELS {
        return Err(Error::param(Param::StepOver, ae, format!("large enough for at most {MAX_LEVELS} rings")));
    }
    Ok(levels)
}

/// Contour-parallel rings of a pocket with the corner strategy `method` (plain, variable or
/// isometric) at their corners, each ring measured by the independent evaluator. Errors:
/// settings out of range (named), `method` medial-axis (a whole-pocket strategy:
/// [`super::plan_perforative`]), a pocket too narrow for the tool (`tool diameter`).
pub fn plan_rings(polygon: &Polygon, settings: PocketSettings, method: CornerMethod) -> Result<RingPlan, Error> {
    settings.validate()?;
    if method == CornerMethod::MedialAxis {
        return Err(Error::param(Param::Method, method.name(), "plain, variable or isometric for pocket rings"));
    }
    let (r, ae) = (settings.tool_radius, settings.step_over);
    let levels = ring_levels(polygon, r, ae)?;
    let opts = EvaluatorOptions::new(r, settings.spacing);
    let mut rings = Vec::new();
    let mut cut: Vec<Segment> = Vec::new();
    let innermost = levels.len() - 1;
    let (mut trochoid_corners, mut plain_corners) = (0, 0);
    for (k, d, loops) in levels.into_iter().rev() {
        for plain in loops {
            let segs = if method == CornerMethod::Plain || k == innermost {
                plain
            } else {
                let (segs, done, skipped) = ring_with_corner_trochoids(polygon, &plain, settings, method)?;
                trochoid_corners += done;
                plain_corners += skipped;
                segs
            };
            let segs = start_mid_longest_line(segs);
            let prof = engagement_profile(polygon, &cut, &segs, &opts)?;
            let entry = prof.samples.first().map_or(0.0, |s| s.angle_rad);
            let best = prof.samples.iter().skip(1).fold(None, |b: Option<(f64, P2)>, s| match b {
                Some((a, _)) if a >= s.angle_rad => b,
                _ => Some((s.angle_rad, p2(s.x_mm, s.y_mm))),
            });
            let (max, at) = best.unwrap_or((entry, segs[0].start()));
            cut.extend(segs.iter().copied());
            rings.push(Ring {
                level: k,
                offset_mm: d,
                length_mm: prof.path_length_mm,
                segments: segs,
                max_engagement_rad: max,
                max_engagement_at: at,
                entry_engagement_rad: entry,
            });
        }
    }
    let link_bound =
        2.0 * (1.0 - ae / r).clamp(-1.0, 1.0).acos().min(0.5 * std::f64::consts::PI) + LINK_ENGAGEMENT_SLACK_RAD;
    let mut links = Vec::with_capacity(rings.len().saturating_sub(1));
    let mut before: Vec<Segment> = Vec::new();
    for pair in rings.windows(2) {
        before.extend(pair[0].segments.iter().copied());
        // Rings are never empty (inward_offset drops loops shorter than MIN_RING_LENGTH).
        let (Some(from), Some(to)) =
            (pair[0].segments.last().map(Segment::end), pair[1].segments.first().map(Segment::start))
        else {
            return Err(Error::geometry("ring", "no segments", "at least one segment"));
        };
        let length_mm = (to - from).norm();
        let link = if link_is_inside(polygon, from, to, r) {
            let max = if length_mm > 0.0 {
                engagement_profile(polygon, &before, &[Segment::Line { start: from, end: to }], &opts)?.max_angle()
            } else {
                0.0
            };
            if max <= link_bound {
                Link { kind: LinkKind::Feed, from, to, length_mm, max_engagement_rad: max }
            } else {
                Link { kind: LinkKind::Retract, from, to, length_mm, max_engagement_rad: 0.0 }
            }
        } else {
            Link { kind: LinkKind::Retract, from, to, length_mm, max_engagement_rad: 0.0 }
        };
        links.push(link);
        if link.kind == LinkKind::Feed && length_mm > 0.0 {
            before.push(Segment::Line { start: from, end: to });
        }
    }
    let len: f64 = rings.iter().map(|g| g.length_mm).sum();
    let max = rings.iter().map(|g| g.max_engagement_rad).fold(0.0, f64::max);
    let toolpath = rings_and_links(&rings, &links);
    let mut path = PocketPath::measured(polygon, settings, toolpath, 0.0, &[MoveKind::Link])?;
    path.time_s = len / settings.feed_mm_per_min * 60.0;
    Ok(RingPlan {
        path,
        method,
        rings,
        path_length_mm: len,
        max_engagement_rad: max,
        trochoid_corners,
        plain_corners,
        links,
        corner_points: Vec::new(),
    })
}

/// The rings and their feed links as one tool path in machining order ([`MoveKind::Ring`],
/// [`MoveKind::Link`]), a retract before the ring a retract link reaches (retract to safe Z,
/// rapid to the segment's start, plunge); no entries.
fn rings_and_links(rings: &[Ring], links: &[Link]) -> Toolpath {
    let mut segs = Vec::new();
    let mut kinds = Vec::new();
    let mut breaks = Vec::new();
    for (i, ring) in rings.iter().enumerate() {
        segs.extend(ring.segments.iter().copied());
        kinds.extend(ring.segments.iter().map(|_| MoveKind::Ring));
        match links.get(i) {
            Some(Link { kind: LinkKind::Feed, from, to, .. }) if (*to - *from).norm() > 0.0 => {
                segs.push(Segment::Line { start: *from, end: *to });
                kinds.push(MoveKind::Link);
            }
            Some(Link { kind: LinkKind::Retract, .. }) => breaks.push(segs.len()),
            _ => {}
        }
    }
    Toolpath::at_depth(&segs, &kinds, 0.0, Vec::new(), breaks)
}

/// The same closed loop, restarted at the midpoint of its longest line (split in two), so the
/// ring is entered on a straight part rather than at a corner (where the corner trochoids of
/// the last corner would run only after the tool had already turned there). Loops without a
/// line are returned as they are.
fn start_mid_longest_line(ring: Vec<Segment>) -> Vec<Segment> {
    let tagged = ring.into_iter().map(|s| (s, MoveKind::Ring)).collect();
    start_mid_longest_line_of(tagged).into_iter().map(|(s, _)| s).collect()
}

/// [`start_mid_longest_line`] of a loop whose segments carry what they do.
fn start_mid_longest_line_of(ring: Vec<(Segment, MoveKind)>) -> Vec<(Segment, MoveKind)> {
    let best = ring.iter().enumerate().filter(|(_, (s, _))| matches!(s, Segment::Line { .. })).fold(
        None,
        |b: Option<(usize, f64)>, (i, (s, _))| match b {
            Some((_, l)) if l >= s.length() => b,
            _ => Some((i, s.length())),
        },
    );
    let Some((i, _)) = best else { return ring };
    let (Segment::Line { start, end }, kind) = ring[i] else { return ring };
    let mid = (start + end) * 0.5;
    let mut out = Vec::with_capacity(ring.len() + 1);
    out.push((Segment::Line { start: mid, end }, kind));
    out.extend(ring[i + 1..].iter().copied());
    out.extend(ring[..i].iter().copied());
    out.push((Segment::Line { start, end: mid }, kind));
    out
}

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

/// A ring with its corners: tagged segments, (corners done, left plain), corner-point arcs.
type CorneredRing = (Tagged, (usize, usize), Vec<RingCorner>);

/// A ring corner whose strategy ends with corner-point arcs: the ring vertex U0, the corner's
/// interior angle (rad) and the arcs.
type RingCorner = (P2, f64, CornerPointArcs);

/// [`ring_with_corner_trochoids`] with each segment tagged: [`MoveKind::Corner`] for the
/// strategy's pieces (its circles and links), [`MoveKind::CornerPoint`] for its corner-point
/// arcs and their moves, [`MoveKind::Ring`] for the ring's own. With a corner tolerance δ
/// (docs/corners.md) each strategy ends with the corner-point arcs of
/// [`crate::corner::plan_corner`] instead of Wu et al.'s move into U0: its last arc ends on the
/// outgoing ring line, δ·cot α past U0 (tangent to it), and the next ring segment starts there
/// (for the last corner, the loop's first segment: the loop stays closed). Returns also the
/// corners that got arcs.
fn corner_ring(
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
struct Piece {
    path: Vec<Segment>,
    kinds: Vec<MoveKind>,
    /// Where it ends: U0, or on the outgoing line past it (after corner-point arcs).
    end: P2,
    /// Interior angle of the corner (rad) and its corner-point arcs, if any.
    angle: f64,
    arcs: Option<CornerPointArcs>,
}

impl Piece {
    /// Whether its first move (along the incoming line) can start at `from` instead: `from`
    /// on that line before the move's end.
    fn starts_after(&self, from: P2) -> bool {
        let Some(Segment::Line { start, end }) = self.path.first() else { return false };
        let len = (end - start).norm();
        let dir = (end - start) / len;
        crate::geom::cross(dir, from - start).abs() < 1e-6 && (from - start).dot(&dir) < len - 1e-9
    }
}

/// The strategy's path from `a` (start of the incoming ring line) to the corner vertex `u0`,
/// or with corner-point arcs to the end of the last arc on the outgoing line u0→`c` (between
/// them), or `None` where the corner scenario does not apply.
fn corner_piece(a: P2, u0: P2, c: P2, base: CornerSettings, method: CornerMethod) -> Option<Piece> {
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

/// The core of [`plan_ring_pocket`]: adaptive clearing of the regions (inward offsets of the
/// pocket), with its finishing pass (`--finish-stock`, which keeps the spiral's stadium off the
/// region's boundary) and corner points; its parts, moves, and the regions' boundary loops.
type Core = (Vec<AdaptivePart>, Builder, Vec<Vec<Segment>>);

fn adaptive_core(
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
    let (parts, b) = clear_regions(&regions, polygon, settings, options, phi, rho_fin, None)?;
    Ok((parts, b, outline.offset(d).iter().map(Region::segments).collect()))
}

/// The rings of [`plan_ring_pocket`] from the core outward, each with its tagged segments
/// (starting after its longest line, ending with it), the corners done and left plain, and
/// the helix centre of its region.
struct Candidate {
    level: usize,
    offset: f64,
    segments: Vec<(Segment, MoveKind)>,
    corners: (usize, usize),
    /// Its corners with corner-point arcs.
    points: Vec<RingCorner>,
    hub: P2,
    /// The loop inside it that was cut before it: the previous ring, or the boundary of the
    /// region the core cleared.
    inner: Vec<Segment>,
}

/// The same closed loop restarted on its longest line a'→e', at Q = e' − min(r, L/4)·u (u its
/// direction, L its length): it starts with Q→e' and ends with a'→Q, where the diagonal link
/// arrives short of the line's end (a plain ring's corner, or the entry of the first corner
/// circle).
fn start_on_longest_line(ring: Vec<(Segment, MoveKind)>, r: f64) -> Vec<(Segment, MoveKind)> {
    let best = ring
        .iter()
        .enumerate()
        .filter(|(_, (s, _))| matches!(s, Segment::Line { .. }))
        .max_by(|a, b| a.1.0.length().total_cmp(&b.1.0.length()));
    let Some((i, _)) = best else { return ring };
    let (Segment::Line { start, end }, kind) = ring[i] else { return ring };
    let len = (end - start).norm();
    let q = end - (end - start) / len * r.min(0.25 * len);
    let mut out = vec![(Segment::Line { start: q, end }, kind)];
    out.extend_from_slice(&ring[i + 1..]);
    out.extend_from_slice(&ring[..i]);
    out.push((Segment::Line { start, end: q }, kind));
    out
}

/// The point of a loop nearest `q`.
fn nearest_on(lp: &[Segment], q: P2) -> P2 {
    lp.iter().map(|s| closest_on(s, q).0).min_by(|a, b| (a - q).norm().total_cmp(&(b - q).norm())).unwrap_or(q)
}

/// The link from `from` (on or inside the loop `inner`, all cleared) into `ring`, which starts
/// at Q on its longest line a'→e' and ends with a'→Q ([`start_on_longest_line`]) (DERIVED):
/// the band of `ring` along that line is entered on the diagonal from A, the point of `inner`
/// a step a_e inside the line, a_e + r/2 along from a' (past the corner and its rounding), to
/// Q. Moving at an angle θ = atan(a_e/|A Q|) to a straight band of depth a_e, the tool's front
/// half reaches θ beyond the band's chord on the side it turns to: engagement φ* + θ at most
/// (φ* at θ = 0, the straight cut); the wedge it leaves is cut by a'→Q, thinner than the band.
/// The tool gets to A through the cleared inside of `inner` on the shortest path that keeps r
/// from the walls ([`Router`]). `None` where the ring does not start on a line or A is more
/// than a_e/10 from where it should be (the loops are not offsets of each other there), or no
/// path reaches A.
fn diagonal_link(
    router: &mut Router,
    r: f64,
    ae: f64,
    from: P2,
    inner: &[Segment],
    ring: &Candidate,
) -> Option<Vec<P2>> {
    if inner.is_empty() {
        return None;
    }
    let (Segment::Line { start: a1, end: q }, _) = *ring.segments.last()? else { return None };

    let u = (q - a1) / (q - a1).norm();
    let wanted = a1 + crate::geom::rot90(u) * ae + u * (ae + 0.5 * r);
    let a = nearest_on(inner, wanted);
    if (a - wanted).norm() > 0.1 * ae || (q - a).dot(&u) <= ae || router.route(a, q)?.len() != 2 {
        return None;
    }
    let mut path = router.route(from, a)?;
    path.push(q);
    Some(path)
}

/// The whole path of [`plan_ring_pocket`]: segments, kinds, retracts, and for each ring its
/// segment range and its link's (range, from, to).
struct Assembled {
    segments: Vec<Segment>,
    kinds: Vec<MoveKind>,
    retract_before: Vec<usize>,
    rings: Vec<(usize, usize)>,
    links: Vec<(usize, usize, P2, P2)>,
}

impl Assembled {
    fn line(&mut self, start: P2, end: P2) {
        if (end - start).norm() > 1e-9 {
            self.segments.push(Segment::Line { start, end });
            self.kinds.push(MoveKind::Link);
        }
    }
}

/// Core, then each ring reached by its [`diagonal_link`]; where there is none, on the shortest
/// path that keeps r from the walls ([`Router`]), else a retract (feeding down at the ring's
/// start, which the core and the rings inside it have cleared).
fn assemble(polygon: &Polygon, r: f64, ae: f64, mut a: Assembled, rings: &[Candidate]) -> Assembled {
    let mut router = Router::new(polygon, r);
    for ring in rings {
        let from = a.segments.last().map_or(ring.hub, Segment::end);
        let to = ring.segments[0].0.start();
        let first = a.segments.len();
        if let Some(pts) = diagonal_link(&mut router, r, ae, from, &ring.inner, ring).or_else(|| router.route(from, to))
        {
            for w in pts.windows(2) {
                a.line(w[0], w[1]);
            }
        } else {
            a.retract_before.push(a.segments.len());
        }
        a.links.push((first, a.segments.len(), from, to));
        let start = a.segments.len();
        for (s, k) in &ring.segments {
            a.segments.push(*s);
            a.kinds.push(*k);
        }
        a.rings.push((start, a.segments.len()));
    }
    a
}

/// Contour-parallel rings without a plunge or a full slot (docs/pockets.md):
/// 1. **Core.** The rings run from level k_c − 1 out to level 0 (the wall). The region inside
///    ring k_c is cleared by adaptive clearing ([`super::adaptive`]: helix at its point of
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
///    along the longest line through the point of largest clearance ([`super::entry`]) and
///    every level is a ring.
/// 2. **Links.** Into each ring on a [`diagonal_link`]: a chord through the cleared inside,
///    then a diagonal of angle atan(a_e/L) into the ring's band along its longest line (φ* + θ
///    at most); otherwise the shortest path on which the tool keeps r from the walls
///    ([`super::route`]), or a retract.
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
    let mut rings: Vec<Vec<CorneredRing>> = Vec::with_capacity(levels.len());
    for (_, d, loops) in &levels {
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
                match adaptive_core(polygon, &settings, &core_options, phi, &outline, levels[kc].1) {
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
            let m = super::perforative::plan_perforative(polygon, settings, &core_options)?;
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
    // The rings from level k_c − 1 out, each after the loop inside it (the nearest loop of the
    // level below, or of the core's regions).
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
    let a = assemble(polygon, r, ae, core, &candidates);
    let toolpath = Toolpath::at_depth(&a.segments, &a.kinds, -options.depth_mm, entries, a.retract_before.clone());
    let path = PocketPath::measured(polygon, settings, toolpath, options.depth_mm, &[MoveKind::Link])?;
    let profile = &path.measurement.profile;
    let owner = sample_owners(profile, &a.segments);
    let in_range = |lo: usize, hi: usize| {
        profile.samples.iter().zip(&owner).filter(move |(_, o)| (lo..hi).contains(*o)).map(|(s, _)| s)
    };
    let mut out_rings = Vec::with_capacity(candidates.len());
    let mut links = Vec::with_capacity(candidates.len());
    let mut corner_points = Vec::new();
    for (i, c) in candidates.iter().enumerate() {
        let (lo, hi) = a.rings[i];
        // each run of corner-point moves belongs to the corner whose vertex its last arc ends
        // next to (δ·cot α from it; the corners of a ring are at least a wall length apart)
        let mut j = lo;
        while j < hi {
            if a.kinds[j] != MoveKind::CornerPoint {
                j += 1;
                continue;
            }
            let run = j;
            while j < hi && a.kinds[j] == MoveKind::CornerPoint {
                j += 1;
            }
            let end = a.segments[j - 1].end();
            let Some((vertex, angle, arcs)) =
                c.points.iter().min_by(|p, q| (p.0 - end).norm().total_cmp(&(q.0 - end).norm()))
            else {
                continue;
            };
            let (max, at) = in_range(run, j)
                .fold((0.0, end), |b, s| if s.angle_rad > b.0 { (s.angle_rad, p2(s.x_mm, s.y_mm)) } else { b });
            corner_points.push(CornerPoint {
                vertex: *vertex,
                angle_rad: *angle,
                arcs: arcs.radii_mm.len(),
                last_radius_mm: arcs.radii_mm.last().copied().unwrap_or(0.0),
                residual_mm: arcs.residual_mm,
                max_radial_depth_mm: arcs.max_radial_depth_mm,
                max_engagement_rad: max,
                at,
            });
        }
        let segments: Vec<Segment> = a.segments[lo..hi].to_vec();
        let best = in_range(lo, hi).fold(None, |b: Option<(f64, P2)>, s| match b {
            Some((m, _)) if m >= s.angle_rad => b,
            _ => Some((s.angle_rad, p2(s.x_mm, s.y_mm))),
        });
        let (max, at) = best.unwrap_or((0.0, segments[0].start()));
        out_rings.push(Ring {
            level: c.level,
            offset_mm: c.offset,
            length_mm: segments.iter().map(Segment::length).sum(),
            segments,
            max_engagement_rad: max,
            max_engagement_at: at,
            entry_engagement_rad: in_range(lo, hi).next().map_or(0.0, |s| s.angle_rad),
        });
        let (l0, l1, from, to) = a.links[i];
        let kind = if l0 == l1 && a.retract_before.contains(&l1) { LinkKind::Retract } else { LinkKind::Feed };
        let length_mm = a.segments[l0..l1].iter().map(Segment::length).sum();
        let max_engagement_rad = in_range(l0, l1).map(|s| s.angle_rad).fold(0.0, f64::max);
        links.push(Link { kind, from, to, length_mm, max_engagement_rad });
    }
    // `links[i]` joins ring i to ring i + 1; the link from the core into the first ring is
    // part of the path, not of that list.
    if !links.is_empty() {
        links.remove(0);
    }
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
