//! The Pocket tab: a whole polygonal pocket planned by the core (`pocket::plan`, as
//! `trochoplan pocket`): adaptive clearing, or contour-parallel rings with a corner method at
//! every ring corner, or circles along the medial axis. The outline is edited as text or read
//! from a drawing (`Command::OpenOutline`); the path is drawn with equal axes beside its
//! numbers ([`super::pocket_numbers`]), the NC program read back over it
//! ([`super::pocket_plot`]), and the NC export ([`super::corner_nc`]) writes the program of
//! the shown plan. The inputs and their fields are in [`super::pocket_inputs`].
//!
//! Planning takes 0.1–1 s, so the window plans on a [`Worker`] thread
//! ([`PocketView::threaded`]; the newest request wins); the tests plan inline
//! ([`PocketView::default`]).

use super::Command;
use super::corner_nc::{self, NcExport};
use super::label;
use super::params::ERROR_COLOR;
use super::plane::{MAX_PATH_POINTS, segment_points};
use super::pocket_inputs::{input_rows, tool_row};
use crate::worker::{Keep, Latest, Task, Worker};
use eframe::egui::{self, RichText};
use std::sync::Arc;
use trochoplan_core::machine::{CutHeights, ProgramTime, toolpath_time};
use trochoplan_core::pocket::{self, PocketPlan, PocketStrategy};
use trochoplan_core::report::{self, PocketReport};
use trochoplan_core::verify::plan_chip::{ChipPeaks, chip_peaks};

pub use super::pocket_inputs::PocketInputs;

/// A planned pocket converted for drawing; its numbers are those of the core's report (what
/// `trochoplan pocket` prints), with the real time and the chip peaks its `--machine` adds.
#[derive(Clone, Debug)]
pub struct PocketResult {
    pub boundary: Vec<[f64; 2]>,
    /// The islands' outlines, closed, for drawing.
    pub islands: Vec<Vec<[f64; 2]>>,
    /// The whole tool path at depth, as points for drawing.
    pub path: Vec<[f64; 2]>,
    /// The core's report of the plan (length, time, engagement, rows).
    pub report: PocketReport,
    /// The plan itself (for the NC program).
    pub plan: PocketPlan,
    /// The machine's name and the real time of the program on it; `None` without a machine.
    pub real_time: Option<(String, Result<ProgramTime, String>)>,
    /// The largest chip at the peaks of the moves (at the reached feed with a machine).
    pub chip: Result<ChipPeaks, String>,
}

/// Plan the pocket as `trochoplan pocket` does (`pocket::plan`, `report::pocket`, with
/// `--machine` the real time and the chip at the reached feed), converted for drawing.
pub fn compute(i: &PocketInputs) -> Result<PocketResult, String> {
    let req = i.request()?;
    let plan = pocket::plan(&req).map_err(|e| e.to_string())?;
    let report = report::pocket(&req, &plan).map_err(|e| e.to_string())?;
    let closed = |poly: &trochoplan_core::geom::Polygon| {
        let mut v: Vec<[f64; 2]> = poly.vertices().iter().map(|v| [v.x, v.y]).collect();
        if let Some(&first) = v.first() {
            v.push(first);
        }
        v
    };
    let boundary = closed(plan.polygon());
    let islands = req.islands.iter().map(closed).collect();
    let path = segment_points(&plan.path().segments(), MAX_PATH_POINTS);
    let heights = CutHeights { depth_mm: i.depth_mm, safe_z_mm: i.safe_z_mm };
    let machine = i.machine()?;
    let real_time = machine.as_ref().map(|m| {
        let t = toolpath_time(plan.toolpath(), heights, i.feed_mm_per_min, m).map_err(|e| e.to_string());
        (m.name.clone(), t)
    });
    let chip = chip_peaks(plan.path(), i.teeth, i.spindle_rpm, machine.as_ref().map(|m| (m, heights)))
        .map_err(|e| e.to_string());
    Ok(PocketResult { boundary, islands, path, report, plan, real_time, chip })
}

/// Plan `inputs`.
fn plan_job(inputs: PocketInputs, task: &Task<Result<Arc<PocketResult>, String>>) {
    task.send(compute(&inputs).map(Arc::new));
}

/// The last pocket, its error, and the worker computing it: plans inline or on its own
/// thread; an answer overtaken by a newer request is still shown if it is newer than the one
/// on screen ([`Keep::Newer`]).
pub type PocketView = Latest<PocketInputs, PocketResult>;

impl Default for PocketView {
    /// A view planning inline (the tests).
    fn default() -> Self {
        Latest::new(Worker::inline(Keep::Newer, plan_job))
    }
}

impl PocketView {
    /// A view planning on its own thread; `repaint` is called when an answer is ready.
    pub fn threaded(repaint: impl Fn() + Send + Sync + 'static) -> PocketView {
        Latest::new(Worker::threaded("pocket", Keep::Newer, plan_job, repaint))
    }
}

/// The Pocket tab: the job's tool, the method and the pocket's inputs; the outline editor
/// beside the path and its numbers; the program beside the path when the NC export is open.
pub fn show(ui: &mut egui::Ui, inputs: &mut PocketInputs, view: &PocketView, nc: &mut NcExport) -> Option<Command> {
    // the program's depth and retract height are the pocket's (the export's depth field and
    // the pocket's edit one depth)
    inputs.depth_mm = nc.settings.depth_mm;
    inputs.safe_z_mm = nc.settings.frame.retract_height_mm();
    ui.horizontal_wrapped(|ui| tool_row(ui, inputs));
    ui.horizontal_wrapped(|ui| {
        strategy_buttons(ui, &mut inputs.strategy);
        ui.separator();
        ui.toggle_value(&mut nc.settings.open, label::NC_EXPORT)
            .on_hover_text("Options, preview and save of the NC program of the pocket");
        ui.toggle_value(&mut inputs.show_program, super::pocket_plot::SHOW_PROGRAM).on_hover_text(
            "Draw the NC program of the shown plan, read back block by block, over the planned path: \
             what the machine will run, not only the plan.",
        );
    });
    strategy_note(ui, inputs.strategy, view);
    input_rows(ui, inputs);
    // the pocket's depth is the program's; the export's depth field edits it too
    nc.settings.depth_mm = inputs.depth_mm;
    status(ui, view);
    let cmd = if nc.settings.open {
        ui.separator();
        let cmd = corner_nc::options(ui, nc.settings, nc.cache, view.error.is_some(), Command::ExportPocketNc);
        ui.separator();
        cmd
    } else {
        None
    };
    inputs.depth_mm = nc.settings.depth_mm;
    let h = (ui.available_height() - 10.0).max(220.0);
    let mut open = false;
    ui.horizontal_top(|ui| {
        ui.vertical(|ui| {
            ui.set_width(300.0);
            polygon_editor(ui, inputs);
            if ui
                .button(label::POCKET_OPEN_OUTLINE)
                .on_hover_text("A DXF or SVG drawing, or an x,y point list")
                .clicked()
            {
                open = true;
            }
            if let Some(r) = view.last.as_deref() {
                ui.add_space(6.0);
                super::pocket_numbers::numbers(ui, r, inputs);
            }
        });
        if let Some(r) = view.last.as_deref() {
            super::pocket_plot::view(ui, r, inputs.show_program, nc, h);
        }
    });
    if open { Some(Command::OpenOutline) } else { cmd }
}

/// One button per strategy of the core ([`PocketStrategy::ALL`]), the chosen one selected.
fn strategy_buttons(ui: &mut egui::Ui, strategy: &mut PocketStrategy) {
    ui.label("Method");
    for s in PocketStrategy::ALL {
        if ui.selectable_label(*strategy == s, s.label()).on_hover_text(s.help()).clicked() {
            *strategy = s;
        }
    }
}

/// When the plan on screen is not of the chosen method: why (adaptive clearing plans a pocket
/// its helix does not fit as a trochoidal slot; or the new plan is still being made).
fn strategy_note(ui: &mut egui::Ui, chosen: PocketStrategy, view: &PocketView) {
    let Some(r) = view.last.as_deref() else { return };
    let planned = r.plan.strategy();
    if planned == chosen {
        return;
    }
    let text = if view.pending() {
        format!("Shown: the last plan ({}) until the {} plan is ready.", planned.label(), chosen.label())
    } else if view.error.is_some() {
        format!("Shown: the last valid plan ({}); the inputs are invalid.", planned.label())
    } else {
        format!(
            "Planned as {}: {} chose it because its helix does not fit this pocket.",
            planned.label(),
            chosen.label()
        )
    };
    ui.label(RichText::new(text).italics());
}

/// The core's message when the inputs are invalid, and a spinner with the time spent while a
/// plan is being made (it moves until the result shows).
fn status(ui: &mut egui::Ui, view: &PocketView) {
    // always the same number of widgets, so that the fields below keep their ids
    let id = egui::Id::NULL.with("pocket_planning_since");
    let now = ui.input(|i| i.time);
    ui.horizontal(|ui| {
        if view.pending() {
            let since = ui.data_mut(|d| *d.get_temp_mut_or_insert_with(id, || now));
            ui.spinner();
            ui.label(format!("planning… {:.1} s", now - since));
            ui.ctx().request_repaint_after(std::time::Duration::from_millis(100));
        } else {
            ui.data_mut(|d| d.remove::<f64>(id));
        }
        if let Some(e) = view.error.as_deref() {
            ui.add(egui::Label::new(RichText::new(format!("invalid: {e}")).color(ERROR_COLOR)).wrap());
        }
    });
}

/// The pocket's vertices as editable text. Its id is fixed, so that what is typed keeps the
/// focus and the cursor however the lines above it change.
fn polygon_editor(ui: &mut egui::Ui, inputs: &mut PocketInputs) {
    let l = ui.label(label::POCKET_VERTICES);
    ui.add(
        egui::TextEdit::multiline(&mut inputs.polygon_text)
            .id_salt("pocket_vertices")
            .desired_rows(8)
            .desired_width(f32::INFINITY)
            .code_editor(),
    )
    .labelled_by(l.id)
    .on_hover_text("A simple polygon, lines only, one vertex \"x,y\" (mm) per line; '#' comments allowed.");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn threaded_view_delivers_the_newest_inputs() {
        let mut v = PocketView::threaded(|| {});
        let mut i = PocketInputs {
            strategy: PocketStrategy::Rings(trochoplan_core::corner::CornerMethod::Variable),
            ..PocketInputs::default()
        };
        v.update(&i);
        i.step_over_mm = 3.0;
        v.update(&i);
        v.settle(&i, 60);
        assert!(!v.pending(), "answered within 60 s");
        let want = compute(&i).expect("the core plans the same inputs");
        let got = v.last.as_ref().expect("a result");
        assert_eq!(got.report, want.report);
        assert_eq!(got.path, want.path);
    }

    /// The strategy row: one button per strategy of the core, only the chosen one selected.
    #[test]
    fn only_the_chosen_strategy_is_shown_selected() {
        for chosen in PocketStrategy::ALL {
            let mut strategy = chosen;
            let mut h = egui_kittest::Harness::new_ui(move |ui| strategy_buttons(ui, &mut strategy));
            h.run();
            use egui_kittest::kittest::{NodeT, Queryable};
            for s in PocketStrategy::ALL {
                let on = h.get_by_label(s.label()).accesskit_node().toggled() == Some(egui::accesskit::Toggled::True);
                assert_eq!(on, s == chosen, "{} shown {on} while {} is chosen", s.label(), chosen.label());
            }
        }
    }
}
