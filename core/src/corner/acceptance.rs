//! The issue #5 acceptance table: for corner angles 30°…150° in 15° steps, the peak engagement
//! of the plain contour-parallel ring and of a corner strategy, measured with the independent
//! evaluator ([`super::evaluator`]), with path length and machining time.
//!
//! Stated limit (DERIVED): every strategy ends its chain of wall-tangent circles when the next
//! tool-centre radius drops below r_min (domain-spec §3.3) and then moves into the tool corner
//! point U0, where the tool touches both walls. The material left there is a sliver between
//! the last offset circle and the walls; the tool periphery outside the last circle is an arc
//! of π − 2α for any small last radius ρ (two circles of radii r and r + ρ whose centres are
//! ρ/sin α apart cross at ±(π/2 − α) about the bisector), while the sliver is only
//! ρ(1/sin α − 1) thick. So the final move is reported separately ("tip") and bounded by
//! max(a* + 1°, π − 2α + 1°); the rest of the path ("body") must stay within a* + 1°.

use super::evaluator::{EvaluatorOptions, engagement_profile};
use super::geometry::Corner;
use super::strategy::{CornerScenario, CornerSettings, Method, plan_corner};
use crate::error::JobError;
use serde::{Deserialize, Serialize};

/// One row of the table (degrees, mm, s).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AcceptanceRow {
    pub corner_angle_deg: f64,
    pub method: Method,
    pub target_deg: f64,
    /// Peak engagement of the plain ring.
    pub plain_max_deg: f64,
    /// Peak engagement of the strategy over its whole path.
    pub max_deg: f64,
    /// Peak engagement except the final move into the corner point.
    pub body_max_deg: f64,
    /// Peak engagement of the final move into the corner point.
    pub tip_deg: f64,
    /// Stated limit of the final move (deg): the arc of the tool periphery at U0 outside the
    /// last offset circle, 2(π − ψ) with cos ψ = (r² + e² − R²)/(2re), e = ρ/sin α, R = r + ρ;
    /// it tends to π − 2α as ρ → 0.
    pub tip_limit_deg: f64,
    /// Radial thickness of the sliver cut by the final move, ρ_last(1/sin α − 1) (mm).
    pub tip_sliver_mm: f64,
    pub circles: usize,
    pub path_length_mm: f64,
    pub time_s: f64,
    pub plain_path_length_mm: f64,
    pub plain_time_s: f64,
}

/// Corner angles of the acceptance table (degrees).
pub const ANGLES_DEG: [f64; 9] = [30.0, 45.0, 60.0, 75.0, 90.0, 105.0, 120.0, 135.0, 150.0];

/// One row: plan the plain ring and `method` for the symmetric corner of `angle_deg`, measure
/// both with the evaluator at `spacing` mm.
pub fn acceptance_row(angle_deg: f64, method: Method, settings: CornerSettings, spacing: f64) -> Result<AcceptanceRow, JobError> {
    let corner = Corner::symmetric(angle_deg.to_radians())?;
    let sc = CornerScenario::new(corner, settings)?;
    let opts = EvaluatorOptions::new(settings.tool_radius, spacing);
    let plain = plan_corner(&sc, Method::Plain)?;
    let plain_prof = engagement_profile(&sc.stock, &sc.previous_ring, &plain.path, &opts)?;
    let plan = plan_corner(&sc, method)?;
    let prof = engagement_profile(&plan.stock, &plan.precut, &plan.path, &opts)?;
    // The final move into U0 is reported apart (see the module docs).
    let (tip_start, tip_end) = match plan.tip_segment {
        Some(i) => {
            let start: f64 = plan.path[..i].iter().map(|s| s.length()).sum();
            (start, start + plan.path[i].length())
        }
        None => (f64::INFINITY, f64::INFINITY),
    };
    let (mut body, mut tip) = (0.0f64, 0.0f64);
    for s in &prof.samples {
        if s.s_mm > tip_start + 1e-9 && s.s_mm <= tip_end + 1e-9 {
            tip = tip.max(s.angle_rad);
        } else {
            body = body.max(s.angle_rad);
        }
    }
    let sin = corner.half_angle.sin();
    let r = settings.tool_radius;
    let rho = plan.circles.last().map_or(0.0, |c| c.tool_circle.radius);
    let sliver = rho * (1.0 / sin - 1.0);
    let tip_limit = if rho > 0.0 {
        let (e, big_r) = (rho / sin, r + rho);
        let psi = ((r * r + e * e - big_r * big_r) / (2.0 * r * e)).clamp(-1.0, 1.0).acos();
        2.0 * (std::f64::consts::PI - psi)
    } else {
        std::f64::consts::PI - 2.0 * corner.half_angle
    };
    Ok(AcceptanceRow {
        corner_angle_deg: angle_deg,
        method,
        target_deg: settings.target.to_degrees(),
        plain_max_deg: plain_prof.max_angle().to_degrees(),
        max_deg: prof.max_angle().to_degrees(),
        body_max_deg: body.to_degrees(),
        tip_deg: tip.to_degrees(),
        tip_limit_deg: tip_limit.to_degrees(),
        tip_sliver_mm: sliver,
        circles: plan.circles.len(),
        path_length_mm: plan.path_length_mm,
        time_s: plan.time_s,
        plain_path_length_mm: plain.path_length_mm,
        plain_time_s: plain.time_s,
    })
}

/// All rows for one method.
pub fn acceptance_table(method: Method, settings: CornerSettings, spacing: f64) -> Result<Vec<AcceptanceRow>, JobError> {
    ANGLES_DEG.iter().map(|&a| acceptance_row(a, method, settings, spacing)).collect()
}

/// The table as Markdown (for the README and the CLI).
pub fn markdown(rows: &[AcceptanceRow]) -> String {
    let mut s = String::from(
        "| corner | method | target | plain max | max | body max | tip | tip limit | tip sliver mm | circles | length mm | time s | plain length mm | plain time s |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        s.push_str(&format!(
            "| {:.0}° | {} | {:.2}° | {:.2}° | {:.2}° | {:.2}° | {:.2}° | {:.2}° | {:.3} | {} | {:.1} | {:.1} | {:.1} | {:.1} |\n",
            r.corner_angle_deg,
            r.method.name(),
            r.target_deg,
            r.plain_max_deg,
            r.max_deg,
            r.body_max_deg,
            r.tip_deg,
            r.tip_limit_deg,
            r.tip_sliver_mm,
            r.circles,
            r.path_length_mm,
            r.time_s,
            r.plain_path_length_mm,
            r.plain_time_s
        ));
    }
    s
}
