//! Derived values of the current plan, always visible.

use eframe::egui::{self, Color32, RichText};
use trochoplan_core::Plan;
use trochoplan_core::quantity::{self, Metric};

/// The derived values shown, in order: feed and path shape, the core's cycle results, its
/// process results (forces, PI, imprints), step limits and the whole job.
pub fn shown() -> impl Iterator<Item = &'static Metric> {
    let shape = [&quantity::F_Z, &quantity::A, &quantity::B];
    let whole_job = [
        &quantity::STEP_LIMIT_46DEG,
        &quantity::STEP_LIMIT_15PCT_DEPTH,
        &quantity::CYCLES,
        &quantity::PATH_LENGTH,
        &quantity::MACHINING_TIME,
    ];
    shape.into_iter().chain(quantity::CYCLE_RESULTS).chain(quantity::PROCESS_RESULTS).chain(whole_job)
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
        for q in shown() {
            ui.label(q.symbol).on_hover_text(q.about);
            let mut text = RichText::new(q.display(m)).monospace();
            if q.key == quantity::ENGAGEMENT_MAX.key && q.of(m) > trochoplan_core::plan::ENGAGEMENT_LIMIT_DEG {
                text = text.color(Color32::from_rgb(210, 40, 40));
            }
            ui.label(text).on_hover_text(q.about);
            ui.end_row();
        }
    });
}
