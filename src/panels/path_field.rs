//! The in-window path field: where no system file dialog can be shown (a Linux desktop
//! without an XDG desktop portal, or a dialog that failed), the window asks for the file's path
//! here instead — typed, Enter to confirm, Escape to cancel. What went wrong with the last
//! attempt (no dialog, a file that cannot be read or written) is shown in it, and it stays open
//! until the file is opened or saved or the user cancels: never a silent no-op.

use super::label;
use super::params::ERROR_COLOR;
use eframe::egui::{self, RichText};
use std::path::{Path, PathBuf};

/// What the path is for.
#[derive(Clone, Debug, PartialEq)]
pub enum PathPurpose {
    OpenJob,
    /// Open a part job file into the Operations tab.
    OpenPart,
    SaveJob,
    /// Save an NC program: its text, written when the path is confirmed.
    SaveNc {
        text: String,
    },
    OpenOutline,
    /// Open an NC program into the Program tab's slot (0: A, 1: B).
    OpenProgram(usize),
    /// Open the Program tab's stock outline (`true`) or part outline.
    OpenProgramOutline(bool),
}

impl PathPurpose {
    /// Title of the field's window.
    pub fn title(&self) -> &'static str {
        match self {
            PathPurpose::OpenJob => "Open job",
            PathPurpose::OpenPart => "Open part",
            PathPurpose::SaveJob => "Save job as",
            PathPurpose::SaveNc { .. } => "Save NC program as",
            PathPurpose::OpenOutline => "Open pocket outline",
            PathPurpose::OpenProgram(_) => "Open NC program",
            PathPurpose::OpenProgramOutline(true) => "Open stock outline",
            PathPurpose::OpenProgramOutline(false) => "Open part outline",
        }
    }

    /// The confirm button's label.
    fn confirm(&self) -> &'static str {
        match self {
            PathPurpose::OpenJob
            | PathPurpose::OpenPart
            | PathPurpose::OpenOutline
            | PathPurpose::OpenProgram(_)
            | PathPurpose::OpenProgramOutline(_) => label::PATH_OPEN,
            PathPurpose::SaveJob | PathPurpose::SaveNc { .. } => label::PATH_SAVE,
        }
    }
}

/// An open path field.
#[derive(Clone, Debug, PartialEq)]
pub struct PathPrompt {
    pub purpose: PathPurpose,
    /// The typed path.
    pub text: String,
    /// Why the field is shown, or what went wrong with the last path (error).
    pub message: (String, bool),
    /// Give the text field the keyboard on the next frame.
    focus: bool,
}

/// What the user did with the field this frame.
#[derive(Clone, Debug, PartialEq)]
pub enum PromptAnswer {
    Confirm(PathBuf),
    Cancel,
}

impl PathPrompt {
    /// A field for `purpose`, pre-filled with `suggestion`, saying `why` it is shown.
    pub fn new(purpose: PathPurpose, suggestion: Option<&Path>, why: &str) -> PathPrompt {
        PathPrompt {
            purpose,
            text: suggestion.map(|p| p.display().to_string()).unwrap_or_default(),
            message: (format!("{why}: type the file's path and press Enter."), false),
            focus: true,
        }
    }

    /// Show an error under the field (it stays open).
    pub fn fail(&mut self, message: String) {
        self.message = (message, true);
        self.focus = true;
    }
}

/// The typed `text` as a path: `~/` is the home directory, a relative path is taken from the
/// current directory; empty text is an error.
pub fn typed_path(text: &str) -> Result<PathBuf, String> {
    let t = text.trim();
    if t.is_empty() {
        return Err("type a file path first".into());
    }
    let path = match (t.strip_prefix("~/"), std::env::var_os("HOME")) {
        (Some(rest), Some(home)) => PathBuf::from(home).join(rest),
        _ => PathBuf::from(t),
    };
    if path.is_absolute() {
        return Ok(path);
    }
    let cwd = std::env::current_dir().map_err(|e| format!("no current directory for the relative path {t}: {e}"))?;
    Ok(cwd.join(path))
}

/// The field as a window over the tabs; the user's answer, if any this frame.
pub fn show(ctx: &egui::Context, prompt: &mut PathPrompt) -> Option<PromptAnswer> {
    let mut answer = None;
    egui::Window::new(prompt.purpose.title())
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_TOP, egui::vec2(0.0, 80.0))
        .show(ctx, |ui| {
            let (msg, is_err) = &prompt.message;
            let color = if *is_err { ERROR_COLOR } else { ui.visuals().text_color() };
            ui.label(RichText::new(msg).color(color));
            let l = ui.label(label::PATH_FIELD);
            let field = ui.add(egui::TextEdit::singleline(&mut prompt.text).desired_width(520.0)).labelled_by(l.id);
            if prompt.focus {
                field.request_focus();
                prompt.focus = false;
            }
            let enter = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            let escape = ui.input(|i| i.key_pressed(egui::Key::Escape));
            ui.horizontal(|ui| {
                if ui.button(prompt.purpose.confirm()).clicked() || enter {
                    answer = Some(match typed_path(&prompt.text) {
                        Ok(p) => PromptAnswer::Confirm(p),
                        Err(e) => {
                            prompt.fail(e);
                            return;
                        }
                    });
                }
                if ui.button(label::PATH_CANCEL).clicked() || escape {
                    answer = Some(PromptAnswer::Cancel);
                }
            });
        });
    answer
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typed_paths_are_absolute_and_empty_text_is_an_error() {
        assert!(typed_path("  ").is_err());
        assert_eq!(typed_path("/tmp/a.toml"), Ok(PathBuf::from("/tmp/a.toml")));
        let rel = typed_path("a.toml").expect("relative");
        assert_eq!(rel, std::env::current_dir().expect("cwd").join("a.toml"));
        if let Some(home) = std::env::var_os("HOME") {
            assert_eq!(typed_path("~/x.nc"), Ok(PathBuf::from(home).join("x.nc")));
        }
    }
}
