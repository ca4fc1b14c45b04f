//! Derived values of the current plan, always visible.

use eframe::egui::{self, Color32, RichText};
use trochoplan_core::Plan;
use trochoplan_core::quantity::{self, Metric};
use trochoplan_core::slot_levels::LevelPlan;
use trochoplan_core::warnings::{Check, Severity, Warning};

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
    let warnings = trochoplan_core::warnings::warnings(plan);
    egui::Grid::new("metrics_grid").num_columns(2).striped(true).spacing([10.0, 3.0]).show(ui, |ui| {
        for q in shown() {
            ui.label(q.symbol).on_hover_text(q.about);
            let text = RichText::new(q.display(m)).monospace();
            match warnings.iter().find(|w| metric_of(w.check).key == q.key) {
                Some(w) => ui.label(text.color(color(w.severity))).on_hover_text(format!("{}\n\n{}", q.about, w.text)),
                None => ui.label(text).on_hover_text(q.about),
            };
            ui.end_row();
        }
    });
    limits(ui, &warnings);
}

/// Colour of a value above a recommendation from the literature.
pub const ADVICE_COLOR: Color32 = Color32::from_rgb(200, 120, 0);

/// The colour of a value beyond a limit of `severity`.
pub fn color(severity: Severity) -> Color32 {
    match severity {
        Severity::Advice => ADVICE_COLOR,
        Severity::Limit => super::params::ERROR_COLOR,
    }
}

/// The derived value a check is about.
fn metric_of(check: Check) -> &'static Metric {
    match check {
        Check::Engagement => &quantity::ENGAGEMENT_MAX,
        Check::Rubbing => &quantity::H_MAX,
        Check::SpindlePower => &quantity::POWER_MAX,
        Check::SpindleTorque => &quantity::TORQUE_MAX,
    }
}

/// What the colours mean.
const COLOURS_TIP: &str = "Orange: above a recommendation from the literature (the job runs, at a cost \
    the message names). Red: above a limit of the tool or the machine (the job will not run as \
    planned). The limits: engagement 46° (Grechishnikov et al. 2017, recommended); the thinnest \
    chip a carbide end mill cuts rather than rubs, 0.02 mm (a typical radius of its cutting edge; \
    chips of the order of the edge radius are ploughed: Son, Lim & Ahn 2005; Liu, DeVor & Kapoor \
    2006); the spindle power and torque of the job's machine.";

/// The limits the plan exceeds, each in its colour, and what the colours mean.
fn limits(ui: &mut egui::Ui, warnings: &[Warning]) {
    ui.add_space(4.0);
    ui.label(RichText::new("Limits").strong()).on_hover_text(COLOURS_TIP);
    if warnings.is_empty() {
        ui.label("No limit exceeded.").on_hover_text(COLOURS_TIP);
    }
    for w in warnings {
        ui.add(egui::Label::new(RichText::new(&w.text).color(color(w.severity))).wrap()).on_hover_text(COLOURS_TIP);
    }
}

/// Largest excess of the levels' measured peak over the steady-state engagement (°) before it
/// is flagged (the same margin as `trochoplan analyze`'s warning).
const LEVELS_MARGIN_DEG: f64 = 1.0;

/// The slot's levels: their count and depth, where the tool centre runs, the engagement
/// measured over every move of every level against the steady-state target, the whole path.
pub fn show_levels(ui: &mut egui::Ui, plan: &Plan, levels: &Result<LevelPlan, String>) {
    ui.add_space(6.0);
    ui.heading("Levels");
    let lp = match levels {
        Ok(lp) => lp,
        Err(e) => {
            ui.colored_label(super::params::ERROR_COLOR, format!("No levels: {e}"));
            return;
        }
    };
    let target = plan.metrics.engagement_max_deg;
    let peak = lp.peak_rad().to_degrees();
    let length = lp.length_mm();
    let time = length / plan.job.feed * 60.0;
    let ends = if lp.closed.is_some() { "closed (helix entry)" } else { "open (entry outside the stock)" };
    let rows: [(&str, String, &str); 6] = [
        (
            "Levels",
            format!("{} × {:.3} mm", lp.levels.count(), lp.levels.axial_depth_mm),
            "Equal levels: their count and the depth of each.",
        ),
        (
            "Slot ends",
            ends.to_owned(),
            "Closed: both ends are walls, each level entered by a helix inside the slot. Open: each level starts outside the stock.",
        ),
        (
            "Tool centre Y",
            format!("{:.3} to {:.3} mm", lp.centre_y_mm.0, lp.centre_y_mm.1),
            "Lowest and highest Y of the tool centre. Closed: D/2 from both end walls. Open: from before Y0, \
             where the tool is off the stock, to past the slot length, where the whole width is cut.",
        ),
        (
            "Engagement peak, every move",
            format!("{peak:.2}° (target {target:.2}°)"),
            "Largest engagement measured over every move of every level (entry, loops, link, end) \
             against the steady-state loop's engagement; flagged red above the target + 1°.",
        ),
        ("Path length, all levels", format!("{length:.1} mm"), "Every level's moves and helical descents."),
        ("Machining time, all levels", quantity::seconds_with_clock(time, 1), "Path length of all levels at the feed."),
    ];
    egui::Grid::new("levels_grid").num_columns(2).striped(true).spacing([10.0, 3.0]).show(ui, |ui| {
        for (i, (name, value, about)) in rows.into_iter().enumerate() {
            ui.label(name).on_hover_text(about);
            let mut text = RichText::new(value).monospace();
            if i == 3 && peak > target + LEVELS_MARGIN_DEG {
                text = text.color(super::params::ERROR_COLOR);
            }
            ui.label(text).on_hover_text(about);
            ui.end_row();
        }
    });
    if peak > target + LEVELS_MARGIN_DEG {
        ui.colored_label(
            super::params::ERROR_COLOR,
            format!(
                "The moves of the levels engage up to {peak:.1}°, more than the steady-state loop's {target:.1}° + 1°: \
                 the entry or the first or last loops of this path type cut more than a loop."
            ),
        );
    }
}
