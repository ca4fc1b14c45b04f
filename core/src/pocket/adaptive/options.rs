//! The options of adaptive clearing, the default target engagement and the concave-cut step
//! every pass follows from (derivations in the module docs of [`super`] and
//! docs/adaptive-clearing.md).

use crate::corner::point::{DEFAULT_CORNER_TOLERANCE_MM, validate_corner_tolerance};
use crate::error::{Error, Param, num};
use crate::geom::bisect_edge;
use crate::job::Direction;
use crate::pocket::PocketSettings;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The options of adaptive clearing beyond [`PocketSettings`] (CLI names in brackets).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AdaptiveOptions {
    /// Helix radius of the tool centre r_h (mm) [`--helix-radius`]; `None`: 0.375·D, reduced
    /// down to 0.25·D (a bore of 50 % of D) where the pocket is narrower.
    pub helix_radius_mm: Option<f64>,
    /// Ramp angle of the helix (deg) [`--ramp-angle`], 0 < angle ≤ 15.
    pub ramp_deg: f64,
    /// Radial stock left for the finishing pass (mm) [`--finish-stock`]; 0: no finishing pass.
    pub finish_stock_mm: f64,
    /// Climb (counter-clockwise loops with M3) or conventional [`--direction`].
    pub direction: Direction,
    /// Depth the helix descends to below Z0 (mm) [`--depth`]: its length and time.
    pub depth_mm: f64,
    /// Engagement the passes are planned to (deg) [`--target-engagement`], from φ* of the
    /// step-over up to 90°; `None`: φ*.
    #[serde(default)]
    pub target_deg: Option<f64>,
    /// How near the finishing corner arcs reach each convex corner point (mm)
    /// [`--corner-tolerance`]: the last arc's tool-centre radius δ, the pocket corner then has
    /// radius r + δ ([`next_corner_point_radius`](crate::corner::point::next_corner_point_radius)).
    #[serde(default = "default_corner_tolerance")]
    pub corner_tolerance_mm: f64,
}

pub(super) fn default_corner_tolerance() -> f64 {
    DEFAULT_CORNER_TOLERANCE_MM
}

impl Default for AdaptiveOptions {
    /// Helix 0.375·D at 5°, 0.2 mm finishing stock, climb, the NC export's default depth of
    /// 6 mm. 5° is the upper end of the 2–5° that standard solid end mills take in ramping,
    /// set by their flutes and core (carbide-tooling.com, "Ramping Angle Calculator"), and
    /// FreeCAD's Adaptive's default helix ramp angle; a ramp deeper per turn than the tool
    /// takes is the user's `--ramp-angle` to lower.
    fn default() -> Self {
        AdaptiveOptions {
            helix_radius_mm: None,
            ramp_deg: 5.0,
            finish_stock_mm: 0.2,
            direction: Direction::Climb,
            depth_mm: 6.0,
            target_deg: None,
            corner_tolerance_mm: DEFAULT_CORNER_TOLERANCE_MM,
        }
    }
}

impl AdaptiveOptions {
    /// Range checks; errors name the flag and its range.
    pub fn validate(&self, settings: &PocketSettings) -> Result<(), Error> {
        let r = settings.tool_radius;
        if let Some(h) = self.helix_radius_mm
            && !(h.is_finite() && h > 0.0 && h <= 0.9 * r)
        {
            return Err(Error::param(
                Param::HelixRadius,
                h,
                format!("greater than 0 and at most 0.45 × D = {} mm", num(0.9 * r)),
            ));
        }
        if !(self.ramp_deg.is_finite() && self.ramp_deg > 0.0 && self.ramp_deg <= 15.0) {
            return Err(Error::param(Param::RampAngle, self.ramp_deg, "greater than 0 and at most 15 degrees"));
        }
        let s = self.finish_stock_mm;
        if !(s.is_finite() && (0.0..=settings.step_over).contains(&s)) {
            return Err(Error::param(
                Param::FinishStock,
                s,
                format!(
                    "from 0 to the step-over {} mm (its default is {} mm: with a step-over this fine give \
                     --finish-stock too)",
                    num(settings.step_over),
                    num(AdaptiveOptions::default().finish_stock_mm)
                ),
            ));
        }
        if !(self.depth_mm.is_finite() && self.depth_mm > 0.0 && self.depth_mm <= 1000.0) {
            return Err(Error::param(Param::Depth, self.depth_mm, "greater than 0 and at most 1000 mm"));
        }
        validate_corner_tolerance(self.corner_tolerance_mm)?;
        crate::pocket::entry::validate_descent(self, r)?;
        if let Some(t) = self.target_deg {
            let phi = crate::engagement::straight_engagement(settings.step_over, r)?.to_degrees();
            if !(t.is_finite() && t >= phi - 1e-9 && t <= 90.0) {
                return Err(Error::param(
                    Param::TargetEngagement,
                    t,
                    format!("from the step-over's straight engagement {}° to 90°", num(phi)),
                ));
            }
        }
        Ok(())
    }

    /// The engagement the passes are planned to (rad): the option, else
    /// [`default_target_rad`] of the step-over.
    pub fn target_rad(&self, settings: &PocketSettings) -> Result<f64, Error> {
        match self.target_deg {
            Some(t) => Ok(t.to_radians()),
            None => default_target_rad(settings.step_over, settings.tool_radius),
        }
    }
}

/// Ceiling of the default target engagement (deg), DECLARED: the limit we hold the 95th
/// percentile of a pocket's engagement to (docs/adaptive-clearing.md). Every kind of move is planned to the target and read
/// within it (up to the evaluator's overshoot at kinks), so the target bounds the percentile.
pub const DEFAULT_TARGET_CAP_DEG: f64 = 50.0;

/// The mean radial depth of a corner pass over its bisector depth, for a corner of interior
/// angle α (DERIVED): two consecutive arcs tangent to both walls, radii ρ and ρ − Δρ, enclose
/// the crescent (ρ² − (ρ − Δρ)²)·c, c = cot(α/2) − (π − α)/2 (the caps' difference), along an
/// arc of length (π − α)(ρ − Δρ), and are Δρ·k apart on the bisector, k = 1/sin(α/2) − 1; for
/// Δρ ≪ ρ the mean depth (area / length) over the bisector depth is 2c/((π − α)·k): 0.660 at
/// 90°.
pub fn corner_pass_mean_depth_ratio(alpha: f64) -> f64 {
    let half = 0.5 * alpha;
    let c = 1.0 / half.tan() - (PI - alpha) / 2.0;
    let k = 1.0 / half.sin() - 1.0;
    2.0 * c / ((PI - alpha) * k)
}

/// The default target engagement (rad) for step-over a_e and tool radius r. FreeCAD's Adaptive
/// reads a_e as an area rate: a_e mm² removed per mm of travel (its optimalCutAreaPD is
/// 2·f·r²/r = a_e for the step-over factor f = a_e/D). On a straight cut and on every concave
/// cut of our spiral the area rate a_e *is* the engagement φ* = arccos(1 − a_e/r) (the
/// concave-cut step a of radius ρ removes a(1 + r/ρ) − a²/(2ρ) per mm, which equals a_e
/// exactly where cos φ* = 1 − a/r − a/ρ + a²/(2ρr), module docs). Where a pass's depth tapers
/// to nothing at both ends — a corner pass, [`corner_pass_mean_depth_ratio`] — the same area
/// rate needs a deepest cut of a_e/m (m = 0.660 for the pocket's usual 90° corner), read as the
/// straight-cut engagement of that depth. The default plans every pass to that engagement,
/// never above [`DEFAULT_TARGET_CAP_DEG`] and never below φ*: for D = 10, a_e = 1.527 mm
/// (φ* = 46.0°) the area rate asks 57.5°, so the cap, 50°, is the target; for a_e = 0.5 mm
/// it is 32.0° (φ* 25.8°); from a_e ≈ 1.79 mm (φ* ≥ 50°) it is φ*.
pub fn default_target_rad(a_e: f64, r: f64) -> Result<f64, Error> {
    let phi_star = crate::engagement::straight_engagement(a_e, r)?;
    let deepest = a_e / corner_pass_mean_depth_ratio(0.5 * PI);
    let by_area = (1.0 - deepest / r).max(0.0).acos();
    Ok(by_area.min(DEFAULT_TARGET_CAP_DEG.to_radians()).max(phi_star))
}

/// The radial step a (mm) a concave cut of tool-centre radius ρ may take at engagement φ
/// (module docs): the smaller root of a²/(2ρr) − a(1/r + 1/ρ) + (1 − cos φ) = 0.
pub fn concave_step(rho: f64, r: f64, phi: f64) -> f64 {
    let k = 1.0 - phi.cos();
    let b = 1.0 / r + 1.0 / rho;
    let c2 = 1.0 / (2.0 * rho * r);
    let disc = (b * b - 4.0 * c2 * k).max(0.0);
    // a = (b − √disc)/(2·c2), written stably as 2k/(b + √disc).
    2.0 * k / (b + disc.sqrt())
}

/// ρ_fin: the concave step of radius ρ_fin + s_f reaches s_f.
pub(crate) fn fin_radius(sf: f64, r: f64, phi: f64) -> f64 {
    (bisect_edge(100.0 * r, 1e-6, 80, |rho| concave_step(rho, r, phi) >= sf) - sf).max(0.1 * r)
}
