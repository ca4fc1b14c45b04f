//! The planner window (eframe/egui).
//!
//! Architecture (docs/architecture.md): the user's [`Inputs`] and the [`View`] are
//! persisted by eframe ([`State`]), and one undo history covers the inputs; [`App`] keeps the
//! last plan ([`Planner`], on a [`crate::worker::Worker`]) and replans only when the job
//! changed, keeping the last *valid* plan on screen while the job is invalid. The tabs are
//! listed once ([`tabs::TABS`]). Panels (`src/panels/`) are functions that edit the inputs or
//! return a [`Command`]; commands (files, undo/redo, pins, sweeps) run after all panels have
//! drawn, and only they touch files or dialogs — dialogs sit behind the [`FileDialogs`] trait so
//! tests never open one.
//!
//! Modules: `state` (what is persisted; `earlier` moves the pocket of states stored before
//! the Pocket tab), `planner`, `commands`, `tabs` (the tab list and each
//! tab's central panel), `layout` (menus, side panels, status bar), `dialogs`, `frames`.

#[path = "../panels/mod.rs"]
pub(crate) mod panels;

mod commands;
mod dialogs;
mod earlier;
mod frames;
mod layout;
mod planner;
mod state;
mod tabs;

pub use commands::Command;
pub use dialogs::{FileDialogs, NativeDialogs};
pub use planner::{Planned, Planner};
pub use state::{Inputs, PinnedJob, State, Tab, View};

use eframe::egui;
use egui::util::undoer::Undoer;
use frames::FrameStats;
use panels::compare::MAX_VARIANTS;
use panels::export::ExportCache;
use panels::graphics::{Chip, Graphics};
use panels::sweep::SweepRun;
use panels::teach::Animation;
use std::path::PathBuf;
use std::time::Instant;
use trochoplan_core::{Job, plan};

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
            let stored = cc.storage.and_then(State::load);
            let stored = stored.map(|s| if job == Job::default() { s } else { s.with_job(job.clone()) });
            let ctx = cc.egui_ctx.clone();
            let planner = Planner::threaded(move || ctx.request_repaint());
            let mut app = App::with_planner(job, stored, Box::new(NativeDialogs::default()), planner);
            let ctx = cc.egui_ctx.clone();
            app.corner = panels::corner::CornerView::threaded(move || ctx.request_repaint());
            let ctx = cc.egui_ctx.clone();
            app.pocket = panels::pocket::PocketView::threaded(move || ctx.request_repaint());
            let ctx = cc.egui_ctx.clone();
            app.operations = panels::operations::PartView::threaded(move || ctx.request_repaint());
            app.reopen_part();
            app.preload_program(&cc.egui_ctx);
            Ok(Box::new(app))
        }),
    )
}

/// Environment variables that open programs in the Program tab at start and verify them (the
/// screenshots use them): program A and B, the stock and part outlines, a machine preset.
const PROGRAM_ENV: [&str; 5] = [
    "TROCHOPLAN_PROGRAM_A",
    "TROCHOPLAN_PROGRAM_B",
    "TROCHOPLAN_PROGRAM_STOCK",
    "TROCHOPLAN_PROGRAM_PART",
    "TROCHOPLAN_PROGRAM_MACHINE",
];

/// A pinned variant with its plan.
pub struct Variant {
    pub label: String,
    pub job: Job,
    pub planned: Planned,
}

impl Variant {
    /// The variant of `pinned` drawn with `cycles_shown` cycles; `None` if its job is invalid.
    fn planned(pinned: &PinnedJob, cycles_shown: usize) -> Option<Variant> {
        let p = plan(&pinned.job).ok()?;
        let graphics = Graphics::new(&p, cycles_shown);
        let planned = Planned { plan: p, graphics, levels: None };
        Some(Variant { label: pinned.label.clone(), job: pinned.job.clone(), planned })
    }

    fn is(&self, pinned: &PinnedJob) -> bool {
        self.label == pinned.label && self.job == pinned.job
    }
}

/// The planner application.
pub struct App {
    /// The user's inputs; undo and redo restore them.
    pub state: Inputs,
    /// The selected tab and the job file.
    pub view: View,
    pub planner: Planner,
    /// The plans of `state.pinned`.
    pub variants: Vec<Variant>,
    undoer: Undoer<Inputs>,
    pub anim: Animation,
    pub sweep: Option<SweepRun>,
    /// The optimiser's run.
    pub optimise: Option<panels::optimise::OptimiseRun>,
    /// The Corner tab's last result (planned inline, or on a thread in the window).
    pub corner: panels::corner::CornerView,
    /// The NC program of the current plan and export settings.
    pub export: ExportCache,
    /// The NC program of the Corner tab's plan and its export settings.
    pub corner_nc: panels::corner_nc::CornerNcCache,
    /// The Pocket tab's last pocket (planned inline, or on a thread in the window).
    pub pocket: panels::pocket::PocketView,
    /// The NC program of the Pocket tab's pocket and its export settings.
    pub pocket_nc: panels::corner_nc::CornerNcCache,
    /// The chip of the animated tooth.
    pub chip: Chip,
    /// The Program tab's programs and their verifications.
    pub program: panels::program::ProgramTab,
    /// The Operations tab's part and its plans.
    pub operations: panels::operations::PartView,
    dialogs: Box<dyn FileDialogs>,
    /// Why no file dialog can be shown, once one failed: file commands then ask in the path
    /// field.
    no_dialog: Option<String>,
    /// The open path field, if any.
    prompt: Option<panels::path_field::PathPrompt>,
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
        let State { inputs, view } = stored.unwrap_or_else(|| State::default().with_job(job));
        let mut app = App {
            state: inputs,
            view,
            variants: Vec::new(),
            planner,
            undoer: Undoer::default(),
            anim: Animation::default(),
            sweep: None,
            optimise: None,
            corner: panels::corner::CornerView::default(),
            export: ExportCache::default(),
            corner_nc: panels::corner_nc::CornerNcCache::default(),
            pocket: panels::pocket::PocketView::default(),
            pocket_nc: panels::corner_nc::CornerNcCache::default(),
            chip: Chip::default(),
            program: panels::program::ProgramTab::default(),
            operations: panels::operations::PartView::default(),
            dialogs,
            no_dialog: None,
            prompt: None,
            status: None,
            titled: None,
            frames: FrameStats::new(std::env::var_os(FRAME_LOG_ENV).is_some()),
        };
        app.sync_variants();
        app.planner.update(&app.state.job, app.state.cycles_shown);
        app
    }

    /// Bring the plans of the pinned variants in line with `state.pinned` (after undo, redo or
    /// a restored session): keep the plans of jobs still pinned, plan the new ones, and unpin
    /// jobs that are invalid or beyond [`MAX_VARIANTS`].
    fn sync_variants(&mut self) {
        let pinned = &self.state.pinned;
        if self.variants.len() == pinned.len() && self.variants.iter().zip(pinned).all(|(v, p)| v.is(p)) {
            return;
        }
        let mut old = std::mem::take(&mut self.variants);
        let cycles_shown = self.state.cycles_shown;
        self.state.pinned.truncate(MAX_VARIANTS);
        self.state.pinned.retain(|p| {
            let kept = old.iter().position(|v| v.is(p)).map(|i| old.swap_remove(i));
            match kept.or_else(|| Variant::planned(p, cycles_shown)) {
                Some(v) => {
                    self.variants.push(v);
                    true
                }
                None => false,
            }
        });
    }

    /// Draw the whole window into `ui` (used by eframe and by the headless tests).
    pub fn show(&mut self, ui: &mut egui::Ui) {
        let t0 = Instant::now();
        let mut cmds: Vec<Command> = Vec::new();
        self.shortcuts(ui, &mut cmds);
        self.tab_shortcuts(ui, &mut cmds);
        if let Some(run) = &mut self.sweep {
            run.poll();
        }
        if let Some(run) = &mut self.optimise {
            run.poll();
        }
        self.program.poll();

        egui::Panel::top("menu_bar").show(ui, |ui| self.menu_bar(ui, &mut cmds));
        egui::Panel::bottom("status_bar").show(ui, |ui| self.status_bar(ui));
        let slot_panels = self.view.tab.spec().slot_panels;
        if slot_panels {
            egui::Panel::left("parameters")
                .resizable(true)
                .default_size(370.0)
                .min_size(300.0)
                .show(ui, |ui| self.parameters_panel(ui, &mut cmds));
        }
        let replanned = self.planner.update(&self.state.job, self.state.cycles_shown);
        if slot_panels {
            egui::Panel::right("derived")
                .resizable(true)
                .default_size(265.0)
                .min_size(210.0)
                .show(ui, |ui| self.derived_panel(ui));
        }
        self.animate(ui);
        egui::CentralPanel::default().show(ui, |ui| (self.view.tab.spec().show)(self, ui, &mut cmds));
        self.path_field(ui.ctx());

        for c in cmds {
            self.apply(c, ui.ctx());
        }
        self.sync_variants();
        self.undoer.feed_state(ui.input(|i| i.time), &self.state);
        self.update_title(ui.ctx());
        self.frames.ui_ms = t0.elapsed().as_secs_f32() * 1e3;
        let dragging = ui.ctx().dragged_id().is_some();
        let background = if self.frames.log { self.background_log() } else { String::new() };
        self.frames.record(ui.input(|i| i.time), dragging, replanned, self.planner.plan_ms, &background);
    }

    /// Open the programs, outlines and machine named by [`PROGRAM_ENV`], if program A is named:
    /// show the Program tab and start verifying.
    fn preload_program(&mut self, ctx: &egui::Context) {
        let [a, b, stock, part, machine] = PROGRAM_ENV.map(std::env::var_os);
        let Some(a) = a else { return };
        self.view.tab = Tab::Program;
        self.open_program(0, std::path::Path::new(&a));
        if let Some(b) = b {
            self.open_program(1, std::path::Path::new(&b));
        }
        if let Some(f) = stock {
            self.open_program_outline(std::path::Path::new(&f), true);
        }
        if let Some(f) = part {
            self.open_program_outline(std::path::Path::new(&f), false);
        }
        if let Some(m) = machine {
            self.state.program.machine = Some(m.to_string_lossy().into_owned());
        }
        let ctx = ctx.clone();
        self.program.start(&self.state.program, move || ctx.request_repaint());
    }

    /// Advance the teaching animation and the chip of its tooth.
    fn animate(&mut self, ui: &egui::Ui) {
        let Some(p) = &self.planner.last else { return };
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

    /// Show the job file's name in the window title when it changed.
    fn update_title(&mut self, ctx: &egui::Context) {
        if self.titled.as_ref() == Some(&self.view.file) {
            return;
        }
        let title = match self.view.file.as_ref().and_then(|f| f.file_name()) {
            Some(name) => format!("TrochoPlan - {}", name.to_string_lossy()),
            None => "TrochoPlan".to_owned(),
        };
        ctx.send_viewport_cmd(egui::ViewportCommand::Title(title));
        self.titled = Some(self.view.file.clone());
    }

    /// Collect the Corner tab's plans, ask for new ones if its inputs changed, and regenerate
    /// its NC program if the plan or the export settings changed.
    fn refresh_corner(&mut self) {
        use panels::corner::CornerMode;
        use panels::corner_nc::Source;
        self.state.corner.feed_mm_per_min = self.state.job.feed;
        self.state.corner_nc.spindle_rpm = self.state.job.rpm;
        self.state.corner_nc.frame.clone_from(&self.state.job.program);
        self.corner.update(&self.state.corner);
        let source = match self.state.corner.mode {
            CornerMode::Corner => self.corner.last.clone().map(Source::Corner),
            CornerMode::Table => None,
        };
        self.corner_nc.update(source, &self.state.corner_nc);
    }

    /// Collect the Pocket tab's plans, ask for a new one if its inputs changed, and regenerate
    /// its NC program if the pocket or the export settings changed.
    fn refresh_pocket(&mut self) {
        let job = &self.state.job;
        (self.state.pocket.feed_mm_per_min, self.state.pocket.spindle_rpm) = (job.feed, job.rpm);
        (self.state.pocket.teeth, self.state.pocket.tool_diameter_mm) = (job.teeth, job.tool_diameter);
        self.state.pocket.depth_mm = self.state.pocket_nc.depth_mm;
        self.state.pocket.safe_z_mm = job.program.retract_height_mm();
        self.state.pocket_nc.spindle_rpm = job.rpm;
        self.state.pocket_nc.frame.clone_from(&job.program);
        self.pocket.update(&self.state.pocket);
        let source = self.pocket.last.clone().map(panels::corner_nc::Source::Pocket);
        self.pocket_nc.update(source, &self.state.pocket_nc);
    }

    /// Regenerate the NC program if the plan or the export settings changed.
    fn refresh_export(&mut self) {
        self.state.export.frame.clone_from(&self.state.job.program);
        if let Some(p) = &self.planner.last {
            self.export.update(&p.plan, p.levels.as_ref(), &self.state.export);
        }
    }
}

impl eframe::App for App {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        self.frames.cpu_s = frame.info().cpu_usage;
        self.show(ui);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        State::save(&self.state, &self.view, storage);
    }
}

#[cfg(test)]
#[path = "../panels/gui_tests/mod.rs"]
mod gui_tests;
