//! The slot's depth in levels (docs/slot-paths.md, "Levels and slot ends"): with a largest
//! step-down m the depth a_p is cut in n = ⌈a_p / m⌉ equal levels of a_p / n each, level k
//! (1…n) reaching Z = −k·a_p/n below the stock top. Equal levels keep one planar path: every
//! level cuts the same loops at the same axial depth. The step-down is checked with the job
//! ([`crate::job::Job::validate`], at most [`crate::job::limits::MAX_LEVELS`] levels).

use crate::job::{ValidJob, level_count};

/// The levels of a slot: their count and depths.
#[derive(Clone, Debug, PartialEq)]
pub struct Levels {
    /// Axial depth of every level (mm), a_p / n.
    pub axial_depth_mm: f64,
    /// The floor of each level, top to bottom (mm below the stock top, negative).
    pub z_mm: Vec<f64>,
}

impl Levels {
    /// The levels of a validated job: one level at the full depth without a step-down.
    pub fn of(job: &ValidJob) -> Levels {
        Levels::equal(job.depth, job.max_step_down)
    }

    /// The equal levels of `depth` (mm, > 0) cut at most `max_step_down` a level (checked by
    /// the caller: > 0): one level at the full depth without a step-down.
    pub fn equal(depth: f64, max_step_down: Option<f64>) -> Levels {
        let n = count(depth, max_step_down);
        let axial_depth_mm = depth / n as f64;
        // The last level exactly at the depth, whatever the rounding of k·a_p/n.
        let z_mm = (1..=n).map(|k| if k == n { -depth } else { -(k as f64) * axial_depth_mm }).collect();
        Levels { axial_depth_mm, z_mm }
    }

    /// Number of levels.
    pub fn count(&self) -> usize {
        self.z_mm.len()
    }

    /// The height the tool cuts down from on level `k` (0-based): the floor of the level above,
    /// the stock top (0) for the first.
    pub fn top_mm(&self, k: usize) -> f64 {
        if k == 0 { 0.0 } else { self.z_mm[k - 1] }
    }
}

/// n = ⌈depth / max⌉ ([`level_count`]), 1 without a step-down.
fn count(depth: f64, max_step_down: Option<f64>) -> usize {
    max_step_down.map_or(1, |m| level_count(depth, m))
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::error::Param;
    use crate::job::Job;

    #[test]
    fn levels_are_equal_and_reach_the_depth() {
        // 12 / 4 = 3 levels of 4 mm; 12 / 5 = 2.4 → 3 levels of 4 mm; 6 / 10 → one level of 6 mm
        for (depth, m, n, each) in [(12.0, 4.0, 3, 4.0), (12.0, 5.0, 3, 4.0), (6.0, 10.0, 1, 6.0), (0.3, 0.1, 3, 0.1)] {
            let job = Job { depth, tool_diameter: 10.0, max_step_down: Some(m), ..Job::default() };
            let l = Levels::of(&job.validate().expect("valid"));
            assert_eq!(l.count(), n, "{depth}/{m}");
            assert!((l.axial_depth_mm - each).abs() < 1e-12, "{depth}/{m}: {}", l.axial_depth_mm);
            assert_eq!(*l.z_mm.last().expect("levels"), -depth);
            for k in 0..n {
                let cut = l.top_mm(k) - l.z_mm[k];
                assert!((cut - each).abs() < 1e-9 && cut <= m + 1e-9, "{depth}/{m} level {k}: {cut}");
            }
        }
        let one = Levels::of(&Job::default().validate().expect("valid"));
        assert_eq!((one.count(), one.z_mm.clone()), (1, vec![-6.0]));
    }

    #[test]
    fn a_bad_step_down_names_the_flag_and_its_range() {
        for m in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e6, 0.01] {
            let err = Job { max_step_down: Some(m), ..Job::default() }.validate().expect_err("refused");
            assert_eq!(err.parameter(), Some(Param::MaxStepDown), "{m}: {err}");
            assert!(err.to_string().contains("max-step-down"), "{err}");
        }
        // 6 mm in 100 levels of 0.06 mm is the most
        assert!(Job { max_step_down: Some(0.06), ..Job::default() }.validate().is_ok());
    }
}
