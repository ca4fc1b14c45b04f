//! The chip of a paced pocket at its peaks, at the programmed feeds and at the feeds the
//! machine reaches (docs/feed-and-rapids.md, "The chip at the peaks").
//!
//! The pace holds the circular-path chip f_z·κ at the target on the measured positions
//! ([`crate::pocket::pace`]); that is an upper bound of the chip the tooth cuts (the edge of earlier
//! cuts shortens it) and it is read only at those positions. Here the moves whose paced chip is
//! largest are sampled again, every half spacing, and at the largest f_z·κ of each the exact
//! chip is measured — the material between the tooth's periphery and the previous tooth's, cut
//! short where the path cut before, the same measurement `verify` makes on the program read
//! back ([`crate::verify::levels::exact_chip`]) — at the move's programmed feed, and, with a
//! machine, at the feed its planner reaches there (the program's moves as the NC writer
//! writes them, [`crate::machine::program_moves`], timed as `verify` times them).

use super::levels::exact_chip;
use super::timing::time_moves;
use crate::engagement::evaluator::{Evaluation, EvaluatorOptions};
use crate::engagement::refine::MAX_REFINED_POSITIONS;
use crate::error::Error;
use crate::machine::{CutHeights, Machine, program_moves};
use crate::pocket::PocketPath;
use crate::toolpath::MoveKind;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// How many moves, of the largest paced chip, are sampled again (at the programmed feed, and
/// as many at the reached feed).
pub const CANDIDATE_MOVES: usize = 48;

/// The largest exact chip of a pocket's moves at depth.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ChipPeaks {
    /// At the feed the machine reaches (mm); at the programmed feeds without a machine.
    pub h_max_mm: f64,
    /// At the programmed feeds (mm).
    pub h_max_programmed_mm: f64,
}

/// The chip peaks of `path` (paced or not) for a tool of `teeth` teeth at `rpm`; `machine`:
/// the machine and the program's heights for the reached feed.
pub fn chip_peaks(
    path: &PocketPath,
    teeth: u32,
    rpm: f64,
    machine: Option<(&Machine, CutHeights)>,
) -> Result<ChipPeaks, Error> {
    let feed = path.settings.feed_mm_per_min;
    let moves = &path.toolpath.moves;
    let segs = path.toolpath.segments();
    let mut starts = crate::geom::cumulative_lengths(&segs);
    starts.pop();
    let r = path.settings.tool_radius;
    let opts = EvaluatorOptions::new(r, path.settings.spacing);
    if segs.is_empty() {
        return Ok(ChipPeaks { h_max_mm: 0.0, h_max_programmed_mm: 0.0 });
    }
    let bores = path.toolpath.bores();
    let eval = Evaluation::new(&path.polygon, &bores, &segs, &opts, MAX_REFINED_POSITIONS)?;
    let programmed = |k: usize| moves[k].feed_mm_per_min.unwrap_or(feed);
    // the reached feed of move k at u mm along it: the program's move of the same segment
    let timed = match machine {
        Some((m, heights)) => {
            let all = program_moves(&path.toolpath, heights, feed);
            let timing = time_moves(&all, Some(m))?;
            let mut of = vec![None; moves.len()];
            let mut j = 0;
            for (k, mv) in moves.iter().enumerate() {
                while j < all.len() && all[j].segment != mv.segment {
                    j += 1;
                }
                if j < all.len() {
                    of[k] = Some(j);
                    j += 1;
                }
            }
            Some((all, timing, of))
        }
        None => None,
    };
    let reached = |k: usize, u: f64| match &timed {
        Some((all, timing, of)) => of[k].map_or(programmed(k), |j| timing.feed_at(j, &all[j], u)),
        None => programmed(k),
    };
    let f_z = |f: f64| f / (rpm * f64::from(teeth));
    // the paced chip of each move (f_z·κ at its feed over its measured positions), else
    // the programmed feed's
    let paced: Vec<f64> = match &path.pace {
        Some(p) => p.h_max_mm.clone(),
        None => vec![f_z(feed); moves.len()],
    };
    let cutting: Vec<usize> = (0..moves.len()).filter(|&k| moves[k].kind != MoveKind::Rapid).collect();
    let ranked = |key: &dyn Fn(usize) -> f64| {
        let mut v = cutting.clone();
        v.sort_by(|&a, &b| key(b).total_cmp(&key(a)));
        v.truncate(CANDIDATE_MOVES);
        v
    };
    let by_programmed = ranked(&|k| paced[k]);
    let by_reached = ranked(&|k| paced[k] * reached(k, 0.5 * segs[k].length()) / programmed(k));
    // the previous tooth is on the move before where the path runs on from it
    let joined = |k: usize| {
        k > 0
            && moves[k - 1].kind != MoveKind::Rapid
            && !path.toolpath.retract_before.contains(&k)
            && (segs[k - 1].end() - segs[k].start()).norm() <= 1e-6
    };
    let peak = |k: usize, at_reached: bool| -> f64 {
        let len = segs[k].length();
        let n = ((len / (0.5 * path.settings.spacing)).ceil() as usize).max(1);
        let feed_at = |u: f64| if at_reached { reached(k, u) } else { programmed(k) };
        let best = (0..=n)
            .map(|i| {
                let u = len * i as f64 / n as f64;
                let (sample, arcs) = eval.sample_arcs(starts[k] + u);
                (u, f_z(feed_at(u)) * sample.chip, arcs)
            })
            .max_by(|a, b| a.1.total_cmp(&b.1));
        let Some((u, _, arcs)) = best else { return 0.0 };
        let fz = f_z(feed_at(u));
        let at = segs[k].eval(if len > 0.0 { u / len } else { 0.0 });
        if fz.is_nan() || fz <= 0.0 || at.d1.norm() <= 0.0 {
            return 0.0;
        }
        let s = starts[k] + u;
        let floor = if joined(k) { 0.0 } else { starts[k] };
        exact_chip(&eval, &arcs, at.p, at.d1.y.atan2(at.d1.x), (s - fz).max(floor), fz, r)
    };
    let max_of =
        |list: &[usize], at_reached: bool| list.par_iter().map(|&k| peak(k, at_reached)).reduce(|| 0.0, f64::max);
    let h_max_programmed_mm = max_of(&by_programmed, false);
    let h_max_mm = if timed.is_some() { max_of(&by_reached, true) } else { h_max_programmed_mm };
    Ok(ChipPeaks { h_max_mm, h_max_programmed_mm })
}
