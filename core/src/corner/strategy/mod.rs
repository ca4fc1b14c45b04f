//! Corner trochoids for one line–line corner of a contour-parallel ring (Wu et al. 2016 §4.2;
//! eqs. 23–25; docs/corners.md), and the corner scenario used to measure them.
//!
//! Scenario (our reading of Figs. 12–14 of Wu et al. 2016): a convex corner
//! of two walls of length `edge_length` from the apex. The previous ring's tool centre ran on
//! the walls offset by `r + a_e` with a sharp corner at `P0` (so it left the corner arc PSQ of
//! radius r about P0), and everything farther inside was cleared before. The current ring U–V
//! runs on the walls offset by `r`, from beyond the end of wall 1 to the tool corner point
//! `U0 = W0 + (r / sin α) b̂` and out beyond the end of wall 2.
//!
//! The ring strategies (variable, isometric) replace the corner of U–V by counter-clockwise (G3)
//! tool-centre circles that are tangent to U (their offset circles touch wall 1), entered and
//! left at that tangent point and linked by straight moves along U, so the path is
//! G1-continuous up to the corner point, where it turns onto V exactly like the plain ring:
//! `U leg → circle 1 → line on U → circle 2 → … → line on U to U0 → V leg` (the isometric
//! layout first runs the U leg a little further and returns along U in air to circle 1).
//! The medial-axis strategy has no rings: it cuts the corner of a triangular pocket down the
//! corner's medial-axis branch (see `medial_axis_plan`).

mod isometric;
mod medial;
mod ring_path;
#[cfg(test)]
mod tests;
mod variable;

use crate::corner::geometry::Corner;
use crate::corner::limits::validate_tool_and_step_over;
use crate::corner::method::CornerMethod;
use crate::corner::point::validate_corner_tolerance;
use crate::corner::request::CornerRequest;
use crate::engagement::straight_engagement;
use crate::error::{Error, Param, num};
use crate::geom::{Circle, P2, Polygon, Segment};
use crate::toolpath::{MoveKind, Toolpath};
use isometric::isometric_circles;
use medial::medial_axis_plan;
use ring_path::{Moves, into_corner_point, ring_path};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
pub use variable::first_circle_radius;
use variable::variable_circles;

/// Bisection steps allowed for one circle (a cap: each step halves the
/// bracket, so 60 steps reach far below any length that matters).
const MAX_BISECTION: usize = 60;

/// Wu et al.'s example tolerance over the straight-part value, t1 = 15 % (eq. 23).
pub const DEFAULT_T1: f64 = 0.15;

/// Circles allowed in one corner (guards against a stop rule that never fires).
const MAX_CIRCLES: usize = 2000;

/// Inputs of a corner plan (mm, rad, mm/min).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CornerSettings {
    /// Tool radius r (mm).
    pub tool_radius: f64,
    /// Radial step-over a_e between rings (mm), 0 < a_e < D.
    pub step_over: f64,
    /// Target engagement a* (rad): the straight-part value a_str·(1 + t1).
    pub target: f64,
    /// Bisection acceptance band ε (rad): accept m ∈ (a*, a* + ε] (eq. 24).
    pub tolerance: f64,
    /// Wall length from the apex (mm).
    pub edge_length: f64,
    /// Feed rate for the machining time (mm/min).
    pub feed_mm_per_min: f64,
    /// Tool-centre radius rh of isometric circles (mm); `None` = r (the default of docs/corners.md).
    pub isometric_radius: Option<f64>,
    /// How the strategies reach the corner point (docs/corners.md): `Some(δ)` by arcs tangent
    /// to both walls that shrink to the tool-centre radius δ (mm), each within the target
    /// ([`corner_point_radii`](crate::corner::point::corner_point_radii)); `None`: Wu et al.'s straight move into the tool corner point
    /// U0 after the last circle (reads up to π − 2α there, [`super::acceptance`]).
    #[serde(default)]
    pub corner_tolerance: Option<f64>,
}

impl CornerSettings {
    /// Settings with Wu et al.'s target a* = a_str·(1 + t1), t1 = 15 % (eq. 23 analogue,
    /// docs/corners.md), and ε, wall length and feed of [`CornerRequest::DEFAULT`] (0.5°,
    /// 100 mm, 600 mm/min).
    pub fn new(tool_radius: f64, step_over: f64) -> Result<CornerSettings, Error> {
        let target = straight_engagement(step_over, tool_radius)? * (1.0 + DEFAULT_T1);
        let d = CornerRequest::DEFAULT;
        Ok(CornerSettings {
            tool_radius,
            step_over,
            target,
            tolerance: d.tolerance_deg.to_radians(),
            edge_length: d.edge_length_mm,
            feed_mm_per_min: d.feed_mm_per_min,
            isometric_radius: d.isometric_radius_mm,
            corner_tolerance: None,
        })
    }

    /// Straight-cut engagement of the ring step, a_str = arccos(1 − a_e/r) (docs/corners.md).
    pub fn straight_engagement(&self) -> Result<f64, Error> {
        straight_engagement(self.step_over, self.tool_radius)
    }

    /// Smallest tool-centre circle radius worth cutting: max(0.05 r, 0.05 mm) (docs/corners.md).
    pub fn r_min(&self) -> f64 {
        (0.05 * self.tool_radius).max(0.05)
    }

    /// Tool-centre radius of isometric circles.
    pub fn rh(&self) -> f64 {
        self.isometric_radius.unwrap_or(self.tool_radius)
    }

    /// Range checks; each error names the parameter and its allowed range.
    pub fn validate(&self) -> Result<(), Error> {
        let r = self.tool_radius;
        validate_tool_and_step_over(r, self.step_over)?;
        if !(self.target.is_finite() && self.target > 0.0 && self.target < PI) {
            return Err(Error::param(
                Param::Target,
                format!("{}°", num(self.target.to_degrees())),
                "greater than 0° and less than 180°",
            ));
        }
        if !(self.tolerance.is_finite() && self.tolerance > 0.0 && self.tolerance <= 10f64.to_radians()) {
            return Err(Error::param(
                Param::Band,
                format!("{}°", num(self.tolerance.to_degrees())),
                "greater than 0° and at most 10°",
            ));
        }
        if !(self.edge_length.is_finite() && self.edge_length > 4.0 * r && self.edge_length <= 1.0e4) {
            return Err(Error::param(
                Param::EdgeLength,
                self.edge_length,
                format!("more than two tool diameters ({} mm) and at most 10000 mm", num(4.0 * r)),
            ));
        }
        if !(self.feed_mm_per_min.is_finite() && self.feed_mm_per_min > 0.0) {
            return Err(Error::param(Param::Feed, self.feed_mm_per_min, "a finite number > 0 mm/min"));
        }
        if let Some(d) = self.corner_tolerance {
            validate_corner_tolerance(d)?;
        }
        let rh = self.rh();
        if !(rh.is_finite() && rh >= self.r_min() && rh <= 10.0 * r) {
            return Err(Error::param(
                Param::IsometricRadius,
                rh,
                format!("from r_min = {} mm to 10·r = {} mm", num(self.r_min()), num(10.0 * r)),
            ));
        }
        Ok(())
    }
}

/// The corner of one ring with the material the previous ring left (see module docs).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CornerScenario {
    pub corner: Corner,
    pub settings: CornerSettings,
    /// Stock before the previous ring: the band between the walls and the previous ring's tool
    /// path (farther inside was cleared by earlier rings).
    pub stock: Polygon,
    /// The previous ring's tool-centre path (walls offset by r + a_e), already cut.
    pub previous_ring: Vec<Segment>,
    /// Start of the current ring (beyond the end of wall 1, on U).
    pub ring_start: P2,
    /// Tool corner point U0 = W0 + (r / sin α) b̂.
    pub corner_point: P2,
    /// End of the current ring (beyond the end of wall 2, on V).
    pub ring_end: P2,
}

impl CornerScenario {
    /// Builds and validates the scenario. A corner too narrow for the tool to enter (the
    /// previous ring's corner would lie within one tool diameter of the wall ends) is an error
    /// naming the corner angle and the smallest angle these walls allow.
    pub fn new(corner: Corner, settings: CornerSettings) -> Result<CornerScenario, Error> {
        settings.validate()?;
        let (r, ae, len) = (settings.tool_radius, settings.step_over, settings.edge_length);
        let alpha = corner.half_angle;
        // Foot of the previous ring's corner on the walls: (r + a_e)·cot α from the apex.
        let foot = (r + ae) / alpha.tan();
        if foot > len - 2.0 * r {
            let min_angle = 2.0 * ((r + ae) / (len - 2.0 * r)).atan();
            return Err(Error::param(
                Param::Angle,
                format!("{:.3}°", (2.0 * alpha).to_degrees()),
                format!(
                    "at least {:.3}° for a {} mm tool, step-over {} mm and {} mm walls (narrower corners cannot be entered)",
                    min_angle.to_degrees(),
                    num(2.0 * r),
                    num(ae),
                    num(len)
                ),
            ));
        }
        let (w0, b, s) = (corner.apex, corner.bisector, alpha.sin());
        let (ni, no) = (corner.normal_in(), corner.normal_out());
        let end1 = w0 - corner.dir_in * len; // far end of wall 1
        let end2 = w0 + corner.dir_out * len; // far end of wall 2
        let w = r + ae;
        let stock = Polygon::new(vec![end1, w0, end2, end2 + no * w, w0 + b * (w / s), end1 + ni * w])?;
        let out = 2.0 * r; // how far the rings run beyond the wall ends
        let p0 = w0 + b * (w / s);
        let previous_ring = vec![
            Segment::Line { start: end1 + ni * w - corner.dir_in * out, end: p0 },
            Segment::Line { start: p0, end: end2 + no * w + corner.dir_out * out },
        ];
        Ok(CornerScenario {
            corner,
            settings,
            stock,
            previous_ring,
            ring_start: end1 + ni * r - corner.dir_in * out,
            corner_point: w0 + b * (r / s),
            ring_end: end2 + no * r + corner.dir_out * out,
        })
    }
}

/// One corner trochoid circle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CornerCircle {
    /// Tool-centre circle (centre, radius R − r).
    pub tool_circle: Circle,
    /// Offset circle (the boundary it cuts), radius R.
    pub offset_radius: f64,
    /// Peak engagement predicted by the two-circle model after the previous circle (rad);
    /// `None` for a circle placed without a predecessor circle (the first one).
    pub predicted_max: Option<f64>,
    /// Bisection steps used to place it (0 when placed directly).
    pub steps: usize,
}

/// A planned corner: circles, the connected tool path and its cost.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CornerPlan {
    pub method: CornerMethod,
    /// Circles in machining order.
    pub circles: Vec<CornerCircle>,
    /// The moves of the whole ring piece (U leg, corner, V leg) at depth 0 (the program gives
    /// the depth), no entries (the piece starts in the ring before it), no retracts. Their
    /// kinds: U and V legs [`MoveKind::Ring`], circles, links along U, corner-point arcs with
    /// their moves, or Wu et al.'s [`MoveKind::Tip`].
    pub toolpath: Toolpath,
    /// Path length (mm).
    pub path_length_mm: f64,
    /// Machining time at the feed rate (s).
    pub time_s: f64,
    /// How the strategy was applied (fallbacks, readings).
    pub notes: Vec<String>,
    /// Material model the plan was made for (what an evaluator should measure it against):
    /// the stock polygon and the tool paths cut before.
    pub stock: Polygon,
    pub precut: Vec<Segment>,
    /// Indices of the moves of the way into the corner point (see [`super::acceptance`] for its
    /// stated engagement limit): the corner-point arcs with their moves along the walls, or
    /// Wu et al.'s final straight move into the tool corner point; `None` for the plain ring.
    pub tip_segments: Option<std::ops::Range<usize>>,
    /// The corner-point arcs, when the settings ask for them.
    pub corner_point: Option<CornerPointArcs>,
}

/// The arcs into the corner point (docs/corners.md): tangent to both walls (tool centre on U
/// and V), radii shrinking from the last circle's to the corner tolerance δ.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CornerPointArcs {
    /// Tool-centre radii of the arcs in machining order (mm); the last is δ.
    pub radii_mm: Vec<f64>,
    /// Material left on the bisector at the corner, δ(1/sin α − 1) (mm): the corner is cut to
    /// radius r + δ.
    pub residual_mm: f64,
    /// Largest radial depth an arc cuts on the bisector, (ρ_k − ρ_k+1)(1/sin α − 1) (mm).
    pub max_radial_depth_mm: f64,
}

/// Plan one corner with a strategy.
pub fn plan_corner(sc: &CornerScenario, method: CornerMethod) -> Result<CornerPlan, Error> {
    let s = sc.settings;
    let mut notes = Vec::new();
    if method == CornerMethod::MedialAxis {
        return medial_axis_plan(sc);
    }
    let (circles, leg_end) = match method {
        CornerMethod::Plain | CornerMethod::MedialAxis => (Vec::new(), None),
        CornerMethod::Variable => (variable_circles(sc)?, None),
        CornerMethod::Isometric => isometric_circles(sc, &mut notes)?,
    };
    let (mut moves, at) = ring_path(sc, &circles, leg_end);
    let (mut tip_segments, mut corner_point) = (None, None);
    match circles.last() {
        None => moves.push(Segment::Line { start: at, end: sc.ring_end }, MoveKind::Ring), // through U0
        Some(last) => {
            let start = moves.path.len();
            corner_point = into_corner_point(&mut moves, sc, last.tool_circle.radius, at, Some(sc.ring_end));
            tip_segments = Some(start..moves.path.len() - 1);
        }
    }
    let Moves { path, kinds } = moves;
    let len: f64 = path.iter().map(Segment::length).sum();
    Ok(CornerPlan {
        method,
        circles,
        toolpath: Toolpath::at_depth(&path, &kinds, 0.0, Vec::new(), Vec::new()),
        path_length_mm: len,
        time_s: len / s.feed_mm_per_min * 60.0,
        notes,
        stock: sc.stock.clone(),
        precut: sc.previous_ring.clone(),
        tip_segments,
        corner_point,
    })
}
