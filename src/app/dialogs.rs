//! File dialogs behind a trait, so that tests never open one, and what the window does when
//! none can be shown: the in-window path field ([`panels::path_field`]), and the recent files.
//!
//! The native dialogs are rfd's XDG desktop portal backend on Linux (the Windows and macOS
//! dialogs there). Without a portal (a plain X11 desktop) rfd shows nothing and answers "no
//! file" at once; a user cannot cancel a dialog that fast, so an answer within
//! [`QUICK_ANSWER`] counts as "no dialog", and so does a missing session bus: the window then
//! asks for the path in its path field, for this and every later file command.

use super::{App, View, panels};
use panels::path_field::{PathPrompt, PathPurpose, PromptAnswer};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Native open/save dialogs; tests substitute their own.
pub trait FileDialogs {
    /// Ask for a job file to open.
    fn open_job(&mut self) -> Option<PathBuf>;
    /// Ask where to save the job (`current`: the file last used).
    fn save_job(&mut self, current: Option<&Path>) -> Option<PathBuf>;
    /// Ask where to save an NC program (`stem`: the default file name without extension,
    /// `extension`: the dialect's, without the dot).
    fn save_nc(&mut self, stem: &str, extension: &str) -> Option<PathBuf>;
    /// Ask for a pocket outline: a drawing (DXF, SVG) or an "x,y" point list.
    fn open_outline(&mut self) -> Option<PathBuf>;
    /// Ask for an NC program to verify.
    fn open_program(&mut self) -> Option<PathBuf>;
    /// Why the last call that answered `None` showed no dialog, if it showed none (`None`: the
    /// user cancelled it). The window then asks for the path in its path field.
    fn unavailable(&mut self) -> Option<String> {
        None
    }
}

/// An answer faster than this showed no dialog (module docs).
pub const QUICK_ANSWER: Duration = Duration::from_millis(150);

/// rfd dialogs (XDG desktop portal on Linux).
#[derive(Default)]
pub struct NativeDialogs {
    /// Why the last dialog was not shown.
    failed: Option<String>,
}

impl NativeDialogs {
    /// Run the dialog `ask`, noting whether it could have been shown (module docs).
    fn run(&mut self, ask: impl FnOnce() -> Option<PathBuf>) -> Option<PathBuf> {
        self.failed = None;
        if cfg!(target_os = "linux") && !session_bus() {
            self.failed = Some("No file dialog: no desktop session bus for a desktop portal".into());
            return None;
        }
        let t = Instant::now();
        let answer = ask();
        self.failed = not_shown(answer.as_deref(), t.elapsed());
        answer
    }
}

/// Why a dialog that answered `answer` after `elapsed` was not shown: no file, faster than a
/// user can cancel ([`QUICK_ANSWER`]). `None`: it was shown (a file, or a cancel).
fn not_shown(answer: Option<&Path>, elapsed: Duration) -> Option<String> {
    (answer.is_none() && elapsed < QUICK_ANSWER)
        .then(|| "No file dialog appeared (no XDG desktop portal running?)".to_string())
}

/// Whether a desktop session bus can be reached (where a portal would answer): its address in
/// the environment, or the default socket `$XDG_RUNTIME_DIR/bus`.
fn session_bus() -> bool {
    std::env::var_os("DBUS_SESSION_BUS_ADDRESS").is_some()
        || std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|d| Path::new(&d).join("bus").exists())
}

impl FileDialogs for NativeDialogs {
    fn open_job(&mut self) -> Option<PathBuf> {
        self.run(|| {
            rfd::FileDialog::new().set_title("Open job").add_filter("TrochoPlan job (TOML)", &["toml"]).pick_file()
        })
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
        self.run(|| d.save_file())
    }

    fn save_nc(&mut self, stem: &str, extension: &str) -> Option<PathBuf> {
        let d = rfd::FileDialog::new()
            .set_title("Export NC program")
            .add_filter(format!("NC program (.{extension})"), &[extension])
            .add_filter("All files", &["*"])
            .set_file_name(format!("{stem}.{extension}"));
        self.run(|| d.save_file())
    }

    fn open_program(&mut self) -> Option<PathBuf> {
        self.run(|| {
            rfd::FileDialog::new()
                .set_title("Open NC program")
                .add_filter("NC program", &["ngc", "nc", "tap", "gcode", "cnc", "mpf", "txt"])
                .add_filter("All files", &["*"])
                .pick_file()
        })
    }

    fn open_outline(&mut self) -> Option<PathBuf> {
        self.run(|| {
            rfd::FileDialog::new()
                .set_title("Open pocket outline")
                .add_filter("Drawing (DXF, SVG)", &["dxf", "svg"])
                .add_filter("Points x,y", &["txt", "csv", "poly"])
                .add_filter("All files", &["*"])
                .pick_file()
        })
    }

    fn unavailable(&mut self) -> Option<String> {
        self.failed.take()
    }
}

/// Most files in the File menu's recent list.
pub const MAX_RECENT: usize = 8;

impl App {
    /// Ask for a path for `purpose` (`stem`.`extension`: the proposed NC file name): the native
    /// dialog, or, where none can be shown, the path field (then `None` now and the action
    /// runs when the path is confirmed).
    pub(super) fn ask_path(&mut self, purpose: PathPurpose, nc_name: Option<(&str, &str)>) -> Option<PathBuf> {
        if self.no_dialog.is_none() {
            let answer = match (&purpose, nc_name) {
                (PathPurpose::OpenJob | PathPurpose::OpenPart, _) => self.dialogs.open_job(),
                (PathPurpose::SaveJob, _) => self.dialogs.save_job(self.view.file.as_deref()),
                (PathPurpose::SaveNc { .. }, Some((stem, ext))) => self.dialogs.save_nc(stem, ext),
                (PathPurpose::SaveNc { .. }, None) => self.dialogs.save_nc("program", "nc"),
                (PathPurpose::OpenOutline | PathPurpose::OpenProgramOutline(_), _) => self.dialogs.open_outline(),
                (PathPurpose::OpenProgram(_), _) => self.dialogs.open_program(),
            };
            if answer.is_some() {
                return answer;
            }
            self.no_dialog = self.dialogs.unavailable();
            self.no_dialog.as_ref()?; // none: the user cancelled
        }
        let why = self.no_dialog.clone().unwrap_or_default();
        let suggestion = self.suggested_path(&purpose, nc_name);
        self.prompt = Some(PathPrompt::new(purpose, suggestion.as_deref(), &why));
        None
    }

    /// The path the field starts with: the job file, or a file named for the program in the
    /// directory last used; for opening, that directory.
    fn suggested_path(&self, purpose: &PathPurpose, nc_name: Option<(&str, &str)>) -> Option<PathBuf> {
        let dir = self
            .view
            .file
            .as_deref()
            .or(self.view.recent.first().map(PathBuf::as_path))
            .and_then(Path::parent)
            .map(Path::to_path_buf)
            .or_else(|| std::env::current_dir().ok())?;
        Some(match (purpose, nc_name) {
            (PathPurpose::SaveJob, _) => self.view.file.clone().unwrap_or_else(|| dir.join("job.toml")),
            (PathPurpose::SaveNc { .. }, Some((stem, ext))) => dir.join(format!("{stem}.{ext}")),
            _ => dir.join(""),
        })
    }

    /// The path field, if open: run what it was opened for when a path is confirmed; keep it
    /// open with the error when that fails.
    pub(super) fn path_field(&mut self, ctx: &eframe::egui::Context) {
        let Some(prompt) = &mut self.prompt else { return };
        match panels::path_field::show(ctx, prompt) {
            None => {}
            Some(PromptAnswer::Cancel) => self.prompt = None,
            Some(PromptAnswer::Confirm(path)) => {
                let purpose = prompt.purpose.clone();
                self.run_path(&purpose, &path);
                match &self.status {
                    Some((msg, true)) => {
                        let msg = msg.clone();
                        if let Some(p) = &mut self.prompt {
                            p.fail(msg);
                        }
                    }
                    _ => self.prompt = None,
                }
            }
        }
    }

    /// Open or save `path` for `purpose`; the outcome is in the status line.
    pub(super) fn run_path(&mut self, purpose: &PathPurpose, path: &Path) {
        self.status = None;
        match purpose {
            PathPurpose::OpenJob => self.open(path),
            PathPurpose::OpenPart => self.open_part(path),
            PathPurpose::SaveJob => self.save_to(path),
            PathPurpose::SaveNc { text } => self.write_nc_to(path, text),
            PathPurpose::OpenOutline => self.open_outline(path),
            PathPurpose::OpenProgram(slot) => self.open_program(*slot, path),
            PathPurpose::OpenProgramOutline(stock) => self.open_program_outline(path, *stock),
        }
    }

    /// Put `path` first in the recent files (jobs and outlines).
    pub(super) fn remember(&mut self, path: &Path) {
        self.view.recent.retain(|p| p != path);
        self.view.recent.insert(0, path.to_owned());
        self.view.recent.truncate(MAX_RECENT);
        let View { recent, recent_parts, .. } = &mut self.view;
        recent_parts.retain(|p| p != path && recent.contains(p));
    }

    /// Put the part job file `path` first in the recent files, as a part.
    pub(crate) fn remember_part(&mut self, path: &Path) {
        self.remember(path);
        self.view.recent_parts.push(path.to_owned());
    }

    /// What the recent file `path` is opened as: a part job file, a job or an outline.
    pub(super) fn recent_purpose(&self, path: &Path) -> PathPurpose {
        if self.view.recent_parts.iter().any(|p| p == path) {
            PathPurpose::OpenPart
        } else if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("toml")) {
            PathPurpose::OpenJob
        } else {
            PathPurpose::OpenOutline
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_instant_no_is_no_dialog_and_a_slow_one_a_cancel() {
        assert!(not_shown(None, Duration::from_millis(5)).is_some());
        assert_eq!(not_shown(None, Duration::from_secs(2)), None, "the user cancelled");
        assert_eq!(not_shown(Some(Path::new("/tmp/a.toml")), Duration::from_millis(5)), None);
    }
}
