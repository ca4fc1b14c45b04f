//! The plots of a plan (and of pinned variants, overlaid). Each function only converts cached
//! [`Graphics`] into a list of curves ([`Series`], coloured from the [`palette`]) and hands them
//! to egui_plot below their legend; no geometry is computed here.

use super::graphics::{Chip, Graphics};
use super::legend::{self, Look, Series, Shape};
use super::palette;
use eframe::egui::{self, Color32, RichText};
use egui_plot::{AxisHints, LineStyle, Plot, PlotPoint, PlotPoints, PlotUi, Points, Text};
use trochoplan_core::plan::ENGAGEMENT_LIMIT_DEG;

/// One plan as drawn: its data, a name for the legend and a colour.
pub struct Layer<'a> {
    pub name: &'a str,
    pub color: Color32,
    pub g: &'a Graphics,
    /// Waviness (W_l, W_r) in mm, marked in the wall plot.
    pub w: (f64, f64),
    /// The plan being edited (drawn with markers, cursor and annotations).
    pub primary: bool,
}

/// Where the animation is: time in the steady-state cycle and the tooth there.
#[derive(Clone, Copy, Debug)]
pub struct Cursor {
    /// Index of the tooth in `Plan::series`.
    pub tooth: usize,
    pub t_s: f64,
    /// Tool centre at that tooth, relative to the cycle origin (mm).
    pub centre: [f64; 2],
    pub h_mm: f64,
    pub engagement_deg: f64,
    pub cutting: bool,
}

/// Colours of the variants: the edited plan first, pinned ones after (defined in the palette).
pub use super::palette::VARIANTS as PALETTE;

/// The plots' titles.
pub mod titles {
    pub const PATH: &str = "Path view";
    pub const H: &str = "Chip thickness h over one steady-state cycle (Fig. 7)";
    pub const ENGAGEMENT: &str = "Engagement angle over one cycle";
    pub const WALLS: &str = "Wall profiles: left solid, right dashed (Figs. 8–9)";
    pub const FORCES: &str = "Cutting forces over one steady-state cycle (Figs. 14–15)";
    pub const IMPRINTS: &str = "Edge imprints on the slot bottom (Figs. 21–22)";
    pub const CHIP: &str = "Chip of the current tooth (zoomed)";
    pub const CHIP_CLOSE_UP: &str = "Chip of the current tooth (close-up)";
    /// Every title.
    #[cfg(test)]
    pub const ALL: [&str; 8] = [PATH, H, ENGAGEMENT, WALLS, FORCES, IMPRINTS, CHIP, CHIP_CLOSE_UP];
}

/// Explanations (teaching mode and hover): formula and source of each plot.
pub mod explain {
    pub const PATH: &str = "Tool-centre path C₁, Wagih et al. (2023) eq. (1): x = −a·cos θ, \
        y = b·sin θ + s·θ/2π, with a = (B − D)/2 and b = r_e·a (eq. 2). Dashed: the tool edge of the \
        previous cycle C₂, the offset of C₁ by R (eq. 3); shaded: the region that cycle swept. Circle: the tool C₃ (eq. 5) at the current \
        tooth, red while it cuts. Grey lines: the slot walls x = ±B/2. Equal axis scale.";
    pub const CHIP: &str = "Chip cut by the current tooth: between this \
        tooth's edge C₃ (eq. 5), the previous tooth's edge f_z back and the previous cycle's edge \
        C₂ (eq. 3); its thickness along the ray from the tool centre is h (eqs. 4, 6).";
    pub const H: &str = "Local maximum chip thickness per tooth, h = |DB| (eq. 4): B is where the \
        previous tooth's circle meets the previous cycle's edge C₂ (eqs. 3, 5), D the point of the \
        current tool circle on the ray O_C-B (eq. 6). Teeth are f_z = f_r/(n·z) apart along the path. \
        Shaded: no tooth cuts (cooling time). Bar: t_hmax, from the start of cutting to h_max \
        (paper Fig. 7, Table 2).";
    pub const ENGAGEMENT: &str = "Engagement angle: the arc of the tool edge in uncut material, \
        bounded by the previous cycle's edge C₂ (eq. 3). Grechishnikov et al. (2017) recommend \
        ≤ 46°; the step keeping the two-circle model (Wu et al. 2016, eqs. 2–6) at 46° is shown in \
        the derived values.";
    pub const WALLS: &str = "Wall profile left by the tool disc swept along the path, as deviation \
        from the deepest point of each wall (paper section 2.3: eq. (3) evaluated at the walls; \
        Figs. 8–9). Waviness W = peak-to-valley height; its spacing is the step s. Smaller r_e \
        raises W (Fig. 9); a linear distance d along the walls lowers it (Figs. 12, 28).";
    pub const FORCES: &str = "Cutting forces on the tool over one steady-state cycle (paper \
        Figs. 14–15): linear edge-force model with helix (Altintas & Lee 1996). \
        Every tooth, every axial slice dz = a_p/50, spindle steps ≤ 1°: dF_t = (Ktc·h + Kte)·dz, \
        dF_r = (Krc·h + Kre)·dz, dF_a = (Kac·h + Kae)·dz with h(φ) the chip thickness at the slice's \
        angle on the engaged arc (the same material model as h, eqs. 3–6); F_R = sqrt(Fx² + Fy² + Fz²). \
        Dashed: mean F_R while cutting. Peaks every tooth pass (z per revolution).";
    pub const WHY_EARLY: &str = "Why F_R peaks early in an elliptical loop: h_max (eq. 4) is the \
        thickest point of one chip, but the force integrates the whole engaged arc over the \
        helix. On an ellipse (r_e < 1) the loop turns sharply at the wall and then runs along the \
        slot, so the engaged arc is widest just after the turn and the force peaks there, while h \
        keeps growing slowly towards h_max: the force rises fast and decays slowly (paper: peak at \
        9.7 % of the cycle for r_e = 0.8, 16 % for the circle, 5–6 % before h_max). On the circle \
        the arc grows and shrinks at the same rate.";
    pub const IMPRINTS: &str = "Imprints of the cutting edges on the slot bottom (paper Figs. 21–22): \
        the circle of the edges (radius R) drawn at every tooth position, f_z apart along the path; \
        density = crossings of these circles with the line x = X, per mm of y, from the left wall \
        to the right wall. More imprints: lower bottom roughness (section 5.2.2).";
}

fn title(ui: &mut egui::Ui, text: &str, explanation: &str, teach: bool) {
    ui.horizontal(|ui| {
        // a narrow cell wraps the title onto a second line instead of growing or cutting it
        ui.scope(|ui| {
            ui.set_max_width((ui.available_width() - 28.0).max(40.0));
            ui.add(egui::Label::new(RichText::new(text).strong()).wrap()).on_hover_text(explanation);
        });
        ui.label(RichText::new("(?)").weak()).on_hover_text(explanation);
    });
    if teach {
        ui.add(egui::Label::new(RichText::new(explanation).weak()).wrap());
    }
}

/// An x axis whose tick labels may sit closer than egui_plot's default (60 px), so that narrow
/// plots still get several labels.
fn x_axis(label: &str) -> Vec<AxisHints<'static>> {
    vec![AxisHints::new_x().label(label.to_owned()).label_spacing(28.0..=44.0)]
}

/// A plot filling the rest of the cell the caller allocated, without egui_plot's legend (which
/// would cover the curves: [`show_series`] draws the legend above the plot).
fn base_plot(ui: &egui::Ui, id: &str) -> Plot<'static> {
    let size = ui.available_size();
    Plot::new(id).width(size.x.max(120.0)).height(size.y.max(80.0)).allow_scroll(false)
}

/// Points of a circle drawn at the path view's scale.
const CIRCLE_POINTS: usize = 72;
/// Points of a circle that looks round when zoomed onto a chip (0.1 mm view of a 5 mm radius).
const FINE_CIRCLE_POINTS: usize = 1440;

/// `n + 1` points around the circle of centre `c` and radius `r` (the first repeated last).
fn circle(c: [f64; 2], r: f64, n: usize) -> Vec<[f64; 2]> {
    (0..=n)
        .map(|i| {
            let a = i as f64 / n as f64 * std::f64::consts::TAU;
            [c[0] + r * a.cos(), c[1] + r * a.sin()]
        })
        .collect()
}

/// The legend's names and colours of `layers`.
fn keys<'l>(layers: &'l [Layer]) -> Vec<(&'l str, Color32)> {
    layers.iter().map(|l| (l.name, l.color)).collect()
}

/// `series` drawn into `plot` (id `id`) below their legend, then `marks` (markers and text,
/// which are not curves). A click on a legend entry hides its curves (a variant's: all of
/// them), another shows them again.
fn show_series<'a>(
    ui: &mut egui::Ui,
    layers: &[Layer],
    id: &str,
    series: Vec<Series<'a>>,
    plot: impl FnOnce(Plot<'a>) -> Plot<'a>,
    marks: impl FnOnce(&mut PlotUi<'a>) + 'a,
) {
    let keys = keys(layers);
    // the legend takes at most a fifth of the cell's height; the plot keeps the rest
    let row = ui.text_style_height(&egui::TextStyle::Small).max(10.0) + legend::ROW_GAP;
    let max_rows = ((0.2 * ui.available_height()) / row).floor().max(1.0) as usize;
    let _legend = legend::show_toggling(ui, id, &legend::entries(&keys, &series), max_rows);
    // the curves whose legend entry was clicked are not drawn
    let hidden = legend::hidden(ui.ctx(), id);
    let series: Vec<Series<'a>> = series.into_iter().filter(|s| !legend::is_hidden(&hidden, &keys, s)).collect();
    #[cfg(test)]
    let drawn = legend::record::drawn(&series);
    let names: Vec<String> = series.iter().map(|s| legend::hover_name(&keys, s)).collect();
    let _shown = plot(base_plot(ui, id)).show(ui, move |p| {
        for (s, name) in series.into_iter().zip(names) {
            s.draw(p, name);
        }
        marks(p);
    });
    #[cfg(test)]
    legend::record::keep(ui.ctx(), id, legend::record::Plot { drawn, legend: _legend, data: _shown.response.rect });
}

/// Path view: tool-centre path over a few cycles, slot walls, previous cycle's edge and the tool
/// at the cursor with the chip it cuts (`chip`: closed outline, absolute mm; empty when the tooth
/// cuts nothing). Equal axis scale.
pub fn path_view(ui: &mut egui::Ui, layers: &[Layer], cursor: Option<Cursor>, chip: &Chip, teach: bool) {
    title(ui, titles::PATH, explain::PATH, teach);
    let mut series = layers.first().map(|l| slot_walls(l.g)).unwrap_or_default();
    for (k, l) in layers.iter().enumerate() {
        series.extend(layer_path(k, l));
    }
    let at_cursor = layers.iter().find(|l| l.primary).zip(cursor).map(|(l, c)| (l.g, c));
    if let Some((g, c)) = at_cursor {
        series.extend(tool_at_cursor(g, c, chip));
    }
    show_series(
        ui,
        layers,
        "path_view",
        series,
        |p| p.data_aspect(1.0).custom_x_axes(x_axis("x [mm]")).y_axis_label("y [mm]"),
        move |p| {
            if let Some((g, c)) = at_cursor {
                cursor_readout(p, g, c);
            }
        },
    );
}

/// The slot walls over the drawn range (within the slot), and the stock face y = 0 where the
/// range reaches it.
fn slot_walls(g: &Graphics) -> Vec<Series<'static>> {
    let (y0, y1) = (g.y_range.0.max(0.0), g.y_range.1.min(g.slot_length));
    let (y0, y1) = if y0 < y1 { (y0, y1) } else { g.y_range };
    let mut out: Vec<Series> = [-g.half_width, g.half_width]
        .into_iter()
        .map(|x| {
            let wall = vec![[x, y0], [x, y1]];
            Series::new(None, "slot walls", Look::solid(palette::WALL, 2.0), Shape::Line(wall.into()))
        })
        .collect();
    if g.y_range.0 < 0.0 && g.y_range.1 > 0.0 {
        let face = vec![[-g.half_width, 0.0], [g.half_width, 0.0]];
        let look = Look::solid(palette::WALL, 1.0).styled(LineStyle::dashed_dense());
        out.push(Series::new(None, "stock face y = 0", look, Shape::Line(face.into())));
    }
    out
}

/// Layer `k`'s tool-centre path (the current cycle bold, the others faint) and the previous
/// cycle's edge; for the edited plan also the region that cycle swept.
fn layer_path<'a>(k: usize, l: &Layer<'a>) -> Vec<Series<'a>> {
    let g = l.g;
    let line = |what: &str, look: Look, pts: &'a [PlotPoint]| {
        Series::new(Some(k), what, look, Shape::Line(PlotPoints::Borrowed(pts)))
    };
    let faint = Look::solid(l.color.gamma_multiply(0.45), 1.0);
    let mut out = vec![
        line("current cycle", Look::solid(l.color, 2.0), &g.path_current),
        line("other cycles", faint, &g.path_before),
        line("other cycles", faint, &g.path_after),
    ];
    if l.primary {
        // The previous cycle's sweep is convex (core: analysis::edge), so its edge
        // closed by the step chord fills correctly as a convex polygon.
        let look = Look::area(l.color.gamma_multiply(0.07), l.color, 0.0);
        let shape = Shape::Polygon(PlotPoints::Borrowed(&g.previous_edge));
        out.push(Series::new(Some(k), "swept by the previous cycle", look, shape));
    }
    let edge = Look::solid(l.color, 1.2).styled(LineStyle::dashed_loose());
    out.push(line("previous cycle's edge C₂", edge, &g.previous_edge));
    out
}

/// The tool at the cursor (red while it cuts), the path it took this cycle and its chip.
fn tool_at_cursor<'a>(g: &Graphics, c: Cursor, chip: &'a Chip) -> Vec<Series<'a>> {
    let centre = [g.origin[0] + c.centre[0], g.origin[1] + c.centre[1]];
    let mut trail: Vec<[f64; 2]> = g.teeth.iter().take_while(|(t, _)| *t <= c.t_s).map(|(_, p)| [p.x, p.y]).collect();
    trail.push(centre);
    let tool = if c.cutting {
        Look::area(palette::CURSOR.gamma_multiply(0.18), palette::CURSOR, 2.5)
    } else {
        Look::area(palette::TOOL.gamma_multiply(0.12), palette::TOOL, 2.0)
    };
    let mut out = vec![
        Series::new(None, "path so far this cycle", Look::solid(palette::CURSOR, 3.0), Shape::Line(trail.into())),
        Series::new(
            None,
            "tool at current tooth",
            tool,
            Shape::Polygon(circle(centre, g.tool_r, CIRCLE_POINTS).into()),
        ),
    ];
    out.extend(chip_series(chip, "chip of the current tooth", 0.9, 1.5));
    out
}

/// The tool centre at the cursor and the readout of h and the engagement above the tool.
fn cursor_readout(p: &mut PlotUi<'_>, g: &Graphics, c: Cursor) {
    let centre = [g.origin[0] + c.centre[0], g.origin[1] + c.centre[1]];
    let color = if c.cutting { palette::CURSOR } else { palette::TOOL };
    p.points(Points::new("", vec![centre]).radius(4.0).color(color));
    p.text(
        Text::new(
            "",
            PlotPoint::new(centre[0], centre[1] + g.tool_r),
            format!("h = {:.4} mm, {:.1}°", c.h_mm, c.engagement_deg),
        )
        .anchor(egui::Align2::CENTER_BOTTOM)
        .color(color),
    );
}

/// Lower and upper corner of a plot's bounds (mm).
type Bounds = ([f64; 2], [f64; 2]);

/// Chip view: the path view zoomed onto the chip of the current tooth (a chip is ~0.06 mm thick
/// and a few mm long: invisible at the path view's scale). The bounds follow the chip
/// ([`chip_bounds`]); while no tooth cuts, the view shows the tool and says so. Equal axis scale.
pub fn chip_view(
    ui: &mut egui::Ui,
    layers: &[Layer],
    cursor: Option<Cursor>,
    chip: &Chip,
    close_up: bool,
    teach: bool,
) {
    let what = if close_up { titles::CHIP_CLOSE_UP } else { titles::CHIP };
    title(ui, what, explain::CHIP, teach);
    let Some(l) = layers.iter().find(|l| l.primary) else { return };
    let g = l.g;
    let centre = cursor.map(|c| [g.origin[0] + c.centre[0], g.origin[1] + c.centre[1]]);
    let bounds = chip_bounds(g, centre, cursor, chip, close_up);
    // about square (equal scale), with room below for the readout
    let side = ui.available_width().min(ui.available_height() - 40.0).max(80.0);
    // no legend: it would hide the chip in this small view; the readout below names the lines
    Plot::new("chip_view")
        .width(ui.available_width().max(80.0))
        .height(side)
        .data_aspect(1.0)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .custom_x_axes(x_axis("x [mm]"))
        .y_axis_label("y [mm]")
        .show(ui, |p| {
            if let Some((lo, hi)) = bounds {
                p.set_plot_bounds(egui_plot::PlotBounds::from_min_max(lo, hi));
            }
            chip_items(p, l, centre, cursor, chip);
        });
    if let Some(c) = cursor {
        ui.add(egui::Label::new(RichText::new(chip_readout(c, chip)).small()).wrap());
    }
}

/// Bounds of the chip view: the chip's box with a margin, or with `close_up` a square of 8·h
/// around the middle of the chip (halfway between the middle points of its outer and inner side,
/// which is where h usually is); the tool at `centre` when there is no chip.
fn chip_bounds(
    g: &Graphics,
    centre: Option<[f64; 2]>,
    cursor: Option<Cursor>,
    chip: &Chip,
    close_up: bool,
) -> Option<Bounds> {
    let square = |mid: [f64; 2], half: f64| ([mid[0] - half, mid[1] - half], [mid[0] + half, mid[1] + half]);
    if chip.outline.is_empty() {
        centre.map(|c| square(c, 1.2 * g.tool_r))
    } else if close_up {
        let pts = &chip.outline[..chip.outline.len() - 1];
        let n = pts.len();
        let (a, b) = (pts[n / 4], pts[n - 1 - n / 4]);
        let half = cursor.map_or(0.1, |c| (4.0 * c.h_mm).max(0.1));
        Some(square([0.5 * (a.x + b.x), 0.5 * (a.y + b.y)], half))
    } else {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in &chip.outline {
            lo = [lo[0].min(p.x), lo[1].min(p.y)];
            hi = [hi[0].max(p.x), hi[1].max(p.y)];
        }
        let m = 0.15 * (hi[0] - lo[0]).max(hi[1] - lo[1]).max(0.05);
        Some(([lo[0] - m, lo[1] - m], [hi[0] + m, hi[1] + m]))
    }
}

/// The chip view's items: the previous cycle's edge, the tool edge at `centre`, and the chip
/// with its h (or a note that the tooth cuts nothing).
fn chip_items<'a>(
    p: &mut egui_plot::PlotUi<'a>,
    l: &Layer<'a>,
    centre: Option<[f64; 2]>,
    cursor: Option<Cursor>,
    chip: &'a Chip,
) {
    let edge = Look::solid(l.color, 1.2).styled(LineStyle::dashed_loose());
    let edge_points = PlotPoints::Borrowed(&l.g.previous_edge);
    Series::new(None, "", edge, Shape::Line(edge_points)).draw(p, "previous cycle's edge C₂".to_owned());
    if let Some(c) = centre {
        let tool = Shape::Line(circle(c, l.g.tool_r, FINE_CIRCLE_POINTS).into());
        Series::new(None, "", Look::solid(palette::TOOL, 1.5), tool).draw(p, "tool edge at current tooth".to_owned());
    }
    let Some(chip_area) = chip_series(chip, "chip", 0.6, 2.0) else {
        if let Some(c) = centre {
            p.text(
                Text::new("", PlotPoint::new(c[0], c[1]), "no chip: this tooth cuts nothing (cooling)")
                    .color(palette::TOOL),
            );
        }
        return;
    };
    chip_area.draw(p, "chip".to_owned());
    if let Some(c) = cursor {
        let outline = &chip.outline;
        let top = outline.iter().map(|p| p.y).fold(f64::NEG_INFINITY, f64::max);
        let xs = outline.iter().map(|p| p.x).sum::<f64>() / outline.len() as f64;
        p.text(
            Text::new("", PlotPoint::new(xs, top), format!("h = {:.4} mm", c.h_mm))
                .anchor(egui::Align2::CENTER_BOTTOM)
                .color(palette::CURSOR),
        );
    }
}

/// The line under the chip view: the tooth, its h and engagement, and what the lines are.
fn chip_readout(c: Cursor, chip: &Chip) -> String {
    if chip.outline.is_empty() {
        format!("tooth {}: no chip (cooling)", c.tooth)
    } else {
        format!(
            "tooth {}: h = {:.4} mm, {:.1}° engaged. True scale; red: chip, grey: tool edge, \
             dashed: previous cycle's edge",
            c.tooth, c.h_mm, c.engagement_deg
        )
    }
}

/// The chip as an area (convex quads) and its outline; nothing while the tooth cuts nothing.
fn chip_series<'a>(chip: &'a Chip, what: &str, fill_alpha: f32, width: f32) -> Option<Series<'a>> {
    if chip.outline.is_empty() {
        return None;
    }
    let quads = chip.fill.iter().map(|q| q.iter().map(|p| [p.x, p.y]).collect()).collect();
    let look = Look::area(palette::CURSOR.gamma_multiply(fill_alpha), palette::CURSOR, width);
    Some(Series::new(None, what, look, Shape::Pieces(PlotPoints::Borrowed(&chip.outline), quads)))
}

/// A line of layer `k` (None: a colour of its own) through `pts`.
fn line<'a>(k: Option<usize>, what: impl Into<String>, look: Look, pts: &'a [PlotPoint]) -> Series<'a> {
    Series::new(k, what, look, Shape::Line(PlotPoints::Borrowed(pts)))
}

/// The current tooth as a vertical line at its time.
fn cursor_line(c: Cursor) -> Series<'static> {
    Series::new(None, "current tooth", Look::solid(palette::CURSOR, 1.5), Shape::VLine(c.t_s))
}

/// The curves of the h plot: h of every layer; for the edited plan the cooling intervals, h_max
/// and t_hmax; the current tooth.
fn h_series<'a>(layers: &[Layer<'a>], cursor: Option<Cursor>) -> Vec<Series<'a>> {
    let mut out = Vec::new();
    for (k, l) in layers.iter().enumerate() {
        let g = l.g;
        if l.primary {
            let cooling = Look::area(palette::COOLING_FILL, palette::COOLING_FILL, 0.0);
            out.extend(g.cooling.iter().map(|&(a, b)| Series::new(None, "cooling", cooling, Shape::Span(a, b))));
        }
        out.push(line(Some(k), "h", Look::solid(l.color, 1.5), &g.h));
        if l.primary {
            let h = g.h_max_at.1;
            let look = Look::solid(l.color.gamma_multiply(0.6), 1.0).styled(LineStyle::dashed_dense());
            out.push(Series::new(Some(k), "h_max", look, Shape::HLine(h)));
            for &(a, b) in &g.t_hmax_spans {
                let bar = vec![[a, h * 1.06], [b, h * 1.06]];
                out.push(Series::new(None, "t_hmax", Look::solid(palette::TIME_TO_PEAK, 3.0), Shape::Line(bar.into())));
            }
        }
    }
    out.extend(cursor.map(cursor_line));
    out
}

/// h over one steady-state cycle with h_max, t_hmax and the cooling intervals.
pub fn h_plot(ui: &mut egui::Ui, layers: &[Layer], cursor: Option<Cursor>, teach: bool) {
    title(ui, titles::H, explain::H, teach);
    let series = h_series(layers, cursor);
    let marks: Vec<(f64, f64, Color32, bool)> =
        layers.iter().map(|l| (l.g.h_max_at.0, l.g.h_max_at.1, l.color, l.primary)).collect();
    show_series(
        ui,
        layers,
        "h_plot",
        series,
        |p| p.custom_x_axes(x_axis("t [s]")).y_axis_label("h [mm]").include_y(0.0),
        move |p| {
            for (t, h, color, primary) in marks {
                p.points(Points::new("", vec![[t, h]]).radius(5.0).color(color));
                if primary {
                    p.text(
                        Text::new("", PlotPoint::new(t, h * 1.12), format!("h_max = {h:.4} mm"))
                            .anchor(egui::Align2::CENTER_BOTTOM)
                            .color(color),
                    );
                }
            }
            if let Some(c) = cursor {
                p.points(Points::new("", vec![[c.t_s, c.h_mm]]).radius(5.0).color(palette::CURSOR));
            }
        },
    );
}

/// The curves of the engagement plot: the recommended limit, every layer's engagement, the
/// current tooth.
fn engagement_series<'a>(layers: &[Layer<'a>], cursor: Option<Cursor>) -> Vec<Series<'a>> {
    let limit = Look::solid(palette::LIMIT, 1.0).styled(LineStyle::dashed_dense());
    let mut out = vec![Series::new(
        None,
        "46° recommended (Grechishnikov et al. 2017)",
        limit,
        Shape::HLine(ENGAGEMENT_LIMIT_DEG),
    )];
    for (k, l) in layers.iter().enumerate() {
        out.push(line(Some(k), "engagement", Look::solid(l.color, 1.5), &l.g.engagement));
    }
    out.extend(cursor.map(cursor_line));
    out
}

/// Engagement angle over one steady-state cycle, with the 46° recommendation.
pub fn engagement_plot(ui: &mut egui::Ui, layers: &[Layer], cursor: Option<Cursor>, teach: bool) {
    title(ui, titles::ENGAGEMENT, explain::ENGAGEMENT, teach);
    let series = engagement_series(layers, cursor);
    show_series(
        ui,
        layers,
        "engagement_plot",
        series,
        |p| p.custom_x_axes(x_axis("t [s]")).y_axis_label("engagement [°]").include_y(0.0),
        move |p| {
            if let Some(c) = cursor {
                p.points(Points::new("", vec![[c.t_s, c.engagement_deg]]).radius(5.0).color(palette::CURSOR));
            }
        },
    );
}

/// The curves of the wall plot: every layer's left wall (solid) and right wall (dashed); for the
/// edited plan its waviness W_l (dotted) and W_r (loosely dotted).
fn wall_series<'a>(layers: &[Layer<'a>]) -> Vec<Series<'a>> {
    let mut out = Vec::new();
    for (k, l) in layers.iter().enumerate() {
        let (w_l, w_r) = l.w;
        out.push(line(Some(k), "left wall", Look::solid(l.color, 1.8), &l.g.wall_left));
        let right = Look::solid(l.color, 1.8).styled(LineStyle::dashed_dense());
        out.push(line(Some(k), "right wall (dashed)", right, &l.g.wall_right));
        if l.primary {
            let look = Look::solid(l.color, 1.0);
            let w = format!("W_l = {w_l:.4} mm");
            out.push(Series::new(Some(k), w, look.styled(LineStyle::dotted_dense()), Shape::HLine(w_l)));
            let w = format!("W_r = {w_r:.4} mm");
            out.push(Series::new(Some(k), w, look.styled(LineStyle::dotted_loose()), Shape::HLine(w_r)));
        }
    }
    out
}

/// Left and right wall deviation along y with W_l and W_r marked.
pub fn wall_plot(ui: &mut egui::Ui, layers: &[Layer], teach: bool) {
    title(ui, titles::WALLS, explain::WALLS, teach);
    show_series(
        ui,
        layers,
        "wall_plot",
        wall_series(layers),
        |p| p.custom_x_axes(x_axis("y [mm]")).y_axis_label("deviation [mm]").include_y(0.0),
        |_| {},
    );
}

/// The names of the force components, in the order of `Graphics::forces`.
const FORCE_COMPONENTS: [&str; 3] = ["Fx", "Fy", "Fz"];

/// The curves of the force plot: the edited plan's components Fx, Fy, Fz (colours of their own)
/// and its mean F_R (dashed), every layer's F_R, the current tooth.
fn force_series<'a>(layers: &[Layer<'a>], cursor: Option<Cursor>) -> Vec<Series<'a>> {
    let mut out = Vec::new();
    for (k, l) in layers.iter().enumerate() {
        let g = l.g;
        if l.primary {
            for ((curve, name), colour) in g.forces.iter().zip(FORCE_COMPONENTS).zip(palette::QUANTITIES) {
                out.push(line(None, name, Look::solid(colour, 1.0), curve));
            }
            let look = Look::solid(l.color, 1.0).styled(LineStyle::dashed_loose());
            let mean = format!("mean F_R = {:.0} N", g.force_mean);
            out.push(Series::new(Some(k), mean, look, Shape::HLine(g.force_mean)));
        }
        out.push(line(Some(k), "F_R", Look::solid(l.color, 1.5), &g.forces[3]));
    }
    out.extend(cursor.map(cursor_line));
    out
}

/// Cutting forces Fx, Fy, Fz and F_R over one steady-state cycle, the mean F_R dashed (Figs.
/// 14–15); pinned variants add their F_R.
pub fn force_plot(ui: &mut egui::Ui, layers: &[Layer], cursor: Option<Cursor>, teach: bool) {
    title(ui, titles::FORCES, explain::FORCES, teach);
    if teach {
        ui.add(egui::Label::new(RichText::new(explain::WHY_EARLY).weak()).wrap());
    }
    let peak = layers.iter().find(|l| l.primary).map(|l| (l.g.force_max_at, l.color));
    show_series(
        ui,
        layers,
        "force_plot",
        force_series(layers, cursor),
        |p| p.custom_x_axes(x_axis("t [s]")).y_axis_label("force [N]"),
        move |p| {
            if let Some(((t, f), color)) = peak {
                p.points(Points::new("", vec![[t, f]]).radius(5.0).color(color));
                p.text(
                    Text::new("", PlotPoint::new(t, f * 1.04), format!("F_R,max = {f:.0} N"))
                        .anchor(egui::Align2::CENTER_BOTTOM)
                        .color(color),
                );
            }
        },
    );
}

/// Imprint density across the slot bottom, left wall to right wall (Figs. 21–22).
pub fn imprint_plot(ui: &mut egui::Ui, layers: &[Layer], teach: bool) {
    title(ui, titles::IMPRINTS, explain::IMPRINTS, teach);
    let series = layers
        .iter()
        .enumerate()
        .map(|(k, l)| line(Some(k), "imprint density", Look::solid(l.color, 1.5), &l.g.imprints));
    show_series(
        ui,
        layers,
        "imprint_plot",
        series.collect(),
        |p| p.custom_x_axes(x_axis("X [mm] (left wall to right wall)")).y_axis_label("imprints [1/mm]").include_y(0.0),
        |_| {},
    );
}
