//! NC programs in levels: [`program_for_path_levels`] writes a [`PathJob`]'s path at one level
//! or several (every path program, [`super::program_for_path`], is one level of it), and
//! [`pocket_levels_program`] a pocket cut in levels ([`crate::pocket::levels`];
//! docs/pockets.md, "Levels"): the header, set-up and end of a pocket program
//! ([`pocket_program`]), a header line on the levels, then the pocket's whole path level by
//! level, top to bottom: each part entered as at one depth, its helix or ramp starting 0.5 mm
//! above the floor of the level above (inside the bore cut there), a retract and rapid between
//! the levels as between the parts; through the program frame ([`NcOptions::frame`]) in every
//! dialect.
//!
//! [`pocket_program`]: super::pocket_program

use super::corner::{CutSetup, pocket_path_program, pocket_summary};
use super::{
    Header, NcOptions, NcProgram, PathJob, Writer, approach, epilogue, fit, helical_approach, preamble, ramp_approach,
};
use crate::error::{Error, Param, num};
use crate::geom::{P2, Segment};
use crate::pocket::{PocketLevels, PocketPlan};
use crate::toolpath::{Entry, MoveKind};

/// The program of the pocket `plan` cut in `levels` (module docs); `cut.depth_mm` is replaced by
/// the depth of the lowest level.
pub fn pocket_levels_program(
    plan: &PocketPlan,
    levels: &PocketLevels,
    cut: CutSetup,
    opts: &NcOptions,
) -> Result<NcProgram, Error> {
    // the levels as the program writes them: each from its top down to its floor
    let path_levels: Vec<PathLevel> =
        levels.per_level.iter().map(|l| PathLevel { top_mm: l.top_mm, depth_mm: -l.z_mm }).collect();
    let depth_mm = path_levels.last().map_or(cut.depth_mm, |l| l.depth_mm);
    pocket_path_program(plan.path(), pocket_summary(plan), CutSetup { depth_mm, ..cut }, &path_levels, opts)
}

/// One pass of a [`PathJob`]'s path in a program of several ([`program_for_path_levels`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathLevel {
    /// The height the pass cuts down from (mm; 0: the stock top, else the floor of the pass
    /// above, ≤ 0): helices and ramps start [`HELIX_START_Z_MM`] above it.
    pub top_mm: f64,
    /// The pass's floor below the stock top Z0 (mm, > 0).
    pub depth_mm: f64,
}

/// The program of a [`PathJob`] cut in `levels`, top to bottom, one after the other
/// ([`program_for_path`] for each, in one program: one header, set-up and end): every level
/// writes the whole path at its depth, each part entered as in [`program_for_path`] but from
/// [`HELIX_START_Z_MM`] above the level's top (inside the bore the level above cut there), a
/// retract and rapid between the levels as between parts.
pub fn program_for_path_levels(job: &PathJob<'_>, levels: &[PathLevel], opts: &NcOptions) -> Result<NcProgram, Error> {
    opts.validate()?;
    job.validate()?;
    check_levels(levels, opts)?;
    let mut w = Writer::with_units(opts.dialect.spec(), opts.frame.units);
    let header = Header {
        default_title: job.default_title,
        description: job.description.clone(),
        tool_diameter_mm: job.tool_diameter_mm,
        spindle_rpm: job.spindle_rpm,
    };
    preamble(&mut w, &header, opts);
    for (index, level) in levels.iter().enumerate() {
        write_path_level(&mut w, job, *level, index == 0, opts);
    }
    epilogue(&mut w, opts);
    let (text, blocks) = w.finish()?;
    Ok(NcProgram { text, blocks })
}

/// The whole path of `job` at one level ([`program_for_path_levels`]); `first_level`: the
/// first part comes from the tool change (the clearance height).
pub(super) fn write_path_level(
    w: &mut Writer,
    job: &PathJob<'_>,
    level: PathLevel,
    first_level: bool,
    opts: &NcOptions,
) {
    let path = job.toolpath;
    let (depth, feed, top) = (level.depth_mm, job.feed_mm_per_min, level.top_mm);
    let descend = |w: &mut Writer, part: usize, start: P2| {
        let first = first_level && part == 0;
        match path.entries.get(part) {
            Some(Entry::Helix(h)) => helical_approach(w, h, top, depth, feed, first, opts),
            Some(Entry::Ramp(r)) => ramp_approach(w, r, top, depth, feed, first, opts),
            // beyond an open edge the tool's disc is off the stock: straight down cuts nothing
            Some(Entry::Outside { at }) => approach(w, *at, depth, feed, first, opts),
            // into stock the path has cleared: straight down cuts nothing either
            Some(Entry::Down { at }) => approach(w, *at, depth, feed, first, opts),
            None => approach(w, start, depth, feed, first, opts),
        }
    };
    descend(w, 0, path.moves[0].segment.start());
    for (i, m) in path.moves.iter().enumerate() {
        if let Some(k) = path.retract_before.iter().position(|&j| j == i) {
            descend(w, k + 1, m.segment.start());
        }
        // a rapid at depth through cleared stock: G0 where G0 is a straight line
        if let (MoveKind::Rapid, Segment::Line { end, .. }) = (m.kind, m.segment)
            && opts.dialect.spec().straight_rapid
        {
            w.linear(Some(end.x), Some(end.y), None, None);
            continue;
        }
        let feed = m.feed_mm_per_min.unwrap_or(feed);
        for piece in fit(&m.segment, opts) {
            w.segment(&piece.seg, feed);
        }
    }
}

/// The levels of a path in levels: at least one, each floor finite, > 0 and ≤ 1000 mm, each
/// top from the floor to the stock top; no loop form, no return feed.
pub(super) fn check_levels(levels: &[PathLevel], opts: &NcOptions) -> Result<(), Error> {
    if opts.compact {
        return Err(Error::param(Param::Compact, "true", "false for a path without repeating cycles"));
    }
    if let Some(f) = opts.return_feed_mm_per_min {
        return Err(Error::param(Param::ReturnFeed, f, "unset for a path without a tooth series"));
    }
    if levels.is_empty() {
        return Err(Error::nc("levels", "none", "at least one level"));
    }
    for l in levels {
        if !(l.depth_mm.is_finite() && l.depth_mm > 0.0 && l.depth_mm <= 1000.0) {
            return Err(Error::param(Param::Depth, l.depth_mm, "a finite number > 0 and ≤ 1000 mm"));
        }
        if !(l.top_mm.is_finite() && l.top_mm <= 0.0 && l.top_mm > -l.depth_mm) {
            return Err(Error::nc("level top", num(l.top_mm), format!("from {} to 0 mm", num(-l.depth_mm))));
        }
    }
    Ok(())
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::nc::{Dialect, backplot, pocket_program};
    use crate::pocket::{PocketRequest, plan, plan_levels};

    /// The 60 × 40 rectangle, 12 mm in 3 levels: the header names them; each level's helix
    /// starts 0.5 mm above the floor above (Z0.5, Z−3.5, Z−7.5) and reaches its floor; the
    /// back-plot is the one-level program's path three times and two rapids from its last
    /// point back to its first (length: 3 × the one level's + 2 × that distance, within the
    /// rs274 tests' 0.1 %), in every dialect.
    #[test]
    fn three_levels_repeat_the_path_and_enter_above_the_floor_above() {
        let p = plan(&PocketRequest::default()).expect("plan");
        let lv = plan_levels(p.path(), 12.0, Some(4.0)).expect("levels");
        let cut = CutSetup { depth_mm: 12.0, ..CutSetup::default() };
        for dialect in Dialect::ALL {
            let opts = NcOptions { dialect, ..NcOptions::default() };
            let prog = pocket_levels_program(&p, &lv, cut, &opts).expect("program");
            let t = &prog.text;
            assert!(t.contains("3 levels of 4.000 mm, each entered 0.5 mm above the floor above"), "{dialect:?}");
            let one = pocket_program(&p, CutSetup { depth_mm: 4.0, ..cut }, &opts).expect("one level");
            let length = |text: &str| {
                let pts = backplot(text, dialect, 1e-3).expect("back-plot");
                let back = pts.first().zip(pts.last()).map_or(0.0, |(a, b)| (a - b).norm());
                (pts.windows(2).map(|w| (w[1] - w[0]).norm()).sum::<f64>(), back)
            };
            let ((three, _), (single, back)) = (length(t), length(&one.text));
            let want = 3.0 * single + 2.0 * back;
            assert!((three - want).abs() < 1e-3 * want, "{dialect:?}: {three} vs {want}");
        }
        let t = pocket_levels_program(&p, &lv, cut, &NcOptions::default()).expect("program").text;
        for top in ["Z0.5000\n", "Z-3.5000\n", "Z-7.5000\n"] {
            assert_eq!(
                t.matches(&format!("\nG0 {top}")).count() + t.matches(&format!("\n{top}")).count(),
                1,
                "{top}: {t}"
            );
        }
    }
}
