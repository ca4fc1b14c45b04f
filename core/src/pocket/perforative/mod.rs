//! Perforative trochoids along the medial axis of a whole polygonal pocket
//! (docs/pockets.md). Wu et al. 2016 §4.2 only say the third
//! method "uses the method of Voronoi diagrams to calculate the medial axis of the cavity and
//! arrange the perforative trochoid according to the medial axis", with steps (1)–(4): reference
//! engagement, guiding curve, circles one by one under the engagement control, a linked list.
//! The algorithm below is ours (derived in docs/pockets.md), written so that every choice can be
//! checked by the independent evaluator.
//!
//! 1. **Axis.** The medial axis of the pocket ([`crate::geom::medial`], boostvoronoi; parabolic edges
//!    as points of the exact parabola). At an axis point q the clearance Rc(q) (distance to the
//!    nearest wall) is the radius of the largest circle the walls allow; the tool centre may be
//!    at q only where Rc(q) ≥ r. The axis is clipped to that part (bisection on Rc = r); a
//!    pocket whose axis falls apart there (a neck narrower than the tool) is cleared part by
//!    part, each part reached by retract, rapid and its own entry, and the axis length the tool cannot
//!    reach is reported (`unreachable_axis_mm`).
//! 2. **Start.** In each part, the tool enters at the axis point of largest clearance (a
//!    Voronoi vertex) on a helix of radius r_h ([`super::entry`], as adaptive clearing: no
//!    plunge), whose flat turn at depth is the first move and whose bore the evaluator counts
//!    as cut. It then clears that largest circle by concentric circles about the helix centre,
//!    joined by half-circles (G1: the half-circle from radius ρi at angle θ to ρi+1 at θ + π
//!    has centre `p + (ρi − ρi+1)/2·e(θ)` and radius `(ρi + ρi+1)/2`), starting from the helix
//!    circle ρ0 = r_h. Each radius is the largest whose two-circle engagement after the
//!    previous circle, and that of the half-circle to it, stay within the target (bisection as
//!    for variable circles), so the first circles grow out of the bore within the target. (From a plunge hole
//!    instead, the two-circle model gives δ = arccos(ρ/2r), β = π for a tool centre at distance ρ from the
//!    hole's centre: π/2 + arcsin(ρ/2r) ≥ 90° for any ρ, DERIVED; that is why the helix.)
//!    Where not even a helix of 0.25·D fits, the tool ramps down along the longest line
//!    through that point (a zig-zag [`Ramp`](crate::toolpath::Ramp)) and the chain starts from there.
//! 3. **Circles along the axis.** The axis is a tree; it is walked depth first from the start,
//!    one root-to-leaf guide at a time (children in counter-clockwise order). On a guide, the
//!    next circle is centred on the axis at arc length s with offset radius Rc(s) (allowance 0:
//!    it touches the walls), tool-centre radius ρ = Rc − r, and s is found by bisection exactly as
//!    for variable circles (Wu et al. 2016 eqs. 23–24) with the axis as guide: accept when the two-circle engagement after the previous
//!    circle is in (a*, a* + ε], or take the far end of the search if it is under a*. The search
//!    reaches at most 2·R_prev ahead (no overlap beyond), not past the next Voronoi vertex (so a
//!    circle that reaches it is the one touching three walls there) and not past the point where
//!    ρ drops below r_min (the variable circles' stop rule). Circles are counter-clockwise (G3, climb with M3), joined by
//!    the common tangent on their right (seen along the guide), so the path is G1 there; each
//!    circle runs a full turn from its entry and on to the exit tangent point (an extra
//!    `δ ∈ [−30°, 330°)`; a few degrees short of the full turn are left where the next link runs
//!    outside the circle anyway). Where one circle contains the other, or the tangent would come
//!    closer than r to a wall (near a reflex corner), the circles are joined instead by the G1
//!    half-circle of step 2 (generalised to offset centres, [`transition`](circles::transition)), whose engagement is
//!    then part of the bisection's metric; for circles that overlap without containment it
//!    lies inside both discs, i.e. in cut material. Disjoint circles whose tangent would touch
//!    a wall are joined along the axis (centre to centre).
//! 4. **Narrow parts.** Where ρ < r_min the tool moves along the axis: into a convex corner this
//!    ends at the tool corner point (Rc = r), reported as the corner's `tip` (see
//!    [`crate::corner::acceptance`] for why its engagement has its own limit); through a neck it is a
//!    `straight` move, after which a circle of radius r_min restarts the chain.
//! 5. **Back.** After a leaf the tool returns along the axis to the centre of the last circle the
//!    next guide shares with this one (cleared material), then moves out to that circle's exit
//!    point; the chain continues from that circle.
//!
//! The whole path is measured by the evaluator over the pocket polygon, the entries' bores
//! counted as cut; samples are classified by the move they belong to ([`MoveKind`]), and the
//! maximum is reported per class and over everything.

mod axis;
mod chain;
mod circles;
mod start;
#[cfg(test)]
mod tests;
mod tips;

use crate::corner::CornerSettings;
use crate::engagement::{EngagementProfile, EvaluatorOptions};
use crate::error::{Error, Param};
use crate::geom::medial::{MedialAxis, Walls, medial_axis};
use crate::geom::{Circle, P2, Polygon, Segment};
use crate::pocket::CornerPoint;
use crate::pocket::PocketSettings;
use crate::pocket::adaptive::AdaptiveOptions;
use crate::pocket::path::PocketPath;
use crate::toolpath::MoveKind;
use crate::toolpath::Toolpath;
use axis::AxisGraph;
use circles::{Builder, Planner};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Grid of the Voronoi input (mm).
const VORONOI_RESOLUTION_MM: f64 = 1e-4;
/// Spacing of the clearance samples along the axis before a crossing is refined (mm).
const CLEARANCE_STEP_MM: f64 = 0.25;
/// Bisection steps allowed for one circle (a cap: each step halves the bracket).
const MAX_BISECTION: usize = 60;
/// Circles allowed in one pocket.
const MAX_CIRCLES: usize = 20_000;
/// Points of the axis closer than this are one node (mm).
const NODE_TOL_MM: f64 = 1e-6;
/// A disc counts as cleared by a circle when it reaches at most this far beyond it (mm): a
/// sliver thinner than this (a fifth of the NC export's default tolerance) is not worth a
/// circle, e.g. the corners of a polygon with many short sides, 2.5e-4 mm beyond the inscribed
/// circle for 1000 sides of radius 50 mm.
const COVER_TOL_MM: f64 = 1e-3;
/// A circle ends this far short of a full turn at most when its exit precedes its entry (rad).
const SHORT_TURN_RAD: f64 = PI / 6.0;
/// Largest spacing of the evaluator's positions when it places the circles out of a ramp's
/// slot (mm): fine whatever the user's `--spacing` (at 1 mm a peak of 65° between positions
/// was missed where 0.25 mm read 53.4°).
const RAMP_SPIRAL_SPACING_MM: f64 = 0.1;
/// Corner-point arcs allowed into one tip (the bound on hostile input; 0.005 mm from a
/// 4.75 mm circle takes 11 at 90°, 31 at 30°).
const MAX_CORNER_ARCS: usize = 200;

/// One circle of the path.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AxisCircle {
    /// Tool-centre circle (centre on the axis, radius ρ = Rc − r).
    pub tool_circle: Circle,
    /// Offset radius R = ρ + r (the circle the tool clears).
    pub offset_radius: f64,
    /// Two-circle engagement after the previous circle (rad); `None` after a plunge or a
    /// straight move.
    pub predicted_max_rad: Option<f64>,
    /// Part of the start (concentric) clearing or on the axis.
    pub kind: MoveKind,
}

/// A pocket cleared by perforative trochoids along its medial axis.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PerforativePlan {
    /// The pocket, the settings, the path in machining order (a retract, rapid and new entry
    /// before every part but the first, which the program's first entry reaches), the entry of
    /// each part (helix, or ramp where no helix fits), and the measurement; links are the
    /// moves between cuts ([`MoveKind::Link`] and [`MoveKind::Return`] along the axis).
    pub path: PocketPath,
    /// Target engagement a* (rad) and the bisection band ε (rad).
    pub target_rad: f64,
    pub tolerance_rad: f64,
    pub axis: MedialAxis,
    pub circles: Vec<AxisCircle>,
    /// Parts of the axis reached separately (one entry each).
    pub parts: usize,
    /// Axis length where the tool does not fit (Rc < r), left uncut (mm).
    pub unreachable_axis_mm: f64,
    /// Each tip thinned by corner-point arcs ([`Planner::thin_tip`]): the corner of the
    /// tool-centre region (`vertex`), its angle, the arcs and the measured peak over their moves.
    pub corner_points: Vec<CornerPoint>,
    /// Largest engagement of the body (spiral, circles, links; rad): what the target bounds.
    pub body_max_rad: f64,
}

impl PerforativePlan {
    /// Maximum of one kind of move (0 if absent).
    pub fn max_of(&self, kind: MoveKind) -> f64 {
        self.path.max_of(kind)
    }
}

/// Plan the pocket `polygon` with perforative trochoids along its medial axis; the target is
/// the corner strategies' a* = a_str·(1 + t1), or `options.target_deg` when given. `options`
/// gives the entry (helix radius, ramp angle), the depth the entries descend to and the corner
/// tolerance of the corner-point arcs.
pub fn plan_perforative(
    polygon: &Polygon,
    settings: PocketSettings,
    options: &AdaptiveOptions,
) -> Result<PerforativePlan, Error> {
    settings.validate()?;
    // the entry's options (no finishing pass here)
    AdaptiveOptions { finish_stock_mm: 0.0, ..*options }.validate(&settings)?;
    let (r, ae) = (settings.tool_radius, settings.step_over);
    let mut cs = CornerSettings { feed_mm_per_min: settings.feed_mm_per_min, ..CornerSettings::new(r, ae)? };
    if options.target_deg.is_some() {
        // `--target-engagement` (validated above: from φ* to 90°) instead of a*
        cs.target = options.target_rad(&settings)?;
    }
    let axis = medial_axis(polygon, VORONOI_RESOLUTION_MM)?;
    let walls = Walls::new(polygon);
    let graph = AxisGraph::new(&walls, &axis, r);
    let parts = graph.parts(&walls);
    if parts.is_empty() {
        let widest = axis.edges.iter().map(|e| e.clearance_a.max(e.clearance_b)).fold(0.0, f64::max);
        return Err(Error::param(
            Param::ToolDiameter,
            2.0 * r,
            format!("at most {:.3} mm, the widest circle that fits in the pocket", 2.0 * widest),
        ));
    }
    let mut p = Planner {
        poly: polygon,
        walls: &walls,
        cs,
        corner_tolerance: options.corner_tolerance_mm,
        opts: EvaluatorOptions::new(r, settings.spacing.min(RAMP_SPIRAL_SPACING_MM)),
        b: Builder { segments: Vec::new(), kinds: Vec::new(), pos: graph.nodes[parts[0][0]] },
        circles: Vec::new(),
        corner_points: Vec::new(),
    };
    let mut retract_before = Vec::new();
    let mut entries = Vec::new();
    for part in &parts {
        retract_before.push(p.b.segments.len());
        entries.push(p.part(&graph, part[0], options)?);
    }
    retract_before.retain(|&i| i > 0); // the first part is reached by the program's first entry
    let Planner { b, circles, corner_points, .. } = p;
    let toolpath = Toolpath::at_depth(&b.segments, &b.kinds, -options.depth_mm, entries, retract_before);
    let path = PocketPath::measured(polygon, settings, toolpath, options.depth_mm)?;
    let body_max_rad = path.measurement.max_over(&[MoveKind::Spiral, MoveKind::Circle, MoveKind::Link]);
    let corner_points = measure_corner_points(&path.measurement.profile, &b.segments, corner_points);
    Ok(PerforativePlan {
        path,
        target_rad: cs.target,
        tolerance_rad: cs.tolerance,
        axis,
        circles,
        parts: parts.len(),
        unreachable_axis_mm: graph.unreachable_mm,
        corner_points,
        body_max_rad,
    })
}

/// Each corner point's peak and where: the largest sample over its moves (`range` of the
/// segments), measured by the evaluator.
fn measure_corner_points(
    profile: &EngagementProfile,
    segments: &[Segment],
    points: Vec<(CornerPoint, std::ops::Range<usize>)>,
) -> Vec<CornerPoint> {
    let starts = crate::geom::cumulative_lengths(segments);
    points
        .into_iter()
        .map(|(mut cp, range)| {
            let (s0, s1) = (starts[range.start], starts[range.end]);
            for smp in profile.samples.iter().filter(|m| m.s_mm > s0 + 1e-9 && m.s_mm <= s1 + 1e-9) {
                if smp.angle_rad > cp.max_engagement_rad {
                    cp.max_engagement_rad = smp.angle_rad;
                    cp.at = P2::new(smp.x_mm, smp.y_mm);
                }
            }
            cp
        })
        .collect()
}
