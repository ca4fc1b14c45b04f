//! The Pocket tab: a whole polygonal pocket planned by the core (`pocket::plan`, as
//! `trochoplan pocket`): adaptive clearing, or contour-parallel rings with a corner method at
//! every ring corner, or circles along the medial axis. The outline is edited as text or read
//! from a drawing (`Command::OpenOutline`); the rings are drawn with equal axes beside their
//! numbers, and the NC export ([`super::corner_nc`]) writes the program of the shown plan.
//!
//! Planning takes 0.1–1 s, so the window plans on a [`Worker`] thread
//! ([`PocketView::threaded`]; the newest request wins); the tests plan inline
//! ([`PocketView::default`]).

use super::Command;
use super::corner_nc::{self, CornerNcCache, NcExport};
use super::label;
use super::plane::{self, MAX_PATH_POINTS, STRATEGY_COLOR, line, plane_plot, segment_points};
use crate::worker::{Keep, Latest, Task, Worker};
use eframe::egui::{self, Color32, DragValue};
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use trochoplan_core::geom::Polygon;
use trochoplan_core::pocket::{self, PocketPlan, PocketRequest, PocketStrategy};
use trochoplan_core::report::{self, PocketReport};

/// Inputs of the Pocket tab, persisted with the app state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct PocketInputs {
    /// Pocket boundary, one vertex "x,y" per line.
    pub polygon_text: String,
    /// Tool diameter D (mm).
    pub tool_diameter_mm: f64,
    /// Ring step-over a_e (mm).
    pub step_over_mm: f64,
    /// How the pocket is cleared (`--method`).
    pub strategy: PocketStrategy,
    /// The pocket's open edges, "i, j, …" (`--open-edges`: edge i from vertex i to i + 1).
    pub open_edges: String,
    /// The job's feed f_r (mm/min), spindle speed (rpm) and teeth (copies taken each frame):
    /// the pocket is paced and its program written at them.
    #[serde(skip)]
    pub feed_mm_per_min: f64,
    #[serde(skip)]
    pub spindle_rpm: f64,
    #[serde(skip)]
    pub teeth: u32,
}

impl Default for PocketInputs {
    /// The defaults of `trochoplan pocket`: the README's rectangle, adaptive clearing.
    fn default() -> Self {
        let pocket = PocketRequest::default();
        PocketInputs {
            polygon_text: crate::shared::outline::points_text(pocket.polygon.vertices()),
            tool_diameter_mm: pocket.tool_diameter_mm,
            step_over_mm: pocket.step_over_mm,
            strategy: pocket.strategy,
            open_edges: String::new(),
            feed_mm_per_min: pocket.feed_mm_per_min,
            spindle_rpm: pocket.pace.rpm,
            teeth: pocket.pace.teeth,
        }
    }
}

impl PocketInputs {
    /// The core's pocket request of the tab's inputs: the polygon text read and validated, the
    /// method as a whole-pocket strategy (or adaptive clearing), the other inputs as
    /// `trochoplan pocket`'s defaults.
    pub fn request(&self) -> Result<PocketRequest, String> {
        // read as a point-list outline: loops separated by an empty line are an error naming
        // them, never joined into one polygon
        let pockets = trochoplan_core::outline::read("polygon", &self.polygon_text).map_err(|e| e.to_string())?;
        let points = pockets.single().map_err(|e| e.to_string())?.to_vec();
        let polygon = Polygon::new(points.clone()).map_err(|e| format!("polygon: {e}"))?;
        let open: Vec<usize> = self
            .open_edges
            .split([',', ' '])
            .filter(|w| !w.trim().is_empty())
            .map(|w| w.trim().parse::<usize>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("open edges: \"{}\" is not a list of edge numbers i, j, …", self.open_edges))?;
        let open_edges = pocket::stored_open_edges(&polygon, &points, &open).map_err(|e| e.to_string())?;
        Ok(PocketRequest {
            open_edges,
            polygon,
            tool_diameter_mm: self.tool_diameter_mm,
            step_over_mm: self.step_over_mm,
            strategy: self.strategy,
            feed_mm_per_min: self.feed_mm_per_min,
            pace: trochoplan_core::pocket::PaceOptions {
                rpm: self.spindle_rpm,
                teeth: self.teeth,
                ..PocketRequest::default().pace
            },
            ..PocketRequest::default()
        })
    }
}

/// A planned pocket converted for drawing; its numbers are those of the core's report (what
/// `trochoplan pocket` prints).
#[derive(Clone, Debug)]
pub struct PocketResult {
    pub method: &'static str,
    pub boundary: Vec<[f64; 2]>,
    /// The whole tool path at depth, as points for drawing.
    pub path: Vec<[f64; 2]>,
    /// The core's report of the plan (length, time, engagement, rows).
    pub report: PocketReport,
    /// The plan itself (for the NC program).
    pub plan: PocketPlan,
}

/// Plan the pocket as `trochoplan pocket` does (`pocket::plan`, `report::pocket`), converted
/// for drawing.
pub fn compute(i: &PocketInputs) -> Result<PocketResult, String> {
    let req = i.request()?;
    let plan = pocket::plan(&req).map_err(|e| e.to_string())?;
    let report = report::pocket(&req, &plan).map_err(|e| e.to_string())?;
    let mut boundary: Vec<[f64; 2]> = plan.polygon().vertices().iter().map(|v| [v.x, v.y]).collect();
    if let Some(&first) = boundary.first() {
        boundary.push(first);
    }
    let path = segment_points(&plan.path().segments(), MAX_PATH_POINTS);
    Ok(PocketResult { method: report.method(), boundary, path, report, plan })
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

/// The Pocket tab: method, tool and step-over; the outline editor beside the rings and their
/// numbers; the program beside the rings when the NC export is open.
pub fn show(ui: &mut egui::Ui, inputs: &mut PocketInputs, view: &PocketView, nc: &mut NcExport) -> Option<Command> {
    pocket_inputs(ui, inputs, nc);
    plane::status(ui, view.error.as_deref(), view.pending(), None);
    let cmd = if nc.settings.open {
        ui.separator();
        let cmd = corner_nc::options(ui, nc.settings, nc.cache, view.error.is_some(), Command::ExportPocketNc);
        ui.separator();
        cmd
    } else {
        None
    };
    let h = (ui.available_height() - 10.0).max(220.0);
    let mut open = false;
    ui.horizontal_top(|ui| {
        ui.vertical(|ui| {
            ui.set_width(230.0);
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
                pocket_numbers(ui, r);
            }
        });
        if let Some(r) = view.last.as_deref() {
            pocket_view(ui, r, nc.settings.open, nc.cache, h);
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

/// The strategy, the tool diameter, the step-over, the open edges and the NC export's
/// toggle.
fn pocket_inputs(ui: &mut egui::Ui, inputs: &mut PocketInputs, nc: &mut NcExport) {
    ui.horizontal_wrapped(|ui| {
        strategy_buttons(ui, &mut inputs.strategy);
        ui.separator();
        let l = ui.label(label::POCKET_TOOL_DIAMETER);
        ui.add(DragValue::new(&mut inputs.tool_diameter_mm).speed(0.1).suffix(" mm"))
            .labelled_by(l.id)
            .on_hover_text("Tool diameter D = 2r.");
        let l = ui.label(label::POCKET_STEP_OVER);
        ui.add(DragValue::new(&mut inputs.step_over_mm).speed(0.05).suffix(" mm"))
            .labelled_by(l.id)
            .on_hover_text("Distance between successive contour-parallel rings, 0 < a_e < D.");
        let l = ui.label(label::POCKET_OPEN_EDGES);
        ui.add_enabled(
            inputs.strategy == PocketStrategy::Adaptive,
            egui::TextEdit::singleline(&mut inputs.open_edges).desired_width(60.0),
        )
        .labelled_by(l.id)
        .on_hover_text(
            "Edges without a wall (adaptive): \"0\" or \"0, 2\"; edge i runs from vertex i to vertex i + 1 \
                 (0-based). The tool goes down outside the stock there and clears inward.",
        );
        ui.separator();
        ui.toggle_value(&mut nc.settings.open, label::NC_EXPORT)
            .on_hover_text("Options, preview and save of the NC program of the pocket");
    });
}

/// The pocket's vertices as editable text.
fn polygon_editor(ui: &mut egui::Ui, inputs: &mut PocketInputs) {
    let l = ui.label(label::POCKET_VERTICES);
    ui.add(egui::TextEdit::multiline(&mut inputs.polygon_text).desired_rows(8).code_editor())
        .labelled_by(l.id)
        .on_hover_text("A simple polygon, lines only, one vertex \"x,y\" (mm) per line; '#' comments allowed.");
}

/// The pocket's method, length, time and engagement (the core's report), and its rings'
/// offsets and engagement, or for a strategy without rings of its own its moves by kind.
fn pocket_numbers(ui: &mut egui::Ui, r: &PocketResult) {
    ui.label(format!("method {}", r.method));
    let rings = r.report.rings();
    if !rings.is_empty() {
        ui.label(if rings.len() == 1 { "1 ring".to_owned() } else { format!("{} rings", rings.len()) });
    }
    ui.label(format!("path {:.1} mm, {:.1} s", r.report.length_at_depth_mm(), r.report.time_s()));
    ui.label(format!("max engagement {:.1}°", r.report.max_engagement_deg()));
    ui.label(r.report.detail());
    ui.label(r.report.pace_line()).on_hover_text(
        "Each move runs at the feed that keeps every tooth's largest chip h_max at the target (f_z): \
         faster where the tool is lightly engaged, up to 3 × the feed. Straight moves through stock \
         already cleared, 0.3 mm clear of any material left, run as rapids at depth.",
    );
    egui::ScrollArea::vertical().id_salt("pocket_rings_scroll").show(ui, |ui| {
        egui::Grid::new("pocket_rings").striped(true).show(ui, |ui| {
            if rings.is_empty() {
                // one pass: its moves by kind, as the JSON's by_kind rows
                ui.label("move");
                ui.label("length");
                ui.label("max eng.");
                ui.end_row();
                for row in r.report.by_kind() {
                    ui.label(row.kind.name());
                    ui.label(format!("{:.1} mm", row.length_mm));
                    ui.label(format!("{:.1}°", row.max_engagement_deg));
                    ui.end_row();
                }
            } else {
                ui.label("ring");
                ui.label("offset");
                ui.label("max eng.");
                ui.end_row();
                for g in rings {
                    ui.label(format!("{}", g.level));
                    ui.label(format!("{:.2} mm", g.offset_mm));
                    ui.label(format!("{:.1}°", g.max_engagement_deg));
                    ui.end_row();
                }
            }
        });
    });
}

/// The pocket and its tool path, `h` high; half as wide, beside the program, when `nc_open`.
fn pocket_view(ui: &mut egui::Ui, r: &PocketResult, nc_open: bool, nc_cache: &CornerNcCache, h: f32) {
    let w = ui.available_width();
    let plot_w = if nc_open { 0.5 * w } else { w };
    plane_plot("pocket_rings_plot", h).width(plot_w).show(ui, |p| {
        p.line(line("pocket", &r.boundary).color(Color32::GRAY).width(2.5));
        p.line(line("tool path", &r.path).color(STRATEGY_COLOR).width(1.0));
    });
    if nc_open {
        ui.vertical(|ui| {
            ui.set_min_size(egui::vec2(ui.available_width(), h));
            corner_nc::preview(ui, nc_cache);
        });
    }
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
