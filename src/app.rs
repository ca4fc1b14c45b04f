//! The planner window (eframe/egui).
//!
//! Architecture (see `../shared/design.md`): the user's inputs live in a serialisable
//! [`State`], persisted by eframe; [`App`] keeps the last plan ([`Planner`]) and replans only
//! when the job changed, keeping the last *valid* plan on screen while the job is invalid.
//! Panels (`src/panels/`) are functions that edit the state or return a [`Command`]; commands
//! (files, undo/redo, pins, sweeps) run after all panels have drawn, and only they touch files
//! or dialogs — dialogs sit behind the [`FileDialogs`] trait so tests never open one.

#[path = "panels/mod.rs"]
pub(crate) mod panels;

use crate::files::write_atomic;
use eframe::egui;
use egui::util::undoer::Undoer;
use panels::Command;
use panels::compare::{self, MAX_VARIANTS, VariantView};
use panels::export::{ExportCache, ExportSettings};
use panels::graphics::{Chip, Graphics};
use panels::plots::{self, Cursor, Layer, PALETTE};
use panels::sweep::{SweepRun, SweepSettings};
use panels::teach::Animation;
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::time::Instant;
use trochoplan_core::{Job, JobError, Plan, plan};

/// eframe storage key of [`State`].
const STORAGE_KEY: &str = "trochoplan-state";
/// Environment variable: when set, every frame's time is printed to stderr (frame-time
/// measurement, see the README).
const FRAME_LOG_ENV: &str = "TROCHOPLAN_FRAME_LOG";

/// Open the window on `job`. A non-default `job` wins over the job restored from the last
/// session; with the built-in default job the last session's state is restored.
pub fn run(job: Job) -> eframe::Result<()> {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("TrochoPlan")
            .with_inner_size([1400.0, 900.0])
            .with_min_inner_size([960.0, 640.0]),
        ..Default::default()
    };
    eframe::run_native(
        "TrochoPlan",
        options,
        Box::new(move |cc| {
            let stored = cc.storage.and_then(|s| eframe::get_value::<State>(s, STORAGE_KEY));
            let stored = stored.map(|s| if job == Job::default() { s } else { State { job: job.clone(), ..s } });
            let ctx = cc.egui_ctx.clone();
            let planner = Planner::threaded(move || ctx.request_repaint());
            let mut app = App::with_planner(job, stored, Box::new(NativeDialogs), planner);
            let ctx = cc.egui_ctx.clone();
            app.corner = panels::corner::CornerView::threaded(move || ctx.request_repaint());
            Ok(Box::new(app))
        }),
    )
}

/// Which view fills the centre of the window.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Tab {
    #[default]
    Plots,
    Compare,
    Sweep,
    /// The "Export NC…" panel.
    Export,
    /// One pocket corner and its corner trochoids (issue #5).
    Corner,
}

/// A pinned variant as persisted.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PinnedJob {
    pub label: String,
    pub job: Job,
}

/// Everything the user chose, persisted between sessions.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct State {
    pub job: Job,
    pub tab: Tab,
    /// Show the explanation text under every plot.
    pub teach: bool,
    /// Cycles drawn in the path view.
    pub cycles_shown: usize,
    /// The chip view zooms onto the middle of the chip instead of showing all of it.
    pub chip_close_up: bool,
    /// Overlay pinned variants in the Plots tab too.
    pub overlay_pins: bool,
    pub pinned: Vec<PinnedJob>,
    pub sweep: SweepSettings,
    /// NC export options.
    pub export: ExportSettings,
    /// Inputs of the Corner tab.
    pub corner: panels::corner::CornerInputs,
    /// NC export options of the Corner tab.
    pub corner_nc: panels::corner_nc::CornerNcSettings,
    /// The job file last opened or saved.
    pub file: Option<PathBuf>,
}

impl Default for State {
    fn default() -> Self {
        State {
            job: Job::default(),
            tab: Tab::Plots,
            teach: false,
            cycles_shown: 5,
            chip_close_up: true,
            overlay_pins: true,
            pinned: Vec::new(),
            sweep: SweepSettings::default(),
            export: ExportSettings::default(),
            corner: panels::corner::CornerInputs::default(),
            corner_nc: panels::corner_nc::CornerNcSettings::default(),
            file: None,
        }
    }
}

/// A plan and its plot data.
#[derive(Clone)]
pub struct Planned {
    pub plan: Plan,
    pub graphics: Graphics,
}

/// A request to the planning thread: generation, job, cycles drawn.
type PlanRequest = (u64, Job, usize);
/// Its answer: generation, plan (or error), time spent in the core and conversion (ms).
type PlanAnswer = (u64, Result<Planned, JobError>, f64);

/// Plan `job` and convert it for drawing.
fn plan_and_draw(job: &Job, cycles_shown: usize) -> (Result<Planned, JobError>, f64) {
    let t0 = Instant::now();
    let planned = plan(job).map(|p| Planned { graphics: Graphics::new(&p, cycles_shown), plan: p });
    (planned, t0.elapsed().as_secs_f64() * 1e3)
}

/// The planning thread of a [`Planner`]: takes the newest request, drops stale ones.
struct PlanWorker {
    tx: std::sync::mpsc::Sender<PlanRequest>,
    rx: std::sync::mpsc::Receiver<PlanAnswer>,
}

impl PlanWorker {
    fn spawn(repaint: impl Fn() + Send + 'static) -> Option<PlanWorker> {
        let (tx, rx_req) = std::sync::mpsc::channel::<PlanRequest>();
        let (tx_ans, rx) = std::sync::mpsc::channel::<PlanAnswer>();
        std::thread::Builder::new()
            .name("planner".into())
            .spawn(move || {
                while let Ok(mut req) = rx_req.recv() {
                    while let Ok(newer) = rx_req.try_recv() {
                        req = newer; // only the newest job matters
                    }
                    let (planned, ms) = plan_and_draw(&req.1, req.2);
                    if tx_ans.send((req.0, planned, ms)).is_err() {
                        break;
                    }
                    repaint();
                }
            })
            .ok()?;
        Some(PlanWorker { tx, rx })
    }
}

/// The cache of the last plan: replans only when the job (or the drawn cycle count) changed.
///
/// Validation runs at once on the UI thread (the field is marked in the same frame); the plan
/// itself runs inline ([`Planner::default`], used by the tests) or on a planning thread
/// ([`Planner::threaded`], used by the window) so that a slow plan never stalls a frame: the
/// plots show the previous plan until the new one arrives.
#[derive(Default)]
pub struct Planner {
    key: Option<(Job, usize)>,
    /// The last valid plan (kept while the job is invalid).
    pub last: Option<Planned>,
    /// Why the current job is invalid.
    pub error: Option<JobError>,
    /// Number of plans requested from the core.
    pub replans: u64,
    /// Duration of the last plan (ms).
    pub plan_ms: f64,
    generation: u64,
    applied: u64,
    worker: Option<PlanWorker>,
}

impl Planner {
    /// A planner computing on its own thread; `repaint` is called when a plan is ready.
    pub fn threaded(repaint: impl Fn() + Send + 'static) -> Planner {
        Planner { worker: PlanWorker::spawn(repaint), ..Planner::default() }
    }

    /// Whether a requested plan has not arrived yet.
    pub fn pending(&self) -> bool {
        self.applied < self.generation
    }

    fn apply(&mut self, generation: u64, planned: Result<Planned, JobError>, ms: f64) {
        if generation < self.applied {
            return;
        }
        self.applied = generation;
        self.plan_ms = ms;
        match planned {
            Ok(p) => self.last = Some(p),
            // Not expected (the job was validated before it was sent); keep the last plan.
            Err(e) => self.error = Some(e),
        }
    }

    /// Collect finished plans from the planning thread.
    pub fn poll(&mut self) {
        let answers: Vec<PlanAnswer> = self.worker.as_ref().map(|w| w.rx.try_iter().collect()).unwrap_or_default();
        for (generation, planned, ms) in answers {
            self.apply(generation, planned, ms);
        }
    }

    /// Replan if `job` differs from the last one; returns whether a plan was requested.
    pub fn update(&mut self, job: &Job, cycles_shown: usize) -> bool {
        self.poll();
        if self.key.as_ref().is_some_and(|(j, c)| j == job && *c == cycles_shown) {
            return false;
        }
        self.key = Some((job.clone(), cycles_shown));
        if let Err(e) = job.validate() {
            self.error = Some(e);
            return false;
        }
        self.error = None;
        self.generation += 1;
        self.replans += 1;
        let first = self.last.is_none();
        if let Some(w) = &self.worker
            && !first
            && w.tx.send((self.generation, job.clone(), cycles_shown)).is_ok()
        {
            return true;
        }
        let (planned, ms) = plan_and_draw(job, cycles_shown);
        self.apply(self.generation, planned, ms);
        true
    }
}

/// A pinned variant with its plan.
pub struct Variant {
    pub label: String,
    pub job: Job,
    pub planned: Planned,
}

/// Native open/save dialogs; tests substitute their own.
pub trait FileDialogs {
    /// Ask for a job file to open.
    fn open_job(&mut self) -> Option<PathBuf>;
    /// Ask where to save the job (`current`: the file last used).
    fn save_job(&mut self, current: Option<&Path>) -> Option<PathBuf>;
    /// Ask where to save an NC program (`stem`: the default file name without extension,
    /// `extension`: the dialect's, without the dot).
    fn save_nc(&mut self, stem: &str, extension: &str) -> Option<PathBuf>;
}

/// rfd dialogs (XDG desktop portal on Linux).
pub struct NativeDialogs;

impl FileDialogs for NativeDialogs {
    fn open_job(&mut self) -> Option<PathBuf> {
        rfd::FileDialog::new().set_title("Open job").add_filter("TrochoPlan job (TOML)", &["toml"]).pick_file()
    }

    fn save_job(&mut self, current: Option<&Path>) -> Option<PathBuf> {
        let mut d = rfd::FileDialog::new().set_title("Save job").add_filter("TrochoPlan job (TOML)", &["toml"]);
        match current {
            Some(p) => {
                if let Some(dir) = p.parent() {
                    d = d.set_directory(dir);
                }
                if let Some(name) = p.file_name() {
                    d = d.set_file_name(name.to_string_lossy());
                }
            }
            None => d = d.set_file_name("job.toml"),
        }
        d.save_file()
    }

    fn save_nc(&mut self, stem: &str, extension: &str) -> Option<PathBuf> {
        rfd::FileDialog::new()
            .set_title("Export NC program")
            .add_filter(format!("NC program (.{extension})"), &[extension])
            .add_filter("All files", &["*"])
            .set_file_name(format!("{stem}.{extension}"))
            .save_file()
    }
}

/// Frame times as egui reports them (CPU time of the previous frame: UI, tessellation, paint).
#[derive(Default)]
struct FrameStats {
    /// (time s, frame ms) of the last two seconds.
    recent: VecDeque<(f64, f32)>,
    /// eframe's report for the previous frame.
    cpu_s: Option<f32>,
    /// Time spent in [`App::show`] this frame (ms).
    ui_ms: f32,
    log: bool,
}

impl FrameStats {
    fn record(&mut self, now: f64, dragging: bool, replanned: bool, plan_ms: f64) {
        if let Some(s) = self.cpu_s {
            let ms = s * 1e3;
            self.recent.push_back((now, ms));
            if self.log {
                eprintln!(
                    "frame_ms={ms:.3} ui_ms={:.3} plan_ms={plan_ms:.3} dragging={dragging} replanned={replanned}",
                    self.ui_ms
                );
            }
        }
        while self.recent.front().is_some_and(|&(t, _)| now - t > 2.0) {
            self.recent.pop_front();
        }
    }

    fn summary(&self) -> Option<(f32, f32)> {
        let last = self.recent.back()?.1;
        Some((last, self.recent.iter().map(|&(_, ms)| ms).fold(0.0, f32::max)))
    }
}

/// The planner application.
pub struct App {
    pub state: State,
    pub planner: Planner,
    pub variants: Vec<Variant>,
    undoer: Undoer<Job>,
    pub anim: Animation,
    pub sweep: Option<SweepRun>,
    /// The Corner tab's last result (planned inline, or on a thread in the window).
    pub corner: panels::corner::CornerView,
    /// The NC program of the current plan and export settings.
    pub export: ExportCache,
    /// The NC program of the Corner tab's plan and its export settings.
    pub corner_nc: panels::corner_nc::CornerNcCache,
    /// The chip of the animated tooth.
    pub chip: Chip,
    dialogs: Box<dyn FileDialogs>,
    /// Last message for the status bar: (text, is_error).
    pub status: Option<(String, bool)>,
    frames: FrameStats,
    /// The job file shown in the window title.
    titled: Option<Option<PathBuf>>,
}

impl App {
    /// The app on `job`, or on the restored `stored` state, planning inline (headless tests).
    #[cfg(test)]
    pub fn new(job: Job, stored: Option<State>, dialogs: Box<dyn FileDialogs>) -> App {
        App::with_planner(job, stored, dialogs, Planner::default())
    }

    /// [`App::new`] with a given planner (the window uses [`Planner::threaded`]).
    pub fn with_planner(job: Job, stored: Option<State>, dialogs: Box<dyn FileDialogs>, planner: Planner) -> App {
        let state = stored.unwrap_or_else(|| State { job, ..State::default() });
        let mut app = App {
            variants: Vec::new(),
            planner,
            undoer: Undoer::default(),
            anim: Animation::default(),
            sweep: None,
            corner: panels::corner::CornerView::default(),
            export: ExportCache::default(),
            corner_nc: panels::corner_nc::CornerNcCache::default(),
            chip: Chip::default(),
            dialogs,
            status: None,
            titled: None,
            frames: FrameStats { log: std::env::var_os(FRAME_LOG_ENV).is_some(), ..FrameStats::default() },
            state,
        };
        let pinned = std::mem::take(&mut app.state.pinned);
        for p in pinned {
            app.pin(p.job, Some(p.label));
        }
        app.planner.update(&app.state.job, app.state.cycles_shown);
        app
    }

    /// Pin `job` (up to [`MAX_VARIANTS`]); false if it is invalid or the list is full.
    fn pin(&mut self, job: Job, label: Option<String>) -> bool {
        if self.variants.len() >= MAX_VARIANTS {
            return false;
        }
        let Ok(p) = plan(&job) else { return false };
        let graphics = Graphics::new(&p, self.state.cycles_shown);
        let label = label.unwrap_or_else(|| compare::variant_label(&job));
        self.variants.push(Variant { label, job, planned: Planned { plan: p, graphics } });
        true
    }

    /// Replace the edited job (one undo step).
    fn set_job(&mut self, job: Job) {
        self.undoer.add_undo(&self.state.job);
        self.state.job = job;
    }

    /// Draw the whole window into `ui` (used by eframe and by the headless tests).
    pub fn show(&mut self, ui: &mut egui::Ui) {
        let t0 = Instant::now();
        let mut cmds: Vec<Command> = Vec::new();
        self.shortcuts(ui, &mut cmds);
        if let Some(run) = &mut self.sweep {
            run.poll();
        }

        egui::Panel::top("menu_bar").show(ui, |ui| self.menu_bar(ui, &mut cmds));
        egui::Panel::bottom("status_bar").show(ui, |ui| self.status_bar(ui));
        // The slot's parameters and derived values mean nothing in the Corner tab (it has its own
        // tool and inputs): it gets the whole width, which its acceptance table needs.
        let slot_panels = self.state.tab != Tab::Corner;
        if slot_panels {
            egui::Panel::left("parameters").resizable(true).default_size(370.0).min_size(300.0).show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    panels::params::show(ui, &mut self.state.job, self.planner.error.as_ref());
                    ui.add_space(8.0);
                    ui.horizontal(|ui| {
                        if ui.add_enabled(self.undoer.has_undo(&self.state.job), egui::Button::new("Undo")).clicked() {
                            cmds.push(Command::Undo);
                        }
                        if ui.add_enabled(self.undoer.has_redo(&self.state.job), egui::Button::new("Redo")).clicked() {
                            cmds.push(Command::Redo);
                        }
                        if ui
                            .button("Reset to paper defaults")
                            .on_hover_text("Wagih et al. (2023) Table 1 conditions")
                            .clicked()
                        {
                            cmds.push(Command::ResetJob);
                        }
                    });
                });
            });
        }
        let replanned = self.planner.update(&self.state.job, self.state.cycles_shown);
        self.undoer.feed_state(ui.input(|i| i.time), &self.state.job);

        if slot_panels {
            egui::Panel::right("derived").resizable(true).default_size(265.0).min_size(210.0).show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    panels::metrics::show(
                        ui,
                        self.planner.last.as_ref().map(|p| &p.plan),
                        self.planner.error.is_some(),
                    );
                });
            });
        }

        if let Some(p) = &self.planner.last {
            let dt = f64::from(ui.input(|i| i.stable_dt).min(0.1));
            self.anim.advance(dt, &p.plan);
            if self.anim.playing {
                ui.ctx().request_repaint();
            }
            match self.anim.cursor(&p.plan) {
                Some(c) => self.chip.update(&p.plan, &p.graphics, c.tooth),
                None => self.chip.clear(),
            }
        }

        egui::CentralPanel::default().show(ui, |ui| self.central(ui, &mut cmds));

        for c in cmds {
            self.apply(c, ui.ctx());
        }
        if self.titled.as_ref() != Some(&self.state.file) {
            let title = match self.state.file.as_ref().and_then(|f| f.file_name()) {
                Some(name) => format!("TrochoPlan - {}", name.to_string_lossy()),
                None => "TrochoPlan".to_owned(),
            };
            ui.ctx().send_viewport_cmd(egui::ViewportCommand::Title(title));
            self.titled = Some(self.state.file.clone());
        }
        self.frames.ui_ms = t0.elapsed().as_secs_f32() * 1e3;
        let dragging = ui.ctx().dragged_id().is_some();
        self.frames.record(ui.input(|i| i.time), dragging, replanned, self.planner.plan_ms);
    }

    fn shortcuts(&self, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
        use egui::{Key, KeyboardShortcut, Modifiers};
        if ui.ctx().memory(|m| m.focused().is_some()) {
            return; // a text field owns the keyboard (and its own undo)
        }
        let table = [
            (KeyboardShortcut::new(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z), Command::Redo),
            (KeyboardShortcut::new(Modifiers::COMMAND, Key::Z), Command::Undo),
            (KeyboardShortcut::new(Modifiers::COMMAND, Key::Y), Command::Redo),
            (KeyboardShortcut::new(Modifiers::COMMAND, Key::O), Command::Open),
            (KeyboardShortcut::new(Modifiers::COMMAND | Modifiers::SHIFT, Key::S), Command::SaveAs),
            (KeyboardShortcut::new(Modifiers::COMMAND, Key::S), Command::Save),
        ];
        for (shortcut, cmd) in table {
            if ui.input_mut(|i| i.consume_shortcut(&shortcut)) {
                cmds.push(cmd);
            }
        }
    }

    fn menu_bar(&mut self, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if ui.button("Open job…  (Ctrl+O)").clicked() {
                    cmds.push(Command::Open);
                }
                if ui.button("Save job  (Ctrl+S)").clicked() {
                    cmds.push(Command::Save);
                }
                if ui.button("Save job as…  (Ctrl+Shift+S)").clicked() {
                    cmds.push(Command::SaveAs);
                }
                ui.separator();
                if ui
                    .button("Export NC…")
                    .on_hover_text("Dialect, tolerance, preview, back-plot and save of the NC program")
                    .clicked()
                {
                    self.state.tab = Tab::Export;
                }
                ui.separator();
                if ui.button("Reset to the paper's default job").clicked() {
                    cmds.push(Command::ResetJob);
                }
            });
            ui.menu_button("Edit", |ui| {
                if ui.add_enabled(self.undoer.has_undo(&self.state.job), egui::Button::new("Undo  (Ctrl+Z)")).clicked()
                {
                    cmds.push(Command::Undo);
                }
                if ui
                    .add_enabled(self.undoer.has_redo(&self.state.job), egui::Button::new("Redo  (Ctrl+Shift+Z)"))
                    .clicked()
                {
                    cmds.push(Command::Redo);
                }
            });
            ui.menu_button("View", |ui| {
                ui.radio_value(&mut self.state.tab, Tab::Plots, "Plots");
                ui.radio_value(&mut self.state.tab, Tab::Compare, "Compare");
                ui.radio_value(&mut self.state.tab, Tab::Sweep, "Sweep");
                ui.radio_value(&mut self.state.tab, Tab::Export, "NC export");
                ui.radio_value(&mut self.state.tab, Tab::Corner, "Corner");
                ui.separator();
                ui.checkbox(&mut self.state.teach, "Teaching: explanations under the plots");
                ui.checkbox(&mut self.state.overlay_pins, "Overlay pinned variants in Plots");
            });
            ui.separator();
            ui.selectable_value(&mut self.state.tab, Tab::Plots, "Plots");
            ui.selectable_value(&mut self.state.tab, Tab::Compare, "Compare");
            ui.selectable_value(&mut self.state.tab, Tab::Sweep, "Sweep");
            ui.selectable_value(&mut self.state.tab, Tab::Export, "Export NC");
            ui.selectable_value(&mut self.state.tab, Tab::Corner, "Corner");
            ui.separator();
            ui.toggle_value(&mut self.state.teach, "Teach")
                .on_hover_text("Explanations with formula and source equation under each plot");
        });
    }

    fn status_bar(&self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            let planning = if self.planner.pending() { " (planning…)" } else { "" };
            ui.label(format!("plan {:.1} ms{planning}", self.planner.plan_ms))
                .on_hover_text(format!("Time of the last core plan() call; {} calls so far.", self.planner.replans));
            ui.separator();
            match self.frames.summary() {
                Some((last, max)) => {
                    ui.label(format!("frame {last:.1} ms (max {max:.1} ms in 2 s)"))
                        .on_hover_text("CPU time of a frame as eframe reports it (UI, tessellation, painting).");
                }
                None => {
                    ui.label(format!("ui {:.1} ms", self.frames.ui_ms));
                }
            }
            if let Some(f) = &self.state.file {
                ui.separator();
                ui.label(format!("file: {}", f.display()));
            }
            if let Some((msg, is_err)) = &self.status {
                ui.separator();
                let color = if *is_err { panels::params::ERROR_COLOR } else { ui.visuals().text_color() };
                ui.colored_label(color, msg);
            }
        });
    }

    fn central(&mut self, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
        match self.state.tab {
            Tab::Plots => {
                ui.horizontal(|ui| {
                    let l = ui.label("cycles drawn");
                    ui.add(egui::DragValue::new(&mut self.state.cycles_shown).range(2..=20))
                        .labelled_by(l.id)
                        .on_hover_text("Cycles of the tool-centre path drawn in the path view");
                    ui.checkbox(&mut self.state.chip_close_up, "chip close-up")
                        .on_hover_text("Chip view: the middle of the chip at 8·h (on) or the whole chip (off)");
                    if !self.variants.is_empty() {
                        ui.checkbox(&mut self.state.overlay_pins, format!("overlay {} pinned", self.variants.len()));
                    }
                });
                let Some(cur) = &self.planner.last else {
                    ui.label("No valid job yet: fix the marked parameter.");
                    return;
                };
                panels::teach::controls(ui, &mut self.anim, &cur.plan);
                let cursor = self.anim.cursor(&cur.plan);
                let layers = layers(&self.planner, &self.variants, self.state.overlay_pins);
                plot_grid(ui, &layers, cursor, &self.chip, self.state.chip_close_up, self.state.teach);
            }
            Tab::Compare => {
                let views: Vec<VariantView> = self
                    .variants
                    .iter()
                    .enumerate()
                    .map(|(i, v)| VariantView {
                        label: &v.label,
                        color: PALETTE[i + 1],
                        metrics: &v.planned.plan.metrics,
                    })
                    .collect();
                let can_pin = self.planner.error.is_none();
                if let Some(c) = compare::show(ui, &views, can_pin) {
                    cmds.push(c);
                }
                ui.separator();
                let cursor = self.planner.last.as_ref().and_then(|p| self.anim.cursor(&p.plan));
                let layers = layers(&self.planner, &self.variants, true);
                plot_grid(ui, &layers, cursor, &self.chip, self.state.chip_close_up, self.state.teach);
            }
            Tab::Sweep => {
                if let Some(c) = panels::sweep::show(ui, &mut self.state.sweep, self.sweep.as_ref(), &self.state.job) {
                    cmds.push(c);
                }
            }
            Tab::Export => {
                self.refresh_export();
                let job_error = self.planner.error.as_ref().map(ToString::to_string);
                if let Some(c) = panels::export::show(ui, &mut self.state.export, &self.export, job_error.as_deref()) {
                    cmds.push(c);
                }
                // settings edited this frame: regenerate now, so the next frame shows them
                self.refresh_export();
            }
            Tab::Corner => {
                self.refresh_corner();
                let (inputs, nc) = (&mut self.state.corner, &mut self.state.corner_nc);
                if let Some(c) = panels::corner::show(ui, inputs, &self.corner, nc, &self.corner_nc) {
                    cmds.push(c);
                }
                // inputs edited this frame: ask for the new plan (and program) now
                self.refresh_corner();
            }
        }
    }

    /// Collect the Corner tab's plans, ask for new ones if its inputs changed, and regenerate
    /// its NC program if the plan or the export settings changed.
    fn refresh_corner(&mut self) {
        self.corner.update(&self.state.corner);
        self.corner_nc.update(&self.corner, self.state.corner.mode, &self.state.corner_nc);
    }

    /// Regenerate the NC program if the plan or the export settings changed.
    fn refresh_export(&mut self) {
        if let Some(p) = &self.planner.last {
            self.export.update(&p.plan, &self.state.export);
        }
    }

    fn apply(&mut self, cmd: Command, ctx: &egui::Context) {
        match cmd {
            Command::Open => {
                if let Some(path) = self.dialogs.open_job() {
                    self.open(&path);
                }
            }
            Command::Save | Command::SaveAs => {
                let target = match (&self.state.file, cmd) {
                    (Some(f), Command::Save) => Some(f.clone()),
                    (f, _) => self.dialogs.save_job(f.as_deref()),
                };
                if let Some(path) = target {
                    self.save_to(&path);
                }
            }
            Command::ResetJob => self.set_job(Job::default()),
            Command::Undo => {
                if let Some(j) = self.undoer.undo(&self.state.job).cloned() {
                    self.state.job = j;
                }
            }
            Command::Redo => {
                if let Some(j) = self.undoer.redo(&self.state.job).cloned() {
                    self.state.job = j;
                }
            }
            Command::Pin => {
                if !self.pin(self.state.job.clone(), None) {
                    self.status = Some(("cannot pin: job invalid or four variants pinned".into(), true));
                }
            }
            Command::PinPaperSet => {
                self.variants.clear();
                let mut failed = 0;
                for job in compare::paper_set(&self.state.job) {
                    failed += usize::from(!self.pin(job, None));
                }
                if failed > 0 {
                    self.status = Some((format!("{failed} of the paper's variants are invalid for this job"), true));
                }
            }
            Command::Unpin(i) => {
                if i < self.variants.len() {
                    self.variants.remove(i);
                }
            }
            Command::ClearPins => self.variants.clear(),
            Command::LoadPinned(i) => {
                if let Some(v) = self.variants.get(i) {
                    let job = v.job.clone();
                    self.set_job(job);
                }
            }
            Command::StartSweep => {
                let ctx = ctx.clone();
                self.sweep = Some(SweepRun::start(&self.state.sweep, &self.state.job, move || ctx.request_repaint()));
            }
            Command::CancelSweep => {
                if let Some(run) = &mut self.sweep {
                    run.cancel();
                }
            }
            Command::ExportNc => self.export_nc(),
            Command::CancelCornerTable => self.corner.table.cancel(),
            Command::RestartCornerTable => self.corner.table.restart(),
            Command::ExportCornerNc => self.export_corner_nc(),
        }
    }

    /// Read a job file into the edited job (one undo step).
    pub fn open(&mut self, path: &Path) {
        let read = std::fs::read_to_string(path)
            .map_err(|e| e.to_string())
            .and_then(|text| Job::from_toml(&text).map_err(|e| e.to_string()));
        match read {
            Ok(job) => {
                self.set_job(job);
                self.state.file = Some(path.to_owned());
                self.status = Some((format!("opened {}", path.display()), false));
            }
            Err(e) => self.status = Some((format!("cannot open {}: {e}", path.display()), true)),
        }
    }

    /// Ask for a file and write the previewed NC program to it (atomically).
    fn export_nc(&mut self) {
        if let Some(e) = &self.planner.error {
            self.status = Some((format!("cannot export: job invalid: {e}"), true));
            return;
        }
        self.refresh_export();
        if let Some(Err(e)) = &self.export.result {
            self.status = Some((format!("cannot export: {e}"), true));
            return;
        }
        let Some(text) = self.export.view().map(|v| v.text.clone()) else { return };
        let Some(path) = self.dialogs.save_nc("slot", self.state.export.dialect.extension()) else { return };
        match write_atomic(&path, text.as_bytes()) {
            Ok(()) => self.status = Some((format!("exported {} ({} bytes)", path.display(), text.len()), false)),
            Err(e) => self.status = Some((e, true)),
        }
    }

    /// Ask for a file and write the Corner tab's previewed NC program to it (atomically).
    fn export_corner_nc(&mut self) {
        self.refresh_corner();
        if let Some(e) = &self.corner.error {
            self.status = Some((format!("cannot export: corner inputs invalid: {e}"), true));
            return;
        }
        let (text, stem) = match &self.corner_nc.result {
            Some(Ok(p)) => (p.text.clone(), p.file_stem),
            Some(Err(e)) => {
                self.status = Some((format!("cannot export: {e}"), true));
                return;
            }
            None => {
                self.status = Some(("cannot export: no corner or pocket planned yet".into(), true));
                return;
            }
        };
        let Some(path) = self.dialogs.save_nc(stem, self.state.corner_nc.dialect.extension()) else { return };
        match write_atomic(&path, text.as_bytes()) {
            Ok(()) => self.status = Some((format!("exported {} ({} bytes)", path.display(), text.len()), false)),
            Err(e) => self.status = Some((e, true)),
        }
    }

    /// Write the edited job as TOML (atomically).
    pub fn save_to(&mut self, path: &Path) {
        match write_atomic(path, self.state.job.to_toml().as_bytes()) {
            Ok(()) => {
                self.state.file = Some(path.to_owned());
                self.status = Some((format!("saved {}", path.display()), false));
            }
            Err(e) => self.status = Some((e, true)),
        }
    }
}

/// The plotted layers: the edited plan (unless it is pinned) and, with `with_pins`, the pinned
/// variants in their table colours. The layer of the edited plan is the primary one (cursor,
/// cooling and h_max annotations), also when it is drawn as one of the pins.
fn layers<'a>(planner: &'a Planner, variants: &'a [Variant], with_pins: bool) -> Vec<Layer<'a>> {
    let current = planner.last.as_ref();
    let is_current = |v: &Variant| current.is_some_and(|p| p.plan.job == v.planned.plan.job);
    let pins: Vec<(usize, &Variant)> = if with_pins { variants.iter().enumerate().collect() } else { Vec::new() };
    let mut out = Vec::new();
    if let Some(p) = current
        && !pins.iter().any(|(_, v)| is_current(v))
    {
        out.push(Layer { name: "current", color: PALETTE[0], g: &p.graphics, w: w_of(&p.plan), primary: true });
    }
    for (i, v) in pins {
        let primary = is_current(v);
        let layer =
            Layer { name: &v.label, color: PALETTE[i + 1], g: &v.planned.graphics, w: w_of(&v.planned.plan), primary };
        if primary { out.insert(0, layer) } else { out.push(layer) }
    }
    out
}

fn w_of(p: &Plan) -> (f64, f64) {
    (p.metrics.waviness_left_mm, p.metrics.waviness_right_mm)
}

/// The four plots in a 2 × 2 grid filling the rest of `ui`; the path view's cell shares its
/// width with the zoomed chip view.
fn plot_grid(
    ui: &mut egui::Ui,
    layers: &[Layer],
    cursor: Option<Cursor>,
    chip: &Chip,
    chip_close_up: bool,
    teach: bool,
) {
    let gap = 8.0;
    let avail = ui.available_size();
    let cell = egui::vec2(((avail.x - gap) / 2.0).max(150.0), ((avail.y - gap) / 2.0).max(140.0));
    let in_sized = |ui: &mut egui::Ui, cell: egui::Vec2, f: &dyn Fn(&mut egui::Ui)| {
        ui.allocate_ui_with_layout(cell, egui::Layout::top_down(egui::Align::Min), |ui| {
            ui.set_min_size(cell);
            ui.set_max_width(cell.x);
            f(ui);
        });
    };
    let in_cell = |ui: &mut egui::Ui, f: &dyn Fn(&mut egui::Ui)| in_sized(ui, cell, f);
    // top row: the path view shares its cell with the chip view, so it gets more of the width
    let wide = egui::vec2(((avail.x - gap) * 0.6).max(300.0), cell.y);
    let narrow = egui::vec2((avail.x - gap - wide.x).max(150.0), cell.y);
    ui.horizontal(|ui| {
        in_sized(ui, wide, &|ui| {
            let w = ui.available_width();
            let chip_w = (0.45 * w).clamp(150.0, 400.0);
            let h = ui.available_height();
            ui.horizontal_top(|ui| {
                let path_w = w - chip_w - ui.spacing().item_spacing.x;
                ui.allocate_ui_with_layout(egui::vec2(path_w, h), egui::Layout::top_down(egui::Align::Min), |ui| {
                    ui.set_min_size(egui::vec2(path_w, h));
                    ui.set_max_width(path_w);
                    plots::path_view(ui, layers, cursor, chip, teach);
                });
                ui.allocate_ui_with_layout(egui::vec2(chip_w, h), egui::Layout::top_down(egui::Align::Min), |ui| {
                    ui.set_min_size(egui::vec2(chip_w, h));
                    ui.set_max_width(chip_w);
                    plots::chip_view(ui, layers, cursor, chip, chip_close_up, teach);
                });
            });
        });
        in_sized(ui, narrow, &|ui| plots::h_plot(ui, layers, cursor, teach));
    });
    ui.add_space(gap);
    ui.horizontal(|ui| {
        in_cell(ui, &|ui| plots::engagement_plot(ui, layers, cursor, teach));
        in_cell(ui, &|ui| plots::wall_plot(ui, layers, teach));
    });
}

impl eframe::App for App {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        self.frames.cpu_s = frame.info().cpu_usage;
        self.show(ui);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        self.state.pinned =
            self.variants.iter().map(|v| PinnedJob { label: v.label.clone(), job: v.job.clone() }).collect();
        eframe::set_value(storage, STORAGE_KEY, &self.state);
    }
}

#[cfg(test)]
#[path = "panels/gui_tests.rs"]
mod gui_tests;
