//! Unit tests of each step of the medial-axis planner (docs/pockets.md): each checks a property
//! of the step or a number derived in the comment next to it. The read-back measurements are in
//! `tests/nc_pocket_rs274.rs` and `core/tests/corner_perforative.rs`.

use super::axis::AxisGraph;
use super::circles::{bisect, transition};
use super::{PerforativePlan, VORONOI_RESOLUTION_MM, plan_perforative};
use crate::engagement::straight_engagement;
use crate::geom::medial::{Walls, clearance, medial_axis};
use crate::geom::{P2, Polygon, p2};
use crate::pocket::AdaptiveOptions;
use crate::pocket::adaptive::tests::{AE, R, rectangle, settings};
use crate::toolpath::{Entry, HELIX_START_Z_MM, MoveKind};
use std::f64::consts::{PI, SQRT_2};
use std::sync::OnceLock;

/// The 60 × 40 rectangle's medial-axis plan (measured), planned once for all tests.
fn rectangle_plan() -> &'static PerforativePlan {
    static PLAN: OnceLock<PerforativePlan> = OnceLock::new();
    PLAN.get_or_init(|| plan_perforative(&rectangle(), settings(), &AdaptiveOptions::default()).unwrap())
}

/// Two rooms 30 × 30 joined by a neck 8 mm wide and 10 mm long: narrower than the tool.
fn dumbbell() -> Polygon {
    Polygon::new(vec![
        p2(0.0, 0.0),
        p2(30.0, 0.0),
        p2(30.0, 11.0),
        p2(40.0, 11.0),
        p2(40.0, 0.0),
        p2(70.0, 0.0),
        p2(70.0, 30.0),
        p2(40.0, 30.0),
        p2(40.0, 19.0),
        p2(30.0, 19.0),
        p2(30.0, 30.0),
        p2(0.0, 30.0),
    ])
    .unwrap()
}

// ---- step 1: the axis graph (axis.rs) ----

/// The walls of `poly` and its tool-feasible axis for r = 5.
fn axis_graph(poly: &Polygon) -> (Walls, AxisGraph) {
    let walls = Walls::new(poly);
    let axis = medial_axis(poly, VORONOI_RESOLUTION_MM).unwrap();
    let g = AxisGraph::new(&walls, &axis, R);
    (walls, g)
}

/// The tool-feasible axis of the 60 × 40 rectangle: the spine (length w − h = 20, clearance 20)
/// and four 45° branches; on a branch the clearance s mm from the corner is s/√2, so the tool
/// (r = 5) fits from s = r√2 to the spine's end at s = (h/2)√2: each branch keeps (h/2 − r)√2.
/// Total 20 + 4·15·√2 = 104.85 mm, one part.
#[test]
fn rectangle_axis_is_clipped_where_the_tool_fits() {
    let (walls, g) = axis_graph(&rectangle());
    let length: f64 = g.edges.iter().map(|(_, _, pts)| pts.windows(2).map(|w| (w[1] - w[0]).norm()).sum::<f64>()).sum();
    let derived = 20.0 + 4.0 * 15.0 * SQRT_2;
    assert!((length - derived).abs() < 1e-3, "{length} vs {derived}");
    // what the tool cannot reach: 4 × r√2 of branch next to the corners
    assert!((g.unreachable_mm - 4.0 * R * SQRT_2).abs() < 1e-3, "{}", g.unreachable_mm);
    assert_eq!(g.parts(&walls).len(), 1);
    // every node the tool may be at keeps r from the walls
    assert!(g.nodes.iter().all(|&n| walls.clearance(n) >= R - 1e-6));
}

/// A neck 8 mm wide is narrower than the tool (D = 10): the axis through it is unreachable and
/// falls into two parts, one per room.
#[test]
fn a_neck_narrower_than_the_tool_splits_the_axis() {
    let (walls, g) = axis_graph(&dumbbell());
    assert_eq!(g.parts(&walls).len(), 2);
    // at least the neck's own 10 mm of spine (clearance 4 < r) is unreachable
    assert!(g.unreachable_mm >= 10.0, "{}", g.unreachable_mm);
}

// ---- the circles' placement (circles.rs) ----

/// The variable-circle bisection: where the metric at the far end is within the target, the far
/// end; else a point whose metric lies in (target, target + ε]. For m(x) = x² on (0, 1] with
/// target 0.25 and ε = 0.01: x ∈ (0.5, √0.26 = 0.5099].
#[test]
fn bisection_lands_in_the_accept_band() {
    let (x, m) = bisect(0.0, 1.0, 0.25, 0.01, |x| x * x);
    assert!(m > 0.25 && m <= 0.26 && x > 0.5 && x <= 0.26_f64.sqrt(), "{x} {m}");
    let (x, m) = bisect(0.0, 0.4, 0.25, 0.01, |x| x * x);
    assert!((x - 0.4).abs() < 1e-15 && (m - 0.16).abs() < 1e-15);
}

/// The G1 half-circle between nested circles (c1 = 0, ρ1 = 5) and (c2 = (1, 0), ρ2 = 2), u = x̂:
/// it starts at A = c1 + ρ1·u = (5, 0), ends at B = c2 − ρ2·u = (−1, 0), so its centre is
/// (2, 0) and radius 3; at A it runs along rot90(u) = ŷ like circle 1, at B along −ŷ like
/// circle 2 (counter-clockwise at its leftmost point).
#[test]
fn transition_is_tangent_to_both_circles() {
    let (centre, radius, start) = transition(p2(0.0, 0.0), 5.0, p2(1.0, 0.0), 2.0);
    assert!((centre - p2(2.0, 0.0)).norm() < 1e-12 && (radius - 3.0).abs() < 1e-12, "{centre:?} {radius}");
    let e = |a: f64| p2(a.cos(), a.sin());
    let a_pt = centre + e(start) * radius;
    let b_pt = centre + e(start + PI) * radius;
    assert!((a_pt - p2(5.0, 0.0)).norm() < 1e-12 && (b_pt - p2(-1.0, 0.0)).norm() < 1e-12);
    // tangent directions of a counter-clockwise arc: rot90 of the radius direction
    let rot = |v: P2| p2(-v.y, v.x);
    assert!((rot(e(start)) - p2(0.0, 1.0)).norm() < 1e-12);
    assert!((rot(e(start + PI)) - p2(0.0, -1.0)).norm() < 1e-12);
}

// ---- step 2: entry and the circles out of the bore (start.rs) ----

/// The helix sits on the spine (the axis points of largest clearance, y = 20), radius
/// 0.375·D = 3.75; 2π·3.75·tan 5° = 2.0614 mm a turn, so ⌈6.5/2.0614⌉ = 4 turns to 6 mm. The
/// circles out of its bore are concentric about it, each within the target by the two-circle
/// model (predicted ≤ a* + ε), growing.
#[test]
fn helix_and_concentric_circles_out_of_its_bore() {
    let plan = rectangle_plan();
    let Entry::Helix(h) = plan.path.toolpath.entries[0] else { panic!("{:?}", plan.path.toolpath.entries) };
    assert!((h.radius - 3.75).abs() < 1e-12 && (h.center.y - 20.0).abs() < 1e-6, "{h:?}");
    assert_eq!(h.turns(HELIX_START_Z_MM + 6.0), 4);
    let spiral: Vec<_> = plan.circles.iter().filter(|c| c.kind == MoveKind::Spiral).collect();
    assert!(spiral.len() >= 2);
    for w in spiral.windows(2) {
        assert!(w[1].tool_circle.radius > w[0].tool_circle.radius);
    }
    for c in &spiral {
        assert!((c.tool_circle.center - h.center).norm() < 1e-9);
        assert!(c.predicted_max_rad.is_some_and(|p| p <= plan.target_rad + plan.tolerance_rad + 1e-12), "{c:?}");
    }
}

// ---- step 3: circles along the axis (chain.rs) ----

/// Every circle along the axis is centred on the axis and touches the walls: its offset radius
/// is the clearance of its centre and its tool-centre radius that less r; each is placed within
/// the target by the two-circle model. The target is a* = a_str·(1 + t1) =
/// arccos(1 − 1.527/5)·1.15 = 52.91°.
#[test]
fn circles_along_the_axis_touch_the_walls() {
    let plan = rectangle_plan();
    let poly = rectangle();
    let a_star = straight_engagement(AE, R).unwrap() * 1.15;
    assert!((plan.target_rad - a_star).abs() < 1e-12 && (a_star.to_degrees() - 52.91).abs() < 0.005);
    let along: Vec<_> = plan.circles.iter().filter(|c| c.kind == MoveKind::Circle).collect();
    assert!(along.len() > 10, "{}", along.len());
    for c in along {
        let centre = c.tool_circle.center;
        assert!((c.offset_radius - clearance(&poly, centre)).abs() < 1e-6, "{c:?}");
        assert!((c.tool_circle.radius - (c.offset_radius - R)).abs() < 1e-9);
        if let Some(p) = c.predicted_max_rad {
            assert!(p <= plan.target_rad + plan.tolerance_rad + 1e-12, "{c:?}");
        }
    }
}

// ---- step 4: tips and corner points (tips.rs) ----

/// The four 90° tips end in corner-point arcs down to δ = 0.005 mm: the residual on the
/// bisector is δ(1/sin 45° − 1) = 0.00207 mm, the corner U0 of the tool-centre region is r
/// from both walls, and the arcs' measured peak stays within a* + 1°.
#[test]
fn tips_end_in_corner_points_within_the_tolerance() {
    let plan = rectangle_plan();
    let delta = AdaptiveOptions::default().corner_tolerance_mm;
    assert_eq!(plan.corner_points.len(), 4);
    for c in &plan.corner_points {
        assert!((c.angle_rad - PI / 2.0).abs() < 1e-6, "{c:?}");
        assert!((c.last_radius_mm - delta).abs() < 1e-12);
        assert!((c.residual_mm - delta * (SQRT_2 - 1.0)).abs() < 1e-9);
        assert!((clearance(&rectangle(), c.vertex) - R).abs() < 1e-6, "{c:?}");
        assert!(c.max_engagement_rad <= plan.target_rad + 1f64.to_radians(), "{c:?}");
    }
    assert!(plan.path.measurement.max_engagement_rad <= plan.target_rad + 1f64.to_radians());
}

// ---- step 5: the way back (chain.rs) and the parts (mod.rs) ----

/// Returns along the axis run through cleared material: every return move keeps r from the
/// walls and reads no engagement.
#[test]
fn returns_run_along_the_axis_through_cleared_material() {
    let plan = rectangle_plan();
    let poly = rectangle();
    let moves = &plan.path.toolpath.moves;
    let returns: Vec<_> = moves.iter().filter(|m| m.kind == MoveKind::Return).collect();
    assert!(!returns.is_empty());
    for m in returns {
        for t in [0.0, 0.5, 1.0] {
            assert!(clearance(&poly, m.segment.point(t)) >= R - 1e-6, "{m:?}");
        }
    }
    assert!(plan.max_of(MoveKind::Return) < 1f64.to_radians());
}
