//! Sweeps: metrics against r_e (the paper's Figs. 5, 9, Table 2) or against d (Figs. 12, 28),
//! computed by calling the core's `plan()` once per value on a worker thread, with progress and
//! cancel; the window never waits for it.

use super::Command;
use super::legend::{self, Entry, Look};
use crate::worker::{Keep, Task, Worker};
use eframe::egui::{self, Color32, RichText};
use egui_plot::{AxisHints, Line, Plot, Points, VLine};
use serde::{Deserialize, Serialize};
use trochoplan_core::quantity::{self, Metric};
use trochoplan_core::sweep::{self, SweepParam};
use trochoplan_core::{Job, Metrics, PathKind, plan};

/// Persisted sweep settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SweepSettings {
    pub param: SweepParam,
    pub from: f64,
    pub to: f64,
    pub steps: usize,
}

impl Default for SweepSettings {
    fn default() -> Self {
        SweepSettings { param: SweepParam::AspectRatio, from: 0.5, to: 1.2, steps: 29 }
    }
}

impl SweepSettings {
    /// Why the sweep cannot run on `base` (the core's rules, as the CLI applies them), if it
    /// cannot: an r_e or d sweep needs a path that has the parameter.
    pub fn refusal(&self, base: &Job) -> Option<String> {
        if let Err(e) = sweep::values(self.from, self.to, self.steps) {
            return Some(e.to_string());
        }
        let p = self.param;
        p.path_for(base.path)
            .is_none()
            .then(|| format!("Sweeping {} needs {}, not {}.", p.metric().symbol, p.needs(), base.path.name()))
    }

    /// The jobs of the sweep, built on `base` with the path the core's rules give
    /// ([`SweepParam::path_for`]: elliptical for r_e on the circular path, linear-elliptical
    /// for d); none when the sweep is refused ([`SweepSettings::refusal`]).
    pub fn jobs(&self, base: &Job) -> Vec<(f64, Job)> {
        let (Ok(values), Some(path)) = (sweep::values(self.from, self.to, self.steps), self.param.path_for(base.path))
        else {
            return Vec::new();
        };
        values
            .into_iter()
            .map(|v| {
                let mut job = Job { path, ..base.clone() };
                self.param.set(&mut job, v);
                (v, job)
            })
            .collect()
    }
}

/// One computed point of a sweep.
#[derive(Clone, Debug)]
pub struct SweepPoint {
    pub value: f64,
    pub result: Result<Metrics, String>,
}

/// The sweep's worker: the jobs in, one point per job out, with progress and cancel.
type SweepWorker = Worker<Vec<(f64, Job)>, SweepPoint>;

/// Plan the jobs one by one, sending each point, until done or cancelled.
fn sweep_job(jobs: Vec<(f64, Job)>, task: &Task<SweepPoint>) {
    let total = jobs.len().max(1) as f32;
    for (i, (value, job)) in jobs.into_iter().enumerate() {
        if task.cancelled() {
            break;
        }
        let result = plan(&job).map(|p| p.metrics).map_err(|e| e.to_string());
        if !task.send(SweepPoint { value, result }) {
            break;
        }
        task.progress((i + 1) as f32 / total, None);
    }
}

/// A running or finished sweep.
pub struct SweepRun {
    pub settings: SweepSettings,
    pub base_path: PathKind,
    pub total: usize,
    pub points: Vec<SweepPoint>,
    worker: SweepWorker,
    pub cancelled: bool,
}

impl SweepRun {
    /// Start the sweep on a worker thread; `repaint` is called after each point.
    pub fn start(settings: &SweepSettings, base: &Job, repaint: impl Fn() + Send + Sync + 'static) -> SweepRun {
        let jobs = settings.jobs(base);
        let total = jobs.len();
        let mut worker = Worker::threaded("sweep", Keep::Newest, sweep_job, repaint);
        worker.request(jobs);
        SweepRun {
            settings: settings.clone(),
            base_path: jobs_path(settings, base),
            total,
            points: Vec::with_capacity(total),
            worker,
            cancelled: false,
        }
    }

    /// Collect the points computed since the last call.
    pub fn poll(&mut self) {
        self.points.extend(self.worker.poll());
    }

    /// Whether the worker is still computing.
    pub fn running(&self) -> bool {
        self.worker.running()
    }

    /// Fraction done, 0–1.
    pub fn progress(&self) -> f32 {
        self.worker.progress().map_or(0.0, |p| p.fraction)
    }

    /// Ask the worker to stop after the current point.
    pub fn cancel(&mut self) {
        self.worker.cancel();
        self.cancelled = true;
    }
}

fn jobs_path(settings: &SweepSettings, base: &Job) -> PathKind {
    settings.jobs(base).first().map_or(base.path, |(_, j)| j.path)
}

/// Draw the sweep settings, progress and plots.
pub fn show(ui: &mut egui::Ui, settings: &mut SweepSettings, run: Option<&SweepRun>, current: &Job) -> Option<Command> {
    let running = run.is_some_and(SweepRun::running);
    let cmd = ui.horizontal_wrapped(|ui| settings_row(ui, settings, running, current)).inner;
    let Some(run) = run else {
        ui.label(
            "Runs the core planner for each value with the current slot, tool and cutting data; the r_e \
             sweep uses the elliptical path (or keeps linear-elliptical), the d sweep the \
             linear-elliptical path with the current r_e; neither runs on the circular-type path.",
        );
        return cmd;
    };
    ui.horizontal(|ui| status_row(ui, run, running));
    plots(ui, run, current);
    cmd
}

/// Colour of the refusal and of the count of invalid values.
const REFUSAL_COLOR: Color32 = Color32::from_rgb(200, 50, 40);

/// The swept parameter and its range, and the run or cancel button.
fn settings_row(ui: &mut egui::Ui, settings: &mut SweepSettings, running: bool, current: &Job) -> Option<Command> {
    ui.label("Sweep parameter:");
    let before = settings.param;
    ui.add_enabled_ui(!running, |ui| {
        ui.selectable_value(&mut settings.param, SweepParam::AspectRatio, "r_e (Figs. 5, 9, Table 2)");
        ui.selectable_value(&mut settings.param, SweepParam::LinearDistance, "d (Figs. 12, 28)");
    });
    if settings.param != before
        && let Some(range) = settings.param.paper_range()
    {
        (settings.from, settings.to) = range;
    }
    // r_e is a ratio b/a, d a length
    let unit = if settings.param == SweepParam::LinearDistance { " mm" } else { " (b/a)" };
    let l = ui.label("from");
    let from = egui::DragValue::new(&mut settings.from).custom_parser(super::number::parse).speed(0.01);
    ui.add(from.max_decimals(3).suffix(unit)).labelled_by(l.id);
    let l = ui.label("to");
    let to = egui::DragValue::new(&mut settings.to).custom_parser(super::number::parse).speed(0.01);
    ui.add(to.max_decimals(3).suffix(unit)).labelled_by(l.id);
    let l = ui.label("values");
    ui.add(egui::DragValue::new(&mut settings.steps).custom_parser(super::number::parse).range(2..=400))
        .labelled_by(l.id);
    let refusal = settings.refusal(current);
    let cmd = run_button(ui, running, refusal.as_deref());
    if let Some(why) = refusal {
        ui.label(RichText::new(why).color(REFUSAL_COLOR));
    }
    cmd
}

/// "Cancel" while running, else "Run sweep" (disabled with the reason when refused).
fn run_button(ui: &mut egui::Ui, running: bool, refusal: Option<&str>) -> Option<Command> {
    if running {
        return ui.button("Cancel").clicked().then_some(Command::CancelSweep);
    }
    ui.add_enabled(refusal.is_none(), egui::Button::new("Run sweep"))
        .on_hover_text("Plan the current job once per value on a background thread.")
        .on_disabled_hover_text(refusal.unwrap_or_default())
        .clicked()
        .then_some(Command::StartSweep)
}

/// Progress, state, the invalid values and the swept path.
fn status_row(ui: &mut egui::Ui, run: &SweepRun, running: bool) {
    let n = run.points.len();
    let bar = egui::ProgressBar::new(run.progress()).desired_width(260.0).text(format!("{n} / {}", run.total));
    ui.add(bar);
    let failed = run.points.iter().filter(|p| p.result.is_err()).count();
    if run.cancelled {
        ui.label(RichText::new("cancelled").color(Color32::from_rgb(200, 120, 0)));
    } else if !running {
        ui.label("done");
    }
    if failed > 0 {
        let first = run.points.iter().find_map(|p| p.result.as_ref().err()).cloned().unwrap_or_default();
        ui.label(RichText::new(format!("{failed} values invalid")).color(REFUSAL_COLOR)).on_hover_text(first);
    }
    ui.label(format!("path: {}", run.base_path.name()));
}

/// The quantities of one sweep plot, each with its colour.
type Series = Vec<(&'static Metric, Color32)>;

/// The six sweep plots: id, y-axis label and the quantities drawn.
fn sweep_plots() -> [(&'static str, &'static str, Series); 6] {
    [
        ("h_max", "h_max [mm]", vec![(&quantity::H_MAX, Color32::from_rgb(30, 110, 220))]),
        ("mrr", "MRR [mm³/min]", vec![(&quantity::MRR, Color32::from_rgb(40, 160, 70))]),
        (
            "waviness",
            "waviness [mm]",
            vec![
                (&quantity::WAVINESS_LEFT, Color32::from_rgb(220, 90, 30)),
                (&quantity::WAVINESS_RIGHT, Color32::from_rgb(170, 60, 190)),
            ],
        ),
        (
            "times",
            "time [s]",
            vec![
                (&quantity::T_COOLING, Color32::from_rgb(30, 110, 220)),
                (&quantity::T_HMAX, Color32::from_rgb(40, 160, 70)),
                (&quantity::T_CYCLE, Color32::from_rgb(120, 120, 120)),
            ],
        ),
        (
            "force",
            "F_R [N]",
            vec![
                (&quantity::FORCE_RESULTANT_MAX, Color32::from_rgb(210, 40, 40)),
                (&quantity::FORCE_RESULTANT_MEAN, Color32::from_rgb(120, 120, 120)),
            ],
        ),
        ("pi", "PI without Ra", vec![(&quantity::PERFORMANCE_INDEX_WITHOUT_RA, Color32::from_rgb(30, 110, 220))]),
    ]
}

/// Colour of the current job's marker.
const MARKER: Color32 = Color32::from_rgb(220, 30, 30);

/// The six plots in a 2 × 3 grid (h_max, MRR, waviness, times, forces (Fig. 16), PI without
/// Ra (Figs. 23, 28)), with the current job's value marked when the sweep's path is its path.
fn plots(ui: &mut egui::Ui, run: &SweepRun, current: &Job) {
    let ok: Vec<(f64, &Metrics)> =
        run.points.iter().filter_map(|p| p.result.as_ref().ok().map(|m| (p.value, m))).collect();
    let param = run.settings.param;
    let marker = (param.path_for(current.path) == Some(current.path)).then(|| param.get(current));
    let avail = ui.available_size();
    let cell = egui::vec2((avail.x - 12.0) / 2.0, ((avail.y - 20.0) / 3.0).max(100.0));
    egui::Grid::new("sweep_grid").num_columns(2).spacing([8.0, 8.0]).show(ui, |ui| {
        for (k, (id, ylabel, series)) in sweep_plots().iter().enumerate() {
            ui.allocate_ui(cell, |ui| {
                let mut entries: Vec<Entry> =
                    series.iter().map(|&(q, color)| Entry::new(q.symbol, Look::solid(color, 1.5))).collect();
                if marker.is_some() {
                    entries.push(Entry::new("current job", Look::solid(MARKER, 1.0)));
                }
                // the legend and the plot share the cell
                let height = cell.y - legend::show_above(ui, &entries, 1);
                let axis = AxisHints::new_x().label(param.label()).label_spacing(28.0..=44.0);
                Plot::new(format!("sweep_{id}"))
                    .width(cell.x)
                    .height(height)
                    .custom_x_axes(vec![axis])
                    .y_axis_label(*ylabel)
                    .allow_scroll(false)
                    .show(ui, |p| draw_series(p, series, &ok, marker));
            });
            if k % 2 == 1 {
                ui.end_row();
            }
        }
    });
}

/// One plot's curves (line and points per quantity) and the current job's marker.
fn draw_series(p: &mut egui_plot::PlotUi<'_>, series: &Series, ok: &[(f64, &Metrics)], marker: Option<f64>) {
    for &(q, color) in series {
        let pts: Vec<[f64; 2]> = ok.iter().map(|&(v, m)| [v, q.of(m)]).collect();
        p.line(Line::new(q.symbol, pts.clone()).color(color).width(1.5));
        p.points(Points::new(q.symbol, pts).color(color).radius(2.5));
    }
    if let Some(x) = marker {
        p.vline(VLine::new("current job", x).color(MARKER));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweeps_follow_the_core_rules_and_say_why_they_refuse() {
        let settings = SweepSettings::default();
        let circular_type = Job { path: PathKind::CircularType, ..Job::default() };
        assert!(settings.jobs(&circular_type).is_empty(), "no silent switch to the elliptical path");
        let why = settings.refusal(&circular_type).unwrap_or_default();
        assert!(why.contains("circular-type") && why.contains("elliptical"), "{why}");
        let jobs = settings.jobs(&Job::default());
        assert_eq!(jobs.len(), settings.steps);
        assert!(jobs.iter().all(|(v, j)| j.path == PathKind::Elliptical && j.aspect_ratio == *v));
        assert_eq!(settings.refusal(&Job::default()), None);
    }

    #[test]
    fn sweep_runs_in_background_and_can_be_cancelled() {
        let settings = SweepSettings { steps: 5, ..SweepSettings::default() };
        let mut run = SweepRun::start(&settings, &Job::default(), || {});
        let t0 = std::time::Instant::now();
        while run.running() && t0.elapsed().as_secs() < 60 {
            run.poll();
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        assert_eq!(run.points.len(), 5);
        assert!(run.points.iter().all(|p| p.result.is_ok()));
        let mrr: Vec<f64> =
            run.points.iter().filter_map(|p| p.result.as_ref().ok()).map(|m| quantity::MRR.of(m)).collect();
        assert!(mrr.windows(2).all(|w| w[0] > w[1]), "MRR falls as r_e grows: {mrr:?}");

        let big = SweepSettings { steps: 400, ..SweepSettings::default() };
        let mut run = SweepRun::start(&big, &Job::default(), || {});
        run.cancel();
        while run.running() {
            run.poll();
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        assert!(run.points.len() < 400, "cancel stops the worker");
    }
}
