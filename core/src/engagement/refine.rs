//! Adaptive sampling of the engagement along a path ([`refined_profile`]): the positions of
//! the uniform profile ([`engagement_profile`](super::evaluator::engagement_profile): every
//! `spacing` mm and every segment end), evaluated only where the engagement changes.
//!
//! **Sampling plan.** The candidates are exactly the uniform profile's positions, so every
//! sample of the refined profile is a sample of the uniform one, with the same value.
//! 1. *Coarse:* every segment end (kinks, where the engagement peaks, are always evaluated),
//!    the path's ends, and between them a position at least every
//!    H = max(spacing, [`COARSE_SPACING_PER_RADIUS`] · r) mm.
//! 2. *Refine:* between two neighbouring evaluated positions with candidates left between
//!    them, the middle candidate is evaluated when the engagement is not linear within
//!    [`REFINE_TOLERANCE_RAD`] (0.05°) over that interval and one beside it (the line through
//!    either neighbouring interval's samples misses this interval's far end by more), or when
//!    its ends lie on either side of the air threshold (1°); repeated (bisection) until no
//!    interval asks. A kink, a peak or an edge of the cut is thus sampled at every candidate,
//!    with one coarse interval of margin each side; where the engagement is linear within the
//!    tolerance over three coarse intervals in a row (steady cuts along straight and circular
//!    passes, slow drifts, air) the middle one is taken as settled.
//! 3. Each pass of the bisection evaluates its positions in parallel (rayon).
//!
//! **Bound.** The refined profile's samples are a subset of the uniform profile's, so its
//! peak is never above the uniform peak. It is below it only if the engagement departs from
//! the line through its neighbours by more than the tolerance inside one coarse interval and
//! comes back before the next sample, with no trace in the evaluated samples: a bump narrower
//! than 2·H (2.5 mm for D = 10). The planners' paths have their kinks at segment ends, where
//! the samples are, so the stated bound — **the peak is within 0.1° of the uniform profile's**,
//! so is the peak of every kind of move, the 95th percentile (length-weighted) within 0.1° and
//! the air length within 1% + 2·spacing — is tested, not proven: on the six reference outlines,
//! the 60 × 40 rectangle with every method, corners and single paths against the uniform
//! profile (`core/tests/refined_profile.rs`). Such bumps do occur below the peak: with
//! isometric circles on the 60 × 40 rectangle the tool grazes slivers of material in air, to
//! 2.8° over 0.75 mm, unseen (3 mm more air of 1397 mm).
//!
//! The samples are not evenly spaced: consumers weight them by the arc length each one
//! stands for ([`sample_weights`]), so the 95th percentile and the air length are shares of
//! path length, as for the uniform profile.

use super::evaluator::{EngagementProfile, EngagementSample, Evaluation, EvaluatorOptions};
use super::measure::AIR_ENGAGEMENT_RAD;
use crate::error::Error;
use crate::geom::{Polygon, Segment};
use rayon::prelude::*;

/// Coarse spacing of the first evaluation, in tool radii: H = 0.25·r (1.25 mm for D = 10),
/// at least the spacing.
pub const COARSE_SPACING_PER_RADIUS: f64 = 0.25;

/// Engagement change (rad) across an interval above which it is refined: 0.05°.
pub const REFINE_TOLERANCE_RAD: f64 = 0.05 * std::f64::consts::PI / 180.0;

/// Most candidate positions (path length / spacing) of one refined profile: bounds the memory
/// of the candidates' arc lengths (80 MB) — a pocket of some 2 m² at D = 10 mm and the
/// default spacing.
pub const MAX_REFINED_POSITIONS: f64 = 1.0e7;

/// Engagement along `path` over `stock` after the `before` paths, as
/// [`engagement_profile`](super::evaluator::engagement_profile) but evaluated adaptively (see
/// the module docs): the samples are a subset of its samples, dense where the engagement
/// changes and every H = max(spacing, 0.25·r) mm where it is steady.
pub fn refined_profile(
    stock: &Polygon,
    before: &[Segment],
    path: &[Segment],
    opts: &EvaluatorOptions,
) -> Result<EngagementProfile, Error> {
    refined_profile_with_islands(stock, &[], before, path, opts)
}

/// [`refined_profile`] over the stock polygon `stock` without its `islands` (polygons inside
/// it, apart from its edges and from each other: material that stays, never cut).
pub fn refined_profile_with_islands(
    stock: &Polygon,
    islands: &[Polygon],
    before: &[Segment],
    path: &[Segment],
    opts: &EvaluatorOptions,
) -> Result<EngagementProfile, Error> {
    let eval = Evaluation::new(stock, before, path, opts, MAX_REFINED_POSITIONS)?.with_islands(islands);
    let positions = eval.positions();
    let coarse = (COARSE_SPACING_PER_RADIUS * opts.tool_radius).max(opts.spacing);
    let picks = coarse_picks(&positions, eval.segment_ends(), coarse);
    let mut done: Vec<(usize, EngagementSample)> =
        picks.into_par_iter().map(|k| (k, eval.sample(positions[k]))).collect();
    loop {
        let split: Vec<usize> = (0..done.len().saturating_sub(1))
            .filter(|&j| done[j + 1].0 - done[j].0 >= 2 && unsettled(&done, j))
            .map(|j| (done[j].0 + done[j + 1].0) / 2)
            .collect();
        if split.is_empty() {
            break;
        }
        let new: Vec<(usize, EngagementSample)> =
            split.into_par_iter().map(|k| (k, eval.sample(positions[k]))).collect();
        done = merged(done, new);
    }
    Ok(EngagementProfile { samples: done.into_iter().map(|(_, s)| s).collect(), path_length_mm: eval.total })
}

/// Indices into `positions` (ascending arc lengths) of the first evaluation: the first and the
/// last, every segment end, and the first position at least `coarse` mm after the previous
/// pick (less 1e-9 mm of rounding).
fn coarse_picks(positions: &[f64], ends: &[f64], coarse: f64) -> Vec<usize> {
    let mut picks = Vec::with_capacity(positions.len() / 4 + ends.len() + 2);
    let mut e = 0; // next segment end not yet passed
    let mut last = f64::NEG_INFINITY;
    for (k, &s) in positions.iter().enumerate() {
        while e < ends.len() && ends[e] < s - 1e-9 {
            e += 1;
        }
        let at_end = e < ends.len() && (ends[e] - s).abs() <= 1e-9;
        if k == 0 || k + 1 == positions.len() || at_end || s >= last + coarse - 1e-9 {
            picks.push(k);
            last = s;
        }
    }
    picks
}

/// Whether the interval between evaluated samples j and j + 1 is to be refined: the
/// engagement is not linear within [`REFINE_TOLERANCE_RAD`] over it and an interval beside it
/// (the line through either neighbouring interval's samples misses the far end of this one by
/// more), or it changes by more than the tolerance across it with no neighbour to compare, or
/// its ends lie on either side of the air threshold ([`AIR_ENGAGEMENT_RAD`]).
fn unsettled(done: &[(usize, EngagementSample)], j: usize) -> bool {
    let at = |k: usize| (done[k].1.s_mm, done[k].1.angle_rad);
    let ((sa, a), (sb, b)) = (at(j), at(j + 1));
    if (a < AIR_ENGAGEMENT_RAD) != (b < AIR_ENGAGEMENT_RAD) {
        return true;
    }
    // the line through samples k and k + 1, at arc length s
    let line = |k: usize, s: f64| {
        let ((s0, v0), (s1, v1)) = (at(k), at(k + 1));
        if s1 > s0 { v0 + (v1 - v0) * (s - s0) / (s1 - s0) } else { v0 }
    };
    let left = (j >= 1).then(|| (line(j - 1, sb) - b).abs());
    let right = (j + 2 < done.len()).then(|| (line(j + 1, sa) - a).abs());
    match (left, right) {
        (None, None) => (a - b).abs() > REFINE_TOLERANCE_RAD,
        (l, r) => l.into_iter().chain(r).any(|e| e > REFINE_TOLERANCE_RAD),
    }
}

/// The union of two lists ascending in their first element (no element in both).
fn merged(a: Vec<(usize, EngagementSample)>, b: Vec<(usize, EngagementSample)>) -> Vec<(usize, EngagementSample)> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut a, mut b) = (a.into_iter().peekable(), b.into_iter().peekable());
    loop {
        let take_a = match (a.peek(), b.peek()) {
            (Some(x), Some(y)) => x.0 < y.0,
            (Some(_), None) => true,
            (None, Some(_)) => false,
            (None, None) => break,
        };
        let next = if take_a { a.next() } else { b.next() };
        out.extend(next);
    }
    out
}

/// The arc length each sample of `profile` stands for: half the way to each neighbour (the
/// first and last sample: half the way to their one neighbour). They sum to the span of the
/// samples; a uniform profile's inner samples weigh one spacing each.
pub fn sample_weights(profile: &EngagementProfile) -> Vec<f64> {
    let s: Vec<f64> = profile.samples.iter().map(|x| x.s_mm).collect();
    (0..s.len())
        .map(|k| {
            let before = if k > 0 { s[k] - s[k - 1] } else { 0.0 };
            let after = if k + 1 < s.len() { s[k + 1] - s[k] } else { 0.0 };
            0.5 * (before + after)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engagement::engagement_profile;
    use crate::geom::p2;

    fn sample(s: f64, angle: f64) -> EngagementSample {
        EngagementSample { s_mm: s, x_mm: 0.0, y_mm: 0.0, angle_rad: angle, chip: 0.0 }
    }

    #[test]
    fn coarse_picks_keep_ends_and_segment_ends() {
        // positions 0, 0.25, …, 3 and a segment end at 1.1 (derived by hand: picks every
        // coarse = 1 mm from the last pick, the end 1.1 restarting the count)
        let mut positions: Vec<f64> = (0..=12).map(|k| f64::from(k) * 0.25).collect();
        positions.push(1.1);
        positions.sort_by(f64::total_cmp);
        let picks = coarse_picks(&positions, &[1.1, 3.0], 1.0);
        let at: Vec<f64> = picks.iter().map(|&k| positions[k]).collect();
        assert_eq!(at, vec![0.0, 1.0, 1.1, 2.25, 3.0]);
    }

    #[test]
    fn a_change_is_refined_a_flat_stretch_is_not() {
        let flat = [sample(0.0, 1.0), sample(1.0, 1.0), sample(2.0, 1.0), sample(3.0, 1.0)];
        let done: Vec<(usize, EngagementSample)> = flat.iter().enumerate().map(|(k, &s)| (4 * k, s)).collect();
        assert!((0..3).all(|j| !unsettled(&done, j)));
        let mut step = done.clone();
        step[3].1.angle_rad = 1.0 + 2.0 * REFINE_TOLERANCE_RAD;
        // the change is in interval 2; interval 1 is beside it, interval 0 is not
        assert_eq!((0..3).map(|j| unsettled(&step, j)).collect::<Vec<_>>(), vec![false, true, true]);
    }

    #[test]
    fn a_linear_drift_is_settled_unless_it_crosses_the_air_threshold() {
        // 0.3° more every interval (six times the tolerance), exactly linear: no interval asks
        let deg = f64::to_radians;
        let ramp: Vec<(usize, EngagementSample)> =
            (0..5).map(|k| (4 * k, sample(f64::from(k as u32), deg(10.0 + 0.3 * f64::from(k as u32))))).collect();
        assert!((0..4).all(|j| !unsettled(&ramp, j)));
        // the same drift from 0.45° to 1.65°: the interval from 0.75° to 1.05° crosses 1°
        let air: Vec<(usize, EngagementSample)> =
            (0..5).map(|k| (4 * k, sample(f64::from(k as u32), deg(0.45 + 0.3 * f64::from(k as u32))))).collect();
        assert_eq!((0..4).map(|j| unsettled(&air, j)).collect::<Vec<_>>(), vec![false, true, false, false]);
    }

    #[test]
    fn weights_are_the_length_each_sample_stands_for() {
        let p = EngagementProfile {
            samples: vec![sample(0.0, 0.0), sample(1.0, 0.0), sample(1.5, 0.0), sample(3.5, 0.0)],
            path_length_mm: 3.5,
        };
        // halves of the gaps 1, 0.5, 2 on either side
        assert_eq!(sample_weights(&p), vec![0.5, 0.75, 1.25, 1.0]);
    }

    #[test]
    fn refined_samples_are_uniform_samples() {
        // a slot into a block that ends: engagement 180°, then air past the block's end
        let stock = Polygon::new(vec![p2(0.0, -20.0), p2(30.0, -20.0), p2(30.0, 20.0), p2(0.0, 20.0)]).unwrap();
        let path = [Segment::Line { start: p2(-10.0, 0.0), end: p2(50.0, 0.0) }];
        let opts = EvaluatorOptions::new(5.0, 0.25);
        let uniform = engagement_profile(&stock, &[], &path, &opts).unwrap();
        let refined = refined_profile(&stock, &[], &path, &opts).unwrap();
        assert!(refined.samples.len() < uniform.samples.len());
        for s in &refined.samples {
            let u = uniform.samples.iter().find(|u| (u.s_mm - s.s_mm).abs() < 1e-12).unwrap();
            assert_eq!(u, s);
        }
        assert_eq!(refined.max_angle(), uniform.max_angle());
        let air = |p: &EngagementProfile| p.air_length_mm(crate::engagement::AIR_ENGAGEMENT_RAD);
        assert!((air(&refined) - air(&uniform)).abs() < 1e-9, "{} {}", air(&refined), air(&uniform));
    }
}
