//! The report of one measured tool path ([`engagement()`]): the evaluator's samples, the peak
//! and where, as `trochoplan engagement` prints them.

use crate::engagement::{EngagementProfile, EngagementSample};
use serde::Serialize;

/// One evaluated tool position.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SampleRow {
    pub s_mm: f64,
    pub x_mm: f64,
    pub y_mm: f64,
    pub engagement_deg: f64,
}

impl SampleRow {
    /// The row of one sample.
    pub fn of(s: &EngagementSample) -> SampleRow {
        SampleRow { s_mm: s.s_mm, x_mm: s.x_mm, y_mm: s.y_mm, engagement_deg: s.angle_rad.to_degrees() }
    }
}

/// The engagement along a path.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EngagementReport {
    pub tool_diameter_mm: f64,
    pub spacing_mm: f64,
    pub path_length_mm: f64,
    pub max_engagement_deg: f64,
    pub max_at: Option<SampleRow>,
    pub samples: Vec<SampleRow>,
}

/// The report of `profile`, measured with a tool of `tool_diameter_mm` at positions
/// `spacing_mm` apart.
pub fn engagement(profile: &EngagementProfile, tool_diameter_mm: f64, spacing_mm: f64) -> EngagementReport {
    EngagementReport {
        tool_diameter_mm,
        spacing_mm,
        path_length_mm: profile.path_length_mm,
        max_engagement_deg: profile.max_angle().to_degrees(),
        max_at: profile.max().as_ref().map(SampleRow::of),
        samples: profile.samples.iter().map(SampleRow::of).collect(),
    }
}
