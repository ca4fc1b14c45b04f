//! Analysis of a slot path in the steady state: chip thickness and engagement per tooth,
//! cycle metrics, wall waviness and the two-circle step limits (the engagement-limited step of
//! a job's own path plans the job again, so it lives in the `plan` module).

pub mod chip;
pub mod edge;
pub mod force;
pub mod imprint;
pub mod step;
pub mod waviness;

pub use chip::{ARC_SAMPLE_STEP_RAD, ChipTiming, EngagedArc, H_CUT_MM, ToothSample, chip_timing, tooth_series};
pub use edge::PreviousEdge;
pub use force::{Cutter, ForceSample, ForceSeries, ForceSummary, cycle_forces};
pub use imprint::{ImprintProfile, imprint_density};
pub use waviness::{Wall, WallProfile, wall_profile};
