//! The machine model: per-axis feed, acceleration and jerk limits and the
//! controller's path tolerance, the presets in `assets/machines/`, and the feed planner that
//! turns a path into the feed over time ([`planner`]).
//!
//! A job names a preset (`machine = "vmc"`) or states its own limits in a `[machine]` table
//! with the keys of [`Machine`]. Without a machine the plan assumes an ideal one (the
//! programmed feed everywhere): real and programmed times are then equal.

pub mod link;
pub mod planner;
pub mod program_time;

use crate::error::{Error, Param, num};
use serde::{Deserialize, Serialize};

pub use planner::{FeedPoint, FeedProfile, RealTime, real_time};
pub use program_time::{CutHeights, ProgramTime, program_moves, program_time, toolpath_time};

/// The limits of one machine. Keys (TOML, kebab-case) are the job file's `[machine]` keys.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct Machine {
    /// Name (a preset's name, or the user's).
    pub name: String,
    /// Largest feed of the X and Y axes (mm/min).
    pub max_feed_x: f64,
    pub max_feed_y: f64,
    /// Largest acceleration of the X and Y axes (mm/s²).
    pub acceleration_x: f64,
    pub acceleration_y: f64,
    /// Largest jerk of the X and Y axes (mm/s³).
    pub jerk_x: f64,
    pub jerk_y: f64,
    /// Path tolerance of the controller's blending (mm): how far it may round a corner or a
    /// curvature jump (LinuxCNC G64 P, GRBL junction deviation, Sinumerik CYCLE832).
    pub path_tolerance: f64,
    /// Shortest time one NC block may take (s) without starving the controller's look-ahead
    /// (its block processing rate, or the serial line that feeds it); the variable feed's
    /// blocks last at least this long (the `feed` module). Job files without it take
    /// [`DEFAULT_BLOCK_TIME_S`].
    #[serde(default = "default_block_time")]
    pub block_time: f64,
    /// Smallest feed the controller runs (mm/min): no program feed is below it, and the
    /// options that would set one lower (`--target-hmax`, `--max-feed`, `--return-feed`,
    /// `feed`) are refused by name. At most each axis's maximum feed. Job files without it
    /// take [`DEFAULT_MIN_FEED_MM_PER_MIN`].
    #[serde(default = "default_min_feed")]
    pub min_feed: f64,
    /// Rate of rapid moves (G0) of every axis (mm/min), with the axes' acceleration and jerk
    /// ([`program_time`]). Job files without it take the slower axis's maximum feed
    /// (GRBL runs G0 at the axes' maximum rates).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rapid_feed: Option<f64>,
    /// Largest power (W) and torque (N·m) of the spindle: `verify` reports the moves above
    /// them. Job files without them: not checked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spindle_power: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spindle_torque: Option<f64>,
}

/// Block time of a machine that does not state one, and of the ideal machine (s): the `vmc`
/// preset's.
pub const DEFAULT_BLOCK_TIME_S: f64 = 0.004;

fn default_block_time() -> f64 {
    DEFAULT_BLOCK_TIME_S
}

/// Smallest feed of a machine that does not state one, and of the ideal machine (mm/min):
/// GRBL's floor (`MINIMUM_FEED_RATE 1.0 // (mm/min)` in its `config.h`, the planner raises
/// lower feeds to it). The NC writer writes F in steps of 0.1 mm/min, so a feed of at least
/// 1 mm/min is written within 5 % (0.05/1) and never as `F0.0`.
pub const DEFAULT_MIN_FEED_MM_PER_MIN: f64 = 1.0;

fn default_min_feed() -> f64 {
    DEFAULT_MIN_FEED_MM_PER_MIN
}

/// Largest feed of any axis, and so of `min-feed` (mm/min).
pub const MAX_FEED_LIMIT_MM_PER_MIN: f64 = 1.0e6;

/// The presets, in the order the GUI lists them: (name, TOML text with the sources).
pub const PRESETS: [(&str, &str); 3] = [
    ("hobby-router", include_str!("../../../assets/machines/hobby-router.toml")),
    ("vmc", include_str!("../../../assets/machines/vmc.toml")),
    ("hsc", include_str!("../../../assets/machines/hsc.toml")),
];

/// The names of the presets.
pub fn preset_names() -> impl Iterator<Item = &'static str> {
    PRESETS.iter().map(|(n, _)| *n)
}

impl Machine {
    /// The preset called `name`.
    pub fn preset(name: &str) -> Result<Machine, Error> {
        let (_, text) = PRESETS.iter().find(|(n, _)| *n == name).ok_or_else(|| {
            Error::param(Param::Machine, name, format!("one of {}", preset_names().collect::<Vec<_>>().join(", ")))
        })?;
        toml::from_str(text).map_err(|e| Error::File(format!("machine preset {name}: {e}")))
    }

    /// The parameters of a machine: its name and every limit (job keys, GUI error lines).
    pub const PARAMS: [Param; 11] = [
        Param::Machine,
        Param::MaxFeedX,
        Param::MaxFeedY,
        Param::AccelerationX,
        Param::AccelerationY,
        Param::JerkX,
        Param::JerkY,
        Param::PathTolerance,
        Param::BlockTime,
        Param::MinFeed,
        Param::RapidFeed,
    ];

    /// Check every limit: finite and > 0, and each axis's maximum feed at least the minimum
    /// feed; the error names the key.
    pub fn validate(&self) -> Result<(), Error> {
        let checks = [
            (Param::MinFeed, self.min_feed, MAX_FEED_LIMIT_MM_PER_MIN, "mm/min"),
            (Param::MaxFeedX, self.max_feed_x, MAX_FEED_LIMIT_MM_PER_MIN, "mm/min"),
            (Param::MaxFeedY, self.max_feed_y, MAX_FEED_LIMIT_MM_PER_MIN, "mm/min"),
            (Param::AccelerationX, self.acceleration_x, 1.0e6, "mm/s²"),
            (Param::AccelerationY, self.acceleration_y, 1.0e6, "mm/s²"),
            (Param::JerkX, self.jerk_x, 1.0e9, "mm/s³"),
            (Param::JerkY, self.jerk_y, 1.0e9, "mm/s³"),
            (Param::PathTolerance, self.path_tolerance, 10.0, "mm"),
            (Param::BlockTime, self.block_time, 1.0, "s"),
            (Param::RapidFeed, self.rapid_mm_per_min(), MAX_FEED_LIMIT_MM_PER_MIN, "mm/min"),
        ];
        for (key, v, max, unit) in
            [("spindle-power", self.spindle_power, 1.0e6, "W"), ("spindle-torque", self.spindle_torque, 1.0e5, "N·m")]
        {
            if let Some(v) = v
                && !(v.is_finite() && v > 0.0 && v <= max)
            {
                return Err(Error::geometry(key, v, format!("a finite number > 0 and ≤ {} {unit}", num(max))));
            }
        }
        for (param, v, max, unit) in checks {
            if !(v.is_finite() && v > 0.0 && v <= max) {
                return Err(Error::param(param, v, format!("a finite number > 0 and ≤ {} {unit}", num(max))));
            }
        }
        for (param, v) in [
            (Param::MaxFeedX, self.max_feed_x),
            (Param::MaxFeedY, self.max_feed_y),
            (Param::RapidFeed, self.rapid_mm_per_min()),
        ] {
            if v < self.min_feed {
                return Err(Error::param(
                    param,
                    v,
                    format!(
                        "from the machine's min-feed {} to {} mm/min",
                        num(self.min_feed),
                        num(MAX_FEED_LIMIT_MM_PER_MIN)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Rate of rapid moves (mm/min): `rapid-feed`, else the slower axis's maximum feed.
    pub fn rapid_mm_per_min(&self) -> f64 {
        self.rapid_feed.unwrap_or(self.max_feed_x.min(self.max_feed_y))
    }

    /// Path feed limit (mm/s): the slower axis, as LinuxCNC bounds a move in the XY plane.
    pub fn max_speed_mm_per_s(&self) -> f64 {
        self.max_feed_x.min(self.max_feed_y) / 60.0
    }

    /// Path acceleration limit a (mm/s²): the weaker axis (LinuxCNC `pmCircleActualMaxVel`
    /// takes the plane's bound).
    pub fn acceleration(&self) -> f64 {
        self.acceleration_x.min(self.acceleration_y)
    }

    /// Path jerk limit J (mm/s³): the weaker axis.
    pub fn jerk(&self) -> f64 {
        self.jerk_x.min(self.jerk_y)
    }
}

/// The machine of a job: a preset by name, or limits given in the job.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum MachineChoice {
    /// `machine = "vmc"`.
    Preset(String),
    /// `[machine]` with every key of [`Machine`].
    Custom(Machine),
}

impl MachineChoice {
    /// The machine's limits, validated.
    pub fn machine(&self) -> Result<Machine, Error> {
        let m = match self {
            MachineChoice::Preset(name) => Machine::preset(name)?,
            MachineChoice::Custom(m) => m.clone(),
        };
        m.validate()?;
        Ok(m)
    }

    /// The name shown for it.
    pub fn name(&self) -> &str {
        match self {
            MachineChoice::Preset(n) => n,
            MachineChoice::Custom(m) => &m.name,
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    #[test]
    fn presets_parse_and_are_valid() {
        for name in preset_names() {
            let m = Machine::preset(name).expect("preset");
            assert_eq!(m.name, name);
            m.validate().expect("valid");
        }
        // the VMC feeds at 20 m/min
        assert_eq!(Machine::preset("vmc").expect("vmc").max_speed_mm_per_s(), 20000.0 / 60.0);
        assert_eq!(Machine::preset("lathe").expect_err("unknown").parameter(), Some(Param::Machine));
    }

    #[test]
    fn bad_limits_are_rejected_by_name() {
        let good = Machine::preset("vmc").expect("vmc");
        type Setter = fn(&mut Machine, f64);
        let cases: [(Setter, Param); 10] = [
            (|m, v| m.max_feed_x = v, Param::MaxFeedX),
            (|m, v| m.max_feed_y = v, Param::MaxFeedY),
            (|m, v| m.acceleration_x = v, Param::AccelerationX),
            (|m, v| m.acceleration_y = v, Param::AccelerationY),
            (|m, v| m.jerk_x = v, Param::JerkX),
            (|m, v| m.jerk_y = v, Param::JerkY),
            (|m, v| m.path_tolerance = v, Param::PathTolerance),
            (|m, v| m.block_time = v, Param::BlockTime),
            (|m, v| m.min_feed = v, Param::MinFeed),
            (|m, v| m.rapid_feed = Some(v), Param::RapidFeed),
        ];
        for (set, param) in cases {
            for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
                let mut m = good.clone();
                set(&mut m, bad);
                let e = m.validate().expect_err("rejected");
                assert_eq!(e.parameter(), Some(param), "{e}");
                assert!(e.to_string().contains(param.cli_name()), "{e}");
            }
        }
    }

    #[test]
    fn min_feed_is_at_most_each_axis_feed_and_defaults_to_one() {
        // every preset states it: 1 mm/min (GRBL's MINIMUM_FEED_RATE, see the preset files)
        for name in preset_names() {
            assert_eq!(Machine::preset(name).expect("preset").min_feed, 1.0, "{name}");
        }
        let mut m = Machine::preset("vmc").expect("vmc");
        // the axis feeds may equal the smallest feed, not fall below it
        m.min_feed = 20000.0;
        m.validate().expect("max = min is valid");
        type Setter = fn(&mut Machine);
        let below: [(Setter, Param); 2] =
            [(|m| m.max_feed_x = 1e-9, Param::MaxFeedX), (|m| m.max_feed_y = 19999.0, Param::MaxFeedY)];
        for (set, param) in below {
            let mut bad = m.clone();
            set(&mut bad);
            let e = bad.validate().expect_err("below min-feed");
            assert_eq!(e.parameter(), Some(param), "{e}");
            assert!(e.to_string().contains("min-feed 20000"), "{e}");
        }
        // a [machine] table without the key takes the default
        let text = "name = \"m\"\nmax-feed-x = 100.0\nmax-feed-y = 100.0\nacceleration-x = 1.0\n\
                    acceleration-y = 1.0\njerk-x = 1.0\njerk-y = 1.0\npath-tolerance = 0.01\n";
        let m: Machine = toml::from_str(text).expect("parse");
        assert_eq!(m.min_feed, DEFAULT_MIN_FEED_MM_PER_MIN);
        // and rapids at the slower axis's feed
        assert_eq!((m.rapid_feed, m.rapid_mm_per_min()), (None, 100.0));
    }
}
