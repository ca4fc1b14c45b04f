//! Pocket corners (issue #5): the engagement model, line–line corner geometry, corner trochoids
//! and an independent numeric engagement evaluator.
//!
//! Source: Wu S., Ma W., Li B., Wang C., "Trochoidal machining for the high-speed milling of
//! pockets", J. Mater. Process. Technol. 233 (2016) 29–43 (papers 000_*, 001_*, 004_*), in the
//! cleaned form of domain-spec §1 and §3. Conventions: mm, radians inside (degrees only at the
//! CLI), XY seen from +Z, counter-clockwise positive. Pockets are walked counter-clockwise with
//! the pocket on the left, circles are counter-clockwise (G3): climb milling with an M3 spindle.
//!
//! Modules:
//! - [`engagement`]: straight cut (§1.1) and two-circle model (eqs. 2–6, §1.2).
//! - [`evaluator`]: generic engagement of any path over any stock polygon (§1.3), independent
//!   of the analytic model; stock polygons and CSV tool paths.
//! - [`geometry`]: offset lines, bisector (eqs. 21–22), wall-tangent circles (§3.2).
//! - [`strategy`]: the corner scenario, the plain contour-parallel corner, the variable-circle
//!   (§3.3) and isometric-circle (§3.4) corner trochoids and the perforative medial-axis
//!   trochoids (§3.5).
//! - [`medial`]: medial axis of a polygon (segment Voronoi by `boostvoronoi`, §3.5).
//! - [`perforative`]: a whole pocket cleared by perforative trochoids along its medial axis
//!   (§3.5), measured with the evaluator.
//! - [`pocket`]: a polygonal pocket cleared by contour-parallel rings (`cavalier_contours`
//!   offsets), measured ring by ring with the evaluator (§3.1; issue #5 item 5).
//! - [`acceptance`]: the issue #5 acceptance table, measured with the evaluator.

pub mod acceptance;
pub mod engagement;
pub mod evaluator;
pub mod geometry;
pub mod medial;
pub mod perforative;
pub mod pocket;
pub mod strategy;

pub use acceptance::{AcceptanceRow, acceptance_row, acceptance_table};
pub use engagement::{Circle, MaxEngagement, Turn, TwoCircle, radial_depth_for_engagement, straight_engagement};
pub use evaluator::{
    EngagementProfile, EngagementSample, EvaluatorOptions, Polygon, engagement_profile, parse_points, polyline,
};
pub use geometry::{Corner, LineEq, bisector_point};
pub use medial::{AxisEdge, MedialAxis, medial_axis};
pub use perforative::{AxisCircle, KindMax, MoveKind, PerforativePlan, plan_perforative_pocket};
pub use pocket::{
    Link, LinkKind, PocketPlan, PocketSettings, Ring, inward_offset, link_is_inside, plan_pocket, pocket_polygon,
};
pub use strategy::{
    CornerCircle, CornerPlan, CornerScenario, CornerSettings, Method, RingStep, TargetSpec, first_circle_radius,
    plan_corner,
};
