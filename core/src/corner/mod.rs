//! Pocket corners: the engagement model, line–line corner geometry, corner trochoids
//! and an independent numeric engagement evaluator.
//!
//! Source: Wu S., Ma W., Li B., Wang C., "Trochoidal machining for the high-speed milling of
//! pockets", J. Mater. Process. Technol. 233 (2016) 29–43, as derived in docs/corners.md and
//! docs/pockets.md. Conventions: mm, radians inside (degrees only at the
//! CLI), XY seen from +Z, counter-clockwise positive. Pockets are walked counter-clockwise with
//! the pocket on the left, circles are counter-clockwise (G3): climb milling with an M3 spindle.
//!
//! Entry point: [`evaluate`] — a [`CornerRequest`] in, a [`CornerReport`] out (the strategy's
//! plan and the plain ring, each with its [`crate::engagement::Measurement`], and their
//! acceptance row); used by the GUI and the CLI. Whole pockets are planned by the pocket
//! module, which comes after this one (docs/architecture.md, module order).
//!
//! Modules:
//! - [`method`]: the corner strategies and their names.
//! - [`request`]: the corner request, its settings and [`evaluate`].
//! - [`limits`]: tool diameter and step-over limits shared with the pocket planners.
//! - [`point`]: arcs into a convex corner point down to the corner tolerance.
//! - [`geometry`]: offset lines, bisector (eqs. 21–22), wall-tangent circles.
//! - [`strategy`]: the corner scenario, the plain contour-parallel corner, the variable-circle
//!   (eqs. 23–24) and isometric-circle (eq. 25) corner trochoids and the perforative
//!   medial-axis trochoids (Wu et al. §4.2).
//!
//! The engagement model and the evaluator are [`crate::engagement`] (re-exported here), the
//! medial axis is [`crate::geom::medial`].
//! - [`acceptance`]: the corner acceptance table of docs/corners.md, measured with the evaluator.

pub mod acceptance;
pub mod geometry;
pub mod limits;
pub mod method;
pub mod point;
pub mod request;
pub mod strategy;

pub use acceptance::{AcceptanceRow, acceptance_row, acceptance_table};
pub use geometry::{Corner, LineEq, bisector_point};
pub use method::CornerMethod;
pub use request::{CornerReport, CornerRequest, evaluate, finite};
pub use strategy::{CornerCircle, CornerPlan, CornerScenario, CornerSettings, first_circle_radius, plan_corner};
