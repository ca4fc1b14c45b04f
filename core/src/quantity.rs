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
    /// A metric that is no count and neither better larger nor smaller.
    pub const fn new(
        key: &'static str,
        symbol: &'static str,
        unit: &'static str,
        decimals: usize,
        value: fn(&Metrics) -> f64,
        about: &'static str,
    ) -> Metric {
        Metric { key, symbol, unit, about, decimals, whole: false, higher_is_better: None, value }
    }

    /// The same metric, a count.
    pub const fn whole(self) -> Metric {
        Metric { whole: true, ..self }
    }

    /// The same metric, better when larger.
    pub const fn higher_is_better(self) -> Metric {
        Metric { higher_is_better: Some(true), ..self }
    }

    /// The same metric, better when smaller.
    pub const fn lower_is_better(self) -> Metric {
        Metric { higher_is_better: Some(false), ..self }
    }

    /// The value in `m`.
    pub fn of(&self, m: &Metrics) -> f64 {
        (self.value)(m)
    }

    /// The value in `m` with the GUI's decimals and the unit, e.g. "0.0581 mm", "51.5°", "32".
    pub fn display(&self, m: &Metrics) -> String {
        let x = self.of(m);
        if x.is_nan() {
            return "— (no value)".to_owned();
        }
        let v = format!("{:.*}", self.decimals, x);
        match self.unit {
            "" => v,
            "°" => format!("{v}°"),
            "s" => seconds_with_clock(x, self.decimals),
            unit => format!("{v} {unit}"),
        }
    }

    /// "symbol [unit]", or the symbol alone for a pure number (table headers, axis labels).
    pub fn heading(&self) -> String {
        if self.unit.is_empty() { self.symbol.to_owned() } else { format!("{} [{}]", self.symbol, self.unit) }
    }
}

pub const CYCLE_LENGTH: Metric = Metric::new(
    "cycle_length_mm",
    "cycle length",
    "mm",
    3,
    |m| m.cycle_length_mm,
    "Path length of one cycle (Fig. 5).",
)
.lower_is_better();
pub const T_CYCLE: Metric =
    Metric::new("t_cycle_s", "t_cycle", "s", 3, |m| m.t_cycle_s, "t_cycle = cycle length / f_r (Table 2).")
        .lower_is_better();
pub const MRR: Metric =
    Metric::new("mrr_mm3_per_min", "MRR", "mm³/min", 0, |m| m.mrr_mm3_per_min, "MRR = B·s·a_p / t_cycle (Table 2).")
        .higher_is_better();
/// `seconds` as hours, minutes and seconds, `h:mm:ss`, rounded to the whole second
/// (3180.1 s: `0:53:00`); negative or not finite: `—`.
pub fn clock(seconds: f64) -> String {
    if !(seconds.is_finite() && seconds >= 0.0) {
        return "—".to_owned();
    }
    let whole = seconds.round() as u64;
    format!("{}:{:02}:{:02}", whole / 3600, whole / 60 % 60, whole % 60)
}

/// A time in seconds with `decimals`, and from a minute on also as `h:mm:ss` ([`clock`]):
/// `3180.1 s (0:53:00)`; `12.5 s`.
pub fn seconds_with_clock(seconds: f64, decimals: usize) -> String {
    if seconds >= 60.0 && seconds.is_finite() {
        format!("{seconds:.decimals$} s ({})", clock(seconds))
    } else {
        format!("{seconds:.decimals$} s")
    }
}

pub const F_Z: Metric = Metric::new("f_z_mm", "f_z", "mm", 4, |m| m.f_z_mm, "Feed per tooth f_z = f_r/(n·z).");
pub const H_MAX: Metric = Metric::new(
    "h_max_mm",
    "h_max",
    "mm",
    4,
    |m| m.h_max_mm,
    "Largest local maximum chip thickness over a steady-state cycle, eqs. (3)–(6) (Table 2), at the feed \
     the machine reaches (each tooth's chip scaled by the reached over the programmed feed).",
)
.lower_is_better();
pub const H_MAX_PROGRAMMED: Metric = Metric::new(
    "h_max_programmed_mm",
    "h_max at f_r",
    "mm",
    4,
    |m| m.h_max_programmed_mm,
    "h_max at the programmed feed everywhere (the same as h_max without a machine or where it holds the feed).",
);
pub const T_HMAX: Metric =
    Metric::new("t_hmax_s", "t_hmax", "s", 3, |m| m.t_hmax_s, "Time from the start of cutting to h_max (Table 2).");
pub const T_COOLING: Metric = Metric::new(
    "t_cooling_s",
    "t_cooling",
    "s",
    3,
    |m| m.t_cooling_s,
    "Time per cycle in which no tooth cuts (Table 2).",
)
.higher_is_better();
pub const ENGAGEMENT_MAX: Metric = Metric::new(
    "engagement_max_deg",
    "max engagement",
    "°",
    1,
    |m| m.engagement_max_deg,
    "Largest engagement angle; recommended ≤ 46° (Grechishnikov et al. 2017).",
)
.lower_is_better();
pub const WAVINESS_LEFT: Metric = Metric::new(
    "waviness_left_mm",
    "W_l",
    "mm",
    4,
    |m| m.waviness_left_mm,
    "Left (−x) wall waviness, peak to valley (section 2.3, Fig. 9).",
)
.lower_is_better();
pub const WAVINESS_RIGHT: Metric = Metric::new(
    "waviness_right_mm",
    "W_r",
    "mm",
    4,
    |m| m.waviness_right_mm,
    "Right (+x) wall waviness, peak to valley (section 2.3, Fig. 9).",
)
.lower_is_better();
pub const A: Metric =
    Metric::new("a_mm", "a", "mm", 3, |m| m.a_mm, "Trochoidal radius a = (B − D)/2 (major semi-axis).");
pub const B: Metric =
    Metric::new("b_mm", "b", "mm", 3, |m| m.b_mm, "b = r_e·a, eq. (2) (minor semi-axis along the slot).");
pub const ASPECT_RATIO: Metric =
    Metric::new("aspect_ratio", "r_e", "", 2, |m| m.aspect_ratio, "Aspect ratio r_e = b/a, eq. (2).");
pub const LINEAR_DISTANCE: Metric = Metric::new(
    "linear_distance_mm",
    "d",
    "mm",
    2,
    |m| m.linear_distance_mm,
    "Linear distance d along each wall (section 3, linear-elliptical path).",
);
pub const STEP: Metric = Metric::new("step_mm", "s", "mm", 3, |m| m.step_mm, "Trochoidal step s: advance per cycle.");
pub const CYCLES: Metric = Metric::new(
    "cycles",
    "cycles",
    "",
    0,
    |m| m.cycles as f64,
    "Number of cycles from outside the stock to beyond the slot end.",
)
.whole();
pub const PATH_LENGTH: Metric =
    Metric::new("path_length_mm", "path length", "mm", 1, |m| m.path_length_mm, "Whole tool-centre path length.");
pub const MACHINING_TIME: Metric = Metric::new(
    "machining_time_s",
    "machining time",
    "s",
    1,
    |m| m.machining_time_s,
    "Whole path at the feed rate f_r.",
);
pub const TEETH_PER_CYCLE: Metric = Metric::new(
    "teeth_per_cycle",
    "teeth per cycle",
    "",
    1,
    |m| m.teeth_per_cycle,
    "Tooth positions per cycle: cycle length / f_z.",
);
pub const STEP_LIMIT_46DEG: Metric = Metric::new(
    "step_limit_46deg_mm",
    "step for 46°",
    "mm",
    3,
    |m| m.step_limit_46deg_mm,
    "Largest step keeping the engagement ≤ 46° (two-circle model, Wu et al. 2016 eqs. 2–6).",
);
pub const STEP_LIMIT_15PCT_DEPTH: Metric = Metric::new(
    "step_limit_15pct_depth_mm",
    "step for 15 % D",
    "mm",
    3,
    |m| m.step_limit_15pct_depth_mm,
    "Largest step for a straight-cut-equivalent depth of 15 % of D (Grechishnikov et al. 2017).",
);

pub const FORCE_RESULTANT_MAX: Metric = Metric::new(
    "force_resultant_max_n",
    "F_R,max",
    "N",
    1,
    |m| m.force_resultant_max_n,
    "Largest resultant cutting force F_R = sqrt(Fx² + Fy² + Fz²) over a steady-state cycle: linear \
     edge-force model with helix, dF_t,r,a = (K_t,r,a c·h + K_t,r,a e)·dz per tooth and slice (Altintas & \
     Lee 1996), h(φ) from the material left by previous cycles (Figs. 14–16).",
)
.lower_is_better();
pub const FORCE_RESULTANT_MEAN: Metric = Metric::new(
    "force_resultant_mean_n",
    "mean F_R",
    "N",
    1,
    |m| m.force_resultant_mean_n,
    "Mean resultant force over the part of the cycle in which the tool cuts (the dashed line of Fig. 15).",
)
.lower_is_better();
pub const T_FORCE_MAX_SHARE: Metric = Metric::new(
    "t_force_max_share",
    "t(F_R,max)/t_cycle",
    "",
    3,
    |m| m.t_force_max_share,
    "Time from the start of cutting to F_R,max as a share of the cycle time (section 5.1: 9.7 % for \
     r_e = 0.8, 16 % for the circular path, each 5–6 % of the cycle before h_max).",
);
pub const FORCE_XY_MAX: Metric = Metric::new(
    "force_xy_max_n",
    "|Fxy|max",
    "N",
    1,
    |m| m.force_xy_max_n,
    "Largest force in the XY plane sqrt(Fx² + Fy²): what bends the tool.",
)
.lower_is_better();
pub const TORQUE_MAX: Metric = Metric::new(
    "torque_max_nm",
    "T_max",
    "N·m",
    2,
    |m| m.torque_max_nm,
    "Largest spindle torque T = Σ dF_t·R over the cycle.",
)
.lower_is_better();
pub const TORQUE_MEAN: Metric =
    Metric::new("torque_mean_nm", "mean T", "N·m", 2, |m| m.torque_mean_nm, "Mean spindle torque while the tool cuts.");
pub const POWER_MAX: Metric =
    Metric::new("power_max_w", "P_max", "W", 0, |m| m.power_max_w, "Largest cutting power P = T·Ω = T·2πn/60.")
        .lower_is_better();
pub const FORCE_RESULTANT_MAX_PROGRAMMED: Metric = Metric::new(
    "force_resultant_max_programmed_n",
    "F_R,max at f_r",
    "N",
    1,
    |m| m.force_resultant_max_programmed_n,
    "F_R,max at the programmed feed everywhere (the forces above are at the feed the machine reaches).",
);
pub const TORQUE_MAX_PROGRAMMED: Metric = Metric::new(
    "torque_max_programmed_nm",
    "T_max at f_r",
    "N·m",
    2,
    |m| m.torque_max_programmed_nm,
    "Largest spindle torque at the programmed feed everywhere.",
);
pub const POWER_MAX_PROGRAMMED: Metric = Metric::new(
    "power_max_programmed_w",
    "P_max at f_r",
    "W",
    0,
    |m| m.power_max_programmed_w,
    "Largest cutting power at the programmed feed everywhere.",
);
pub const POWER_MEAN: Metric =
    Metric::new("power_mean_w", "mean P", "W", 0, |m| m.power_mean_w, "Mean cutting power while the tool cuts.");
pub const PERFORMANCE_INDEX: Metric = Metric::new(
    "performance_index",
    "PI",
    "",
    3,
    |m| m.performance_index.unwrap_or(f64::NAN),
    "Performance index PI = MRR / (F_R,max · Ra,max · W_max), eq. (7) (mm³/min, N, µm, µm; W_max = \
     max(W_l, W_r)). Needs the measured Ra,max (ra-um); compare PI only within one unit system.",
)
.higher_is_better();
pub const PERFORMANCE_INDEX_WITHOUT_RA: Metric = Metric::new(
    "performance_index_without_ra",
    "PI without Ra",
    "",
    3,
    |m| m.performance_index_without_ra,
    "Eq. (7) without Ra: MRR / (F_R,max · W_max) (mm³/min, N, µm) ranks paths by the predictable part; \
     Ra,max is not predicted (it depends on the tool's wear, the machine and the chatter).",
)
.higher_is_better();
pub const IMPRINT_DENSITY_MEAN: Metric = Metric::new(
    "imprint_density_mean_per_mm",
    "imprints (mean)",
    "1/mm",
    1,
    |m| m.imprint_density_mean_per_mm,
    "Mean density of cutting-edge imprints on the slot bottom: crossings of the edge circles (one every \
     f_z along the path) with a line x = X, per mm of y, averaged across the slot (Figs. 21–22).",
)
.higher_is_better();
pub const IMPRINT_DENSITY_PEAK: Metric = Metric::new(
    "imprint_density_peak_per_mm",
    "imprints (peak)",
    "1/mm",
    1,
    |m| m.imprint_density_peak_per_mm,
    "Largest imprint density across the slot bottom (Fig. 22: highest mid-slot).",
);

pub const T_CYCLE_REAL: Metric = Metric::new(
    "t_cycle_real_s",
    "t_cycle real",
    "s",
    3,
    |m| m.t_cycle_real_s,
    "Steady-state cycle time on the job's machine: feed planned with its acceleration, jerk and \
     curvature limits (LinuxCNC v ≤ √(0.866·a·R)); = t_cycle without a machine.",
)
.lower_is_better();
pub const MACHINING_TIME_REAL: Metric = Metric::new(
    "machining_time_real_s",
    "machining time real",
    "s",
    1,
    |m| m.machining_time_real_s,
    "Whole path on the job's machine, from rest to rest.",
)
.lower_is_better();
pub const MRR_REAL: Metric = Metric::new(
    "mrr_real_mm3_per_min",
    "MRR real",
    "mm³/min",
    0,
    |m| m.mrr_real_mm3_per_min,
    "MRR = B·s·a_p / t_cycle real: the removal rate the machine achieves.",
)
.higher_is_better();
pub const FEED_HELD_SHARE: Metric = Metric::new(
    "feed_held_share",
    "feed held",
    "",
    3,
    |m| m.feed_held_share,
    "Share of the steady-state cycle's time at the programmed feed (1 = held everywhere).",
)
.higher_is_better();

/// Every numeric metric of [`Metrics`] (all its fields but the path kind), in field order.
pub const METRICS: [&Metric; 41] = [
    &CYCLE_LENGTH,
    &T_CYCLE,
    &MRR,
    &F_Z,
    &H_MAX,
    &H_MAX_PROGRAMMED,
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
    &FORCE_RESULTANT_MAX,
    &FORCE_RESULTANT_MEAN,
    &T_FORCE_MAX_SHARE,
    &FORCE_XY_MAX,
    &TORQUE_MAX,
    &TORQUE_MEAN,
    &POWER_MAX,
    &POWER_MEAN,
    &FORCE_RESULTANT_MAX_PROGRAMMED,
    &TORQUE_MAX_PROGRAMMED,
    &POWER_MAX_PROGRAMMED,
    &PERFORMANCE_INDEX,
    &PERFORMANCE_INDEX_WITHOUT_RA,
    &IMPRINT_DENSITY_MEAN,
    &IMPRINT_DENSITY_PEAK,
    &T_CYCLE_REAL,
    &MACHINING_TIME_REAL,
    &MRR_REAL,
    &FEED_HELD_SHARE,
];

/// The process results of a steady-state cycle (section 5: forces, eq. 7, Figs. 21–22).
pub const PROCESS_RESULTS: [&Metric; 6] = [
    &FORCE_RESULTANT_MAX,
    &FORCE_RESULTANT_MEAN,
    &T_FORCE_MAX_SHARE,
    &PERFORMANCE_INDEX,
    &PERFORMANCE_INDEX_WITHOUT_RA,
    &IMPRINT_DENSITY_MEAN,
];

/// The results of a steady-state cycle the paper compares paths by (Table 2, Figs. 5, 9):
/// cycle length and time, MRR, chip thickness and its timing, engagement, wall waviness.
pub const CYCLE_RESULTS: [&Metric; 9] =
    [&CYCLE_LENGTH, &T_CYCLE, &MRR, &H_MAX, &T_HMAX, &T_COOLING, &ENGAGEMENT_MAX, &WAVINESS_LEFT, &WAVINESS_RIGHT];

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
    /// A column.
    pub const fn new(
        key: &'static str,
        symbol: &'static str,
        unit: &'static str,
        decimals: usize,
        value: fn(&ToothSample) -> f64,
        about: &'static str,
    ) -> SeriesColumn {
        SeriesColumn { key, symbol, unit, about, decimals, value }
    }

    /// The value for `t`.
    pub fn of(&self, t: &ToothSample) -> f64 {
        (self.value)(t)
    }

    /// The value for `t` as the CSV writes it.
    pub fn csv(&self, t: &ToothSample) -> String {
        format!("{:.*}", self.decimals, self.of(t))
    }
}

pub const TIME: SeriesColumn =
    SeriesColumn::new("time_s", "t", "s", 6, |t| t.time_s, "Time from the start of the cycle.");
pub const H: SeriesColumn = SeriesColumn::new(
    "h_mm",
    "h",
    "mm",
    7,
    |t| t.h_mm,
    "Local maximum chip thickness of the tooth, eqs. (3)–(6), Fig. 6.",
);
pub const ENGAGEMENT: SeriesColumn = SeriesColumn::new(
    "engagement_deg",
    "engagement",
    "°",
    4,
    |t| t.engagement_rad.to_degrees(),
    "Engagement angle: angular extent of the tool edge in uncut material.",
);
pub const CUTTING: SeriesColumn = SeriesColumn::new(
    "cutting",
    "cutting",
    "",
    0,
    |t| f64::from(u8::from(t.cutting)),
    "1 if the tooth removes material (h above the numeric noise floor), else 0.",
);
pub const S: SeriesColumn =
    SeriesColumn::new("s_mm", "s", "mm", 6, |t| t.s_mm, "Arc length from the start of the cycle.");
pub const X: SeriesColumn =
    SeriesColumn::new("x_mm", "x", "mm", 6, |t| t.x_mm, "Tool centre x, cycle origin at (0, 0).");
pub const Y: SeriesColumn =
    SeriesColumn::new("y_mm", "y", "mm", 6, |t| t.y_mm, "Tool centre y, cycle origin at (0, 0).");

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
        assert_eq!(fields.len(), METRICS.len() + 2, "every field but `path` and `direction` has an entry");
        for q in METRICS {
            let v = fields.get(q.key).and_then(serde_json::Value::as_f64);
            // A metric without a value (PI without Ra,max) is NaN in the table, null in JSON.
            let want = Some(q.of(&m)).filter(|x| !x.is_nan());
            assert!(fields.contains_key(q.key), "{}", q.key);
            assert_eq!(v, want, "{}", q.key);
            assert_eq!(q.whole, fields[q.key].is_u64(), "{}", q.key);
        }
    }

    #[test]
    fn display_and_heading_follow_the_unit() {
        let m = plan(&Job::default()).expect("plan").metrics;
        assert_eq!(F_Z.display(&m), "0.0750 mm");
        // 3180.1 s = 53 min 0.1 s: 0 h, 53 min, 0 s after rounding; 3600 s + 61 s = 1:01:01
        assert_eq!(seconds_with_clock(3180.1, 1), "3180.1 s (0:53:00)");
        assert_eq!(clock(3661.0), "1:01:01");
        assert_eq!(clock(59.6), "0:01:00", "rounded to the whole second");
        assert_eq!(seconds_with_clock(12.5, 1), "12.5 s", "under a minute: seconds only");
        assert_eq!(clock(f64::NAN), "—");
        assert_eq!(CYCLES.display(&m), m.cycles.to_string());
        assert!(ENGAGEMENT_MAX.display(&m).ends_with('°'));
        assert_eq!(MRR.heading(), "MRR [mm³/min]");
        assert_eq!(ASPECT_RATIO.heading(), "r_e");
        assert_eq!(PERFORMANCE_INDEX.display(&m), "— (no value)", "no Ra,max in the default job");
    }
}
