//! The NC program of a pocket cut in levels ([`crate::pocket::levels`]; docs/pockets.md,
//! "Levels"): the header, set-up and end of a pocket program ([`pocket_program`]), a header
//! line on the levels, then the pocket's whole path level by level, top to bottom
//! ([`super::program_for_path_levels`]): each part entered as at one depth, its helix or ramp
//! starting 0.5 mm above the floor of the level above (inside the bore cut there), a retract
//! and rapid between the levels as between the parts; through the program frame
//! ([`NcOptions::frame`]) in every dialect.
//!
//! [`pocket_program`]: super::pocket_program

use super::corner::{CutSetup, pocket_path_program, pocket_summary};
use super::{NcOptions, NcProgram};
use crate::error::Error;
use crate::pocket::{PocketLevels, PocketPlan};

/// The program of the pocket `plan` cut in `levels` (module docs); `cut.depth_mm` is replaced by
/// the depth of the lowest level.
pub fn pocket_levels_program(
    plan: &PocketPlan,
    levels: &PocketLevels,
    cut: CutSetup,
    opts: &NcOptions,
) -> Result<NcProgram, Error> {
    let path_levels = levels.path_levels();
    let depth_mm = path_levels.last().map_or(cut.depth_mm, |l| l.depth_mm);
    pocket_path_program(plan.path(), pocket_summary(plan), CutSetup { depth_mm, ..cut }, &path_levels, opts)
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
