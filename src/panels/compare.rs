//! Compare mode: pinned variants (up to four) and a table of their metrics with the % change
//! against the first, as the paper reports them.

use super::Command;
use eframe::egui::{self, Color32, RichText};
use trochoplan_core::job::Direction;
use trochoplan_core::quantity::{self, Metric};
use trochoplan_core::{Job, Metrics, PathKind};

/// Most pinned variants.
pub const MAX_VARIANTS: usize = 4;

/// What the compare panel needs of one pinned variant.
pub struct VariantView<'a> {
    pub label: &'a str,
    pub color: Color32,
    pub metrics: &'a Metrics,
}

/// The compared quantities, in order: the path's shape, then the core's cycle results and its
/// process results (F_R,max, PI: the paper's Figs. 16 and 23).
fn quantities() -> impl Iterator<Item = &'static Metric> {
    [&quantity::ASPECT_RATIO, &quantity::LINEAR_DISTANCE]
        .into_iter()
        .chain(quantity::CYCLE_RESULTS)
        .chain(quantity::PROCESS_RESULTS)
}

/// Percentage change of `v` against `base` (None when the base is zero).
pub fn percent_change(v: f64, base: f64) -> Option<f64> {
    (base.abs() > 1e-12).then(|| (v - base) / base * 100.0).filter(|p| p.is_finite())
}

/// A short label for a job, as the paper names its variants; ", climb" when it is not the
/// paper's conventional loop.
pub fn variant_label(job: &Job) -> String {
    let label = match job.path {
        PathKind::Circular | PathKind::CircularType => job.path.name().to_owned(),
        PathKind::Elliptical => format!("elliptical r_e = {}", job.aspect_ratio),
        PathKind::LinearElliptical => {
            format!("lin.-elliptical r_e = {}, d = {}", job.aspect_ratio, job.linear_distance)
        }
    };
    match job.direction {
        Direction::Conventional => label,
        Direction::Climb => format!("{label}, climb"),
    }
}

/// The paper's comparison set built on `job`: circular (r_e = 1), elliptical r_e = 0.8 and
/// linear-elliptical r_e = 0.8 with d = s.
pub fn paper_set(job: &Job) -> Vec<Job> {
    vec![
        Job { path: PathKind::Circular, aspect_ratio: 1.0, ..job.clone() },
        Job { path: PathKind::Elliptical, aspect_ratio: 0.8, ..job.clone() },
        Job { path: PathKind::LinearElliptical, aspect_ratio: 0.8, linear_distance: job.step, ..job.clone() },
    ]
}

/// Draw the pin list and the metrics table.
pub fn show(ui: &mut egui::Ui, variants: &[VariantView], can_pin: bool) -> Option<Command> {
    let mut cmd = ui.horizontal_wrapped(|ui| pin_buttons(ui, variants, can_pin)).inner;
    if variants.is_empty() {
        ui.label(
            "No variants pinned. Pin the current job, change a parameter, pin again: every plot overlays the pins.",
        );
        return cmd;
    }
    ui.add_space(4.0);
    // scroll bars that stay visible (not egui's floating ones) where the table is still too big
    ui.scope(|ui| {
        ui.spacing_mut().scroll = egui::style::ScrollStyle::solid();
        let bar = ui.spacing().scroll.allocated_width();
        let widths = column_widths(ui.available_width() - bar, variants.len(), COLUMN_GAP);
        // at most 40 % of the height: the plots below keep the rest
        let area = egui::ScrollArea::both().max_height((ui.available_height() * 0.4).max(120.0));
        area.show(ui, |ui| {
            egui::Grid::new("compare_table").striped(true).spacing([COLUMN_GAP, 4.0]).show(ui, |ui| {
                cmd = header_row(ui, variants, widths).or(cmd);
                for q in quantities() {
                    quantity_row(ui, q, variants, widths);
                }
            });
            let table_width = widths.0 + variants.len() as f32 * (widths.1 + COLUMN_GAP);
            cell(ui, table_width, |ui| {
                ui.add(
                    egui::Label::new(
                        RichText::new(
                            "% change against variant #1. Green: better, red: worse, by at least 0.05 % (MRR and \
                         cooling time up, h_max, engagement and waviness down). The paper ranks paths by \
                         PI = MRR/(F_R,max·Ra,max·W_max), eq. (7): the forces are modelled, the roughness Ra,max \
                         is not; PI has a value once Ra,max is entered in the Material and process fields \
                         (— (no value) until then).",
                        )
                        .weak(),
                    )
                    .wrap(),
                )
            });
        });
    });
    cmd
}

/// Horizontal gap between the table's columns (px).
const COLUMN_GAP: f32 = 10.0;
/// Narrowest column of a variant (px): a value over its change, "(+1278.4 %)", on two lines.
const MIN_COLUMN: f32 = 88.0;

/// Widths of the table's first column (the quantities) and of each of `n` variant columns,
/// sharing `avail` px with `gap` between columns; the variant columns never narrower than
/// [`MIN_COLUMN`] (the table scrolls then).
fn column_widths(avail: f32, n: usize, gap: f32) -> (f32, f32) {
    let first = (avail * 0.28).clamp(100.0, 240.0);
    let n = n.max(1) as f32;
    (first, ((avail - first - gap * n) / n).max(MIN_COLUMN))
}

/// A table cell `width` px wide whose labels wrap within it.
fn cell<R>(ui: &mut egui::Ui, width: f32, add: impl FnOnce(&mut egui::Ui) -> R) -> R {
    ui.vertical(|ui| {
        ui.set_width(width);
        add(ui)
    })
    .inner
}

/// Pin the current job, pin the paper's set, clear the pins.
fn pin_buttons(ui: &mut egui::Ui, variants: &[VariantView], can_pin: bool) -> Option<Command> {
    let mut cmd = None;
    let full = variants.len() >= MAX_VARIANTS;
    if ui
        .add_enabled(can_pin && !full, egui::Button::new("Pin current job"))
        .on_hover_text("Add the current job as a variant (up to four); it is overlaid in every plot.")
        .on_disabled_hover_text("Needs a valid job and fewer than four pinned variants.")
        .clicked()
    {
        cmd = Some(Command::Pin);
    }
    if ui
        .button("Pin the paper's set")
        .on_hover_text("Replace the pins by: circular (r_e = 1), elliptical r_e = 0.8 and linear-elliptical r_e = 0.8 with d = s, all with the current slot, tool and cutting data.")
        .clicked()
    {
        cmd = Some(Command::PinPaperSet);
    }
    if ui.add_enabled(!variants.is_empty(), egui::Button::new("Clear pins")).clicked() {
        cmd = Some(Command::ClearPins);
    }
    cmd
}

/// The table's first row: each variant's name with its load and unpin buttons.
fn header_row(ui: &mut egui::Ui, variants: &[VariantView], (first, width): (f32, f32)) -> Option<Command> {
    let mut cmd = None;
    cell(ui, first, |ui| ui.label(RichText::new("variant").strong()));
    for (i, v) in variants.iter().enumerate() {
        cell(ui, width, |ui| {
            let name = RichText::new(format!("#{} {}", i + 1, v.label)).color(v.color).strong();
            ui.add(egui::Label::new(name).wrap());
            ui.horizontal_wrapped(|ui| {
                if ui.small_button("load").on_hover_text("Make this the job being edited (undoable).").clicked() {
                    cmd = Some(Command::LoadPinned(i));
                }
                if ui.small_button("unpin").on_hover_text("Unpin").clicked() {
                    cmd = Some(Command::Unpin(i));
                }
            });
        });
    }
    ui.end_row();
    cmd
}

/// Shown for a quantity without a value (PI without a measured Ra,max).
const NO_VALUE: &str = "— (no value)";

/// One quantity of every variant, with the % change against the first coloured by whether it
/// is better.
fn quantity_row(ui: &mut egui::Ui, q: &Metric, variants: &[VariantView], (first, width): (f32, f32)) {
    cell(ui, first, |ui| ui.add(egui::Label::new(q.heading()).wrap()).on_hover_text(q.about));
    let base = q.of(variants[0].metrics);
    for (i, v) in variants.iter().enumerate() {
        let x = q.of(v.metrics);
        let change = if i > 0 { percent_change(x, base) } else { None };
        let text = match change {
            _ if !x.is_finite() => NO_VALUE.to_owned(),
            Some(p) => format!("{x:.*}  ({p:+.1} %)", q.decimals),
            None => format!("{x:.*}", q.decimals),
        };
        let text = RichText::new(text).monospace();
        let text = match change.and_then(|p| change_color(q, p)) {
            Some(c) => text.color(c),
            None => text,
        };
        // the change wraps under the value in a narrow column
        cell(ui, width, |ui| ui.add(egui::Label::new(text).wrap()));
    }
    ui.end_row();
}

/// Green for a change of at least 0.05 % for the better, red for the worse; none for a small
/// change or a quantity that is neither better high nor low.
fn change_color(q: &Metric, percent: f64) -> Option<Color32> {
    let up = q.higher_is_better.filter(|_| percent.abs() >= 0.05)?;
    Some(if (percent > 0.0) == up { Color32::from_rgb(30, 140, 60) } else { Color32::from_rgb(200, 50, 40) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percent_change_against_first() {
        assert!((percent_change(110.0, 100.0).unwrap_or(0.0) - 10.0).abs() < 1e-12);
        assert!((percent_change(90.0, 100.0).unwrap_or(0.0) + 10.0).abs() < 1e-12);
        assert_eq!(percent_change(1.0, 0.0), None);
        assert_eq!(percent_change(f64::NAN, 1.0), None, "no value: no change");
    }

    #[test]
    fn four_variants_share_the_width_of_a_small_screens_table() {
        // 1366 px wide window: the tab between the parameters and the derived values is ~600 px
        let (first, w) = column_widths(600.0, 4, COLUMN_GAP);
        assert!(w > MIN_COLUMN, "{w}");
        assert!((first + 4.0 * (w + COLUMN_GAP) - 600.0).abs() < 1e-3, "{first} + 4 × {w}");
        assert_eq!(column_widths(300.0, 4, COLUMN_GAP).1, MIN_COLUMN, "narrower: the table scrolls");
    }

    #[test]
    fn labels_tell_climb_from_the_papers_conventional_loops() {
        let conv = Job { path: PathKind::Elliptical, aspect_ratio: 0.8, ..Job::default() };
        assert_eq!(variant_label(&conv), "elliptical r_e = 0.8");
        let climb = Job { direction: Direction::Climb, ..conv };
        assert_eq!(variant_label(&climb), "elliptical r_e = 0.8, climb");
    }
}
