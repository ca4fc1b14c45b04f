//! The Program tab: open an NC program (and a second one to compare), its stock, part, tool,
//! material and machine; verify it in the background with progress and cancel; the path
//! coloured by engagement, chip thickness or force, the quantity over time with the tool's
//! position, the problems with the program's lines, and the summaries of both programs side by
//! side.

use super::Command;
use super::label;
use super::program::{ProgramSettings, ProgramTab, Quantity, Shown, Verified};
use super::program_plots::{PathClick, path_plot, scale_max, time_plot};
use eframe::egui::{self, Color32, RichText};
use std::sync::Arc;
use trochoplan_core::verify::{Problem, ProblemKind};

const ERROR: Color32 = Color32::from_rgb(200, 40, 30);
const HIGHLIGHT: Color32 = Color32::from_rgb(255, 230, 120);

/// The slots' names.
pub const SLOT_NAMES: [&str; 2] = ["A", "B"];

/// Draw the tab.
pub fn show(ui: &mut egui::Ui, s: &mut ProgramSettings, tab: &mut ProgramTab) -> Vec<Command> {
    let mut cmds = Vec::new();
    files_row(ui, s, tab, &mut cmds);
    tool_row(ui, s, tab, &mut cmds);
    ui.horizontal_wrapped(|ui| {
        ui.label("Show:");
        ui.radio_value(&mut tab.shown, Shown::A, "program A");
        ui.radio_value(&mut tab.shown, Shown::B, "program B");
        ui.radio_value(&mut tab.shown, Shown::Both, "A and B side by side");
        ui.separator();
        ui.label("Colour by:");
        for q in Quantity::ALL {
            ui.radio_value(&mut tab.quantity, q, q.label()).on_hover_text(q.tooltip());
        }
    });
    for (i, slot) in tab.slots.iter().enumerate() {
        let err = slot.load_error.as_ref().or(slot.result.as_ref().and_then(|r| r.as_ref().err()));
        if let Some(e) = err {
            ui.label(RichText::new(format!("Program {}: {e}", SLOT_NAMES[i])).color(ERROR));
        }
    }
    if let Some(e) = &tab.error {
        ui.label(RichText::new(e).color(ERROR));
    }
    ui.separator();
    match tab.shown {
        Shown::Both => both(ui, tab),
        Shown::A | Shown::B => single(ui, tab),
    }
    cmds
}

/// Program, stock and part files.
fn files_row(ui: &mut egui::Ui, s: &mut ProgramSettings, tab: &ProgramTab, cmds: &mut Vec<Command>) {
    ui.horizontal_wrapped(|ui| {
        for (i, open) in [label::OPEN_PROGRAM_A, label::OPEN_PROGRAM_B].into_iter().enumerate() {
            if ui.button(open).on_hover_text("Read a G-code program (LinuxCNC, Fanuc, GRBL or Sinumerik)").clicked() {
                cmds.push(Command::OpenProgram(i));
            }
            let name = tab.slots[i].loaded.as_ref().map_or("none".to_owned(), |p| p.name());
            ui.label(RichText::new(name).strong());
            ui.separator();
        }
        ui.label("Stock:");
        ui.radio_value(&mut s.stock_from_file, true, "outline")
            .on_hover_text("The material before the program: for a pocket, its outline");
        ui.radio_value(&mut s.stock_from_file, false, "box");
        if s.stock_from_file {
            if ui.button(label::OPEN_STOCK).clicked() {
                cmds.push(Command::OpenProgramStock);
            }
            ui.label(tab.stock.as_ref().map_or("none".to_owned(), |o| file_name(&o.path)));
        } else {
            for (v, name) in s.stock_box.iter_mut().zip(["X min", "Y min", "X max", "Y max"]) {
                let l = ui.label(name);
                ui.add(egui::DragValue::new(v).speed(0.5).suffix(" mm")).labelled_by(l.id);
            }
        }
        let l = ui.label("top at Z");
        ui.add(egui::DragValue::new(&mut s.stock_top_mm).speed(0.1).suffix(" mm"))
            .labelled_by(l.id)
            .on_hover_text("Height of the stock's top face: the program cuts below it");
        ui.separator();
        if ui
            .button(label::OPEN_PART)
            .on_hover_text("The finished outline whose walls the tool must not cut into (optional)")
            .clicked()
        {
            cmds.push(Command::OpenProgramPart);
        }
        match &tab.part {
            Some(o) => {
                ui.label(file_name(&o.path));
                if ui.small_button("×").on_hover_text("No part outline: walls not checked").clicked() {
                    cmds.push(Command::ClearProgramPart);
                }
            }
            None => {
                ui.label("none");
            }
        }
    });
}

fn file_name(p: &std::path::Path) -> String {
    p.file_name().map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into_owned())
}

/// Tool, material, machine, spindle speed; Verify or Cancel with the progress.
fn tool_row(ui: &mut egui::Ui, s: &mut ProgramSettings, tab: &ProgramTab, cmds: &mut Vec<Command>) {
    let running = tab.running();
    ui.horizontal_wrapped(|ui| {
        ui.add_enabled_ui(!running, |ui| {
            let l = ui.label("Tool diameter");
            ui.add(egui::DragValue::new(&mut s.tool_diameter_mm).range(0.1..=1000.0).speed(0.1).suffix(" mm"))
                .labelled_by(l.id);
            let l = ui.label("Teeth");
            ui.add(egui::DragValue::new(&mut s.teeth).range(1..=64)).labelled_by(l.id);
            let l = ui.label("Helix angle");
            ui.add(egui::DragValue::new(&mut s.helix_deg).range(0.0..=60.0).speed(0.5).suffix("°")).labelled_by(l.id);
            let lib = trochoplan_core::material::Library::builtin();
            let shown = lib.get(&s.material).map_or(s.material.clone(), |m| m.label.clone());
            egui::ComboBox::from_label("material").selected_text(shown).show_ui(ui, |ui| {
                for m in &lib.materials {
                    ui.selectable_value(&mut s.material, m.name.clone(), &m.label);
                }
            });
            let shown = s.machine.clone().unwrap_or_else(|| "ideal (programmed feed)".into());
            egui::ComboBox::from_label("machine")
                .selected_text(shown)
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut s.machine, None, "ideal (programmed feed)");
                    for n in trochoplan_core::machine::preset_names() {
                        ui.selectable_value(&mut s.machine, Some(n.to_owned()), n);
                    }
                })
                .response
                .on_hover_text(
                    "The machine's accelerations give the real time and the feed it reaches; its spindle's \
                     power and torque are the limits",
                );
            ui.checkbox(&mut s.rpm_override, "spindle speed")
                .on_hover_text("Use this spindle speed instead of the program's S words");
            ui.add_enabled(
                s.rpm_override,
                egui::DragValue::new(&mut s.rpm).range(1.0..=1.0e6).speed(50.0).suffix(" rpm"),
            );
        });
        if running {
            if ui.button(label::CANCEL_VERIFY).clicked() {
                cmds.push(Command::CancelVerify);
            }
            for (i, slot) in tab.slots.iter().enumerate() {
                if let Some(run) = slot.run.as_ref().filter(|r| r.running()) {
                    ui.label(SLOT_NAMES[i]);
                    ui.add(egui::ProgressBar::new(run.fraction()).desired_width(120.0).show_percentage());
                }
            }
        } else {
            let any = tab.slots.iter().any(|s| s.loaded.is_some());
            if ui
                .add_enabled(any, egui::Button::new(label::VERIFY))
                .on_hover_text("Measure every move of the programs over the stock (in the background)")
                .clicked()
            {
                cmds.push(Command::StartVerify);
            }
            let cancelled: Vec<_> = tab.slots.iter().filter_map(|s| s.run.as_ref().filter(|r| r.cancelled)).collect();
            // a run that started stops at its next progress report (after the bands of the stock
            // at the latest)
            if cancelled.iter().any(|r| r.started() && r.stopped().is_none()) {
                ui.label("Stopping…");
            } else if !cancelled.is_empty() {
                ui.label("Cancelled.");
            }
        }
    });
}

/// One program: path and time plot on the left; summary, problems and program text on the right.
fn single(ui: &mut egui::Ui, tab: &mut ProgramTab) {
    let i = tab.shown_slot();
    let Some(v) = tab.slots[i].verified().cloned() else {
        ui.label(match (&tab.slots[i].loaded, tab.slots[i].running()) {
            (None, _) => "Open a program, its stock, then Verify.",
            (Some(_), true) => "Verifying…",
            (Some(_), false) => "Press Verify.",
        });
        return;
    };
    let avail = ui.available_size();
    let left = egui::vec2((avail.x * 0.58).max(300.0), avail.y);
    let right = egui::vec2((avail.x - left.x - 8.0).max(200.0), avail.y);
    let q = tab.quantity;
    let max = scale_max(q, &both_verified(tab).iter().map(|v| &**v).collect::<Vec<_>>());
    let selected = tab.selected.and_then(|p| v.report.problems.get(p));
    let mark = selected.map(|p| [p.x, p.y]);
    ui.horizontal_top(|ui| {
        ui.allocate_ui_with_layout(left, egui::Layout::top_down(egui::Align::Min), |ui| {
            let path_h = (left.y * 0.62).max(200.0);
            ui.allocate_ui(egui::vec2(left.x, path_h), |ui| {
                ui.set_min_size(egui::vec2(left.x, path_h));
                let cursor = v.position_at(tab.cursor_s);
                if let Some(PathClick::Move(k)) = path_plot(ui, &format!("program_path_{i}"), &v, q, max, cursor, mark)
                {
                    tab.cursor_s = v.middle_s(k);
                }
            });
            position_slider(ui, &v, &mut tab.cursor_s);
            if let Some(t) = time_plot(ui, &format!("program_time_{i}"), &v, q, tab.cursor_s) {
                tab.cursor_s = t;
            }
        });
        ui.allocate_ui_with_layout(right, egui::Layout::top_down(egui::Align::Min), |ui| {
            ui.set_min_size(right);
            summary_table(ui, tab);
            ui.separator();
            if let Some(k) = problems_list(ui, &v.report.problems, tab.selected) {
                tab.selected = Some(k);
                tab.scroll_to_selected = true;
                let p = &v.report.problems[k];
                if let Some(m) = v.move_of_line(p.line) {
                    tab.cursor_s = v.middle_s(m);
                }
            }
            ui.separator();
            if let Some(loaded) = &tab.slots[i].loaded {
                let line =
                    selected.map(|p| p.line).or_else(|| v.move_at(tab.cursor_s).map(|(k, _)| v.report.moves[k].line));
                let scroll = std::mem::take(&mut tab.scroll_to_selected);
                program_text(ui, loaded, line, scroll, i);
            }
        });
    });
}

/// The finished verifications of both slots.
fn both_verified(tab: &ProgramTab) -> Vec<Arc<Verified>> {
    tab.slots.iter().filter_map(|s| s.verified().cloned()).collect()
}

/// The slider of the position in the program.
fn position_slider(ui: &mut egui::Ui, v: &Verified, cursor_s: &mut f64) {
    ui.horizontal(|ui| {
        let l = ui.label(label::POSITION);
        ui.spacing_mut().slider_width = (ui.available_width() - 200.0).max(100.0);
        ui.add(egui::Slider::new(cursor_s, 0.0..=v.total_s.max(1e-9)).suffix(" s"))
            .labelled_by(l.id)
            .on_hover_text("Where the tool is: drag, or click the time plot or the path");
        if let Some((k, _)) = v.move_at(*cursor_s) {
            ui.label(format!("line {}", v.report.moves[k].line));
        }
    });
}

/// Both paths side by side on one colour scale, and the summaries.
fn both(ui: &mut egui::Ui, tab: &mut ProgramTab) {
    let q = tab.quantity;
    let verified: Vec<Option<Arc<Verified>>> = tab.slots.iter().map(|s| s.verified().cloned()).collect();
    let max = scale_max(q, &verified.iter().flatten().map(|v| &**v).collect::<Vec<_>>());
    let avail = ui.available_size();
    let cell = egui::vec2(((avail.x - 8.0) / 2.0).max(200.0), (avail.y * 0.62).max(200.0));
    ui.horizontal_top(|ui| {
        for (i, v) in verified.iter().enumerate() {
            ui.allocate_ui_with_layout(cell, egui::Layout::top_down(egui::Align::Min), |ui| {
                ui.set_min_size(cell);
                let name = tab.slots[i].loaded.as_ref().map_or("none".to_owned(), |p| p.name());
                ui.label(RichText::new(format!("{}: {name}", SLOT_NAMES[i])).strong());
                match v {
                    Some(v) => {
                        path_plot(ui, &format!("program_both_{i}"), v, q, max, None, None);
                    }
                    None => {
                        ui.label(if tab.slots[i].running() { "Verifying…" } else { "Not verified." });
                    }
                }
            });
        }
    });
    ui.separator();
    summary_table(ui, tab);
}

/// The summaries of A and B side by side.
fn summary_table(ui: &mut egui::Ui, tab: &ProgramTab) {
    let v: Vec<Option<Arc<Verified>>> = tab.slots.iter().map(|s| s.verified().cloned()).collect();
    type Row = (&'static str, &'static str, fn(&Verified) -> String);
    let rows: [Row; 11] = [
        ("Largest engagement (°)", "Largest engagement of the cuts at one height", |v| {
            format!("{:.1}", v.report.plane.max_engagement_deg)
        }),
        ("Engagement, 95 % of the cut (°)", "95 % of the cutting length engages less than this", |v| {
            format!("{:.1}", v.report.p95_engagement_deg)
        }),
        ("Thickest chip h_max (mm)", "At the feed the machine reaches", |v| format!("{:.4}", v.report.plane.h_max_mm)),
        ("Largest cutting force (N)", "Resultant force on the tool", |v| {
            format!("{:.0}", v.report.plane.force_resultant_max_n)
        }),
        ("Largest spindle power (W)", "Power the spindle gives at the most loaded place", |v| {
            format!("{:.0}", v.report.plane.power_max_w)
        }),
        ("Run time (min)", "On the chosen machine (ideal: at the programmed feed, rapids take no time)", |v| {
            format!("{:.2}", v.report.time_real_s / 60.0)
        }),
        ("Length at feed (mm)", "Cutting moves", |v| format!("{:.0}", v.report.length_at_feed_mm)),
        ("Rapid length (mm)", "Rapid moves", |v| format!("{:.0}", v.report.rapid_length_mm)),
        ("Descending moves: largest engagement (°)", "Helix turns, ramps and plunges", |v| {
            format!("{:.1}", v.report.descending.max_engagement_deg)
        }),
        ("Problems listed", "Runs of moves with one problem", |v| v.report.problems.len().to_string()),
        ("Moves with a problem", "Every move with a problem, by kind", |v| {
            let parts: Vec<String> =
                v.report.problem_moves.iter().map(|(k, n)| format!("{n} {}", kind_short(k))).collect();
            if parts.is_empty() { "none".into() } else { parts.join(", ") }
        }),
    ];
    egui::Grid::new("program_summary").striped(true).num_columns(3).show(ui, |ui| {
        ui.label(RichText::new("Summary").strong());
        for (i, slot) in tab.slots.iter().enumerate() {
            let name = slot.loaded.as_ref().map_or("—".to_owned(), |p| p.name());
            ui.label(RichText::new(format!("{}: {name}", SLOT_NAMES[i])).strong());
        }
        ui.end_row();
        for (name, tip, f) in rows {
            ui.label(name).on_hover_text(tip);
            for x in &v {
                ui.label(x.as_ref().map_or("—".to_owned(), |v| f(v)));
            }
            ui.end_row();
        }
    });
}

/// A problem kind in words.
pub fn kind_words(k: ProblemKind) -> &'static str {
    match k {
        ProblemKind::Plunge => "plunge into material",
        ProblemKind::RapidThroughStock => "rapid through material",
        ProblemKind::Gouge => "cuts into the part's wall",
        ProblemKind::DeepFullWidthCut => "full-width cut too deep",
        ProblemKind::Power => "spindle power too high",
        ProblemKind::Torque => "spindle torque too high",
    }
}

/// A kind's JSON name in short words (the counts).
fn kind_short(name: &str) -> &str {
    match name {
        "plunge" => "plunges",
        "rapid-through-stock" => "rapids through material",
        "gouge" => "into the part",
        "deep-full-width-cut" => "deep full-width",
        "power" => "over power",
        "torque" => "over torque",
        other => other,
    }
}

/// A problem's value with its unit.
fn value_text(p: &Problem) -> String {
    let unit = if p.unit == "deg" { "°" } else { p.unit };
    let sep = if unit == "°" { "" } else { " " };
    let limit = p.limit.map_or(String::new(), |l| format!(" (limit {l:.2}{sep}{unit})"));
    format!("{:.2}{sep}{unit}{limit}", p.value)
}

/// The problems as rows; returns the one clicked.
fn problems_list(ui: &mut egui::Ui, problems: &[Problem], selected: Option<usize>) -> Option<usize> {
    ui.label(RichText::new(format!("Problems: {}", problems.len())).strong());
    let mut clicked = None;
    egui::ScrollArea::vertical().id_salt("program_problems").max_height(180.0).show(ui, |ui| {
        egui::Grid::new("program_problems_grid").striped(true).num_columns(6).show(ui, |ui| {
            for h in ["Problem", "Line", "X (mm)", "Y (mm)", "Z (mm)", "Value"] {
                ui.label(RichText::new(h).strong());
            }
            ui.end_row();
            for (k, p) in problems.iter().enumerate() {
                let tip = format!(
                    "Lines {}–{}: {} move{} in a row",
                    p.first_line,
                    p.last_line,
                    p.move_count,
                    if p.move_count == 1 { "" } else { "s" }
                );
                let r = ui.selectable_label(selected == Some(k), kind_words(p.kind)).on_hover_text(tip);
                if r.clicked() {
                    clicked = Some(k);
                }
                ui.label(p.line.to_string());
                ui.label(format!("{:.3}", p.x));
                ui.label(format!("{:.3}", p.y));
                ui.label(format!("{:.3}", p.z));
                ui.label(value_text(p));
                ui.end_row();
            }
        });
    });
    clicked
}

/// The program's text with line `line` highlighted; `scroll` brings it into view.
fn program_text(ui: &mut egui::Ui, p: &super::program::LoadedProgram, line: Option<usize>, scroll: bool, slot: usize) {
    ui.label(RichText::new(format!("Program {}: {}", SLOT_NAMES[slot], p.name())).strong());
    let font = egui::TextStyle::Monospace;
    let row_h = ui.text_style_height(&font);
    let n = p.line_starts.len();
    // scroll bars that stay visible (not egui's floating ones): a long line shows it goes on
    ui.spacing_mut().scroll = egui::style::ScrollStyle::solid();
    let mut area = egui::ScrollArea::both().id_salt(("program_text", slot)).auto_shrink([false, false]);
    if scroll && let Some(l) = line {
        let spacing = ui.spacing().item_spacing.y;
        area = area.vertical_scroll_offset(((l.saturating_sub(4)) as f32) * (row_h + spacing));
    }
    area.show_rows(ui, row_h, n, |ui, rows| {
        for r in rows {
            let n = r + 1;
            let text = RichText::new(format!("{n:>6}  {}", p.line(n))).monospace();
            let text = if Some(n) == line { text.background_color(HIGHLIGHT).color(Color32::BLACK) } else { text };
            ui.add(egui::Label::new(text).wrap_mode(egui::TextWrapMode::Extend));
        }
    });
}
