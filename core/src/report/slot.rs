//! The report of a narrow pocket cleared as a trochoidal slot ([`crate::pocket::slot`]).

use super::pocket::{kind_rows, polygon_rows};
use super::{CornerPointRow, KindRow, RampRow, entry_rows, xy};
use crate::geom::Segment;
use crate::pocket::{Pace, PocketStrategy, SlotPlan};
use crate::toolpath::MoveKind;
use serde::Serialize;

/// A narrow pocket cleared as one trochoidal slot along its medial axis.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SlotReport {
    pub method: &'static str,
    pub direction: &'static str,
    pub tool_diameter_mm: f64,
    pub step_over_mm: f64,
    pub feed_mm_per_min: f64,
    /// Target engagement (`--target-engagement`, default as adaptive clearing's), and the angle
    /// the loops were planned to by the two-circle model so that the measured peak keeps it.
    pub target_deg: f64,
    pub planned_deg: f64,
    pub polygon: Vec<[f64; 2]>,
    /// The zig-zag ramp down on the centre line, its legs, the pass depth asked for
    /// (`--ramp-pass-depth`) and the deepest full-width pass it cuts (mm).
    pub ramps: Vec<RampRow>,
    pub ramp_pass_limit_mm: f64,
    pub ramp_full_width_depth_mm: f64,
    /// The centre line (polylines) and the loops cut along it, the largest loop radius (mm).
    pub axis: Vec<Vec<[f64; 2]>>,
    pub loops: usize,
    pub loop_radius_mm: f64,
    pub corner_points: Vec<CornerPointRow>,
    pub corner_radius_left_mm: f64,
    pub finish_stock_mm: f64,
    /// Maximum over every move at depth (the ramp's flat pass, the stadiums widening it, the
    /// loops, their links, the runs back, the finishing contour, the corner points), measured
    /// by the evaluator with the ramp's bore as cut; and the 95th percentile.
    pub max_engagement_deg: f64,
    pub p95_engagement_deg: f64,
    pub by_kind: Vec<KindRow>,
    pub length_at_depth_mm: f64,
    pub link_length_mm: f64,
    /// Moves at depth with engagement below 1°.
    pub air_length_mm: f64,
    pub entry_length_mm: f64,
    /// The ramp and moves at depth at the feed.
    pub time_s: f64,
    /// Rapids at depth through cleared stock and the feed of every move (see the other reports).
    pub pace: Option<Pace>,
    pub segments: Vec<Segment>,
    pub kinds: Vec<MoveKind>,
    pub retract_before: Vec<usize>,
}

impl SlotReport {
    /// The report of a slot plan.
    pub fn of(plan: &SlotPlan) -> SlotReport {
        let s = plan.path.settings;
        let m = &plan.path.measurement;
        SlotReport {
            method: PocketStrategy::Slot.name(),
            direction: plan.options.direction.name(),
            tool_diameter_mm: 2.0 * s.tool_radius,
            step_over_mm: s.step_over,
            feed_mm_per_min: s.feed_mm_per_min,
            target_deg: plan.target_rad.to_degrees(),
            planned_deg: plan.planned_rad.to_degrees(),
            polygon: polygon_rows(&plan.path),
            ramps: entry_rows(&plan.path.toolpath.entries, plan.options.depth_mm).1,
            ramp_pass_limit_mm: plan.ramp_pass_limit_mm,
            ramp_full_width_depth_mm: plan.ramp_pass_depth_mm,
            axis: plan.axis.iter().map(|l| l.iter().map(|&p| xy(p)).collect()).collect(),
            loops: plan.loops,
            loop_radius_mm: plan.loop_radius_mm,
            corner_points: plan.corner_points.iter().map(CornerPointRow::of).collect(),
            corner_radius_left_mm: plan.corner_radius_left_mm,
            finish_stock_mm: plan.options.finish_stock_mm,
            max_engagement_deg: m.max_engagement_rad.to_degrees(),
            p95_engagement_deg: m.p95_engagement_rad.to_degrees(),
            by_kind: kind_rows(&plan.path),
            length_at_depth_mm: m.length_at_depth_mm,
            link_length_mm: plan.path.link_length_mm,
            air_length_mm: m.air_length_mm,
            entry_length_mm: plan.path.entry_length_mm,
            time_s: plan.path.time_s,
            pace: plan.path.pace.clone(),
            segments: plan.path.segments(),
            kinds: plan.path.kinds(),
            retract_before: plan.path.toolpath.retract_before.clone(),
        }
    }
}
