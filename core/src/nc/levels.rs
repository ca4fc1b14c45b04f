//! The NC program of a slot in levels, open or closed ([`crate::slot_levels`];
//! docs/nc-export.md, "Levels and closed slots"): the header, set-up and end of a slot
//! program ([`super::program`]), then level by level, top to bottom:
//!
//! - open slot: safe Z, rapid to the path start outside the open end (the tool's disc off the
//!   stock), feed down to the level's floor there, the cycles;
//! - closed slot: safe Z, rapid to the helix start, rapid down to 0.5 mm above the stock top
//!   (first level) or above the floor of the level above (inside the space it cleared), the
//!   helix down to the level's floor in whole turns, one flat turn there, the whole cycles, the
//!   link along the wall and the cycle into the end.
//!
//! The cycles are fitted once and translated, as in a slot program, with the same feeds
//! (programmed, return or variable feed). The loop form is not written for levels.

use super::{
    CycleMove, NcOptions, NcProgram, Writer, approach, cycle_moves, epilogue, preamble, slot_header,
    variable_feed_moves,
};
use crate::error::{Error, Param, num};
use crate::geom::{P2, p2};
use crate::plan::Plan;
use crate::slot_levels::LevelPlan;
use crate::toolpath::Entry;

/// The program of `plan` cut in the levels `levels` (module docs).
pub fn levels_program(plan: &Plan, levels: &LevelPlan, opts: &NcOptions) -> Result<NcProgram, Error> {
    opts.validate()?;
    if opts.compact {
        return Err(Error::param(
            Param::Compact,
            "true",
            "false for a slot in levels or closed (--max-step-down, --closed): the loop form writes one level",
        ));
    }
    let job = &plan.job;
    let cycles = levels.closed.as_ref().map_or(plan.path.cycles, |c| c.cycles + 1);
    let mut header = slot_header(plan, opts);
    // the first line: the path of one level (the slot header's is the open one-level path)
    let length = levels.per_level.first().map_or(0.0, |l| l.toolpath.length_mm());
    header.description[0] = format!("path {}, {cycles} cycles a level, {length:.3} mm a level", job.path.name());
    header.description.extend(level_lines(levels));
    let mut w = Writer::with_units(opts.dialect.spec(), opts.frame.units);
    preamble(&mut w, &header, opts);
    levels_body(&mut w, plan, levels, opts)?;
    epilogue(&mut w, opts);
    let (text, blocks) = w.finish()?;
    Ok(NcProgram { text, blocks })
}

/// The levels of `plan` after the tool is loaded and turning (module docs), the first approach
/// from the clearance height; shared by [`levels_program`] and a program of several operations.
pub(super) fn levels_body(w: &mut Writer, plan: &Plan, levels: &LevelPlan, opts: &NcOptions) -> Result<(), Error> {
    let min_feed = plan.job.min_feed();
    if let Some(f) = opts.return_feed_mm_per_min.filter(|&f| f < min_feed) {
        return Err(Error::param(
            Param::ReturnFeed,
            f,
            format!("from the machine's min-feed {} to 1000000 mm/min", num(min_feed)),
        ));
    }
    let job = &plan.job;
    let moves = match &opts.variable_feed {
        Some(vf) => variable_feed_moves(plan, vf, opts)?,
        None => cycle_moves(plan, opts),
    };
    let cycles = levels.closed.as_ref().map_or(plan.path.cycles, |c| c.cycles + 1);
    let blocks = moves.len().saturating_mul(cycles).saturating_mul(levels.levels.count());
    if blocks > super::MAX_PROGRAM_BLOCKS {
        return Err(Error::param(
            Param::MaxStepDown,
            plan.job.max_step_down.map_or_else(|| "none".to_string(), num),
            format!(
                "fewer levels: {} levels of {cycles} cycles of {} blocks make a program of more than {} blocks",
                levels.levels.count(),
                moves.len(),
                super::MAX_PROGRAM_BLOCKS
            ),
        ));
    }
    for (index, level) in levels.per_level.iter().enumerate() {
        let first = index == 0;
        match (&levels.closed, level.toolpath.entries.first()) {
            (Some(c), Some(Entry::Helix(h))) => {
                let start = h.center + p2(h.start_angle.cos(), h.start_angle.sin()) * h.radius;
                let top = level.descent_from_mm.min(super::retract(opts));
                w.linear(None, None, Some(super::up_height(first, opts)), None);
                w.linear(Some(start.x), Some(start.y), None, None);
                w.linear(None, None, Some(top), None);
                let drop = top - level.z_mm;
                let turns = h.turns(drop);
                for k in 1..=turns {
                    w.helical_arc(&h.circle(), top - drop * k as f64 / turns as f64, job.feed);
                }
                // the flat turn at the floor, then the loops
                w.segment(&h.circle(), job.feed);
                for i in 0..c.cycles {
                    write_cycle(w, &moves, c.origin(i));
                }
                if let Some(link) = c.link() {
                    w.segment(&link, job.feed);
                }
                write_cycle(w, &moves, p2(0.0, c.end_origin_y));
            }
            _ => {
                let path = &plan.path;
                let start = path.origin(0) + moves.first().map_or(path.cycle.segments[0].start(), |m| m.seg.start());
                approach(w, start, -level.z_mm, job.feed, first, opts);
                for i in 0..path.cycles {
                    write_cycle(w, &moves, path.origin(i));
                }
            }
        }
    }
    Ok(())
}

/// One cycle's blocks about `origin`.
fn write_cycle(w: &mut Writer, moves: &[CycleMove], origin: P2) {
    for m in moves {
        w.segment(&m.seg.translated(origin), m.feed_mm_per_min);
    }
}

/// The header lines of the levels and the slot's ends (each within a comment's 70 characters).
fn level_lines(levels: &LevelPlan) -> [String; 2] {
    let (lo, hi) = levels.centre_y_mm;
    [
        format!(
            "{} levels of {:.3} mm, {}",
            levels.levels.count(),
            levels.levels.axial_depth_mm,
            if levels.closed.is_some() {
                "closed slot, helix entry inside it"
            } else {
                "open slot, entry outside the stock"
            }
        ),
        format!("tool centre from Y{lo:.3} to Y{hi:.3}"),
    ]
}
