//! A slot closed at both ends, e.g. a keyway (docs/slot-paths.md, "Levels and slot ends"):
//! the slot is B wide and L long from end to end (y = 0 to y = L), and the tool centre never
//! comes nearer than r to either end wall.
//!
//! - **Entry**: a helix on the loop radius a = (B − D)/2 about (0, y₀), turning in the
//!   loops' sense and ending at the first cycle's start, so the loops begin where the helix
//!   ends; its bore (radius a + r = B/2) is the round end at y = 0 when the loops reach no
//!   further back than a. y₀ = r + max(a, −y_back), y_back ≤ 0 the lowest point of a cycle
//!   about its origin: the helix and the first cycle both keep r from the end wall y = 0.
//!   Each turn descends at most 0.1·D and at most at [`HELIX_RAMP_DEG`]: a full-width pass of
//!   the helix is never deeper than the narrow pockets' default ramp pass depth.
//! - **Loops**: whole cycles from y₀, one step s apart, as long as a cycle's front
//!   (y_front, its highest point about its origin) stays at or below L − r.
//! - **Into the end**: a short link back along the wall (x = ∓a, less than s long, through
//!   what the last cycle cut), then one more cycle whose front is exactly L − r: it cuts less
//!   than a step, so no more than a steady-state cycle does.
//!
//! Both ends are round, as a helix and a loop of radius a leave them (radius about B/2).

use super::Cycle;
use crate::error::{Error, Param, num};
use crate::geom::{P2, Segment, p2};
use crate::job::{Direction, ValidJob};
use crate::toolpath::{Helix, MoveKind};
use std::f64::consts::PI;

/// Largest ramp angle of the helix entry (degrees): the pockets' default.
pub const HELIX_RAMP_DEG: f64 = 5.0;
/// Deepest descent of one helix turn, as a share of D: the narrow pockets' default ramp pass
/// depth.
pub const HELIX_PITCH_RATIO: f64 = 0.1;
/// Smallest helix radius a = (B − D)/2 of a closed slot, as a share of D: below it a level
/// takes hundreds of helix turns.
pub const MIN_HELIX_RADIUS_RATIO: f64 = 0.05;

/// The planar path of one level of a closed slot.
#[derive(Clone, Debug, PartialEq)]
pub struct ClosedSlot {
    /// The job's cycle (in the job's direction).
    pub cycle: Cycle,
    /// The entry of every level: about (0, y₀), radius a, ending at the first cycle's start.
    pub helix: Helix,
    /// y₀: origin of the first cycle (mm).
    pub first_origin_y: f64,
    /// Whole cycles from y₀.
    pub cycles: usize,
    /// Origin of the cycle into the end, whose front is L − r (mm).
    pub end_origin_y: f64,
    /// Lowest and highest y of the tool centre (mm): r and L − r where the path touches the
    /// ends.
    pub centre_y_mm: (f64, f64),
}

impl ClosedSlot {
    /// The closed-slot path of a validated job (checked by [`ClosedSlot::check`]).
    pub fn for_job(job: &ValidJob) -> ClosedSlot {
        let cycle = job_cycle(job);
        let (r, a, s) = (job.tool_radius(), job.trochoidal_radius(), job.step);
        let (back, front) = (extreme_y(&cycle, -1.0), extreme_y(&cycle, 1.0));
        let y0 = r + a.max(-back);
        let end_origin_y = job.slot_length - r - front;
        // whole cycles whose front stays at or below L − r
        let fit = ((end_origin_y - y0) / s + 1e-9).floor().max(0.0) as usize + 1;
        // the cycle into the end replaces a last whole cycle that already ends there
        let cycles = if end_origin_y - (y0 + (fit - 1) as f64 * s) < 1e-6 { fit - 1 } else { fit };
        let conventional = job.direction == Direction::Conventional;
        let ramp = HELIX_RAMP_DEG.to_radians().min((HELIX_PITCH_RATIO * job.tool_diameter / (2.0 * PI * a)).atan());
        let helix = Helix {
            center: p2(0.0, y0),
            radius: a,
            start_angle: if conventional { PI } else { 0.0 },
            sense: if conventional { -1.0 } else { 1.0 },
            ramp_rad: ramp,
        };
        let centre_y_mm = ((y0 - a).min(y0 + back), end_origin_y + front);
        ClosedSlot { cycle, helix, first_origin_y: y0, cycles, end_origin_y, centre_y_mm }
    }

    /// The least slot length of a closed slot (mm): r at each end, the first cycle's reach
    /// behind its origin (at least a: the helix) and one cycle's front.
    pub fn least_length(job: &ValidJob) -> f64 {
        let cycle = job_cycle(job);
        let (back, front) = (extreme_y(&cycle, -1.0), extreme_y(&cycle, 1.0));
        2.0 * job.tool_radius() + job.trochoidal_radius().max(-back) + front
    }

    /// Whether a closed slot fits the job: the helix radius (B − D)/2 at least
    /// [`MIN_HELIX_RADIUS_RATIO`]·D, the length at least [`ClosedSlot::least_length`].
    pub fn check(job: &ValidJob) -> Result<(), Error> {
        let d = job.tool_diameter;
        let least_width = d * (1.0 + 2.0 * MIN_HELIX_RADIUS_RATIO);
        if job.slot_width < least_width {
            return Err(Error::param(
                Param::SlotWidth,
                job.slot_width,
                format!(
                    "at least {} mm for a closed slot (--closed): its helix entry turns on the loop radius \
                     (B − D)/2, at least {}·D",
                    num(least_width),
                    num(MIN_HELIX_RADIUS_RATIO)
                ),
            ));
        }
        let least = ClosedSlot::least_length(job);
        if job.slot_length < least - 1e-9 {
            return Err(Error::param(
                Param::SlotLength,
                job.slot_length,
                format!(
                    "at least {} mm for a closed slot (--closed) of this width, tool and path: the tool \
                     centre keeps r = {} mm from each end, with room for the helix and one loop between",
                    num(least),
                    num(job.tool_radius())
                ),
            ));
        }
        Ok(())
    }

    /// Origin of whole cycle `i`.
    pub fn origin(&self, i: usize) -> P2 {
        p2(0.0, self.first_origin_y + i as f64 * self.cycle.step)
    }

    /// The link from the end of the whole cycles to the start of the cycle into the end, along
    /// the loops' start line x = ∓a; `None` where they meet.
    pub fn link(&self) -> Option<Segment> {
        let x = self.cycle.segments[0].start().x;
        let (from, to) = (p2(x, self.origin(self.cycles).y), p2(x, self.end_origin_y));
        ((to - from).norm() > 1e-9).then_some(Segment::Line { start: from, end: to })
    }

    /// Every move of one level in the plane, in order, with what it does: the helix's flat turn
    /// at the level (the entry), the whole cycles, the link and the cycle into the end.
    pub fn moves(&self) -> Vec<(Segment, MoveKind)> {
        let mut out = vec![(self.helix.circle(), MoveKind::Entry)];
        for i in 0..self.cycles {
            let o = self.origin(i);
            out.extend(self.cycle.segments.iter().map(|s| (s.translated(o), MoveKind::Circle)));
        }
        out.extend(self.link().map(|l| (l, MoveKind::Link)));
        let o = p2(0.0, self.end_origin_y);
        out.extend(self.cycle.segments.iter().map(|s| (s.translated(o), MoveKind::Circle)));
        out
    }
}

/// The job's cycle in its direction (as [`super::SlotPath::for_job`]).
fn job_cycle(job: &ValidJob) -> Cycle {
    let paper = Cycle::for_job(job);
    match job.direction {
        Direction::Conventional => paper,
        Direction::Climb => paper.mirrored_x(),
    }
}

/// The largest `sign`·y of the cycle's points (sign +1: its front, −1: minus its back), about
/// its origin: the best of 256 points per segment, refined by ternary search between its
/// neighbours (to ~10⁻¹² of the segment).
fn extreme_y(cycle: &Cycle, sign: f64) -> f64 {
    const N: usize = 256;
    let mut best = f64::NEG_INFINITY;
    for seg in &cycle.segments {
        let f = |t: f64| sign * seg.eval(t).p.y;
        let (mut at, mut value) = (0, f(0.0));
        for i in 1..=N {
            let v = f(i as f64 / N as f64);
            if v > value {
                (at, value) = (i, v);
            }
        }
        let (mut lo, mut hi) = ((at.saturating_sub(1)) as f64 / N as f64, ((at + 1).min(N)) as f64 / N as f64);
        for _ in 0..80 {
            let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
            if f(m1) < f(m2) { lo = m1 } else { hi = m2 }
        }
        best = best.max(value).max(f(0.5 * (lo + hi)));
    }
    sign * best
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::job::{Job, PathKind};

    fn keyway(direction: Direction) -> ValidJob {
        Job {
            slot_width: 10.0,
            slot_length: 60.0,
            depth: 12.0,
            tool_diameter: 8.0,
            closed: true,
            direction,
            ..Job::default()
        }
        .validate()
        .expect("valid keyway")
    }

    /// Every point of every move (sampled every ~0.01 mm) keeps r from both end walls and a
    /// from the centre line; the moves join; the path reaches both ends (within 1 µm).
    #[test]
    fn the_tool_centre_stays_r_from_both_ends_and_reaches_them() {
        let jobs = [
            keyway(Direction::Conventional),
            keyway(Direction::Climb),
            Job { closed: true, slot_length: 40.0, ..Job::default() }.validate().expect("valid"),
            Job { closed: true, slot_length: 40.0, path: PathKind::Elliptical, aspect_ratio: 0.6, ..Job::default() }
                .validate()
                .expect("valid"),
            Job { closed: true, slot_length: 40.0, path: PathKind::Elliptical, aspect_ratio: 1.2, ..Job::default() }
                .validate()
                .expect("valid"),
            Job {
                closed: true,
                slot_length: 40.0,
                path: PathKind::LinearElliptical,
                aspect_ratio: 0.8,
                linear_distance: 0.75,
                ..Job::default()
            }
            .validate()
            .expect("valid"),
            Job { closed: true, slot_length: 40.0, path: PathKind::CircularType, ..Job::default() }
                .validate()
                .expect("valid"),
        ];
        for job in jobs {
            let c = ClosedSlot::for_job(&job);
            let (r, a, l) = (job.tool_radius(), job.trochoidal_radius(), job.slot_length);
            let moves = c.moves();
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for (seg, _) in &moves {
                let n = (seg.length() / 0.01).ceil() as usize + 1;
                for p in seg.sample(n) {
                    assert!(p.x.abs() <= a + 1e-9, "{:?}: x {}", job.path, p.x);
                    (lo, hi) = (lo.min(p.y), hi.max(p.y));
                }
            }
            assert!(lo >= r - 1e-9 && hi <= l - r + 1e-9, "{:?}: y from {lo} to {hi}", job.path);
            assert!(hi > l - r - 1e-3, "{:?}: reaches the far end: {hi}", job.path);
            assert!((c.centre_y_mm.1 - (l - r)).abs() < 1e-9 && c.centre_y_mm.0 >= r - 1e-9);
            for w in moves.windows(2) {
                assert!((w[1].0.start() - w[0].0.end()).norm() < 1e-9, "{:?}: moves join", job.path);
            }
            // the link goes back less than one step, through what the last cycle cut
            if let Some(link) = c.link() {
                assert!(link.end().y < link.start().y && link.length() < job.step, "{link:?}");
            }
        }
        // the circular keyway: the helix bore is the round end at y = 0 (y₀ = r + a = B/2)
        let c = ClosedSlot::for_job(&keyway(Direction::Conventional));
        assert!((c.first_origin_y - 5.0).abs() < 1e-12 && (c.centre_y_mm.0 - 4.0).abs() < 1e-12);
    }

    #[test]
    fn a_closed_slot_too_short_or_too_narrow_names_the_flag_and_range() {
        // shorter than the tool, and shorter than the least length (about B + s/4 for a circular path)
        for l in [5.0, 9.0, 10.0] {
            let job = Job { closed: true, slot_width: 10.0, tool_diameter: 8.0, slot_length: l, ..Job::default() };
            let err = crate::plan::plan(&job).expect_err("too short");
            assert_eq!(err.parameter(), Some(Param::SlotLength), "{err}");
            assert!(err.to_string().contains("--closed") && err.to_string().contains("at least"), "{err}");
        }
        // (B − D)/2 = 0.2 mm < 0.05 · 10 mm
        let job = Job { closed: true, slot_width: 10.4, tool_diameter: 10.0, step: 0.5, ..Job::default() };
        let err = crate::plan::plan(&job).expect_err("too narrow");
        assert_eq!(err.parameter(), Some(Param::SlotWidth), "{err}");
        // the same job open is fine
        assert!(crate::plan::plan(&Job { closed: false, ..job }).is_ok());
    }
}
