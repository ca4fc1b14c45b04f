//! The Operations tab's panel: the part's file and machine, the progress of its planning, the
//! list of its operations (a click opens one in its own tab) with the part's totals, and the
//! export of the part's one program (dialect, tolerance, arcs or chords).

use super::Command;
use super::operations::{OperationRow, PartView, Totals};
use super::params::ERROR_COLOR;
use eframe::egui::{self, RichText};
use trochoplan_core::nc::Dialect;

/// Label of the button that opens a part job file.
pub const OPEN_PART: &str = "Open part…";
/// Label of the machine choice.
pub const PART_MACHINE: &str = "Machine of the part";
/// The machine choice of no machine.
pub const IDEAL_MACHINE: &str = "ideal (no times)";
/// Label of the tolerance slider.
pub const PART_NC_TOLERANCE: &str = "Part NC tolerance";
/// Label of the chords checkbox.
pub const PART_CHORDS: &str = "Part program in G1 chords only";
/// Label of the save button.
pub const SAVE_PART_PROGRAM: &str = "Save part program…";
/// Label of the totals row.
pub const WHOLE_PART: &str = "Whole part";

/// The row's button: its number and kind ("2. pocket").
pub fn row_label(k: usize, row: &OperationRow) -> String {
    format!("{}. {}", k + 1, row.kind)
}

/// The path length as shown.
pub fn length_text(mm: f64) -> String {
    format!("{mm:.1} mm")
}

/// The peak engagement as shown.
pub fn peak_text(deg: f64) -> String {
    format!("{deg:.2}°")
}

/// A time on the machine as shown: seconds, and minutes and seconds from a minute on.
pub fn time_text(s: Option<f64>) -> String {
    match s {
        None => "—".to_owned(),
        Some(s) if s < 60.0 => format!("{s:.1} s"),
        Some(s) => format!("{s:.1} s ({}:{:02} min)", (s / 60.0).floor(), (s % 60.0).floor()),
    }
}

/// The tab: open a part, its operations and totals, the export.
pub fn show(ui: &mut egui::Ui, view: &mut PartView) -> Option<Command> {
    let mut cmd = None;
    ui.horizontal_wrapped(|ui| {
        if ui
            .button(OPEN_PART)
            .on_hover_text(
                "A part job file (TOML): the program's set-up, the tool table and the operations in \
                 machining order (slots, pockets, corners), each with its tool. Ctrl+Shift+P.",
            )
            .clicked()
        {
            cmd = Some(Command::OpenPart);
        }
        match &view.path {
            Some(p) => ui.label(format!("part: {}", p.display())),
            None => ui.label("No part open."),
        };
        ui.separator();
        machine_choice(ui, &mut view.settings.machine);
    });
    if view.file.is_none() {
        ui.label(
            "Open a part job file to see its operations, plan them all and write one program for the \
             part with its tool changes.",
        );
        return cmd;
    }
    progress(ui, view);
    ui.separator();
    egui::ScrollArea::both().id_salt("part_operations").max_height((ui.available_height() - 150.0).max(160.0)).show(
        ui,
        |ui| {
            if let Some(c) = table(ui, view) {
                cmd = Some(c);
            }
        },
    );
    ui.separator();
    if export(ui, view) {
        cmd = Some(Command::ExportPart);
    }
    cmd
}

/// A progress bar that moves while the operations are planned.
fn progress(ui: &mut egui::Ui, view: &PartView) {
    let n = view.rows.len();
    let done = view.rows.iter().filter(|r| r.result.is_some()).count();
    if view.pending() {
        let p = view.progress();
        #[allow(clippy::cast_precision_loss)]
        let fraction = p.map_or(done as f32 / n.max(1) as f32, |p| p.fraction);
        let text = p.and_then(|p| p.text.clone()).unwrap_or_else(|| format!("{done} of {n} operations planned"));
        ui.add(egui::ProgressBar::new(fraction).text(text).animate(true)).on_hover_text(
            "The operations are planned one after the other; each row shows its numbers as soon as it is planned.",
        );
        ui.ctx().request_repaint_after(std::time::Duration::from_millis(100));
    } else {
        let errors = view.rows.iter().filter(|r| matches!(r.result, Some(Err(_)))).count();
        let text = match errors {
            0 => format!("{done} of {n} operations planned."),
            1 => format!("{done} of {n} operations planned, 1 with an error: the part program needs every one."),
            e => format!("{done} of {n} operations planned, {e} with errors: the part program needs every one."),
        };
        ui.label(text);
    }
}

/// The operations, one row each, and the part's totals; the command of a clicked operation.
fn table(ui: &mut egui::Ui, view: &PartView) -> Option<Command> {
    let mut cmd = None;
    egui::Grid::new("part_operations_grid").striped(true).spacing([14.0, 6.0]).show(ui, |ui| {
        header(ui);
        for (k, row) in view.rows.iter().enumerate() {
            if ui
                .button(row_label(k, row))
                .on_hover_text(format!(
                    "Operation {} in machining order. Click to open it in its own tab with its tool, depth and \
                     options: a slot in the slot's tabs, a pocket in the Pocket tab, a corner in the Corner tab.",
                    k + 1
                ))
                .clicked()
            {
                cmd = Some(Command::OpenOperation(k));
            }
            let tool = match (row.tool_number, row.tool) {
                (_, Some(t)) => format!("T{} · D {:.2} mm", t.number, t.diameter),
                (Some(n), None) => format!("T{n} (not in the tool table)"),
                (None, None) => "—".to_owned(),
            };
            ui.label(tool);
            ui.label(row.depth_mm.map_or_else(|| "—".to_owned(), |d| format!("{d:.2} mm")));
            match &row.result {
                None => {
                    ui.spinner();
                    ui.label("");
                    ui.label("");
                    ui.label("waiting");
                }
                Some(Ok(d)) => {
                    ui.label(length_text(d.report.path_length_mm));
                    ui.label(peak_text(d.report.peak_engagement_deg));
                    ui.label(time_text(d.report.time_real_s));
                    ui.label("planned");
                }
                Some(Err(e)) => {
                    ui.label("—");
                    ui.label("—");
                    ui.label("—");
                    // one line (the table scrolls sideways): a row of the grid keeps one height
                    ui.add(egui::Label::new(RichText::new(e).color(ERROR_COLOR)).extend());
                }
            }
            ui.end_row();
        }
        totals(ui, view.totals(), view.rows.len());
    });
    cmd
}

/// The column heads, each explained.
fn header(ui: &mut egui::Ui) {
    let heads = [
        ("Operation", "Number in machining order and kind: slot, pocket or corner. Click one to open it."),
        ("Tool", "Tool number T of the tool table and its diameter D."),
        ("Depth", "Depth of the operation below the top of the stock Z0."),
        (
            "Path length",
            "Length travelled by the tool centre: a slot's whole path (every level), a pocket's path at \
             depth (without its helix or ramp entries), a corner's path.",
        ),
        (
            "Peak engagement",
            "Largest angle of the tool's circumference in the cut over all measured moves: the most the \
             tool is loaded anywhere in the operation.",
        ),
        (
            "Time",
            "Time of the operation's moves on the chosen machine, with its acceleration, jerk and rapid \
             rate, from the retract height; tool changes not counted.",
        ),
        ("State", "Planned, waiting, or why the operation cannot be planned."),
    ];
    for (text, tip) in heads {
        ui.label(RichText::new(text).strong()).on_hover_text(tip);
    }
    ui.end_row();
}

/// The totals row.
fn totals(ui: &mut egui::Ui, t: Option<Totals>, n: usize) {
    ui.label(RichText::new(WHOLE_PART).strong())
        .on_hover_text(format!("All {n} operations: the sum of the lengths and times, the largest peak."));
    ui.label("");
    ui.label("");
    match t {
        Some(t) => {
            ui.label(RichText::new(length_text(t.path_length_mm)).strong())
                .on_hover_text("Sum of the operations' tool-centre path lengths.");
            ui.label(RichText::new(peak_text(t.peak_engagement_deg)).strong())
                .on_hover_text("The largest peak engagement of all operations.");
            ui.label(RichText::new(time_text(t.time_real_s)).strong())
                .on_hover_text("Sum of the operations' times on the machine, tool changes not counted.");
        }
        None => {
            ui.label("—");
            ui.label("—");
            ui.label("—");
        }
    }
    ui.label("");
    ui.end_row();
}

/// The machine: an ideal one (no times) or a preset.
fn machine_choice(ui: &mut egui::Ui, choice: &mut Option<String>) {
    super::pocket_inputs::machine_picker(
        ui,
        [PART_MACHINE, IDEAL_MACHINE, "part_machine"],
        choice,
        "The machine the part runs on: its acceleration, jerk and rapid rate give each operation's \
         time, and the pockets' feeds are paced to its largest feed. Ideal: no times, every \
         programmed feed held.",
    );
}

/// One line saying what the part's program writes: the set-up of the part file and the tool
/// calls with their length offsets, in the order the tools are first used.
fn set_up(view: &PartView, frame: &trochoplan_core::frame::ProgramFrame) -> String {
    let sinumerik = view.settings.dialect == Dialect::Sinumerik;
    let mut tools: Vec<String> = Vec::new();
    for t in view.rows.iter().filter_map(|r| r.tool) {
        let call = if sinumerik {
            format!("T{} D{}", t.number, t.length_offset.unwrap_or(1))
        } else {
            format!("T{} H{}", t.number, t.length_offset.unwrap_or(t.number))
        };
        if !tools.contains(&call) {
            tools.push(call);
        }
    }
    format!(
        "Set-up: {}, clearance {} mm, retract {} mm, {}; tools {}",
        frame.work_offset.name(),
        frame.clearance_mm,
        frame.retract_height_mm(),
        frame.units.unit(),
        tools.join(", ")
    )
}

/// The program's format and the save button; true when it was clicked.
fn export(ui: &mut egui::Ui, view: &mut PartView) -> bool {
    let s = &mut view.settings;
    ui.label(RichText::new("Program of the part").strong()).on_hover_text(
        "One NC program for every operation in order, with a tool change wherever the tool changes \
         (tool call, length offset, spindle and coolant of the new tool).",
    );
    ui.horizontal_wrapped(|ui| {
        ui.label("Dialect");
        for d in Dialect::ALL {
            ui.radio_value(&mut s.dialect, d, d.label()).on_hover_text(d.about());
        }
        ui.separator();
        let l = ui.label(PART_NC_TOLERANCE).on_hover_text(
            "Largest distance of the written path from the planned one before rounding (mm); curves \
             become arcs (or chords) within it. Default 0.005 mm.",
        );
        ui.spacing_mut().slider_width = 110.0;
        ui.add(super::corner_nc::tolerance_slider(&mut s.tolerance_mm)).labelled_by(l.id);
        ui.checkbox(&mut s.linear_segments, PART_CHORDS)
            .on_hover_text("Write every arc as G1 chords instead of G2/G3 (more blocks).");
    });
    if let Some(f) = &view.file {
        ui.label(set_up(view, &f.program)).on_hover_text(
            "The program's set-up from the part file's program table; each operation's tool gives its own \
             tool number, length offset, spindle direction and coolant (the tool table's).",
        );
    }
    let ready = view.planned().is_some();
    ui.horizontal(|ui| {
        let clicked = ui
            .add_enabled(ready, egui::Button::new(SAVE_PART_PROGRAM))
            .on_hover_text("Choose a file; the part's program is written to it whole, or not at all.")
            .on_disabled_hover_text("Every operation must be planned without error first.")
            .clicked();
        if !ready {
            ui.label("Saved once every operation is planned.");
        }
        clicked
    })
    .inner
}
