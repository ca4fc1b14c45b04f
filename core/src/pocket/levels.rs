//! A pocket cut in several levels (docs/pockets.md, "Levels"): with a largest step-down m the
//! depth a_p is cut in n = ⌈a_p / m⌉ equal levels of a_p / n ([`Levels::equal`], the slot's
//! levels), level k (1…n) with its floor at Z = −k·a_p/n.
//!
//! Equal levels cut the same planar path: the outline, the islands and the tool are the same
//! on every level, so the pocket is planned once and its path repeated per level. Each level is
//! entered as the path's parts are at one depth, but its helices and ramps start just above
//! the floor of the level above ([`crate::toolpath::HELIX_START_Z_MM`] above it), inside the
//! bore that level cut at the same place: only the level's own axial depth is helixed.
//!
//! Every level is measured by the engagement evaluator ([`measure`]) over its own stock: the
//! pocket less its islands, the levels above having cut only the slab above the level. With
//! equal levels and the same path that stock and the moves are the same on every level, so the
//! radial engagement of each move is the same on every level; each is measured all the same.

use crate::engagement::{EvaluatorOptions, Measurement, Stock, measure};
use crate::error::{Error, Param, num};
use crate::job::level_count;
use crate::job::limits::{MAX_LEVELS, MAX_SIZE_MM};
use crate::path::levels::Levels;
use crate::pocket::PocketPath;
use rayon::prelude::*;

/// One level of a pocket.
#[derive(Clone, Debug)]
pub struct PocketLevel {
    /// The height the level is cut down from (mm; 0: the stock top) and its floor (negative).
    pub top_mm: f64,
    pub z_mm: f64,
    /// Axial depth of the level (mm).
    pub axial_depth_mm: f64,
    /// Every move of the level measured by the evaluator over the level's stock.
    pub measurement: Measurement,
}

/// A pocket in levels: the same path on each.
#[derive(Clone, Debug)]
pub struct PocketLevels {
    pub levels: Levels,
    pub per_level: Vec<PocketLevel>,
}

impl PocketLevels {
    /// Largest engagement measured over every move of every level (rad).
    pub fn peak_rad(&self) -> f64 {
        self.per_level.iter().map(|l| l.measurement.max_engagement_rad).fold(0.0, f64::max)
    }
}

/// Check the pocket's `depth_mm` and step-down `max_mm`: the depth finite, > 0 and at most
/// [`MAX_SIZE_MM`]; the step-down finite, > 0, at most the depth and at least depth /
/// [`MAX_LEVELS`]. The errors name `--depth` and `--max-step-down` and their ranges.
pub fn check_step_down(depth_mm: f64, max_mm: f64) -> Result<(), Error> {
    if !(depth_mm.is_finite() && depth_mm > 0.0 && depth_mm <= MAX_SIZE_MM) {
        return Err(Error::param(Param::Depth, depth_mm, format!("a finite number > 0 and ≤ {} mm", num(MAX_SIZE_MM))));
    }
    let least = depth_mm / MAX_LEVELS as f64;
    if !(max_mm.is_finite() && max_mm > 0.0 && max_mm <= depth_mm) {
        return Err(Error::param(
            Param::MaxStepDown,
            max_mm,
            format!("a finite number > 0 and ≤ the depth {} mm", num(depth_mm)),
        ));
    }
    if level_count(depth_mm, max_mm) > MAX_LEVELS {
        return Err(Error::param(
            Param::MaxStepDown,
            max_mm,
            format!(
                "from depth / {MAX_LEVELS} = {} mm to the depth {} mm (at most {MAX_LEVELS} levels)",
                num(least),
                num(depth_mm)
            ),
        ));
    }
    Ok(())
}

/// The pocket whose planned path is `path` cut `depth_mm` deep in equal levels of at most
/// `max_step_down_mm` (one level without), each level measured (module docs).
pub fn plan_levels(path: &PocketPath, depth_mm: f64, max_step_down_mm: Option<f64>) -> Result<PocketLevels, Error> {
    match max_step_down_mm {
        Some(m) => check_step_down(depth_mm, m)?,
        None => check_step_down(depth_mm, depth_mm)?,
    }
    let levels = Levels::equal(depth_mm, max_step_down_mm);
    let opts = EvaluatorOptions::new(path.settings.tool_radius, path.settings.spacing);
    let per_level = (0..levels.count())
        .into_par_iter()
        .map(|k| {
            let (top_mm, z_mm) = (levels.top_mm(k), levels.z_mm[k]);
            let stock = Stock { polygon: &path.polygon, precut: &[], islands: &path.islands };
            let measurement = measure(&path.toolpath, stock, &opts)?;
            Ok(PocketLevel { top_mm, z_mm, axial_depth_mm: top_mm - z_mm, measurement })
        })
        .collect::<Result<Vec<_>, Error>>()?;
    Ok(PocketLevels { levels, per_level })
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::pocket::{PocketRequest, plan};

    /// The 60 × 40 rectangle, D 10, adaptive: 12 mm in levels of at most 5 mm is 3 levels of
    /// 4 mm (⌈12/5⌉ = 3), floors at −4, −8, −12; every level measures the same (the same moves
    /// over the same stock: the evaluator is deterministic), and as the one-depth plan within
    /// 0.01° (the plan measured its moves before pacing split them, so the positions differ).
    #[test]
    fn equal_levels_reach_the_depth_and_measure_as_the_one_depth_plan() {
        let p = plan(&PocketRequest::default()).expect("plan");
        let lv = plan_levels(p.path(), 12.0, Some(5.0)).expect("levels");
        assert_eq!(lv.levels.z_mm, vec![-4.0, -8.0, -12.0]);
        let (first, whole) = (&lv.per_level[0].measurement, &p.path().measurement);
        for (k, l) in lv.per_level.iter().enumerate() {
            assert!((l.axial_depth_mm - 4.0).abs() < 1e-12 && (l.top_mm + 4.0 * k as f64).abs() < 1e-12, "{k}");
            assert_eq!(l.measurement.max_engagement_rad, first.max_engagement_rad);
            assert_eq!(l.measurement.p95_engagement_rad, first.p95_engagement_rad);
        }
        for (a, b) in
            [(first.max_engagement_rad, whole.max_engagement_rad), (first.p95_engagement_rad, whole.p95_engagement_rad)]
        {
            assert!((a - b).abs().to_degrees() < 0.01, "{a} vs {b}");
        }
        assert_eq!(lv.peak_rad(), first.max_engagement_rad);
        assert_eq!((lv.per_level[2].top_mm, lv.per_level[2].z_mm), (-8.0, -12.0));
        // 12 / 4 is 3 levels, 12 / 12 one
        assert_eq!(plan_levels(p.path(), 12.0, Some(4.0)).expect("levels").levels.count(), 3);
        assert_eq!(plan_levels(p.path(), 12.0, None).expect("levels").levels.count(), 1);
    }

    #[test]
    fn a_bad_step_down_names_the_flag_and_its_range() {
        for m in [0.0, -1.0, f64::NAN, f64::INFINITY, 12.5, 0.1] {
            let err = check_step_down(12.0, m).expect_err("refused");
            assert_eq!(err.parameter(), Some(Param::MaxStepDown), "{m}: {err}");
            assert!(err.to_string().contains("max-step-down") && err.to_string().contains("mm"), "{err}");
        }
        for d in [0.0, -3.0, f64::NAN] {
            let err = check_step_down(d, 1.0).expect_err("refused");
            assert_eq!(err.parameter(), Some(Param::Depth), "{d}: {err}");
        }
        // 12 mm in 100 levels of 0.12 mm is the most; the whole depth in one level is allowed
        assert!(check_step_down(12.0, 0.12).is_ok() && check_step_down(12.0, 12.0).is_ok());
    }
}
