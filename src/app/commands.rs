//! Commands: what panels ask for that touches files, dialogs, the undo history, pins or
//! threads. They run after all panels have drawn ([`App::apply`]).

use super::panels::compare::{self, MAX_VARIANTS};
use super::panels::corner_nc::NcPreview;
use super::panels::optimise::OptimiseRun;
use super::panels::path_field::PathPurpose;
use super::panels::sweep::SweepRun;
use super::tabs::{TABS, TabSpec};
use super::{App, PinnedJob, Variant};
use crate::shared::files::write_atomic;
use eframe::egui;
use std::path::Path;
use trochoplan_core::Job;

/// Something a panel asks for that touches files, dialogs, the undo history, pins or threads.
#[must_use]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    Open,
    Save,
    SaveAs,
    ResetJob,
    Undo,
    Redo,
    Pin,
    PinPaperSet,
    Unpin(usize),
    ClearPins,
    LoadPinned(usize),
    StartSweep,
    CancelSweep,
    /// Ask for a file and write the previewed NC program.
    ExportNc,
    /// Stop the Corner tab's acceptance table.
    CancelCornerTable,
    /// Compute the acceptance table again.
    RestartCornerTable,
    /// Ask for a file and write the Corner tab's previewed NC program.
    ExportCornerNc,
    /// Ask for a file and write the Pocket tab's previewed NC program.
    ExportPocketNc,
    /// Run the optimiser on a worker thread.
    StartOptimise,
    CancelOptimise,
    /// Load a job of the optimiser's front (`None`: its best job).
    LoadOptimised(Option<usize>),
    /// Ask for a pocket outline (DXF, SVG or points) and put its vertices in the Pocket tab.
    OpenOutline,
    /// Ask for an NC program for the Program tab's slot (0: A, 1: B).
    OpenProgram(usize),
    /// Ask for the Program tab's stock outline.
    OpenProgramStock,
    /// Ask for the Program tab's part outline.
    OpenProgramPart,
    /// The Program tab without a part outline.
    ClearProgramPart,
    /// Verify the Program tab's programs on worker threads.
    StartVerify,
    CancelVerify,
    /// Ask for a part job file for the Operations tab.
    OpenPart,
    /// Open the part's operation (0-based) in its own tab.
    OpenOperation(usize),
    /// Ask for a file and write the part's program.
    ExportPart,
    /// Show the tab at this index of the tab bar ([`TABS`]).
    ShowTab(usize),
    /// Switch the teaching explanations under the plots on or off.
    ToggleTeach,
}

/// The digit keys of the tab shortcuts, Ctrl+1 … Ctrl+9 then Ctrl+0, in the tab bar's order.
const TAB_KEYS: [egui::Key; 10] = {
    use egui::Key::{Num0, Num1, Num2, Num3, Num4, Num5, Num6, Num7, Num8, Num9};
    [Num1, Num2, Num3, Num4, Num5, Num6, Num7, Num8, Num9, Num0]
};

/// The shortcut that switches the teaching explanations on or off.
pub const TEACH_SHORTCUT: egui::KeyboardShortcut = egui::KeyboardShortcut::new(egui::Modifiers::COMMAND, egui::Key::T);

/// The shortcut that shows the tab at `index` of the tab bar, if it has one.
pub fn tab_shortcut(index: usize) -> Option<egui::KeyboardShortcut> {
    TAB_KEYS.get(index).map(|&key| egui::KeyboardShortcut::new(egui::Modifiers::COMMAND, key))
}

impl TabSpec {
    /// The tab's tooltip with its keyboard shortcut (tab bar and View menu).
    pub fn hover_text(&self, ctx: &egui::Context) -> String {
        let index = TABS.iter().position(|t| t.tab == self.tab);
        match index.and_then(tab_shortcut) {
            Some(s) => format!("{} ({})", self.tooltip, ctx.format_shortcut(&s)),
            None => self.tooltip.to_owned(),
        }
    }
}

impl App {
    /// Run `cmd`; `ctx` is the window's (threads ask it to repaint).
    pub(super) fn apply(&mut self, cmd: Command, ctx: &egui::Context) {
        match cmd {
            Command::Open | Command::Save | Command::SaveAs => self.file_command(cmd),
            Command::ResetJob => self.set_job(Job::default()),
            Command::Undo => {
                if let Some(inputs) = self.undoer.undo(&self.state).cloned() {
                    self.state = inputs;
                }
            }
            Command::Redo => {
                if let Some(inputs) = self.undoer.redo(&self.state).cloned() {
                    self.state = inputs;
                }
            }
            Command::Pin | Command::PinPaperSet | Command::Unpin(_) | Command::ClearPins | Command::LoadPinned(_) => {
                self.pin_command(cmd);
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
            Command::ExportPocketNc => self.export_pocket_nc(),
            Command::StartOptimise => {
                let ctx = ctx.clone();
                self.optimise =
                    Some(OptimiseRun::start(&self.state.optimise, &self.state.job, move || ctx.request_repaint()));
            }
            Command::CancelOptimise => {
                if let Some(run) = &mut self.optimise {
                    run.cancel();
                }
            }
            Command::LoadOptimised(i) => {
                let by_force = self.state.optimise.front_by_force;
                let job =
                    self.optimise.as_ref().and_then(|r| i.map_or_else(|| r.best_job(), |i| r.front_job(i, by_force)));
                if let Some(job) = job {
                    self.set_job(job);
                }
            }
            Command::OpenOutline => {
                if let Some(path) = self.ask_path(PathPurpose::OpenOutline, None) {
                    self.open_outline(&path);
                }
            }
            Command::OpenProgram(slot) => {
                if let Some(path) = self.ask_path(PathPurpose::OpenProgram(slot), None) {
                    self.open_program(slot, &path);
                }
            }
            Command::OpenProgramStock | Command::OpenProgramPart => {
                let stock = cmd == Command::OpenProgramStock;
                if let Some(path) = self.ask_path(PathPurpose::OpenProgramOutline(stock), None) {
                    self.open_program_outline(&path, stock);
                }
            }
            Command::ClearProgramPart => self.program.part = None,
            Command::StartVerify => {
                let ctx = ctx.clone();
                self.program.start(&self.state.program, move || ctx.request_repaint());
            }
            Command::CancelVerify => self.program.cancel(),
            Command::OpenPart => self.ask_part(),
            Command::OpenOperation(k) => self.open_operation(k),
            Command::ExportPart => self.export_part(),
            Command::ToggleTeach => self.state.teach = !self.state.teach,
            Command::ShowTab(i) => {
                if let Some(t) = TABS.get(i) {
                    self.view.tab = t.tab;
                }
            }
        }
    }

    /// What runs in the background, for the frame log: whether the slot, the Pocket and the
    /// Corner tab wait for a plan, and the optimiser's progress (0–1, `done` once its result is shown, `-`
    /// when it was not started or was cancelled).
    pub(super) fn background_log(&self) -> String {
        let optimise = match &self.optimise {
            Some(r) if r.running() => format!("{:.3}", r.fraction()),
            Some(r) if r.result.is_some() => "done".to_owned(),
            _ => "-".to_owned(),
        };
        format!(
            "slot_pending={} pocket_pending={} corner_pending={} optimise={optimise}",
            self.planner.pending(),
            self.pocket.pending(),
            self.corner.pending()
        )
    }

    /// The tab shortcuts ([`tab_shortcut`]) and [`TEACH_SHORTCUT`]: they work while a text field
    /// has the keyboard too, as no text field takes Ctrl with a digit or T.
    pub(super) fn tab_shortcuts(&self, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
        if ui.input_mut(|input| input.consume_shortcut(&TEACH_SHORTCUT)) {
            cmds.push(Command::ToggleTeach);
        }
        for i in 0..TABS.len() {
            if let Some(s) = tab_shortcut(i)
                && ui.input_mut(|input| input.consume_shortcut(&s))
            {
                cmds.push(Command::ShowTab(i));
            }
        }
    }

    /// Open, Save and Save as (through the dialogs).
    fn file_command(&mut self, cmd: Command) {
        if cmd == Command::Open {
            if let Some(path) = self.ask_path(PathPurpose::OpenJob, None) {
                self.open(&path);
            }
            return;
        }
        let target = match (&self.view.file, cmd) {
            (Some(f), Command::Save) => Some(f.clone()),
            _ => self.ask_path(PathPurpose::SaveJob, None),
        };
        if let Some(path) = target {
            self.save_to(&path);
        }
    }

    /// The commands of the Compare tab's pins (each one undo step).
    fn pin_command(&mut self, cmd: Command) {
        self.undoer.add_undo(&self.state);
        match cmd {
            Command::Pin => {
                let pinned = self.pin(self.state.job.clone());
                if !pinned {
                    self.status = Some(("cannot pin: job invalid or four variants pinned".into(), true));
                }
            }
            Command::PinPaperSet => {
                self.state.pinned.clear();
                self.variants.clear();
                let failed =
                    compare::paper_set(&self.state.job).into_iter().filter(|job| !self.pin(job.clone())).count();
                if failed > 0 {
                    self.status = Some((format!("{failed} of the paper's variants are invalid for this job"), true));
                }
            }
            Command::Unpin(i) if i < self.state.pinned.len() => {
                self.state.pinned.remove(i);
            }
            Command::ClearPins => self.state.pinned.clear(),
            Command::LoadPinned(i) => {
                if let Some(p) = self.state.pinned.get(i) {
                    self.state.job = p.job.clone();
                }
            }
            _ => {}
        }
    }

    /// Pin `job` (up to [`MAX_VARIANTS`]); false if it is invalid or the list is full.
    fn pin(&mut self, job: Job) -> bool {
        if self.state.pinned.len() >= MAX_VARIANTS {
            return false;
        }
        let pinned = PinnedJob { label: compare::variant_label(&job), job };
        let Some(variant) = Variant::planned(&pinned, self.state.cycles_shown) else { return false };
        self.state.pinned.push(pinned);
        self.variants.push(variant);
        true
    }

    /// Replace the edited job (one undo step).
    pub(super) fn set_job(&mut self, job: Job) {
        self.undoer.add_undo(&self.state);
        self.state.job = job;
    }

    /// Read a job file into the edited job (one undo step).
    pub fn open(&mut self, path: &Path) {
        let read = crate::shared::files::read_input(path, "job file")
            .and_then(|text| Job::from_toml(&text).map_err(|e| e.to_string()));
        match read {
            Ok(job) => {
                self.set_job(job);
                self.view.file = Some(path.to_owned());
                self.remember(path);
                self.status = Some((format!("opened {}", path.display()), false));
            }
            Err(e) => self.status = Some((format!("cannot open {}: {e}", path.display()), true)),
        }
    }

    /// Read a pocket outline (`pocket --polygon`'s formats) into the Pocket tab's vertices.
    pub fn open_outline(&mut self, path: &Path) {
        // the boundary and its islands, as `trochoplan pocket --polygon` reads them: the
        // islands follow the boundary, each after an empty line
        let read = crate::shared::outline::read_pocket(path, "outline");
        match read {
            Ok((points, islands)) => {
                let mut text = crate::shared::outline::points_text(&points);
                for island in &islands {
                    text.push('\n');
                    text.push_str(&crate::shared::outline::points_text(island));
                }
                self.state.pocket.polygon_text = text;
                self.remember(path);
                let with = match islands.len() {
                    0 => String::new(),
                    1 => ", 1 island".to_owned(),
                    n => format!(", {n} islands"),
                };
                self.status =
                    Some((format!("opened outline {} ({} vertices{with})", path.display(), points.len()), false));
            }
            Err(e) => self.status = Some((format!("cannot open {}: {e}", path.display()), true)),
        }
    }

    /// Read an NC program into the Program tab's slot `slot` (0: A, 1: B).
    pub fn open_program(&mut self, slot: usize, path: &Path) {
        let Some(s) = self.program.slots.get_mut(slot) else { return };
        self.status = Some(match s.open(path) {
            Ok(()) => (format!("opened program {}", path.display()), false),
            Err(e) => (format!("cannot open {}: {e}", path.display()), true),
        });
    }

    /// Read the Program tab's stock (`stock`) or part outline.
    pub fn open_program_outline(&mut self, path: &Path, stock: bool) {
        let what = if stock { "stock outline" } else { "part outline" };
        match super::panels::program::Outline::read(path, what) {
            Ok(o) => {
                self.status = Some((format!("opened {what} {}", path.display()), false));
                if stock {
                    self.program.stock = Some(o);
                    self.state.program.stock_from_file = true;
                } else {
                    self.program.part = Some(o);
                }
            }
            Err(e) => self.status = Some((format!("cannot open {}: {e}", path.display()), true)),
        }
    }

    /// Write the edited job as TOML (atomically).
    pub fn save_to(&mut self, path: &Path) {
        match write_atomic(path, self.state.job.to_toml().as_bytes()) {
            Ok(()) => {
                self.view.file = Some(path.to_owned());
                self.remember(path);
                self.status = Some((format!("saved {}", path.display()), false));
            }
            Err(e) => self.status = Some((e, true)),
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
        self.write_nc("slot", self.state.export.dialect.extension(), &text);
    }

    /// Ask for a file and write the Corner tab's previewed NC program to it (atomically).
    fn export_corner_nc(&mut self) {
        self.refresh_corner();
        if let Some(e) = &self.corner.error {
            self.status = Some((format!("cannot export: corner inputs invalid: {e}"), true));
            return;
        }
        let result = self.corner_nc.result.clone();
        self.write_program(result, "corner", self.state.corner_nc.dialect.extension());
    }

    /// Ask for a file and write the Pocket tab's previewed NC program to it (atomically).
    fn export_pocket_nc(&mut self) {
        self.refresh_pocket();
        if let Some(e) = &self.pocket.error {
            self.status = Some((format!("cannot export: pocket inputs invalid: {e}"), true));
            return;
        }
        let result = self.pocket_nc.result.clone();
        self.write_program(result, "pocket", self.state.pocket_nc.dialect.extension());
    }

    /// Save the previewed program `result` of a tab that plans `what` (through [`Self::write_nc`]).
    fn write_program(&mut self, result: Option<Result<NcPreview, String>>, what: &str, extension: &str) {
        match result {
            Some(Ok(p)) => self.write_nc(p.file_stem, extension, &p.text),
            Some(Err(e)) => self.status = Some((format!("cannot export: {e}"), true)),
            None => self.status = Some((format!("cannot export: no {what} planned yet"), true)),
        }
    }

    /// Ask where to save an NC program (`stem`.`extension` proposed) and write `text` there.
    fn write_nc(&mut self, stem: &str, extension: &str, text: &str) {
        let purpose = PathPurpose::SaveNc { text: text.to_owned() };
        if let Some(path) = self.ask_path(purpose, Some((stem, extension))) {
            self.write_nc_to(&path, text);
        }
    }

    /// Write the NC program `text` to `path` (atomically).
    pub(super) fn write_nc_to(&mut self, path: &Path, text: &str) {
        match write_atomic(path, text.as_bytes()) {
            Ok(()) => self.status = Some((format!("exported {} ({} bytes)", path.display(), text.len()), false)),
            Err(e) => self.status = Some((e, true)),
        }
    }
}
