//! The time of every move of a program on a machine and the feed the machine reaches along it.
//!
//! The runs are those of `machine::program_time` (module docs there): consecutive feed moves
//! with motion in the plane form one run planned from rest to rest by the feed planner
//! (`machine::planner::plan_feed`), each move at the plane's share of its own feed
//! (F·L_xy/L); every rapid and every move along Z only is a straight line from rest to rest,
//! a rapid at the machine's rapid rate. The total is therefore `program_time`'s (tested). What
//! is kept here besides: each feed run's [`FeedProfile`], so that the reached feed is known at
//! any place of any move ([`Timing::feed_at`]). Without a machine every move runs at its
//! programmed feed (rapids take no time: the ideal machine has no rapid rate).

use crate::error::{Error, Param};
use crate::geom::Segment;
use crate::machine::planner::{Dynamics, FeedProfile, plan_feed};
use crate::machine::program_time::{length_3d, line_time};
use crate::machine::{Machine, ProgramTime};
use crate::toolpath::{Move, MoveKind};

/// Shortest move that is timed (mm), as in `machine::program_time`.
const MIN_MOVE_MM: f64 = 1e-9;

/// Where a move's time comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Source {
    /// A feed move with motion in the plane: run `run`, from arc length `s0` (mm, in the
    /// plane) on.
    Run { run: usize, s0: f64 },
    /// A rapid, a move along Z only, or a move too short to time: its own time.
    Own,
}

/// The timed program.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Timing {
    /// Time of each move (s).
    pub move_time_s: Vec<f64>,
    /// Time of the whole program (s) and its parts, and their lengths, as
    /// [`machine::program_time`](crate::machine::program_time) gives them (its
    /// `feed_held_share` is not kept here).
    pub totals: ProgramTime,
    sources: Vec<Source>,
    runs: Vec<FeedProfile>,
}

/// Time `moves` on `machine` (`None`: the ideal machine). A feed move's feed is its own `F`
/// (the reader gives every feed move one).
pub fn time_moves(moves: &[Move], machine: Option<&Machine>) -> Result<Timing, Error> {
    let mut t =
        Timing { move_time_s: vec![0.0; moves.len()], sources: vec![Source::Own; moves.len()], ..Timing::default() };
    let feed_of = |k: usize, mv: &Move| -> Result<f64, Error> {
        match mv.feed_mm_per_min {
            Some(f) if f.is_finite() && f > 0.0 => Ok(f),
            f => Err(Error::param(
                Param::Feed,
                f.unwrap_or(0.0),
                format!("a finite number > 0 mm/min (move #{})", k + 1),
            )),
        }
    };
    let Some(m) = machine else {
        for (k, mv) in moves.iter().enumerate() {
            let len = length_3d(mv);
            if len <= MIN_MOVE_MM {
                continue;
            }
            let is_vertical = mv.segment.length() <= MIN_MOVE_MM;
            if mv.kind == MoveKind::Rapid {
                if is_vertical {
                    t.totals.vertical_length_mm += len
                } else {
                    t.totals.rapid_length_mm += len
                }
                continue;
            }
            let dt = len / feed_of(k, mv)? * 60.0;
            t.move_time_s[k] = dt;
            if is_vertical {
                t.totals.vertical_s += dt;
                t.totals.vertical_length_mm += len;
            } else {
                t.totals.feed_s += dt;
                t.totals.feed_length_mm += len;
            }
        }
        t.totals.total_s = t.totals.feed_s + t.totals.rapid_s + t.totals.vertical_s;
        return Ok(t);
    };
    m.validate()?;
    let d = Dynamics::of(m);
    let rapid = m.rapid_mm_per_min();
    let d_rapid = Dynamics { v_max: rapid / 60.0, ..d };
    // the run being collected: its moves, segments and planar feeds
    let mut run: (Vec<usize>, Vec<Segment>, Vec<f64>) = (Vec::new(), Vec::new(), Vec::new());
    let flush = |run: &mut (Vec<usize>, Vec<Segment>, Vec<f64>), t: &mut Timing| {
        if run.0.is_empty() {
            return;
        }
        let profile = plan_feed(&run.1, &run.2, &d);
        t.totals.feed_s += profile.time_s();
        let index = t.runs.len();
        let mut s0 = 0.0;
        for (&k, seg) in run.0.iter().zip(&run.1) {
            let s1 = s0 + seg.length();
            t.sources[k] = Source::Run { run: index, s0 };
            t.move_time_s[k] = time_at(&profile, s1) - time_at(&profile, s0);
            s0 = s1;
        }
        t.runs.push(profile);
        run.0.clear();
        run.1.clear();
        run.2.clear();
    };
    for (k, mv) in moves.iter().enumerate() {
        let len = length_3d(mv);
        if len <= MIN_MOVE_MM {
            continue;
        }
        let vertical = mv.segment.length() <= MIN_MOVE_MM;
        if !vertical && mv.kind != MoveKind::Rapid {
            let f = feed_of(k, mv)?;
            if let Some(&last) = run.1.last()
                && (last.end() - mv.segment.start()).norm() > m.path_tolerance
            {
                flush(&mut run, &mut t);
            }
            run.0.push(k);
            run.1.push(mv.segment);
            run.2.push(f * mv.segment.length() / len);
            t.totals.feed_length_mm += len;
            continue;
        }
        flush(&mut run, &mut t);
        if vertical {
            let (f, dd) = if mv.kind == MoveKind::Rapid { (rapid, &d_rapid) } else { (feed_of(k, mv)?, &d) };
            let dt = line_time(len, f, dd);
            t.move_time_s[k] = dt;
            t.totals.vertical_s += dt;
            t.totals.vertical_length_mm += len;
        } else {
            let dt = line_time(len, rapid, &d_rapid);
            t.move_time_s[k] = dt;
            t.totals.rapid_s += dt;
            t.totals.rapid_length_mm += len;
        }
    }
    flush(&mut run, &mut t);
    t.totals.total_s = t.totals.feed_s + t.totals.rapid_s + t.totals.vertical_s;
    Ok(t)
}

/// Time at arc length `s` of a profile, linear between its points.
fn time_at(p: &FeedProfile, s: f64) -> f64 {
    interpolate(p, s, |q| q.t_s)
}

/// A value of the profile's points at arc length `s`, linear between them.
fn interpolate(p: &FeedProfile, s: f64, value: impl Fn(&crate::machine::FeedPoint) -> f64) -> f64 {
    let pts = &p.points;
    let i = pts.partition_point(|q| q.s_mm < s);
    match (i.checked_sub(1).and_then(|k| pts.get(k)), pts.get(i)) {
        (Some(a), Some(b)) if b.s_mm > a.s_mm => value(a) + (value(b) - value(a)) * (s - a.s_mm) / (b.s_mm - a.s_mm),
        (_, Some(b)) => value(b),
        (Some(a), None) => value(a),
        (None, None) => 0.0,
    }
}

impl Timing {
    /// The feed the machine reaches in the plane (mm/min) at `u` mm (in the plane) from the
    /// start of move `k`, `mv` that move; the programmed planar feed where the move is timed on
    /// its own (ideal machine, moves along Z only).
    pub fn feed_at(&self, k: usize, mv: &Move, u: f64) -> f64 {
        let programmed = || {
            let len = length_3d(mv);
            let f = mv.feed_mm_per_min.unwrap_or(0.0);
            if len > 0.0 { f * mv.segment.length() / len } else { f }
        };
        match self.sources.get(k) {
            Some(Source::Run { run, s0 }) => {
                self.runs.get(*run).map_or_else(programmed, |p| interpolate(p, s0 + u, |q| q.feed_mm_per_min))
            }
            _ => programmed(),
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::verify::read_program;

    /// The runs are `machine::program_time`'s: on a program of lines, arcs, a helix, rapids and Z
    /// moves the totals and their parts are the same on every preset; without a machine a feed
    /// move takes its 3D length at its feed (a 10 mm line at 600 mm/min: 1 s).
    #[test]
    fn totals_are_program_times() {
        let text = "G21\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X10 F600\nG3 X20 Y0 R5 Z-2\nG2 X20 Y0 I-5 J0\nG0 Z5\nG0 X0 Y20\n\
                    G1 Z-2 F300\nG1 X30 F1200\nG1 Y30\nG0 Z5\n";
        let moves: Vec<Move> = read_program(text, "t.ngc").expect("read").moves.iter().map(|m| m.mv).collect();
        for name in crate::machine::preset_names() {
            let m = Machine::preset(name).expect("preset");
            let (ours, theirs) = (
                time_moves(&moves, Some(&m)).expect("timed"),
                crate::machine::program_time(&moves, &m, 600.0).expect("timed"),
            );
            for (a, b) in [
                (ours.totals.total_s, theirs.total_s),
                (ours.totals.feed_s, theirs.feed_s),
                (ours.totals.rapid_s, theirs.rapid_s),
                (ours.totals.vertical_s, theirs.vertical_s),
                (ours.totals.feed_length_mm, theirs.feed_length_mm),
                (ours.totals.rapid_length_mm, theirs.rapid_length_mm),
            ] {
                assert!((a - b).abs() <= 1e-12 * b.max(1.0), "{name}: {a} {b}");
            }
            let sum: f64 = ours.move_time_s.iter().sum();
            assert!((sum - ours.totals.total_s).abs() < 1e-9, "{name}: {sum} {}", ours.totals.total_s);
        }
        let ideal = time_moves(&moves, None).expect("timed");
        assert!((ideal.move_time_s[1] - 1.0).abs() < 1e-12, "{}", ideal.move_time_s[1]);
    }
}
