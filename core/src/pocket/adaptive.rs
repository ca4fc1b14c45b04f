//! Adaptive pocket clearing (docs/adaptive-clearing.md): helix entry, a spiral out of the bore, rings that
//! grow along the pocket's core, thinning passes into every convex corner and a finishing
//! contour — every move at depth measured by the independent evaluator
//! ([`crate::engagement::evaluator`]). The algorithm is ours (DERIVED below); its engagement model
//! is the straight cut and the two-circle model of Wu et al. 2016 (docs/corners.md).
//!
//! Notation: `r` tool radius, `a_e` the step-over, φ* = arccos(1 − a_e/r) its straight-cut
//! engagement, φ the target every pass is planned to (the steps below all follow from
//! it): `--target-engagement`, by default [`default_target_rad`] — a_e read as FreeCAD reads
//! it, an area rate, capped at 50° (50° for a_e = 1.527 mm, D = 10) — `C` the
//! region of tool centres = the pocket offset inward by r + s_f (s_f the finishing stock).
//!
//! **Concave-cut step (DERIVED).** A tool centre on a circle of radius ρ that cuts outward from
//! a disc already cleared to radius R = ρ_prev + r sees material where its periphery is farther
//! than R from the centre; the periphery point at angle ψ from the outward normal is at
//! distance² ρ² + r² + 2ρr·cos ψ, and the front half of the periphery is engaged over
//! ψ ≤ arccos((R² − ρ² − r²)/(2ρr)). With R = ρ + r − a (a radial step a) this reads
//! `cos φ = 1 − a/r − a/ρ + a²/(2ρr)`, which tends to the straight cut's 1 − a/r for ρ → ∞. Solved for a
//! at φ = φ* it gives [`concave_step`], the step a circle (or a corner arc) of radius ρ may
//! take; it is below a_e for every finite ρ.
//!
//! 1. **Entry.** A helix of radius r_h (default 0.375·D: a bore of 75 % of D, the helix of
//!    FreeCAD's Adaptive for D = 10) and ramp angle ≤ 3° about the point `k0` of largest
//!    clearance of `C` (bisection on inward offsets), from 0.5 mm above the stock top down to
//!    depth, then one flat turn at depth. The evaluator treats the bore as cut (the helix
//!    circle is its `before` path): the tool descends into it on the ramp, never plunges.
//! 2. **Spiral.** Half-turns alternating between two ends, each from radius q_i to q_i+1
//!    (centre offset (q_i − q_i+1)/2, so the spiral is G1), joined by straight lines parallel
//!    to the axis below. Where the core C ⊖ q_f (q_f = 0.995 × the inscribed radius) is thin
//!    (all its vertices within half a concave-cut step of the line through k0 along its
//!    longest edge: a rectangle's core is a segment), the ends' centres travel along that axis
//!    once the radius passes q₂, reaching its ends at q_f: the spiral grows into the stadium
//!    (axis ⊕ q_f) = the rectangle's opening instead of a disc, and cuts along its whole
//!    length. A revolution moves an end's tip by Δq(1 + κ), κ = s_ext/(q_f − q₂), held to the
//!    concave-cut step of the radius; q₂ is the candidate (r_h + {0, ¼, ½, ¾}(q_f − r_h)) with
//!    the shortest spiral. Without an axis the ends coincide at k0: the spiral about k0.
//!    Ring 0 closes it once around the stadium (the circle about k0). Where the stadium is
//!    the last ring, ring 0 leaves out the end half-circle the spiral ended on (the last
//!    half-turn left a crescent at most Δ thick there, the gap between the two circles); the
//!    corner passes at that end start Δ/k further out (below) and cut it.
//! 3. **Rings.** The core K = C ⊖ T (inward offset): for T just below the inscribed radius, K
//!    is a thin strip along the pocket's middle. Ring j is the boundary of (K ∩ D(k0, s_j)) ⊕ T,
//!    s_j growing by the concave-cut step of radius T: each ring is smooth (its corners are
//!    arcs of radius ≥ T about K), lies a step outside the previous one (the offset of a set
//!    that grew by at most the step), runs along the walls where it meets them tangentially,
//!    and passes through the wall point q0 where the spiral ended, where consecutive rings
//!    join without a link into material. A ring inside the stadium (it adds less than a strip
//!    2 % of a step wide along its length) is not cut. The last ring is the opening of C with
//!    radius T. T starts at 0.995 × the inscribed radius and shrinks by 10 % until that opening
//!    leaves only the corner caps uncut (area check: a cap of a convex corner α is
//!    T²(cot(α/2) − (π − α)/2)). A ring is cut only where it adds to the previous one (its
//!    runs off the previous ring: the ends where the core grew); where every later ring adds
//!    at the same n ≥ 2 places (the ends of an L's arms), each place is cleared in turn, ring
//!    after ring, the tool crossing back through what the last run cleared ([`super::runs::cut_rings`]).
//! 4. **Corners.** Every convex corner V of C (angle α) is thinned by arcs tangent to both
//!    walls with radii ρ_k from T down to ρ_fin, centre V + b·ρ/sin(α/2) on the bisector b.
//!    Consecutive arcs are a distance (ρ_k − ρ_k+1)(1/sin(α/2) − 1) apart on the bisector and
//!    tangent to each other's walls; that distance is held to the concave-cut step of ρ_k+1.
//!    A pass is the arc from wall A to wall B, then a straight move back to wall A, nine
//!    tenths of the way from this arc's tangent point to the next one's (it cuts a little near
//!    its end: measured, within the target), and the last tenth along wall A into the next arc.
//!    The corners are taken in the loop's order from the one nearest the tool. These passes
//!    stop at ρ_fin, where the finishing arc of radius ρ_fin + s_f stays within the target.
//!    **Cusps** — convex corners of C where a wall is an arc about a reflex pocket vertex (a
//!    neck's mouth, a reflex vertex near a wall) — get the same passes from [`super::cusp`]:
//!    arcs tangent to both walls centred at the matching vertex of C ⊖ ρ, each crescent's
//!    deepest cut held to the concave-cut step, back on the chord and along the incoming wall
//!    into the next. Their caps count in T's area check like the corners' caps.
//! 5. **Finish.** With s_f > 0: the opening of the final wall offset with radius ρ_fin + s_f,
//!    concentric with the last corner arcs, once around (climb), entered on a quarter circle
//!    beside the straight wall nearest the tool.
//! 6. **Corner points.** At each convex corner the finishing pass, after its arc, cuts arcs
//!    tangent to both final walls with radii from [`next_corner_point_radius`] down to the
//!    corner tolerance δ (each arc within the target, derived there); the pocket corner is left
//!    with radius r + δ, δ(1/sin(α/2) − 1) on the bisector. Reaching V itself would read π − α
//!    ([`corner_point_bound_rad`]).
//!
//! **Open sides** ([`plan_adaptive_open`], `--open-edges`). Where an edge of the pocket has no
//! wall, the tool-centre region reaches past it (the pocket extended across it, far corners
//! rounded: no corner passes there) while the stock stays the pocket. The part starts outside
//! the stock instead of steps 1–2: the tool goes straight down where its disc is off the
//! material ([`Entry::Outside`]), and the rings of step 3 grow from the air by geodesic
//! dilation instead of about k0 ([`grown_rings`]); steps 4–6 follow at the closed corners.
//!
//! **Sampling error bound (DERIVED).** The evaluator measures at every segment end (kinks are
//! exact) and every h mm (`spacing`). Take two tool positions c, c' a distance δ apart along
//! the path. Material only shrinks, and the periphery point c' + r·e(θ) is c + r·e(θ) moved by
//! δ, so θ can be engaged at c' only if c + r·e(θ) lies within δ of the material at c, and
//! only if e(θ)·t ≥ −δ/(2r) (t the direction of motion; nearer than r to c is swept). Each end
//! of the engaged arc thus moves by at most
//! - δ/(r·sin β) where it lies on a boundary left by an earlier position c_p, to first order in
//!   δ; β = 2·arcsin(|c − c_p|/(2r)) is the angle at which the two circles cross (β = φ on a
//!   straight cut at engagement φ);
//! - δ/(2r) + κ·δ where it is the edge of the front half (κ the path's curvature: the front
//!   half turns with the direction).
//!
//! A peak between two samples h apart lies within h/2 of one of them, so the reported maximum
//! misses at most ε = (h/2)·(1/(r·sin β) + 1/(2r) + κ). With r = 5, β ≈ φ ≈ 50° and the default
//! h = 0.25 mm: ε ≤ 4.5° where the path's radius is ≥ 3.75 mm (spiral, stadium, rings, the
//! first corner arcs), ≤ 0.9° at h = 0.05 mm; on the last corner arcs (radius ρ_fin ≈ 0.7 mm)
//! the κ term dominates (12° at 0.25 mm, 2.5° at 0.05 mm). Measured: the rectangle's peak at
//! h = 0.05 mm equals the one at 0.25 mm within 0.01° (`core/tests/adaptive_pocket.rs`), and
//! with every arc cut into pieces of h/r rad (the curvature term then h/(2r)) within 0.001°.
//!
//! Conventional milling mirrors the pocket in x, plans it, and mirrors the path back: every
//! loop then runs clockwise, with the same engagement by symmetry.

use super::PocketSettings;
use super::mirror::{mirror_segment, mirrored_polygon};
use super::path::PocketPath;
pub use crate::corner::point::{
    DEFAULT_CORNER_TOLERANCE_MM, corner_point_bound_rad, corner_point_radii, next_corner_point_radius,
    validate_corner_tolerance,
};
use crate::engagement::sample_owners;
use crate::error::{Error, Param, num};
use crate::geom::offset::{BoolOp, Region, largest};
use crate::geom::{P2, Polygon, Segment, bisect_edge, cross, p2};
use crate::job::Direction;
pub use crate::toolpath::HELIX_START_Z_MM;
use crate::toolpath::Toolpath;
use crate::toolpath::{Entry, Helix, MoveKind};
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

/// Most rings or corner passes per part (bounds run time on hostile input).
const MAX_PASSES: usize = 20_000;
/// Fractions of the inscribed radius the core radius T starts from (the shortest plan wins).
const CORE_FRACTIONS: [f64; 5] = [1.0, 0.85, 0.7, 0.55, 0.4];
/// Candidates q₂ = r_h + (j/N)(q_f − r_h), j < N, for the radius where the spiral's ends start
/// along the axis (the shortest spiral wins).
const SPIRAL_CANDIDATES: usize = 16;
/// How far along wall A, from one corner arc's start toward the next one's, the straight move
/// from the previous arc's end reaches (the rest is run along the wall into the arc).
const CORNER_CHORD_REACH: f64 = 0.9;
/// Bisection steps for the inscribed radius.
const INSCRIBED_STEPS: usize = 48;

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
    /// radius r + δ ([`next_corner_point_radius`]).
    #[serde(default = "default_corner_tolerance")]
    pub corner_tolerance_mm: f64,
}

fn default_corner_tolerance() -> f64 {
    DEFAULT_CORNER_TOLERANCE_MM
}

impl Default for AdaptiveOptions {
    /// Helix 0.375·D at 3° (a 3-flute carbide end mill's ramp), 0.2 mm finishing stock, climb,
    /// the NC export's default depth of 6 mm.
    fn default() -> Self {
        AdaptiveOptions {
            helix_radius_mm: None,
            ramp_deg: 3.0,
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
        super::entry::validate_descent(self, r)?;
        if let Some(t) = self.target_deg {
            let phi = crate::corner::straight_engagement(settings.step_over, r)?.to_degrees();
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
    let phi_star = crate::corner::straight_engagement(a_e, r)?;
    let deepest = a_e / corner_pass_mean_depth_ratio(0.5 * PI);
    let by_area = (1.0 - deepest / r).max(0.0).acos();
    Ok(by_area.min(DEFAULT_TARGET_CAP_DEG.to_radians()).max(phi_star))
}

/// One convex corner of a part, thinned by arcs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CornerPasses {
    /// The corner of the tool-centre region (mm).
    pub vertex: P2,
    /// Interior angle of the corner (rad).
    pub angle_rad: f64,
    /// Arcs cut, and the radius of the last (mm).
    pub passes: usize,
    pub last_radius_mm: f64,
    /// Largest radial depth a pass removes, on the bisector (mm).
    pub max_radial_depth_mm: f64,
    /// Largest engagement measured over the corner's passes (rad) and where.
    pub max_engagement_rad: f64,
    pub at: P2,
}

/// One convex corner point reached by the finishing pass's corner arcs (within δ).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CornerPoint {
    /// The corner of the final tool-centre region (the pocket offset by r) (mm).
    pub vertex: P2,
    /// Interior angle α of the corner (rad).
    pub angle_rad: f64,
    /// Arcs cut after the finishing arc, and the radius of the last, δ (mm).
    pub arcs: usize,
    pub last_radius_mm: f64,
    /// Material left on the corner's bisector, δ(1/sin(α/2) − 1) (mm).
    pub residual_mm: f64,
    /// Largest radial depth an arc removes, on the bisector (mm).
    pub max_radial_depth_mm: f64,
    /// Largest engagement over the arcs, their approach along the wall and their way out
    /// (rad), and where; h_max/f_z = sin of it (at most 1): the chip thickness per tooth feed.
    pub max_engagement_rad: f64,
    pub at: P2,
}

/// A connected region of tool centres, cleared from its own entry: a helix bore, a zig-zag
/// ramp where no helix fits, or straight down outside the stock beyond an open edge.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AdaptivePart {
    pub entry: Entry,
    /// Its moves at depth: `segments[range.0..range.1]` of the plan.
    pub first_segment: usize,
    pub end_segment: usize,
    /// Core radius T (mm) and rings cut.
    pub core_radius_mm: f64,
    pub rings: usize,
    pub corners: Vec<CornerPasses>,
    /// The corner points reached by the finishing pass (none without a finishing pass).
    #[serde(default)]
    pub corner_points: Vec<CornerPoint>,
}

/// A pocket cleared adaptively.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AdaptivePlan {
    /// The pocket, the settings, every move at depth in machining order (parts one after the
    /// other; a retract before each part but the first and before a link with no path at
    /// depth), the parts' entries, and the measurement with the helix and ramp bores counted as
    /// cut; links are the [`MoveKind::Link`] moves.
    pub path: PocketPath,
    /// The open edges of the polygon (edge i from vertex i to vertex i + 1): no wall there, the
    /// stock ends ([`plan_adaptive_open`]).
    #[serde(default)]
    pub open_edges: Vec<usize>,
    pub options: AdaptiveOptions,
    /// Target engagement φ* = arccos(1 − a_e/r) (rad).
    pub target_rad: f64,
    pub parts: Vec<AdaptivePart>,
    /// Radius of the pocket's convex corners as cut (mm): r + δ after the finishing pass's
    /// corner arcs, r + ρ_fin without a finishing pass ([`corner_point_bound_rad`]).
    pub corner_radius_left_mm: f64,
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

/// The closest point of a line or arc to `q`, and its local parameter.
pub(crate) fn closest_on(seg: &Segment, q: P2) -> (P2, f64) {
    match *seg {
        Segment::Line { start, end } => {
            let d = end - start;
            let t = if d.norm_squared() > 0.0 { ((q - start).dot(&d) / d.norm_squared()).clamp(0.0, 1.0) } else { 0.0 };
            (start + d * t, t)
        }
        Segment::Arc { start_angle, sweep, center, .. } => {
            let v = q - center;
            let ang = v.y.atan2(v.x);
            let rel =
                if sweep >= 0.0 { (ang - start_angle).rem_euclid(TAU) } else { (start_angle - ang).rem_euclid(TAU) };
            let t = if rel <= sweep.abs() {
                rel / sweep.abs()
            } else if (q - seg.start()).norm() <= (q - seg.end()).norm() {
                0.0
            } else {
                1.0
            };
            (seg.point(t), t)
        }
        Segment::Trochoid { .. } => (seg.start(), 0.0),
    }
}

/// The two pieces of a line or arc split at local parameter t.
pub(crate) fn split(seg: &Segment, t: f64) -> (Segment, Segment) {
    match *seg {
        Segment::Line { start, end } => {
            let m = seg.point(t);
            (Segment::Line { start, end: m }, Segment::Line { start: m, end })
        }
        Segment::Arc { center, radius, start_angle, sweep } => (
            Segment::Arc { center, radius, start_angle, sweep: sweep * t },
            Segment::Arc { center, radius, start_angle: start_angle + sweep * t, sweep: sweep * (1.0 - t) },
        ),
        other => (other, other),
    }
}

/// The closed loop re-started at its point nearest `q`.
fn start_near(lp: &[Segment], q: P2) -> Vec<Segment> {
    let (mut best, mut bt, mut bd) = (0, 0.0, f64::INFINITY);
    for (i, s) in lp.iter().enumerate() {
        let (p, t) = closest_on(s, q);
        if (p - q).norm() < bd {
            (best, bt, bd) = (i, t, (p - q).norm());
        }
    }
    let (head, tail) = split(&lp[best], bt);
    let mut out = Vec::with_capacity(lp.len() + 1);
    if tail.length() > 1e-9 {
        out.push(tail);
    }
    out.extend_from_slice(&lp[best + 1..]);
    out.extend_from_slice(&lp[..best]);
    if head.length() > 1e-9 {
        out.push(head);
    }
    out
}

/// The moves of one part being built.
pub(crate) struct Builder {
    pub(crate) segments: Vec<Segment>,
    pub(crate) kinds: Vec<MoveKind>,
    /// Corner-point radii already derived, by (α, ρ₀): the finishing pass is the same for every
    /// core fraction, so each sequence is computed once per region.
    pub(crate) radii: Vec<(f64, f64, Vec<f64>)>,
    /// The links' router (kept across the core fractions) and the moves reached by a retract.
    pub(crate) router: super::route::RouterCache,
    pub(crate) retracts: Vec<usize>,
}

impl Builder {
    pub(crate) fn push(&mut self, seg: Segment, kind: MoveKind) {
        if seg.length() > 1e-9 {
            self.segments.push(seg);
            self.kinds.push(kind);
        }
    }

    fn at(&self) -> P2 {
        self.segments.last().map_or(P2::zeros(), Segment::end)
    }

    fn line(&mut self, to: P2, kind: MoveKind) {
        let from = self.at();
        self.push(Segment::Line { start: from, end: to }, kind);
    }
}

/// A convex corner of a tool-centre loop between two lines.
struct Corner {
    vertex: P2,
    d_in: P2,
    d_out: P2,
    alpha: f64,
    len_in: f64,
    len_out: f64,
}

/// The loop with consecutive collinear lines joined (offsets keep the vertices where other
/// edges' offsets ended), so that a corner's walls are whole.
fn merged(lp: &[Segment]) -> Vec<Segment> {
    let mut out: Vec<Segment> = Vec::with_capacity(lp.len());
    for seg in lp {
        if let (Some(Segment::Line { start, end }), Segment::Line { end: e2, .. }) = (out.last().copied(), *seg)
            && cross((end - start).normalize(), (e2 - end).normalize()).abs() < 1e-9
            && (end - start).dot(&(e2 - end)) > 0.0
        {
            *out.last_mut().unwrap_or(&mut Segment::Line { start, end }) = Segment::Line { start, end: e2 };
            continue;
        }
        out.push(*seg);
    }
    if out.len() > 2
        && let (Segment::Line { start: s0, end: e0 }, Segment::Line { start: sl, end: el }) =
            (out[0], out[out.len() - 1])
        && cross((el - sl).normalize(), (e0 - s0).normalize()).abs() < 1e-9
        && (el - sl).dot(&(e0 - s0)) > 0.0
    {
        out[0] = Segment::Line { start: sl, end: e0 };
        out.pop();
    }
    out
}

fn convex_corners(lp: &[Segment]) -> Vec<Corner> {
    let lp = merged(lp);
    let n = lp.len();
    let mut out = Vec::new();
    for i in 0..n {
        let (a, b) = (&lp[i], &lp[(i + 1) % n]);
        let (Segment::Line { start: a0, end: v }, Segment::Line { end: b1, .. }) = (*a, *b) else { continue };
        let (d_in, d_out) = ((v - a0).normalize(), (b1 - v).normalize());
        let turn = cross(d_in, d_out).atan2(d_in.dot(&d_out));
        if turn > 1e-6 {
            out.push(Corner {
                vertex: v,
                d_in,
                d_out,
                alpha: PI - turn,
                len_in: (v - a0).norm(),
                len_out: (b1 - v).norm(),
            });
        }
    }
    out
}

impl Corner {
    /// Tangent points on the incoming and outgoing walls and the arc of radius ρ.
    fn arc(&self, rho: f64) -> (P2, P2, Segment) {
        let half = 0.5 * self.alpha;
        let l = rho / half.tan();
        let b = (self.d_out - self.d_in).normalize();
        let center = self.vertex + b * (rho / half.sin());
        let a = self.vertex - self.d_in * l;
        let e = self.vertex + self.d_out * l;
        let start_angle = (a.y - center.y).atan2(a.x - center.x);
        (a, e, Segment::Arc { center, radius: rho, start_angle, sweep: PI - self.alpha })
    }

    /// The corner whose walls are the tangents at the ends of a counter-clockwise arc of radius
    /// ρ (centre, start angle, sweep π − α): V lies ρ/sin(α/2) from the centre on the arc's
    /// middle radius. The walls' lengths are the arc's tangent lengths ρ/tan(α/2).
    fn of_arc(center: P2, rho: f64, start_angle: f64, sweep: f64) -> Corner {
        let alpha = PI - sweep;
        let half = 0.5 * alpha;
        let dir = |a: f64| p2(a.cos(), a.sin());
        let mid = dir(start_angle + 0.5 * sweep);
        let l = rho / half.tan();
        Corner {
            vertex: center + mid * (rho / half.sin()),
            d_in: crate::geom::rot90(dir(start_angle)),
            d_out: crate::geom::rot90(dir(start_angle + sweep)),
            alpha,
            len_in: l,
            len_out: l,
        }
    }

    /// Cap area between the corner and its arc of radius ρ.
    fn cap_area(&self, rho: f64) -> f64 {
        let half = 0.5 * self.alpha;
        rho * rho * (1.0 / half.tan() - (PI - self.alpha) / 2.0)
    }
}

/// Plan the adaptive clearing of `polygon`.
pub fn plan_adaptive(
    polygon: &Polygon,
    settings: PocketSettings,
    options: AdaptiveOptions,
) -> Result<AdaptivePlan, Error> {
    plan_adaptive_open(polygon, &[], settings, options)
}

/// Plan the adaptive clearing of `polygon` open on the edges `open_edges` (edge i runs from
/// vertex i to vertex i + 1 of the polygon as stored, counter-clockwise; none: a closed
/// pocket). The walls of an open edge do not constrain the tool: the tool-centre region
/// reaches beyond it ([`OPEN_REACH_FACTOR`]); the stock stays the polygon, so outside it is
/// air. The part that reaches an open edge starts there: straight down outside the stock
/// ([`Entry::Outside`]), then rings grown inward from what lies outside ([`grown_rings`]).
pub fn plan_adaptive_open(
    polygon: &Polygon,
    open_edges: &[usize],
    settings: PocketSettings,
    options: AdaptiveOptions,
) -> Result<AdaptivePlan, Error> {
    let (parts, b, corner_radius_left_mm) = plan_path(polygon, open_edges, &settings, &options)?;
    let phi = options.target_rad(&settings)?;
    let mut plan = measure(polygon.clone(), settings, options, phi, parts, b, corner_radius_left_mm)?;
    plan.open_edges = open_edges.to_vec();
    Ok(plan)
}

/// The parts, their moves at depth and kinds, and the corner radius left (mm).
pub type AdaptivePath = (Vec<AdaptivePart>, Vec<Segment>, Vec<MoveKind>, f64);

/// The moves of an adaptive plan without measuring them (what the speed bench times).
pub fn adaptive_path(
    polygon: &Polygon,
    settings: PocketSettings,
    options: AdaptiveOptions,
) -> Result<AdaptivePath, Error> {
    let (parts, b, left) = plan_path(polygon, &[], &settings, &options)?;
    Ok((parts, b.segments, b.kinds, left))
}

fn plan_path(
    polygon: &Polygon,
    open_edges: &[usize],
    settings: &PocketSettings,
    options: &AdaptiveOptions,
) -> Result<(Vec<AdaptivePart>, Builder, f64), Error> {
    let (settings, options) = (*settings, *options);
    settings.validate()?;
    options.validate(&settings)?;
    validate_open_edges(polygon, open_edges)?;
    let mirror = options.direction == Direction::Conventional;
    let work = if mirror { mirrored_polygon(polygon)? } else { polygon.clone() };
    // the open edges of `work`: the mirror image reverses the vertex order
    let n_v = polygon.vertices().len();
    let work_open: Vec<usize> = open_edges.iter().map(|&i| if mirror { (2 * n_v - 2 - i) % n_v } else { i }).collect();
    let r = settings.tool_radius;
    let phi = options.target_rad(&settings)?;
    let sf = options.finish_stock_mm;
    let outline = Region::polygon(work.vertices());
    let closed_regions = outline.offset(r + sf);
    if closed_regions.is_empty() {
        return Err(Error::param(
            Param::Polygon,
            "narrower than the tool",
            format!("room for a tool of D = {} mm plus the finishing stock", num(2.0 * r)),
        ));
    }
    // The finishing corner radius: the finishing arc of radius ρ_fin + s_f removes s_f
    // concentrically, within φ* (concave-cut step); at least r/10.
    let rho_fin = if sf > 0.0 { fin_radius(sf, r, phi) } else { 0.1 * r };
    let (mut parts, mut b) = if work_open.is_empty() {
        clear_regions(&closed_regions, &work, &settings, &options, phi, rho_fin, None)?
    } else {
        let open = OpenPocket::new(&work, &work_open, &closed_regions, r + sf)?;
        let regions = open.near.offset(r + sf);
        clear_regions(&regions, &open.near_polygon, &settings, &options, phi, rho_fin, Some(&open))?
    };
    if mirror {
        for s in &mut b.segments {
            *s = mirror_segment(s);
        }
        for p in &mut parts {
            p.entry = p.entry.mirrored();
            for c in &mut p.corners {
                c.vertex.x = -c.vertex.x;
            }
            for c in &mut p.corner_points {
                c.vertex.x = -c.vertex.x;
            }
        }
    }
    let left = if sf > 0.0 { r + options.corner_tolerance_mm } else { r + rho_fin };
    Ok((parts, b, left))
}

/// Entry, spiral, rings, corner passes down to `rho_fin` and (with a finishing stock) the
/// finishing pass of each region of tool centres of `work`, one part each: for each, the
/// shortest plan over the core fractions. Each region grows from its seed: outside the stock
/// where it reaches past an open edge of `open`, else a helix. Also the core of the ring
/// methods ([`super::rings::plan_ring_pocket`], closed: `open` = `None`).
pub(crate) fn clear_regions(
    regions: &[Region],
    work: &Polygon,
    settings: &PocketSettings,
    options: &AdaptiveOptions,
    phi: f64,
    rho_fin: f64,
    open: Option<&OpenPocket>,
) -> Result<(Vec<AdaptivePart>, Builder), Error> {
    let router =
        open.map_or_else(Default::default, |o| super::route::RouterCache::pinned(&o.far_polygon, settings.tool_radius));
    let mut b = Builder { segments: Vec::new(), kinds: Vec::new(), radii: Vec::new(), router, retracts: Vec::new() };
    let mut parts = Vec::new();
    for region in regions {
        // The core radius trades ring length against corner caps: plan with T starting at each
        // fraction of the inscribed radius and keep the shortest path (geometry only).
        let (mut inscribed_radius, k0) = inscribed(region);
        let seed = open.and_then(|o| o.seed_of(region)).unwrap_or(Seed::Helix);
        if let Seed::Outside { closed, .. } = &seed {
            inscribed_radius = inscribed(closed).0;
        }
        let mut best: Option<(f64, Builder, AdaptivePart)> = None;
        let mut last_err = None;
        let (mut radii, mut router) = (Vec::new(), std::mem::take(&mut b.router));
        for fraction in CORE_FRACTIONS {
            let (taken, routes) = (std::mem::take(&mut radii), std::mem::take(&mut router));
            let mut bb =
                Builder { segments: Vec::new(), kinds: Vec::new(), radii: taken, router: routes, retracts: Vec::new() };
            let planned = plan_part(
                region,
                (inscribed_radius, k0),
                work,
                settings,
                options,
                phi,
                rho_fin,
                fraction,
                &mut bb,
                &seed,
            );
            (radii, router) = (std::mem::take(&mut bb.radii), std::mem::take(&mut bb.router));
            match planned {
                Ok(part) => {
                    let len: f64 = bb.segments.iter().map(Segment::length).sum();
                    if best.as_ref().is_none_or(|(l, _, _)| len < *l) {
                        best = Some((len, bb, part));
                    }
                }
                Err(e) => last_err = Some(e),
            }
        }
        let Some((_, bb, part)) = best else {
            return Err(last_err.unwrap_or_else(|| Error::param(Param::Polygon, "no plan", "a pocket the tool fits")));
        };
        let first = b.segments.len();
        b.router = router;
        b.retracts.extend(bb.retracts.iter().map(|i| i + first));
        b.segments.extend(bb.segments);
        b.kinds.extend(bb.kinds);
        parts.push(AdaptivePart { first_segment: first, end_segment: b.segments.len(), ..part });
    }
    Ok((parts, b))
}

/// ρ_fin: the concave step of radius ρ_fin + s_f reaches s_f.
pub(crate) fn fin_radius(sf: f64, r: f64, phi: f64) -> f64 {
    (bisect_edge(100.0 * r, 1e-6, 80, |rho| concave_step(rho, r, phi) >= sf) - sf).max(0.1 * r)
}

/// Helix about k0, the spiral out of its bore into the stadium (ring 0) and the rings along the
/// core `core` = C ⊖ T (module docs, steps 1–3); the helix, the end ring 0 left to the corner
/// passes (its centre, the other end's, the gap) and the number of rings.
#[allow(clippy::too_many_arguments)]
fn spiral_and_rings(
    b: &mut Builder,
    region: &Region,
    core: &Region,
    (inscribed, k0): (f64, P2),
    polygon: &Polygon,
    (r, t, r_h, phi): (f64, f64, f64, f64),
    options: &AdaptiveOptions,
) -> (Helix, Option<(P2, P2, f64)>, usize) {
    // Wall point nearest k0: every ring passes within (inscribed − T) of it.
    let walls = region.segments();
    let foot = walls
        .iter()
        .map(|s| closest_on(s, k0).0)
        .min_by(|a, c| (a - k0).norm().total_cmp(&(c - k0).norm()))
        .unwrap_or(k0);
    let n_foot = if (foot - k0).norm() > 1e-9 { (foot - k0).normalize() } else { p2(1.0, 0.0) };
    // The first ring is the circle about k0 that (nearly) touches the nearest wall, at q0:
    // (K ∩ D(k0, s0)) ⊕ T with s0 = 0.995·R_in − T; every later ring contains it, so passes
    // within 0.005·R_in of q0, where consecutive rings are joined.
    let s0 = (0.995 * inscribed - t).max(0.0);
    let spiral_end = s0 + t;
    // Where the centres of the spiral's end half-turns may travel: along the axis of a thin
    // core C ⊖ q_f (q_f = spiral_end), so the spiral ends as the stadium of that axis.
    let axis = stadium_axis(region, spiral_end, k0, concave_step(spiral_end, r, phi)).filter(|&(u, _, _, w)| {
        // the stadium's side must meet a wall at k0, where the rings are joined (below)
        let m = crate::geom::rot90(u);
        let side = k0 + (if m.dot(&n_foot) >= 0.0 { m } else { -m }) * (spiral_end + w);
        walls.iter().map(|sg| (closest_on(sg, side).0 - side).norm()).fold(f64::INFINITY, f64::min)
            <= 0.005 * inscribed + 1e-9
    });
    let (u, s_plus, s_minus, w) = axis.unwrap_or((crate::geom::rot90(n_foot), 0.0, 0.0, 0.0));
    let spiral_end = spiral_end + w;
    let n = if axis.is_some() {
        let m = crate::geom::rot90(u);
        if m.dot(&n_foot) >= 0.0 { m } else { -m }
    } else {
        n_foot
    };
    // Spiral radii at half turns, r_h → q_f. The ends' centres start along the axis once the
    // radius passes q₂ and reach the axis' ends at q_f: a revolution then moves each end's
    // centre by κ·Δq (κ = s_ext/(q_f − q₂)), so the tip of an end steps Δq(1 + κ), held to
    // the concave-cut step of the radius. q₂ is the candidate with the shortest spiral.
    let s_ext = s_plus.max(s_minus);
    let radii = |q2: f64| {
        let kappa = s_ext / (spiral_end - q2).max(1e-9);
        let mut q = vec![r_h];
        while let Some(&last) = q.last() {
            if last >= spiral_end - 1e-9 || q.len() > MAX_PASSES {
                break;
            }
            let next = if last < q2 - 1e-9 {
                (last + 0.5 * concave_step(last, r, phi)).min(q2)
            } else {
                last + 0.5 * concave_step(last, r, phi) / (1.0 + kappa)
            };
            q.push(next.min(spiral_end));
        }
        q
    };
    let lambda_of = |q2: f64, qi: f64| ((qi - q2) / (spiral_end - q2).max(1e-9)).clamp(0.0, 1.0);
    let spiral_length = |q2: f64, q: &[f64]| -> f64 {
        q.windows(2).map(|w| 0.5 * PI * (w[0] + w[1]) + 2.0 * s_ext * lambda_of(q2, w[0])).sum()
    };
    let (q2, q) = (0..SPIRAL_CANDIDATES)
        .map(|j| r_h + (j as f64 / SPIRAL_CANDIDATES as f64) * (spiral_end - r_h))
        .map(|q2| (q2, radii(q2)))
        .min_by(|a, c| spiral_length(a.0, &a.1).total_cmp(&spiral_length(c.0, &c.1)))
        .unwrap_or((r_h, vec![r_h]));
    let halves = q.len() - 1;
    // The last half-turn ends on the side n (toward the nearest wall): e_last = −n.
    let e_of = |i: usize| if (halves - 1 - i).is_multiple_of(2) { -n } else { n };
    let theta0 = if halves > 0 { e_of(0).y.atan2(e_of(0).x) } else { n.y.atan2(n.x) };
    let helix =
        Helix { center: k0, radius: r_h, start_angle: theta0, sense: 1.0, ramp_rad: options.ramp_deg.to_radians() };
    b.push(helix.circle(), MoveKind::Entry);
    let mut last_half = None;
    for i in 0..halves {
        let e = e_of(i);
        // Centre of this end half-turn on the axis: its middle direction rot90(e) is ±u.
        let lambda = lambda_of(q2, q[i]);
        let ext = if crate::geom::rot90(e).dot(&u) > 0.0 { s_plus } else { -s_minus };
        let a = k0 + u * (lambda * ext);
        let start = a + e * q[i];
        b.line(start, MoveKind::Spiral);
        let seg = Segment::Arc {
            center: a + e * (0.5 * (q[i] - q[i + 1])),
            radius: 0.5 * (q[i] + q[i + 1]),
            start_angle: e.y.atan2(e.x),
            sweep: PI,
        };
        last_half = Some(seg);
        b.push(seg, MoveKind::Spiral);
    }
    // Ring 0 closes the spiral: the stadium of radius q_f about the axis (the circle about k0
    // where the core has no axis).
    let m = crate::geom::rot90(u);
    let (a_plus, a_minus) = (k0 + u * s_plus, k0 - u * s_minus);
    let ang = |v: P2| v.y.atan2(v.x);
    let stadium = [
        Segment::Line { start: a_minus - m * spiral_end, end: a_plus - m * spiral_end },
        Segment::Arc { center: a_plus, radius: spiral_end, start_angle: ang(-m), sweep: PI },
        Segment::Line { start: a_plus + m * spiral_end, end: a_minus + m * spiral_end },
        Segment::Arc { center: a_minus, radius: spiral_end, start_angle: ang(m), sweep: PI },
    ];
    let q0 = b.at();
    let mut ring0 = start_near(&stadium, q0);
    let cut = Region::with_bulges(&[
        (a_minus - m * spiral_end, 0.0),
        (a_plus - m * spiral_end, 1.0),
        (a_plus + m * spiral_end, 0.0),
        (a_minus + m * spiral_end, 1.0),
    ]);
    // Rings: (K ∩ D(k0, s)) ⊕ T a step apart, joined at the wall point q0 where the spiral
    // ended; a ring that adds to the stadium less area than a strip of 2 % of the step along
    // its whole length (it lies inside the stadium but for slivers) is not cut.
    let step = concave_step(t, r, phi);
    let reach = core.vertices().iter().map(|&v| (v - k0).norm()).fold(0.0, f64::max);
    let mut s = (s0 + step).min(reach);
    let (mut rings_cut, mut prev): (Vec<Vec<Segment>>, Option<Region>) = (Vec::new(), None);
    while s > s0 + 1e-9 && rings_cut.len() < MAX_PASSES {
        let grown = super::growth::grown(core, k0, s, reach, prev.as_ref(), step);
        let filled = grown.as_ref().is_none_or(|g| super::growth::fills(g, core));
        if let Some(o) = grown.as_ref().and_then(|g| largest(g.offset(-t))) {
            let outside: f64 = o.boolean(&cut, BoolOp::Not).iter().map(|p| p.area().abs()).sum();
            if outside >= 0.02 * step * o.path_length() {
                rings_cut.push(start_near(&o.segments(), q0));
            }
        }
        let stalled = prev.as_ref().zip(grown.as_ref()).is_some_and(|(p, g)| g.area() <= p.area() * (1.0 + 1e-9));
        if s >= reach && (filled || stalled) {
            break;
        }
        (s, prev) = ((s + step).min(reach), grown.or(prev));
    }
    // Where no ring follows the stadium, ring 0 stops before the end half-circle the spiral
    // ended on: that half-turn left a crescent from Δ = q_f − q_{n−1} at its start to 0 at its
    // end, which the corner passes at that end take with their first arc (started Δ/k further
    // out on the bisector, below), instead of a half-circle mostly in air and the link back.
    let mut trimmed = None;
    if axis.is_some() && rings_cut.is_empty() && halves >= 2 {
        // (the spiral's end may lie a short line before the stadium's half-circle ends)
        while ring0.last().is_some_and(|sg| matches!(sg, Segment::Line { .. }) && sg.length() < 0.1 * r) {
            ring0.pop();
        }
        if let (Some(&Segment::Arc { center, radius, .. }), Some(&Segment::Arc { center: c_h, radius: r_half, .. })) =
            (ring0.last(), last_half.as_ref())
        {
            ring0.pop();
            let other = if (center - a_plus).norm() < (center - a_minus).norm() { a_minus } else { a_plus };
            // the gap between this half-circle and the spiral's last half-turn, at most
            trimmed = Some((center, other, radius - r_half + (center - c_h).norm()));
        }
    }
    for seg in ring0 {
        b.push(seg, MoveKind::Ring);
    }
    let rings = 1 + rings_cut.len();
    super::runs::cut_rings(b, polygon, r, &stadium, rings_cut);
    (helix, trimmed, rings)
}

/// Entry, spiral, rings and corners of one region of tool centres; the finishing pass.
#[allow(clippy::too_many_arguments)]
fn plan_part(
    region: &Region,
    (inscribed, k0): (f64, P2),
    polygon: &Polygon,
    settings: &PocketSettings,
    options: &AdaptiveOptions,
    phi: f64,
    rho_fin: f64,
    fraction: f64,
    b: &mut Builder,
    seed: &Seed<'_>,
) -> Result<AdaptivePart, Error> {
    let r = settings.tool_radius;
    // The least core radius: the helix radius; from outside a share of the inscribed radius.
    let r_h = match seed {
        Seed::Helix => super::entry::helix_radius(options, r, inscribed)?,
        _ => MIN_CORE_SHARE * inscribed,
    };
    // Open: T is chosen on the closed pocket's region (the open one reaches far past the edges).
    let t_region = match seed {
        Seed::Outside { closed, .. } => closed,
        _ => region,
    };
    let area = t_region.area();
    let corners_all = convex_corners(&region.segments());
    let t_corners = match seed {
        Seed::Outside { .. } => convex_corners(&t_region.segments()),
        _ => Vec::new(),
    };
    let t_corners = if t_corners.is_empty() { &corners_all } else { &t_corners };
    let sf = options.finish_stock_mm;
    let cusps_all = super::cusp::cusps(&region.segments(), polygon, r + sf, sf);
    let open_cusps;
    let t_cusps = match seed {
        Seed::Outside { .. } => {
            open_cusps = super::cusp::cusps(&t_region.segments(), polygon, r + sf, sf);
            &open_cusps
        }
        _ => &cusps_all,
    };
    // Core radius T: the largest (from 0.995 × the inscribed radius, −10 % a step) whose
    // opening of the region leaves only the corner caps.
    let mut t = 0.995 * fraction * inscribed;
    let core = loop {
        if t < r_h {
            t = r_h;
        }
        let ks = t_region.offset(t);
        if ks.len() == 1
            && let Some(opened) = largest(ks[0].offset(-t))
        {
            let caps: f64 = t_corners.iter().map(|c| c.cap_area(t)).sum::<f64>()
                + t_cusps.iter().map(|c| c.cap_area(t)).sum::<f64>();
            // the corner passes start from the opening's arc of radius T: it must fit the walls
            let fits = t_corners.iter().all(|c| t <= c.len_in.min(c.len_out) * (0.5 * c.alpha).tan() + 1e-9)
                && t_cusps.iter().all(|c| t <= c.rho_max + 1e-9);
            if (fits && area - opened.area() <= caps + 1e-3 * area) || t <= r_h {
                break ks.into_iter().next();
            }
        }
        if t <= r_h {
            break None;
        }
        t *= 0.9;
    };
    let Some(core) = core else {
        return Err(Error::param(
            Param::Polygon,
            "a region whose core does not hold the helix",
            "a pocket whose tool-centre region is one piece at least the helix radius wide",
        ));
    };
    let (entry, trimmed, rings) = match seed {
        Seed::Helix => {
            let (helix, trimmed, rings) =
                spiral_and_rings(b, region, &core, (inscribed, k0), polygon, (r, t, r_h, phi), options);
            (Entry::Helix(helix), trimmed, rings)
        }
        Seed::Outside { stock, grow, .. } => {
            let grow_core = largest(grow.offset(t)).ok_or_else(|| {
                Error::param(Param::OpenEdges, "no core beyond the open edges", "open edges at least D long")
            })?;
            let (rings, at) = grown_rings(b, polygon, r, &grow_core, t, phi, k0, stock)?;
            (Entry::Outside { at }, None, rings)
        }
    };
    // Corners: the caps between the opening (radius T) and ρ_fin.
    // The first corner pass's radius: T, or Δ/k more at the end whose half-circle ring 0 left.
    let first_radius = |c: &Corner| {
        let k = 1.0 / (0.5 * c.alpha).sin() - 1.0;
        let extra = match trimmed {
            Some((end, other, delta)) if (c.vertex - end).norm() < (c.vertex - other).norm() => delta / k,
            _ => 0.0,
        };
        (t + extra).min(c.len_in.min(c.len_out) * (0.5 * c.alpha).tan())
    };
    // From the corner whose first pass starts nearest the tool, in the loop's order.
    let here = b.at();
    let first = (0..corners_all.len())
        .min_by(|&i, &j| {
            let d = |c: &Corner| (c.arc(first_radius(c)).0 - here).norm();
            d(&corners_all[i]).total_cmp(&d(&corners_all[j]))
        })
        .unwrap_or(0);
    let mut corners = Vec::new();
    for c in corners_all[first..].iter().chain(&corners_all[..first]) {
        let k = 1.0 / (0.5 * c.alpha).sin() - 1.0;
        let mut rho = first_radius(c);
        // (a corner that leaves no more than the corner tolerance on its bisector has no passes)
        if rho <= rho_fin + 1e-6 || (rho - rho_fin) * k <= options.corner_tolerance_mm {
            continue;
        }
        let (a0, _, _) = c.arc(rho);
        link(b, polygon, r, a0);
        let mut passes = 0;
        let mut deepest: f64 = 0.0;
        while rho > rho_fin + 1e-6 && passes < MAX_PASSES {
            // Fixed point: the step allowed at the new radius.
            let mut next = rho - concave_step(rho, r, phi) / k;
            next = (rho - concave_step(next.max(rho_fin), r, phi) / k).max(rho_fin);
            // After the first: from the previous arc's end on wall B straight to wall A, short
            // of this arc's start by a tenth of the gap between the two arcs' tangent points,
            // then along wall A into the arc (entered tangentially, as the step rule assumes).
            let (a, _, arc) = c.arc(next);
            if passes > 0 {
                let (a_prev, _, _) = c.arc(rho);
                b.line(a_prev + (a - a_prev) * CORNER_CHORD_REACH, MoveKind::Link);
            }
            b.line(a, MoveKind::Corner);
            b.push(arc, MoveKind::Corner);
            deepest = deepest.max((rho - next) * k);
            rho = next;
            passes += 1;
        }
        corners.push(CornerPasses {
            vertex: c.vertex,
            angle_rad: c.alpha,
            passes,
            last_radius_mm: rho,
            max_radial_depth_mm: deepest,
            max_engagement_rad: 0.0,
            at: c.vertex,
        });
    }
    // Cusps (a neck's mouth): arcs tangent to both walls from T down to ρ_fin, each back on
    // its chord (inside its own disc: cleared) and along the incoming wall into the next.
    for c in &cusps_all {
        let rho0 = t.min(c.rho_max);
        let radii = c.radii(rho0, rho_fin, r, phi);
        let (Some((a0, _, _)), false) = (c.arc(rho0), radii.is_empty()) else { continue };
        link(b, polygon, r, a0);
        let (mut rho_prev, mut a_prev, mut deepest) = (rho0, a0, 0.0_f64);
        for &rho in &radii {
            let Some((a, _, arc)) = c.arc(rho) else { break };
            b.line(a_prev, MoveKind::Link);
            for sg in c.along_wall(a_prev, a) {
                b.push(sg, MoveKind::Corner);
            }
            b.push(arc, MoveKind::Corner);
            deepest = deepest.max(c.depth(rho_prev, rho));
            (rho_prev, a_prev) = (rho, a);
        }
        corners.push(CornerPasses {
            vertex: c.vertex,
            angle_rad: c.alpha,
            passes: radii.len(),
            last_radius_mm: rho_prev,
            max_radial_depth_mm: deepest,
            max_engagement_rad: 0.0,
            at: c.vertex,
        });
    }
    // Finishing contour: the opening of the final wall offset with radius ρ_fin + s_f, and at
    // every convex corner arc of it the arcs into the corner point.
    let mut corner_points = Vec::new();
    if sf > 0.0 {
        let inner = largest(region.offset(rho_fin)).ok_or_else(|| {
            Error::param(Param::Polygon, "no finishing contour", "a pocket wider than the tool plus the stock")
        })?;
        let fin = largest(inner.offset(-(rho_fin + sf)))
            .ok_or_else(|| Error::param(Param::Polygon, "no finishing contour", "a pocket wider than the tool"))?;
        // Start on the straight wall nearest the tool (at its point nearest the tool, at least
        // ρ_l from the wall's start; the longest wall's middle where no wall is 2ρ_l long),
        // entered on a quarter circle of radius ρ_l = max(s_f, r/2) tangent to it (the stock
        // grows from 0 to s_f under a convex arc); the lead-in starts ρ_l from the wall, in
        // cleared material.
        let loop_segs = fin.segments();
        let lead = sf.max(0.5 * r);
        let here = b.at();
        let lines: Vec<(P2, P2)> = loop_segs
            .iter()
            .filter_map(|sg| match *sg {
                Segment::Line { start, end } => Some((start, end)),
                _ => None,
            })
            .collect();
        // (a lead-in whose quarter circle would come within r of another wall is not taken;
        // where none is clear, the link goes straight to the wall point)
        let lead_in = |(mid, dir): (P2, P2)| {
            let (center, start_angle) = (mid + crate::geom::rot90(dir) * lead, (-dir.y).atan2(-dir.x));
            (mid, Segment::Arc { center, radius: lead, start_angle, sweep: 0.5 * PI })
        };
        let clear = |(_, arc): &(P2, Segment)| super::guard::keeps_off_walls(polygon, arc, r);
        let nearest = lines
            .iter()
            .filter(|(a, c)| (c - a).norm() >= 2.0 * lead)
            .map(|&(a, c)| {
                let (len, dir) = ((c - a).norm(), (c - a).normalize());
                lead_in((a + dir * (here - a).dot(&dir).clamp(lead, len - 1e-3), dir))
            })
            .filter(clear)
            .min_by(|x, y| (x.0 - here).norm().total_cmp(&(y.0 - here).norm()));
        let longest = lead_in(
            lines
                .iter()
                .max_by(|a, c| (a.1 - a.0).norm().total_cmp(&(c.1 - c.0).norm()))
                .map_or((loop_segs[0].start(), p2(1.0, 0.0)), |(a, c)| ((a + c) * 0.5, (c - a).normalize())),
        );
        let (mid, arc) = nearest.unwrap_or(longest);
        let arc = Some(arc).filter(|a| clear(&(mid, *a)));
        link(b, polygon, r, arc.map_or(mid, |a| a.start()));
        arc.into_iter().for_each(|a| b.push(a, MoveKind::Finish));
        let fin_loop = start_near(&loop_segs, mid);
        let n = fin_loop.len();
        for (i, seg) in fin_loop.iter().enumerate() {
            b.push(*seg, MoveKind::Finish);
            let is_line = |sg: &Segment| matches!(sg, Segment::Line { .. });
            if let Segment::Arc { center, radius, start_angle, sweep } = *seg
                && sweep > 1e-9
                && (radius - (rho_fin + sf)).abs() < 1e-6
                && (radius - options.corner_tolerance_mm) * (1.0 / (0.5 * sweep).cos() - 1.0)
                    > options.corner_tolerance_mm
                && is_line(&fin_loop[(i + n - 1) % n])
                && is_line(&fin_loop[(i + 1) % n])
            {
                let corner = Corner::of_arc(center, radius, start_angle, sweep);
                let (before, point) =
                    (b.segments.len(), corner_point_arcs(b, &corner, radius, r, phi, options.corner_tolerance_mm));
                // not where they would come within r of a wall whose offset the loop has lost
                // (a short edge between the corner's walls, farther than r + s_f from the region)
                if b.segments[before..].iter().all(|sg| super::guard::keeps_off_walls(polygon, sg, r)) {
                    corner_points.push(point);
                } else {
                    b.segments.truncate(before);
                    b.kinds.truncate(before);
                }
            }
        }
    }
    Ok(AdaptivePart { entry, first_segment: 0, end_segment: 0, core_radius_mm: t, rings, corners, corner_points })
}

/// The least core radius T grown from outside the stock, as a share of the inscribed radius
/// of the closed pocket's tool-centre region (a helix's radius bounds T otherwise).
const MIN_CORE_SHARE: f64 = 0.25;

/// Margin by which ring 0 grown from outside keeps off the stock (mm), beyond r: the tool
/// goes down there.
const OUTSIDE_MARGIN_MM: f64 = 0.05;

/// Where a part's clearing grows from.
pub(crate) enum Seed<'a> {
    /// A helix bore about k0 and the spiral out of it ([`spiral_and_rings`]).
    Helix,
    /// Outside the stock, beyond open edges: `stock` the pocket outline (the material ends
    /// there), `grow` the tool-centre region of the pocket extended far enough across its open
    /// edges that its core holds tool centres off the stock, `closed` the tool-centre region
    /// of the closed pocket, on which T is chosen.
    Outside { stock: &'a Region, grow: &'a Region, closed: &'a Region },
}

/// Rings grown from outside the stock in the core `core` = C ⊖ T of the pocket extended across
/// its open edges, cut where they add (DERIVED like the rings of step 3 of the module docs,
/// the disc about k0 replaced by a dilation): G₀ is the largest piece of the core at least
/// T + r (+ [`OUTSIDE_MARGIN_MM`]) from the stock `stock`, so G₀ ⊕ T ⊕ r is air, and
/// G_j+1 = core ∩ (G_j ⊕ a), a = the concave-cut step of radius T (geodesic growth in the
/// core: each set lies within a of the previous). Ring j = ∂(G_j ⊕ T) (one loop a piece):
/// smooth (arcs of radius ≥ T about the core), at most a step outside ring j − 1, so a pass
/// cuts at most the concave-cut step of radius T: within φ. Ring 0 cuts nothing and is not
/// cut; a ring is cut only where it adds to the previous one ([`super::runs::new_runs`]) and comes within
/// r of the stock, its runs in order ([`super::runs::cut_runs`]). The tool goes down on ring 0 (off the
/// stock) nearest the first run. Returns the rings cut and that point.
#[allow(clippy::too_many_arguments)]
fn grown_rings(
    b: &mut Builder,
    polygon: &Polygon,
    r: f64,
    core: &Region,
    t: f64,
    phi: f64,
    k0: P2,
    stock: &Region,
) -> Result<(usize, P2), Error> {
    let step = concave_step(t, r, phi);
    let pieces = |res: Vec<Region>| res.into_iter().map(Region::ccw).filter(|pl| pl.area() > 1e-9).collect::<Vec<_>>();
    let near = largest(stock.offset(-(t + r + OUTSIDE_MARGIN_MM)))
        .ok_or_else(|| Error::param(Param::Polygon, "no stock", "a pocket with area"))?;
    // One seed: the largest piece of air (beyond two opposite open edges the rings grow from
    // one through to the other, instead of crossing uncut stock between two fronts).
    let mut grown: Vec<Region> = largest(pieces(core.boolean(&near, BoolOp::Not))).into_iter().collect();
    if grown.is_empty() {
        return Err(Error::param(
            Param::OpenEdges,
            "no room for the tool beyond the open edges",
            "open edges the tool can pass through (at least D long)",
        ));
    }
    let loops_of = |g: &[Region]| -> Vec<Vec<Segment>> {
        g.iter().filter_map(|p| largest(p.offset(-t))).map(|o| o.segments()).collect()
    };
    let mut rings = vec![loops_of(&grown)];
    let mut area: f64 = grown.iter().map(Region::area).sum();
    let least_growth = 1e-6 * core.area().max(1.0);
    while rings.len() < MAX_PASSES {
        let mut next: Vec<Region> = Vec::new();
        for g in &grown {
            let Some(d) = largest(g.offset(-step)) else { continue };
            for piece in pieces(core.boolean(&d, BoolOp::And)) {
                merge_into(&mut next, piece);
            }
        }
        let next_area: f64 = next.iter().map(Region::area).sum();
        if next_area <= area + least_growth {
            break;
        }
        (grown, area) = (next, next_area);
        rings.push(loops_of(&grown));
    }
    // the runs: ring 0 is air (the previous ring of ring 1); not the runs whose tool stays
    // r off the stock (air)
    let flat = |loops: &[Vec<Segment>]| loops.iter().flatten().copied().collect::<Vec<Segment>>();
    let ring0 = flat(&rings[0]);
    let mut ring_runs: Vec<Vec<Vec<Segment>>> = Vec::new();
    for pair in rings.windows(2) {
        let prev = flat(&pair[0]);
        let mut runs: Vec<Vec<Segment>> = pair[1].iter().flat_map(|lp| super::runs::new_runs(lp, &prev)).collect();
        runs.retain(|run| run.iter().any(|sg| reaches_stock(stock, sg, r)));
        if !runs.is_empty() {
            ring_runs.push(runs);
        }
    }
    // straight down on ring 0 (off the stock) nearest the first run's start
    let first = ring_runs.first().and_then(|runs| runs.first()).map_or(k0, |run| run[0].start());
    let at = ring0
        .iter()
        .map(|sg| closest_on(sg, first).0)
        .min_by(|a, c| (a - first).norm().total_cmp(&(c - first).norm()))
        .unwrap_or(first);
    b.push(Segment::Line { start: at, end: first }, MoveKind::Entry);
    let count = ring_runs.len();
    super::runs::cut_runs(b, polygon, r, ring_runs);
    Ok((count, at))
}

/// Whether the tool on `seg` comes within r of the stock `stock` (at its ends and 15 points
/// between; the runs are smooth, a step long at most where they start to cut).
fn reaches_stock(stock: &Region, seg: &Segment, r: f64) -> bool {
    let walls = stock.segments();
    (0..=16).any(|k| {
        let p = seg.point(k as f64 / 16.0);
        stock.contains(p) || walls.iter().any(|w| (closest_on(w, p).0 - p).norm() < r + 0.5 * OUTSIDE_MARGIN_MM)
    })
}

/// Add `p` to the disjoint regions `list`, uniting it with those it overlaps.
fn merge_into(list: &mut Vec<Region>, p: Region) {
    let mut p = p;
    while let Some(i) = list.iter().position(|q| !q.boolean(&p, BoolOp::And).is_empty()) {
        let q = list.swap_remove(i);
        match largest(q.boolean(&p, BoolOp::Or)) {
            Some(u) => p = u.ccw(),
            None => break,
        }
    }
    list.push(p);
}

/// How far the pocket is extended across an open edge for its tool-centre region, in units of
/// r + s_f: 3, so that the region reaches 2(r + s_f) past the edge, where the tool's disc is
/// r + s_f off the stock; the extension's far corners are rounded with radius 1.5(r + s_f),
/// so the region's far corners are arcs of radius (r + s_f)/2 (no corner passes, no corner
/// points there: air).
pub const OPEN_REACH_FACTOR: f64 = 3.0;

/// A pocket open on some edges: the stock and the pocket extended across its open edges.
pub(crate) struct OpenPocket {
    /// The pocket outline: the stock.
    stock: Region,
    /// Extended by [`OPEN_REACH_FACTOR`] (r + s_f) across the open edges: its tool-centre
    /// regions are the parts'; as a polygon (arcs by their chords) for the links.
    near: Region,
    near_polygon: Polygon,
    /// The pocket extended as for `far` (arcs by 32 chords each): where the links are routed.
    far_polygon: Polygon,
    /// The tool-centre regions of the pocket extended by 2T + 2r + s_f + 2 mm (T up to the
    /// closed region's inscribed radius), so their cores reach past the open edges by more
    /// than T + r: the rings' seed lies there.
    far: Vec<Region>,
    /// The largest tool-centre region of the closed pocket.
    closed: Region,
}

impl OpenPocket {
    /// The open pocket of `work` open on `open` (its edge indices), tool-centre offset `rs`
    /// = r + s_f; `closed_regions` the closed pocket's tool-centre regions.
    fn new(work: &Polygon, open: &[usize], closed_regions: &[Region], rs: f64) -> Result<OpenPocket, Error> {
        let closed = largest(closed_regions.to_vec()).ok_or_else(|| {
            Error::param(Param::Polygon, "narrower than the tool", "room for the tool plus the finishing stock")
        })?;
        let reach = OPEN_REACH_FACTOR * rs;
        let near = extended(work, open, reach, 0.5 * reach)?;
        let near_polygon = Polygon::new(near.vertices())?;
        let far_reach = 2.0 * inscribed(&closed).0 + 2.0 * rs + 2.0;
        let far_outline = extended(work, open, far_reach, 0.5 * far_reach)?;
        let chords = far_outline
            .segments()
            .iter()
            .flat_map(|sg| if matches!(sg, Segment::Arc { .. }) { sg.sample(32) } else { vec![sg.start(), sg.end()] })
            .skip(1)
            .fold(Vec::<P2>::new(), |mut v, p| {
                if v.last().is_none_or(|q| (p - q).norm() > 1e-9) {
                    v.push(p);
                }
                v
            });
        let (far_polygon, far) = (Polygon::new(chords)?, far_outline.offset(rs));
        Ok(OpenPocket { stock: Region::polygon(work.vertices()), near, near_polygon, far_polygon, far, closed })
    }

    /// The seed of a tool-centre region of the extended pocket: outside the stock where the
    /// region reaches past an open edge (a vertex of it off the stock), from the far region
    /// that holds it.
    fn seed_of(&self, region: &Region) -> Option<Seed<'_>> {
        let here = region.vertices().into_iter().find(|&v| !self.stock.contains(v))?;
        let grow = self.far.iter().find(|f| f.contains(here)).or_else(|| self.far.first())?;
        Some(Seed::Outside { stock: &self.stock, grow, closed: &self.closed })
    }
}

/// `work` extended outward across each open edge by `reach`: the edge swept along its outward
/// normal, the far corners rounded with radius `round` (at most half the edge).
fn extended(work: &Polygon, open: &[usize], reach: f64, round: f64) -> Result<Region, Error> {
    let v = work.vertices();
    let n = v.len();
    let quarter = (PI / 8.0).tan();
    let mut out = Region::polygon(v);
    for &i in open {
        let (a, b) = (v[i], v[(i + 1) % n]);
        let len = (b - a).norm();
        let u = (b - a) / len;
        let out_n = p2(u.y, -u.x);
        let rho = round.min(0.49 * len).min(reach);
        let q = Region::with_bulges(&[
            (a, 0.0),
            (a + out_n * (reach - rho), quarter),
            (a + out_n * reach + u * rho, 0.0),
            (b + out_n * reach - u * rho, quarter),
            (b + out_n * (reach - rho), 0.0),
            (b, 0.0),
        ]);
        out = largest(out.boolean(&q, BoolOp::Or))
            .map(Region::ccw)
            .ok_or_else(|| Error::param(Param::OpenEdges, i, "edges whose extension joins the pocket"))?;
    }
    Ok(out)
}

/// Each open edge index below the polygon's vertex count, none twice; the error names
/// `--open-edges`.
pub fn validate_open_edges(polygon: &Polygon, open_edges: &[usize]) -> Result<(), Error> {
    let n = polygon.vertices().len();
    for (k, &i) in open_edges.iter().enumerate() {
        if i >= n || open_edges[..k].contains(&i) {
            return Err(Error::param(
                Param::OpenEdges,
                i,
                format!(
                    "distinct edge numbers from 0 to {} (edge i runs from vertex i to vertex i + 1, 0-based)",
                    n - 1
                ),
            ));
        }
    }
    Ok(())
}

/// Pieces each corner-point arc is cut into, so that the evaluator measures it at its
/// bisector and quarter points (the arcs are shorter than the sampling spacing).
const CORNER_POINT_PIECES: usize = 4;

/// The arcs into a corner point after the finishing arc of radius ρ₀ (the tool at its end, on
/// wall B): back on that arc's chord (cleared) to wall A, then per arc: along wall A to its
/// tangent point, the arc (radius from [`next_corner_point_radius`]), and back on its chord;
/// after the last (radius δ) along wall B to the finishing arc's end. Every move is
/// [`MoveKind::CornerPoint`], measured like the rest.
fn corner_point_arcs(b: &mut Builder, c: &Corner, rho0: f64, r: f64, phi: f64, delta: f64) -> CornerPoint {
    let (a0, e0, _) = c.arc(rho0);
    let k = 1.0 / (0.5 * c.alpha).sin() - 1.0;
    let (mut rho, mut arcs, mut deepest) = (rho0, 0, 0.0_f64);
    b.line(a0, MoveKind::CornerPoint);
    let known = b.radii.iter().position(|(alpha, r0, _)| *alpha == c.alpha && *r0 == rho0);
    let radii = match known {
        Some(i) => b.radii[i].2.clone(),
        None => {
            let radii = corner_point_radii(rho0, c.alpha, r, phi, delta, MAX_PASSES);
            b.radii.push((c.alpha, rho0, radii.clone()));
            radii
        }
    };
    for next in radii {
        let (a, _, arc) = c.arc(next);
        b.line(a, MoveKind::CornerPoint);
        if let Segment::Arc { center, radius, start_angle, sweep } = arc {
            let piece = sweep / CORNER_POINT_PIECES as f64;
            for j in 0..CORNER_POINT_PIECES {
                let start_angle = start_angle + piece * j as f64;
                b.push(Segment::Arc { center, radius, start_angle, sweep: piece }, MoveKind::CornerPoint);
            }
        }
        if next > delta * (1.0 + 1e-9) {
            b.line(a, MoveKind::CornerPoint);
        }
        deepest = deepest.max((rho - next) * k);
        rho = next;
        arcs += 1;
    }
    b.line(e0, MoveKind::CornerPoint);
    CornerPoint {
        vertex: c.vertex,
        angle_rad: c.alpha,
        arcs,
        last_radius_mm: rho,
        residual_mm: rho * k,
        max_radial_depth_mm: deepest,
        max_engagement_rad: 0.0,
        at: c.vertex,
    }
}

/// The axis of a thin core: the core C ⊖ q (one loop) whose vertices lie within `width` of a
/// line through `k0`, as the unit direction u and the extents s₊, s₋ ≥ 0 of its vertices along
/// u either side of k0 (u along the core's longest edge), and the widening w of the
/// stadium's radius q (below). `None` where the core is
/// not that thin (an L, a square) or its extents are below a tenth of `width`.
fn stadium_axis(region: &Region, q: f64, k0: P2, width: f64) -> Option<(P2, f64, f64, f64)> {
    let ks = region.offset(q);
    let [k] = ks.as_slice() else { return None };
    let vs: Vec<P2> = k.vertices();
    let (mut u, mut far) = (p2(1.0, 0.0), 0.0);
    for (i, a) in vs.iter().enumerate() {
        let c = vs[(i + 1) % vs.len()];
        if (c - a).norm() > far {
            (u, far) = ((c - a) / (c - a).norm(), (c - a).norm());
        }
    }
    if far < 0.2 * width {
        return None;
    }
    let off = |v: &P2| cross(u, v - k0);
    if vs.iter().any(|v| off(v).abs() > 0.5 * width) {
        return None;
    }
    let along = |v: &P2| u.dot(&(v - k0));
    let s_plus = vs.iter().map(along).fold(0.0, f64::max);
    let s_minus = vs.iter().map(|v| -along(v)).fold(0.0, f64::max);
    // Widened by the core's half-width w (the stadium then reaches the walls the core's offset
    // reaches) and shortened by w, where its axis keeps q + w from every wall.
    let w = vs.iter().map(|v| off(v).abs()).fold(0.0, f64::max);
    let walls = region.segments();
    let clear = |p: P2| walls.iter().map(|sg| (closest_on(sg, p).0 - p).norm()).fold(f64::INFINITY, f64::min);
    let (sp, sm) = ((s_plus - w).max(0.0), (s_minus - w).max(0.0));
    if [k0 + u * sp, k0 - u * sm, k0].iter().all(|&p| clear(p) >= q + w - 1e-9) {
        Some((u, sp, sm, w))
    } else {
        Some((u, s_plus, s_minus, 0.0))
    }
}

/// A link through cleared material from the current position to `to`: the shortest path on
/// which the tool keeps r from the walls ([`super::route`]); a retract where there is none.
pub(crate) fn link(b: &mut Builder, polygon: &Polygon, r: f64, to: P2) {
    let from = b.at();
    match b.router.get(polygon, r).route(from, to) {
        Some(pts) => pts.iter().skip(1).for_each(|&p| b.line(p, MoveKind::Link)),
        None => b.retracts.push(b.segments.len()),
    }
}

/// The radius of the largest circle in the region, by bisection on inward offsets, and its
/// centre (the middle of the last offset that does not vanish).
pub(crate) fn inscribed(region: &Region) -> (f64, P2) {
    let ext = region.extents();
    let (mut lo, mut hi) = (0.0, ext.map_or(1.0, |(a, b)| 0.5 * (b.x - a.x).min(b.y - a.y)) + 1e-9);
    let mut centre = region.vertices().first().copied().unwrap_or_else(P2::zeros);
    for _ in 0..INSCRIBED_STEPS {
        let mid = 0.5 * (lo + hi);
        match largest(region.offset(mid)) {
            Some(o) => {
                lo = mid;
                if let Some((a, b)) = o.extents() {
                    centre = p2(0.5 * (a.x + b.x), 0.5 * (a.y + b.y));
                }
            }
            None => hi = mid,
        }
    }
    (lo, centre)
}

/// Evaluate every move at depth and gather the report.
fn measure(
    polygon: Polygon,
    settings: PocketSettings,
    options: AdaptiveOptions,
    phi: f64,
    mut parts: Vec<AdaptivePart>,
    b: Builder,
    corner_radius_left_mm: f64,
) -> Result<AdaptivePlan, Error> {
    // a retract before every part but the first, and before the links with no path at depth
    let mut retract_before: Vec<usize> =
        parts.iter().skip(1).map(|q| q.first_segment).chain(b.retracts.iter().copied()).collect();
    retract_before.sort_unstable();
    retract_before.dedup();
    let entries = parts.iter().map(|p| p.entry).collect();
    let toolpath = Toolpath::at_depth(&b.segments, &b.kinds, -options.depth_mm, entries, retract_before);
    // the bores of helices and ramps are cut; outside the stock nothing was
    let path = PocketPath::measured(&polygon, settings, toolpath, options.depth_mm, &[MoveKind::Link])?;
    let profile = &path.measurement.profile;
    // Corner maxima: the samples on each part's corner passes nearest each corner.
    for (smp, &i) in profile.samples.iter().zip(&sample_owners(profile, &b.segments)) {
        let at = p2(smp.x_mm, smp.y_mm);
        let nearest = |v: P2, w: P2| (v - at).norm().total_cmp(&(w - at).norm());
        let slot = match b.kinds.get(i) {
            Some(MoveKind::Corner) => parts
                .iter_mut()
                .flat_map(|p| p.corners.iter_mut())
                .min_by(|a, c| nearest(a.vertex, c.vertex))
                .map(|c| (&mut c.max_engagement_rad, &mut c.at)),
            Some(MoveKind::CornerPoint) => parts
                .iter_mut()
                .flat_map(|p| p.corner_points.iter_mut())
                .min_by(|a, c| nearest(a.vertex, c.vertex))
                .map(|c| (&mut c.max_engagement_rad, &mut c.at)),
            _ => None,
        };
        if let Some((max, where_)) = slot
            && smp.angle_rad > *max
        {
            *max = smp.angle_rad;
            *where_ = at;
        }
    }
    Ok(AdaptivePlan { path, open_edges: Vec::new(), options, target_rad: phi, parts, corner_radius_left_mm })
}
