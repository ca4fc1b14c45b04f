//! Quantities as data: every metric of a plan ([`Metric`], read from [`Metrics`]) and every
//! column of the per-tooth series ([`SeriesColumn`], read from [`ToothSample`]) with its key
//! (the CLI's JSON and CSV name), label, unit, explanation and source, once.
//!
//! The front ends read these tables: the CLI's `analyze` JSON writes [`METRICS`], its sweep
//! table and series CSV the entries they list, the GUI's metrics, compare and sweep panels
//! the entries they show. Adding a quantity: its field in [`Metrics`] (or [`ToothSample`]),
//! one entry here (a `const` and its line in [`METRICS`] or [`SERIES`]), and one line in each
//! front end that shows it.

use crate::analysis::ToothSample;
use crate::plan::Metrics;

/// One metric of a plan.
#[derive(Debug)]
pub struct Metric {
    /// Name in the CLI's `analyze` JSON and sweep CSV (the [`Metrics`] field).
    pub key: &'static str,
    /// Short label as the paper writes it (GUI rows, legends, table headers).
    pub symbol: &'static str,
    /// Unit ("" for a pure number); "°" is written without a space.
    pub unit: &'static str,
    /// What it is and where it comes from (paper equation, figure or table): the tooltip.
    pub about: &'static str,
    /// Decimals shown in the GUI.
    pub decimals: usize,
    /// A count: written as a whole number (JSON integer).
    pub whole: bool,
    /// Whether a larger value is better (`None`: neither), for colouring comparisons.
    pub higher_is_better: Option<bool>,
    /// Its value in a plan's metrics.
    pub value: fn(&Metrics) -> f64,
}

impl Metric {
    /// The value in `m`.
    pub fn of(&self, m: &Metrics) -> f64 {
        (self.value)(m)
    }

    /// The value in `m` with the GUI's decimals and the unit, e.g. "0.0581 mm", "51.5°", "32".
    pub fn display(&self, m: &Metrics) -> String {
        let v = format!("{:.*}", self.decimals, self.of(m));
        match self.unit {
            "" => v,
            "°" => format!("{v}°"),
            unit => format!("{v} {unit}"),
        }
    }

    /// "symbol [unit]", or the symbol alone for a pure number (table headers, axis labels).
    pub fn heading(&self) -> String {
        if self.unit.is_empty() { self.symbol.to_owned() } else { format!("{} [{}]", self.symbol, self.unit) }
    }
}

pub const CYCLE_LENGTH: Metric = Metric {
    key: "cycle_length_mm",
    symbol: "cycle length",
    unit: "mm",
    about: "Path length of one cycle (Fig. 5).",
    decimals: 3,
    whole: false,
    higher_is_better: Some(false),
    value: |m| m.cycle_length_mm,
};
pub const T_CYCLE: Metric = Metric {
    key: "t_cycle_s",
    symbol: "t_cycle",
    unit: "s",
    about: "t_cycle = cycle length / f_r (Table 2).",
    decimals: 3,
    whole: false,
    higher_is_better: Some(false),
    value: |m| m.t_cycle_s,
};
pub const MRR: Metric = Metric {
    key: "mrr_mm3_per_min",
    symbol: "MRR",
    unit: "mm³/min",
    about: "MRR = B·s·a_p / t_cycle (Table 2).",
    decimals: 0,
    whole: false,
    higher_is_better: Some(true),
    value: |m| m.mrr_mm3_per_min,
};
pub const F_Z: Metric = Metric {
    key: "f_z_mm",
    symbol: "f_z",
    unit: "mm",
    about: "Feed per tooth f_z = f_r/(n·z).",
    decimals: 4,
    whole: false,
    higher_is_better: None,
    value: |m| m.f_z_mm,
};
pub const H_MAX: Metric = Metric {
    key: "h_max_mm",
    symbol: "h_max",
    unit: "mm",
    about: "Largest local maximum chip thickness over a steady-state cycle, eqs. (3)–(6) (Table 2).",
    decimals: 4,
    whole: false,
    higher_is_better: Some(false),
    value: |m| m.h_max_mm,
};
pub const T_HMAX: Metric = Metric {
    key: "t_hmax_s",
    symbol: "t_hmax",
    unit: "s",
    about: "Time from the start of cutting to h_max (Table 2).",
    decimals: 3,
    whole: false,
    higher_is_better: None,
    value: |m| m.t_hmax_s,
};
pub const T_COOLING: Metric = Metric {
    key: "t_cooling_s",
    symbol: "t_cooling",
    unit: "s",
    about: "Time per cycle in which no tooth cuts (Table 2).",
    decimals: 3,
    whole: false,
    higher_is_better: Some(true),
    value: |m| m.t_cooling_s,
};
pub const ENGAGEMENT_MAX: Metric = Metric {
    key: "engagement_max_deg",
    symbol: "max engagement",
    unit: "°",
    about: "Largest engagement angle; recommended ≤ 46° (Grechishnikov et al. 2017).",
    decimals: 1,
    whole: false,
    higher_is_better: Some(false),
    value: |m| m.engagement_max_deg,
};
pub const WAVINESS_LEFT: Metric = Metric {
    key: "waviness_left_mm",
    symbol: "W_l",
    unit: "mm",
    about: "Left (−x) wall waviness, peak to valley (section 2.3, Fig. 9).",
    decimals: 4,
    whole: false,
    higher_is_better: Some(false),
    value: |m| m.waviness_left_mm,
};
pub const WAVINESS_RIGHT: Metric = Metric {
    key: "waviness_right_mm",
    symbol: "W_r",
    unit: "mm",
    about: "Right (+x) wall waviness, peak to valley (section 2.3, Fig. 9).",
    decimals: 4,
    whole: false,
    higher_is_better: Some(false),
    value: |m| m.waviness_right_mm,
};
pub const A: Metric = Metric {
    key: "a_mm",
    symbol: "a",
    unit: "mm",
    about: "Trochoidal radius a = (B − D)/2 (major semi-axis).",
    decimals: 3,
    whole: false,
    higher_is_better: None,
    value: |m| m.a_mm,
};
pub const B: Metric = Metric {
    key: "b_mm",
    symbol: "b",
    unit: "mm",
    about: "b = r_e·a, eq. (2) (minor semi-axis along the slot).",
    decimals: 3,
    whole: false,
    higher_is_better: None,
    value: |m| m.b_mm,
};
pub const ASPECT_RATIO: Metric = Metric {
    key: "aspect_ratio",
    symbol: "r_e",
    unit: "",
    about: "Aspect ratio r_e = b/a, eq. (2).",
    decimals: 2,
    whole: false,
    higher_is_better: None,
    value: |m| m.aspect_ratio,
};
pub const LINEAR_DISTANCE: Metric = Metric {
    key: "linear_distance_mm",
    symbol: "d",
    unit: "mm",
    about: "Linear distance d along each wall (section 3, linear-elliptical path).",
    decimals: 2,
    whole: false,
    higher_is_better: None,
    value: |m| m.linear_distance_mm,
};
pub const STEP: Metric = Metric {
    key: "step_mm",
    symbol: "s",
    unit: "mm",
    about: "Trochoidal step s: advance per cycle.",
    decimals: 3,
    whole: false,
    higher_is_better: None,
    value: |m| m.step_mm,
};
pub const CYCLES: Metric = Metric {
    key: "cycles",
    symbol: "cycles",
    unit: "",
    about: "Number of cycles from outside the stock to beyond the slot end.",
    decimals: 0,
    whole: true,
    higher_is_better: None,
    value: |m| m.cycles as f64,
};
pub const PATH_LENGTH: Metric = Metric {
    key: "path_length_mm",
    symbol: "path length",
    unit: "mm",
    about: "Whole tool-centre path length.",
    decimals: 1,
    whole: false,
    higher_is_better: None,
    value: |m| m.path_length_mm,
};
pub const MACHINING_TIME: Metric = Metric {
    key: "machining_time_s",
    symbol: "machining time",
    unit: "s",
    about: "Whole path at the feed rate f_r.",
    decimals: 1,
    whole: false,
    higher_is_better: None,
    value: |m| m.machining_time_s,
};
pub const TEETH_PER_CYCLE: Metric = Metric {
    key: "teeth_per_cycle",
    symbol: "teeth per cycle",
    unit: "",
    about: "Tooth positions per cycle: cycle length / f_z.",
    decimals: 1,
    whole: false,
    higher_is_better: None,
    value: |m| m.teeth_per_cycle,
};
pub const STEP_LIMIT_46DEG: Metric = Metric {
    key: "step_limit_46deg_mm",
    symbol: "step for 46°",
    unit: "mm",
    about: "Largest step keeping the engagement ≤ 46° (two-circle model, Wu et al. 2016 eqs. 2–6).",
    decimals: 3,
    whole: false,
    higher_is_better: None,
    value: |m| m.step_limit_46deg_mm,
};
pub const STEP_LIMIT_15PCT_DEPTH: Metric = Metric {
    key: "step_limit_15pct_depth_mm",
    symbol: "step for 15 % D",
    unit: "mm",
    about: "Largest step for a straight-cut-equivalent depth of 15 % of D (Grechishnikov et al. 2017).",
    decimals: 3,
    whole: false,
    higher_is_better: None,
    value: |m| m.step_limit_15pct_depth_mm,
};

/// Every numeric metric of [`Metrics`] (all its fields but the path kind), in field order.
pub const METRICS: [&Metric; 21] = [
    &CYCLE_LENGTH,
    &T_CYCLE,
    &MRR,
    &F_Z,
    &H_MAX,
    &T_HMAX,
    &T_COOLING,
    &ENGAGEMENT_MAX,
    &WAVINESS_LEFT,
    &WAVINESS_RIGHT,
    &A,
    &B,
    &ASPECT_RATIO,
    &LINEAR_DISTANCE,
    &STEP,
    &CYCLES,
    &PATH_LENGTH,
    &MACHINING_TIME,
    &TEETH_PER_CYCLE,
    &STEP_LIMIT_46DEG,
    &STEP_LIMIT_15PCT_DEPTH,
];

/// One column of the per-tooth series of a steady-state cycle.
#[derive(Debug)]
pub struct SeriesColumn {
    /// Column name in the CLI's series CSV.
    pub key: &'static str,
    /// Short label (GUI axes and legends).
    pub symbol: &'static str,
    /// Unit ("" for a pure number or a flag).
    pub unit: &'static str,
    /// What it is and where it comes from.
    pub about: &'static str,
    /// Decimals written in the CSV.
    pub decimals: usize,
    /// Its value for one tooth (a flag as 0 or 1).
    pub value: fn(&ToothSample) -> f64,
}

impl SeriesColumn {
    /// The value for `t`.
    pub fn of(&self, t: &ToothSample) -> f64 {
        (self.value)(t)
    }

    /// The value for `t` as the CSV writes it.
    pub fn csv(&self, t: &ToothSample) -> String {
        format!("{:.*}", self.decimals, self.of(t))
    }
}

pub const TIME: SeriesColumn = SeriesColumn {
    key: "time_s",
    symbol: "t",
    unit: "s",
    about: "Time from the start of the cycle.",
    decimals: 6,
    value: |t| t.time_s,
};
pub const H: SeriesColumn = SeriesColumn {
    key: "h_mm",
    symbol: "h",
    unit: "mm",
    about: "Local maximum chip thickness of the tooth, eqs. (3)–(6), Fig. 6.",
    decimals: 7,
    value: |t| t.h_mm,
};
pub const ENGAGEMENT: SeriesColumn = SeriesColumn {
    key: "engagement_deg",
    symbol: "engagement",
    unit: "°",
    about: "Engagement angle: angular extent of the tool edge in uncut material.",
    decimals: 4,
    value: |t| t.engagement_rad.to_degrees(),
};
pub const CUTTING: SeriesColumn = SeriesColumn {
    key: "cutting",
    symbol: "cutting",
    unit: "",
    about: "1 if the tooth removes material (h above the numeric noise floor), else 0.",
    decimals: 0,
    value: |t| f64::from(u8::from(t.cutting)),
};
pub const S: SeriesColumn = SeriesColumn {
    key: "s_mm",
    symbol: "s",
    unit: "mm",
    about: "Arc length from the start of the cycle.",
    decimals: 6,
    value: |t| t.s_mm,
};
pub const X: SeriesColumn = SeriesColumn {
    key: "x_mm",
    symbol: "x",
    unit: "mm",
    about: "Tool centre x, cycle origin at (0, 0).",
    decimals: 6,
    value: |t| t.x_mm,
};
pub const Y: SeriesColumn = SeriesColumn {
    key: "y_mm",
    symbol: "y",
    unit: "mm",
    about: "Tool centre y, cycle origin at (0, 0).",
    decimals: 6,
    value: |t| t.y_mm,
};

/// The columns of the series CSV, in order.
pub const SERIES: [&SeriesColumn; 7] = [&TIME, &H, &ENGAGEMENT, &CUTTING, &S, &X, &Y];

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::{Job, plan};

    /// The table covers every numeric field of [`Metrics`] under its serialised name, with
    /// the value of that field.
    #[test]
    fn metrics_table_is_the_metrics_struct() {
        let m = plan(&Job::default()).expect("plan").metrics;
        let json = serde_json::to_value(&m).expect("json");
        let fields = json.as_object().expect("object");
        assert_eq!(fields.len(), METRICS.len() + 1, "every field but `path` has an entry");
        for q in METRICS {
            let v = fields.get(q.key).and_then(serde_json::Value::as_f64);
            assert_eq!(v, Some(q.of(&m)), "{}", q.key);
            assert_eq!(q.whole, fields[q.key].is_u64(), "{}", q.key);
        }
    }

    #[test]
    fn display_and_heading_follow_the_unit() {
        let m = plan(&Job::default()).expect("plan").metrics;
        assert_eq!(F_Z.display(&m), "0.0750 mm");
        assert_eq!(CYCLES.display(&m), m.cycles.to_string());
        assert!(ENGAGEMENT_MAX.display(&m).ends_with('°'));
        assert_eq!(MRR.heading(), "MRR [mm³/min]");
        assert_eq!(ASPECT_RATIO.heading(), "r_e");
    }
}
