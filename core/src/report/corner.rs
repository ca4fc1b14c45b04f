//! The report of one planned corner ([`corner()`]): the strategy's circles, length, time; from
//! its measurement the peak and where, each kind of move's maximum and the air; the way into
//! the corner point, and the plain ring it is compared with.

use super::{KindRow, hmax_per_fz, xy};
use crate::corner::CornerReport;
use crate::error::Error;
use crate::geom::Segment;
use crate::toolpath::MoveKind;
use serde::Serialize;

/// One corner trochoid circle.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CircleRow {
    pub x_mm: f64,
    pub y_mm: f64,
    pub tool_center_radius_mm: f64,
    pub offset_radius_mm: f64,
    pub predicted_max_engagement_deg: Option<f64>,
    pub bisection_steps: usize,
}

/// The report of one corner.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CornerSummary {
    pub method: &'static str,
    pub corner_angle_deg: f64,
    pub tool_diameter_mm: f64,
    pub step_over_mm: f64,
    pub straight_engagement_deg: f64,
    pub target_deg: f64,
    pub circles: Vec<CircleRow>,
    pub path_length_mm: f64,
    pub time_s: f64,
    /// Measured with the independent evaluator over the plan's material model: the maximum
    /// over every move (legs, circles, links, the way into the corner point).
    pub max_engagement_deg: f64,
    pub max_engagement_at: [f64; 2],
    /// Every move is at depth: the path length.
    pub length_at_depth_mm: f64,
    /// The `link` rows of `by_kind`.
    pub link_length_mm: f64,
    pub air_length_mm: f64,
    pub by_kind: Vec<KindRow>,
    /// The way into the corner point: arcs down to the corner tolerance, or the straight move.
    pub corner_point: CornerTipRow,
    pub plain_max_engagement_deg: f64,
    pub plain_path_length_mm: f64,
    pub notes: Vec<String>,
    pub path: Vec<Segment>,
}

/// The way into a corner's corner point.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CornerTipRow {
    /// 0: Wu et al.'s straight move into the tool corner point.
    pub corner_tolerance_mm: f64,
    /// Tool-centre radii of the corner-point arcs (mm), in machining order.
    pub arc_radii_mm: Vec<f64>,
    /// Material left on the bisector (mm): the corner is cut to radius r + δ.
    pub residual_mm: f64,
    /// Deepest radial cut of one arc (or of the straight move) on the bisector (mm).
    pub max_radial_depth_mm: f64,
    pub max_engagement_deg: f64,
    pub at: [f64; 2],
    /// Chip thickness per tooth feed at the peak, h_max/f_z = sin(peak) (1 at 90° and above).
    pub hmax_per_fz: f64,
    /// The limit it is planned to (deg): the target a* for arcs, π − angle-derived for the move.
    pub limit_deg: f64,
}

/// The report of an evaluated corner.
pub fn corner(report: &CornerReport) -> Result<CornerSummary, Error> {
    let s = report.settings();
    let (plan, m) = (&report.plan, &report.measurement);
    let mx = m.profile.max();
    let by_kind = report.by_kind();
    let tip = by_kind.iter().find(|k| matches!(k.kind, MoveKind::CornerPoint | MoveKind::Tip));
    let rows: Vec<KindRow> = by_kind.iter().map(KindRow::of).collect();
    Ok(CornerSummary {
        method: plan.method.name(),
        corner_angle_deg: report.angle_deg,
        tool_diameter_mm: 2.0 * s.tool_radius,
        step_over_mm: s.step_over,
        straight_engagement_deg: s.straight_engagement()?.to_degrees(),
        target_deg: s.target.to_degrees(),
        circles: plan
            .circles
            .iter()
            .map(|c| CircleRow {
                x_mm: c.tool_circle.center.x,
                y_mm: c.tool_circle.center.y,
                tool_center_radius_mm: c.tool_circle.radius,
                offset_radius_mm: c.offset_radius,
                predicted_max_engagement_deg: c.predicted_max.map(f64::to_degrees),
                bisection_steps: c.steps,
            })
            .collect(),
        path_length_mm: plan.path_length_mm,
        time_s: plan.time_s,
        max_engagement_deg: m.max_engagement_rad.to_degrees(),
        max_engagement_at: mx.map_or([f64::NAN; 2], |m| [m.x_mm, m.y_mm]),
        length_at_depth_mm: plan.path_length_mm,
        link_length_mm: report.link_length_mm(),
        air_length_mm: report.air_length_mm(),
        by_kind: rows,
        corner_point: CornerTipRow {
            corner_tolerance_mm: s.corner_tolerance.unwrap_or(0.0),
            arc_radii_mm: plan.corner_point.as_ref().map_or(Vec::new(), |c| c.radii_mm.clone()),
            residual_mm: report.row.corner_residual_mm,
            max_radial_depth_mm: report.row.tip_sliver_mm,
            max_engagement_deg: tip.map_or(0.0, |t| t.max_rad.to_degrees()),
            at: tip.map_or([f64::NAN; 2], |t| xy(t.at)),
            hmax_per_fz: tip.map_or(0.0, |t| hmax_per_fz(t.max_rad)),
            limit_deg: report.row.tip_limit_deg,
        },
        plain_max_engagement_deg: report.plain_measurement.max_engagement_rad.to_degrees(),
        plain_path_length_mm: report.plain.path_length_mm,
        notes: plan.notes.clone(),
        path: plan.toolpath.segments(),
    })
}
