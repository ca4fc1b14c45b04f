//! The Corner tab: one line–line pocket corner planned by the core's corner
//! strategies (Wu et al. 2016), the corner drawn with equal axes, and the engagement measured by
//! the core's independent evaluator along the plain ring and along the strategy's path.
//!
//! The inputs are those of `trochoplan corner` (the core's `CornerRequest`, with its
//! defaults); [`compute`] calls the same core entry point (`corner::evaluate`) and only
//! converts its results to plot points. Whole pockets have their own tab ([`super::pocket`]). Planning takes 0.1–1 s, so the window runs it on a [`Worker`] thread
//! ([`CornerView::threaded`]; the newest request wins); the tests plan inline
//! ([`CornerView::default`]). The acceptance table
//! ([`super::corner_table`], always on its own thread) and the NC export
//! ([`super::corner_nc`]) are sub-views of the tab.

use super::Command;
use super::corner_nc::{self, CornerNcCache, CornerNcSettings, NcExport};
use super::corner_table::{self, TableView};
use super::label;
use super::legend::{self, Entry, Look};
use super::params::ERROR_COLOR;
use super::plane::{self, MAX_PATH_POINTS, PLAIN_COLOR, STRATEGY_COLOR, line, plane_plot, segment_points};
use crate::worker::{Keep, Latest, Task, Worker};
use eframe::egui::{self, Color32, DragValue, RichText, Slider, SliderClamping};
use egui_plot::{HLine, LineStyle, Plot};
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use trochoplan_core::corner::{self, CornerMethod, CornerReport, CornerRequest};
use trochoplan_core::engagement::EngagementProfile;
use trochoplan_core::geom::Segment;
use trochoplan_core::report::CornerSummary;

/// What the tab shows: one corner, or the acceptance table of all corner angles.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum CornerMode {
    /// Also read for the pocket mode of stored states from before the Pocket tab (the state
    /// loader moves those to the Pocket tab, see `app/state.rs`).
    #[default]
    #[serde(alias = "Pocket")]
    Corner,
    Table,
}

/// Inputs of the Corner tab, persisted with the app state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct CornerInputs {
    /// Interior corner angle (degrees).
    pub angle_deg: f64,
    pub method: CornerMethod,
    /// Tool diameter D (mm).
    pub tool_diameter_mm: f64,
    /// Give the step-over directly (else it follows from the straight engagement).
    pub use_step_over: bool,
    /// Ring step-over a_e (mm).
    pub step_over_mm: f64,
    /// Engagement on the straight part a_str (degrees).
    pub straight_engagement_deg: f64,
    /// Allowed excess t1: target a* = a_str·(1 + t1).
    pub t1: f64,
    pub mode: CornerMode,
    /// The job's feed f_r (mm/min; a copy taken each frame): the corner's program runs at it.
    #[serde(skip)]
    pub feed_mm_per_min: f64,
}

impl Default for CornerInputs {
    /// The defaults of `trochoplan corner`.
    fn default() -> Self {
        let corner = CornerRequest::DEFAULT;
        CornerInputs {
            angle_deg: corner.angle_deg,
            method: corner.method,
            tool_diameter_mm: corner.tool_diameter_mm,
            use_step_over: corner.step_over_mm.is_some(),
            // shown when "give step-over" is ticked: the pocket's default ring step-over
            step_over_mm: corner.step_over_mm.unwrap_or(trochoplan_core::pocket::PocketRequest::default().step_over_mm),
            straight_engagement_deg: corner.straight_engagement_deg,
            t1: corner.t1,
            mode: CornerMode::Corner,
            feed_mm_per_min: corner.feed_mm_per_min,
        }
    }
}

impl CornerInputs {
    /// The core's corner request of the tab's inputs at the job's feed (the tab has no target,
    /// tolerance, wall length, isometric radius or spacing fields: the defaults of
    /// `trochoplan corner`).
    pub fn request(&self) -> CornerRequest {
        CornerRequest {
            angle_deg: self.angle_deg,
            method: self.method,
            tool_diameter_mm: self.tool_diameter_mm,
            step_over_mm: self.use_step_over.then_some(self.step_over_mm),
            straight_engagement_deg: self.straight_engagement_deg,
            t1: self.t1,
            feed_mm_per_min: self.feed_mm_per_min,
            ..CornerRequest::DEFAULT
        }
    }
}

/// A planned corner converted for drawing: its numbers are the core's report (what
/// `trochoplan corner` prints) and acceptance row, its points sampled from the plan's segments.
#[derive(Clone, Debug)]
pub struct CornerResult {
    /// The core's report of the corner (circles, length, time, engagement, the plain ring).
    pub summary: CornerSummary,
    /// Largest engagement outside the final move into the corner point (degrees).
    pub body_max_deg: f64,
    /// Largest engagement of the final move into the corner point, and its stated limit (degrees).
    pub tip_deg: f64,
    pub tip_limit_deg: f64,
    /// Body within a* + 1° and tip within its allowance (core `AcceptanceRow::passes`).
    pub passes: bool,
    pub plain_time_s: f64,
    /// Wall 1 to the apex to wall 2.
    pub walls: Vec<[f64; 2]>,
    /// The previous ring's tool-centre path (already cut).
    pub previous_ring: Vec<[f64; 2]>,
    /// Tool-centre circles of the corner trochoids.
    pub circle_points: Vec<Vec<[f64; 2]>>,
    /// The strategy's tool-centre path (decimated).
    pub path: Vec<[f64; 2]>,
    /// Engagement (degrees) against path position (mm).
    pub profile: Vec<[f64; 2]>,
    pub plain_profile: Vec<[f64; 2]>,
    /// The core's evaluation (plans, profiles, settings; for the NC program).
    pub report: CornerReport,
}

/// Plan the corner and measure the strategy and the plain ring with the evaluator
/// (`corner::evaluate` and `report::corner`, as `trochoplan corner`), converted for drawing.
pub fn compute(i: &CornerInputs) -> Result<CornerResult, String> {
    let report = corner::evaluate(&i.request()).map_err(|e| e.to_string())?;
    let summary = trochoplan_core::report::corner(&report).map_err(|e| e.to_string())?;
    let (s, c, row) = (report.settings(), report.scenario.corner, &report.row);
    let wall = |p: trochoplan_core::geom::P2| [p.x, p.y];
    Ok(CornerResult {
        summary,
        body_max_deg: row.body_max_deg,
        tip_deg: row.tip_deg,
        tip_limit_deg: row.tip_limit_deg,
        passes: row.passes(),
        plain_time_s: row.plain_time_s,
        walls: vec![wall(c.apex - c.dir_in * s.edge_length), wall(c.apex), wall(c.apex + c.dir_out * s.edge_length)],
        previous_ring: segment_points(&report.scenario.previous_ring, MAX_PATH_POINTS / 4),
        circle_points: report
            .plan
            .circles
            .iter()
            .map(|cc| {
                let full = Segment::Arc {
                    center: cc.tool_circle.center,
                    radius: cc.tool_circle.radius,
                    start_angle: 0.0,
                    sweep: std::f64::consts::TAU,
                };
                full.sample(72).iter().map(|p| [p.x, p.y]).collect()
            })
            .collect(),
        path: segment_points(&report.plan.toolpath.segments(), MAX_PATH_POINTS),
        profile: profile_points(&report.measurement.profile),
        plain_profile: profile_points(&report.plain_measurement.profile),
        report,
    })
}

fn profile_points(p: &EngagementProfile) -> Vec<[f64; 2]> {
    p.samples.iter().map(|s| [s.s_mm, s.angle_rad.to_degrees()]).collect()
}

/// Plan the corner of `inputs`.
fn plan_job(inputs: CornerInputs, task: &Task<Result<Arc<CornerResult>, String>>) {
    task.send(compute(&inputs).map(Arc::new));
}

/// The last corner result, its error and the worker computing it ([`Latest`], which the view
/// dereferences to), and the acceptance table. Plans inline or on its own thread; an answer
/// overtaken by a newer request is still shown if it is newer than the one on screen
/// ([`Keep::Newer`]), so the view follows a dragged slider.
pub struct CornerView {
    /// The acceptance table (its own worker thread).
    pub table: TableView,
    corner: Latest<CornerInputs, CornerResult>,
}

impl std::ops::Deref for CornerView {
    type Target = Latest<CornerInputs, CornerResult>;
    fn deref(&self) -> &Self::Target {
        &self.corner
    }
}

impl Default for CornerView {
    /// A view planning inline (the tests).
    fn default() -> Self {
        CornerView { table: TableView::default(), corner: Latest::new(Worker::inline(Keep::Newer, plan_job)) }
    }
}

impl CornerView {
    /// A view planning on its own thread; `repaint` is called when an answer is ready.
    pub fn threaded(repaint: impl Fn() + Send + Sync + 'static) -> CornerView {
        let repaint = Arc::new(repaint);
        let table_repaint = repaint.clone();
        let table = TableView::new(CornerRequest::DEFAULT.spacing_mm, move || table_repaint());
        let worker = Worker::threaded("corner", Keep::Newer, plan_job, move || repaint());
        CornerView { table, corner: Latest::new(worker) }
    }

    /// Collect answers and ask for a plan of `inputs` if they changed; in the table mode, ask
    /// for the table of their settings instead.
    pub fn update(&mut self, inputs: &CornerInputs) {
        if inputs.mode == CornerMode::Table {
            self.table.update(inputs.request().settings().map_err(|e| e.to_string()));
            return;
        }
        self.corner.update(inputs);
    }
}

/// The Corner tab: the mode, its inputs and results (one corner with its view and engagement
/// plot, or the acceptance table), and the NC export when it is open.
pub fn show(
    ui: &mut egui::Ui,
    inputs: &mut CornerInputs,
    view: &CornerView,
    nc: &mut CornerNcSettings,
    nc_cache: &CornerNcCache,
) -> Option<Command> {
    mode_bar(ui, inputs, nc);
    let nc = &mut NcExport { settings: nc, cache: nc_cache };
    match inputs.mode {
        CornerMode::Table => {
            tool_inputs(ui, inputs);
            corner_table::show(ui, &view.table)
        }
        CornerMode::Corner => corner(ui, inputs, view, nc),
    }
}

/// The mode buttons and the NC export's toggle (off in the table mode).
fn mode_bar(ui: &mut egui::Ui, inputs: &mut CornerInputs, nc: &mut CornerNcSettings) {
    ui.horizontal(|ui| {
        ui.selectable_value(&mut inputs.mode, CornerMode::Corner, "One corner")
            .on_hover_text("A single line–line corner between two walls, apex at the origin");
        ui.selectable_value(&mut inputs.mode, CornerMode::Table, "Acceptance table").on_hover_text(
            "Every corner angle from 30° to 150° in 15° steps: the plain ring and the three strategies, measured \
             by the evaluator (the rows of trochoplan corner --method M --table)",
        );
        ui.separator();
        ui.add_enabled_ui(inputs.mode != CornerMode::Table, |ui| {
            ui.toggle_value(&mut nc.open, label::NC_EXPORT)
                .on_hover_text("Options, preview and save of the NC program of the corner")
                .on_disabled_hover_text("Export one corner; the table has no single tool path.");
        });
    });
}

/// Tool, step-over (or straight engagement) and t1: the inputs of the corner and the table.
fn tool_inputs(ui: &mut egui::Ui, inputs: &mut CornerInputs) {
    ui.horizontal_wrapped(|ui| {
        let l = ui.label(label::CORNER_TOOL_DIAMETER);
        ui.add(DragValue::new(&mut inputs.tool_diameter_mm).speed(0.1).suffix(" mm"))
            .labelled_by(l.id)
            .on_hover_text("Tool diameter D = 2r.");
        ui.separator();
        ui.checkbox(&mut inputs.use_step_over, "give step-over")
            .on_hover_text("On: enter the ring step-over a_e. Off: a_e follows from the straight engagement.");
        if inputs.use_step_over {
            let l = ui.label(label::RING_STEP_OVER);
            ui.add(DragValue::new(&mut inputs.step_over_mm).speed(0.05).suffix(" mm"))
                .labelled_by(l.id)
                .on_hover_text("Distance between successive contour-parallel rings, 0 < a_e < D.");
        } else {
            let l = ui.label(label::STRAIGHT_ENGAGEMENT);
            ui.add(DragValue::new(&mut inputs.straight_engagement_deg).speed(0.5).suffix("°"))
                .labelled_by(l.id)
                .on_hover_text(
                    "Engagement angle of the ring on the straight part of the walls, arccos(1 − a_e/r) \
                     for a step-over a_e and a tool radius r (straight cut); the acceptance table uses 46°.",
                );
        }
        ui.separator();
        let l = ui.label(label::ALLOWED_CORNER_EXCESS);
        ui.add(DragValue::new(&mut inputs.t1).speed(0.01).range(-1.0..=2.0)).labelled_by(l.id).on_hover_text(
            "Wu et al. (2016): the corner circles aim at the straight walls' engagement × (1 + this \
                 share) (their eq. 23); the variable circles are bisected until their engagement lies just \
                 above that target (eq. 24); isometric circles use it for their spacing and their least \
                 radius (eq. 25). From 0 to 1.",
        );
    });
}

/// One corner: angle, method, tool inputs, numbers; the corner view beside the engagement plot,
/// or beside the program when the NC export is open.
fn corner(ui: &mut egui::Ui, inputs: &mut CornerInputs, view: &CornerView, nc: &mut NcExport) -> Option<Command> {
    corner_inputs(ui, inputs);
    let kept = view.last.is_some().then_some("Showing the last valid corner.");
    plane::status(ui, view.error.as_deref(), view.pending(), kept);
    let Some(r) = view.last.as_deref() else {
        if view.error.is_none() {
            ui.label("Planning the corner…");
        }
        return None;
    };
    numbers(ui, r);
    ui.separator();
    let cmd = nc_options(ui, view, nc);
    corner_plots(ui, r, nc.settings.open, nc.cache);
    if !nc.settings.open {
        ui.separator();
        teaching(ui);
    }
    cmd
}

/// The corner angle, the method and the tool inputs.
fn corner_inputs(ui: &mut egui::Ui, inputs: &mut CornerInputs) {
    ui.horizontal_wrapped(|ui| {
        let l = ui.label(label::CORNER_ANGLE);
        ui.add(Slider::new(&mut inputs.angle_deg, 30.0..=150.0).step_by(1.0).clamping(SliderClamping::Never))
            .labelled_by(l.id)
            .on_hover_text(
                "Interior angle between the two walls (30°–150°); the apex is at the origin, the bisector along +x.",
            );
        ui.separator();
        plane::method_buttons(ui, &mut inputs.method);
    });
    tool_inputs(ui, inputs);
}

/// The NC export's options and a separator, when the export is open.
fn nc_options(ui: &mut egui::Ui, view: &CornerView, nc: &mut NcExport) -> Option<Command> {
    if !nc.settings.open {
        return None;
    }
    let cmd = corner_nc::options(ui, nc.settings, nc.cache, view.error.is_some(), Command::ExportCornerNc);
    ui.separator();
    cmd
}

/// The corner view beside the engagement plot, or beside the program when `nc_open`; they leave
/// room for the teaching text when the program is not shown.
fn corner_plots(ui: &mut egui::Ui, r: &CornerResult, nc_open: bool, nc_cache: &CornerNcCache) {
    let teach = if nc_open { 0.0 } else { TEACH_HEIGHT + 16.0 };
    let h = (ui.available_height() - teach).max(220.0);
    ui.columns(2, |cols| {
        cols[0].label(
            RichText::new(format!("Corner {:.0}°: walls, circles, tool path", r.summary.corner_angle_deg)).strong(),
        );
        corner_plot(&mut cols[0], r, h - 20.0);
        if nc_open {
            cols[1].allocate_ui(egui::vec2(cols[1].available_width(), h), |ui| corner_nc::preview(ui, nc_cache));
        } else {
            cols[1].label(RichText::new("Engagement along the path (evaluator)").strong());
            engagement_plot(&mut cols[1], r, h - 20.0);
        }
    });
}

/// Height of the teaching text under the plots.
const TEACH_HEIGHT: f32 = 120.0;

fn numbers(ui: &mut egui::Ui, r: &CornerResult) {
    egui::Grid::new("corner_numbers").num_columns(6).striped(true).show(ui, |ui| {
        ui.label("");
        ui.label("max engagement");
        ui.label("body / tip (limit)").on_hover_text(
            "Body: everything but the way into the corner point. Tip: that way in — arcs tangent to both walls \
             shrinking to the corner tolerance (0.005 mm), each planned to the target engagement, so the corner is cut \
             to radius r + 0.005 mm; its stated limit in brackets (see the README's acceptance table). \
             Measured by the evaluator.",
        );
        ui.label("path length");
        ui.label("time");
        ui.label("circles");
        ui.end_row();
        ui.colored_label(PLAIN_COLOR, "plain ring");
        ui.label(format!("{:.1}°", r.summary.plain_max_engagement_deg));
        ui.label("–");
        ui.label(format!("{:.1} mm", r.summary.plain_path_length_mm));
        ui.label(format!("{:.2} s", r.plain_time_s));
        ui.label("–");
        ui.end_row();
        ui.colored_label(STRATEGY_COLOR, r.summary.method);
        ui.label(format!("{:.1}°", r.summary.max_engagement_deg));
        let text = RichText::new(format!("{:.1}° / {:.1}° ({:.1}°)", r.body_max_deg, r.tip_deg, r.tip_limit_deg));
        ui.label(if r.passes { text } else { text.color(ERROR_COLOR) });
        ui.label(format!("{:.1} mm", r.summary.path_length_mm));
        ui.label(format!("{:.2} s", r.summary.time_s));
        ui.label(format!("{}", r.summary.circles.len()));
        ui.end_row();
    });
    ui.label(format!(
        "step-over a_e {:.3} mm · straight walls {:.1}° · target {:.1}° · feed {:.0} mm/min",
        r.summary.step_over_mm,
        r.summary.straight_engagement_deg,
        r.summary.target_deg,
        r.report.settings().feed_mm_per_min
    ));
    for n in &r.summary.notes {
        ui.add(egui::Label::new(RichText::new(n).italics()).wrap());
    }
}

fn corner_plot(ui: &mut egui::Ui, r: &CornerResult, height: f32) {
    let walls = Look::solid(Color32::GRAY, 2.5);
    let previous = Look::solid(Color32::from_gray(150), 1.5).styled(LineStyle::dashed_dense());
    let circles = Look::solid(Color32::from_rgb(60, 160, 90), 0.8);
    let path = Look::solid(STRATEGY_COLOR, 1.2);
    let entries = [
        Entry::new("walls", walls),
        Entry::new("previous ring", previous),
        Entry::new("corner circles", circles),
        Entry::new("tool path", path),
    ];
    let height = height - legend::show_above(ui, &entries, 2);
    // start on the corner region (the circles and a margin); the whole walls after a zoom-out.
    // A new corner or method gets a new plot memory, so the view follows the plan.
    let reach = r.circle_points.iter().flatten().map(|p| p[0]).fold(0.0f64, f64::max);
    let x_max = (reach * 1.5).max(30.0);
    plane_plot(("corner_geometry", r.summary.corner_angle_deg.to_bits(), r.summary.method), height)
        .default_x_bounds(-5.0, x_max)
        .default_y_bounds(-0.5 * (x_max + 5.0), 0.5 * (x_max + 5.0))
        .show(ui, |p| {
            p.line(walls.line(line("walls", &r.walls)));
            p.line(previous.line(line("previous ring", &r.previous_ring)));
            for c in &r.circle_points {
                p.line(circles.line(line("corner circles", c)));
            }
            p.line(path.line(line("tool path", &r.path)));
        });
}

fn engagement_plot(ui: &mut egui::Ui, r: &CornerResult, height: f32) {
    let target = Look::solid(Color32::from_rgb(200, 40, 40), 1.0);
    let straight = Look::solid(Color32::GRAY, 1.0);
    let entries = [
        Entry::new("plain ring", Look::solid(PLAIN_COLOR, 1.5)),
        Entry::new(r.summary.method, Look::solid(STRATEGY_COLOR, 1.5)),
        Entry::new("target", target),
        Entry::new("straight walls", straight),
    ];
    let height = height - legend::show_above(ui, &entries, 2);
    Plot::new("corner_engagement")
        .height(height)
        .x_axis_label("position along the path s (mm)")
        .y_axis_label("engagement (°)")
        .include_y(0.0)
        .show(ui, |p| {
            p.line(line("plain ring", &r.plain_profile).color(PLAIN_COLOR).width(1.5));
            p.line(line(r.summary.method, &r.profile).color(STRATEGY_COLOR).width(1.5));
            p.hline(HLine::new("target", r.summary.target_deg).color(target.color).width(target.width));
            p.hline(
                HLine::new("straight walls", r.summary.straight_engagement_deg)
                    .color(straight.color)
                    .width(straight.width),
            );
        });
}

/// Short explanation of the engagement model and the strategies.
fn teaching(ui: &mut egui::Ui) {
    egui::ScrollArea::vertical().id_salt("corner_teach").max_height(TEACH_HEIGHT).show(ui, |ui| {
        ui.label(
            "Engagement: on a straight wall the tool of radius r cuts the arc arccos(1 − a_e/r) \
             (the straight cut). At an inside corner the next ring's tool wraps around the material the \
             previous ring left, and the engaged arc jumps (two-circle model, Wu et al. 2016 eqs. 2–6): \
             forces spike. The right plot is measured by the independent evaluator (material left by \
             everything cut before, engaged arc per tool position every 0.1 mm), not by the model.",
        );
        ui.label(
            "Variable circles: circles tangent to both offset walls with centres on the bisector \
             (eqs. 21–22); each next circle is found by bisection between the limit points M and N until \
             its engagement lies just above the target, the straight walls' engagement × (1 + the allowed \
             corner excess) (eqs. 23–24).",
        );
        ui.label(
            "Isometric circles: one radius rh, centre spacing from the engagement limit; the radius must \
             exceed a least radius (eq. 25). Medial axis: perforative circles along the medial axis of the \
             remaining material (segment Voronoi diagram). Plain: the ring as it is, for comparison.",
        );
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn threaded_view_delivers_the_newest_inputs() {
        let mut v = CornerView::threaded(|| {});
        let mut i = CornerInputs { angle_deg: 120.0, ..CornerInputs::default() };
        v.update(&i);
        i.angle_deg = 100.0;
        v.update(&i);
        v.corner.settle(&i, 60);
        assert!(!v.pending(), "answered within 60 s");
        assert_eq!(v.last.as_ref().expect("a result").summary.corner_angle_deg, 100.0);
    }
}
