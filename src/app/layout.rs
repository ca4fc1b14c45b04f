//! The window's frame around the tabs: keyboard shortcuts, menu and tab bar, status bar, and the
//! slot's parameter and derived-value panels.

use super::tabs::TABS;
use super::{App, Command, Tab, panels};
use eframe::egui;

impl App {
    /// The keyboard shortcuts (unless a text field has the keyboard).
    pub(super) fn shortcuts(&self, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
        use egui::{Key, KeyboardShortcut, Modifiers};
        if ui.ctx().memory(|m| m.focused().is_some()) {
            return; // a text field owns the keyboard (and its own undo)
        }
        let table = [
            (KeyboardShortcut::new(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z), Command::Redo),
            (KeyboardShortcut::new(Modifiers::COMMAND, Key::Z), Command::Undo),
            (KeyboardShortcut::new(Modifiers::COMMAND, Key::Y), Command::Redo),
            // with Shift before without: a shortcut without Shift matches with it too
            (KeyboardShortcut::new(Modifiers::COMMAND | Modifiers::SHIFT, Key::O), Command::OpenOutline),
            (KeyboardShortcut::new(Modifiers::COMMAND, Key::O), Command::Open),
            (KeyboardShortcut::new(Modifiers::COMMAND | Modifiers::SHIFT, Key::P), Command::OpenPart),
            (KeyboardShortcut::new(Modifiers::COMMAND | Modifiers::SHIFT, Key::S), Command::SaveAs),
            (KeyboardShortcut::new(Modifiers::COMMAND, Key::S), Command::Save),
            (KeyboardShortcut::new(Modifiers::COMMAND, Key::E), self.export_command()),
        ];
        for (shortcut, cmd) in table {
            if ui.input_mut(|i| i.consume_shortcut(&shortcut)) {
                cmds.push(cmd);
            }
        }
    }

    /// The menus, then the tab bar and the teaching toggle.
    pub(super) fn menu_bar(&mut self, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| self.file_menu(ui, cmds));
            ui.menu_button("Edit", |ui| self.undo_buttons(ui, cmds, ["Undo  (Ctrl+Z)", "Redo  (Ctrl+Shift+Z)"]));
            ui.menu_button("View", |ui| {
                for t in &TABS {
                    ui.radio_value(&mut self.view.tab, t.tab, t.label).on_hover_text(t.hover_text(ui.ctx()));
                }
                ui.separator();
                ui.checkbox(&mut self.state.teach, "Teaching: explanations under the plots");
                ui.checkbox(&mut self.state.overlay_pins, "Overlay pinned variants in Plots");
            });
            ui.separator();
            for t in &TABS {
                ui.selectable_value(&mut self.view.tab, t.tab, t.label).on_hover_text(t.hover_text(ui.ctx()));
            }
            ui.separator();
            let teach = ui.ctx().format_shortcut(&super::commands::TEACH_SHORTCUT);
            ui.toggle_value(&mut self.state.teach, "Teach")
                .on_hover_text(format!("Explanations with formula and source equation under each plot ({teach})"));
        });
    }

    fn file_menu(&mut self, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
        if ui.button("Open job…  (Ctrl+O)").clicked() {
            cmds.push(Command::Open);
        }
        if ui.button("Save job  (Ctrl+S)").clicked() {
            cmds.push(Command::Save);
        }
        if ui.button("Save job as…  (Ctrl+Shift+S)").clicked() {
            cmds.push(Command::SaveAs);
        }
        self.recent_menu(ui);
        if ui.button("Open part…  (Ctrl+Shift+P)").on_hover_text(Tab::Operations.spec().tooltip).clicked() {
            cmds.push(Command::OpenPart);
        }
        ui.separator();
        let export = Tab::Export.spec();
        if ui.button(format!("{}…", export.label)).on_hover_text(export.tooltip).clicked() {
            self.view.tab = Tab::Export;
        }
        if ui
            .button("Save NC program…  (Ctrl+E)")
            .on_hover_text("The program of the Corner or Pocket tab when it is shown, else the slot's.")
            .clicked()
        {
            cmds.push(self.export_command());
        }
        if ui.button("Open pocket outline…  (Ctrl+Shift+O)").clicked() {
            cmds.push(Command::OpenOutline);
        }
        ui.separator();
        if ui.button("Reset to the paper's default job").clicked() {
            cmds.push(Command::ResetJob);
        }
    }

    /// Save the NC program of the tab shown: the corner's, the pocket's, else the slot's.
    fn export_command(&self) -> Command {
        match self.view.tab {
            Tab::Corner => Command::ExportCornerNc,
            Tab::Pocket => Command::ExportPocketNc,
            _ => Command::ExportNc,
        }
    }

    /// The recent jobs (`.toml`), part job files and outlines, newest first; a click opens one
    /// as what it was opened as.
    fn recent_menu(&mut self, ui: &mut egui::Ui) {
        use super::panels::path_field::PathPurpose;
        ui.add_enabled_ui(!self.view.recent.is_empty(), |ui| {
            ui.menu_button("Open recent", |ui| {
                for path in self.view.recent.clone() {
                    let purpose = self.recent_purpose(&path);
                    let kind = match purpose {
                        PathPurpose::OpenPart => "part",
                        PathPurpose::OpenJob => "job",
                        _ => "outline",
                    };
                    if ui.button(format!("{} ({kind})", path.display())).clicked() {
                        self.run_path(&purpose, &path);
                    }
                }
            });
        });
    }

    /// The Undo and Redo buttons labelled `labels`, enabled when there is something to undo or
    /// redo.
    fn undo_buttons(&self, ui: &mut egui::Ui, cmds: &mut Vec<Command>, labels: [&str; 2]) {
        if ui.add_enabled(self.undoer.has_undo(&self.state), egui::Button::new(labels[0])).clicked() {
            cmds.push(Command::Undo);
        }
        if ui.add_enabled(self.undoer.has_redo(&self.state), egui::Button::new(labels[1])).clicked() {
            cmds.push(Command::Redo);
        }
    }

    /// The slot's parameters with the Undo, Redo and Reset buttons.
    pub(super) fn parameters_panel(&mut self, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
        #[cfg(test)]
        keep_panel_rect(ui, "parameters");
        egui::ScrollArea::vertical().show(ui, |ui| {
            panels::params::show(ui, &mut self.state.job, self.planner.error.as_ref());
            ui.add_space(8.0);
            ui.horizontal(|ui| {
                self.undo_buttons(ui, cmds, ["Undo", "Redo"]);
                if ui
                    .button("Reset to paper defaults")
                    .on_hover_text("Wagih et al. (2023) Table 1 conditions")
                    .clicked()
                {
                    cmds.push(Command::ResetJob);
                }
            });
        });
    }

    /// The derived values of the edited job.
    pub(super) fn derived_panel(&self, ui: &mut egui::Ui) {
        #[cfg(test)]
        keep_panel_rect(ui, "derived");
        egui::ScrollArea::vertical().show(ui, |ui| {
            panels::metrics::show(ui, self.planner.last.as_ref().map(|p| &p.plan), self.planner.error.is_some());
            if let Some((p, levels)) = self.planner.last.as_ref().and_then(|p| Some((&p.plan, p.levels.as_ref()?))) {
                panels::metrics::show_levels(ui, p, levels);
            }
        });
    }

    /// Plan time, frame time, file and the last message.
    pub(super) fn status_bar(&self, ui: &mut egui::Ui) {
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
            if let Some(f) = &self.view.file {
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
}

/// Keep the rectangle a side panel draws in (`ui`'s clip rectangle), for the tests that check
/// that nothing is cut off at a panel's edge.
#[cfg(test)]
fn keep_panel_rect(ui: &egui::Ui, panel: &str) {
    let rect = ui.clip_rect();
    ui.ctx().data_mut(|d| d.insert_temp(panel_rect_id(panel), rect));
}

/// Where [`keep_panel_rect`] keeps the rectangle of `panel`.
#[cfg(test)]
pub(super) fn panel_rect_id(panel: &str) -> egui::Id {
    egui::Id::NULL.with("panel rect").with(panel)
}
