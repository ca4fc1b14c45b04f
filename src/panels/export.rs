//! "Export NC…" panel: dialect, tolerance and options, a read-only preview
//! of the program text, the program's own back-plot over the planned path, and a save button.
//!
//! The program comes from the core (`nc::program`), the back-plot from interpreting that text
//! (`nc::backplot`), both computed once per (plan, settings) in [`ExportCache`], not per frame.
//! Compact loop programs are not interpreted: their back-plot is that of the expanded program
//! with the same options (the core guarantees the same motion), and the panel says so.
//! A slot cut in levels or closed gets the core's levels program (`nc::levels_program`), the
//! one `trochoplan export` writes for the same job.

use super::Command;
use super::corner_nc::tolerance_slider;
use super::label;
use super::legend::{self, Entry, Look};
use super::params::ERROR_COLOR;
use crate::shared::nc::NcChoices;
use eframe::egui::{self, Color32, RichText};
use egui_plot::{Line, Plot, PlotPoint, PlotPoints};
use serde::{Deserialize, Serialize};
use trochoplan_core::Plan;
use trochoplan_core::frame::ProgramFrame;
use trochoplan_core::job::ValidJob;
use trochoplan_core::nc::{self, DEFAULT_TOLERANCE_MM, Dialect, NcOptions, NcProgram};
use trochoplan_core::slot_levels::LevelPlan;

/// Chord tolerance of the drawn back-plot (mm), raised for very long programs.
const BACKPLOT_CHORD_MM: f64 = 0.002;
/// Most back-plot points drawn before the chord tolerance is raised.
const MAX_BACKPLOT_POINTS: usize = 60_000;
/// Points per path segment of the planned path under the back-plot.
const PLANNED_POINTS_PER_SEGMENT: usize = 48;

/// The export options the user chose (persisted with the rest of the state).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ExportSettings {
    pub dialect: Dialect,
    pub tolerance_mm: f64,
    pub linear_segments: bool,
    pub compact: bool,
    pub return_feed: bool,
    pub return_feed_mm_per_min: f64,
    /// The job's program frame (a copy taken each frame; saved with the job, not here).
    #[serde(skip)]
    pub frame: ProgramFrame,
}

impl Default for ExportSettings {
    fn default() -> Self {
        ExportSettings {
            dialect: Dialect::LinuxCnc,
            tolerance_mm: DEFAULT_TOLERANCE_MM,
            linear_segments: false,
            compact: false,
            return_feed: false,
            return_feed_mm_per_min: 1800.0,
            frame: ProgramFrame::default(),
        }
    }
}

impl ExportSettings {
    /// The core's options (validated by the core when the program is written).
    pub fn options(&self) -> NcOptions {
        NcChoices {
            return_feed_mm_per_min: self.return_feed.then_some(self.return_feed_mm_per_min),
            compact: self.compact,
            ..NcChoices::new(self.dialect, self.tolerance_mm, self.linear_segments, self.frame.clone())
        }
        .options()
    }
}

/// A written program and its back-plot, ready to draw.
#[derive(Clone, Debug)]
pub struct ExportView {
    pub text: String,
    /// Line start offsets of `text` (the preview draws only the visible rows).
    line_starts: Vec<usize>,
    pub blocks: usize,
    /// The program's own motion (XY, mm), from its text.
    pub backplot: Vec<PlotPoint>,
    /// Why the back-plot is not of the previewed text itself, if it is not.
    pub backplot_note: Option<String>,
    /// Why there is no back-plot (the program itself is fine).
    pub backplot_error: Option<String>,
    /// The planned tool-centre path (XY, mm).
    pub planned: Vec<PlotPoint>,
}

impl ExportView {
    #[cfg(test)]
    fn line(&self, i: usize) -> &str {
        line_of(&self.text, &self.line_starts, i)
    }

    fn lines(&self) -> usize {
        self.line_starts.len()
    }
}

/// Byte offsets of the line starts of `text` (for [`program_text`]).
pub(super) fn line_starts(text: &str) -> Vec<usize> {
    let mut starts = vec![0];
    starts.extend(text.match_indices('\n').map(|(i, _)| i + 1).filter(|&i| i < text.len()));
    starts
}

/// Line `i` of `text` without its newline (`starts` from [`line_starts`]).
fn line_of<'a>(text: &'a str, starts: &[usize], i: usize) -> &'a str {
    let start = starts[i];
    let end = starts.get(i + 1).map_or(text.len(), |&e| e);
    text[start..end].trim_end_matches('\n')
}

/// A read-only program preview filling `ui`: only the visible lines are laid out, so a long
/// program costs nothing per frame.
pub(super) fn program_text(ui: &mut egui::Ui, id: &str, text: &str, starts: &[usize]) {
    let row_h = ui.text_style_height(&egui::TextStyle::Monospace);
    ui.scope(|ui| {
        // scroll bars that stay visible (not egui's floating ones): a long line shows it goes on
        ui.spacing_mut().scroll = egui::style::ScrollStyle::solid();
        let area = egui::ScrollArea::both().id_salt(id).auto_shrink([false, false]);
        area.show_rows(ui, row_h, starts.len(), |ui, rows| {
            for i in rows {
                ui.add(egui::Label::new(RichText::new(line_of(text, starts, i)).monospace()).extend());
            }
        });
    });
}

/// A program generated once per key (the plan it is written from and the export settings),
/// not per frame: the slot's ([`ExportCache`]) and the Corner tab's
/// (`corner_nc::CornerNcCache`).
pub struct ProgramCache<K, V> {
    key: Option<K>,
    /// The program, or the core's message.
    pub result: Option<Result<V, String>>,
    /// Programs generated (tests check the cache).
    pub generated: u64,
}

impl<K, V> Default for ProgramCache<K, V> {
    fn default() -> Self {
        ProgramCache { key: None, result: None, generated: 0 }
    }
}

impl<K: PartialEq, V> ProgramCache<K, V> {
    /// Generate the program of `key` unless it is the key of the last call.
    pub fn update_with(&mut self, key: K, generate: impl FnOnce(&K) -> Result<V, String>) {
        if self.key.as_ref() == Some(&key) {
            return;
        }
        self.generated += 1;
        self.result = Some(generate(&key));
        self.key = Some(key);
    }

    /// Forget the program (there is no plan to write one from).
    pub fn clear(&mut self) {
        self.key = None;
        self.result = None;
    }

    /// The current program, if it was written without error.
    pub fn view(&self) -> Option<&V> {
        self.result.as_ref().and_then(|r| r.as_ref().ok())
    }
}

/// The slot's program and back-plot of the last (plan, settings).
pub type ExportCache = ProgramCache<(ValidJob, ExportSettings), ExportView>;

impl ExportCache {
    /// Regenerate if `plan` or `settings` changed since the last call; `levels`: the plan's
    /// levels (or the core's message) when the job is cut in levels or closed.
    pub fn update(&mut self, plan: &Plan, levels: Option<&Result<LevelPlan, String>>, settings: &ExportSettings) {
        self.update_with((plan.job.clone(), settings.clone()), |(_, settings)| generate(plan, levels, settings));
    }
}

/// The program of `plan` with `opts`: the levels' program when the job has levels, else the
/// one-level slot program.
fn write(plan: &Plan, levels: Option<&Result<LevelPlan, String>>, opts: &NcOptions) -> Result<NcProgram, String> {
    match levels {
        Some(Ok(lp)) => nc::levels_program(plan, lp, opts).map_err(|e| e.to_string()),
        Some(Err(e)) => Err(e.clone()),
        None => nc::program(plan, opts).map_err(|e| e.to_string()),
    }
}

fn to_points(pts: Vec<trochoplan_core::geom::P2>) -> Vec<PlotPoint> {
    pts.into_iter().map(|p| PlotPoint::new(p.x, p.y)).collect()
}

fn generate(
    plan: &Plan,
    levels: Option<&Result<LevelPlan, String>>,
    settings: &ExportSettings,
) -> Result<ExportView, String> {
    let opts = settings.options();
    let program = write(plan, levels, &opts)?;
    // Loop programs are not interpreted: back-plot the expanded program of the same options.
    let (plotted, note) = if opts.compact {
        let expanded = NcOptions { compact: false, ..opts.clone() };
        let text = nc::program(plan, &expanded).map_err(|e| e.to_string())?.text;
        let note = "Back-plot of the expanded program with the same options: the loop form \
            describes the same motion (checked by the core's tests); loops are not interpreted here.";
        (text, Some(note.to_owned()))
    } else {
        (program.text.clone(), None)
    };
    let mut chord = BACKPLOT_CHORD_MM;
    let mut backplot = nc::backplot(&plotted, opts.dialect, chord);
    while matches!(&backplot, Ok(p) if p.len() > MAX_BACKPLOT_POINTS) && chord < 0.1 {
        chord *= 4.0;
        backplot = nc::backplot(&plotted, opts.dialect, chord);
    }
    let (backplot, backplot_error) = match backplot {
        Ok(p) => (to_points(p), None),
        Err(e) => (Vec::new(), Some(e)),
    };
    let path = &plan.path;
    let per_segment = (PLANNED_POINTS_PER_SEGMENT * 40 / path.cycles.max(1)).clamp(8, PLANNED_POINTS_PER_SEGMENT);
    let planned = match levels.and_then(|l| l.as_ref().ok()).and_then(|lp| lp.per_level.first()) {
        // every level has the same planar moves: the first level's
        Some(level) => to_points(level.toolpath.moves.iter().flat_map(|m| m.segment.sample(per_segment)).collect()),
        None => to_points(path.sample_cycles(0, path.cycles, per_segment)),
    };
    let line_starts = line_starts(&program.text);
    Ok(ExportView {
        text: program.text,
        line_starts,
        blocks: program.blocks,
        backplot,
        backplot_note: note,
        backplot_error,
        planned,
    })
}

/// The export panel: options and the program's frame (`frame`: the job's, edited here) on
/// top, then preview and back-plot side by side. `levels`: the job is cut in levels or closed
/// (no loop form). `job_error`: the edited job is invalid (the
/// program would be of the last valid plan).
pub fn show(
    ui: &mut egui::Ui,
    settings: &mut ExportSettings,
    frame: &mut ProgramFrame,
    cache: &ExportCache,
    levels: bool,
    job_error: Option<&str>,
) -> Option<Command> {
    ui.horizontal_wrapped(|ui| dialect_row(ui, settings));
    ui.horizontal_wrapped(|ui| options_row(ui, settings, levels));
    super::program_frame::show(ui, frame, settings.dialect);
    if levels {
        ui.label(
            "The slot is cut in levels or closed: the program cuts level by level, each entered as \
             the Slot fields say (the loop form writes one level only, so it is not offered).",
        );
    }
    if let Some(e) = job_error {
        ui.colored_label(ERROR_COLOR, format!("Job invalid ({e}): fix it before exporting."));
    }
    let view = match &cache.result {
        None => {
            ui.label("No valid job yet: fix the marked parameter.");
            return None;
        }
        Some(Err(e)) => {
            ui.colored_label(ERROR_COLOR, format!("Cannot write the program: {e}"));
            return None;
        }
        Some(Ok(v)) => v,
    };
    let cmd = ui.horizontal(|ui| save_row(ui, view, job_error.is_none())).inner;
    ui.separator();
    program_and_backplot(ui, view);
    cmd
}

/// The controller dialects, one radio button each.
fn dialect_row(ui: &mut egui::Ui, settings: &mut ExportSettings) {
    ui.label(RichText::new("Dialect").strong());
    for d in Dialect::ALL {
        ui.radio_value(&mut settings.dialect, d, d.label()).on_hover_text(d.about());
    }
}

/// Tolerance, chords, loop form, coolant and return feed.
fn options_row(ui: &mut egui::Ui, settings: &mut ExportSettings, levels: bool) {
    let l = ui.label(label::NC_TOLERANCE).on_hover_text(
        "Largest distance of the written path from the planned one before rounding (mm). \
         Curves become biarcs (or chords) within it; default 0.005 mm.",
    );
    ui.spacing_mut().slider_width = 140.0;
    ui.add(tolerance_slider(&mut settings.tolerance_mm)).labelled_by(l.id);
    ui.checkbox(&mut settings.linear_segments, label::LINEAR_SEGMENTS)
        .on_hover_text("Write every curve as G1 chords instead of G2/G3 arcs (many more blocks).");
    let loops = settings.dialect.spec().loop_style.is_some() && !levels;
    if !loops {
        settings.compact = false;
    }
    ui.add_enabled(loops, egui::Checkbox::new(&mut settings.compact, label::COMPACT_LOOP))
        .on_hover_text("LinuxCNC O-word while loop / Sinumerik R-parameter loop: one cycle's blocks, repeated.")
        .on_disabled_hover_text(
            "Only LinuxCNC and Sinumerik have a loop form, and it writes one level: not for a slot \
             in levels or a closed slot.",
        );
    ui.checkbox(&mut settings.return_feed, label::FASTER_RETURN_FEED)
        .on_hover_text("A faster feed on the moves where no tooth cuts in the steady state.");
    let l = ui.label(label::RETURN_FEED);
    ui.add_enabled(
        settings.return_feed,
        egui::DragValue::new(&mut settings.return_feed_mm_per_min)
            .custom_parser(super::number::parse)
            .speed(10.0)
            .suffix(" mm/min"),
    )
    .labelled_by(l.id);
}

/// The save button (enabled when the job is valid, `ok`) and the program's size.
fn save_row(ui: &mut egui::Ui, view: &ExportView, ok: bool) -> Option<Command> {
    let save = ui
        .add_enabled(ok, egui::Button::new(label::SAVE_NC_PROGRAM))
        .on_hover_text("Choose a file; it is written atomically (temporary file, then rename).")
        .clicked();
    ui.label(format!("{} blocks, {} bytes, {} lines", view.blocks, view.text.len(), view.lines()));
    save.then_some(Command::ExportNc)
}

/// The program text (left) and its back-plot over the planned path (right).
fn program_and_backplot(ui: &mut egui::Ui, view: &ExportView) {
    let avail = ui.available_size();
    let left = (avail.x * 0.42).max(260.0);
    ui.horizontal_top(|ui| {
        ui.allocate_ui_with_layout(egui::vec2(left, avail.y), egui::Layout::top_down(egui::Align::Min), |ui| {
            ui.set_min_size(egui::vec2(left, avail.y));
            ui.label(RichText::new("Program (read-only)").strong());
            program_text(ui, "nc_preview", &view.text, &view.line_starts);
        });
        ui.vertical(|ui| {
            ui.label(RichText::new("Back-plot: the program's own motion over the planned path").strong());
            if let Some(n) = &view.backplot_note {
                ui.add(egui::Label::new(RichText::new(n).weak()).wrap());
            }
            if let Some(e) = &view.backplot_error {
                ui.colored_label(ERROR_COLOR, format!("No back-plot: {e}"));
            }
            backplot_plot(ui, view);
        });
    });
}

fn backplot_plot(ui: &mut egui::Ui, view: &ExportView) {
    let planned = Look::solid(Color32::from_rgb(120, 170, 240).gamma_multiply(0.6), 5.0);
    let backplot = Look::solid(Color32::from_rgb(200, 40, 40), 1.0);
    legend::show(ui, &[Entry::new("planned path", planned), Entry::new("program back-plot", backplot)], 2);
    let size = ui.available_size();
    Plot::new("nc_backplot")
        .width(size.x.max(120.0))
        .height(size.y.max(80.0))
        .data_aspect(1.0)
        .x_axis_label("X [mm]")
        .y_axis_label("Y [mm]")
        .allow_scroll(false)
        .show(ui, |p| {
            p.line(planned.line(Line::new("planned path", PlotPoints::Borrowed(&view.planned))));
            p.line(backplot.line(Line::new("program back-plot", PlotPoints::Borrowed(&view.backplot))));
        });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cache_regenerates_only_on_change_and_reports_core_errors() {
        let plan = trochoplan_core::plan(&trochoplan_core::Job::default()).expect("plan");
        let mut c = ExportCache::default();
        let s = ExportSettings::default();
        c.update(&plan, None, &s);
        c.update(&plan, None, &s);
        assert_eq!(c.generated, 1);
        let v = c.view().expect("program");
        assert_eq!(v.line(0), v.text.lines().next().expect("a line"));
        assert_eq!(v.lines(), v.text.lines().count());
        assert!(!v.backplot.is_empty() && v.backplot_error.is_none());
        c.update(&plan, None, &ExportSettings { tolerance_mm: 5.0, ..s.clone() });
        assert_eq!(c.generated, 2);
        let e = c.result.as_ref().expect("result").as_ref().expect_err("invalid tolerance");
        assert!(e.contains("tolerance"), "{e}");
        c.update(&plan, None, &ExportSettings { compact: true, dialect: Dialect::Sinumerik, ..s });
        let v = c.view().expect("compact program");
        assert!(v.text.contains("GOTOB"));
        assert!(v.backplot_note.is_some() && !v.backplot.is_empty());
    }
}
