//! The Machine & optimise tab: the feed over one cycle on the job's machine (where
//! it cannot hold the programmed feed), and the optimiser — limits, a run on a worker thread
//! with progress and cancel, the Pareto front of real MRR against W_max; a click on a point
//! loads its job.

use super::Command;
use super::legend::{self, Entry, Look};
use crate::worker::{Keep, Task, Worker};
use eframe::egui::{self, Color32, RichText};
use egui_plot::{Line, Plot, PlotPoints, Points};
use serde::{Deserialize, Serialize};
use trochoplan_core::optimize::{Candidate, Control, Limits, Outcome, optimize};
use trochoplan_core::{Job, Plan};

/// Persisted optimiser limits (the CLI's `optimize` flags).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct OptimiseSettings {
    /// `--max-hmax` (mm).
    pub max_hmax_mm: f64,
    /// `--max-engagement` (degrees).
    pub max_engagement_deg: f64,
    /// `--max-waviness` (mm), used when `limit_waviness`.
    pub max_waviness_mm: f64,
    pub limit_waviness: bool,
    /// `--max-force` (N), used when `limit_force`.
    pub max_force_n: f64,
    pub limit_force: bool,
    /// `--min-cooling` (share of the cycle), used when `limit_cooling`.
    pub min_cooling_share: f64,
    pub limit_cooling: bool,
    /// Show (and load from) the front against F_R,max instead of W_max.
    pub front_by_force: bool,
}

impl Default for OptimiseSettings {
    /// The comparison with FreeCAD Adaptive in docs/process-model.md ("Optimiser"): its peak
    /// chip thickness (0.075 mm) and engagement (57.5°) on the paper's slot as the limits.
    fn default() -> Self {
        OptimiseSettings {
            max_hmax_mm: 0.075,
            max_engagement_deg: 57.5,
            max_waviness_mm: 0.01,
            limit_waviness: false,
            max_force_n: 700.0,
            limit_force: false,
            min_cooling_share: 0.5,
            limit_cooling: false,
            front_by_force: false,
        }
    }
}

impl OptimiseSettings {
    fn limits(&self) -> Result<Limits, String> {
        let limits = Limits::new(
            self.max_hmax_mm,
            self.max_engagement_deg,
            self.limit_waviness.then_some(self.max_waviness_mm),
            self.limit_cooling.then_some(self.min_cooling_share),
        );
        match limits {
            Ok(l) if self.limit_force => l.with_max_force(self.max_force_n),
            other => other,
        }
        .map_err(|e| e.to_string())
    }
}

/// The optimiser's worker: (base job, limits) in, the outcome out.
type OptimiseWorker = Worker<(Job, Limits), Result<Outcome, String>>;

fn optimise_job((base, limits): (Job, Limits), task: &Task<Result<Outcome, String>>) {
    let progress = |f: f64| task.progress(f as f32, None);
    let cancelled = || task.cancelled();
    let control = Control { progress: &progress, cancelled: &cancelled };
    match optimize(&base, &limits, &control) {
        Ok(Some(out)) => {
            task.send(Ok(out));
        }
        Ok(None) => {}
        Err(e) => {
            task.send(Err(e.to_string()));
        }
    }
}

/// A running or finished optimisation.
pub struct OptimiseRun {
    worker: OptimiseWorker,
    pub result: Option<Result<Outcome, String>>,
    pub cancelled: bool,
}

impl OptimiseRun {
    /// Start on a worker thread; `repaint` is called on progress and at the end.
    pub fn start(settings: &OptimiseSettings, base: &Job, repaint: impl Fn() + Send + Sync + 'static) -> OptimiseRun {
        let mut worker = Worker::threaded("optimise", Keep::Newest, optimise_job, repaint);
        let result = match settings.limits() {
            Ok(limits) => {
                worker.request((base.clone(), limits));
                None
            }
            Err(e) => Some(Err(e)),
        };
        OptimiseRun { worker, result, cancelled: false }
    }

    /// Collect the outcome if it arrived.
    pub fn poll(&mut self) {
        if let Some(r) = self.worker.poll().pop() {
            self.result = Some(r);
        }
    }

    pub fn running(&self) -> bool {
        self.result.is_none() && !self.cancelled && self.worker.running()
    }

    /// The share of the search done (0–1), as the progress bar shows it.
    pub fn fraction(&self) -> f32 {
        self.worker.progress().map_or(0.0, |p| p.fraction)
    }

    pub fn cancel(&mut self) {
        self.worker.cancel();
        self.cancelled = true;
    }

    /// The job of point `i` of the front shown (against F_R,max if `by_force`, else W_max).
    pub fn front_job(&self, i: usize, by_force: bool) -> Option<Job> {
        match &self.result {
            Some(Ok(out)) => front(out, by_force).get(i).map(|c| c.job.clone()),
            _ => None,
        }
    }

    /// The best job.
    pub fn best_job(&self) -> Option<Job> {
        match &self.result {
            Some(Ok(out)) => Some(out.best.job.clone()),
            _ => None,
        }
    }
}

/// The front against F_R,max or against W_max.
fn front(out: &Outcome, by_force: bool) -> &[Candidate] {
    if by_force { &out.front_force } else { &out.front }
}

/// Colour of the stretches where the machine cannot hold the programmed feed.
const NOT_HELD: Color32 = Color32::from_rgb(210, 60, 40);

/// Draw the tab: feed plot, limits, run/cancel, front.
pub fn show(
    ui: &mut egui::Ui,
    settings: &mut OptimiseSettings,
    run: Option<&OptimiseRun>,
    plan: Option<&Plan>,
) -> Option<Command> {
    if let Some(p) = plan {
        feed_plot(ui, p);
    }
    ui.separator();
    ui.heading("Optimise: highest real MRR within the limits");
    let running = run.is_some_and(OptimiseRun::running);
    let mut cmd = None;
    ui.horizontal_wrapped(|ui| {
        ui.add_enabled_ui(!running, |ui| {
            let l = ui.label("h_max <=");
            ui.add(
                egui::DragValue::new(&mut settings.max_hmax_mm)
                    .custom_parser(super::number::parse)
                    .speed(0.001)
                    .max_decimals(4)
                    .suffix(" mm"),
            )
            .labelled_by(l.id);
            let l = ui.label("engagement <=");
            ui.add(
                egui::DragValue::new(&mut settings.max_engagement_deg)
                    .custom_parser(super::number::parse)
                    .speed(0.5)
                    .max_decimals(2)
                    .suffix("°"),
            )
            .labelled_by(l.id);
            ui.checkbox(&mut settings.limit_waviness, "W_max <=");
            ui.add_enabled(
                settings.limit_waviness,
                egui::DragValue::new(&mut settings.max_waviness_mm)
                    .custom_parser(super::number::parse)
                    .speed(0.001)
                    .max_decimals(4)
                    .suffix(" mm"),
            );
            ui.checkbox(&mut settings.limit_cooling, "cooling share >=").on_hover_text(
                "Smallest share of the cycle in which a tooth does not cut: its cooling time t_cooling \
                 over the cycle time.",
            );
            ui.add_enabled(
                settings.limit_cooling,
                egui::DragValue::new(&mut settings.min_cooling_share)
                    .custom_parser(super::number::parse)
                    .range(0.0..=1.0)
                    .speed(0.005)
                    .max_decimals(3)
                    .suffix(" of the cycle"),
            );
            ui.checkbox(&mut settings.limit_force, "F_R,max <=").on_hover_text(
                "Limit the largest resultant cutting force of the force model (Forces tab; Altintas & Lee 1996)",
            );
            ui.add_enabled(
                settings.limit_force,
                egui::DragValue::new(&mut settings.max_force_n)
                    .custom_parser(super::number::parse)
                    .speed(5.0)
                    .max_decimals(0)
                    .suffix(" N"),
            );
        });
        if running {
            if ui.button("Cancel").clicked() {
                cmd = Some(Command::CancelOptimise);
            }
            let f = run.map_or(0.0, OptimiseRun::fraction);
            ui.add(egui::ProgressBar::new(f).desired_width(160.0).show_percentage());
        } else if ui
            .button("Optimise")
            .on_hover_text(
                "Search path type, r_e, d, step and feed for the highest real MRR on the job's machine, \
                 with the slot, tool, rpm and depth of the edited job (background thread)",
            )
            .clicked()
        {
            cmd = Some(Command::StartOptimise);
        }
    });
    match run.and_then(|r| r.result.as_ref()) {
        Some(Err(e)) => {
            ui.label(RichText::new(e).color(NOT_HELD));
        }
        Some(Ok(out)) => {
            let m = &out.best.metrics;
            ui.horizontal_wrapped(|ui| {
                ui.label(format!(
                    "Best: {} r_e {:.3} d {:.3} mm s {:.3} mm feed {:.0} mm/min gives real MRR {:.0} mm³/min, \
                     h_max {:.4} mm, engagement {:.1}°, W_max {:.4} mm, F_R,max {:.0} N ({} plans)",
                    out.best.job.path.name(),
                    m.aspect_ratio,
                    m.linear_distance_mm,
                    m.step_mm,
                    out.best.job.feed,
                    m.mrr_real_mm3_per_min,
                    m.h_max_mm,
                    m.engagement_max_deg,
                    out.best.waviness(),
                    m.force_resultant_max_n,
                    out.evaluations
                ));
                if ui.button("Load best").clicked() {
                    cmd = Some(Command::LoadOptimised(None));
                }
            });
            ui.horizontal(|ui| {
                ui.label("Pareto front against");
                ui.radio_value(&mut settings.front_by_force, false, "W_max");
                ui.radio_value(&mut settings.front_by_force, true, "F_R,max");
            });
            if let Some(i) = front_plot(ui, out, settings.front_by_force) {
                cmd = Some(Command::LoadOptimised(Some(i)));
            }
        }
        None if run.is_some_and(|r| r.cancelled) => {
            ui.label("Cancelled.");
        }
        None => {}
    }
    cmd
}

/// Real and programmed feed over one steady-state cycle; red where the feed is not held.
fn feed_plot(ui: &mut egui::Ui, p: &Plan) {
    let machine = p.job.machine.as_ref().map_or("ideal machine", |m| m.name.as_str());
    ui.label(format!(
        "Feed over one cycle on {machine}: real cycle {:.3} s vs programmed {:.3} s, feed held {:.0} % of the time",
        p.metrics.t_cycle_real_s,
        p.metrics.t_cycle_s,
        100.0 * p.metrics.feed_held_share
    ));
    let pts = &p.feed.points;
    let real: Vec<[f64; 2]> = pts.iter().map(|q| [q.t_s, q.feed_mm_per_min]).collect();
    let programmed: Vec<[f64; 2]> = pts.iter().map(|q| [q.t_s, q.programmed_mm_per_min]).collect();
    let not_held: Vec<[f64; 2]> = pts.iter().filter(|q| !q.held()).map(|q| [q.t_s, q.feed_mm_per_min]).collect();
    let entries = [
        Entry::new("programmed", Look::solid(Color32::GRAY, 1.5)),
        Entry::new("real", Look::solid(Color32::from_rgb(40, 110, 200), 1.5)),
        Entry::new("not held", Look::points(NOT_HELD, 1.5)),
    ];
    // the legend and the plot share the plot's 200 px
    let height = 200.0 - legend::show_above(ui, &entries, 1);
    Plot::new("feed_plot")
        .height(height)
        .x_axis_label("t [s]")
        .y_axis_label("feed [mm/min]")
        .include_y(0.0)
        .allow_scroll(false)
        .show(ui, |plot| {
            plot.line(Line::new("programmed", PlotPoints::new(programmed)).color(Color32::GRAY));
            plot.line(Line::new("real", PlotPoints::new(real)).color(Color32::from_rgb(40, 110, 200)).width(1.5));
            plot.points(Points::new("not held", not_held).color(NOT_HELD).radius(1.5));
        });
}

/// A front (real MRR against W_max, or against F_R,max); returns the point clicked.
fn front_plot(ui: &mut egui::Ui, out: &Outcome, by_force: bool) -> Option<usize> {
    let x = |c: &Candidate| if by_force { c.metrics.force_resultant_max_n } else { c.waviness() * 1000.0 };
    let pts: Vec<[f64; 2]> = front(out, by_force).iter().map(|c| [x(c), c.mrr()]).collect();
    let best = [x(&out.best), out.best.mrr()];
    let jobs = Color32::from_rgb(40, 110, 200);
    let best_color = Color32::from_rgb(20, 150, 60);
    let entries = [
        Entry::new("Pareto front", Look::solid(Color32::GRAY, 1.5)),
        Entry::new("jobs (click to load)", Look::points(jobs, 4.0)),
        Entry::new("best", Look::points(best_color, 6.0)),
    ];
    // the legend and the plot share the plot's 220 px
    let height = 220.0 - legend::show_above(ui, &entries, 1);
    let resp = Plot::new("pareto_plot")
        .height(height)
        .x_axis_label(if by_force { "F_R,max [N]" } else { "W_max [µm]" })
        .y_axis_label("real MRR [mm³/min]")
        .allow_scroll(false)
        .show(ui, |plot| {
            plot.line(Line::new("Pareto front", PlotPoints::new(pts.clone())).color(Color32::GRAY));
            plot.points(Points::new("jobs (click to load)", pts.clone()).radius(4.0).color(jobs));
            plot.points(Points::new("best", vec![best]).radius(6.0).color(best_color));
            plot.pointer_coordinate()
        });
    let at = resp.inner?;
    if !resp.response.clicked() {
        return None;
    }
    // The nearest point in screen units.
    let t = &resp.transform;
    let click = t.position_from_point(&at);
    pts.iter()
        .enumerate()
        .map(|(i, p)| (i, t.position_from_point(&egui_plot::PlotPoint::new(p[0], p[1])).distance(click)))
        .filter(|&(_, d)| d < 12.0)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}
