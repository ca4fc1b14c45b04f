//! A plot's curves as data before they are handed to egui_plot ([`Series`]: what it shows, whose
//! it is, how it looks), and the legend drawn from them in a row above the plot, outside the
//! data: a swatch of each curve's colour and line style with its name.
//!
//! With several variants drawn, the legend names each variant once by its colour and each
//! quantity once by its line style (in grey); curves of one colour of their own (force
//! components, the current tooth, limits) are named with their colour.

use eframe::egui::{self, Color32, RichText, Stroke};
use egui_plot::{HLine, Line, LineStyle, PlotPoints, PlotUi, Polygon, Span, VLine};

/// How a curve looks: colour, line style and width (px) of its line, and the colour it fills
/// (transparent for a line).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Look {
    pub color: Color32,
    pub style: LineStyle,
    pub width: f32,
    pub fill: Color32,
}

impl Look {
    /// A solid line.
    pub fn solid(color: Color32, width: f32) -> Look {
        Look { color, style: LineStyle::Solid, width, fill: Color32::TRANSPARENT }
    }

    /// An area filled with `fill`, outlined in `color` (width 0: no outline).
    pub fn area(fill: Color32, color: Color32, width: f32) -> Look {
        Look { fill, ..Look::solid(color, width) }
    }

    /// This look with another line style.
    pub fn styled(self, style: LineStyle) -> Look {
        Look { style, ..self }
    }

    /// `line` drawn in this look's colour, line style and width.
    pub fn line<'a>(self, line: Line<'a>) -> Line<'a> {
        line.color(self.color).style(self.style).width(self.width)
    }

    /// Points of `radius` px, shown in the legend as a row of dots.
    pub fn points(color: Color32, radius: f32) -> Look {
        Look::solid(color, radius).styled(LineStyle::Dotted { spacing: 7.0 })
    }
}

/// The geometry of a curve.
pub enum Shape<'a> {
    /// A polyline through the points.
    Line(PlotPoints<'a>),
    /// A horizontal line at y.
    HLine(f64),
    /// A vertical line at x.
    VLine(f64),
    /// A closed convex polygon, filled and outlined with the look.
    Polygon(PlotPoints<'a>),
    /// The band between two x values, filled with the look's fill.
    Span(f64, f64),
    /// An area made of convex pieces (filled with the look's fill) and its outline (drawn with
    /// the look's line).
    Pieces(PlotPoints<'a>, Vec<Vec<[f64; 2]>>),
}

/// One curve of a plot.
pub struct Series<'a> {
    /// The variant (index into the plot's layers) whose colour it is drawn in; None for a curve
    /// in a colour of its own.
    pub layer: Option<usize>,
    /// What it shows, in the legend; empty: not in the legend.
    pub what: String,
    pub look: Look,
    pub shape: Shape<'a>,
}

impl<'a> Series<'a> {
    /// A curve of variant `layer` (None: its own colour).
    pub fn new(layer: Option<usize>, what: impl Into<String>, look: Look, shape: Shape<'a>) -> Series<'a> {
        Series { layer, what: what.into(), look, shape }
    }

    /// Hand it to egui_plot; `name` is shown when the pointer is over the curve.
    pub fn draw(self, p: &mut PlotUi<'a>, name: String) {
        let Look { color, style, width, fill } = self.look;
        match self.shape {
            Shape::Line(points) => p.line(Line::new(name, points).color(color).style(style).width(width)),
            Shape::HLine(y) => p.hline(HLine::new(name, y).color(color).style(style).width(width)),
            Shape::VLine(x) => p.vline(VLine::new(name, x).color(color).style(style).width(width)),
            Shape::Polygon(points) => {
                p.polygon(Polygon::new(name, points).fill_color(fill).stroke(Stroke::new(width, color)).style(style));
            }
            Shape::Span(a, b) => p.add(Span::new(name, a..=b).fill(fill).border_width(0.0)),
            Shape::Pieces(outline, pieces) => {
                for piece in pieces {
                    p.polygon(Polygon::new("", piece).fill_color(fill).stroke(Stroke::new(0.0, fill)));
                }
                p.line(Line::new(name, outline).color(color).style(style).width(width));
            }
        }
    }
}

/// One entry of a legend.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    pub name: String,
    pub look: Look,
}

impl Entry {
    /// The entry `name` drawn in `look`.
    pub fn new(name: impl Into<String>, look: Look) -> Entry {
        Entry { name: name.into(), look }
    }
}

/// The legend of `series` drawn for variants named `layers` (name, colour). One variant: every
/// named curve with its look. Several: each variant by its colour, then the quantities of the
/// variants' curves by their line style in grey (when there are several), then the curves of
/// their own colour.
pub fn entries(layers: &[(&str, Color32)], series: &[Series]) -> Vec<Entry> {
    let mut out: Vec<Entry> = Vec::new();
    let mut push = |name: &str, look: Look| {
        if !name.is_empty() && !out.iter().any(|e| e.name == name) {
            out.push(Entry { name: name.to_owned(), look });
        }
    };
    let several = layers.len() > 1;
    if several {
        for (name, color) in layers {
            push(name, Look::solid(*color, 2.0));
        }
    }
    let mut quantities: Vec<&str> = series.iter().filter(|s| s.layer.is_some()).map(|s| s.what.as_str()).collect();
    quantities.dedup();
    quantities.sort_unstable();
    quantities.dedup();
    for s in series {
        match s.layer {
            Some(_) if several => {
                if quantities.len() > 1 {
                    // grey, as faint as the curve (and its fill)
                    let grey = |c: Color32| Color32::GRAY.gamma_multiply(f32::from(c.a()) / 255.0);
                    push(&s.what, Look { color: grey(s.look.color), fill: grey(s.look.fill), ..s.look });
                }
            }
            _ => push(&s.what, s.look),
        }
    }
    out
}

/// The name egui_plot shows for series `s` on hover: with several variants, the variant's name
/// before what the curve shows.
pub fn hover_name(layers: &[(&str, Color32)], s: &Series) -> String {
    match s.layer.and_then(|k| layers.get(k)) {
        Some((name, _)) if layers.len() > 1 => format!("{name}: {}", s.what),
        _ => s.what.clone(),
    }
}

/// Width and height of a swatch (px).
const SWATCH: egui::Vec2 = egui::vec2(26.0, 10.0);

/// Gap between a swatch and its name, and after an entry (px).
const GAP: f32 = 4.0;
/// Gap between the rows of a legend (px).
pub const ROW_GAP: f32 = 2.0;

/// [`show`] above a plot of fixed height: returns the height the legend takes from it (px), its
/// rows and the gap below them (0 without entries).
pub fn show_above(ui: &mut egui::Ui, entries: &[Entry], max_rows: usize) -> f32 {
    let rect = show(ui, entries, max_rows);
    if rect.is_positive() { rect.height() + ui.spacing().item_spacing.y } else { 0.0 }
}

/// The legend as a wrapped row of swatches and names above a plot, in at most `max_rows` rows:
/// the entries that do not fit are listed when the pointer is over "+N more". Returns the
/// rectangle it takes.
pub fn show(ui: &mut egui::Ui, entries: &[Entry], max_rows: usize) -> egui::Rect {
    show_entries(ui, entries, max_rows, None)
}

/// [`show`] for plot `plot_id` with entries that hide and show their curves on a click (a
/// hidden one drawn faint); [`hidden`] tells which are hidden.
pub fn show_toggling(ui: &mut egui::Ui, plot_id: &str, entries: &[Entry], max_rows: usize) -> egui::Rect {
    show_entries(ui, entries, max_rows, Some(plot_id))
}

fn hidden_id(plot_id: &str) -> egui::Id {
    egui::Id::NULL.with("hidden curves").with(plot_id)
}

/// The names of the legend entries of plot `plot_id` clicked to hide their curves.
pub fn hidden(ctx: &egui::Context, plot_id: &str) -> Vec<String> {
    ctx.data(|d| d.get_temp::<Vec<String>>(hidden_id(plot_id))).unwrap_or_default()
}

/// Whether series `s` of a plot of variants `layers` is hidden by the entries `hidden`: its
/// own name's, or (with several variants, each an entry) its variant's.
pub fn is_hidden(hidden: &[String], layers: &[(&str, Color32)], s: &Series) -> bool {
    let variant = s.layer.and_then(|k| layers.get(k)).filter(|_| layers.len() > 1).map(|(name, _)| *name);
    hidden.iter().any(|h| *h == s.what || Some(h.as_str()) == variant)
}

/// The legend of [`show`]; `toggling`: the id of the plot whose curves a click hides or shows.
fn show_entries(ui: &mut egui::Ui, entries: &[Entry], max_rows: usize, toggling: Option<&str>) -> egui::Rect {
    if entries.is_empty() {
        return egui::Rect::NOTHING;
    }
    let mut hidden_names = toggling.map(|id| hidden(ui.ctx(), id));
    let mut clicked: Option<String> = None;
    let mut draw_entry = |ui: &mut egui::Ui, e: &Entry| {
        let hidden = hidden_names.as_ref().map(|h| h.contains(&e.name));
        if entry(ui, e, hidden).clicked() {
            clicked = Some(e.name.clone());
        }
    };
    let gap = 3.0 * GAP;
    let widths: Vec<f32> = entries.iter().map(|e| entry_size(ui, e).x).collect();
    let more = more_label(entries.len());
    let more_width = entry_galley(ui, &more).size().x;
    let shown = fitting(&widths, ui.available_width(), gap, max_rows, more_width);
    let rect = ui
        .scope(|ui| {
            // rows as high as the small text, not as a button (set before the row is made)
            let row = ui.text_style_height(&egui::TextStyle::Small).max(SWATCH.y);
            ui.spacing_mut().interact_size.y = row;
            ui.spacing_mut().item_spacing = egui::vec2(gap, ROW_GAP);
            ui.horizontal_wrapped(|ui| {
                for e in &entries[..shown] {
                    draw_entry(ui, e);
                }
                if let Some(rest) = entries.get(shown..).filter(|r| !r.is_empty()) {
                    ui.label(RichText::new(more_label(rest.len())).small()).on_hover_ui(|ui| {
                        for e in rest {
                            draw_entry(ui, e);
                        }
                    });
                }
            })
            .response
            .rect
        })
        .inner;
    if let (Some(id), Some(names), Some(name)) = (toggling, &mut hidden_names, clicked) {
        if let Some(i) = names.iter().position(|n| *n == name) {
            names.remove(i);
        } else {
            names.push(name);
        }
        ui.ctx().data_mut(|d| d.insert_temp(hidden_id(id), names.clone()));
    }
    rect
}

/// The label standing for `n` entries that do not fit.
fn more_label(n: usize) -> String {
    format!("+{n} more")
}

/// How many of the entries of `widths` (px) fit in `rows` rows `width` px wide, `gap` px apart:
/// all, or as many as leave room for the "+N more" label (`more` px) in the last row.
fn fitting(widths: &[f32], width: f32, gap: f32, rows: usize, more: f32) -> usize {
    let fits = |n: usize, extra: Option<f32>| {
        let (mut row, mut x) = (1, 0.0_f32);
        for w in widths[..n].iter().copied().chain(extra) {
            if x > 0.0 && x + gap + w > width {
                (row, x) = (row + 1, w);
            } else {
                x = if x > 0.0 { x + gap + w } else { w };
            }
        }
        row <= rows
    };
    if fits(widths.len(), None) {
        return widths.len();
    }
    (0..widths.len()).rev().find(|&n| fits(n, Some(more))).unwrap_or(0)
}

/// The name of an entry laid out on one line.
fn entry_galley(ui: &egui::Ui, name: &str) -> std::sync::Arc<egui::Galley> {
    let text = egui::WidgetText::from(RichText::new(name).small());
    text.into_galley(ui, Some(egui::TextWrapMode::Extend), f32::INFINITY, egui::TextStyle::Small)
}

/// The size of entry `e`: its swatch and its name.
fn entry_size(ui: &egui::Ui, e: &Entry) -> egui::Vec2 {
    let g = entry_galley(ui, &e.name).size();
    egui::vec2(SWATCH.x + GAP + g.x, SWATCH.y.max(g.y))
}

/// One entry: a short line in the entry's look and its name, one widget (so that the row wraps
/// between entries, never inside one). `hidden`: whether its curves are hidden, for an entry
/// that a click hides or shows (None: a plain entry).
fn entry(ui: &mut egui::Ui, e: &Entry, hidden: Option<bool>) -> egui::Response {
    let galley = entry_galley(ui, &e.name);
    let size = egui::vec2(SWATCH.x + GAP + galley.size().x, SWATCH.y.max(galley.size().y));
    let sense = if hidden.is_some() { egui::Sense::click() } else { egui::Sense::hover() };
    let (rect, mut response) = ui.allocate_exact_size(size, sense);
    let role = if hidden.is_some() { egui::Role::Button } else { egui::Role::Label };
    response.widget_info(|| egui::WidgetInfo::labeled(role, true, &e.name));
    if ui.is_rect_visible(rect) {
        let faint = hidden == Some(true);
        let look = if faint {
            Look { color: e.look.color.gamma_multiply(0.3), fill: e.look.fill.gamma_multiply(0.3), ..e.look }
        } else {
            e.look
        };
        let swatch_rect =
            egui::Rect::from_center_size(egui::pos2(rect.left() + SWATCH.x / 2.0, rect.center().y), SWATCH);
        swatch(ui, swatch_rect, look);
        let text_pos = egui::pos2(rect.left() + SWATCH.x + GAP, rect.center().y - galley.size().y / 2.0);
        let color = if faint { ui.visuals().weak_text_color() } else { ui.visuals().text_color() };
        ui.painter().galley(text_pos, galley, color);
    }
    if let Some(h) = hidden {
        response = response.on_hover_text(if h { "Hidden: click to show it again" } else { "Click to hide it" });
    }
    response
}

/// A short line in `look` across `rect` (a filled box for an area).
fn swatch(ui: &egui::Ui, rect: egui::Rect, look: Look) {
    let (a, b) = (rect.left_center(), rect.right_center());
    let width = look.width.clamp(1.0, 3.0);
    let painter = ui.painter();
    if look.fill != Color32::TRANSPARENT {
        painter.rect_filled(rect, 1.0, look.fill);
        if look.width <= 0.0 {
            return;
        }
    }
    match look.style {
        LineStyle::Solid => {
            painter.line_segment([a, b], Stroke::new(width, look.color));
        }
        LineStyle::Dashed { length } => {
            let gap = length * (std::f32::consts::GOLDEN_RATIO - 1.0);
            painter.extend(egui::Shape::dashed_line(&[a, b], Stroke::new(width, look.color), length, gap));
        }
        LineStyle::Dotted { spacing } => {
            painter.extend(egui::Shape::dotted_line(&[a, b], look.color, spacing, width));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_legend_keeps_to_its_rows_and_says_how_many_more() {
        // entries 50 px wide, 10 px apart, rows of 120 px: two a row (50 + 10 + 50 = 110; a third
        // would need 170)
        let widths = [50.0; 6];
        assert_eq!(fitting(&widths, 120.0, 10.0, 3, 40.0), 6, "three rows of two");
        // two rows: three entries and "+3 more" (40 px: 50 + 10 + 40 = 100 in the second row)
        assert_eq!(fitting(&widths, 120.0, 10.0, 2, 40.0), 3);
        // one row too narrow for anything but the label
        assert_eq!(fitting(&widths, 45.0, 10.0, 1, 40.0), 0);
    }
}

/// The curves last drawn in each plot, kept for the tests (which check that no two curves of
/// one plot look alike).
#[cfg(test)]
pub mod record {
    use super::*;

    /// One curve as drawn: its variant, what it shows and its look.
    #[derive(Clone, Debug, PartialEq)]
    pub struct Drawn {
        pub layer: Option<usize>,
        pub what: String,
        pub look: Look,
    }

    /// One plot as last drawn: its curves, the rectangle of its legend and of its data.
    #[derive(Clone, Debug)]
    pub struct Plot {
        pub drawn: Vec<Drawn>,
        pub legend: egui::Rect,
        pub data: egui::Rect,
    }

    fn id(plot: &str) -> egui::Id {
        egui::Id::NULL.with("drawn series").with(plot)
    }

    /// The curves of `series` as drawn.
    pub fn drawn(series: &[Series]) -> Vec<Drawn> {
        series.iter().map(|s| Drawn { layer: s.layer, what: s.what.clone(), look: s.look }).collect()
    }

    /// Keep `plot` as the plot of id `plot_id`.
    pub fn keep(ctx: &egui::Context, plot_id: &str, plot: Plot) {
        ctx.data_mut(|d| d.insert_temp(id(plot_id), plot));
    }

    /// Forget the plot of id `plot_id` (to see whether it is drawn again).
    pub fn forget(ctx: &egui::Context, plot_id: &str) {
        ctx.data_mut(|d| d.remove::<Plot>(id(plot_id)));
    }

    /// The plot of id `plot_id` as last drawn.
    pub fn get(ctx: &egui::Context, plot_id: &str) -> Option<Plot> {
        ctx.data(|d| d.get_temp(id(plot_id)))
    }
}
