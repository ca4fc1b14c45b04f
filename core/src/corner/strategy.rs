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

use super::geometry::Corner;
pub use super::limits::{MAX_TOOL_DIAMETER_MM, tool_diameter, validate_tool_and_step_over};
use super::method::CornerMethod;
use super::point::{corner_point_radii, validate_corner_tolerance};
use super::request::CornerRequest;
use crate::engagement::{Turn, TwoCircle, straight_engagement};
use crate::error::{Error, Param, num};
use crate::geom::{Circle, P2, Polygon, Segment};
use crate::toolpath::{MoveKind, Toolpath};
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

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
    /// ([`corner_point_radii`]); `None`: Wu et al.'s straight move into the tool corner point
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

/// Limit point M of the bisection (Wu et al. 2016 §4.2.1 step 1; derived in docs/corners.md):
/// `tM = (tN(1 − sin α) + 2r)/(1 + sin α)`, valid while `R_N = tN sin α > r`.
pub fn limit_point(t_n: f64, alpha: f64, r: f64) -> f64 {
    let s = alpha.sin();
    (t_n * (1.0 - s) + 2.0 * r) / (1.0 + s)
}

/// Metric m(t) of the bisection: peak two-circle engagement (Wu et al. 2016 eqs. 2–6) of the wall-tangent circle at
/// bisector parameter `t` after the one at `t_n` (eq. 24 with the engagement angle).
pub fn engagement_after(corner: &Corner, r: f64, t_n: f64, t: f64) -> f64 {
    let model = TwoCircle {
        previous: corner.wall_tangent_circle(t_n),
        current: corner.wall_tangent_circle(t),
        tool_radius: r,
        turn: Turn::Ccw,
    };
    model.max_engagement().angle
}

/// Result of one bisection (Wu et al. 2016 eqs. 23–24).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct NextCircle {
    /// Accepted bisector parameter t.
    pub t: f64,
    /// m(t) (rad).
    pub metric: f64,
    /// Bisection steps taken.
    pub steps: usize,
}

/// Next variable circle after the one at `t_n` by bisection on the bisector between `t_n`
/// (Z < 0: nothing left to cut) and the limit point `tM` (Wu et al. 2016 eqs. 23–24):
/// accept when `0 < Z ≤ ε` with `Z = m(t) − a*`; if `Z(tM) ≤ 0` take tM. After 60 steps the
/// low end (Z < 0, under the target) is taken.
pub fn next_variable_circle(corner: &Corner, r: f64, t_n: f64, target: f64, eps: f64) -> Result<NextCircle, Error> {
    let alpha = corner.half_angle;
    if t_n.is_nan() || t_n * alpha.sin() <= r {
        return Err(Error::geometry(
            "t_N",
            t_n,
            format!("> r / sin α = {} mm (the current circle must be larger than the tool)", num(r / alpha.sin())),
        ));
    }
    let t_m = limit_point(t_n, alpha, r);
    let m_m = engagement_after(corner, r, t_n, t_m);
    if m_m - target <= 0.0 {
        return Ok(NextCircle { t: t_m, metric: m_m, steps: 0 });
    }
    let (mut lo, mut hi) = (t_n, t_m); // Z(lo) < 0 (same circle), Z(hi) > 0
    for step in 1..=MAX_BISECTION {
        let t = 0.5 * (lo + hi);
        let m = engagement_after(corner, r, t_n, t);
        let z = m - target;
        if z > 0.0 && z <= eps {
            return Ok(NextCircle { t, metric: m, steps: step });
        }
        if z < 0.0 {
            lo = t;
        } else {
            hi = t;
        }
    }
    Ok(NextCircle { t: lo, metric: engagement_after(corner, r, t_n, lo), steps: MAX_BISECTION })
}

/// Variable circles from `t_start` towards the apex until the next tool-centre radius drops
/// below `r_min` (the stop rule of docs/corners.md). Returns the circles after the start circle.
fn variable_chain(sc: &CornerScenario, t_start: f64) -> Result<Vec<CornerCircle>, Error> {
    let (corner, s) = (&sc.corner, &sc.settings);
    let r = s.tool_radius;
    let mut out = Vec::new();
    let mut t = t_start;
    while t * corner.half_angle.sin() - r >= s.r_min() {
        let next = next_variable_circle(corner, r, t, s.target, s.tolerance)?;
        let big_r = next.t * corner.half_angle.sin();
        if big_r - r < s.r_min() || next.t >= t {
            break;
        }
        out.push(CornerCircle {
            tool_circle: Circle::new(corner.on_bisector(next.t), big_r - r),
            offset_radius: big_r,
            predicted_max: Some(next.metric),
            steps: next.steps,
        });
        if out.len() > MAX_CIRCLES {
            return Err(Error::geometry("circles", out.len(), format!("at most {MAX_CIRCLES} per corner")));
        }
        t = next.t;
    }
    Ok(out)
}

/// Offset radius R1 of the first corner circle (DERIVED; the fragment only says c1 is "the
/// circle on the end position of the corner"). The previous ring cleared everything inside the
/// walls offset by a_e except the tip beyond its corner arc, so for a wall-tangent circle of
/// radius R the concentric circle of radius R − a_e (tangent to the offset walls, radius ≥ r)
/// is already cut. With that as the previous circle, the two-circle model's closed form gives
/// `cos a = ((R − a_e)² − ρ² − r²)/(2ρr)`, ρ = R − r; solving `a = a*` for R:
/// `R1 = (2r²(1 − cos a*) − a_e²) / (2r(cos a_str − cos a*))`, a_str = arccos(1 − a_e/r).
/// A concave circle cutting the full band of depth a_e always exceeds a_str (R1 → ∞ as
/// a* → a_str), so the target must exceed the straight-part engagement: Wu et al. use
/// a* = a_str·(1 + t1), t1 = 15 %.
pub fn first_circle_radius(s: &CornerSettings) -> Result<f64, Error> {
    let r = s.tool_radius;
    let a_str = straight_engagement(s.step_over, r)?;
    let (cs, ct) = (a_str.cos(), s.target.cos());
    let den = 2.0 * r * (cs - ct);
    if !(s.target > a_str + 1e-6 && den > 0.0) {
        return Err(Error::param(
            Param::Target,
            format!("{:.3}°", s.target.to_degrees()),
            format!(
                "greater than the straight-part engagement {:.3}° (corner circles cut the wall band concavely)",
                a_str.to_degrees()
            ),
        ));
    }
    let big_r = (2.0 * r * r * (1.0 - ct) - s.step_over * s.step_over) / den;
    // The concentric circle must be a real offset circle (radius ≥ r) for the argument above.
    Ok(big_r.max(r + s.step_over))
}

/// Bisector parameter of the first variable circle c1, checked against the wall length.
fn first_variable_t(sc: &CornerScenario) -> Result<f64, Error> {
    let big_r = first_circle_radius(&sc.settings)?;
    let t1 = sc.corner.t_for_radius(big_r);
    let along = t1 * sc.corner.half_angle.cos();
    let need = along + 2.0 * sc.settings.tool_radius;
    if need > sc.settings.edge_length {
        return Err(Error::param(
            Param::EdgeLength,
            sc.settings.edge_length,
            format!(
                "at least {need:.3} mm: the first corner circle (R = {big_r:.3} mm) touches the walls {along:.3} mm from the apex"
            ),
        ));
    }
    Ok(t1)
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

/// The way into the corner point after the last wall-tangent circle (tool-centre radius
/// `rho_last`, the tool at `at`, its tangent point on U), then along V to `end` if given.
/// With a corner tolerance δ: the corner-point arcs of [`corner_point_radii`] — per arc a move
/// along U to its tangent point, the arc (counter-clockwise through π − 2α) to its tangent
/// point on V and, but after the last, back on its chord (between the arc and the last circle,
/// cut) — so the tool never reaches U0 and the corner is cut to radius r + δ. Without: Wu et
/// al.'s straight move into U0. The last move (along V) is not part of the way in. Returns
/// the arcs, if any.
fn into_corner_point(
    moves: &mut Moves,
    sc: &CornerScenario,
    rho_last: f64,
    at: P2,
    end: Option<P2>,
) -> Option<CornerPointArcs> {
    let s = sc.settings;
    let Some(delta) = s.corner_tolerance else {
        moves.push(Segment::Line { start: at, end: sc.corner_point }, MoveKind::Tip);
        if let Some(e) = end {
            moves.push(Segment::Line { start: sc.corner_point, end: e }, MoveKind::Ring);
        }
        return None;
    };
    let (corner, r) = (&sc.corner, s.tool_radius);
    let (n_in, n_out, alpha) = (corner.normal_in(), corner.normal_out(), corner.half_angle);
    let radii = corner_point_radii(rho_last, 2.0 * alpha, r, s.target, delta, MAX_CIRCLES);
    let k = 1.0 / alpha.sin() - 1.0;
    let (mut here, mut rho, mut deepest) = (at, rho_last, 0.0_f64);
    for (i, &next) in radii.iter().enumerate() {
        let o = corner.on_bisector(corner.t_for_radius(next + r));
        let (a, e) = (o - n_in * next, o - n_out * next);
        if (a - here).norm() > 1e-12 {
            moves.push(Segment::Line { start: here, end: a }, MoveKind::CornerPoint);
        }
        let dir = a - o;
        let arc = Segment::Arc { center: o, radius: next, start_angle: dir.y.atan2(dir.x), sweep: PI - 2.0 * alpha };
        moves.push(arc, MoveKind::CornerPoint);
        here = if i + 1 < radii.len() {
            moves.push(Segment::Line { start: e, end: a }, MoveKind::CornerPoint);
            a
        } else {
            e
        };
        deepest = deepest.max((rho - next) * k);
        rho = next;
    }
    if let Some(e) = end {
        moves.push(Segment::Line { start: here, end: e }, MoveKind::Ring);
    }
    Some(CornerPointArcs { residual_mm: rho * k, max_radial_depth_mm: deepest, radii_mm: radii })
}

/// Perforative trochoids along the medial axis (Wu et al. 2016 §4.2 (c); docs/pockets.md) for the
/// corner as part of a triangular pocket (apex, ends of the two walls). The axis comes from
/// [`crate::geom::medial::medial_axis`]; the corner's branch runs from the apex to the first Voronoi
/// node, whose clearance Rc is the largest circle there. The perforative trochoids that reached
/// the node along the rest of the axis have cleared that circle (modelled as concentric passes,
/// `precut`); from it, circles of offset radius Rc(t) = t·sin α (allowance 0) are placed down
/// the branch by the variable-circle bisection (the axis as guide; docs/pockets.md), linked
/// along U, and the tool finishes at the tool corner point. With no contour-parallel ring here the
/// two-circle model's "material everywhere outside the previous circle" is exact.
fn medial_axis_plan(sc: &CornerScenario) -> Result<CornerPlan, Error> {
    let s = sc.settings;
    let (r, corner) = (s.tool_radius, &sc.corner);
    let end1 = corner.apex - corner.dir_in * s.edge_length;
    let end2 = corner.apex + corner.dir_out * s.edge_length;
    let pocket = Polygon::new(vec![end1, corner.apex, end2])?;
    let axis = crate::geom::medial::medial_axis(&pocket, 1e-4)?;
    let (node, rc) = axis.branch_from(corner.apex, 1e-3).ok_or_else(|| {
        Error::geometry("polygon", "no medial-axis branch at the corner", "a corner with a Voronoi branch")
    })?;
    if rc - r < s.r_min() {
        return Err(Error::param(
            Param::EdgeLength,
            s.edge_length,
            format!(
                "long enough that the largest circle in the pocket (radius {rc:.3} mm) exceeds the tool radius by r_min = {} mm",
                num(s.r_min())
            ),
        ));
    }
    let t_node = (node - corner.apex).dot(&corner.bisector);
    let mut circles =
        vec![CornerCircle { tool_circle: Circle::new(node, rc - r), offset_radius: rc, predicted_max: None, steps: 0 }];
    circles.extend(variable_chain(sc, t_node)?);
    // Concentric passes clearing the node circle (tool-centre radii rc − r, rc − 2.5r, …).
    let mut precut = Vec::new();
    let mut rho = rc - r;
    while rho > 0.0 {
        precut.push(Segment::Arc { center: node, radius: rho, start_angle: 0.0, sweep: TAU });
        rho -= 1.5 * r;
    }
    precut.push(Segment::Line { start: node, end: node + corner.bisector * 1e-3 });
    let mut moves = Moves::default();
    let at = circles_along_u(&mut moves, corner, &circles[1..], node - corner.normal_in() * (rc - r));
    let rho_last = circles.last().map_or(rc - r, |c| c.tool_circle.radius);
    let start = moves.path.len();
    let corner_point = into_corner_point(&mut moves, sc, rho_last, at, None);
    let tip_segments = Some(start..moves.path.len());
    let Moves { path, kinds } = moves;
    let len: f64 = path.iter().map(Segment::length).sum();
    let notes = vec![format!(
        "medial axis (boostvoronoi) of the triangular pocket: corner branch to the node at {:.3} mm from the apex, clearance {rc:.3} mm; {} circles down the branch",
        t_node,
        circles.len() - 1
    )];
    Ok(CornerPlan {
        method: CornerMethod::MedialAxis,
        circles,
        toolpath: Toolpath::at_depth(&path, &kinds, 0.0, Vec::new(), Vec::new()),
        path_length_mm: len,
        time_s: len / s.feed_mm_per_min * 60.0,
        notes,
        stock: pocket,
        precut,
        tip_segments,
        corner_point,
    })
}

/// Isometric circles (Wu et al. 2016 §4.2.2, eq. 25), our reading of Fig. 14a.
/// All circles have tool-centre radius rh (offset radius R = rh + r) and
/// centres on Up (U offset by rh), spaced at most `L = P(a*)` of docs/slot-paths.md with
/// `Rs = R`, which bounds the engagement of each circle after its predecessor (assuming
/// material everywhere outside it). The first circle is placed where it cuts nothing: the U
/// leg runs to X, one tool radius before the foot of the previous ring's corner P0 (where the
/// band ends and the corner material begins), and returns along U to the first circle, whose
/// disc then lies in the U leg's sweep and keeps a_e clear of wall 2. The circles march
/// towards the corner to the circle on the bisector (tangent to both walls); the tip beyond
/// it is finished by variable circles (Wu et al. 2016 §4.2.1) from there (noted), because one size of circle
/// cannot reach into the tip.
///
/// eq. 25: `rh1 = |PH1|/2 − r` with P the point of the previous corner arc PSQ farthest from
/// wall 1 (our reading); if `rh ≤ rh1` the Fig. 14b layout would be
/// needed and the variable method is used instead (noted).
fn isometric_circles(sc: &CornerScenario, notes: &mut Vec<String>) -> Result<(Vec<CornerCircle>, Option<P2>), Error> {
    let s = sc.settings;
    let (r, ae, corner) = (s.tool_radius, s.step_over, &sc.corner);
    let alpha = corner.half_angle;
    let (sin, tan) = (alpha.sin(), alpha.tan());
    let rh = s.rh();
    // eq. 25 threshold. P0 is r + a_e from both walls; the arc PSQ of radius r about P0 ends on
    // wall 2's band line at Q = P0 − r·n_out, its point farthest from wall 1.
    let p0 = corner.on_bisector((r + ae) / sin);
    let q = p0 - corner.normal_out() * r;
    let (l1, _) = corner.wall_lines()?;
    let rh1 = l1.distance_offset(q, 0.0) / 2.0 - r;
    if rh <= rh1 {
        notes.push(format!(
            "rh = {rh:.4} mm ≤ rh1 = {rh1:.4} mm (eq. 25): the isometric circles cannot cover the previous corner arc; Fig. 14b layout is not in the source, variable circles used"
        ));
        return Ok((variable_circles(sc)?, None));
    }
    let big_r = rh + r;
    let spacing = isometric_spacing(rh, r, s.target);
    if spacing.is_nan() || spacing <= 1e-6 {
        return Err(Error::param(
            Param::Target,
            format!("{}°", num(s.target.to_degrees())),
            "large enough for a positive isometric centre spacing",
        ));
    }
    // Along-wall coordinates measure distance from the apex along wall 1.
    let foot = (r + ae) / tan;
    let x_along = foot + r;
    let leg_end = corner.apex - corner.dir_in * x_along + corner.normal_in() * r;
    let o_bis = corner.on_bisector(big_r / sin);
    // First circle: its disc starts at X along wall 1 and stays a_e clear of wall 2.
    let u1 = (x_along + big_r - big_r / tan).max(ae / (2.0 * alpha).sin()).max(0.0);
    let first_along = big_r / tan + u1;
    if first_along + 2.0 * r > s.edge_length {
        return Err(Error::param(
            Param::EdgeLength,
            s.edge_length,
            format!(
                "at least {:.3} mm for isometric circles of rh = {} mm (the first touches wall 1 {first_along:.3} mm from the apex)",
                first_along + 2.0 * r,
                num(rh)
            ),
        ));
    }
    let n = (u1 / spacing).ceil() as usize;
    if n > MAX_CIRCLES {
        return Err(Error::geometry("circles", n, format!("at most {MAX_CIRCLES} per corner")));
    }
    let step = if n > 0 { u1 / n as f64 } else { 0.0 };
    let mut circles: Vec<CornerCircle> = Vec::with_capacity(n + 1);
    for k in 0..=n {
        let center = o_bis - corner.dir_in * (u1 - k as f64 * step);
        let predicted_max = circles.last().map(|prev| {
            TwoCircle {
                previous: Circle::new(prev.tool_circle.center, big_r),
                current: Circle::new(center, big_r),
                tool_radius: r,
                turn: Turn::Ccw,
            }
            .max_engagement()
            .angle
        });
        circles.push(CornerCircle {
            tool_circle: Circle::new(center, rh),
            offset_radius: big_r,
            predicted_max,
            steps: 0,
        });
    }
    notes.push(format!(
        "isometric: rh = {rh:.4} mm, rh1 = {rh1:.4} mm (eq. 25), {} circles spaced {step:.4} mm (≤ P(a*) = {spacing:.4} mm); U leg to {x_along:.3} mm from the apex, then back along U to the first circle",
        n + 1
    ));
    let tip = variable_chain(sc, big_r / sin)?;
    if !tip.is_empty() {
        notes.push(format!(
            "corner tip finished with {} variable circles (Wu et al. 2016 §4.2.1) after the bisector circle",
            tip.len()
        ));
    }
    circles.extend(tip);
    Ok((circles, Some(leg_end)))
}

/// Centre spacing of equal circles for a peak engagement `a` (derived in docs/slot-paths.md
/// from the two-circle model of Wu et al. 2016 with R1 = R2 = Rs = rh + r, ρ = rh): `P(a) = Rs − sqrt(ρ² + r² + 2ρr·cos a)`.
pub fn isometric_spacing(rh: f64, r: f64, a: f64) -> f64 {
    (rh + r) - (rh * rh + r * r + 2.0 * rh * r * a.cos()).max(0.0).sqrt()
}

/// Variable circles: c1 from [`first_circle_radius`], then the chain of [`next_variable_circle`].
fn variable_circles(sc: &CornerScenario) -> Result<Vec<CornerCircle>, Error> {
    let t1 = first_variable_t(sc)?;
    let sin = sc.corner.half_angle.sin();
    let r = sc.settings.tool_radius;
    let mut c = vec![CornerCircle {
        tool_circle: Circle::new(sc.corner.on_bisector(t1), t1 * sin - r),
        offset_radius: t1 * sin,
        predicted_max: None,
        steps: 0,
    }];
    c.extend(variable_chain(sc, t1)?);
    Ok(c)
}

/// The ring piece up to the corner's way in: U leg to the first circle's tangent point on U (or
/// to `leg_end` and back along U to it), then [`circles_along_u`].
fn ring_path(sc: &CornerScenario, circles: &[CornerCircle], leg_end: Option<P2>) -> (Moves, P2) {
    let mut moves = Moves::default();
    let first = circles
        .first()
        .map_or(sc.corner_point, |c| c.tool_circle.center - sc.corner.normal_in() * c.tool_circle.radius);
    let at = match leg_end {
        Some(x) => {
            moves.push(Segment::Line { start: sc.ring_start, end: x }, MoveKind::Ring);
            x
        }
        None => {
            moves.push(Segment::Line { start: sc.ring_start, end: first }, MoveKind::Ring);
            first
        }
    };
    let at = circles_along_u(&mut moves, &sc.corner, circles, at);
    (moves, at)
}

/// Each circle once round (CCW) from its tangent point on U, linked by straight moves along U
/// from `at`; returns where the tool ends (the last circle's tangent point).
fn circles_along_u(moves: &mut Moves, corner: &Corner, circles: &[CornerCircle], mut at: P2) -> P2 {
    let n_in = corner.normal_in();
    for c in circles {
        let (o, rho) = (c.tool_circle.center, c.tool_circle.radius);
        let tangent = o - n_in * rho; // point of the tool circle on U
        if (tangent - at).norm() > 1e-12 {
            moves.push(Segment::Line { start: at, end: tangent }, MoveKind::Link);
        }
        let dir = tangent - o;
        moves.push(
            Segment::Arc { center: o, radius: rho, start_angle: dir.y.atan2(dir.x), sweep: TAU },
            MoveKind::Circle,
        );
        at = tangent;
    }
    at
}

/// A corner path under construction: the moves and what each does.
#[derive(Default)]
struct Moves {
    path: Vec<Segment>,
    kinds: Vec<MoveKind>,
}

impl Moves {
    fn push(&mut self, seg: Segment, kind: MoveKind) {
        self.path.push(seg);
        self.kinds.push(kind);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn deg(x: f64) -> f64 {
        x.to_degrees()
    }

    #[test]
    fn variable_circle_worked_example() {
        // Worked example of docs/corners.md: α = 30°, r = 5, tN = 30 (RN = 15), a* = 46°, ε = 0.5°.
        let corner = Corner::symmetric(60f64.to_radians()).unwrap();
        let r = 5.0;
        let t_m = limit_point(30.0, corner.half_angle, r);
        assert!((t_m - 16.6667).abs() < 1e-4, "tM = {t_m}");
        for (t, want) in [(29.0, 31.788), (27.0, 56.633), (25.0, 75.522), (20.0, 120.0)] {
            let m = deg(engagement_after(&corner, r, 30.0, t));
            assert!((m - want).abs() < 1e-3, "m({t}) = {m}, want {want}");
        }
        // m(tM): a 0.05° scan reads 162.844° (docs/corners.md: 162.8°); the peak is a kink at the entry point E,
        // so refinement can only raise it. An independent dense scan (2·10⁶ points) gives
        // 162.8538° at φ = 84.26°; the closed form (first case) would say 180°.
        let m = deg(engagement_after(&corner, r, 30.0, t_m));
        assert!((162.844..162.844 + 0.02).contains(&m), "m(tM) = {m}");
        let closed = TwoCircle {
            previous: corner.wall_tangent_circle(30.0),
            current: corner.wall_tangent_circle(t_m),
            tool_radius: r,
            turn: Turn::Ccw,
        }
        .closed_form_max();
        assert!((deg(closed) - 180.0).abs() < 1e-4, "closed form {}", deg(closed)); // acos near −1: ill-conditioned
        let next = next_variable_circle(&corner, r, 30.0, 46f64.to_radians(), 0.5f64.to_radians()).unwrap();
        assert!((next.t - 27.9427).abs() < 1e-4, "t = {}", next.t);
        assert_eq!(next.steps, 9);
        assert!((deg(next.metric) - 46.0 - 0.258).abs() < 1e-3, "Z = {}", deg(next.metric) - 46.0);
        let big_r = next.t * 0.5;
        assert!((big_r - 13.9714).abs() < 1e-4 && (big_r - r - 8.9714).abs() < 1e-4);
    }

    #[test]
    fn variable_circle_sequence_worked_example() {
        // The chain of docs/corners.md: R = 15, 13.971, 12.990, 12.054, 11.172, 10.336, 9.572, 8.869, 8.245.
        let corner = Corner::symmetric(60f64.to_radians()).unwrap();
        let mut t = 30.0;
        for want in [13.971, 12.990, 12.054, 11.172, 10.336, 9.572, 8.869, 8.245] {
            t = next_variable_circle(&corner, 5.0, t, 46f64.to_radians(), 0.5f64.to_radians()).unwrap().t;
            assert!((t * 0.5 - want).abs() < 1e-3, "R = {}, want {want}", t * 0.5);
        }
    }

    #[test]
    fn isometric_spacing_worked_example() {
        // docs/corners.md: rh = 5, r = 5 (Rs = 10), a_lim = 46° → L = 0.7950 mm; docs/slot-paths.md
        // (same relation): P(30°) = 0.3407, P(60°) = 1.3397; D = 12 (r = 6, rh = 4): 0.7618.
        for (rh, r, a, want) in
            [(5.0, 5.0, 46.0, 0.7950), (5.0, 5.0, 30.0, 0.3407), (5.0, 5.0, 60.0, 1.3397), (4.0, 6.0, 46.0, 0.7618)]
        {
            let l = isometric_spacing(rh, r, f64::to_radians(a));
            assert!((l - want).abs() < 1e-4, "L({rh}, {r}, {a}°) = {l}, want {want}");
            // Independent check: two equal circles that far apart peak at exactly a (two-circle model, scanned).
            let m = TwoCircle {
                previous: Circle::new(crate::geom::p2(0.0, 0.0), rh + r),
                current: Circle::new(crate::geom::p2(l, 0.0), rh + r),
                tool_radius: r,
                turn: Turn::Ccw,
            };
            assert!((m.max_engagement().angle.to_degrees() - a).abs() < 1e-3);
        }
    }

    #[test]
    fn paths_are_connected_and_circles_shrink_towards_the_apex() {
        let settings =
            CornerSettings::new(5.0, crate::corner::radial_depth_for_engagement(46f64.to_radians(), 5.0)).unwrap();
        for angle in [30.0f64, 90.0, 150.0] {
            let sc = CornerScenario::new(Corner::symmetric(angle.to_radians()).unwrap(), settings).unwrap();
            for m in [CornerMethod::Plain, CornerMethod::Variable, CornerMethod::Isometric] {
                let p = plan_corner(&sc, m).unwrap();
                let path = p.toolpath.segments();
                for w in path.windows(2) {
                    assert!((w[0].end() - w[1].start()).norm() < 1e-9, "{angle}° {m:?}: gap");
                }
                assert!((path[0].start() - sc.ring_start).norm() < 1e-12);
                assert!((path.last().unwrap().end() - sc.ring_end).norm() < 1e-12);
                if m == CornerMethod::Variable {
                    for w in p.circles.windows(2) {
                        assert!(w[1].offset_radius < w[0].offset_radius, "{angle}°: radii must shrink");
                    }
                }
            }
        }
    }

    #[test]
    fn corner_point_arcs_touch_both_walls_and_shrink_to_the_tolerance() {
        let delta = 0.005;
        let base =
            CornerSettings::new(5.0, crate::corner::radial_depth_for_engagement(46f64.to_radians(), 5.0)).unwrap();
        let settings = CornerSettings { corner_tolerance: Some(delta), ..base };
        for angle in [30.0f64, 60.0, 90.0, 120.0, 150.0] {
            let sc = CornerScenario::new(Corner::symmetric(angle.to_radians()).unwrap(), settings).unwrap();
            let (l1, l2) = sc.corner.wall_lines().unwrap();
            for m in [CornerMethod::Variable, CornerMethod::Isometric, CornerMethod::MedialAxis] {
                let p = plan_corner(&sc, m).unwrap();
                let arcs = p.corner_point.as_ref().expect("corner-point arcs");
                let radii = &arcs.radii_mm;
                assert_eq!(*radii.last().unwrap(), delta, "{angle}° {m:?}: ends at δ");
                assert!(radii.windows(2).all(|w| w[1] < w[0]), "{angle}° {m:?}: radii shrink");
                assert!(radii[0] < p.circles.last().unwrap().tool_circle.radius);
                for w in p.toolpath.segments().windows(2) {
                    assert!((w[0].end() - w[1].start()).norm() < 1e-9, "{angle}° {m:?}: gap");
                }
                // Every corner-point arc: its tool envelope (radius ρ + r) touches both walls,
                // it turns through π − angle, and no tool position comes nearer than r to a wall.
                let tip = p.tip_segments.clone().expect("tip range");
                let mut seen = 0;
                for mv in &p.toolpath.moves[tip] {
                    let (seg, kind) = (&mv.segment, &mv.kind);
                    assert_eq!(*kind, MoveKind::CornerPoint);
                    if let Segment::Arc { center, radius, sweep, .. } = *seg {
                        let want = radius + 5.0;
                        assert!((l1.distance_offset(center, 0.0) - want).abs() < 1e-9, "{angle}° wall 1");
                        assert!((l2.distance_offset(center, 0.0) - want).abs() < 1e-9, "{angle}° wall 2");
                        assert!((sweep - (PI - angle.to_radians())).abs() < 1e-12);
                        assert_eq!(radius, radii[seen]);
                        seen += 1;
                    }
                    for q in [seg.start(), seg.end(), seg.point(0.5)] {
                        let d = l1.distance_offset(q, 0.0).min(l2.distance_offset(q, 0.0));
                        assert!(d >= 5.0 - 1e-9, "{angle}° {m:?}: {d} from a wall");
                    }
                }
                assert_eq!(seen, radii.len());
                // residual on the bisector: δ(1/sin α − 1)
                let k = 1.0 / sc.corner.half_angle.sin() - 1.0;
                assert!((arcs.residual_mm - delta * k).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn bad_settings_are_named() {
        let ok = CornerSettings::new(5.0, 1.5).unwrap();
        for (s, name) in [
            (CornerSettings { step_over: 10.0, ..ok }, "step-over"),
            (CornerSettings { step_over: f64::NAN, ..ok }, "step-over"),
            (CornerSettings { tool_radius: -1.0, ..ok }, "tool-diameter"),
            (CornerSettings { target: 0.0, ..ok }, "target"),
            (CornerSettings { feed_mm_per_min: 0.0, ..ok }, "feed"),
            (CornerSettings { edge_length: 5.0, ..ok }, "edge-length"),
            (CornerSettings { corner_tolerance: Some(0.0), ..ok }, "corner-tolerance"),
            (CornerSettings { corner_tolerance: Some(f64::NAN), ..ok }, "corner-tolerance"),
        ] {
            assert_eq!(s.validate().unwrap_err().subject(), Some(name));
        }
        // Target not above the straight-part engagement: no first circle exists.
        let flat = CornerSettings { target: straight_engagement(1.5, 5.0).unwrap(), ..ok };
        assert_eq!(first_circle_radius(&flat).unwrap_err().subject(), Some("target"));
        // A 5° corner with 100 mm walls cannot be entered by a 10 mm tool.
        let e = CornerScenario::new(Corner::symmetric(5f64.to_radians()).unwrap(), ok).unwrap_err();
        assert_eq!(e.subject(), Some("angle"), "{e}");
    }
}
