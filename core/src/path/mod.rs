//! Slot tool-centre paths (Wagih et al. 2023, sections 2–3; docs/slot-paths.md).
//!
//! The slot runs along +y, centred on x = 0, stock from y = 0 to y = L. A path is one *cycle*
//! (a list of exact segments starting at the left extreme x = −a, y = 0 and ending at
//! x = −a, y = s) repeated with a translation of s·ŷ. Trochoidal radius a = (B − D)/2,
//! b = r_e·a. A [`Cycle`] follows the paper's eq. (1) orientation: it starts at the left
//! extreme moving +y and turns clockwise seen from +z — conventional milling with M3; the
//! analysis works in this frame. A [`SlotPath`] is the job's path in the job's
//! [`Direction`]: for climb milling every cycle is mirrored in the slot's centre line x = 0
//! (it starts at the right extreme and turns counter-clockwise; docs/slot-paths.md).
//!
//! A [`SlotPath`] is the open slot's path (entered from outside the stock at y < 0, leaving
//! it beyond y = L); [`closed`] the path of a slot closed at both ends, and [`levels`] the
//! slot's depth in equal levels.

pub mod closed;
pub mod levels;

use crate::geom::{P2, Segment, SegmentPoint, p2};
use crate::job::{Direction, PathKind, ValidJob};
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

/// One cycle of a periodic path, relative to the cycle origin.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Cycle {
    /// Exact segments, G1-continuous, start (−a, 0), end (−a, s).
    pub segments: Vec<Segment>,
    /// Advance per cycle along +y, s (mm).
    pub step: f64,
    /// Arc length of each segment (mm).
    pub lengths: Vec<f64>,
}

/// A position on a cycle: segment index and local parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CyclePos {
    pub seg: usize,
    pub t: f64,
}

impl Cycle {
    fn new(segments: Vec<Segment>, step: f64) -> Cycle {
        let lengths = segments.iter().map(Segment::length).collect();
        Cycle { segments, step, lengths }
    }

    /// The cycle of the given path kind (paper eq. 1 and section 3; docs/slot-paths.md).
    pub fn for_job(job: &ValidJob) -> Cycle {
        let (a, s) = (job.trochoidal_radius(), job.step);
        let b = job.b();
        let troch = |origin: P2, theta0: f64, theta1: f64| Segment::Trochoid { origin, a, b, step: s, theta0, theta1 };
        let segments = match job.path {
            PathKind::Circular | PathKind::Elliptical => vec![troch(P2::zeros(), 0.0, TAU)],
            PathKind::LinearElliptical => {
                let d = job.linear_distance;
                let mut segs = Vec::with_capacity(4);
                if d > 0.0 {
                    segs.push(Segment::Line { start: p2(-a, 0.0), end: p2(-a, d) });
                }
                segs.push(troch(p2(0.0, d), 0.0, PI));
                if d > 0.0 {
                    segs.push(Segment::Line { start: p2(a, d + s / 2.0), end: p2(a, s / 2.0) });
                }
                segs.push(troch(P2::zeros(), PI, TAU));
                segs
            }
            PathKind::CircularType => vec![
                Segment::Line { start: p2(-a, 0.0), end: p2(-a, s) },
                Segment::Arc { center: p2(0.0, s), radius: a, start_angle: PI, sweep: -TAU },
            ],
        };
        Cycle::new(segments, s)
    }

    /// The cycle mirrored in x = 0 ([`Segment::mirrored_x`]): the climb-milling loop.
    pub fn mirrored_x(&self) -> Cycle {
        Cycle { segments: self.segments.iter().map(Segment::mirrored_x).collect(), ..self.clone() }
    }

    /// Path length of one cycle (mm).
    pub fn length(&self) -> f64 {
        self.lengths.iter().sum()
    }

    /// Position and derivatives at a cycle position.
    #[inline]
    pub fn eval(&self, pos: CyclePos) -> SegmentPoint {
        self.segments[pos.seg].eval(pos.t)
    }

    /// The position `ds` (mm, ≥ 0) further along the cycle from `pos`, or `None` past the end.
    pub fn advance(&self, mut pos: CyclePos, mut ds: f64) -> Option<CyclePos> {
        loop {
            let seg = &self.segments[pos.seg];
            let rest = seg.length_between(pos.t, 1.0);
            if ds <= rest {
                return Some(CyclePos { seg: pos.seg, t: seg.param_after_length(pos.t, ds) });
            }
            ds -= rest;
            pos = CyclePos { seg: pos.seg + 1, t: 0.0 };
            if pos.seg >= self.segments.len() {
                return None;
            }
        }
    }

    /// Positions spaced `spacing` mm along the cycle starting `offset` mm after its start,
    /// as (arc length from cycle start, position). Marches segment by segment; each step
    /// inverts the exact arc length over the step only.
    pub fn positions(&self, offset: f64, spacing: f64) -> Vec<(f64, CyclePos)> {
        let mut out = Vec::with_capacity(((self.length() - offset).max(0.0) / spacing) as usize + 2);
        let mut seg_start = 0.0; // arc length at the start of the current segment
        let mut next = offset; // arc length of the next position
        for (k, (seg, &len)) in self.segments.iter().zip(&self.lengths).enumerate() {
            let (mut t, mut at) = (0.0, seg_start);
            while next <= seg_start + len {
                t = seg.param_after_length(t, next - at);
                at = next;
                out.push((next, CyclePos { seg: k, t }));
                next += spacing;
            }
            seg_start += len;
        }
        out
    }

    /// `n` points per segment of the cycle shifted by `shift`, for plotting.
    pub fn sample(&self, shift: P2, n: usize) -> Vec<P2> {
        let mut pts = Vec::new();
        for seg in &self.segments {
            let s = seg.translated(shift).sample(n);
            let skip = usize::from(!pts.is_empty());
            pts.extend(s.into_iter().skip(skip));
        }
        pts
    }
}

/// A complete slot path: the cycle repeated from outside the stock to beyond its end.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SlotPath {
    pub kind: PathKind,
    pub cycle: Cycle,
    /// y of the first cycle origin (mm, negative: the tool starts outside the stock).
    pub first_origin_y: f64,
    /// Number of cycles.
    pub cycles: usize,
}

impl SlotPath {
    /// The slot path for a validated job.
    ///
    /// The first cycle is placed so that its swept region just reaches the stock face y = 0
    /// (the tool starts outside the stock); cycles repeat until the left extreme of the last
    /// one is at or beyond the slot end y = L, so both walls are cut over the full length.
    /// The job's direction decides the loops' sense (module docs).
    pub fn for_job(job: &ValidJob) -> SlotPath {
        let paper = Cycle::for_job(job);
        let cycle = match job.direction {
            Direction::Conventional => paper,
            Direction::Climb => paper.mirrored_x(),
        };
        let reach = cycle.segments.iter().flat_map(|s| s.sample(64)).map(|p| p.y).fold(f64::NEG_INFINITY, f64::max)
            + job.tool_radius();
        let first_origin_y = -reach;
        let cycles = ((job.slot_length - first_origin_y) / job.step).ceil() as usize + 1;
        SlotPath { kind: job.path, cycle, first_origin_y, cycles }
    }

    /// Origin of cycle `i`.
    pub fn origin(&self, i: usize) -> P2 {
        p2(0.0, self.first_origin_y + i as f64 * self.cycle.step)
    }

    /// Total path length (mm).
    pub fn length(&self) -> f64 {
        self.cycle.length() * self.cycles as f64
    }

    /// All segments of the path, in order.
    pub fn segments(&self) -> impl Iterator<Item = Segment> + '_ {
        (0..self.cycles).flat_map(move |i| self.cycle.segments.iter().map(move |s| s.translated(self.origin(i))))
    }

    /// Points of cycles `first..first+count` for plotting (`n` points per segment).
    pub fn sample_cycles(&self, first: usize, count: usize, n: usize) -> Vec<P2> {
        let mut pts = Vec::new();
        for i in first..(first + count).min(self.cycles) {
            let s = self.cycle.sample(self.origin(i), n);
            let skip = usize::from(!pts.is_empty());
            pts.extend(s.into_iter().skip(skip));
        }
        pts
    }
}

/// The cycle of the default job with another path, r_e and d (tests of this crate).
#[cfg(test)]
#[allow(clippy::expect_used)]
pub(crate) fn test_cycle(path: PathKind, r_e: f64, d: f64) -> Cycle {
    let job = crate::job::Job { path, aspect_ratio: r_e, linear_distance: d, ..crate::job::Job::default() };
    Cycle::for_job(&job.validate().expect("valid"))
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::job::Job;
    use test_cycle as cycle;

    #[test]
    fn every_cycle_starts_at_left_extreme_and_advances_one_step() {
        for (kind, r_e, d) in [
            (PathKind::Circular, 1.0, 0.0),
            (PathKind::Elliptical, 0.6, 0.0),
            (PathKind::LinearElliptical, 0.8, 0.75),
            (PathKind::CircularType, 1.0, 0.0),
        ] {
            let c = cycle(kind, r_e, d);
            let first = c.segments.first().expect("segments").start();
            let last = c.segments.last().expect("segments").end();
            assert!((first - p2(-5.0, 0.0)).norm() < 1e-12, "{kind:?} start {first}");
            assert!((last - p2(-5.0, 1.0)).norm() < 1e-12, "{kind:?} end {last}");
            for w in c.segments.windows(2) {
                let (e0, e1) = (w[0].eval(1.0), w[1].eval(0.0));
                assert!((e0.p - e1.p).norm() < 1e-12, "{kind:?} gap");
                let turn = crate::geom::cross(e0.d1.normalize(), e1.d1.normalize());
                assert!(turn.abs() < 1e-9 && e0.d1.dot(&e1.d1) > 0.0, "{kind:?} not tangent-continuous");
            }
        }
    }

    #[test]
    fn linear_elliptical_adds_two_d_per_cycle() {
        let base = cycle(PathKind::Elliptical, 0.8, 0.0).length();
        let lin = cycle(PathKind::LinearElliptical, 0.8, 1.2).length();
        assert!((lin - base - 2.4).abs() < 1e-9, "{lin} - {base}");
        let zero = cycle(PathKind::LinearElliptical, 0.8, 0.0).length();
        assert!((zero - base).abs() < 1e-9);
    }

    #[test]
    fn circular_type_is_step_plus_full_circle() {
        let c = cycle(PathKind::CircularType, 1.0, 0.0);
        assert!((c.length() - (1.0 + TAU * 5.0)).abs() < 1e-12);
    }

    #[test]
    fn positions_are_spaced_by_arc_length() {
        let c = cycle(PathKind::LinearElliptical, 0.7, 0.5);
        let pos = c.positions(0.0, 0.075);
        assert_eq!(pos.len(), (c.length() / 0.075).floor() as usize + 1);
        for w in pos.windows(2) {
            let (p0, p1) = (c.eval(w[0].1).p, c.eval(w[1].1).p);
            let chord = (p1 - p0).norm();
            assert!(chord <= 0.075 + 1e-12 && chord > 0.0749, "chord {chord}");
        }
    }

    #[test]
    fn slot_path_starts_outside_stock_and_ends_beyond_it() {
        let job = Job::default().validate().expect("valid");
        let path = SlotPath::for_job(&job);
        let first = path.segments().next().expect("segment").start();
        assert!(first.y + job.tool_radius() < 0.0, "tool starts outside the stock");
        let last_origin = path.origin(path.cycles - 1);
        assert!(last_origin.y >= job.slot_length);
        assert!((path.length() - path.cycles as f64 * path.cycle.length()).abs() < 1e-9);
    }
}
