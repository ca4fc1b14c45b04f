//! The Pocket tab's plot: the pocket, its planned tool path and, when shown, the NC program of
//! that plan read back block by block by the core's back-plot (`nc::backplot`, the reader the
//! program checks use), so the user sees what the machine will run, not only the plan. The
//! read-back is made once per program text and kept in the window's memory.

use super::corner_nc::{self, NcExport};
use super::legend::{self, Entry, Look};
use super::plane::{STRATEGY_COLOR, line, plane_plot};
use super::pocket::PocketResult;
use eframe::egui::{self, Color32};
use std::hash::{Hash, Hasher};
use std::sync::Arc;
use trochoplan_core::nc::{Dialect, backplot};

/// Label of the toggle that draws the program over the plan.
pub const SHOW_PROGRAM: &str = "Program over the plan";
/// Legend name of the program read back.
pub const PROGRAM_LINE: &str = "NC program (read back)";
/// Largest distance of the drawn chords from the program's arcs (mm): a fifth of a pixel of
/// a 60 mm pocket 1000 pixels wide (0.06 mm a pixel), so the drawing is exact to the eye with
/// about a third of the points of the back-plot's own 0.001 mm.
pub const DRAW_CHORD_TOLERANCE_MM: f64 = 0.01;
/// Colour of the program read back.
const PROGRAM_COLOR: Color32 = Color32::from_rgb(230, 140, 20);

/// The program read back: its tool-centre points in mm, or why it could not be read.
pub type BackPlot = Arc<Result<Vec<[f64; 2]>, String>>;

/// The key of the read-back in the window's memory.
fn memory_id() -> egui::Id {
    egui::Id::NULL.with("pocket_program_backplot")
}

/// The tool-centre polyline of the program `text` written in `dialect`, in mm (the back-plot
/// reads an inch program's G20 and gives mm).
pub fn read_back(text: &str, dialect: Dialect) -> Result<Vec<[f64; 2]>, String> {
    let points = backplot(text, dialect, DRAW_CHORD_TOLERANCE_MM)?;
    Ok(points.iter().map(|p| [p.x, p.y]).collect())
}

/// The read-back of the program shown last, if any (the tests compare it with the program).
#[cfg(test)]
pub fn shown_backplot(ctx: &egui::Context) -> Option<BackPlot> {
    ctx.data(|d| d.get_temp::<(u64, BackPlot)>(memory_id())).map(|(_, b)| b)
}

/// The read-back of `text`, made once per text.
fn cached_backplot(ctx: &egui::Context, text: &str, dialect: Dialect) -> BackPlot {
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    (text, dialect.name()).hash(&mut hasher);
    let key = hasher.finish();
    if let Some((k, b)) = ctx.data(|d| d.get_temp::<(u64, BackPlot)>(memory_id()))
        && k == key
    {
        return b;
    }
    let b: BackPlot = Arc::new(read_back(text, dialect));
    ctx.data_mut(|d| d.insert_temp(memory_id(), (key, b.clone())));
    b
}

/// The pocket and its tool path, `h` high, with the program read back over it when
/// `show_program`; half as wide, beside the program, when the NC export is open.
pub fn view(ui: &mut egui::Ui, r: &PocketResult, show_program: bool, nc: &NcExport, h: f32) {
    let program = match (show_program, nc.cache.view()) {
        (true, Some(p)) => Some(cached_backplot(ui.ctx(), &p.text, nc.settings.dialect)),
        _ => None,
    };
    let w = ui.available_width();
    let plot_w = if nc.settings.open { 0.5 * w } else { w };
    ui.vertical(|ui| {
        if let Some(Err(e)) = program.as_deref() {
            ui.colored_label(super::params::ERROR_COLOR, format!("The program cannot be read back: {e}"));
        }
        let walls = Look::solid(Color32::GRAY, 2.5);
        let path = Look::solid(STRATEGY_COLOR, 2.5);
        let read_back = Look::solid(PROGRAM_COLOR, 1.0).styled(egui_plot::LineStyle::dashed_dense());
        let points = match program.as_deref() {
            Some(Ok(points)) => Some(points),
            _ => None,
        };
        let mut entries = vec![Entry::new("pocket", walls)];
        if !r.islands.is_empty() {
            entries.push(Entry::new("islands", walls));
        }
        entries.push(Entry::new("planned tool path", path));
        if points.is_some() {
            entries.push(Entry::new(PROGRAM_LINE, read_back));
        }
        let h = h - ui
            .scope(|ui| {
                ui.set_max_width(plot_w);
                legend::show_above(ui, &entries, 1)
            })
            .inner;
        plane_plot("pocket_rings_plot", h).width(plot_w).show(ui, |p| {
            p.line(walls.line(line("pocket", &r.boundary)));
            for island in &r.islands {
                p.line(walls.line(line("islands", island)));
            }
            p.line(path.line(line("planned tool path", &r.path)));
            if let Some(points) = points {
                p.line(read_back.line(line(PROGRAM_LINE, points)));
            }
        });
    });
    if nc.settings.open {
        ui.vertical(|ui| {
            ui.set_min_size(egui::vec2(ui.available_width(), h));
            corner_nc::preview(ui, nc.cache);
        });
    }
}
