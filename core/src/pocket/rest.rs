//! Rest machining (docs/pockets.md "Rest machining"): a pocket a larger tool has cleared, the
//! smaller tool clearing only what the larger one left (corners, narrow gaps).
//!
//! The larger tool's adaptive plan of the same pocket is what was cut before; the smaller
//! tool's full adaptive plan is measured over the pocket less that cut, and only its moves that
//! engage the rest material are kept, in order. Each run of kept moves starts where the full
//! plan's tool was, in stock cleared there: straight down ([`Entry::Down`]) after a retract, or
//! the full plan's own entry where the run starts with it.

use super::adaptive::{AdaptivePart, AdaptivePlan};
use super::path::PocketPath;
use super::{PocketPlan, PocketRequest, PocketSettings, PocketStrategy, guard, pace, plan_with};
use crate::corner::limits::MAX_TOOL_DIAMETER_MM;
use crate::engagement::{AIR_ENGAGEMENT_RAD, EvaluatorOptions, Stock, measure, move_peaks};
use crate::error::{Error, Param, num};
use crate::geom::{P2, Segment};
use crate::toolpath::{Entry, Toolpath};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// Longest stretch of dropped moves kept as a link at depth between two kept moves, in tool
/// diameters: a longer one is a retract and a descent straight down.
const LINK_AT_DEPTH_DIAMETERS: f64 = 2.0;

/// What a rest plan was planned after, and what it saves.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RestSource {
    /// Diameter of the larger tool that cleared the pocket before (mm, `--rest-from`).
    pub rest_from_mm: f64,
    /// Length at depth of the smaller tool's full adaptive clearing of the pocket (mm): what
    /// the rest path replaces.
    pub full_length_mm: f64,
    /// Moves of the full clearing kept (they engage the rest material, or link two that do at
    /// depth), of all its moves.
    pub kept_moves: usize,
    pub full_moves: usize,
}

/// The validated `--rest-from` diameter (mm): finite, larger than the tool diameter `d` and at
/// most the largest tool diameter. Only adaptive clearing plans rest machining.
pub fn validate_rest_from(req: &PocketRequest) -> Result<Option<f64>, Error> {
    let Some(big) = req.rest_from_mm else { return Ok(None) };
    let d = req.tool_diameter_mm;
    if !(big.is_finite() && big > d && big <= MAX_TOOL_DIAMETER_MM) {
        return Err(Error::param(
            Param::RestFrom,
            big,
            format!(
                "a finite diameter larger than the tool diameter {} mm, at most {} mm",
                num(d),
                num(MAX_TOOL_DIAMETER_MM)
            ),
        ));
    }
    if req.strategy != PocketStrategy::Adaptive {
        return Err(Error::param(
            Param::RestFrom,
            format!("{} with --method {}", num(big), req.strategy.name()),
            "--method adaptive (the default): the other methods plan no rest machining",
        ));
    }
    Ok(Some(big))
}

/// The larger tool's cut as paths the smaller tool's evaluator (radius `r`) reads: where the
/// tool of radius R = r + w swept, so did the tool of radius r along every curve within w of
/// its path. For each segment of `path`: itself, its offsets at ±j·w/n on both sides (lines
/// and concentric arcs; j = 1…n, n = ⌈w/2r⌉, so consecutive curves are at most 2r apart) and
/// circles of radius j·w/n about its ends; an arc whose inner offset would pass its centre has
/// a small circle about the centre instead. Every curve lies within w of the path, so its
/// r-sweep lies within R of it: the model never removes material the larger tool left. Every
/// point within R of the path is within r of one of the curves (the nearest point of the path
/// is on a segment or at an end; along that normal the curves are at most 2r apart), so the
/// model removes all the larger tool removed. A trochoid piece is kept as it is (its own
/// r-sweep: less than the larger tool cut, never more).
pub fn swept_as(path: &[Segment], r: f64, big_r: f64) -> Vec<Segment> {
    let w = big_r - r;
    let n = (w / (2.0 * r) - 1e-9).ceil().max(1.0) as usize;
    let offsets: Vec<f64> = (1..=n).map(|j| w * j as f64 / n as f64).collect();
    let circle = |c: P2, radius: f64| Segment::Arc { center: c, radius, start_angle: 0.0, sweep: TAU };
    let mut out = Vec::new();
    let mut ends: Vec<P2> = Vec::new();
    for &seg in path {
        out.push(seg);
        match seg {
            Segment::Line { start, end } => {
                let v = end - start;
                let len = v.norm();
                if len > 1e-9 {
                    let nrm = P2::new(-v.y, v.x) / len;
                    for &d in &offsets {
                        for s in [1.0, -1.0] {
                            out.push(Segment::Line { start: start + nrm * (s * d), end: end + nrm * (s * d) });
                        }
                    }
                }
            }
            Segment::Arc { center, radius, start_angle, sweep } => {
                for &d in &offsets {
                    out.push(Segment::Arc { center, radius: radius + d, start_angle, sweep });
                    if radius - d > 1e-6 {
                        out.push(Segment::Arc { center, radius: radius - d, start_angle, sweep });
                    } else {
                        out.push(circle(center, 1e-3));
                    }
                }
            }
            Segment::Trochoid { .. } => continue,
        }
        for p in [seg.start(), seg.end()] {
            if ends.last().is_none_or(|q| (*q - p).norm() > 1e-9) {
                ends.push(p);
            }
        }
    }
    for p in ends {
        out.extend(offsets.iter().map(|&d| circle(p, d)));
    }
    out
}

/// Plan `req` as rest machining after the larger tool `big` (mm): the larger tool's adaptive
/// plan, the smaller tool's full adaptive plan, the moves of the latter that engage the rest
/// material (more than [`AIR_ENGAGEMENT_RAD`] over the pocket less the larger tool's cut, the
/// earlier moves of the full plan cut), measured, checked against the walls and paced.
pub(super) fn plan_rest(req: &PocketRequest, settings: PocketSettings, big: f64) -> Result<PocketPlan, Error> {
    // the larger tool: the same pocket and options, its own diameter; its peak is its own plan's
    // business (it was cut before), so it is not held to this tool's target
    let large_req = PocketRequest {
        tool_diameter_mm: big,
        rest_from_mm: None,
        peak_limit_deg: Some(180.0),
        strategy: PocketStrategy::Adaptive,
        ..req.clone()
    };
    let large = super::plan(&large_req)?;
    let mut large_cut = large.toolpath().segments();
    large_cut.extend(large.toolpath().bores());
    let r = settings.tool_radius;
    let before = swept_as(&large_cut, r, big / 2.0);
    let PocketPlan::Adaptive(full) = plan_with(req, PocketStrategy::Adaptive, settings)? else {
        return Err(Error::geometry("pocket", "not planned adaptively", "a pocket adaptive clearing plans"));
    };
    let full_tp = &full.path.toolpath;
    // the full plan over the rest stock, without its entries' bores (a kept run cuts its own)
    let bare = Toolpath { moves: full_tp.moves.clone(), entries: Vec::new(), retract_before: Vec::new() };
    let opts = EvaluatorOptions::new(r, settings.spacing);
    let stock = Stock { polygon: &req.polygon, precut: &before, islands: &req.islands };
    let over_rest = measure(&bare, stock, &opts)?;
    let segments = bare.segments();
    let peak = move_peaks(&over_rest.profile, &segments);
    let mut keep: Vec<usize> = (0..segments.len()).filter(|&i| peak[i] > AIR_ENGAGEMENT_RAD).collect();
    // a short stretch of dropped moves between two kept ones, with no retract in it, stays as
    // a link at depth: it cuts nothing (it read no material) and kept the walls (the full plan
    // was checked), and it spares a retract and a descent
    let mut linked = Vec::with_capacity(keep.len());
    for (n, &k) in keep.iter().enumerate() {
        if n > 0 {
            let prev = keep[n - 1];
            let gap = prev + 1..k;
            let length: f64 = segments[gap.clone()].iter().map(Segment::length).sum();
            let retract = (prev + 1..=k).any(|j| full_tp.retract_before.contains(&j));
            if !gap.is_empty() && !retract && length <= LINK_AT_DEPTH_DIAMETERS * 2.0 * r {
                linked.extend(gap);
            }
        }
        linked.push(k);
    }
    keep = linked;
    if keep.is_empty() {
        return Err(Error::param(
            Param::RestFrom,
            num(big),
            format!(
                "a larger tool that leaves material for D = {} mm (the tool of D = {} mm leaves none it can reach)",
                num(2.0 * r),
                num(big)
            ),
        ));
    }
    // the runs: a kept move whose predecessor was dropped, or that the full plan reaches by a
    // retract, starts one; its entry is the full plan's own there, else straight down where the
    // dropped move ended (stock the full plan had cleared, and the dropped moves cut nothing)
    let entry_at = |k: usize| -> Entry {
        let own = if k == 0 {
            full_tp.entries.first()
        } else {
            full_tp.retract_before.iter().position(|&j| j == k).and_then(|p| full_tp.entries.get(p + 1))
        };
        own.copied().unwrap_or(Entry::Down { at: segments[k].start() })
    };
    let mut moves = Vec::with_capacity(keep.len());
    let (mut entries, mut retract_before) = (Vec::new(), Vec::new());
    for (n, &k) in keep.iter().enumerate() {
        let starts_run = n == 0 || keep[n - 1] + 1 != k || full_tp.retract_before.contains(&k);
        if starts_run {
            entries.push(entry_at(k));
            if n > 0 {
                retract_before.push(n);
            }
        }
        moves.push(full_tp.moves[k]);
    }
    let toolpath = Toolpath { moves, entries, retract_before };
    let mut path = PocketPath::measured_over(
        Stock { polygon: &req.polygon, precut: &before, islands: &req.islands },
        settings,
        toolpath,
        req.adaptive.depth_mm,
    )?;
    let kinds = path.kinds();
    let name = |i: usize| {
        format!("move #{} ({})", i + 1, kinds.get(i).map_or("move".into(), |k| format!("{k:?}").to_lowercase()))
    };
    guard::check_clearance_with_islands(
        (&req.polygon, &req.islands),
        &req.open_edges,
        r,
        &path.segments(),
        name,
        &path.toolpath.entries,
    )?;
    let parts = refreshed(full.parts.clone(), &keep, &path);
    path.pace = Some(pace::pace(&mut path, &req.pace)?);
    let rest = RestSource {
        rest_from_mm: big,
        full_length_mm: full.path.measurement.length_at_depth_mm,
        kept_moves: keep.len(),
        full_moves: segments.len(),
    };
    Ok(PocketPlan::Adaptive(AdaptivePlan { path, parts, rest: Some(rest), ..full }))
}

/// The full plan's parts for the rest path: their segment ranges in the kept moves (`keep`:
/// the full plan's index of each), and their corner passes' and corner points' maxima as the
/// rest path measures them (the samples on its corner and corner-point moves, each given to
/// the nearest corner, as the adaptive planner gives them; 0 where no such move is kept).
fn refreshed(mut parts: Vec<AdaptivePart>, keep: &[usize], path: &PocketPath) -> Vec<AdaptivePart> {
    let new_index = |old: usize| keep.partition_point(|&k| k < old);
    for p in &mut parts {
        p.first_segment = new_index(p.first_segment);
        p.end_segment = new_index(p.end_segment);
        p.corners.iter_mut().for_each(|c| c.max_engagement_rad = 0.0);
        p.corner_points.iter_mut().for_each(|c| c.max_engagement_rad = 0.0);
    }
    super::adaptive::corner_maxima(&mut parts, path);
    parts
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::p2;

    /// Every point within R of a line is within r of one of its model curves, and none of the
    /// curves is farther than R − r from it: sampled on a grid round the line.
    #[test]
    fn the_swept_model_covers_exactly_the_larger_sweep() {
        for (r, big_r) in [(3.0, 8.0), (1.0, 8.0), (2.0, 2.5)] {
            let line = [Segment::Line { start: p2(0.0, 0.0), end: p2(10.0, 0.0) }];
            let model = swept_as(&line, r, big_r);
            // the model of a line: lines and full circles
            let dist = |q: P2, s: &Segment| match *s {
                Segment::Line { start, end } => {
                    let v = end - start;
                    let t = ((q - start).dot(&v) / v.dot(&v)).clamp(0.0, 1.0);
                    (q - (start + v * t)).norm()
                }
                Segment::Arc { center, radius, .. } => ((q - center).norm() - radius).abs(),
                Segment::Trochoid { .. } => f64::INFINITY,
            };
            for s in &model {
                for t in [0.0, 0.3, 0.7, 1.0] {
                    assert!(dist(s.point(t), &line[0]) <= big_r - r + 1e-9, "{s:?}");
                }
            }
            for i in -100..=200 {
                for j in -100..=100 {
                    let q = p2(i as f64 * 0.1, j as f64 * 0.1);
                    if dist(q, &line[0]) <= big_r - 1e-6 {
                        assert!(model.iter().any(|s| dist(q, s) <= r + 1e-9), "{q:?} r {r} R {big_r}");
                    }
                }
            }
        }
    }

    #[test]
    fn rest_from_is_refused_by_name_outside_its_range_and_for_other_methods() {
        let base = PocketRequest { tool_diameter_mm: 6.0, ..PocketRequest::default() };
        for bad in [6.0, 4.0, f64::NAN, f64::INFINITY, 1.0e6] {
            let req = PocketRequest { rest_from_mm: Some(bad), ..base.clone() };
            let e = super::super::plan(&req).expect_err("refused");
            assert_eq!(e.subject(), Some("rest-from"), "{e}");
            assert!(e.to_string().contains("larger than the tool diameter 6 mm"), "{e}");
        }
        let req = PocketRequest { rest_from_mm: Some(16.0), strategy: PocketStrategy::MedialAxis, ..base.clone() };
        let e = super::super::plan(&req).expect_err("refused");
        assert_eq!(e.subject(), Some("rest-from"), "{e}");
        assert!(e.to_string().contains("medial-axis"), "{e}");
    }
}
