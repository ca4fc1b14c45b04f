//! Headless GUI tests (egui_kittest, no display): drive the real window contents through the
//! accessibility tree and check the plan and the shown values. This file holds the harness;
//! the tests are grouped by what they drive: `slot` (the slot job's tabs), `window` (tabs,
//! persisted state), `corner` (the Corner tab), `pocket` (the Pocket tab), `operations` (the
//! Operations tab: a part's operations), `program` (the
//! Program tab), `program_frame` (the program's frame), `files` (files without a system
//! dialog), `machine` (forces, machine and optimiser), `levels` (a slot in levels and a closed
//! slot), `limits` (the shop's words and the limits a job exceeds), `words` (no code names in
//! the window or the help), `fit` (the window at common screen sizes, plot legends and colours).

mod corner;
mod files;
mod fit;
mod levels;
mod limits;
mod machine;
mod operations;
mod pocket;
mod program;
mod program_frame;
mod slot;
mod window;
mod words;

use super::panels::label;
use super::*;
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use panels::compare;
use std::path::Path;
use trochoplan_core::{Error, Param};

/// Dialogs answering from fixed paths: tests never open a real dialog.
struct FakeDialogs {
    open: Option<PathBuf>,
    save: Option<PathBuf>,
}

impl FileDialogs for FakeDialogs {
    fn open_job(&mut self) -> Option<PathBuf> {
        self.open.clone()
    }
    fn save_job(&mut self, _current: Option<&Path>) -> Option<PathBuf> {
        self.save.clone()
    }
    fn save_nc(&mut self, _stem: &str, _extension: &str) -> Option<PathBuf> {
        self.save.clone()
    }
    fn open_outline(&mut self) -> Option<PathBuf> {
        self.open.clone()
    }
    fn open_program(&mut self) -> Option<PathBuf> {
        self.open.clone()
    }
}

/// Dialogs of a desktop without a portal: no dialog ever shows, every file goes through the
/// path field.
struct NoPortal;

impl FileDialogs for NoPortal {
    fn open_job(&mut self) -> Option<PathBuf> {
        None
    }
    fn save_job(&mut self, _current: Option<&Path>) -> Option<PathBuf> {
        None
    }
    fn save_nc(&mut self, _stem: &str, _extension: &str) -> Option<PathBuf> {
        None
    }
    fn open_outline(&mut self) -> Option<PathBuf> {
        None
    }
    fn open_program(&mut self) -> Option<PathBuf> {
        None
    }
    fn unavailable(&mut self) -> Option<String> {
        Some("No file dialog appeared".into())
    }
}

/// Replace the open path field's text with `path` and press Enter.
fn type_path(h: &mut Harness<'_, App>, path: &Path) {
    assert!(shows(h, label::PATH_FIELD), "the path field is open");
    h.get_by_label(label::PATH_FIELD).click();
    h.run();
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.get_by_label(label::PATH_FIELD).type_text(&path.display().to_string());
    h.run();
    h.key_press(egui::Key::Enter);
    h.run();
}

fn harness_with(app: App) -> Harness<'static, App> {
    let mut h =
        Harness::builder().with_size(egui::vec2(1400.0, 900.0)).build_ui_state(|ui, app: &mut App| app.show(ui), app);
    h.run();
    h
}

fn harness() -> Harness<'static, App> {
    harness_with(App::new(Job::default(), None, Box::new(FakeDialogs { open: None, save: None })))
}

/// The default job's window whose save dialog answers `file`.
fn harness_saving_to(file: &std::path::Path) -> Harness<'static, App> {
    harness_with(App::new(Job::default(), None, Box::new(FakeDialogs { open: None, save: Some(file.to_owned()) })))
}

fn metrics(h: &Harness<'_, App>) -> trochoplan_core::Metrics {
    h.state().planner.last.as_ref().expect("a plan").plan.metrics.clone()
}

fn shows(h: &Harness<'_, App>, text: &str) -> bool {
    h.query_all_by_label(text).next().is_some()
}

/// Run the command line `trochoplan` built with these tests on `args` (the window's tests
/// compare its files and texts with the command line's; the window does not call the command
/// line's code). `cargo test` builds it next to the test binary, one folder up.
fn command_line(args: &[&str]) -> std::process::Output {
    let exe = std::env::current_exe().expect("test binary");
    let bin = exe.parent().and_then(Path::parent).map(|d| d.join("trochoplan")).expect("target folder");
    assert!(bin.exists(), "{} not built (cargo test builds it)", bin.display());
    std::process::Command::new(&bin).args(args).output().expect("run trochoplan")
}

/// eframe storage in memory.
#[derive(Default)]
struct MemoryStorage(std::collections::HashMap<String, String>);

impl eframe::Storage for MemoryStorage {
    fn get_string(&self, key: &str) -> Option<String> {
        self.0.get(key).cloned()
    }
    fn set_string(&mut self, key: &str, value: String) {
        self.0.insert(key.to_owned(), value);
    }
    fn remove_string(&mut self, key: &str) {
        self.0.remove(key);
    }
    fn flush(&mut self) {}
}

/// Let the undo history settle: the harness advances 0.25 s a step, the undoer records a state
/// that stayed unchanged for 1 s.
fn settle(h: &mut Harness<'_, App>) {
    for _ in 0..6 {
        h.step();
    }
}
