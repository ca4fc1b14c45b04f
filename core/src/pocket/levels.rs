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
//!
//! A floor pass ([`with_floor_pass`]): with a floor stock F the levels stop at the depth − F;
//! the floor pass is one last level at the full depth, the same path cutting only the floor
//! stock (axial depth F), entered inside the level above and measured over its own stock as
//! every level.
//!
//! The lengths and the time of each level ([`PocketLevel::totals`]): the path's moves at depth
//! are the same on every level; its entries descend from [`crate::toolpath::HELIX_START_Z_MM`]
//! above the level's top to its floor. The program's are their sums ([`PocketLevels::totals`]).

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
    /// Whether this is the floor pass ([`with_floor_pass`]).
    pub floor_pass: bool,
}

/// Lengths (mm) and time (s) of one level or of every level.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LevelTotals {
    /// Moves at depth (the evaluator's length, as the one-level report's).
    pub length_at_depth_mm: f64,
    /// Links at depth.
    pub link_length_mm: f64,
    /// Moves at depth through cleared stock (the evaluator's air).
    pub air_length_mm: f64,
    /// The entries' descents, from 0.5 mm above the level's top to its floor.
    pub entry_length_mm: f64,
    /// Rapids at depth through cleared stock.
    pub rapid_length_mm: f64,
    /// The descents at the feed and every move at depth at its own feed (as the path's
    /// `time_s`).
    pub time_s: f64,
}

impl LevelTotals {
    fn add(self, o: LevelTotals) -> LevelTotals {
        LevelTotals {
            length_at_depth_mm: self.length_at_depth_mm + o.length_at_depth_mm,
            link_length_mm: self.link_length_mm + o.link_length_mm,
            air_length_mm: self.air_length_mm + o.air_length_mm,
            entry_length_mm: self.entry_length_mm + o.entry_length_mm,
            rapid_length_mm: self.rapid_length_mm + o.rapid_length_mm,
            time_s: self.time_s + o.time_s,
        }
    }
}

impl PocketLevel {
    /// The level's lengths and time for the pocket's `path` (module docs): its moves at depth
    /// as measured, its entries down its own axial depth, the path's time with the one-depth
    /// descents replaced by the level's.
    pub fn totals(&self, path: &PocketPath) -> LevelTotals {
        let feed = path.settings.feed_mm_per_min;
        let entry_length_mm = path.toolpath.entry_length_mm(self.axial_depth_mm);
        LevelTotals {
            length_at_depth_mm: self.measurement.length_at_depth_mm,
            link_length_mm: path.link_length_mm,
            air_length_mm: self.measurement.air_length_mm,
            entry_length_mm,
            rapid_length_mm: path.pace.as_ref().map_or(0.0, |p| p.rapid_length_mm),
            time_s: path.time_s + (entry_length_mm - path.entry_length_mm) / feed * 60.0,
        }
    }
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

    /// The lengths and time of the whole program: the sums over every level.
    pub fn totals(&self, path: &PocketPath) -> LevelTotals {
        self.per_level.iter().fold(LevelTotals::default(), |t, l| t.add(l.totals(path)))
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
            let stock = Stock { polygon: &path.polygon, precut: &path.precut, islands: &path.islands };
            let measurement = measure(&path.toolpath, stock, &opts)?;
            Ok(PocketLevel { top_mm, z_mm, axial_depth_mm: top_mm - z_mm, measurement, floor_pass: false })
        })
        .collect::<Result<Vec<_>, Error>>()?;
    Ok(PocketLevels { levels, per_level })
}

/// Check a floor pass: only with a floor stock F > 0 (the pass cuts it), at most the
/// step-down `max_step_down_mm` when one is given (the pass is a level). Error naming
/// `floor-pass` and `--floor-stock` (or `--max-step-down`).
pub fn check_floor_pass(
    floor_pass: bool,
    floor_stock_mm: Option<f64>,
    max_step_down_mm: Option<f64>,
) -> Result<(), Error> {
    match floor_stock_mm {
        _ if !floor_pass => Ok(()),
        Some(f) if f > 0.0 && max_step_down_mm.is_some_and(|m| f > m) => Err(Error::param(
            Param::FloorPass,
            format!("through --floor-stock {}", num(f)),
            format!(
                "a floor stock of at most --max-step-down {} mm (the floor pass is one level)",
                num(max_step_down_mm.unwrap_or(f))
            ),
        )),
        Some(f) if f > 0.0 => Ok(()),
        other => Err(Error::param(
            Param::FloorPass,
            match other {
                Some(f) => format!("set with --floor-stock {}", num(f)),
                None => "set without --floor-stock".to_owned(),
            },
            "used with --floor-stock F > 0: the floor pass cuts the floor stock F at the full depth",
        )),
    }
}

/// `lv`, the pocket's levels down to the depth − the floor stock, with the floor pass (module
/// docs): one last level from the lowest floor down to `depth_mm`, the same `path`, measured
/// over its stock. Error naming `floor-pass` where `depth_mm` is not below the lowest floor.
pub fn with_floor_pass(mut lv: PocketLevels, path: &PocketPath, depth_mm: f64) -> Result<PocketLevels, Error> {
    let top_mm = lv.per_level.last().map_or(0.0, |l| l.z_mm);
    let z_mm = -depth_mm;
    if !(z_mm < top_mm && depth_mm <= MAX_SIZE_MM) {
        return Err(Error::param(
            Param::FloorPass,
            format!("to the depth {} mm", num(depth_mm)),
            format!("a depth below the lowest level's floor {} mm", num(top_mm)),
        ));
    }
    let opts = EvaluatorOptions::new(path.settings.tool_radius, path.settings.spacing);
    let stock = Stock { polygon: &path.polygon, precut: &path.precut, islands: &path.islands };
    let measurement = measure(&path.toolpath, stock, &opts)?;
    lv.per_level.push(PocketLevel { top_mm, z_mm, axial_depth_mm: top_mm - z_mm, measurement, floor_pass: true });
    Ok(lv)
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

    /// The 60 × 40 rectangle, 12 mm with 0.5 mm floor stock in levels of at most 4 mm, and the
    /// floor pass: 3 levels of 11.5/3 mm, then the pass from −11.5 to −12 (axial 0.5 mm),
    /// measured as every level (the same moves over the same stock: the same reading). Each
    /// level's entry descends from 0.5 mm above its top: the pass's helix drops 1 mm, the
    /// others' 11.5/3 + 0.5 (the toolpath's own descent lengths at those drops); the whole
    /// program's totals are the sums.
    #[test]
    fn the_floor_pass_cuts_the_floor_stock_as_a_last_level() {
        let p = plan(&PocketRequest::default()).expect("plan");
        let lv = plan_levels(p.path(), 11.5, Some(4.0)).expect("levels");
        let lv = with_floor_pass(lv, p.path(), 12.0).expect("floor pass");
        assert_eq!(lv.per_level.len(), 4);
        let pass = &lv.per_level[3];
        assert!(pass.floor_pass && !lv.per_level[2].floor_pass);
        assert_eq!((pass.top_mm, pass.z_mm), (-11.5, -12.0));
        assert!((pass.axial_depth_mm - 0.5).abs() < 1e-12);
        assert_eq!(pass.measurement.max_engagement_rad, lv.per_level[0].measurement.max_engagement_rad);
        let path = p.path();
        let (first, last) = (lv.per_level[0].totals(path), pass.totals(path));
        assert!((last.entry_length_mm - path.toolpath.entry_length_mm(0.5)).abs() < 1e-12);
        assert!((first.entry_length_mm - path.toolpath.entry_length_mm(11.5 / 3.0)).abs() < 1e-9);
        assert!(last.entry_length_mm < first.entry_length_mm);
        let feed = path.settings.feed_mm_per_min;
        let dt = (first.entry_length_mm - last.entry_length_mm) / feed * 60.0;
        assert!((first.time_s - last.time_s - dt).abs() < 1e-9);
        let all = lv.totals(path);
        let sum: f64 = lv.per_level.iter().map(|l| l.totals(path).time_s).sum();
        assert!(
            (all.time_s - sum).abs() < 1e-9 && (all.length_at_depth_mm - 4.0 * first.length_at_depth_mm).abs() < 1e-6
        );
        // below the lowest floor only
        let lv = plan_levels(p.path(), 11.5, Some(4.0)).expect("levels");
        assert_eq!(with_floor_pass(lv, p.path(), 11.5).expect_err("no depth").parameter(), Some(Param::FloorPass));
    }

    #[test]
    fn a_floor_pass_needs_a_floor_stock_within_the_step_down() {
        check_floor_pass(false, None, None).expect("no pass");
        check_floor_pass(true, Some(0.5), Some(4.0)).expect("pass");
        for (stock, step, words) in [
            (None, None, "without --floor-stock"),
            (Some(0.0), None, "--floor-stock F > 0"),
            (Some(5.0), Some(4.0), "--max-step-down 4 mm"),
        ] {
            let e = check_floor_pass(true, stock, step).expect_err("refused");
            assert_eq!(e.parameter(), Some(Param::FloorPass), "{e}");
            assert!(e.to_string().contains("floor-pass") && e.to_string().contains(words), "{e}");
        }
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
