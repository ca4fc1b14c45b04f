//! Rapid or fast feed: which way a machine crosses cleared stock at depth sooner.
//!
//! A straight stretch through cleared stock can run as a rapid (`G0`) or as a feed move at the
//! largest feed (`G1`). The rapid's rate is at least the largest feed, but a controller runs a
//! rapid from rest to rest ([`super::program_time`]): the feed moves before it brake to a stop
//! at its start and those after it start from rest at its end. A feed move instead blends into
//! its neighbours at the speed their curvature and the corners allow. Over a long stretch the
//! rapid's higher rate wins; over a short one, between the small loops of a trochoid, the two
//! stops cost more than the rapid gains.
//!
//! [`feed_link_gain`] plans both with the feed planner ([`plan_feed`]) over a window of the
//! neighbouring feed moves, each side at most [`window_mm`] long: the rapid as three runs
//! (before, rapid, after; each from rest to rest), the feed link as one run. Both start and end
//! the window at rest; the window is long enough that the machine reaches its largest feed from
//! rest within it, so the speed at the window's ends, where the two plans differ from the
//! machine's real motion, is the same in both.

use super::Machine;
use super::planner::{Dynamics, plan_feed};
use crate::geom::Segment;

/// Length of the window of feed moves on each side of a stretch (mm): the distance in which
/// the machine reaches its largest feed v from rest on a curve, v²/(2·a_t) with the tangential
/// acceleration a_t = a/2 ([`super::planner::TANGENTIAL_SHARE`]), plus v·a/J for the
/// jerk-limited start and end of the ramp (an S-curve from rest to v runs v²/(2a_t) +
/// v·a_t/(2J)), and 1 mm.
pub fn window_mm(m: &Machine) -> f64 {
    let (v, a, j) = (m.max_speed_mm_per_s(), m.acceleration(), m.jerk());
    v * v / a + v * a / j + 1.0
}

/// Time saved (s) by running the straight `line` as a feed move at `link_feed` (mm/min),
/// blended with the feed moves `before` and `after` it (each segment with its feed, mm/min,
/// in the order of the path: `before` ends where `line` starts, `after` starts where it
/// ends), rather than as a rapid from rest to rest: positive where the feed link is sooner.
pub fn feed_link_gain(
    before: &[(Segment, f64)],
    line: Segment,
    after: &[(Segment, f64)],
    link_feed: f64,
    m: &Machine,
) -> f64 {
    let d = Dynamics::of(m);
    let d_rapid = Dynamics { v_max: m.rapid_mm_per_min() / 60.0, ..d };
    let time = |moves: &[(Segment, f64)], d: &Dynamics| {
        if moves.is_empty() {
            return 0.0;
        }
        let (segs, feeds): (Vec<Segment>, Vec<f64>) = moves.iter().copied().unzip();
        plan_feed(&segs, &feeds, d).time_s()
    };
    let as_rapid = time(before, &d) + time(&[(line, m.rapid_mm_per_min())], &d_rapid) + time(after, &d);
    let whole: Vec<(Segment, f64)> =
        before.iter().copied().chain(std::iter::once((line, link_feed))).chain(after.iter().copied()).collect();
    as_rapid - time(&whole, &d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::p2;

    fn vmc() -> Machine {
        Machine::preset("vmc").unwrap()
    }

    /// A half circle of radius `a` about (x, 0) from its bottom to its top (counter-clockwise).
    fn loop_at(x: f64, a: f64) -> Segment {
        Segment::Arc {
            center: p2(x, 0.0),
            radius: a,
            start_angle: -std::f64::consts::FRAC_PI_2,
            sweep: std::f64::consts::PI,
        }
    }

    #[test]
    fn a_short_link_between_small_loops_is_sooner_as_a_feed_move() {
        // Two loops of radius 2.8 mm joined by a 5.6 mm straight back across: the arcs hold at
        // most √(0.866·a·R) = 85 mm/s on `vmc` (a = 3000 mm/s², planner module doc), so the
        // feed link starts near that speed, where the rapid starts from rest, and a 5.6 mm
        // rapid from rest to rest takes at least 2·√(5.6/3000) = 86 ms (a bang-bang move at
        // a), while 5.6 mm at 85 mm/s take 66 ms.
        let m = vmc();
        let before = [(loop_at(0.0, 2.8), 1000.0)];
        let line = Segment::Line { start: p2(0.0, 2.8), end: p2(0.0, -2.8) };
        let after = [(loop_at(0.0, 2.8), 1000.0)];
        let gain = feed_link_gain(&before, line, &after, 20_000.0, &m);
        assert!(gain > 0.0, "gain {gain}");
    }

    #[test]
    fn a_long_stretch_is_sooner_as_a_rapid() {
        // 400 mm between two feed moves at 600 mm/min: the rapid at 24000 mm/min saves
        // 400/333 − 400/400 = 0.2 s over the feed link at 20000 mm/min, far more than the
        // stops cost when the neighbours run at 10 mm/s (a stop from 10 mm/s takes ~10 ms).
        let m = vmc();
        let before = [(Segment::Line { start: p2(-20.0, 0.0), end: p2(0.0, 0.0) }, 600.0)];
        let line = Segment::Line { start: p2(0.0, 0.0), end: p2(400.0, 0.0) };
        let after = [(Segment::Line { start: p2(400.0, 0.0), end: p2(420.0, 0.0) }, 600.0)];
        let gain = feed_link_gain(&before, line, &after, 20_000.0, &m);
        assert!(gain < -0.1, "gain {gain}");
    }

    #[test]
    fn the_window_lets_the_machine_reach_its_largest_feed() {
        // vmc: v = 333.3 mm/s, a = 3000 mm/s², J = 50000 mm/s³: 37.0 + 20.0 + 1 mm
        let w = window_mm(&vmc());
        assert!((w - (333.333f64.powi(2) / 3000.0 + 333.333 * 3000.0 / 50_000.0 + 1.0)).abs() < 0.01, "{w}");
        let d = Dynamics::of(&vmc());
        let line = Segment::Line { start: p2(0.0, 0.0), end: p2(w, 0.0) };
        let peak = plan_feed(&[line], &[20_000.0], &d).points.iter().map(|p| p.feed_mm_per_min).fold(0.0, f64::max);
        // on a line (tangential acceleration a) the S-curve from rest to v takes
        // v²/(2a) + v·a/(2J): W − 1 mm holds the ramp up and the ramp down
        assert!(peak > 0.99 * 20_000.0, "peak {peak}");
    }
}
