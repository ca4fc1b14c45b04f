//! The Program tab's plots: the program's path in the plane coloured by a quantity (with its
//! colour bar, the stock and part outlines, the tool's position and the selected problem), and
//! the quantity over the program's time with the position marked.

use super::legend::{self, Entry, Look};
use super::program::{Quantity, Verified};
use eframe::egui::{self, Color32, Pos2, Stroke};
use egui_plot::{Line, Plot, PlotPoint, PlotPoints, Points, VLine};

/// Colour of rapid moves and of feed moves in the air.
const RAPID: Color32 = Color32::from_rgb(150, 150, 150);
const AIR: Color32 = Color32::from_rgb(205, 205, 205);
const STOCK: Color32 = Color32::from_rgb(120, 80, 40);
const PART: Color32 = Color32::from_rgb(30, 140, 60);
const CURSOR: Color32 = Color32::from_rgb(230, 0, 200);
const PROBLEM: Color32 = Color32::from_rgb(220, 30, 30);
/// Colour steps of the scale.
const STEPS: usize = 24;
/// Shortest step between the points of a drawn polyline (screen points).
const MIN_PIXEL_STEP: f32 = 0.75;
/// Below this engagement (°) a feed move is in the air.
const AIR_DEG: f64 = 1.0;

/// The colour map (viridis, five stops) at `s` in 0–1.
pub fn colour(s: f64) -> Color32 {
    const STOPS: [[f32; 3]; 5] =
        [[68.0, 1.0, 84.0], [59.0, 82.0, 139.0], [33.0, 145.0, 140.0], [94.0, 201.0, 98.0], [253.0, 231.0, 37.0]];
    let x = (s.clamp(0.0, 1.0) * 4.0) as f32;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f32;
    let c = |k: usize| (STOPS[i][k] + f * (STOPS[i + 1][k] - STOPS[i][k])).round() as u8;
    Color32::from_rgb(c(0), c(1), c(2))
}

/// The colour step of value `v` on a scale 0–`max`.
fn step_of(v: f64, max: f64) -> usize {
    if max > 0.0 { ((v / max * STEPS as f64) as usize).min(STEPS - 1) } else { 0 }
}

/// The largest value of `q` over the feed moves at one height of the verified programs (the
/// common scale of the colours; a descending move beyond it takes the top colour: its
/// engagement is that of a disc swept down through the material, up to 360°).
pub fn scale_max(q: Quantity, programs: &[&Verified]) -> f64 {
    programs
        .iter()
        .flat_map(|v| v.report.moves.iter())
        .filter(|m| m.kind != "rapid" && m.z0 == m.z1)
        .map(|m| q.of(m))
        .fold(0.0, f64::max)
}

/// Colour of move `k` (`None`: a rapid).
fn move_colour(v: &Verified, k: usize, q: Quantity, max: f64) -> Option<Color32> {
    let m = &v.report.moves[k];
    if m.kind == "rapid" {
        return None;
    }
    if m.engagement_deg <= AIR_DEG {
        return Some(AIR);
    }
    Some(colour((step_of(q.of(m), max) as f64 + 0.5) / STEPS as f64))
}

/// A closed outline as a plot line.
fn outline(name: &str, p: &trochoplan_core::geom::Polygon, color: Color32) -> Line<'static> {
    let mut pts: Vec<[f64; 2]> = p.vertices().iter().map(|q| [q.x, q.y]).collect();
    if let Some(&first) = pts.first() {
        pts.push(first);
    }
    Line::new(name, PlotPoints::new(pts)).color(color).width(1.5)
}

/// What a click on the path asks for.
pub enum PathClick {
    /// The move nearest the click.
    Move(usize),
}

/// The path in the plane coloured by `q` on the scale 0–`max`, with the colour bar on its right,
/// the tool at `cursor` and the problem place `mark` (x, y); `id` keeps plots apart.
pub fn path_plot(
    ui: &mut egui::Ui,
    id: &str,
    v: &Verified,
    q: Quantity,
    max: f64,
    cursor: Option<[f64; 2]>,
    mark: Option<[f64; 2]>,
) -> Option<PathClick> {
    let bar_w = 92.0;
    let size = ui.available_size();
    let mut click = None;
    ui.horizontal_top(|ui| {
        let plot_size = egui::vec2((size.x - bar_w - ui.spacing().item_spacing.x).max(120.0), size.y);
        ui.allocate_ui(plot_size, |ui| click = path_only(ui, id, v, q, max, cursor, mark));
        colour_bar(ui, egui::vec2(bar_w, size.y.min(360.0)), q, max);
    });
    click
}

fn path_only(
    ui: &mut egui::Ui,
    id: &str,
    v: &Verified,
    q: Quantity,
    max: f64,
    cursor: Option<[f64; 2]>,
    mark: Option<[f64; 2]>,
) -> Option<PathClick> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in
        v.polylines.iter().flatten().chain(v.stock.vertices().iter().map(|p| [p.x, p.y]).collect::<Vec<_>>().iter())
    {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    let mut entries = vec![Entry::new("stock", Look::solid(STOCK, 1.5))];
    if v.part.is_some() {
        entries.push(Entry::new("part", Look::solid(PART, 1.5)));
    }
    if cursor.is_some() {
        entries.push(Entry::new("tool position", Look::points(CURSOR, 5.0)));
    }
    if mark.is_some() {
        entries.push(Entry::new("selected problem", Look::points(PROBLEM, 7.0)));
    }
    legend::show(ui, &entries, 1);
    let resp = Plot::new(id)
        .data_aspect(1.0)
        .x_axis_label("X (mm)")
        .y_axis_label("Y (mm)")
        .include_x(lo[0])
        .include_x(hi[0])
        .include_y(lo[1])
        .include_y(hi[1])
        .allow_scroll(false)
        .show(ui, |plot| {
            plot.line(outline("stock", &v.stock, STOCK));
            for i in &v.stock_islands {
                plot.line(outline("stock", i, STOCK));
            }
            if let Some(p) = &v.part {
                plot.line(outline("part", p, PART));
                for i in &v.part_islands {
                    plot.line(outline("part", i, PART));
                }
            }
            if let Some(c) = cursor {
                plot.points(Points::new("tool position", vec![c]).color(CURSOR).radius(5.0));
            }
            if let Some(m) = mark {
                plot.points(Points::new("selected problem", vec![m]).color(PROBLEM).radius(7.0).filled(false));
            }
        });
    let t = &resp.transform;
    let frame = *t.frame();
    let painter = ui.painter().with_clip_rect(frame);
    let screen = |p: &[f64; 2]| t.position_from_point(&PlotPoint::new(p[0], p[1]));
    // runs of consecutive moves of one colour as one polyline each: first the rapids and the
    // moves in the air, then the cutting moves over them (a trochoid's return half would
    // otherwise hide the cutting half of the loop before)
    let mut run: Vec<Pos2> = Vec::new();
    let mut run_colour: Option<Option<Color32>> = None;
    let flush = |run: &mut Vec<Pos2>, c: Option<Option<Color32>>| {
        if run.len() > 1
            && let Some(c) = c
        {
            let stroke = match c {
                Some(c) => Stroke::new(1.6, c),
                None => Stroke::new(0.8, RAPID),
            };
            painter.add(egui::Shape::line(std::mem::take(run), stroke));
        }
        run.clear();
    };
    for cutting in [false, true] {
        for (k, poly) in v.polylines.iter().enumerate() {
            let c = move_colour(v, k, q, max);
            let c = (matches!(c, Some(c) if c != AIR) == cutting).then_some(c);
            if c != run_colour {
                // a run continues from the end of the move before it when that move is drawn
                let last = if c.is_some() && run_colour.is_some() { run.last().copied() } else { None };
                flush(&mut run, run_colour);
                run_colour = c;
                run.extend(last);
            }
            if c.is_none() {
                continue;
            }
            // points closer than a pixel to the last one drawn add nothing on screen
            for p in poly.iter().map(screen) {
                if run.last().is_none_or(|q| q.distance_sq(p) >= MIN_PIXEL_STEP * MIN_PIXEL_STEP) {
                    run.push(p);
                }
            }
        }
        flush(&mut run, run_colour);
        run_colour = None;
    }
    // the markers over the path
    if let Some(c) = cursor {
        painter.circle_filled(screen(&c), 5.0, CURSOR);
    }
    if let Some(m) = mark {
        painter.circle_stroke(screen(&m), 8.0, Stroke::new(2.5, PROBLEM));
    }
    if !resp.response.clicked() {
        return None;
    }
    let at = resp.response.interact_pointer_pos()?;
    v.polylines
        .iter()
        .enumerate()
        .filter(|(k, _)| v.report.moves[*k].kind != "rapid")
        .flat_map(|(k, poly)| poly.iter().map(move |p| (k, p)))
        .map(|(k, p)| (k, screen(p).distance(at)))
        .filter(|&(_, d)| d < 15.0)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(k, _)| PathClick::Move(k))
}

/// The colour bar of `q` on 0–`max`, with the rapid and in-air colours.
fn colour_bar(ui: &mut egui::Ui, size: egui::Vec2, q: Quantity, max: f64) {
    let (rect, _) = ui.allocate_exact_size(size, egui::Sense::hover());
    let p = ui.painter_at(rect);
    let font = egui::FontId::proportional(11.0);
    let text = ui.visuals().text_color();
    let title = match q {
        Quantity::Engagement => "engagement\n(°)",
        Quantity::ChipThickness => "chip h_max\n(mm)",
        Quantity::Force => "force\n(N)",
    };
    p.text(rect.left_top() + egui::vec2(2.0, 0.0), egui::Align2::LEFT_TOP, title, font.clone(), text);
    let bar =
        egui::Rect::from_min_size(rect.left_top() + egui::vec2(4.0, 34.0), egui::vec2(18.0, rect.height() - 90.0));
    let h = bar.height() / STEPS as f32;
    for i in 0..STEPS {
        let y1 = bar.bottom() - i as f32 * h;
        let r = egui::Rect::from_min_max(egui::pos2(bar.left(), y1 - h), egui::pos2(bar.right(), y1));
        p.rect_filled(r, 0.0, colour((i as f64 + 0.5) / STEPS as f64));
    }
    for i in 0..=4 {
        let f = f64::from(i) / 4.0;
        let y = bar.bottom() - bar.height() * f as f32;
        p.text(
            egui::pos2(bar.right() + 4.0, y),
            egui::Align2::LEFT_CENTER,
            format!("{:.*}", q.decimals(), max * f),
            font.clone(),
            text,
        );
    }
    let y = bar.bottom() + 14.0;
    p.line_segment([egui::pos2(bar.left(), y), egui::pos2(bar.right(), y)], Stroke::new(3.0, AIR));
    p.text(egui::pos2(bar.right() + 4.0, y), egui::Align2::LEFT_CENTER, "in the air", font.clone(), text);
    let y = y + 16.0;
    p.line_segment([egui::pos2(bar.left(), y), egui::pos2(bar.right(), y)], Stroke::new(1.0, RAPID));
    p.text(egui::pos2(bar.right() + 4.0, y), egui::Align2::LEFT_CENTER, "rapid", font, text);
}

/// Most time buckets drawn: beyond, the steps are drawn as the least and largest value of each
/// bucket (min/max decimation: every peak stays visible).
const TIME_BUCKETS: usize = 1000;

/// `q` over the program's time as a step per move, or min/max per bucket of time for long
/// programs.
fn time_points(v: &Verified, q: Quantity) -> Vec<PlotPoint> {
    let steps = v.report.moves.iter().zip(&v.starts_s).map(|(m, &t)| (t, t + m.time_s, q.of(m)));
    if v.report.moves.len() <= TIME_BUCKETS || v.total_s <= 0.0 {
        return steps.flat_map(|(t0, t1, y)| [PlotPoint::new(t0, y), PlotPoint::new(t1, y)]).collect();
    }
    let width = v.total_s / TIME_BUCKETS as f64;
    let mut lo = vec![f64::INFINITY; TIME_BUCKETS];
    let mut hi = vec![f64::NEG_INFINITY; TIME_BUCKETS];
    for (t0, t1, y) in steps {
        let (b0, b1) = ((t0 / width) as usize, (t1 / width) as usize);
        for b in b0.min(TIME_BUCKETS - 1)..=b1.min(TIME_BUCKETS - 1) {
            lo[b] = lo[b].min(y);
            hi[b] = hi[b].max(y);
        }
    }
    (0..TIME_BUCKETS)
        .filter(|&b| lo[b] <= hi[b])
        .flat_map(|b| {
            let t = (b as f64 + 0.5) * width;
            [PlotPoint::new(t, lo[b]), PlotPoint::new(t, hi[b])]
        })
        .collect()
}

/// `q` over the program's time (a step per move) with the position `cursor_s` marked; returns
/// the time clicked.
pub fn time_plot(ui: &mut egui::Ui, id: &str, v: &Verified, q: Quantity, cursor_s: f64) -> Option<f64> {
    let pts = time_points(v, q);
    let here = v.move_at(cursor_s).map(|(k, _)| q.of(&v.report.moves[k]));
    let resp = Plot::new(id)
        .x_axis_label("time on the machine (s)")
        .y_axis_label(q.label())
        .include_y(0.0)
        .allow_scroll(false)
        .show(ui, |plot| {
            plot.line(Line::new(q.label(), PlotPoints::Owned(pts)).color(colour(0.35)).width(1.2));
            plot.vline(VLine::new("position", cursor_s).color(CURSOR));
            if let Some(y) = here {
                plot.points(Points::new("position", vec![[cursor_s, y]]).color(CURSOR).radius(4.0));
            }
            plot.pointer_coordinate()
        });
    if resp.response.clicked() || resp.response.dragged() {
        return resp.inner.map(|p| p.x.clamp(0.0, v.total_s));
    }
    None
}
