//! Engagement: how much of the tool's periphery is in material along a path.
//!
//! - [`model`]: the analytic straight cut and two-circle model (Wu et al. 2016 eqs. 2–6).
//! - [`evaluator`]: the independent numeric evaluator of any path over any stock polygon;
//!   CSV tool paths.
//! - [`nearby`]: the evaluator's spatial index of the swept path and the local stock.
//! - [`refine`]: the evaluator's positions chosen adaptively — dense where the engagement
//!   changes, coarse where it is steady — for measurements of whole tool paths.
//! - [`measure`](mod@measure): one [`Measurement`] of a [`crate::toolpath::Toolpath`] over a
//!   [`Stock`] — profile, per-kind maxima, peak, 95th percentile, length and air — for pockets
//!   and corners alike.

pub mod evaluator;
pub mod measure;
pub mod model;
pub mod nearby;
pub mod refine;
pub mod residual;

pub use evaluator::{
    EngagementProfile, EngagementSample, EvaluatorOptions, engagement_profile, engagement_profile_on, parse_points,
    polyline,
};
pub use measure::{
    AIR_ENGAGEMENT_RAD, KindMax, Measurement, Stock, maxima, measure, measured, move_peaks, peak_and_p95, sample_owners,
};
pub use model::{MaxEngagement, Turn, TwoCircle, radial_depth_for_engagement, straight_engagement};
pub use refine::{REFINE_TOLERANCE_RAD, refined_profile, sample_weights};
pub use residual::{Residual, ResidualOptions, residual_area};
