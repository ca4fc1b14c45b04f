//! The corner acceptance table (docs/corners.md): for corner angles 30°…150° in 15° steps, the peak engagement
//! of the plain contour-parallel ring and of a corner strategy, measured with the independent
//! evaluator ([`crate::engagement::evaluator`]), with path length and machining time.
//!
//! Stated limit (DERIVED): every strategy ends its chain of wall-tangent circles when the next
//! tool-centre radius drops below r_min (docs/corners.md, variable circles). From there the "tip" — the way into
//! the corner point — is reported apart from the rest of the path ("body", which must stay
//! within a* + 1°):
//! - with a corner tolerance δ (the default of `trochoplan corner`), arcs
//!   tangent to both walls shrink to δ, each planned to a* by the derivation of
//!   [`super::point::next_corner_point_radius`]: the tip's limit is a* itself, and
//!   the corner is left with radius r + δ;
//! - without (Wu et al.), the tool moves into the tool corner point U0, where it touches both
//!   walls. The material left there is a sliver between the last offset circle and the walls;
//!   the tool periphery outside the last circle is an arc of π − 2α for any small last radius
//!   ρ (two circles of radii r and r + ρ whose centres are ρ/sin α apart cross at ±(π/2 − α)
//!   about the bisector), while the sliver is only ρ(1/sin α − 1) thick: the tip is bounded by
//!   max(a* + 1°, π − 2α + 1°).

use super::geometry::Corner;
use super::method::CornerMethod;
use super::request::{CornerRequest, measured, symmetric_scenario};
use super::strategy::{CornerPlan, CornerSettings};
use crate::engagement::{EngagementProfile, EvaluatorOptions};
use crate::error::{Error, Param};
use serde::{Deserialize, Serialize};

/// One row of the table (degrees, mm, s).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AcceptanceRow {
    pub corner_angle_deg: f64,
    pub method: CornerMethod,
    pub target_deg: f64,
    /// Peak engagement of the plain ring.
    pub plain_max_deg: f64,
    /// Peak engagement of the strategy over its whole path.
    pub max_deg: f64,
    /// Peak engagement except the final move into the corner point.
    pub body_max_deg: f64,
    /// Peak engagement of the way into the corner point (module docs).
    pub tip_deg: f64,
    /// Stated limit of the way in (deg): a* for corner-point arcs; for Wu et al.'s final move
    /// the arc of the tool periphery at U0 outside the last offset circle, 2(π − ψ) with
    /// cos ψ = (r² + e² − R²)/(2re), e = ρ/sin α, R = r + ρ, which tends to π − 2α as ρ → 0.
    pub tip_limit_deg: f64,
    /// Radial thickness of the sliver cut by the way in (mm): the deepest corner-point arc's,
    /// or ρ_last(1/sin α − 1) for the final move into U0.
    pub tip_sliver_mm: f64,
    /// Material left on the bisector at the corner (mm): δ(1/sin α − 1) after corner-point
    /// arcs, 0 after a move into U0 (and for the plain ring).
    #[serde(default)]
    pub corner_residual_mm: f64,
    pub circles: usize,
    pub path_length_mm: f64,
    pub time_s: f64,
    pub plain_path_length_mm: f64,
    pub plain_time_s: f64,
}

/// Corner angles of the acceptance table (degrees).
pub const ANGLES_DEG: [f64; 9] = [30.0, 45.0, 60.0, 75.0, 90.0, 105.0, 120.0, 135.0, 150.0];

/// The corner strategies of the table (the plain ring is measured in every row).
pub const STRATEGIES: [CornerMethod; 3] = [CornerMethod::Variable, CornerMethod::Isometric, CornerMethod::MedialAxis];

/// Margin over the target a* (and over the tip's stated limit) that still passes (degrees):
/// the table accepts the measured peak within a* + 1°.
pub const MARGIN_DEG: f64 = 1.0;

impl AcceptanceRow {
    /// Largest accepted body engagement, a* + [`MARGIN_DEG`] (degrees).
    pub fn body_limit_deg(&self) -> f64 {
        self.target_deg + MARGIN_DEG
    }

    /// Largest accepted tip engagement, max(a* + 1°, tip limit + 1°) (degrees; module docs).
    pub fn tip_allowed_deg(&self) -> f64 {
        self.body_limit_deg().max(self.tip_limit_deg + MARGIN_DEG)
    }

    /// The body stays within a* + 1°.
    pub fn body_passes(&self) -> bool {
        self.body_max_deg <= self.body_limit_deg()
    }

    /// The final move into the corner point stays within its allowance ([`Self::tip_allowed_deg`]).
    pub fn tip_passes(&self) -> bool {
        self.tip_deg <= self.tip_allowed_deg()
    }

    /// Both the body and the tip pass (a NaN anywhere fails).
    pub fn passes(&self) -> bool {
        self.body_passes() && self.tip_passes()
    }
}

/// One row: plan the plain ring and `method` for the symmetric corner of `angle_deg`, measure
/// both with the evaluator at `spacing` mm.
pub fn acceptance_row(
    angle_deg: f64,
    method: CornerMethod,
    settings: CornerSettings,
    spacing: f64,
) -> Result<AcceptanceRow, Error> {
    let rows = acceptance_rows_at(angle_deg, &[method], settings, spacing)?;
    rows.into_iter().next().ok_or_else(|| Error::param(Param::Method, "none", "one corner strategy"))
}

/// The rows of several methods at one corner angle, in the order of `methods`: the plain ring
/// is planned and measured once and shared; each row equals [`acceptance_row`] for its method
/// (and the row of [`super::evaluate`] for that corner).
pub fn acceptance_rows_at(
    angle_deg: f64,
    methods: &[CornerMethod],
    settings: CornerSettings,
    spacing: f64,
) -> Result<Vec<AcceptanceRow>, Error> {
    let sc = symmetric_scenario(angle_deg, settings)?;
    let opts = EvaluatorOptions::new(settings.tool_radius, spacing);
    let (plain, plain_measurement) = measured(&sc, CornerMethod::Plain, &opts)?;
    methods
        .iter()
        .map(|&method| {
            let (plan, m) = measured(&sc, method, &opts)?;
            Ok(row(angle_deg, method, &sc.corner, settings, (&plan, &m.profile), (&plain, &plain_measurement.profile)))
        })
        .collect()
}

/// The row of a plan and the plain ring, both already measured by the evaluator (body / tip
/// split and the tip's limit, module docs), for callers that keep the plans and profiles.
pub fn row(
    angle_deg: f64,
    method: CornerMethod,
    corner: &Corner,
    settings: CornerSettings,
    (plan, prof): (&CornerPlan, &EngagementProfile),
    (plain, plain_prof): (&CornerPlan, &EngagementProfile),
) -> AcceptanceRow {
    // The way into the corner point is reported apart (see the module docs).
    let (tip_start, tip_end) = match &plan.tip_segments {
        Some(range) => {
            let path = plan.toolpath.segments();
            let start: f64 = path[..range.start].iter().map(|s| s.length()).sum();
            (start, start + path[range.clone()].iter().map(|s| s.length()).sum::<f64>())
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
    let (sliver, residual) = match &plan.corner_point {
        Some(arcs) => (arcs.max_radial_depth_mm, arcs.residual_mm),
        None => (rho * (1.0 / sin - 1.0), 0.0),
    };
    let tip_limit = if plan.corner_point.is_some() {
        settings.target
    } else if rho > 0.0 {
        let (e, big_r) = (rho / sin, r + rho);
        let psi = ((r * r + e * e - big_r * big_r) / (2.0 * r * e)).clamp(-1.0, 1.0).acos();
        2.0 * (std::f64::consts::PI - psi)
    } else {
        std::f64::consts::PI - 2.0 * corner.half_angle
    };
    AcceptanceRow {
        corner_angle_deg: angle_deg,
        method,
        target_deg: settings.target.to_degrees(),
        plain_max_deg: plain_prof.max_angle().to_degrees(),
        max_deg: prof.max_angle().to_degrees(),
        body_max_deg: body.to_degrees(),
        tip_deg: tip.to_degrees(),
        tip_limit_deg: tip_limit.to_degrees(),
        tip_sliver_mm: sliver,
        corner_residual_mm: residual,
        circles: plan.circles.len(),
        path_length_mm: plan.path_length_mm,
        time_s: plan.time_s,
        plain_path_length_mm: plain.path_length_mm,
        plain_time_s: plain.time_s,
    }
}

/// All rows for the request's method, settings and evaluator spacing (its angle is not used).
pub fn acceptance_table(req: &CornerRequest) -> Result<Vec<AcceptanceRow>, Error> {
    let settings = req.settings()?;
    ANGLES_DEG.iter().map(|&a| acceptance_row(a, req.method, settings, req.spacing_mm)).collect()
}

/// The table as Markdown (for the README and the CLI).
pub fn markdown(rows: &[AcceptanceRow]) -> String {
    let mut s = String::from(
        "| corner | method | target | plain max | max | body max | tip | tip limit | tip sliver mm | residual mm | circles | length mm | time s | plain length mm | plain time s |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        s.push_str(&format!(
            "| {:.0}° | {} | {:.2}° | {:.2}° | {:.2}° | {:.2}° | {:.2}° | {:.2}° | {:.3} | {:.4} | {} | {:.1} | {:.1} | {:.1} | {:.1} |\n",
            r.corner_angle_deg,
            r.method.name(),
            r.target_deg,
            r.plain_max_deg,
            r.max_deg,
            r.body_max_deg,
            r.tip_deg,
            r.tip_limit_deg,
            r.tip_sliver_mm,
            r.corner_residual_mm,
            r.circles,
            r.path_length_mm,
            r.time_s,
            r.plain_path_length_mm,
            r.plain_time_s
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engagement::radial_depth_for_engagement;

    /// The table's settings (module docs of the integration test `corner_acceptance.rs`):
    /// D = 10, a_e giving 46° on the straight part, t1 = 15 %.
    fn settings() -> CornerSettings {
        let r = 5.0;
        CornerSettings::new(r, radial_depth_for_engagement(46f64.to_radians(), r)).expect("settings")
    }

    #[test]
    fn rows_at_one_angle_equal_the_single_rows_and_share_the_plain_ring() {
        let (angle, spacing) = (120.0, 1.0);
        let rows = acceptance_rows_at(angle, &STRATEGIES, settings(), spacing).expect("rows");
        assert_eq!(rows.len(), STRATEGIES.len());
        for (row, &m) in rows.iter().zip(&STRATEGIES) {
            let single = acceptance_row(angle, m, settings(), spacing).expect("row");
            assert_eq!(*row, single, "{}", m.name());
        }
        assert!(rows.windows(2).all(|w| w[0].plain_max_deg == w[1].plain_max_deg));
        assert!(acceptance_rows_at(angle, &[], settings(), spacing).expect("no methods").is_empty());
        let e = acceptance_rows_at(200.0, &STRATEGIES, settings(), spacing).expect_err("angle");
        assert!(e.to_string().contains("angle"), "{e}");
    }

    #[test]
    fn pass_flags_compare_with_the_target_and_the_tip_allowance() {
        let row = acceptance_row(90.0, CornerMethod::Variable, settings(), 1.0).expect("row");
        let at = |body: f64, tip: f64, limit: f64| AcceptanceRow {
            body_max_deg: body,
            tip_deg: tip,
            tip_limit_deg: limit,
            ..row.clone()
        };
        let t = row.target_deg;
        // boundaries are inclusive: a* + 1° passes, anything above fails
        assert!(at(t + MARGIN_DEG, 0.0, 0.0).body_passes());
        assert!(!at(t + MARGIN_DEG + 1e-9, 0.0, 0.0).body_passes());
        assert!(!at(t + 2.0, 0.0, 0.0).passes());
        // the tip may reach its own limit + 1° when that is above a* + 1° ...
        assert!(at(t, 120.0, 119.0).tip_passes() && at(t, 120.0, 119.0).passes());
        assert!(!at(t, 120.0 + 1e-9, 119.0).tip_passes());
        // ... and a* + 1° when its limit is below the target
        assert_eq!(at(t, 0.0, 20.0).tip_allowed_deg(), t + MARGIN_DEG);
        assert!(at(t, t + MARGIN_DEG, 20.0).tip_passes() && !at(t, t + 1.5, 20.0).tip_passes());
        assert!(!at(f64::NAN, 0.0, 0.0).passes() && !at(t, f64::NAN, 90.0).passes());
        assert_eq!(row.passes(), row.body_passes() && row.tip_passes());
    }
}
