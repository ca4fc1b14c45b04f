//! Real time of a whole program on a machine: every move of a [`Toolpath`], feed moves,
//! rapids (`G0`) and moves along Z alike, timed by the feed planner ([`plan_feed`]: feed and
//! acceleration limits, jerk-limited ramps, the curvature and blend limits of arcs and joints).
//!
//! Two readings of a tool path give the moves:
//! - a program read back from its text (`nc`'s `read_toolpath`): its moves are every block, the
//!   rapids and Z moves included ([`program_time`] times them as they are);
//! - a planned tool path (a pocket, a corner): its moves at depth, its entries and retracts;
//!   [`program_moves`] turns it into the moves its program makes (the NC writer's approach,
//!   helix or ramp, retract, rapid and final retract, at the depth and safe height of
//!   [`CutHeights`]) and [`toolpath_time`] times those.
//!
//! The moves are timed in runs: consecutive feed moves with motion in the plane form one run,
//! planned from rest to rest with each move's own feed (its `F`, else the default feed), so the
//! planner blends the joints inside a run. A run ends at a rapid, at a move along Z only, and at
//! a retract (which is a rapid). Every rapid is its own run: a straight line of its 3D length at
//! the machine's rapid rate ([`Machine::rapid_mm_per_min`]) with the machine's acceleration and
//! jerk, from rest to rest. A move along Z only (feed or rapid) is a straight line of its length,
//! from rest to rest. A feed move that changes Z while it moves in the plane (a helix turn, a ramp
//! leg) runs at its feed along its 3D length: it is planned in the plane at the plane's share of
//! the feed, F·L_xy/L (L its 3D length), so its time is L/F where the feed is held; its Z
//! component (slope ≤ tan 15° for entries) is left to the Z axis, which is not a limit there.
//!
//! **The Z axis** is assumed to have the limits of the weaker XY axis (feed, rapid rate,
//! acceleration, jerk): the presets state X and Y only; GRBL's Shapeoko 3 defaults
//! (`grbl/defaults.h`), the `hobby-router` preset's source, give Z the same 5000 mm/min and
//! 400 mm/s² as X and Y.

use super::Machine;
use super::planner::{Dynamics, FeedProfile, plan_feed};
use crate::error::{Error, Param, num};
use crate::geom::{P2, Segment, p2};
use crate::toolpath::{Entry, HELIX_START_Z_MM, Move, MoveKind, Toolpath};
use serde::Serialize;

/// Shortest move that is timed (mm); shorter ones (a repeated point) take no time.
const MIN_MOVE_MM: f64 = 1e-9;

/// The heights of a planned tool path's program (the NC writer's): depth below the stock top
/// and the safe height above it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutHeights {
    /// Cutting depth below the stock top Z0 (mm, > 0).
    pub depth_mm: f64,
    /// Height of retracts and rapids above the stock top (mm).
    pub safe_z_mm: f64,
}

/// Real time of a program, in total and by kind of move, with the lengths of each kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct ProgramTime {
    /// Whole program (s): the sum of the three below.
    pub total_s: f64,
    /// Feed moves with motion in the plane: at depth, helix turns, ramp legs (s).
    pub feed_s: f64,
    /// Rapids with motion in the plane (s).
    pub rapid_s: f64,
    /// Moves along Z only, at feed or rapid (s).
    pub vertical_s: f64,
    /// 3D length of the feed moves with motion in the plane (mm).
    pub feed_length_mm: f64,
    /// 3D length of the rapids with motion in the plane (mm).
    pub rapid_length_mm: f64,
    /// Length of the moves along Z only (mm).
    pub vertical_length_mm: f64,
    /// Share of `feed_s` in which the programmed feed is held.
    pub feed_held_share: f64,
}

/// What a move is for the timing.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Class {
    Feed,
    Rapid,
    Vertical,
}

fn class(m: &Move) -> Class {
    if m.segment.length() <= MIN_MOVE_MM {
        Class::Vertical
    } else if m.kind == MoveKind::Rapid {
        Class::Rapid
    } else {
        Class::Feed
    }
}

/// 3D length of a move (mm).
pub(crate) fn length_3d(m: &Move) -> f64 {
    m.segment.length().hypot(m.z_end_mm - m.z_start_mm)
}

/// Time of a straight line of `len` mm at `feed` mm/min from rest to rest.
pub(crate) fn line_time(len: f64, feed: f64, d: &Dynamics) -> f64 {
    plan_feed(&[Segment::Line { start: p2(0.0, 0.0), end: p2(len, 0.0) }], &[feed], d).time_s()
}

/// The real time of `moves` in order on machine `m` (see the module doc); a move without its
/// own feed takes `default_feed_mm_per_min`. Error naming `feed` for a feed that is not a
/// finite number > 0, and the machine's key for an invalid machine.
pub fn program_time(moves: &[Move], m: &Machine, default_feed_mm_per_min: f64) -> Result<ProgramTime, Error> {
    m.validate()?;
    let feed_of = |k: usize, mv: &Move| -> Result<f64, Error> {
        let f = mv.feed_mm_per_min.unwrap_or(default_feed_mm_per_min);
        if f.is_finite() && f > 0.0 {
            Ok(f)
        } else {
            Err(Error::param(Param::Feed, f, format!("a finite number > 0 mm/min (move #{})", k + 1)))
        }
    };
    let d = Dynamics::of(m);
    let rapid = m.rapid_mm_per_min();
    let d_rapid = Dynamics { v_max: rapid / 60.0, ..d };
    let mut out = ProgramTime::default();
    let mut held_s = 0.0;
    // The feed run being collected: segments in the plane and their planar feeds.
    let (mut segs, mut feeds): (Vec<Segment>, Vec<f64>) = (Vec::new(), Vec::new());
    let flush = |segs: &mut Vec<Segment>, feeds: &mut Vec<f64>, out: &mut ProgramTime, held_s: &mut f64| {
        if segs.is_empty() {
            return;
        }
        let profile: FeedProfile = plan_feed(segs, feeds, &d);
        out.feed_s += profile.time_s();
        *held_s += profile.held_share() * profile.time_s();
        segs.clear();
        feeds.clear();
    };
    for (k, mv) in moves.iter().enumerate() {
        let len = length_3d(mv);
        if len <= MIN_MOVE_MM {
            continue;
        }
        match class(mv) {
            Class::Feed => {
                let f = feed_of(k, mv)?;
                // a gap wider than the path tolerance (never in a program, whose arcs read back
                // end within rounding of the next block's start) starts a new run
                if let Some(last) = segs.last()
                    && (last.end() - mv.segment.start()).norm() > m.path_tolerance
                {
                    flush(&mut segs, &mut feeds, &mut out, &mut held_s);
                }
                segs.push(mv.segment);
                feeds.push(f * mv.segment.length() / len);
                out.feed_length_mm += len;
            }
            Class::Rapid => {
                flush(&mut segs, &mut feeds, &mut out, &mut held_s);
                out.rapid_s += line_time(len, rapid, &d_rapid);
                out.rapid_length_mm += len;
            }
            Class::Vertical => {
                flush(&mut segs, &mut feeds, &mut out, &mut held_s);
                let (f, dd) = if mv.kind == MoveKind::Rapid { (rapid, &d_rapid) } else { (feed_of(k, mv)?, &d) };
                out.vertical_s += line_time(len, f, dd);
                out.vertical_length_mm += len;
            }
        }
    }
    flush(&mut segs, &mut feeds, &mut out, &mut held_s);
    out.total_s = out.feed_s + out.rapid_s + out.vertical_s;
    out.feed_held_share = if out.feed_s > 0.0 { held_s / out.feed_s } else { 1.0 };
    Ok(out)
}

/// The real time of a planned tool path's program on machine `m`: [`program_moves`] timed by
/// [`program_time`].
pub fn toolpath_time(
    path: &Toolpath,
    heights: CutHeights,
    feed_mm_per_min: f64,
    m: &Machine,
) -> Result<ProgramTime, Error> {
    if !(heights.depth_mm.is_finite() && heights.depth_mm > 0.0) {
        return Err(Error::param(Param::Depth, heights.depth_mm, "a finite number > 0 mm"));
    }
    if !(heights.safe_z_mm.is_finite() && heights.safe_z_mm > 0.0) {
        return Err(Error::param(
            Param::SafeZ,
            heights.safe_z_mm,
            format!("a finite number > 0 mm, e.g. {}", num(5.0)),
        ));
    }
    program_time(&program_moves(path, heights, feed_mm_per_min), m, feed_mm_per_min)
}

/// The moves the program of a planned tool path makes, as the NC writer writes it
/// (`nc`'s `program_for_path`) and as its program reads back: per connected part the way down
/// — a rapid from the safe height to [`HELIX_START_Z_MM`] and the helix turns or ramp legs at
/// `feed_mm_per_min`, or, without an entry (and outside the stock), straight down at that feed
/// from the safe height — then the moves at depth (their own feed, else `feed_mm_per_min`);
/// between parts a rapid up to the safe height and across to the next part's start; at the
/// end a rapid up to the safe height. The first part's rapids to its start are not moves (the
/// position before the program is unknown, as when it is read back).
pub fn program_moves(path: &Toolpath, heights: CutHeights, feed_mm_per_min: f64) -> Vec<Move> {
    let (safe, z_d) = (heights.safe_z_mm, -heights.depth_mm);
    let top = HELIX_START_Z_MM.min(safe);
    let drop = top + heights.depth_mm;
    let mut out: Vec<Move> = Vec::new();
    let line = |a: P2, b: P2, z0: f64, z1: f64, kind: MoveKind, feed: Option<f64>| Move {
        segment: Segment::Line { start: a, end: b },
        z_start_mm: z0,
        z_end_mm: z1,
        kind,
        feed_mm_per_min: feed,
    };
    let feed = Some(feed_mm_per_min);
    // The way down of part `part` whose first move starts at `start`; `from`: where the tool
    // is at the safe height before it (None for the first part).
    let descend = |out: &mut Vec<Move>, part: usize, start: P2, from: Option<P2>| {
        let entry_start = match path.entries.get(part) {
            Some(Entry::Helix(h)) => h.center + p2(h.start_angle.cos(), h.start_angle.sin()) * h.radius,
            Some(Entry::Ramp(r)) => r.first_point(drop),
            Some(Entry::Outside { at } | Entry::Down { at }) => *at,
            None => start,
        };
        if let Some(p) = from {
            out.push(line(p, entry_start, safe, safe, MoveKind::Rapid, None));
        }
        match path.entries.get(part) {
            Some(Entry::Helix(h)) => {
                out.push(line(entry_start, entry_start, safe, top, MoveKind::Rapid, None));
                let turns = h.turns(drop);
                for k in 1..=turns {
                    let z0 = top - drop * (k - 1) as f64 / turns as f64;
                    let z1 = top - drop * k as f64 / turns as f64;
                    out.push(Move {
                        segment: h.circle(),
                        z_start_mm: z0,
                        z_end_mm: z1,
                        kind: MoveKind::Entry,
                        feed_mm_per_min: feed,
                    });
                }
            }
            Some(Entry::Ramp(r)) => {
                out.push(line(entry_start, entry_start, safe, top, MoveKind::Rapid, None));
                let legs = r.legs(drop);
                let mut at = entry_start;
                for k in 1..=legs {
                    let to = if (legs - k).is_multiple_of(2) { r.start } else { r.end };
                    let z0 = top - drop * (k - 1) as f64 / legs as f64;
                    let z1 = top - drop * k as f64 / legs as f64;
                    out.push(line(at, to, z0, z1, MoveKind::Entry, feed));
                    at = to;
                }
            }
            Some(Entry::Outside { .. } | Entry::Down { .. }) | None => {
                out.push(line(entry_start, entry_start, safe, z_d, MoveKind::Cut, feed));
            }
        }
    };
    let Some(first) = path.moves.first() else {
        return out;
    };
    descend(&mut out, 0, first.segment.start(), None);
    for (i, m) in path.moves.iter().enumerate() {
        if let Some(k) = path.retract_before.iter().position(|&j| j == i)
            && let Some(prev) = out.last().map(|p| p.segment.end())
        {
            out.push(line(prev, prev, z_d, safe, MoveKind::Rapid, None));
            descend(&mut out, k + 1, m.segment.start(), Some(prev));
        }
        out.push(Move { z_start_mm: z_d, z_end_mm: z_d, feed_mm_per_min: m.feed_mm_per_min.or(feed), ..*m });
    }
    if let Some(end) = out.last().map(|p| p.segment.end()) {
        out.push(line(end, end, z_d, safe, MoveKind::Rapid, None));
    }
    out
}

#[cfg(test)]
#[path = "program_time_tests.rs"]
mod tests;
