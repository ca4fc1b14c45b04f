//! NC export from the Corner and Pocket tabs: the program of the planned corner or pocket,
//! with dialect, tolerance, arcs or G1 chords and depth, at the job's feed and spindle speed in the
//! job's program frame (the Export tab's Program panel); previewed
//! read-only and saved through the app's file dialog (`Command::ExportCornerNc`,
//! `Command::ExportPocketNc`). Each tab has its own settings and program.
//!
//! The program comes from the core (`nc::corner_program`, `nc::pocket_program`), the same calls
//! as `trochoplan corner --export` and `trochoplan pocket --export`, so the GUI writes the
//! CLI's text. It is generated once per (plan, settings) in [`CornerNcCache`], not per frame.

use super::Command;
use super::corner::CornerResult;
use super::export::{ProgramCache, line_starts, program_text};
use super::label;
use super::params::ERROR_COLOR;
use super::pocket::PocketResult;
use crate::shared::nc::{self as shared_nc, NcChoices};
use eframe::egui::{self, DragValue, RichText, Slider, SliderClamping};
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use trochoplan_core::frame::ProgramFrame;
use trochoplan_core::nc::{self, CutSetup, DEFAULT_TOLERANCE_MM, Dialect, NcOptions};

/// The export options of the Corner tab, or of the Pocket tab (persisted with the app state).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct CornerNcSettings {
    /// Show the export options and the program preview.
    pub open: bool,
    pub dialect: Dialect,
    /// Largest distance of the written path from the planned one, before rounding (mm).
    pub tolerance_mm: f64,
    pub linear_segments: bool,
    /// Cutting depth below the stock top Z0 (mm).
    pub depth_mm: f64,
    /// The job's spindle speed (rpm; a copy taken each frame).
    #[serde(skip)]
    pub spindle_rpm: f64,
    /// The job's program frame (a copy taken each frame; saved with the job, not here).
    #[serde(skip)]
    pub frame: ProgramFrame,
}

impl Default for CornerNcSettings {
    /// The defaults of `trochoplan corner --export`.
    fn default() -> Self {
        let cut = CutSetup::default();
        CornerNcSettings {
            open: false,
            dialect: Dialect::LinuxCnc,
            tolerance_mm: DEFAULT_TOLERANCE_MM,
            linear_segments: false,
            depth_mm: cut.depth_mm,
            spindle_rpm: cut.spindle_rpm,
            frame: ProgramFrame::default(),
        }
    }
}

impl CornerNcSettings {
    /// The core's options (validated by the core when the program is written).
    pub fn options(&self) -> NcOptions {
        NcChoices::new(self.dialect, self.tolerance_mm, self.linear_segments, self.frame.clone()).options()
    }

    pub fn cut(&self) -> CutSetup {
        shared_nc::cut_setup(self.depth_mm, self.spindle_rpm)
    }
}

/// A written program, ready to preview and save.
#[derive(Clone, Debug)]
pub struct NcPreview {
    pub text: String,
    line_starts: Vec<usize>,
    pub blocks: usize,
    /// Default file name without extension ("corner" or "pocket").
    pub file_stem: &'static str,
}

/// The plan a program is written from (the same plan: the same `Arc`).
#[derive(Clone)]
pub enum Source {
    Corner(Arc<CornerResult>),
    Pocket(Arc<PocketResult>),
}

impl PartialEq for Source {
    fn eq(&self, other: &Source) -> bool {
        match (self, other) {
            (Source::Corner(a), Source::Corner(b)) => Arc::ptr_eq(a, b),
            (Source::Pocket(a), Source::Pocket(b)) => Arc::ptr_eq(a, b),
            _ => false,
        }
    }
}

/// The program of the shown plan and the export settings, regenerated only when either changed.
pub type CornerNcCache = ProgramCache<(Source, CornerNcSettings), NcPreview>;

impl CornerNcCache {
    /// Regenerate if the shown plan (`None`: none, or the acceptance table) or the settings
    /// changed.
    pub fn update(&mut self, source: Option<Source>, settings: &CornerNcSettings) {
        let Some(source) = source else {
            self.clear();
            return;
        };
        // showing or hiding the panel does not change the program
        let settings = CornerNcSettings { open: false, ..settings.clone() };
        self.update_with((source, settings), |(source, settings)| generate(source, settings));
    }
}

/// The export as the tab's panels see it: the settings they edit and the program of the shown
/// plan.
pub struct NcExport<'a> {
    pub settings: &'a mut CornerNcSettings,
    pub cache: &'a CornerNcCache,
}

fn generate(source: &Source, settings: &CornerNcSettings) -> Result<NcPreview, String> {
    let opts = settings.options();
    let (program, file_stem) = match source {
        Source::Corner(r) => {
            let report = &r.report;
            (nc::corner_program(&report.plan, report.settings(), report.angle_deg, settings.cut(), &opts), "corner")
        }
        Source::Pocket(r) => (nc::pocket_program(&r.plan, settings.cut(), &opts), "pocket"),
    };
    let program = program.map_err(|e| e.to_string())?;
    Ok(NcPreview { line_starts: line_starts(&program.text), text: program.text, blocks: program.blocks, file_stem })
}

/// The options, the program's size and the save button (`save`: its command). `inputs_error`:
/// the tab's inputs are invalid (the program would be of the last valid plan, so saving is
/// disabled).
pub fn options(
    ui: &mut egui::Ui,
    settings: &mut CornerNcSettings,
    cache: &CornerNcCache,
    inputs_error: bool,
    save: Command,
) -> Option<Command> {
    ui.horizontal_wrapped(|ui| format_options(ui, settings));
    ui.horizontal_wrapped(|ui| cut_options(ui, settings));
    match &cache.result {
        None => {
            ui.label("No plan yet.");
            None
        }
        Some(Err(e)) => {
            ui.add(egui::Label::new(RichText::new(format!("Cannot write the program: {e}")).color(ERROR_COLOR)).wrap());
            None
        }
        Some(Ok(p)) => ui.horizontal(|ui| save_row(ui, p, inputs_error)).inner.then_some(save),
    }
}

/// How the program is written: the dialect and the tolerance.
fn format_options(ui: &mut egui::Ui, settings: &mut CornerNcSettings) {
    ui.label(RichText::new("Dialect").strong());
    for d in Dialect::ALL {
        ui.radio_value(&mut settings.dialect, d, d.label());
    }
    ui.separator();
    let l = ui.label(label::CORNER_NC_TOLERANCE).on_hover_text(
        "Largest distance of the written path from the planned one before rounding (mm); \
         curves become biarcs (or chords) within it. Default 0.005 mm.",
    );
    ui.spacing_mut().slider_width = 110.0;
    ui.add(tolerance_slider(&mut settings.tolerance_mm)).labelled_by(l.id);
}

/// The slider of an NC tolerance: 0.1 µm to 1 mm on a logarithmic scale, typed values outside
/// kept (the core rejects them with its message).
pub(super) fn tolerance_slider(tolerance_mm: &mut f64) -> Slider<'_> {
    Slider::new(tolerance_mm, 1e-4..=1.0)
        .custom_parser(super::number::parse)
        .logarithmic(true)
        .clamping(SliderClamping::Never)
        .max_decimals(4)
        .suffix(" mm")
}

/// How it cuts: chords or arcs, coolant, depth and spindle speed.
fn cut_options(ui: &mut egui::Ui, settings: &mut CornerNcSettings) {
    ui.checkbox(&mut settings.linear_segments, label::G1_CHORDS_ONLY)
        .on_hover_text("Write every arc as G1 chords instead of G2/G3 (more blocks).");
    ui.separator();
    let l = ui.label(label::DEPTH_BELOW_Z0);
    ui.add(DragValue::new(&mut settings.depth_mm).speed(0.1).suffix(" mm")).labelled_by(l.id).on_hover_text(
        "Cutting depth below the stock top Z0, 0 < depth ≤ 1000 mm; the tool feeds down at the path start.",
    );
    ui.label(format!("{}: {:.0} rpm (the job's)", label::SPINDLE, settings.spindle_rpm));
    ui.end_row();
    ui.label(super::program_frame::summary(&settings.frame, settings.dialect));
}

/// The save button (disabled while the inputs are invalid) and the program's size; true when
/// it was clicked.
fn save_row(ui: &mut egui::Ui, p: &NcPreview, inputs_error: bool) -> bool {
    let save = ui
        .add_enabled(!inputs_error, egui::Button::new(label::SAVE_PROGRAM_AS))
        .on_hover_text("Choose a file; it is written atomically (temporary file, then rename).")
        .on_disabled_hover_text("The inputs are invalid: fix them first.")
        .clicked();
    ui.label(format!("{} blocks, {} bytes, {} lines", p.blocks, p.text.len(), p.line_starts.len()));
    save
}

/// The read-only program text filling `ui`.
pub fn preview(ui: &mut egui::Ui, cache: &CornerNcCache) {
    ui.label(RichText::new("Program (read-only)").strong());
    match cache.view() {
        Some(p) => program_text(ui, "corner_nc_preview", &p.text, &p.line_starts),
        None => {
            ui.label("No program.");
        }
    }
}
