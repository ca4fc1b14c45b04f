//! The corner job as the front ends state it ([`CornerRequest`]) and its one entry point,
//! [`evaluate`]: the symmetric corner's scenario, the strategy's plan and the plain ring, both
//! measured by the independent evaluator, and their acceptance row ([`super::acceptance`]).

use super::acceptance::{self, AcceptanceRow};
use super::geometry::Corner;
use super::limits::tool_diameter;
use super::method::CornerMethod;
use super::point::{DEFAULT_CORNER_TOLERANCE_MM, validate_corner_tolerance};
use super::strategy::{CornerPlan, CornerScenario, CornerSettings, DEFAULT_T1, plan_corner};
use crate::engagement::{EvaluatorOptions, KindMax, Measurement, Stock, measure};
use crate::engagement::{radial_depth_for_engagement, straight_engagement};
use crate::error::{Error, Param, num};
use crate::geom::mirror::{flip_y, flip_y_segment, flipped_y_polygon};
use crate::job::Direction;
use crate::toolpath::MoveKind;
use serde::{Deserialize, Serialize};

/// One symmetric corner to plan and measure, in the user's units (degrees, mm, mm/min): the
/// flags of `trochoplan corner` and the fields of the GUI's Corner tab.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CornerRequest {
    /// Interior corner angle (degrees).
    pub angle_deg: f64,
    pub method: CornerMethod,
    /// Tool diameter D (mm).
    pub tool_diameter_mm: f64,
    /// Ring step-over a_e (mm); `None`: the step-over giving `straight_engagement_deg`.
    pub step_over_mm: Option<f64>,
    /// Engagement on the straight part of the ring a_str (degrees), when `step_over_mm` is `None`.
    pub straight_engagement_deg: f64,
    /// Target engagement a* (degrees); `None`: a* = a_str·(1 + t1).
    pub target_deg: Option<f64>,
    /// Allowed excess over the straight-part engagement (Wu et al. eq. 23), when `target_deg`
    /// is `None`.
    pub t1: f64,
    /// Bisection acceptance band ε (degrees).
    pub tolerance_deg: f64,
    /// Wall length from the apex (mm).
    pub edge_length_mm: f64,
    /// Feed rate for the machining time (mm/min).
    pub feed_mm_per_min: f64,
    /// Tool-centre radius rh of isometric circles (mm); `None`: the tool radius.
    pub isometric_radius_mm: Option<f64>,
    /// Arc-length spacing of the tool positions measured by the evaluator (mm).
    pub spacing_mm: f64,
    /// Climb (counter-clockwise circles and ring with M3) or conventional (the mirror image).
    #[serde(default)]
    pub direction: Direction,
    /// Corner tolerance δ (mm): the way into the corner point ends on an arc of tool-centre
    /// radius δ (docs/corners.md); 0: Wu et al.'s straight move into the tool corner point.
    #[serde(default = "default_corner_tolerance")]
    pub corner_tolerance_mm: f64,
}

fn default_corner_tolerance() -> f64 {
    DEFAULT_CORNER_TOLERANCE_MM
}

impl CornerRequest {
    /// The defaults of `trochoplan corner` and of the Corner tab: a 90° corner, variable
    /// circles, D = 10 mm, a_str = 46°, t1 = 15 %, ε = 0.5°, 100 mm walls, 600 mm/min, the
    /// evaluator every 0.1 mm, climb, corner-point arcs down to δ = 0.005 mm.
    pub const DEFAULT: CornerRequest = CornerRequest {
        angle_deg: 90.0,
        method: CornerMethod::Variable,
        tool_diameter_mm: 10.0,
        step_over_mm: None,
        straight_engagement_deg: 46.0,
        target_deg: None,
        t1: DEFAULT_T1,
        tolerance_deg: 0.5,
        edge_length_mm: 100.0,
        feed_mm_per_min: 600.0,
        isometric_radius_mm: None,
        spacing_mm: 0.1,
        direction: Direction::Climb,
        corner_tolerance_mm: DEFAULT_CORNER_TOLERANCE_MM,
    };

    /// The validated settings of the corner plan. Each error names the input (as the CLI flag
    /// spells it) and its allowed range.
    pub fn settings(&self) -> Result<CornerSettings, Error> {
        let d = tool_diameter(self.tool_diameter_mm)?;
        let r = d / 2.0;
        let step_over = match self.step_over_mm {
            Some(ae) => finite(Param::StepOver, ae)?,
            None => {
                let a = finite(Param::StraightEngagement, self.straight_engagement_deg)?;
                if !(a > 0.0 && a < 180.0) {
                    return Err(Error::param(Param::StraightEngagement, a, "greater than 0° and less than 180°"));
                }
                radial_depth_for_engagement(a.to_radians(), r)
            }
        };
        let mut s = CornerSettings::new(r, step_over).map_err(|e| match e {
            Error::Param { param: Param::StepOver, value, .. } => Error::param(
                Param::StepOver,
                value,
                format!("greater than 0 and less than the tool diameter {} mm", num(d)),
            ),
            other => other,
        })?;
        s.target = match self.target_deg {
            Some(t) => finite(Param::Target, t)?.to_radians(),
            None => {
                let t1 = finite(Param::T1, self.t1)?;
                if !(0.0..=1.0).contains(&t1) {
                    return Err(Error::param(Param::T1, t1, "from 0 to 1"));
                }
                straight_engagement(step_over, r)? * (1.0 + t1)
            }
        };
        s.tolerance = finite(Param::Band, self.tolerance_deg)?.to_radians();
        s.edge_length = self.edge_length_mm;
        s.feed_mm_per_min = self.feed_mm_per_min;
        s.isometric_radius = self.isometric_radius_mm;
        let delta = finite(Param::CornerTolerance, self.corner_tolerance_mm)?;
        if delta != 0.0 {
            validate_corner_tolerance(delta).map_err(|_| {
                Error::param(
                    Param::CornerTolerance,
                    delta,
                    "0 (into the corner point, Wu et al.) or from 0.001 to 1 mm",
                )
            })?;
            s.corner_tolerance = Some(delta);
        }
        s.validate()?;
        Ok(s)
    }
}

impl Default for CornerRequest {
    /// [`CornerRequest::DEFAULT`].
    fn default() -> Self {
        CornerRequest::DEFAULT
    }
}

/// A corner planned and measured: what `trochoplan corner` prints and the Corner tab shows.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CornerReport {
    /// Interior corner angle (degrees, as requested).
    pub angle_deg: f64,
    /// The corner, its validated settings and the material the previous ring left.
    pub scenario: CornerScenario,
    /// The requested strategy's plan and its [`measure`]ment over the plan's material model.
    pub plan: CornerPlan,
    pub measurement: Measurement,
    /// The plain ring of the same corner and its measurement.
    pub plain: CornerPlan,
    pub plain_measurement: Measurement,
    /// Body / tip split and pass flags of the plan ([`acceptance::row`]).
    pub row: AcceptanceRow,
}

impl CornerReport {
    /// The settings the corner was planned with.
    pub fn settings(&self) -> &CornerSettings {
        &self.scenario.settings
    }

    /// Per kind of move (U and V legs, circles, links, corner-point arcs or the tip): the
    /// largest engagement measured and where, and the length.
    pub fn by_kind(&self) -> &[KindMax] {
        &self.measurement.maxima
    }

    /// Length of the moves along U between circles and of the isometric return (mm).
    pub fn link_length_mm(&self) -> f64 {
        let links = self.plan.toolpath.moves.iter().filter(|m| m.kind == MoveKind::Link);
        links.fold(0.0, |sum, m| sum + m.segment.length())
    }

    /// Length of the moves that engage less than 1° (mm).
    pub fn air_length_mm(&self) -> f64 {
        self.measurement.air_length_mm
    }
}

/// Plan the requested corner with its strategy and with the plain ring, measure both with the
/// evaluator, and make their acceptance row. Errors name the input at fault.
pub fn evaluate(req: &CornerRequest) -> Result<CornerReport, Error> {
    let settings = req.settings()?;
    // circles of a small step-over grow in number as 1/a_e, each found by bisection: below the
    // papers' range they take seconds to minutes for no useful gain (plain has none)
    let least = super::limits::MEDIAL_AXIS_MIN_STEP_OVER_RATIO * 2.0 * settings.tool_radius;
    if req.method != CornerMethod::Plain && settings.step_over < least {
        return Err(Error::param(
            Param::StepOver,
            settings.step_over,
            format!(
                "at least {} × the tool diameter = {} mm for --method {} (the papers' smallest radial depth)",
                super::limits::MEDIAL_AXIS_MIN_STEP_OVER_RATIO,
                num(least),
                req.method.name()
            ),
        ));
    }
    let angle_deg = finite(Param::Angle, req.angle_deg)?;
    let scenario = symmetric_scenario(angle_deg, settings)?;
    let opts = EvaluatorOptions::new(settings.tool_radius, req.spacing_mm);
    let (plan, measurement) = measured(&scenario, req.method, &opts)?;
    let (plain, plain_measurement) = measured(&scenario, CornerMethod::Plain, &opts)?;
    let row = acceptance::row(
        angle_deg,
        req.method,
        &scenario.corner,
        settings,
        (&plan, &measurement.profile),
        (&plain, &plain_measurement.profile),
    );
    let report = CornerReport { angle_deg, scenario, plan, measurement, plain, plain_measurement, row };
    match req.direction {
        Direction::Climb => Ok(report),
        Direction::Conventional => report.mirrored(),
    }
}

impl CornerReport {
    /// Conventional milling: the report reflected in the corner's bisector
    /// (the x axis, y → −y: the same corner, walls swapped): every circle and the ring turn
    /// clockwise, the engagement is the climb plan's (a reflection of tool, path and stock
    /// leaves every engaged angle unchanged) at the reflected places, the acceptance row the
    /// same.
    fn mirrored(mut self) -> Result<CornerReport, Error> {
        let sc = &mut self.scenario;
        let c = sc.corner;
        sc.corner = Corner {
            apex: flip_y(c.apex),
            dir_in: flip_y(c.dir_in),
            dir_out: flip_y(c.dir_out),
            half_angle: c.half_angle,
            bisector: flip_y(c.bisector),
        };
        sc.stock = flipped_y_polygon(&sc.stock)?;
        sc.previous_ring = sc.previous_ring.iter().map(flip_y_segment).collect();
        for p in [&mut sc.ring_start, &mut sc.corner_point, &mut sc.ring_end] {
            *p = flip_y(*p);
        }
        for (plan, measurement) in
            [(&mut self.plan, &mut self.measurement), (&mut self.plain, &mut self.plain_measurement)]
        {
            for circle in &mut plan.circles {
                circle.tool_circle.center = flip_y(circle.tool_circle.center);
            }
            for m in &mut plan.toolpath.moves {
                m.segment = flip_y_segment(&m.segment);
            }
            plan.stock = flipped_y_polygon(&plan.stock)?;
            plan.precut = plan.precut.iter().map(flip_y_segment).collect();
            for s in &mut measurement.profile.samples {
                s.y_mm = -s.y_mm;
            }
            for m in &mut measurement.maxima {
                m.at = flip_y(m.at);
            }
        }
        Ok(self)
    }
}

/// The scenario of the symmetric corner of `angle_deg` (the corner of [`evaluate`] and of
/// every row of the acceptance table).
pub(super) fn symmetric_scenario(angle_deg: f64, settings: CornerSettings) -> Result<CornerScenario, Error> {
    CornerScenario::new(Corner::symmetric(angle_deg.to_radians())?, settings)
}

/// The plan of `method` in the scenario and its measurement over the plan's material model
/// (its stock polygon with the previous ring cut).
pub(super) fn measured(
    sc: &CornerScenario,
    method: CornerMethod,
    opts: &EvaluatorOptions,
) -> Result<(CornerPlan, Measurement), Error> {
    let plan = plan_corner(sc, method)?;
    let measurement =
        measure(&plan.toolpath, Stock { polygon: &plan.stock, precut: &plan.precut, islands: &[] }, opts)?;
    Ok((plan, measurement))
}

/// `v` if it is finite, else an error naming `param`.
pub fn finite(param: Param, v: f64) -> Result<f64, Error> {
    if v.is_finite() { Ok(v) } else { Err(Error::param(param, v, "a finite number")) }
}
