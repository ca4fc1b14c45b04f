//! Generic engagement evaluator (docs/corners.md): any tool-centre path of
//! exact segments over any simple stock polygon.
//!
//! Material at a tool position = inside the stock polygon and farther than `r` from every
//! tool-centre position swept before (the `before` paths, then the path itself up to the
//! current position). The engaged angle is the measure of the tool periphery in material: the
//! periphery is sampled at `samples` points (720 by default) and every in/out transition is
//! refined by bisection on the same predicate to ~1e-10 rad, so the result is far finer than the
//! sample spacing. Points of the periphery ahead of the tool are exactly `r` from the current
//! position; they count as material (the predicate is `distance ≥ r − 1e-11 mm`; the tangency at the side of the tool makes that an
//! angular error of √(2·1e-11/r) ≈ 1e-4° at r = 5), points behind
//! are nearer than `r` to the path just travelled and do not.
//!
//! This module deliberately shares nothing with the analytic two-circle model
//! ([`super::model`]): it is the independent check of every corner strategy.

use super::nearby::{CutGrid, Cutter, LocalStock};
use crate::error::{Error, Param, num};
use crate::geom::{P2, Polygon, Segment, p2};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

/// Distance tolerance of the material test (mm).
const DIST_TOL: f64 = 1e-11;
/// Bisection steps refining one in/out transition on the periphery.
const REFINE_STEPS: usize = 36;
/// Upper bound of tool positions in one evaluation (keeps run time bounded).
const MAX_POSITIONS: f64 = 2.0e5;
/// Lines used for one trochoid piece (the evaluator works on lines and arcs).
const TROCHOID_LINES: usize = 256;

/// Reads the points of a tool path "x,y" (or "x y", "x;y"), one per line; `what` names the
/// file in errors: the point-list reader of outlines ([`crate::outline::text::path_points`]),
/// its empty lines ignored.
pub fn parse_points(text: &str, what: &str) -> Result<Vec<P2>, Error> {
    crate::outline::text::path_points(what, text)
}

/// A tool-centre polyline from points; consecutive duplicate points are skipped.
pub fn polyline(points: &[P2]) -> Result<Vec<Segment>, Error> {
    let mut segs = Vec::new();
    let mut last: Option<P2> = None;
    for &p in points {
        if !(p.x.is_finite() && p.y.is_finite()) {
            return Err(Error::geometry("path point", format!("({}, {})", num(p.x), num(p.y)), "finite coordinates"));
        }
        match last {
            Some(q) if (p - q).norm() <= 1e-12 => {}
            Some(q) => {
                segs.push(Segment::Line { start: q, end: p });
                last = Some(p);
            }
            None => last = Some(p),
        }
    }
    if segs.is_empty() {
        return Err(Error::geometry("path points", points.len(), "at least 2 distinct points"));
    }
    Ok(segs)
}

/// Evaluation settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EvaluatorOptions {
    /// Tool radius r (mm).
    pub tool_radius: f64,
    /// Arc-length spacing of evaluated tool positions (mm).
    pub spacing: f64,
    /// Periphery samples before refinement (≥ 8; 720 = every 0.5°).
    pub samples: usize,
    /// Radial margin of the periphery (mm, ≥ 0): the periphery tested is the circle of radius
    /// r + margin about the tool centre, the material cut by the tool still the points nearer
    /// than r to the swept path. 0 measures the tool; a margin > 0 asks whether uncut material
    /// comes within the margin of the tool (a move through cleared stock reads 0 with a margin).
    #[serde(default)]
    pub margin_mm: f64,
}

impl EvaluatorOptions {
    /// Tool radius and position spacing with 720 periphery samples.
    pub fn new(tool_radius: f64, spacing: f64) -> EvaluatorOptions {
        EvaluatorOptions { tool_radius, spacing, samples: 720, margin_mm: 0.0 }
    }

    fn validate(&self) -> Result<(), Error> {
        if !(self.tool_radius.is_finite() && self.tool_radius > 0.0) {
            return Err(Error::param(Param::ToolDiameter, 2.0 * self.tool_radius, "a finite number > 0 mm"));
        }
        if !(self.spacing.is_finite() && self.spacing > 0.0) {
            return Err(Error::param(Param::Spacing, self.spacing, "a finite number > 0 mm"));
        }
        if !(self.margin_mm.is_finite() && self.margin_mm >= 0.0 && self.margin_mm <= self.tool_radius) {
            return Err(Error::geometry("margin", self.margin_mm, "from 0 to the tool radius"));
        }
        if !(8..=100_000).contains(&self.samples) {
            return Err(Error::geometry("samples", self.samples, "from 8 to 100000"));
        }
        Ok(())
    }
}

/// Engagement at one tool position.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EngagementSample {
    /// Arc length along the evaluated path (mm).
    pub s_mm: f64,
    /// Tool-centre position (mm).
    pub x_mm: f64,
    pub y_mm: f64,
    /// Engaged angle of the periphery (rad).
    pub angle_rad: f64,
    /// Chip factor κ = h_max / f_z: the largest cos(θ − θ_f) over the engaged periphery, θ_f the
    /// direction of travel (1 where the point straight ahead is in material, sin φ for a side
    /// cut of engagement φ ≤ 90°, 0 where nothing is engaged). A tooth at angle θ from the
    /// direction of travel cuts a chip h = f_z·cos(θ − θ_f) (the circular-path approximation of
    /// the chip, docs/pockets.md).
    #[serde(default)]
    pub chip: f64,
}

/// Engagement along a whole path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EngagementProfile {
    /// One sample per evaluated position, in path order.
    pub samples: Vec<EngagementSample>,
    /// Path length (mm).
    pub path_length_mm: f64,
}

impl EngagementProfile {
    /// The sample with the largest engagement (None for an empty profile).
    pub fn max(&self) -> Option<EngagementSample> {
        self.samples.iter().copied().fold(None, |best: Option<EngagementSample>, s| match best {
            Some(b) if b.angle_rad >= s.angle_rad => Some(b),
            _ => Some(s),
        })
    }

    /// Largest engagement (rad), 0 for an empty profile.
    pub fn max_angle(&self) -> f64 {
        self.max().map_or(0.0, |s| s.angle_rad)
    }

    /// Path length between consecutive samples that both engage less than `threshold` (rad):
    /// the moves in air (engagement < 1°).
    pub fn air_length_mm(&self, threshold: f64) -> f64 {
        self.samples
            .windows(2)
            .filter(|w| w[0].angle_rad < threshold && w[1].angle_rad < threshold)
            .fold(0.0, |sum, w| sum + (w[1].s_mm - w[0].s_mm))
    }
}

/// Exact distance from `p` to the line or arc of `k` (its end points precomputed).
fn distance(p: P2, k: &Cutter) -> f64 {
    match k.seg {
        Segment::Line { start, end } => {
            let d = end - start;
            let l2 = d.norm_squared();
            let t = if l2 > 0.0 { ((p - start).dot(&d) / l2).clamp(0.0, 1.0) } else { 0.0 };
            (p - (start + d * t)).norm()
        }
        Segment::Arc { center, radius, start_angle, sweep } => {
            let v = p - center;
            let on_arc = if sweep.abs() <= PI {
                // p's direction lies in the wedge from the start to the end direction (≤ π):
                // after the start and before the end in the sweep's sense
                let cross = |a: P2, b: P2| a.x * b.y - a.y * b.x;
                let sense = sweep.signum();
                sense * cross(k.start - center, v) >= 0.0 && sense * cross(v, k.end - center) >= 0.0
            } else {
                let ang = v.y.atan2(v.x);
                // Parameter of p's direction along the sweep, in [0, 2π) measured in sweep sense.
                let rel = if sweep >= 0.0 {
                    (ang - start_angle).rem_euclid(TAU)
                } else {
                    (start_angle - ang).rem_euclid(TAU)
                };
                rel <= sweep.abs()
            };
            if on_arc { (v.norm() - radius).abs() } else { (p - k.start).norm().min((p - k.end).norm()) }
        }
        // Not reached: trochoid pieces are flattened to lines before evaluation.
        Segment::Trochoid { .. } => f64::INFINITY,
    }
}

/// A lower bound of the distance from `p` to the segment of `k`: exact within `reach` of its
/// box, the distance to the box beyond.
fn lower_distance(p: P2, k: &Cutter, reach: f64) -> f64 {
    if k.within(p, reach) { distance(p, k) } else { k.box_distance(p) }
}

/// Whether `p` is at least `r − tol` from the segment of `k` (not cut by it). A point more
/// than r·(1 + 1e-9) outside the segment's box is, without computing the distance.
fn leaves(p: P2, k: &Cutter, r: f64, tol: f64) -> bool {
    !k.within(p, r * (1.0 + 1e-9)) || distance(p, k) >= r - tol
}

/// Lines and arcs only: trochoid pieces become `TROCHOID_LINES` chords each.
fn flatten(path: &[Segment]) -> Vec<Segment> {
    let mut out = Vec::with_capacity(path.len());
    for seg in path {
        match seg {
            Segment::Trochoid { .. } => {
                let pts = seg.sample(TROCHOID_LINES);
                out.extend(pts.windows(2).map(|w| Segment::Line { start: w[0], end: w[1] }));
            }
            _ => out.push(*seg),
        }
    }
    out
}

fn check_segments(path: &[Segment], name: &'static str) -> Result<(), Error> {
    for (i, s) in path.iter().enumerate() {
        let (a, b) = (s.start(), s.end());
        if !(a.x.is_finite() && a.y.is_finite() && b.x.is_finite() && b.y.is_finite() && s.length().is_finite()) {
            return Err(Error::geometry(name, format!("segment #{} is not finite", i + 1), "finite coordinates"));
        }
    }
    Ok(())
}

/// Engagement along `path` (tool-centre segments) over `stock`, after the tool already swept
/// the `before` paths (previous rings, earlier passes; no engagement reported for them).
/// Positions are `spacing` apart in arc length, plus the end of every segment (where the
/// engagement peaks at kinks), each one evaluated; at most 2·10⁵ of them. Measurements of whole
/// tool paths evaluate a subset of these positions chosen adaptively
/// ([`refined_profile`](super::refine::refined_profile)).
pub fn engagement_profile(
    stock: &Polygon,
    before: &[Segment],
    path: &[Segment],
    opts: &EvaluatorOptions,
) -> Result<EngagementProfile, Error> {
    engagement_profile_on(stock, before, path, opts, None)
}

/// [`engagement_profile`] at the positions of the segments `on` selects only (`on[i]` for
/// `path[i]`; `None`: all): the material is still cut by every segment before each position,
/// selected or not. The samples' arc lengths are along the whole path.
pub fn engagement_profile_on(
    stock: &Polygon,
    before: &[Segment],
    path: &[Segment],
    opts: &EvaluatorOptions,
    on: Option<&[bool]>,
) -> Result<EngagementProfile, Error> {
    // the bound counts the positions evaluated: those of the selected segments
    let whole = if on.is_some() { f64::INFINITY } else { MAX_POSITIONS };
    let eval = Evaluation::new(stock, before, path, opts, whole)?;
    let mut positions = eval.positions();
    if let Some(on) = on {
        positions.retain(|&s| on.get(eval.segment_of(s)).copied().unwrap_or(false));
        let selected: f64 = path.iter().zip(on).filter(|(_, o)| **o).map(|(s, _)| s.length()).sum();
        if positions.len() as f64 > MAX_POSITIONS {
            return Err(Error::param(
                Param::Spacing,
                opts.spacing,
                format!("≥ selected path length / {} = {} mm", num(MAX_POSITIONS), num(selected / MAX_POSITIONS)),
            ));
        }
    }
    let samples = positions.into_par_iter().map(|s| eval.sample(s)).collect();
    Ok(EngagementProfile { samples, path_length_mm: eval.total })
}

/// One path prepared for evaluation over one stock: the path flattened to lines and arcs, the
/// swept segments binned ([`CutGrid`]) and the periphery's directions. [`Evaluation::sample`]
/// evaluates any one position; which positions is the caller's choice (every one of
/// [`Evaluation::positions`] in [`engagement_profile`], a subset in
/// [`refined_profile`](super::refine::refined_profile)).
pub(crate) struct Evaluation<'a> {
    stock: &'a Polygon,
    /// Islands inside the stock polygon: not material ([`Evaluation::with_islands`]).
    islands: &'a [Polygon],
    path: Vec<Segment>,
    lengths: Vec<f64>,
    /// Arc length at the end of every segment, summed in path order.
    ends: Vec<f64>,
    /// Path length (mm).
    pub total: f64,
    /// Spacing of the positions (mm).
    pub spacing: f64,
    grid: CutGrid,
    /// Number of `before` segments (the first grid indices).
    nb: usize,
    r: f64,
    tol: f64,
    reach: f64,
    periphery: Periphery,
    /// Periphery margin ([`EvaluatorOptions::margin_mm`]).
    margin: f64,
    /// The segment of the path as given of each flattened segment.
    origin: Vec<usize>,
}

impl<'a> Evaluation<'a> {
    /// Validates the inputs and prepares the evaluation; refuses a path with more than
    /// `max_positions` positions `spacing` apart (the error names the spacing and its least
    /// value).
    pub(crate) fn new(
        stock: &'a Polygon,
        before: &[Segment],
        path: &[Segment],
        opts: &EvaluatorOptions,
        max_positions: f64,
    ) -> Result<Evaluation<'a>, Error> {
        opts.validate()?;
        check_segments(before, "before path")?;
        check_segments(path, "path")?;
        if path.is_empty() {
            return Err(Error::geometry("path", "empty", "at least one segment"));
        }
        let r = opts.tool_radius;
        let origin: Vec<usize> = path
            .iter()
            .enumerate()
            .flat_map(|(i, s)| {
                std::iter::repeat_n(i, if matches!(s, Segment::Trochoid { .. }) { TROCHOID_LINES } else { 1 })
            })
            .collect();
        let path = flatten(path);
        let lengths: Vec<f64> = path.iter().map(Segment::length).collect();
        let mut ends = Vec::with_capacity(lengths.len());
        let mut end = 0.0;
        for l in &lengths {
            end += l;
            ends.push(end);
        }
        let total: f64 = lengths.iter().sum();
        if total / opts.spacing > max_positions {
            return Err(Error::param(
                Param::Spacing,
                opts.spacing,
                format!("≥ path length / {} = {} mm", num(max_positions), num(total / max_positions)),
            ));
        }
        let tol = DIST_TOL * r.min(1.0);
        let before = flatten(before);
        let nb = before.len();
        let cutters: Vec<Cutter> = before.into_iter().chain(path.iter().copied()).map(Cutter::new).collect();
        // Reach r·(1 + 1e-9): every segment within r of a periphery point (see `leaves`).
        let reach = r * (1.0 + 1e-9);
        let grid = CutGrid::new(cutters, reach);
        let periphery = Periphery::new(opts.samples);
        Ok(Evaluation {
            stock,
            islands: &[],
            path,
            lengths,
            ends,
            total,
            spacing: opts.spacing,
            grid,
            nb,
            r,
            tol,
            reach,
            periphery,
            margin: opts.margin_mm,
            origin,
        })
    }

    /// Arc lengths of the positions, ascending: 0, spacing, 2·spacing, …, and the end of every
    /// segment (the engagement peaks at kinks, e.g. where a move ends in a corner point, and
    /// can fall by tens of degrees within 0.1 mm before it); positions within 1e-9 mm are one.
    pub(crate) fn positions(&self) -> Vec<f64> {
        let (total, spacing) = (self.total, self.spacing);
        let mut targets: Vec<f64> = Vec::new();
        let mut k = 0.0;
        while k * spacing < total - 1e-9 {
            targets.push(k * spacing);
            k += 1.0;
        }
        targets.extend(self.ends.iter().map(|e| e.min(total)));
        targets.push(total);
        targets.sort_by(f64::total_cmp);
        targets.dedup_by(|a, b| (*a - *b).abs() <= 1e-9);
        targets
    }

    /// The segment of the path as given (before trochoid pieces became lines) of the position at
    /// arc length `s`.
    pub(crate) fn segment_of(&self, s: f64) -> usize {
        let i = self.ends.partition_point(|&e| e < s).min(self.path.len() - 1);
        self.origin[i]
    }

    /// Arc lengths of the segments' ends (summed in path order, as [`Evaluation::positions`]
    /// holds them).
    pub(crate) fn segment_ends(&self) -> &[f64] {
        &self.ends
    }

    /// Engagement at arc length `s` (0 ≤ s ≤ path length): the position on the first segment
    /// whose end is at or beyond s.
    pub(crate) fn sample(&self, s: f64) -> EngagementSample {
        self.sample_with(s, None)
    }

    /// [`Evaluation::sample`] and the engaged arcs of the periphery there: `(start, end)`
    /// world angles (rad), counter-clockwise from start to end, `end − start` in (0, 2π].
    pub(crate) fn sample_arcs(&self, s: f64) -> (EngagementSample, Vec<(f64, f64)>) {
        let mut ends = Vec::new();
        let sample = self.sample_with(s, Some(&mut ends));
        (sample, arcs_of(&ends))
    }

    /// The same evaluation with `islands` (polygons inside the stock polygon, apart from its
    /// edges and from each other) taken out of the stock: the material is inside the stock
    /// polygon and outside every island.
    pub(crate) fn with_islands(mut self, islands: &'a [Polygon]) -> Evaluation<'a> {
        self.islands = islands;
        self
    }

    /// Whether `q` is material for the tool at arc length `s`: inside the stock and at least r
    /// (less the tolerance) from the `before` paths and from the path up to `s`.
    pub(crate) fn material_at(&self, s: f64, q: P2) -> bool {
        let i = self.ends.partition_point(|&e| e < s).min(self.path.len() - 1);
        let s0 = if i == 0 { 0.0 } else { self.ends[i - 1] };
        let local = if self.lengths[i] > 0.0 { ((s - s0) / self.lengths[i]).clamp(0.0, 1.0) } else { 1.0 };
        let head = Cutter::new(self.path[i].part(0.0, local));
        if !self.stock.contains(q) || self.islands.iter().any(|i| i.contains(q)) || !leaves(q, &head, self.r, self.tol)
        {
            return false;
        }
        let (near, _) = self.grid.near(q);
        for (_, k) in near.take_while(|(j, _)| *j < self.nb + i) {
            if !leaves(q, k, self.r, self.tol) {
                return false;
            }
        }
        true
    }

    fn sample_with(&self, s: f64, ends: Option<&mut Vec<(f64, bool)>>) -> EngagementSample {
        let (path, grid, stock, periphery) = (&self.path, &self.grid, self.stock, &self.periphery);
        let (r, tol, reach, nb) = (self.r, self.tol, self.reach, self.nb);
        let i = self.ends.partition_point(|&e| e < s).min(path.len() - 1);
        let s0 = if i == 0 { 0.0 } else { self.ends[i - 1] };
        let local = if self.lengths[i] > 0.0 { ((s - s0) / self.lengths[i]).clamp(0.0, 1.0) } else { 1.0 };
        let seg = &path[i];
        let c = seg.point(local);
        // Cut so far: the `before` paths (grid indices below nb), the path before segment i,
        // and segment i up to the position.
        // The segment that cut the last point tried is tried first (neighbouring points of
        // the periphery are mostly cut by the same segment).
        let head = Cutter::new(seg.part(0.0, local));
        let last = std::cell::Cell::new(head);
        let room = |p: P2| {
            if !leaves(p, &head, r, tol) || !leaves(p, &last.get(), r, tol) {
                return None;
            }
            let (near, gap) = grid.near(p);
            let mut room = lower_distance(p, &head, reach).min(r + gap);
            for (_, k) in near.take_while(|(j, _)| *j < nb + i) {
                if !leaves(p, k, r, tol) {
                    last.set(*k);
                    return None;
                }
                room = room.min(lower_distance(p, k, reach));
            }
            Some(room - r)
        };
        let rp = r + self.margin;
        let stock = LocalStock::new(stock, self.islands, c, rp);
        let d1 = seg.eval(local).d1;
        let ahead = if d1.norm() > 0.0 { Some(d1.y.atan2(d1.x)) } else { None };
        let (mut angle, chip) = engaged_angle(&stock, c, rp, room, periphery, ahead, ends);
        // Behind a tool that has moved, every point of the periphery is nearer than r to the
        // path just travelled: the engaged arc lies in the front half. Only the tolerance of
        // the material test at the two side points can make it read more than π.
        if s > 0.0 {
            angle = angle.min(PI);
        }
        EngagementSample { s_mm: s, x_mm: c.x, y_mm: c.y, angle_rad: angle, chip }
    }
}

/// The unit directions of the periphery samples, θ_k = k·2π/n.
struct Periphery {
    step: f64,
    dirs: Vec<P2>,
}

impl Periphery {
    fn new(n: usize) -> Periphery {
        let step = TAU / n as f64;
        let dirs = (0..n)
            .map(|k| {
                let th = k as f64 * step;
                p2(th.cos(), th.sin())
            })
            .collect();
        Periphery { step, dirs }
    }
}

/// Measure (rad) of the periphery (radius `r`) about `c` that lies in material: inside the
/// stock and not cut, and its chip factor ([`EngagementSample::chip`]) for travel in direction
/// `ahead` (rad; `None`: 0). `room(p)` is `None` where p is cut (nearer than the tool radius −
/// tol to the swept path), else a lower bound of its distance from the swept path minus the tool
/// radius: the next samples closer to p than that (less a rounding margin) are not cut either,
/// without asking again.
fn engaged_angle(
    stock: &LocalStock,
    c: P2,
    r: f64,
    room: impl Fn(P2) -> Option<f64>,
    periphery: &Periphery,
    ahead: Option<f64>,
    mut ends: Option<&mut Vec<(f64, bool)>>,
) -> (f64, f64) {
    if matches!(stock, LocalStock::Outside) {
        return (0.0, 0.0);
    }
    let in_material = |p: P2| room(p).is_some() && stock.contains(p);
    let at = |th: f64| c + p2(th.cos(), th.sin()) * r;
    let (n, step) = (periphery.dirs.len(), periphery.step);
    let mut flags: Vec<bool> = Vec::with_capacity(n);
    while flags.len() < n {
        let p = c + periphery.dirs[flags.len()] * r;
        let Some(free) = room(p) else {
            flags.push(false);
            continue;
        };
        // Sample k + j is at most r·j·step from sample k.
        let same = (free - 1e-9 * (1.0 + r)) / (r * step);
        let more = if same.is_finite() && same > 1.0 { same.ceil() as usize - 1 } else { 0 };
        let k = flags.len();
        for j in k..(k + 1 + more).min(n) {
            flags.push(stock.contains(c + periphery.dirs[j] * r));
        }
    }
    let count = flags.iter().filter(|&&f| f).count();
    if count == 0 {
        return (0.0, 0.0);
    }
    // The chip factor: 1 where the point ahead is in material, else the largest cosine at an
    // end of an engaged arc (the cosine falls away from `ahead` on both sides).
    let ahead_in = |th: f64| if in_material(at(th)) { 1.0 } else { 0.0 };
    if count == n {
        if let Some(e) = ends.as_deref_mut() {
            e.push((0.0, false));
        }
        return (TAU, ahead.map_or(0.0, |_| 1.0));
    }
    let mut total = if flags[0] { TAU } else { 0.0 };
    let mut chip = ahead.map_or(0.0, ahead_in);
    for k in 0..n {
        let (a, b) = (flags[k], flags[(k + 1) % n]);
        if a == b {
            continue;
        }
        // Bisection between sample k (state a) and k+1 (state b).
        let (mut lo, mut hi) = (k as f64 * step, (k + 1) as f64 * step);
        for _ in 0..REFINE_STEPS {
            let mid = 0.5 * (lo + hi);
            if in_material(at(mid)) == a {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let boundary = 0.5 * (lo + hi);
        total += if a { boundary } else { -boundary };
        if let Some(e) = ends.as_deref_mut() {
            e.push((boundary, !a));
        }
        if let Some(f) = ahead {
            chip = f64::max(chip, (boundary - f).cos());
        }
    }
    (total, chip.max(0.0))
}

/// Arcs from the boundaries of [`engaged_angle`] in increasing angle (`true`: material
/// starts there); one `(θ, false)` alone: the whole periphery.
fn arcs_of(ends: &[(f64, bool)]) -> Vec<(f64, f64)> {
    match ends {
        [] => Vec::new(),
        [(a, false)] => vec![(*a, a + TAU)],
        _ => {
            let n = ends.len();
            (0..n)
                .filter(|&k| ends[k].1)
                .map(|k| {
                    let start = ends[k].0;
                    let end = (1..=n).map(|j| ends[(k + j) % n]).find(|e| !e.1).map_or(start, |e| e.0);
                    (start, start + (end - start).rem_euclid(TAU))
                })
                .collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x0: f64, y0: f64, x1: f64, y1: f64) -> Polygon {
        Polygon::new(vec![p2(x0, y0), p2(x1, y0), p2(x1, y1), p2(x0, y1)]).unwrap()
    }

    #[test]
    fn straight_cut_engagement_is_arccos_of_depth() {
        // Independent of the two-circle model: a straight pass with radial depth a_e into a block whose wall is
        // y = a_e above the tool's edge. Expected arccos(1 − a_e/r), the straight cut of docs/corners.md.
        let r = 5.0;
        for (ae_d, want_deg) in [(0.05, 25.842), (0.10, 36.870), (0.20, 53.130), (0.30, 66.422), (0.50, 90.0)] {
            let ae = ae_d * 10.0;
            // Material: y from r − ae to 100 (tool centre on y = 0 moving +x).
            let stock = square(-50.0, r - ae, 50.0, 100.0);
            let path = [Segment::Line { start: p2(-20.0, 0.0), end: p2(20.0, 0.0) }];
            let prof = engagement_profile(&stock, &[], &path, &EvaluatorOptions::new(r, 1.0)).unwrap();
            // Steady state away from the ends.
            for s in prof.samples.iter().filter(|s| s.s_mm > 10.0 && s.s_mm < 30.0) {
                let got = s.angle_rad.to_degrees();
                assert!((got - want_deg).abs() < 1e-3, "ae/D {ae_d}: got {got}, want {want_deg}");
            }
        }
    }

    #[test]
    fn chip_factor_of_a_side_cut_is_the_sine_of_the_engagement() {
        // Tool moving +x, material y ≥ r − a_e: the engaged arc runs from θ₁ (sin θ₁ = 1 − a_e/r)
        // up to the side at 90° (behind it is cut), so φ = 90° − θ₁ and the largest cos θ over it
        // is cos θ₁ = sin φ: h_max = f_z·sin φ, the side-milling chip for φ ≤ 90°.
        let r = 5.0;
        for ae in [0.5, 1.527, 3.0, 5.0] {
            let stock = square(-50.0, r - ae, 50.0, 100.0);
            let path = [Segment::Line { start: p2(-20.0, 0.0), end: p2(20.0, 0.0) }];
            let prof = engagement_profile(&stock, &[], &path, &EvaluatorOptions::new(r, 1.0)).unwrap();
            for s in prof.samples.iter().filter(|s| s.s_mm > 10.0 && s.s_mm < 30.0) {
                // the angle carries the side tangency's tolerance (module doc), ~1e-6 here
                let want = s.angle_rad.sin();
                assert!((s.chip - want).abs() < 1e-5, "a_e {ae}: chip {} want {want}", s.chip);
                assert!((s.chip - (1.0 - (1.0 - ae / r).powi(2)).sqrt()).abs() < 1e-6);
            }
        }
        // A full slot has the point ahead in material: κ = 1.
        let stock = square(-50.0, -50.0, 50.0, 50.0);
        let path = [Segment::Line { start: p2(-20.0, 0.0), end: p2(20.0, 0.0) }];
        let prof = engagement_profile(&stock, &[], &path, &EvaluatorOptions::new(r, 1.0)).unwrap();
        assert!(prof.samples.iter().filter(|s| s.s_mm > 5.0).all(|s| s.chip == 1.0));
    }

    #[test]
    fn margin_finds_stock_near_a_move_through_cleared_space() {
        // A channel cut along y = 0 (the `before` path) leaves material from |y| = r; a pass
        // along it again engages nothing, and any margin reaches the material. Two more cuts at
        // y = ±0.3 widen the channel to |y| < r + 0.3: a margin of 0.2 mm then finds nothing,
        // 0.5 mm finds the walls.
        let r = 5.0;
        let line = |y: f64| Segment::Line { start: p2(-30.0, y), end: p2(30.0, y) };
        let path = [Segment::Line { start: p2(-10.0, 0.0), end: p2(10.0, 0.0) }];
        let stock = square(-50.0, -50.0, 50.0, 50.0);
        // 0 within the tangency tolerance at the tool's sides (module doc): below 1e-4 rad
        let read = |margin: f64, before: &[Segment]| {
            let opts = EvaluatorOptions { margin_mm: margin, ..EvaluatorOptions::new(r, 0.5) };
            let a = engagement_profile(&stock, before, &path, &opts).unwrap().max_angle();
            if a < 1e-4 { 0.0 } else { a }
        };
        let channel = [line(0.0)];
        assert_eq!(read(0.0, &channel), 0.0);
        assert!(read(0.2, &channel) > 0.0);
        let wide = [line(0.0), line(0.3), line(-0.3)];
        assert_eq!(read(0.0, &wide), 0.0);
        assert_eq!(read(0.2, &wide), 0.0);
        assert!(read(0.5, &wide) > 0.0);
        let bad = EvaluatorOptions { margin_mm: -0.1, ..EvaluatorOptions::new(r, 0.5) };
        assert_eq!(engagement_profile(&stock, &channel, &path, &bad).unwrap_err().subject(), Some("margin"));
    }

    #[test]
    fn a_selection_is_bounded_by_its_own_positions() {
        // 60 000 mm at 0.25 mm is 240 000 positions, over the bound of 200 000: the whole path
        // is refused, a selection of a 20 mm segment after it evaluates its 80 positions (0.25 to
        // 20 mm along it every 0.25: the position on the joint belongs to the segment that ends
        // there), the long segment alone is refused again.
        let stock = square(-100.0, -100.0, 70_000.0, 100.0);
        let path = [
            Segment::Line { start: p2(0.0, 0.0), end: p2(60_000.0, 0.0) },
            Segment::Line { start: p2(60_000.0, 0.0), end: p2(60_020.0, 0.0) },
        ];
        let opts = EvaluatorOptions::new(5.0, 0.25);
        assert_eq!(engagement_profile(&stock, &[], &path, &opts).unwrap_err().subject(), Some("spacing"));
        let short = engagement_profile_on(&stock, &[], &path, &opts, Some(&[false, true])).unwrap();
        assert_eq!(short.samples.len(), 80);
        assert!(short.samples.iter().all(|s| s.s_mm > 60_000.0));
        let long = engagement_profile_on(&stock, &[], &path, &opts, Some(&[true, false])).unwrap_err();
        assert_eq!(long.subject(), Some("spacing"));
    }

    #[test]
    fn full_slot_is_half_the_periphery() {
        let stock = square(-50.0, -50.0, 50.0, 50.0);
        let path = [Segment::Line { start: p2(-20.0, 0.0), end: p2(20.0, 0.0) }];
        let prof = engagement_profile(&stock, &[], &path, &EvaluatorOptions::new(5.0, 2.0)).unwrap();
        let mid = prof.samples.iter().find(|s| s.s_mm >= 20.0).unwrap();
        assert!((mid.angle_rad.to_degrees() - 180.0).abs() < 1e-3, "{mid:?}");
    }

    #[test]
    fn parse_points_reads_csv_with_header_and_reports_bad_lines() {
        let pts = parse_points("x,y\n0,0\n1.5, 2\n# comment\n\n3 4\n", "path").unwrap();
        assert_eq!(pts, vec![p2(0.0, 0.0), p2(1.5, 2.0), p2(3.0, 4.0)]);
        let err = parse_points("0,0\n1,abc\n", "path").unwrap_err().to_string();
        assert!(err.contains("line 2"), "{err}");
        assert!(parse_points("0,0\nNaN,1\n", "path").is_err());
        assert_eq!(polyline(&[p2(0.0, 0.0), p2(0.0, 0.0)]).unwrap_err().subject(), Some("path points"));
    }

    #[test]
    fn bad_options_are_named() {
        let stock = square(0.0, 0.0, 1.0, 1.0);
        let path = [Segment::Line { start: p2(0.0, 0.0), end: p2(1.0, 0.0) }];
        for (o, name) in [
            (EvaluatorOptions::new(0.0, 1.0), "tool-diameter"),
            (EvaluatorOptions::new(1.0, f64::NAN), "spacing"),
            (EvaluatorOptions { samples: 2, ..EvaluatorOptions::new(1.0, 1.0) }, "samples"),
        ] {
            assert_eq!(engagement_profile(&stock, &[], &path, &o).unwrap_err().subject(), Some(name));
        }
        let empty = engagement_profile(&stock, &[], &[], &EvaluatorOptions::new(1.0, 1.0)).unwrap_err();
        assert_eq!(empty.subject(), Some("path"));
    }
}
