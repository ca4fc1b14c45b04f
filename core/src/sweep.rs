//! Parameter sweeps (the paper's Figs. 5, 9, 12, 28 and Table 2 vary r_e or d): which
//! parameter, on which path type, over which values. The rules both front ends follow (the
//! CLI's `sweep` command and the GUI's sweep panel).

use crate::error::{Error, Param, num};
use crate::job::limits::{MAX_FORCE_TOOTH_SAMPLES, MAX_TOOTH_SAMPLES};
use crate::job::{Job, PathKind, ValidJob};
use crate::path::Cycle;
use crate::quantity::{self, Metric};
use serde::{Deserialize, Serialize};

/// Most values in one sweep: each value is one whole plan, measured at up to 13.7 ms for the
/// default job (`sweep --param linear-distance --from 0 --to 1.5 --steps 100` in 1.37 s on the
/// reference machine, 2 cores; `step` and `aspect-ratio` 0.8–1.1 s), so 200 values take
/// about 2.7 s, within the 5 s a command may take with room for a loaded machine (300 took
/// 4.0 s; 10 000 would take over 2 minutes).
pub const MAX_STEPS: usize = 200;

/// The swept parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SweepParam {
    /// Aspect ratio r_e (elliptical and linear-elliptical paths; circular becomes elliptical).
    #[serde(alias = "AspectRatio")]
    AspectRatio,
    /// Linear distance d (linear-elliptical path; circular and elliptical become it).
    #[serde(alias = "LinearDistance")]
    LinearDistance,
    /// Trochoidal step s (every path).
    #[serde(alias = "Step")]
    Step,
}

impl SweepParam {
    /// All parameters, in CLI order.
    pub const ALL: [SweepParam; 3] = [SweepParam::AspectRatio, SweepParam::LinearDistance, SweepParam::Step];

    /// The name used on the command line (`--param`).
    pub fn name(self) -> &'static str {
        match self {
            SweepParam::AspectRatio => "aspect-ratio",
            SweepParam::LinearDistance => "linear-distance",
            SweepParam::Step => "step",
        }
    }

    /// Parse a CLI name.
    pub fn from_name(s: &str) -> Result<SweepParam, Error> {
        SweepParam::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| Error::param(Param::SweepParam, s, "one of aspect-ratio, linear-distance, step"))
    }

    /// Axis label with unit.
    pub fn label(self) -> &'static str {
        match self {
            SweepParam::AspectRatio => "aspect ratio r_e",
            SweepParam::LinearDistance => "linear distance d [mm]",
            SweepParam::Step => "step s [mm]",
        }
    }

    /// The metric that reports the parameter (its key is the sweep table's value column).
    pub fn metric(self) -> &'static Metric {
        match self {
            SweepParam::AspectRatio => &quantity::ASPECT_RATIO,
            SweepParam::LinearDistance => &quantity::LINEAR_DISTANCE,
            SweepParam::Step => &quantity::STEP,
        }
    }

    /// The range the paper sweeps: r_e 0.5–1.2 (Figs. 5, 9, Table 2), d 0–1.5 mm (Figs. 12,
    /// 28); none for s.
    pub fn paper_range(self) -> Option<(f64, f64)> {
        match self {
            SweepParam::AspectRatio => Some((0.5, 1.2)),
            SweepParam::LinearDistance => Some((0.0, 1.5)),
            SweepParam::Step => None,
        }
    }

    /// The path type a sweep of this parameter runs on, starting from `path`: the circular
    /// path is the elliptical one at r_e = 1 and the elliptical one the linear-elliptical at
    /// d = 0, so those switch; `None` where the parameter does not shape the path (r_e or d on
    /// the circular-type path, d on nothing but the linear-elliptical family).
    pub fn path_for(self, path: PathKind) -> Option<PathKind> {
        match (self, path) {
            (SweepParam::AspectRatio, PathKind::Circular) => Some(PathKind::Elliptical),
            (SweepParam::AspectRatio, p) => p.uses_aspect_ratio().then_some(p),
            (SweepParam::LinearDistance, PathKind::CircularType) => None,
            (SweepParam::LinearDistance, _) => Some(PathKind::LinearElliptical),
            (SweepParam::Step, p) => Some(p),
        }
    }

    /// The paths [`SweepParam::path_for`] accepts, in words ("… needs {this}").
    pub fn needs(self) -> &'static str {
        match self {
            SweepParam::AspectRatio => "an elliptical or linear-elliptical path",
            SweepParam::LinearDistance => "a linear-elliptical path",
            SweepParam::Step => "any path",
        }
    }

    /// The parameter's value in `job`.
    pub fn get(self, job: &Job) -> f64 {
        match self {
            SweepParam::AspectRatio => job.aspect_ratio,
            SweepParam::LinearDistance => job.linear_distance,
            SweepParam::Step => job.step,
        }
    }

    /// Set the parameter in `job`.
    pub fn set(self, job: &mut Job, v: f64) {
        match self {
            SweepParam::AspectRatio => job.aspect_ratio = v,
            SweepParam::LinearDistance => job.linear_distance = v,
            SweepParam::Step => job.step = v,
        }
    }
}

/// The error of a value count `steps` outside 1…[`MAX_STEPS`] (also for a negative count
/// typed on the command line).
pub fn steps_error(steps: i64) -> Error {
    Error::param(Param::Steps, steps, format!("a whole number from 1 to {MAX_STEPS}"))
}

/// The `steps` values from `from` to `to`, both included (`from` alone for one step), each
/// rounded to 1e-9 so binary noise such as 0.7000000000000001 reads as typed. `steps` must be
/// 1…[`MAX_STEPS`] and both ends finite.
pub fn values(from: f64, to: f64, steps: usize) -> Result<Vec<f64>, Error> {
    if steps == 0 || steps > MAX_STEPS {
        return Err(steps_error(steps as i64));
    }
    for (param, v) in [(Param::From, from), (Param::To, to)] {
        if !v.is_finite() {
            return Err(Error::param(param, v, "a finite number"));
        }
    }
    Ok((0..steps)
        .map(|i| {
            let v = if steps == 1 { from } else { from + (to - from) * i as f64 / (steps - 1) as f64 };
            (v * 1e9).round() / 1e9
        })
        .collect())
}

/// Estimated CPU time of one analysed tooth position (chip geometry, engaged arcs) in ms, and
/// of one (force sample × tooth) pair of the force series, fitted on the reference machine
/// (2 cores) to whole plans of a slot of `--slot-width 1000 --tool-diameter 900 --step 100
/// --depth 10 --teeth 4 --rpm 1000`, an engagement near 180° (the costliest; the paper's
/// default job costs less than half as much for its counts): 39 ms a plan at 1611 tooth
/// positions a cycle and 69 ms at 4027 (both at the 400 000 pairs' cap). Their difference gives
/// 30 ms / 2416 positions = 0.0124 ms a position; the 1611 case then leaves 19 ms for 400 000
/// pairs.
const POSITION_MS: f64 = 0.0124;
/// See [`POSITION_MS`].
const PAIR_MS: f64 = 19.0 / 400_000.0;
/// Extra time for each doubling of the tooth positions beyond [`MAX_TOOTH_SAMPLES`] (ms): every
/// analysed position then stands for several teeth and its neighbours are farther apart; the
/// same slot took 87 ms at 12 887 positions (1.65 doublings), 101 ms at 161 000 (5.3) and
/// 115 ms at 3.2 million (9.6, 64 teeth), all at both caps (69.8 ms from the counts), so 10 ms
/// a doubling covers the first and bounds the others.
const DOUBLING_MS: f64 = 10.0;
/// Margin over the fitted costs: the 403-position plan (15 ms measured with the process
/// start-up shared by ten plans) is estimated 11.9 ms from the counts alone.
const MARGIN: f64 = 1.15;

/// Most estimated work of one sweep (ms of CPU, [`plan_cost_ms`] summed over the values): on
/// 2 cores about 3.5 s, under the 5 s a command may take with room for a loaded machine. The
/// paper's default job is estimated at 14 ms a plan (6 ms measured), so its sweeps over the
/// whole r_e and d ranges keep all [`MAX_STEPS`] values.
pub const MAX_SWEEP_COST_MS: f64 = 5000.0;

/// The estimated CPU time (ms, reference machine) of one plan of `job`, from counts known
/// before planning: a cycle holds n = (cycle length)/f_z tooth positions, of which the chip
/// analysis takes at most [`MAX_TOOTH_SAMPLES`], and the force series one sample per spindle
/// degree for each tooth, 360·n pairs, at most [`MAX_FORCE_TOOTH_SAMPLES`]; each count at its
/// cost per unit ([`POSITION_MS`], [`PAIR_MS`]), plus [`DOUBLING_MS`] per doubling of n beyond
/// the first cap, times [`MARGIN`]. The costs are those of an engagement near 180°, so the
/// estimate is on the high side for lighter cuts.
pub fn plan_cost_ms(job: &ValidJob) -> f64 {
    let n = tooth_positions(job);
    let cap = MAX_TOOTH_SAMPLES as f64;
    let positions = n.min(cap);
    let pairs = (360.0 * n).min(MAX_FORCE_TOOTH_SAMPLES as f64);
    let doublings = (n / cap).max(1.0).log2();
    MARGIN * (POSITION_MS * positions + PAIR_MS * pairs + DOUBLING_MS * doublings)
}

/// Tooth positions in one cycle of `job`: cycle length / f_z.
fn tooth_positions(job: &ValidJob) -> f64 {
    Cycle::for_job(job).length() / job.f_z()
}

/// Check a sweep before planning any of it: every job valid (the first error is the one
/// planning would give) and their estimated work ([`plan_cost_ms`]) at most
/// [`MAX_SWEEP_COST_MS`]; the error names `steps`, the most values this job allows, and what
/// drives a plan's work (tooth positions per cycle).
pub fn check_cost(jobs: &[Job]) -> Result<(), Error> {
    let mut total = 0.0;
    let (mut worst, mut worst_n) = (0.0, 0.0);
    for job in jobs {
        let valid = job.validate()?;
        let cost = plan_cost_ms(&valid);
        total += cost;
        if cost > worst {
            (worst, worst_n) = (cost, tooth_positions(&valid));
        }
    }
    if total <= MAX_SWEEP_COST_MS {
        return Ok(());
    }
    let most = ((MAX_SWEEP_COST_MS / worst).floor() as usize).max(1);
    Err(Error::param(
        Param::Steps,
        jobs.len(),
        format!(
            "at most {most} for this job: a plan of it is estimated at up to {} ms ({} tooth positions \
             a cycle), and a sweep may take at most {} ms of estimated work (fewer tooth positions a \
             cycle, i.e. a larger feed per tooth f_z = feed/(rpm·teeth), allow more values)",
            num((worst * 10.0).round() / 10.0),
            num(worst_n.round()),
            num(MAX_SWEEP_COST_MS)
        ),
    ))
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    #[test]
    fn paths_of_a_sweep() {
        use PathKind::*;
        let r_e = SweepParam::AspectRatio;
        let d = SweepParam::LinearDistance;
        let cases = [
            (r_e, Circular, Some(Elliptical)),
            (r_e, CircularType, None),
            (r_e, Elliptical, Some(Elliptical)),
            (r_e, LinearElliptical, Some(LinearElliptical)),
            (d, Circular, Some(LinearElliptical)),
            (d, CircularType, None),
            (d, Elliptical, Some(LinearElliptical)),
            (d, LinearElliptical, Some(LinearElliptical)),
            (SweepParam::Step, CircularType, Some(CircularType)),
        ];
        for (param, path, want) in cases {
            assert_eq!(param.path_for(path), want, "{} on {}", param.name(), path.name());
        }
    }

    #[test]
    fn values_are_checked_and_rounded() {
        assert_eq!(values(0.5, 1.2, 8).expect("valid")[2], 0.7);
        assert_eq!(values(0.5, 1.2, 1).expect("valid"), vec![0.5]);
        assert_eq!(values(0.5, 1.0, 0).expect_err("zero").parameter(), Some(Param::Steps));
        assert_eq!(values(f64::NAN, 1.0, 2).expect_err("nan").parameter(), Some(Param::From));
        assert_eq!(values(0.0, f64::INFINITY, 2).expect_err("inf").parameter(), Some(Param::To));
        assert_eq!(steps_error(-1).to_string(), "invalid steps = -1: must be a whole number from 1 to 200");
    }

    #[test]
    fn names_round_trip_and_old_gui_spellings_load() {
        for p in SweepParam::ALL {
            assert_eq!(SweepParam::from_name(p.name()), Ok(p));
            p.set(&mut Job::default(), 0.5);
        }
        let old: SweepParam = serde_json::from_str("\"LinearDistance\"").expect("old spelling");
        assert_eq!(old, SweepParam::LinearDistance);
        assert_eq!(serde_json::to_string(&SweepParam::AspectRatio).expect("json"), "\"aspect-ratio\"");
    }

    #[test]
    fn the_cost_estimate_follows_the_counts() {
        // Default job (paper Table 1): a cycle of 31.424 mm at f_z = 0.075 mm holds 419.0 tooth
        // positions (the plan's own teeth_per_cycle); 360·419 = 150 839 force pairs; below the
        // first cap, no doublings.
        let job = Job::default().validate().expect("valid");
        let n = 31.42388478711044 / 0.075;
        let want = 1.15 * (0.0124 * n + 19.0 / 400_000.0 * 360.0 * n);
        assert!((plan_cost_ms(&job) / want - 1.0).abs() < 1e-6, "{} vs {want}", plan_cost_ms(&job));
        // 64 teeth at 20 000 rpm: f_z = 600/(20000·64) = 4.6875e-4 mm, 67 038 positions: both
        // caps, 4096·0.0124 + 19 = 69.79 ms, and log2(67 038/4096) = 4.03 doublings of 10 ms.
        let heavy = Job { teeth: 64, rpm: 20_000.0, ..Job::default() }.validate().expect("valid");
        let n: f64 = 31.42388478711044 / 4.6875e-4;
        let capped = 1.15 * (0.0124 * 4096.0 + 19.0 + 10.0 * (n / 4096.0).log2());
        assert!((plan_cost_ms(&heavy) / capped - 1.0).abs() < 1e-12, "{} vs {capped}", plan_cost_ms(&heavy));
    }

    #[test]
    fn a_sweep_over_its_budget_is_refused_naming_steps() {
        // The default job's 200 values: 200 × 14.2 ms = 2.85 s ≤ 5 s, accepted.
        assert_eq!(check_cost(&vec![Job::default(); MAX_STEPS]), Ok(()));
        // 64 teeth at 20 000 rpm (previous test): 1.15·(69.79 + 40.32) = 126.6 ms a plan;
        // 5000/126.6 = 39.5, so 39 values pass and 40 do not.
        let heavy = Job { teeth: 64, rpm: 20_000.0, ..Job::default() };
        assert_eq!(check_cost(&vec![heavy.clone(); 39]), Ok(()));
        let err = check_cost(&vec![heavy; 40]).expect_err("over the budget");
        assert_eq!(err.parameter(), Some(Param::Steps));
        assert!(err.to_string().contains("at most 39 for this job"), "{err}");
        // An invalid value is its own error, as planning it would say.
        let bad = Job { step: -1.0, ..Job::default() };
        assert_eq!(check_cost(&[bad]).expect_err("invalid").parameter(), Some(Param::Step));
    }
}
