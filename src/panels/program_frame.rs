//! "Program" panel: the frame of every NC program the window writes (slot, corner and pocket):
//! tool and length offset, work offset, clearance and retract heights, units, coolant,
//! spindle direction, program number (Fanuc) or name (Sinumerik). It edits the job's
//! [`ProgramFrame`], so the settings are saved with the job (`[program]` in the job file) and
//! shared by every export; the core checks them when a program is written and its message
//! shows under the export options.

use super::label;
use eframe::egui::{self, DragValue, RichText};
use trochoplan_core::frame::{
    Coolant, DEFAULT_PROGRAM_NUMBER, MAX_CLEARANCE_MM, ProgramFrame, SpindleDirection, Units, WorkOffset,
};
use trochoplan_core::nc::Dialect;

/// The panel: one wrapped row of fields for `frame`; `dialect` decides which of the tool,
/// number and name fields apply.
pub fn show(ui: &mut egui::Ui, frame: &mut ProgramFrame, dialect: Dialect) {
    ui.horizontal_wrapped(|ui| {
        ui.label(RichText::new("Program").strong());
        tool_fields(ui, frame, dialect);
        ui.separator();
        height_fields(ui, frame);
        ui.separator();
        word_fields(ui, frame, dialect);
    });
}

/// Tool number, length offset and work offset.
fn tool_fields(ui: &mut egui::Ui, frame: &mut ProgramFrame, dialect: Dialect) {
    let spec = dialect.spec();
    let l = ui.label(label::TOOL_NUMBER);
    ui.add(DragValue::new(&mut frame.tool_number).range(1..=spec.max_tool_number).prefix("T"))
        .labelled_by(l.id)
        .on_hover_text(format!("Tool number T, 1 to {} on {}.", spec.max_tool_number, spec.label));
    let mut own_offset = frame.length_offset.is_some();
    let offset_word = if dialect == Dialect::Sinumerik { "D" } else { "H" };
    ui.checkbox(&mut own_offset, label::OWN_LENGTH_OFFSET).on_hover_text(format!(
        "Off: the length offset is {} (H = the tool number; D1 on Sinumerik).",
        if dialect == Dialect::Sinumerik { "D1" } else { "H = T" }
    ));
    if own_offset {
        let mut h = frame.length_offset.unwrap_or(frame.length_offset_number(dialect)).min(spec.max_length_offset);
        let l = ui.label(label::LENGTH_OFFSET);
        ui.add(DragValue::new(&mut h).range(1..=spec.max_length_offset).prefix(offset_word))
            .labelled_by(l.id)
            .on_hover_text(format!("Length offset number, 1 to {}.", spec.max_length_offset));
        frame.length_offset = Some(h);
    } else {
        frame.length_offset = None;
    }
    egui::ComboBox::from_label(label::WORK_OFFSET).selected_text(frame.work_offset.name()).show_ui(ui, |ui| {
        for w in WorkOffset::ALL {
            ui.selectable_value(&mut frame.work_offset, w, w.name());
        }
    });
}

/// Clearance and retract heights (mm whatever the units) and the units.
fn height_fields(ui: &mut egui::Ui, frame: &mut ProgramFrame) {
    let l = ui.label(label::CLEARANCE);
    ui.add(DragValue::new(&mut frame.clearance_mm).speed(0.1).range(0.1..=MAX_CLEARANCE_MM).suffix(" mm"))
        .labelled_by(l.id)
        .on_hover_text("Height above the stock top Z0 for the approach from the tool change and the final retract.");
    let mut own_retract = frame.retract_mm.is_some();
    ui.checkbox(&mut own_retract, label::OWN_RETRACT)
        .on_hover_text("Off: the tool retracts to the clearance height between the parts of a path.");
    if own_retract {
        let mut r = frame.retract_mm.unwrap_or(frame.clearance_mm).min(frame.clearance_mm);
        let l = ui.label(label::RETRACT);
        ui.add(DragValue::new(&mut r).speed(0.1).range(0.1..=frame.clearance_mm).suffix(" mm"))
            .labelled_by(l.id)
            .on_hover_text("Height above the stock top between the parts of a path, at most the clearance.");
        frame.retract_mm = Some(r);
    } else {
        frame.retract_mm = None;
    }
    ui.label(label::UNITS);
    for u in Units::ALL {
        let text = match u {
            Units::Mm => "mm (G21)",
            Units::Inch => "inch (G20)",
        };
        ui.radio_value(&mut frame.units, u, text)
            .on_hover_text("Units of the written program: an inch program writes every coordinate and feed in inch.");
    }
}

/// Coolant, spindle direction, program number (Fanuc) or name (Sinumerik).
fn word_fields(ui: &mut egui::Ui, frame: &mut ProgramFrame, dialect: Dialect) {
    egui::ComboBox::from_label(label::PROGRAM_COOLANT).selected_text(frame.coolant.help()).show_ui(ui, |ui| {
        for c in Coolant::ALL {
            ui.selectable_value(&mut frame.coolant, c, c.help());
        }
    });
    ui.label(label::SPINDLE_DIRECTION);
    for s in SpindleDirection::ALL {
        ui.radio_value(&mut frame.spindle_direction, s, s.word()).on_hover_text(s.help());
    }
    match dialect {
        Dialect::Fanuc => {
            let mut n = frame.program_number_or_default();
            let l = ui.label(label::PROGRAM_NUMBER);
            ui.add(DragValue::new(&mut n).range(1..=9999).prefix("O")).labelled_by(l.id);
            frame.program_number = (n != DEFAULT_PROGRAM_NUMBER).then_some(n);
        }
        Dialect::Sinumerik => {
            let mut name = frame.program_name.clone().unwrap_or_default();
            let l = ui.label(label::PROGRAM_NAME);
            ui.add(egui::TextEdit::singleline(&mut name).desired_width(120.0))
                .labelled_by(l.id)
                .on_hover_text("Written as the %_N_NAME_MPF header; empty: none (the file name names the program).");
            frame.program_name = (!name.trim().is_empty()).then(|| name.trim().to_string());
        }
        _ => {}
    }
}

/// One line saying what the frame writes (the Corner and Pocket tabs, which share the Export
/// tab's settings).
pub fn summary(frame: &ProgramFrame, dialect: Dialect) -> String {
    let mut s = format!(
        "Program: T{} {}{} {}, clearance {} mm, retract {} mm, {}, {}",
        frame.tool_number,
        if dialect == Dialect::Sinumerik { "D" } else { "H" },
        frame.length_offset_number(dialect),
        frame.work_offset.name(),
        frame.clearance_mm,
        frame.retract_height_mm(),
        frame.units.unit(),
        frame.spindle_direction.word(),
    );
    if let Some(w) = frame.coolant.word() {
        s.push_str(&format!(", coolant {w}"));
    }
    s.push_str(" (set in the Export tab)");
    s
}
