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
//! Measurement: each ring is measured by the independent evaluator ([`engagement_profile`](crate::engagement::engagement_profile))
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

mod corners;
mod links;
mod pocket;
mod report;
mod simple;

pub use corners::ring_with_corner_trochoids;
pub use pocket::plan_ring_pocket;
pub use simple::plan_rings;

use crate::corner::{CornerMethod, strategy::CornerPointArcs};
use crate::error::{Error, Param};
use crate::geom::offset::Region;
use crate::geom::{P2, Polygon, Segment};
use crate::pocket::CornerPoint;
use crate::pocket::path::PocketPath;
use crate::toolpath::MoveKind;
use serde::{Deserialize, Serialize};

/// Upper bound on the number of offset levels (keeps run time bounded for tiny step-overs).
pub(super) const MAX_LEVELS: usize = 10_000;

/// Offset loops shorter than this are dropped as numerical slivers (mm).
pub(super) const MIN_RING_LENGTH: f64 = 1e-6;

/// Rounding allowance of the link engagement bound (rad): far above the evaluator's
/// refinement (~1e-8 rad), far below any engagement difference that matters (0.006°).
pub const LINK_ENGAGEMENT_SLACK_RAD: f64 = 1e-4;

/// Rounding allowance (mm) of "the strategy keeps the ring's offset from every wall": the
/// ring's own lines are at exactly that offset, up to the offsetting's rounding (~1e-12 mm).
pub(super) const RING_SLACK_MM: f64 = 1e-6;

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
pub(super) type Level = (usize, f64, Vec<Vec<Segment>>);

/// A loop whose segments carry what they do.
pub(super) type Tagged = Vec<(Segment, MoveKind)>;

/// The offset levels of a pocket: level k is the inward offset by d = r + k·a_e, its loops,
/// while it is non-empty. Errors: the tool does not fit (`tool diameter`), too many levels.
pub(super) fn ring_levels(polygon: &Polygon, r: f64, ae: f64) -> Result<Vec<Level>, Error> {
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

/// A ring with its corners: tagged segments, (corners done, left plain), corner-point arcs.
pub(super) type CorneredRing = (Tagged, (usize, usize), Vec<RingCorner>);

/// A ring corner whose strategy ends with corner-point arcs: the ring vertex U0, the corner's
/// interior angle (rad) and the arcs.
pub(super) type RingCorner = (P2, f64, CornerPointArcs);
