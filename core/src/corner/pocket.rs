//! Polygonal pocket cleared by contour-parallel rings (issue #5 item 5; Wu et al. 2016 §4,
//! domain-spec §3.1: the plain contour-parallel path whose corners the strategies replace).
//!
//! Conventions as in [`super`]: mm, counter-clockwise pocket boundary, tool-centre rings walked
//! counter-clockwise (pocket material on the left: climb milling with M3).
//!
//! Rings: ring `k` is the inward offset of the pocket boundary by `d_k = r + k·a_e`
//! (`k = 0, 1, …`) while that offset is non-empty. Offsetting is done by `cavalier_contours`
//! (J. Buckmccready, MIT/Apache-2.0), called from this module only, and only on a polygon that
//! [`Polygon::new`] has validated (≥ 3 finite vertices, no degenerate edges, simple, CCW) and
//! with a finite positive offset, so the library's preconditions hold (it can panic on
//! degenerate input; nothing is caught here). Its output keeps arcs exact as bulges; they are
//! converted to [`Segment::Arc`] (`sweep = 4·atan(bulge)`, cavalier_contours' bulge
//! definition). Note: an *inward* offset of a convex pocket corner stays sharp; arcs appear at
//! reflex (concave-of-pocket) vertices, with radius `d_k`.
//!
//! Measurement: each ring is measured by the independent evaluator ([`engagement_profile`])
//! over the pocket polygon as stock, after every ring machined before it. Rings are machined
//! from the innermost outward (the usual contour-parallel order starting in the middle), so
//! the innermost ring is a full slot (180°) and each further ring cuts a band of `a_e`.
//! Links between rings are not part of the path (not measured, not in the length or time).
//! The first position of each ring (the entry, where the evaluator has no swept path behind
//! the tool yet) is reported apart from the ring's running maximum.
//!
//! Corner strategies (variable / isometric circles at each corner of each ring) are not applied
//! yet: [`plan_pocket`] plans the plain rings only.

use super::evaluator::{EvaluatorOptions, Polygon, engagement_profile};
use crate::error::JobError;
use crate::geom::{P2, Segment, p2};
use cavalier_contours::polyline::{PlineSource, PlineSourceMut, PlineVertex, Polyline, seg_arc_radius_and_center};
use serde::{Deserialize, Serialize};

/// Upper bound on the number of offset levels (keeps run time bounded for tiny step-overs).
const MAX_LEVELS: usize = 10_000;
/// Offset loops shorter than this are dropped as numerical slivers (mm).
const MIN_RING_LENGTH: f64 = 1e-6;

/// Inputs of a pocket plan (mm, mm/min).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PocketSettings {
    /// Tool radius r (mm).
    pub tool_radius: f64,
    /// Radial step-over a_e between rings (mm), 0 < a_e < D.
    pub step_over: f64,
    /// Feed rate for the machining time (mm/min).
    pub feed_mm_per_min: f64,
    /// Arc-length spacing of the evaluated tool positions (mm).
    pub spacing: f64,
}

impl PocketSettings {
    /// Range checks; each error names the parameter, the value and the allowed range.
    pub fn validate(&self) -> Result<(), JobError> {
        let r = self.tool_radius;
        if !(r.is_finite() && r > 0.0 && r <= 500.0) {
            return Err(JobError::range("tool diameter", 2.0 * r, "a finite number greater than 0 and at most 1000 mm"));
        }
        if !(self.step_over.is_finite() && self.step_over > 0.0 && self.step_over < 2.0 * r) {
            return Err(JobError::range(
                "step-over",
                self.step_over,
                format!("greater than 0 and less than the tool diameter {} mm", 2.0 * r),
            ));
        }
        if !(self.feed_mm_per_min.is_finite() && self.feed_mm_per_min > 0.0) {
            return Err(JobError::range("feed", self.feed_mm_per_min, "a finite number > 0 mm/min"));
        }
        if !(self.spacing.is_finite() && self.spacing > 0.0 && self.spacing <= r) {
            return Err(JobError::range("spacing", self.spacing, format!("greater than 0 and at most r = {r} mm")));
        }
        Ok(())
    }
}

/// One closed tool-centre ring.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Ring {
    /// Offset level k (0 = the ring next to the wall).
    pub level: usize,
    /// Inward offset of the pocket boundary, d = r + k·a_e (mm).
    pub offset_mm: f64,
    /// Closed counter-clockwise loop of lines and arcs.
    pub segments: Vec<Segment>,
    /// Length (mm).
    pub length_mm: f64,
    /// Largest engagement after the entry position, measured by the evaluator (rad).
    pub max_engagement_rad: f64,
    /// Where it occurs (mm).
    pub max_engagement_at: P2,
    /// Engagement at the entry position (rad; the tool has no swept path behind it there).
    pub entry_engagement_rad: f64,
}

/// A planned pocket.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PocketPlan {
    /// The validated pocket (counter-clockwise).
    pub polygon: Polygon,
    pub settings: PocketSettings,
    /// Rings in machining order (innermost first).
    pub rings: Vec<Ring>,
    /// Total ring length (mm), links excluded.
    pub path_length_mm: f64,
    /// Machining time of the rings at the feed (s).
    pub time_s: f64,
    /// Largest running engagement over all rings (rad), entries excluded.
    pub max_engagement_rad: f64,
}

/// Validates a pocket boundary: ≥ 3 finite vertices, no zero-length edges, not
/// self-intersecting, non-zero area; clockwise input is reversed. Errors name the parameter
/// (`polygon …`) and the offending vertex or edge index (1-based).
pub fn pocket_polygon(vertices: Vec<P2>) -> Result<Polygon, JobError> {
    Polygon::new(vertices)
}

/// The inward offset loops of a validated polygon at distance `d` (> 0, finite), as closed
/// counter-clockwise segment loops. Empty when the offset vanishes.
pub fn inward_offset(polygon: &Polygon, d: f64) -> Result<Vec<Vec<Segment>>, JobError> {
    if !(d.is_finite() && d > 0.0) {
        return Err(JobError::range("offset", d, "a finite number > 0 mm"));
    }
    let mut pline: Polyline<f64> = Polyline::new_closed();
    for v in polygon.vertices() {
        pline.add(v.x, v.y, 0.0);
    }
    // Counter-clockwise boundary: positive offset is to the left, i.e. inward.
    let mut loops = Vec::new();
    for mut off in pline.parallel_offset(d) {
        if off.vertex_count() < 2 || !off.is_closed() {
            continue;
        }
        if off.area() < 0.0 {
            off.invert_direction_mut();
        }
        let segs = to_segments(&off);
        let len: f64 = segs.iter().map(Segment::length).sum();
        if len > MIN_RING_LENGTH && segs.iter().all(|s| s.length().is_finite()) {
            loops.push(segs);
        }
    }
    Ok(loops)
}

/// Closed cavalier_contours polyline to lines and arcs. Arc from bulge b between v1 and v2:
/// centre and radius by `seg_arc_radius_and_center`, sweep `4·atan(b)` (b > 0: CCW).
fn to_segments(pl: &Polyline<f64>) -> Vec<Segment> {
    let n = pl.vertex_count();
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let v1: PlineVertex<f64> = pl.at(i);
        let v2: PlineVertex<f64> = pl.at((i + 1) % n);
        let (a, b) = (p2(v1.x, v1.y), p2(v2.x, v2.y));
        if (b - a).norm() <= 1e-12 {
            continue;
        }
        if v1.bulge.abs() <= 1e-12 {
            out.push(Segment::Line { start: a, end: b });
        } else {
            let (radius, c) = seg_arc_radius_and_center(v1, v2);
            let center = p2(c.x, c.y);
            let start_angle = (a.y - center.y).atan2(a.x - center.x);
            out.push(Segment::Arc { center, radius, start_angle, sweep: 4.0 * v1.bulge.atan() });
        }
    }
    out
}

/// Plain contour-parallel rings of a pocket, each measured by the independent evaluator.
/// Errors: settings out of range (named), a pocket too narrow for the tool (`tool diameter`).
pub fn plan_pocket(polygon: &Polygon, settings: PocketSettings) -> Result<PocketPlan, JobError> {
    settings.validate()?;
    let (r, ae) = (settings.tool_radius, settings.step_over);
    let mut levels: Vec<(usize, f64, Vec<Vec<Segment>>)> = Vec::new();
    for k in 0..MAX_LEVELS {
        let d = r + k as f64 * ae;
        let loops = inward_offset(polygon, d)?;
        if loops.is_empty() {
            break;
        }
        levels.push((k, d, loops));
    }
    if levels.is_empty() {
        return Err(JobError::range(
            "tool diameter",
            2.0 * r,
            "small enough to fit in the pocket (the inward offset of the polygon by the tool radius is empty)",
        ));
    }
    if levels.len() == MAX_LEVELS {
        return Err(JobError::range("step-over", ae, format!("large enough for at most {MAX_LEVELS} rings")));
    }
    let opts = EvaluatorOptions::new(r, settings.spacing);
    let mut rings = Vec::new();
    let mut cut: Vec<Segment> = Vec::new();
    for (k, d, loops) in levels.into_iter().rev() {
        for segs in loops {
            let prof = engagement_profile(polygon, &cut, &segs, &opts)?;
            let entry = prof.samples.first().map_or(0.0, |s| s.angle_rad);
            let best = prof.samples.iter().skip(1).fold(None, |b: Option<(f64, P2)>, s| match b {
                Some((a, _)) if a >= s.angle_rad => b,
                _ => Some((s.angle_rad, p2(s.x_mm, s.y_mm))),
            });
            let (max, at) = best.unwrap_or((entry, segs[0].start()));
            cut.extend(segs.iter().copied());
            rings.push(Ring {
                level: k,
                offset_mm: d,
                length_mm: prof.path_length_mm,
                segments: segs,
                max_engagement_rad: max,
                max_engagement_at: at,
                entry_engagement_rad: entry,
            });
        }
    }
    let len: f64 = rings.iter().map(|g| g.length_mm).sum();
    let max = rings.iter().map(|g| g.max_engagement_rad).fold(0.0, f64::max);
    Ok(PocketPlan {
        polygon: polygon.clone(),
        settings,
        rings,
        path_length_mm: len,
        time_s: len / settings.feed_mm_per_min * 60.0,
        max_engagement_rad: max,
    })
}
