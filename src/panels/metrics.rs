//! Derived values of the current plan, always visible.

use eframe::egui::{self, Color32, RichText};
use trochoplan_core::{Metrics, Plan};

/// One derived quantity: symbol, formatted value with unit, tooltip (definition and source).
pub struct Row {
    pub symbol: &'static str,
    pub value: String,
    pub tooltip: &'static str,
}

/// The rows shown for a plan (also used by the compare table).
pub fn rows(m: &Metrics) -> Vec<Row> {
    let r = |symbol, value: String, tooltip| Row { symbol, value, tooltip };
    vec![
        r("f_z", format!("{:.4} mm", m.f_z_mm), "Feed per tooth f_z = f_r/(n·z)."),
        r("a", format!("{:.3} mm", m.a_mm), "Trochoidal radius a = (B − D)/2 (major semi-axis)."),
        r("b", format!("{:.3} mm", m.b_mm), "b = r_e·a, eq. (2) (minor semi-axis along the slot)."),
        r("cycle length", format!("{:.3} mm", m.cycle_length_mm), "Path length of one cycle (Fig. 5)."),
        r("t_cycle", format!("{:.3} s", m.t_cycle_s), "t_cycle = cycle length / f_r (Table 2)."),
        r("MRR", format!("{:.0} mm³/min", m.mrr_mm3_per_min), "MRR = B·s·a_p / t_cycle (Table 2)."),
        r(
            "h_max",
            format!("{:.4} mm", m.h_max_mm),
            "Largest local maximum chip thickness over a steady-state cycle, eqs. (3)–(6) (Table 2).",
        ),
        r("t_hmax", format!("{:.3} s", m.t_hmax_s), "Time from the start of cutting to h_max (Table 2)."),
        r("t_cooling", format!("{:.3} s", m.t_cooling_s), "Time per cycle in which no tooth cuts (Table 2)."),
        r(
            "max engagement",
            format!("{:.1}°", m.engagement_max_deg),
            "Largest engagement angle; recommended ≤ 46° (Grechishnikov et al. 2017).",
        ),
        r(
            "W_l",
            format!("{:.4} mm", m.waviness_left_mm),
            "Left (−x) wall waviness, peak to valley (section 2.3, Fig. 9).",
        ),
        r(
            "W_r",
            format!("{:.4} mm", m.waviness_right_mm),
            "Right (+x) wall waviness, peak to valley (section 2.3, Fig. 9).",
        ),
        r(
            "step for 46°",
            format!("{:.3} mm", m.step_limit_46deg_mm),
            "Largest step keeping the engagement ≤ 46° (two-circle model, Wu et al. 2016 eqs. 2–6).",
        ),
        r(
            "step for 15 % D",
            format!("{:.3} mm", m.step_limit_15pct_depth_mm),
            "Largest step for a straight-cut-equivalent depth of 15 % of D (Grechishnikov et al. 2017).",
        ),
        r("cycles", format!("{}", m.cycles), "Number of cycles from outside the stock to beyond the slot end."),
        r("path length", format!("{:.1} mm", m.path_length_mm), "Whole tool-centre path length."),
        r("machining time", format!("{:.1} s", m.machining_time_s), "Whole path at the feed rate f_r."),
    ]
}

/// Draw the derived values of `plan`; `stale` when the current job is invalid and the values
/// belong to the last valid job.
pub fn show(ui: &mut egui::Ui, plan: Option<&Plan>, stale: bool) {
    ui.heading("Derived values");
    let Some(plan) = plan else {
        ui.label("No valid job yet.");
        return;
    };
    if stale {
        ui.colored_label(Color32::from_rgb(200, 120, 0), "Job invalid: showing the last valid plan.");
    }
    let m = &plan.metrics;
    egui::Grid::new("metrics_grid").num_columns(2).striped(true).spacing([10.0, 3.0]).show(ui, |ui| {
        for row in rows(m) {
            ui.label(row.symbol).on_hover_text(row.tooltip);
            let mut text = RichText::new(&row.value).monospace();
            if row.symbol == "max engagement" && m.engagement_max_deg > trochoplan_core::plan::ENGAGEMENT_LIMIT_DEG {
                text = text.color(Color32::from_rgb(210, 40, 40));
            }
            ui.label(text).on_hover_text(row.tooltip);
            ui.end_row();
        }
    });
}
