//! Narrow pockets cleared as one trochoidal slot along their medial axis (docs/pockets.md,
//! "Narrow pockets"). A pocket is *narrow* when the default helix (radius 0.375·D) does not fit
//! its tool-centre region (the pocket offset by r + s_f): every point of that region is then
//! within 0.375·D of its centre line, and a slot along the line, its loops as wide as the
//! region, clears it in one pass where rings or a spiral would mostly cut air.
//!
//! 1. **Centre line** ([`axis`]): the pocket's medial axis where the wall clearance is at least
//!    r + s_f + ρ_fin, a tree; its branches run into the corners of the region and end where
//!    the loop radius is ρ_fin, the finishing corner radius (a loop into the region's corner
//!    itself would meet both walls at once: π − α).
//! 2. **Entry**: a straight zig-zag ramp on the longest straight piece of the line, its legs
//!    L ≤ t_max/(2·tan θ) long (θ the ramp angle, t_max the ramp pass depth). At a point of the
//!    line two consecutive legs pass at heights that differ by at most twice a leg's descent,
//!    so every full-width pass of the ramp cuts at most t_max deep
//!    ([`SlotPlan::ramp_pass_depth_mm`] reports the deepest). A ramp rather than a ramping
//!    trochoid: its full-width depth is bounded by the leg length alone, and the loops that
//!    follow then all cut at the full depth, where the evaluator measures them. Where the bore
//!    must be longer for the stadiums (below), θ is lowered to keep t_max.
//! 3. **Stadiums** widen the ramp's slot (width D) to the loop radius, each side a step of
//!    r(1 − cos φ/2) further out (a side is entered where the end arc turns into it, about twice
//!    the straight cut's engagement there), the right side on a slant; their ends stay so far in
//!    (e² ≥ 2rg − g² for sides g out) that no tool disc on an end arc reaches past the bore's
//!    end disc.
//! 4. **Loops** ([`loops`]): from both ends of the widened bore, along every branch of the
//!    line away from the entry, half circles of radius a = clearance − r − s_f (the local
//!    half-width of the tool-centre region) joined across the back; the step of each from the
//!    two-circle model within the planned angle; a loop larger than the one before cuts its
//!    whole circle. After a branch the tool runs back along the line (through cleared
//!    material) to the branch point.
//! 5. **Finishing contour** ([`finish`]) with s_f > 0, and the arcs into each corner point.
//!
//! The whole path is measured by the evaluator ([`PocketPath::measured`]); where its peak
//! exceeds the target, the loops (or the stadiums, where they hold the peak) are planned again
//! to a smaller angle, at most [`REPLANS`] times.

mod axis;
mod finish;
mod loops;
#[cfg(test)]
mod tests;

use super::adaptive::{AdaptiveOptions, Builder, fin_radius, inscribed};
use super::path::PocketPath;
use super::{CornerPoint, PocketSettings};
use crate::engagement::sample_owners;
use crate::error::{Error, Param, num};
use crate::geom::medial::{Walls, medial_axis};
use crate::geom::offset::Region;
use crate::geom::{P2, Polygon, Segment, bisect_edge, p2};
use crate::toolpath::entry::{HELIX_START_Z_MM, Ramp};
use crate::toolpath::{Entry, MoveKind, Toolpath};
use axis::{Run, Tree};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Share of D of the default ramp pass depth t_max.
pub const DEFAULT_RAMP_PASS_DEPTH_RATIO: f64 = 0.1;
/// Largest ramp pass depth, as a share of D.
pub const MAX_RAMP_PASS_DEPTH_RATIO: f64 = 0.5;
/// Grid of the Voronoi diagram of the centre line (mm).
const VORONOI_RESOLUTION_MM: f64 = 1e-4;
/// Most loops of one slot (bounds the work on hostile input).
const MAX_LOOPS: usize = 20_000;
/// Plans after the first one when the measured peak exceeds the target.
pub const REPLANS: usize = 4;
/// The loops' front arcs have this times the loop radius (their centres behind the loops'):
/// 1, half circles. Flatter fronts (1.5) take 15 % fewer loops, but meet the side walls at an
/// angle: the link into the next loop then cuts the corner of stock left there at 100°.
const FRONT_RATIO: f64 = 1.0;
/// How far below the target the loops are replanned when the peak exceeds it (rad, 0.25°).
const REPLAN_MARGIN_RAD: f64 = 0.25 * PI / 180.0;

/// A narrow pocket cleared as a trochoidal slot.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SlotPlan {
    /// The pocket, settings, moves at depth (ramp's flat pass, stadiums, loops, runs back,
    /// finishing contour, corner points) and their measurement with the ramp's bore as cut.
    pub path: PocketPath,
    pub options: AdaptiveOptions,
    /// Target engagement (rad), and the angle the loops were planned to in the end.
    pub target_rad: f64,
    pub planned_rad: f64,
    /// Ramp pass depth t_max asked for, and the deepest full-width pass of the ramp (mm).
    pub ramp_pass_limit_mm: f64,
    pub ramp_pass_depth_mm: f64,
    /// Largest loop radius a (mm) and the loops cut.
    pub loop_radius_mm: f64,
    pub loops: usize,
    /// The centre line the loops follow (polylines, mm).
    pub axis: Vec<Vec<P2>>,
    /// The corner points reached by the finishing pass.
    pub corner_points: Vec<CornerPoint>,
    /// Radius of the pocket's convex corners as cut (mm).
    pub corner_radius_left_mm: f64,
}

/// The ramp pass depth (mm) asked for: the option, else 0.1·D. Error naming
/// `--ramp-pass-depth` outside (0, 0.5·D].
pub fn ramp_pass_limit(option: Option<f64>, r: f64) -> Result<f64, Error> {
    let d = 2.0 * r;
    let t = option.unwrap_or(DEFAULT_RAMP_PASS_DEPTH_RATIO * d);
    if !(t.is_finite() && t > 0.0 && t <= MAX_RAMP_PASS_DEPTH_RATIO * d) {
        return Err(Error::param(
            Param::RampPassDepth,
            t,
            format!(
                "greater than 0 and at most {MAX_RAMP_PASS_DEPTH_RATIO} × D = {} mm",
                num(MAX_RAMP_PASS_DEPTH_RATIO * d)
            ),
        ));
    }
    Ok(t)
}

/// The tool-centre region of `polygon` (offset by r + s_f) when it is one piece, with its
/// inscribed radius.
fn region(polygon: &Polygon, r: f64, sf: f64) -> Option<(Region, f64)> {
    let regions = Region::polygon(polygon.vertices()).offset(r + sf);
    if regions.len() != 1 {
        return None;
    }
    let region = regions.into_iter().next()?;
    let ins = inscribed(&region).0;
    Some((region, ins))
}

/// Whether the pocket is narrow: its tool-centre region one piece in which the default helix
/// (0.375·D, or the helix radius asked for) does not fit (inscribed radius below it / 0.98).
pub fn is_narrow(polygon: &Polygon, settings: &PocketSettings, options: &AdaptiveOptions) -> bool {
    let r = settings.tool_radius;
    let helix = options.helix_radius_mm.unwrap_or(0.75 * r);
    region(polygon, r, options.finish_stock_mm).is_some_and(|(_, ins)| 0.98 * ins < helix)
}

/// Plan `polygon` as a trochoidal slot along its centre line (module docs). Errors: a pocket
/// the tool does not fit (naming `--tool-diameter`), a pocket that is not narrow
/// ([`is_narrow`]) or whose centre line is not one tree (naming `--method`), a ramp that does
/// not fit.
pub fn plan_slot(
    polygon: &Polygon,
    settings: PocketSettings,
    options: &AdaptiveOptions,
    ramp_pass: Option<f64>,
) -> Result<SlotPlan, Error> {
    settings.validate()?;
    options.validate(&settings)?;
    let r = settings.tool_radius;
    let sf = options.finish_stock_mm;
    let t_max = ramp_pass_limit(ramp_pass, r)?;
    let walls = Walls::new(polygon);
    let axis = medial_axis(polygon, VORONOI_RESOLUTION_MM)?;
    let widest = axis.edges.iter().map(|e| e.clearance_a.max(e.clearance_b)).fold(0.0, f64::max);
    let Some((region, inscribed)) = region(polygon, r, sf) else {
        if Region::polygon(polygon.vertices()).offset(r + sf).is_empty() {
            return Err(Error::param(
                Param::ToolDiameter,
                2.0 * r,
                format!(
                    "at most {} mm for this pocket (its widest inscribed circle has a diameter of {} mm, less \
                     twice the finishing stock {} mm)",
                    num((2.0 * (widest - sf)).max(0.0)),
                    num(2.0 * widest),
                    num(sf)
                ),
            ));
        }
        return Err(not_a_slot("its tool-centre region is in several pieces"));
    };
    let helix = options.helix_radius_mm.unwrap_or(0.75 * r);
    if 0.98 * inscribed >= helix {
        return Err(not_a_slot(&format!("the helix of {} mm fits this one", num(helix))));
    }
    let need = r + sf;
    let phi = options.target_rad(&settings)?;
    let rho_fin = if sf > 0.0 { fin_radius(sf, r, phi) } else { 0.1 * r };
    // The branches end where the loop radius is ρ_fin (as adaptive clearing's corner passes):
    // a loop into the corner of the region itself would meet both walls at once (π − α).
    let least = rho_fin.min(0.9 * (widest - need).max(0.0));
    let tree = Tree::new(&axis, &walls, need + least).ok_or_else(|| not_a_slot("its centre line is not one tree"))?;
    let radius = |c: P2| (walls.clearance(c) - need).max(0.0);
    // the angles the loops and the stadiums are planned to, each lowered where it is the peak
    let (mut planned, mut widen) = (phi, phi);
    let mut best: Option<SlotPlan> = None;
    for _ in 0..=REPLANS {
        let plan = build(polygon, &settings, options, &tree, &region, &radius, (phi, planned, widen, rho_fin, t_max))?;
        let m = &plan.path.measurement;
        let over = m.max_engagement_rad - phi;
        let stadium = m.max_of(MoveKind::Spiral) >= m.max_engagement_rad;
        best = Some(plan);
        if over <= REPLAN_MARGIN_RAD {
            break;
        }
        if stadium {
            widen -= over + REPLAN_MARGIN_RAD;
        } else {
            planned -= over + REPLAN_MARGIN_RAD;
        }
        // not below half the target: a peak that far above it is not the model's error
        if planned < 0.5 * phi || widen < 0.5 * phi {
            break;
        }
    }
    best.ok_or_else(|| not_a_slot("no plan"))
}

fn not_a_slot(why: &str) -> Error {
    Error::param(
        Param::Method,
        "slot",
        format!("a narrow pocket for the slot ({why}); adaptive clearing takes any pocket"),
    )
}

/// One plan of the slot with the loops planned to `planned` (rad).
fn build(
    polygon: &Polygon,
    settings: &PocketSettings,
    options: &AdaptiveOptions,
    tree: &Tree,
    region: &Region,
    radius: &dyn Fn(P2) -> f64,
    (phi, planned, widen, rho_fin, t_max): (f64, f64, f64, f64, f64),
) -> Result<SlotPlan, Error> {
    let r = settings.tool_radius;
    let sf = options.finish_stock_mm;
    let ramp_rad = options.ramp_deg.to_radians();
    // The ramp: on the longest straight piece, from its start, L = t_max / (2 tan θ) at most.
    let (edge, k, piece) = tree.longest_straight();
    let (q0, q1) = (tree.edges[edge].points[k], tree.edges[edge].points[k + 1]);
    let u = (q1 - q0) / piece;
    // Stadium ends e = shrink(g) in from the bore's, so that no tool disc on an end arc reaches
    // past the bore's end disc (the tool centre at (−e, g) from the end: e² ≥ 2rg − g²).
    let shrink = |g: f64| g.max((2.0 * r * g - g * g).max(0.0).sqrt());
    let a_piece = (0..=16).map(|i| radius(q0 + (q1 - q0) * (i as f64 / 16.0))).fold(f64::INFINITY, f64::min);
    // The bore long enough for stadiums to the loop width (sides at least half of it), at a
    // ramp angle below the option where that is needed to keep the pass depth.
    let len = piece.min((t_max / (2.0 * ramp_rad.tan())).max(4.2 * shrink(a_piece)));
    let ramp_rad = ramp_rad.min((t_max / (2.0 * len)).atan());
    let (p0, p1) = (q0, q0 + u * len);
    let ramp = Ramp { start: p0, end: p1, ramp_rad };
    let drop = HELIX_START_Z_MM + options.depth_mm;
    let legs = ramp.legs(drop);
    if legs as f64 > crate::pocket::entry::MAX_DESCENT_TURNS {
        return Err(Error::param(
            Param::RampPassDepth,
            t_max,
            format!(
                "at least {} mm for a {} mm straight centre line at {}° (at most {} ramp legs)",
                num(2.0 * drop / crate::pocket::entry::MAX_DESCENT_TURNS),
                num(piece),
                num(options.ramp_deg),
                crate::pocket::entry::MAX_DESCENT_TURNS
            ),
        ));
    }
    let ramp_pass_depth_mm = (2.0 * drop / legs as f64).min(options.depth_mm);
    let mut b = Builder::default();
    b.push(Segment::Line { start: p0, end: p1 }, MoveKind::Entry);
    // Stadiums widening the bore to the loop radius a_st (the least along the bore), each
    // wider by at most r(1 − cos φ/2) (each side is entered where the end arc turns into it,
    // the engagement there about twice the straight cut's), the right side on a slant; the last closed by its side cut again. Their sides are at least half the
    // bore (shortened where the bore is short).
    let a_bore = (0..=8).map(|i| radius(p0 + (p1 - p0) * (i as f64 / 8.0))).fold(f64::INFINITY, f64::min);
    let a_st =
        if 4.0 * shrink(a_bore) <= len { a_bore } else { bisect_edge(0.0, a_bore, 40, |g| 4.0 * shrink(g) <= len) };
    let grow = r * (1.0 - (0.5 * widen).cos());
    let rings = (a_st / grow).ceil().max(1.0) as usize;
    let n_r = p2(u.y, -u.x);
    let start = n_r.y.atan2(n_r.x);
    let mut g_prev = 0.0;
    let (mut e0, mut e1) = (p0, p1);
    for i in 1..=rings {
        let g = a_st * i as f64 / rings as f64;
        (e0, e1) = (p0 + u * shrink(g), p1 - u * shrink(g));
        b.line(e0 + n_r * g_prev, if i == 1 { MoveKind::Return } else { MoveKind::Spiral });
        b.push(Segment::Line { start: e0 + n_r * g_prev, end: e1 + n_r * g }, MoveKind::Spiral);
        b.push(Segment::Arc { center: e1, radius: g, start_angle: start, sweep: PI }, MoveKind::Spiral);
        b.push(Segment::Line { start: e1 - n_r * g, end: e0 - n_r * g }, MoveKind::Spiral);
        b.push(Segment::Arc { center: e0, radius: g, start_angle: start + PI, sweep: PI }, MoveKind::Spiral);
        g_prev = g;
    }
    b.push(Segment::Line { start: e0 + n_r * a_st, end: e1 + n_r * a_st }, MoveKind::Spiral);
    let (c0, c1) = (e0, e1);
    let mut count = 0;
    let mut loop_radius = a_st;
    // what is cut about a point of the axis before the loops: the stadium's ends, the nodes
    let cut_about = |q: P2| if (q - c0).norm() < 1e-9 || (q - c1).norm() < 1e-9 { a_st + r } else { radius(q) + r };
    let runs = tree.runs_around(edge, k, c0, c1);
    let first = match runs.first() {
        Some(Run::Cut(line) | Run::Back(line)) => line[0],
        None => c0,
    };
    let mut prev = (first, cut_about(first), cut_about(first) - r);
    for run in runs {
        match run {
            Run::Cut(line) => {
                let (loops, last) =
                    loops::loops_along(&line, prev, radius, (r, planned, FRONT_RATIO), MAX_LOOPS - count)
                        .map_err(|()| too_many_loops(settings))?;
                count += loops.len();
                let mut before = prev.2;
                for lp in &loops {
                    b.line(lp.right(), MoveKind::Link);
                    // a loop larger than the one before cuts its whole circle: the back half of
                    // its disc was not cut by the smaller loops
                    let seg = if lp.radius > before + 1e-9 {
                        let n = lp.right() - lp.center;
                        Segment::Arc {
                            center: lp.center,
                            radius: lp.radius,
                            start_angle: n.y.atan2(n.x),
                            sweep: 2.0 * PI,
                        }
                    } else {
                        let (center, radius, start_angle, sweep) = lp.arc(FRONT_RATIO);
                        Segment::Arc { center, radius, start_angle, sweep }
                    };
                    before = lp.radius;
                    if lp.radius > 1e-9 {
                        b.push(seg, MoveKind::Circle);
                    }
                    loop_radius = loop_radius.max(lp.radius);
                }
                prev = last;
            }
            Run::Back(line) => {
                for &q in &line {
                    b.line(q, MoveKind::Return);
                }
                if let Some(&end) = line.last() {
                    prev = (end, cut_about(end), cut_about(end) - r);
                }
            }
        }
    }
    let finish = finish::Finish { polygon, region, r, sf, rho_fin, phi, delta: options.corner_tolerance_mm };
    let mut corner_points = if sf > 0.0 { finish::finishing_pass(&mut b, &finish)? } else { Vec::new() };
    let toolpath =
        Toolpath::at_depth(&b.segments, &b.kinds, -options.depth_mm, vec![Entry::Ramp(ramp)], b.retracts.clone());
    let path = PocketPath::measured(polygon, *settings, toolpath, options.depth_mm)?;
    // each corner point's peak: the corner-point samples nearest its vertex
    let profile = &path.measurement.profile;
    for (smp, &i) in profile.samples.iter().zip(&sample_owners(profile, &b.segments)) {
        let at = p2(smp.x_mm, smp.y_mm);
        if b.kinds.get(i) == Some(&MoveKind::CornerPoint)
            && let Some(c) =
                corner_points.iter_mut().min_by(|a, c| (a.vertex - at).norm().total_cmp(&(c.vertex - at).norm()))
            && smp.angle_rad > c.max_engagement_rad
        {
            c.max_engagement_rad = smp.angle_rad;
            c.at = at;
        }
    }
    let corner_radius_left_mm = if sf > 0.0 { r + options.corner_tolerance_mm } else { r };
    Ok(SlotPlan {
        path,
        options: *options,
        target_rad: phi,
        planned_rad: planned,
        ramp_pass_limit_mm: t_max,
        ramp_pass_depth_mm,
        loop_radius_mm: loop_radius,
        loops: count,
        axis: tree.edges.iter().map(|e| e.points.clone()).collect(),
        corner_points,
        corner_radius_left_mm,
    })
}

fn too_many_loops(settings: &PocketSettings) -> Error {
    Error::param(
        Param::Polygon,
        format!("more than {MAX_LOOPS} loops"),
        format!(
            "a narrow pocket whose slot takes at most {MAX_LOOPS} loops of a D = {} mm tool",
            num(2.0 * settings.tool_radius)
        ),
    )
}

impl SlotPlan {
    /// The same plan mirrored in x for the pocket `polygon` (the original of a mirrored plan).
    pub fn mirrored(mut self, polygon: &Polygon) -> SlotPlan {
        use crate::geom::mirror::mirror_point;
        self.path = self.path.mirrored(polygon);
        for line in &mut self.axis {
            for p in line.iter_mut() {
                *p = mirror_point(*p);
            }
        }
        for c in &mut self.corner_points {
            c.vertex = mirror_point(c.vertex);
            c.at = mirror_point(c.at);
        }
        self
    }
}
