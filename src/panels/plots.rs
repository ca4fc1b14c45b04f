//! The four plots of a plan (and of pinned variants, overlaid). Each function only converts
//! cached [`Graphics`] into egui_plot items; no geometry is computed here.

use super::graphics::{Chip, Graphics};
use eframe::egui::{self, Color32, RichText, Stroke};
use egui_plot::{
    AxisHints, ColorConflictHandling, Corner, HLine, Legend, Line, LineStyle, Plot, PlotPoint, PlotPoints, Points,
    Polygon, Span, Text, VLine,
};
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

/// Colours of the variants: the edited plan first, pinned ones after.
pub const PALETTE: [Color32; 5] = [
    Color32::from_rgb(30, 110, 220),
    Color32::from_rgb(220, 90, 30),
    Color32::from_rgb(40, 160, 70),
    Color32::from_rgb(170, 60, 190),
    Color32::from_rgb(200, 160, 0),
];

const COOLING_FILL: Color32 = Color32::from_rgba_unmultiplied_const(40, 120, 200, 45);
const CHIP_COLOR: Color32 = Color32::from_rgb(220, 30, 30);

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
        // a narrow cell truncates the title (full text on hover) instead of growing
        ui.scope(|ui| {
            ui.set_max_width((ui.available_width() - 28.0).max(40.0));
            ui.add(egui::Label::new(RichText::new(text).strong()).truncate()).on_hover_text(explanation);
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

/// A plot filling the rest of the cell the caller allocated.
fn base_plot(ui: &egui::Ui, id: &str) -> Plot<'static> {
    base_plot_at(ui, id, Corner::RightTop)
}

/// [`base_plot`] with the legend in `corner`.
fn base_plot_at(ui: &egui::Ui, id: &str, corner: Corner) -> Plot<'static> {
    let size = ui.available_size();
    Plot::new(id)
        .width(size.x.max(120.0))
        .height(size.y.max(80.0))
        .legend(
            Legend::default()
                .position(corner)
                .background_alpha(0.75)
                .text_style(egui::TextStyle::Small)
                .color_conflict_handling(ColorConflictHandling::PickFirst),
        )
        .allow_scroll(false)
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

/// Legend name of an item of layer `l`: with several layers, all items of a layer share its name
/// (one legend entry per variant, toggling all of its items).
fn named(layers: &[Layer], l: &Layer, what: &str) -> String {
    if layers.len() > 1 { l.name.to_owned() } else { what.to_owned() }
}

/// Path view: tool-centre path over a few cycles, slot walls, previous cycle's edge and the tool
/// at the cursor with the chip it cuts (`chip`: closed outline, absolute mm; empty when the tooth
/// cuts nothing). Equal axis scale.
pub fn path_view(ui: &mut egui::Ui, layers: &[Layer], cursor: Option<Cursor>, chip: &Chip, teach: bool) {
    title(ui, "Path view (tool centre, slot walls, previous cycle's edge)", explain::PATH, teach);
    base_plot_at(ui, "path_view", Corner::LeftBottom)
        .data_aspect(1.0)
        .custom_x_axes(x_axis("x [mm]"))
        .y_axis_label("y [mm]")
        .show(ui, |p| {
            if let Some(first) = layers.first() {
                slot_walls(p, first.g);
            }
            for l in layers {
                layer_path(p, layers, l);
                if l.primary
                    && let Some(c) = cursor
                {
                    tool_at_cursor(p, l.g, c, chip);
                }
            }
        });
}

/// The slot walls over the drawn range (within the slot), and the stock face y = 0 where the
/// range reaches it.
fn slot_walls(p: &mut egui_plot::PlotUi<'_>, g: &Graphics) {
    let (y0, y1) = (g.y_range.0.max(0.0), g.y_range.1.min(g.slot_length));
    let (y0, y1) = if y0 < y1 { (y0, y1) } else { g.y_range };
    let wall = Stroke::new(2.0, Color32::GRAY);
    for x in [-g.half_width, g.half_width] {
        p.line(Line::new("slot walls", vec![[x, y0], [x, y1]]).stroke(wall));
    }
    if g.y_range.0 < 0.0 && g.y_range.1 > 0.0 {
        p.line(
            Line::new("stock face y = 0", vec![[-g.half_width, 0.0], [g.half_width, 0.0]])
                .stroke(Stroke::new(1.0, Color32::GRAY))
                .style(LineStyle::dashed_dense()),
        );
    }
}

/// One layer's tool-centre path (the current cycle bold, the others faint) and the previous
/// cycle's edge; for the edited plan also the region that cycle swept.
fn layer_path<'a>(p: &mut egui_plot::PlotUi<'a>, layers: &[Layer], l: &Layer<'a>) {
    let g = l.g;
    let faint = l.color.gamma_multiply(0.45);
    let label = |what: &str| named(layers, l, what);
    p.line(Line::new(label("current cycle"), PlotPoints::Borrowed(&g.path_current)).color(l.color).width(2.0));
    p.line(Line::new(label("other cycles"), PlotPoints::Borrowed(&g.path_before)).color(faint).width(1.0));
    p.line(Line::new(label("other cycles"), PlotPoints::Borrowed(&g.path_after)).color(faint).width(1.0));
    if l.primary {
        // The previous cycle's sweep is convex (core: analysis::edge), so its edge
        // closed by the step chord fills correctly as a convex polygon.
        p.polygon(
            Polygon::new("swept by the previous cycle", PlotPoints::Borrowed(&g.previous_edge))
                .fill_color(l.color.gamma_multiply(0.07))
                .stroke(Stroke::new(0.0, l.color)),
        );
    }
    p.line(
        Line::new(label("previous cycle's edge C₂"), PlotPoints::Borrowed(&g.previous_edge))
            .color(l.color)
            .style(LineStyle::dashed_loose())
            .width(1.2),
    );
}

/// The tool at the cursor (red while it cuts), the path it took this cycle, its chip and a
/// readout of h and the engagement above it.
fn tool_at_cursor<'a>(p: &mut egui_plot::PlotUi<'a>, g: &Graphics, c: Cursor, chip: &'a Chip) {
    let centre = [g.origin[0] + c.centre[0], g.origin[1] + c.centre[1]];
    let mut trail: Vec<[f64; 2]> = g.teeth.iter().take_while(|(t, _)| *t <= c.t_s).map(|(_, p)| [p.x, p.y]).collect();
    trail.push(centre);
    p.line(Line::new("path so far this cycle", trail).color(CHIP_COLOR).width(3.0));
    let (stroke, fill) = if c.cutting {
        (Stroke::new(2.5, CHIP_COLOR), CHIP_COLOR.gamma_multiply(0.18))
    } else {
        (Stroke::new(2.0, Color32::DARK_GRAY), Color32::from_gray(128).gamma_multiply(0.12))
    };
    p.polygon(
        Polygon::new("tool at current tooth", circle(centre, g.tool_r, CIRCLE_POINTS)).stroke(stroke).fill_color(fill),
    );
    p.points(Points::new("", vec![centre]).radius(4.0).color(stroke.color));
    draw_chip(p, chip, "chip of the current tooth", 0.9, 1.5);
    p.text(
        Text::new(
            "",
            PlotPoint::new(centre[0], centre[1] + g.tool_r),
            format!("h = {:.4} mm, {:.1}°", c.h_mm, c.engagement_deg),
        )
        .anchor(egui::Align2::CENTER_BOTTOM)
        .color(stroke.color),
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
    let what = if close_up { "Chip of the current tooth (close-up)" } else { "Chip of the current tooth (zoomed)" };
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
    p.line(
        Line::new("previous cycle's edge C₂", PlotPoints::Borrowed(&l.g.previous_edge))
            .color(l.color)
            .style(LineStyle::dashed_loose())
            .width(1.2),
    );
    if let Some(c) = centre {
        p.line(
            Line::new("tool edge at current tooth", circle(c, l.g.tool_r, FINE_CIRCLE_POINTS))
                .color(Color32::DARK_GRAY)
                .width(1.5),
        );
    }
    if chip.outline.is_empty() {
        if let Some(c) = centre {
            p.text(
                Text::new("", PlotPoint::new(c[0], c[1]), "no chip: this tooth cuts nothing (cooling)")
                    .color(Color32::DARK_GRAY),
            );
        }
        return;
    }
    draw_chip(p, chip, "chip", 0.6, 2.0);
    if let Some(c) = cursor {
        let outline = &chip.outline;
        let top = outline.iter().map(|p| p.y).fold(f64::NEG_INFINITY, f64::max);
        let xs = outline.iter().map(|p| p.x).sum::<f64>() / outline.len() as f64;
        p.text(
            Text::new("", PlotPoint::new(xs, top), format!("h = {:.4} mm", c.h_mm))
                .anchor(egui::Align2::CENTER_BOTTOM)
                .color(CHIP_COLOR),
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

/// The chip filled (convex quads) and outlined.
fn draw_chip<'a>(p: &mut egui_plot::PlotUi<'a>, chip: &'a Chip, name: &str, fill_alpha: f32, width: f32) {
    if chip.outline.is_empty() {
        return;
    }
    for (k, q) in chip.fill.iter().enumerate() {
        let pts: Vec<[f64; 2]> = q.iter().map(|p| [p.x, p.y]).collect();
        p.polygon(
            Polygon::new(if k == 0 { name } else { "" }, pts)
                .fill_color(CHIP_COLOR.gamma_multiply(fill_alpha))
                .stroke(Stroke::new(0.0, CHIP_COLOR)),
        );
    }
    p.line(Line::new(name, PlotPoints::Borrowed(&chip.outline)).color(CHIP_COLOR).width(width));
}

/// h over one steady-state cycle with h_max, t_hmax and the cooling intervals.
pub fn h_plot(ui: &mut egui::Ui, layers: &[Layer], cursor: Option<Cursor>, teach: bool) {
    title(ui, "Chip thickness h over one steady-state cycle (Fig. 7)", explain::H, teach);
    base_plot(ui, "h_plot").custom_x_axes(x_axis("t [s]")).y_axis_label("h [mm]").include_y(0.0).show(ui, |p| {
        for l in layers {
            let g = l.g;
            if l.primary {
                for (k, &(a, b)) in g.cooling.iter().enumerate() {
                    let name = if k == 0 { "cooling" } else { "" };
                    p.add(Span::new(name, a..=b).fill(COOLING_FILL).border_width(0.0));
                }
            }
            p.line(Line::new(named(layers, l, "h"), PlotPoints::Borrowed(&g.h)).color(l.color).width(1.5));
            let (t, h) = g.h_max_at;
            p.points(Points::new("", vec![[t, h]]).radius(5.0).color(l.color));
            if l.primary {
                p.hline(HLine::new("h_max", h).color(l.color.gamma_multiply(0.6)).style(LineStyle::dashed_dense()));
                for &(a, b) in &g.t_hmax_spans {
                    p.line(Line::new("", vec![[a, h * 1.06], [b, h * 1.06]]).color(Color32::DARK_GREEN).width(3.0));
                }
                p.text(
                    Text::new("", PlotPoint::new(t, h * 1.12), format!("h_max = {h:.4} mm"))
                        .anchor(egui::Align2::CENTER_BOTTOM)
                        .color(l.color),
                );
                if let Some(c) = cursor {
                    p.vline(VLine::new("current tooth", c.t_s).color(CHIP_COLOR).width(1.5));
                    p.points(Points::new("", vec![[c.t_s, c.h_mm]]).radius(5.0).color(CHIP_COLOR));
                }
            }
        }
    });
}

/// Engagement angle over one steady-state cycle, with the 46° recommendation.
pub fn engagement_plot(ui: &mut egui::Ui, layers: &[Layer], cursor: Option<Cursor>, teach: bool) {
    title(ui, "Engagement angle over one cycle", explain::ENGAGEMENT, teach);
    base_plot(ui, "engagement_plot").custom_x_axes(x_axis("t [s]")).y_axis_label("engagement [°]").include_y(0.0).show(
        ui,
        |p| {
            p.hline(
                HLine::new("46° recommended (Grechishnikov et al. 2017)", ENGAGEMENT_LIMIT_DEG)
                    .color(Color32::from_rgb(200, 60, 60))
                    .style(LineStyle::dashed_dense()),
            );
            for l in layers {
                p.line(
                    Line::new(named(layers, l, "engagement"), PlotPoints::Borrowed(&l.g.engagement))
                        .color(l.color)
                        .width(1.5),
                );
                if l.primary
                    && let Some(c) = cursor
                {
                    p.vline(VLine::new("current tooth", c.t_s).color(CHIP_COLOR).width(1.5));
                    p.points(Points::new("", vec![[c.t_s, c.engagement_deg]]).radius(5.0).color(CHIP_COLOR));
                }
            }
        },
    );
}

/// Left and right wall deviation along y with W_l and W_r marked.
pub fn wall_plot(ui: &mut egui::Ui, layers: &[Layer], teach: bool) {
    title(ui, "Wall profiles: left solid, right dashed (Figs. 8–9)", explain::WALLS, teach);
    base_plot(ui, "wall_plot").custom_x_axes(x_axis("y [mm]")).y_axis_label("deviation [mm]").include_y(0.0).show(
        ui,
        |p| {
            for l in layers {
                let (w_l, w_r) = l.w;
                let right = l.color.gamma_multiply(0.55);
                p.line(
                    Line::new(named(layers, l, "left wall"), PlotPoints::Borrowed(&l.g.wall_left))
                        .color(l.color)
                        .width(1.8),
                );
                p.line(
                    Line::new(named(layers, l, "right wall (dashed)"), PlotPoints::Borrowed(&l.g.wall_right))
                        .color(right)
                        .style(LineStyle::dashed_dense())
                        .width(1.8),
                );
                if l.primary {
                    p.hline(
                        HLine::new(format!("W_l = {w_l:.4} mm"), w_l).color(l.color).style(LineStyle::dotted_dense()),
                    );
                    p.hline(
                        HLine::new(format!("W_r = {w_r:.4} mm"), w_r).color(right).style(LineStyle::dotted_loose()),
                    );
                }
            }
        },
    );
}

/// Cutting forces Fx, Fy, Fz and F_R over one steady-state cycle, the mean F_R dashed (Figs.
/// 14–15); pinned variants add their F_R.
pub fn force_plot(ui: &mut egui::Ui, layers: &[Layer], cursor: Option<Cursor>, teach: bool) {
    title(ui, "Cutting forces over one steady-state cycle (Figs. 14–15)", explain::FORCES, teach);
    if teach {
        ui.add(egui::Label::new(RichText::new(explain::WHY_EARLY).weak()).wrap());
    }
    base_plot(ui, "force_plot").custom_x_axes(x_axis("t [s]")).y_axis_label("force [N]").show(ui, |p| {
        for l in layers {
            let g = l.g;
            if l.primary {
                let names = ["Fx", "Fy", "Fz"];
                let colours =
                    [Color32::from_rgb(40, 160, 70), Color32::from_rgb(220, 90, 30), Color32::from_rgb(170, 60, 190)];
                for ((curve, name), colour) in g.forces.iter().zip(names).zip(colours) {
                    p.line(Line::new(name, PlotPoints::Borrowed(curve)).color(colour.gamma_multiply(0.8)).width(1.0));
                }
                p.hline(
                    HLine::new(format!("mean F_R = {:.0} N", g.force_mean), g.force_mean)
                        .color(l.color)
                        .style(LineStyle::dashed_loose()),
                );
                let (t, f) = g.force_max_at;
                p.points(Points::new("", vec![[t, f]]).radius(5.0).color(l.color));
                p.text(
                    Text::new("", PlotPoint::new(t, f * 1.04), format!("F_R,max = {f:.0} N"))
                        .anchor(egui::Align2::CENTER_BOTTOM)
                        .color(l.color),
                );
                if let Some(c) = cursor {
                    p.vline(VLine::new("current tooth", c.t_s).color(CHIP_COLOR).width(1.5));
                }
            }
            p.line(Line::new(named(layers, l, "F_R"), PlotPoints::Borrowed(&g.forces[3])).color(l.color).width(1.5));
        }
    });
}

/// Imprint density across the slot bottom, left wall to right wall (Figs. 21–22).
pub fn imprint_plot(ui: &mut egui::Ui, layers: &[Layer], teach: bool) {
    title(ui, "Edge imprints on the slot bottom (Figs. 21–22)", explain::IMPRINTS, teach);
    base_plot(ui, "imprint_plot")
        .custom_x_axes(x_axis("X [mm] (left wall to right wall)"))
        .y_axis_label("imprints [1/mm]")
        .include_y(0.0)
        .show(ui, |p| {
            for l in layers {
                p.line(
                    Line::new(named(layers, l, "imprint density"), PlotPoints::Borrowed(&l.g.imprints))
                        .color(l.color)
                        .width(1.5),
                );
            }
        });
}
