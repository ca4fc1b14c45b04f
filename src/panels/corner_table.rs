//! The acceptance table of the Corner tab: at every corner angle of the core's
//! `acceptance::ANGLES_DEG`, the plain ring and the three corner strategies measured by the
//! independent evaluator — the rows of `trochoplan corner --method M --table`, one command per
//! strategy — for the tab's tool, step-over and target.
//!
//! The core computes each angle's rows (`acceptance_rows_at`, the plain ring measured once and
//! shared) and says whether they pass (`AcceptanceRow::passes`); this module only runs it on a
//! [`Worker`] thread, angle by angle, and draws the rows. A whole table takes about 10 s, so the
//! newest settings win: a change restarts the table, *Cancel* stops it between two angles.

use super::Command;
use super::label;
use super::legend::{self, Entry, Look};
use super::params::ERROR_COLOR;
use super::plane::PLAIN_COLOR;
use crate::worker::{Keep, Task, Worker};
use eframe::egui::{self, Color32, RichText};
use egui_plot::{HLine, Line, LineStyle, Plot, PlotPoints, Points};
use trochoplan_core::corner::acceptance::{ANGLES_DEG, AcceptanceRow, MARGIN_DEG, STRATEGIES, acceptance_rows_at};
use trochoplan_core::corner::{CornerRequest, CornerSettings};

/// Colours of the three strategies in the table and the plot (order of `STRATEGIES`).
pub const STRATEGY_COLORS: [Color32; 3] =
    [Color32::from_rgb(40, 110, 200), Color32::from_rgb(60, 160, 90), Color32::from_rgb(150, 80, 190)];
/// Colour of the passes and fails.
const PASS_COLOR: Color32 = Color32::from_rgb(70, 170, 80);

/// The rows of one corner angle, in the order of `STRATEGIES`, or why they could not be made.
#[derive(Clone, Debug)]
pub struct AngleRows {
    pub angle_deg: f64,
    pub rows: Result<Vec<AcceptanceRow>, String>,
}

/// The table's request: the settings and the spacing of the evaluated tool positions (mm).
type Request = (CornerSettings, f64);

/// Measure angle after angle, one [`AngleRows`] each, stopping between two angles as soon as a
/// newer request (or a cancel) supersedes this one.
fn measure((settings, spacing_mm): Request, task: &Task<AngleRows>) {
    for &angle_deg in &ANGLES_DEG {
        if task.cancelled() {
            return;
        }
        let rows = acceptance_rows_at(angle_deg, &STRATEGIES, settings, spacing_mm).map_err(|e| e.to_string());
        if !task.send(AngleRows { angle_deg, rows }) {
            return;
        }
    }
}

/// The table for the newest settings: rows as they arrive, progress, cancel.
pub struct TableView {
    /// Spacing of the evaluated tool positions (mm).
    pub spacing_mm: f64,
    /// The inputs of the newest request (settings, or why they are invalid).
    key: Option<Result<CornerSettings, String>>,
    /// Settings of the rows in `angles`.
    pub shown: Option<CornerSettings>,
    /// Rows received for `shown`, in the order of `ANGLES_DEG`.
    pub angles: Vec<AngleRows>,
    /// Why the newest inputs are invalid.
    pub error: Option<String>,
    /// The user stopped the table before it was complete.
    pub cancelled: bool,
    /// Measures the newest request's angles on its own thread ([`Keep::Newest`]: no row of an
    /// older request joins the table).
    worker: Worker<Request, AngleRows>,
}

impl TableView {
    /// A table measuring every `spacing_mm` along the paths on its own thread; `repaint` is
    /// called after each angle.
    pub fn new(spacing_mm: f64, repaint: impl Fn() + Send + Sync + 'static) -> TableView {
        TableView {
            spacing_mm,
            key: None,
            shown: None,
            angles: Vec::new(),
            error: None,
            cancelled: false,
            worker: Worker::threaded("corner-table", Keep::Newest, measure, repaint),
        }
    }

    /// All angles are in.
    pub fn complete(&self) -> bool {
        self.angles.len() == ANGLES_DEG.len()
    }

    /// Rows are being computed for `shown`.
    pub fn running(&self) -> bool {
        self.shown.is_some() && !self.complete() && !self.cancelled && self.error.is_none()
    }

    /// Collect the angles computed since the last call.
    pub fn poll(&mut self) {
        self.angles.extend(self.worker.poll());
    }

    /// Collect rows, and start a new table if `settings` changed (an invalid input stops the
    /// running table and keeps the last rows on screen).
    pub fn update(&mut self, settings: Result<CornerSettings, String>) {
        self.poll();
        if self.key.as_ref() == Some(&settings) {
            return;
        }
        self.key = Some(settings.clone());
        match settings {
            Err(e) => {
                self.error = Some(e);
                self.worker.cancel();
            }
            Ok(s) => {
                self.error = None;
                if self.shown == Some(s) && self.complete() {
                    return; // back to the settings of the complete table on screen
                }
                self.start(s);
            }
        }
    }

    fn start(&mut self, settings: CornerSettings) {
        self.cancelled = false;
        self.shown = Some(settings);
        self.angles.clear();
        self.worker.request((settings, self.spacing_mm));
    }

    /// Stop the running table between two angles; its rows so far stay.
    pub fn cancel(&mut self) {
        if self.running() {
            self.worker.cancel();
            self.cancelled = true;
        }
    }

    /// Compute the table again (after a cancel).
    pub fn restart(&mut self) {
        if let Some(Ok(s)) = self.key.clone() {
            self.start(s);
        }
    }
}

impl Default for TableView {
    /// The tab's table: the CLI's evaluator spacing, no repaint callback.
    fn default() -> Self {
        TableView::new(CornerRequest::DEFAULT.spacing_mm, || {})
    }
}

/// Tooltips of the columns (module docs of `core/src/corner/acceptance.rs`).
mod tip {
    pub const ANGLE: &str = "Interior angle of the symmetric line–line corner (walls 100 mm from the apex).";
    pub const PLAIN: &str = "Peak engagement of the plain contour-parallel ring turning at the corner, no trochoids \
        (measured by the evaluator, like every number here).";
    pub const BODY: &str = "Body: peak engagement of the strategy's whole path except the way into the corner point. \
        It must stay within the target + 1°.";
    pub const TIP: &str = "Tip: peak engagement of the way into the corner point: arcs tangent to both walls whose \
        radii shrink from the last circle's to the corner tolerance (0.005 mm), each planned to the target; the corner is \
        cut to radius r + 0.005 mm. (With --corner-tolerance 0, Wu et al.'s straight move into the corner point, \
        which engages about 180° minus the corner angle.)";
    pub const LIMIT: &str = "Stated limit of the tip: the target for the corner-point arcs (each is planned to it); for Wu \
        et al.'s move into the corner point the arc of the tool periphery outside the last offset circle, \
        2(π − ψ). The tip is judged against max(target + 1°, limit + 1°).";
    pub const PASS: &str = "pass: body ≤ target + 1° and tip ≤ max(target + 1°, tip limit + 1°).";
    pub const LENGTH: &str =
        "Tool-centre path length (mm): both walls and the corner; medial axis: the corner branch only.";
    pub const TIME: &str = "Machining time at the feed rate (s).";
}

fn header(ui: &mut egui::Ui, text: &str, tooltip: &str) {
    ui.label(RichText::new(text).strong()).on_hover_text(tooltip);
}

fn deg_cell(ui: &mut egui::Ui, v: f64, over: bool) {
    let text = RichText::new(format!("{v:.2}")).monospace();
    ui.label(if over { text.color(ERROR_COLOR) } else { text });
}

/// Label of a strategy as the tab's method buttons name it.
fn strategy_label(i: usize) -> &'static str {
    STRATEGIES[i].label()
}

/// What the table's body and tip columns mean (under the grid).
const BODY_AND_TIP: &str = "Body and tip: every strategy ends its chain of wall-tangent circles when the next circle \
    gets too small; the tip is the way from there into the corner point — arcs tangent to both walls shrinking to \
    0.005 mm, each planned to the target — reported apart (dashed in the plot); reaching the corner point itself would \
    engage 180° minus the corner angle. Body and tip must both stay within the target + 1°. Hover the column titles for details.";

/// The table (grid) and the plot of peak engagement against the corner angle.
pub fn show(ui: &mut egui::Ui, view: &TableView) -> Option<Command> {
    let cmd = ui.horizontal(|ui| progress(ui, view)).inner;
    if let Some(e) = &view.error {
        ui.add(egui::Label::new(RichText::new(format!("invalid: {e}")).color(ERROR_COLOR)).wrap());
        if !view.angles.is_empty() {
            ui.label("Showing the table of the last valid settings.");
        }
    }
    let Some(s) = view.shown else {
        return cmd;
    };
    let target = s.target.to_degrees();
    ui.label(format!(
        "target {target:.2}° (pass: body ≤ target + {MARGIN_DEG:.0}° = {:.2}°) · a_e {:.3} mm · D {:.1} mm · feed {:.0} mm/min",
        target + MARGIN_DEG,
        s.step_over,
        2.0 * s.tool_radius,
        s.feed_mm_per_min
    ));
    ui.add_space(4.0);
    grid(ui, view);
    ui.add_space(6.0);
    ui.add(egui::Label::new(RichText::new(BODY_AND_TIP).weak()).wrap());
    ui.add_space(4.0);
    ui.label(RichText::new("Peak engagement against the corner angle (evaluator)").strong());
    let (w, h) = (ui.available_width(), (ui.available_height() - 8.0).max(200.0));
    plot(ui, view, target, w, h);
    cmd
}

/// The progress bar and *Cancel* while the table runs, *Restart* after a cancel, what the rows
/// are once it is complete.
fn progress(ui: &mut egui::Ui, view: &TableView) -> Option<Command> {
    let n = ANGLES_DEG.len();
    if view.running() {
        let done = view.angles.len();
        let next = ANGLES_DEG.get(done).copied().unwrap_or(0.0);
        ui.add(
            egui::ProgressBar::new(done as f32 / n as f32)
                .desired_width(220.0)
                .text(format!("{done} of {n} angles, measuring {next:.0}°…")),
        );
        let cancel = ui.button(label::CANCEL_TABLE).on_hover_text("Stop after the angle being measured").clicked();
        return cancel.then_some(Command::CancelCornerTable);
    }
    if view.cancelled {
        ui.label(format!("Cancelled after {} of {n} angles.", view.angles.len()));
        return ui.button(label::RESTART_TABLE).clicked().then_some(Command::RestartCornerTable);
    }
    if view.complete() {
        ui.label(format!(
            "{n} corner angles × 3 strategies, measured by the evaluator every {} mm — the rows of \
             trochoplan corner --method M --table.",
            view.spacing_mm
        ));
    }
    None
}

/// One row per corner angle: the plain ring's peak and, per strategy, body, tip, limit,
/// verdict, length and time.
fn grid(ui: &mut egui::Ui, view: &TableView) {
    egui::Grid::new("corner_acceptance_table").striped(true).spacing(egui::vec2(10.0, 3.0)).show(ui, |ui| {
        grid_header(ui);
        for a in &view.angles {
            ui.label(format!("{:.0}°", a.angle_deg));
            match &a.rows {
                Ok(rows) => {
                    let plain = rows.first().map_or(f64::NAN, |r| r.plain_max_deg);
                    deg_cell(ui, plain, false);
                    for r in rows {
                        row_cells(ui, r);
                    }
                }
                Err(e) => {
                    ui.label(RichText::new(format!("cannot plan: {e}")).color(ERROR_COLOR));
                }
            }
            ui.end_row();
        }
    });
}

/// The two header rows: the strategies' names over their columns, then the column titles.
fn grid_header(ui: &mut egui::Ui) {
    ui.label("");
    ui.label("");
    for (i, color) in STRATEGY_COLORS.iter().enumerate() {
        ui.label(RichText::new(strategy_label(i)).strong().color(*color));
        for _ in 0..5 {
            ui.label("");
        }
    }
    ui.end_row();
    header(ui, "corner", tip::ANGLE);
    header(ui, "plain max °", tip::PLAIN);
    for _ in STRATEGIES {
        header(ui, "body °", tip::BODY);
        header(ui, "tip °", tip::TIP);
        header(ui, "limit °", tip::LIMIT);
        header(ui, "pass?", tip::PASS);
        header(ui, "length mm", tip::LENGTH);
        header(ui, "time s", tip::TIME);
    }
    ui.end_row();
}

/// One strategy's cells of a row: body, tip, limit, verdict (why, on hover), length, time.
fn row_cells(ui: &mut egui::Ui, r: &AcceptanceRow) {
    deg_cell(ui, r.body_max_deg, !r.body_passes());
    deg_cell(ui, r.tip_deg, !r.tip_passes());
    ui.label(RichText::new(format!("{:.2}", r.tip_limit_deg)).monospace().weak());
    let (text, color) = if r.passes() { ("pass", PASS_COLOR) } else { ("fail", ERROR_COLOR) };
    ui.label(RichText::new(text).color(color)).on_hover_text(format!(
        "body {:.2}° ≤ {:.2}°: {}; tip {:.2}° ≤ {:.2}°: {}",
        r.body_max_deg,
        r.body_limit_deg(),
        r.body_passes(),
        r.tip_deg,
        r.tip_allowed_deg(),
        r.tip_passes()
    ));
    ui.label(RichText::new(format!("{:.1}", r.path_length_mm)).monospace());
    ui.label(RichText::new(format!("{:.1}", r.time_s)).monospace());
}

fn plot(ui: &mut egui::Ui, view: &TableView, target_deg: f64, width: f32, height: f32) {
    let ok: Vec<&Vec<AcceptanceRow>> = view.angles.iter().filter_map(|a| a.rows.as_ref().ok()).collect();
    let series = |f: &dyn Fn(&Vec<AcceptanceRow>) -> Option<f64>| -> Vec<[f64; 2]> {
        ok.iter().filter_map(|rows| Some([rows.first()?.corner_angle_deg, f(rows)?])).collect()
    };
    let plain = series(&|rows| rows.first().map(|r| r.plain_max_deg));
    // each strategy by its colour, its two curves by their line style (in grey)
    let target = Look::solid(Color32::from_rgb(200, 40, 40), 1.0);
    let mut entries = vec![Entry::new("plain ring", Look::solid(PLAIN_COLOR, 2.0))];
    for (i, color) in STRATEGY_COLORS.iter().enumerate() {
        entries.push(Entry::new(strategy_label(i), Look::solid(*color, 2.0)));
    }
    entries.push(Entry::new("body", Look::solid(Color32::GRAY, 2.0)));
    entries
        .push(Entry::new("tip", Look::solid(Color32::GRAY.gamma_multiply(0.7), 1.5).styled(LineStyle::dashed_loose())));
    entries.push(Entry::new("target + 1°", target));
    let height = height - legend::show_above(ui, &entries, 2);
    Plot::new("corner_table_plot")
        .width(width)
        .height(height)
        .x_axis_label("corner angle (°)")
        .y_axis_label("peak engagement (°)")
        .include_x(ANGLES_DEG[0] - 5.0)
        .include_x(ANGLES_DEG[ANGLES_DEG.len() - 1] + 5.0)
        .include_y(0.0)
        .include_y(185.0)
        .allow_scroll(false)
        .show(ui, |p| {
            p.line(Line::new("plain ring", PlotPoints::from(plain.clone())).color(PLAIN_COLOR).width(2.0));
            p.points(Points::new("plain ring", PlotPoints::from(plain)).color(PLAIN_COLOR).radius(3.0));
            for (i, color) in STRATEGY_COLORS.iter().enumerate() {
                let name = strategy_label(i);
                let body = series(&|rows| rows.get(i).map(|r| r.body_max_deg));
                let tip = series(&|rows| rows.get(i).map(|r| r.tip_deg));
                p.line(Line::new(format!("{name}: body"), PlotPoints::from(body.clone())).color(*color).width(2.0));
                p.points(Points::new(format!("{name}: body"), PlotPoints::from(body)).color(*color).radius(3.0));
                p.line(
                    Line::new(format!("{name}: tip"), PlotPoints::from(tip))
                        .color(color.gamma_multiply(0.7))
                        .style(LineStyle::dashed_loose()),
                );
            }
            p.hline(HLine::new("target + 1°", target_deg + MARGIN_DEG).color(target.color).width(target.width));
        });
}

#[cfg(test)]
mod tests {
    use super::*;
    use trochoplan_core::corner::acceptance::acceptance_row;

    /// Coarse evaluator spacing: the worker's logic, not the numbers, is under test here.
    const SPACING: f64 = 2.0;

    fn settings(t1: f64) -> CornerSettings {
        CornerRequest { t1, ..CornerRequest::DEFAULT }.settings().expect("settings")
    }

    fn wait(v: &mut TableView) {
        let t0 = std::time::Instant::now();
        while v.running() && t0.elapsed().as_secs() < 120 {
            std::thread::sleep(std::time::Duration::from_millis(20));
            v.poll();
        }
    }

    #[test]
    fn newest_settings_win_and_cancel_keeps_the_rows_so_far() {
        let mut v = TableView::new(SPACING, || {});
        v.update(Ok(settings(0.15)));
        assert!(v.running());
        v.update(Ok(settings(0.2))); // restart at once: rows of the first settings never show
        wait(&mut v);
        assert!(v.complete(), "{} angles", v.angles.len());
        let want = acceptance_row(ANGLES_DEG[4], STRATEGIES[1], settings(0.2), SPACING).expect("row");
        let got = v.angles[4].rows.as_ref().expect("rows");
        assert_eq!(got[1], want, "the newest settings' rows");
        assert_eq!(got.len(), STRATEGIES.len());
        // the same settings again: nothing recomputed
        v.update(Ok(settings(0.2)));
        assert!(v.complete() && !v.running());
        // an invalid input keeps the table and says why
        v.update(Err("invalid step-over".into()));
        assert!(v.complete() && v.error.is_some() && !v.running());
        v.update(Ok(settings(0.2)));
        assert!(v.complete() && v.error.is_none(), "back to the shown settings: kept");
        // cancel stops between two angles and keeps what came in
        v.update(Ok(settings(0.1)));
        v.cancel();
        assert!(v.cancelled && !v.running());
        std::thread::sleep(std::time::Duration::from_millis(300));
        v.poll();
        assert!(v.angles.is_empty(), "rows of a cancelled generation are dropped");
        v.restart();
        assert!(v.running() && !v.cancelled);
        wait(&mut v);
        assert!(v.complete());
    }
}
