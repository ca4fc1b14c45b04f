//! Parameter sweeps (the paper's Figs. 5, 9, 12, 28 and Table 2 vary r_e or d): which
//! parameter, on which path type, over which values. The rules both front ends follow (the
//! CLI's `sweep` command and the GUI's sweep panel).

use crate::error::{Error, Param};
use crate::job::{Job, PathKind};
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
}
