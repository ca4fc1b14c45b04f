//! What the Corner and Pocket tabs draw alike: tool paths in the plane with equal axes, their
//! colours, the method buttons and the status line of a background plan.

use super::params::ERROR_COLOR;
use eframe::egui::{self, Color32, RichText};
use egui_plot::{Line, Plot, PlotPoints};
use trochoplan_core::corner::CornerMethod;
use trochoplan_core::geom::Segment;

/// Most points drawn for a tool path.
pub const MAX_PATH_POINTS: usize = 6000;

/// Colour of the plain ring.
pub const PLAIN_COLOR: Color32 = Color32::from_rgb(200, 90, 40);
/// Colour of the planned strategy's path.
pub const STRATEGY_COLOR: Color32 = Color32::from_rgb(40, 110, 200);

/// Points along `segments` for drawing: about `max` in all, lines by their ends.
pub fn segment_points(segments: &[Segment], max: usize) -> Vec<[f64; 2]> {
    let total: f64 = segments.iter().map(Segment::length).sum::<f64>().max(1e-9);
    let mut out = Vec::new();
    for seg in segments {
        let n = match seg {
            Segment::Line { .. } => 1,
            _ => ((seg.length() / total * max as f64).ceil() as usize).clamp(4, max),
        };
        let pts = seg.sample(n);
        let skip = usize::from(!out.is_empty());
        out.extend(pts.iter().skip(skip).map(|p| [p.x, p.y]));
    }
    out
}

/// A named plot line through `pts`.
pub fn line(name: &str, pts: &[[f64; 2]]) -> Line<'static> {
    Line::new(name.to_owned(), PlotPoints::from(pts.to_vec()))
}

/// A plot of the plane, `height` high, with equal axis scale (its legend is drawn above it with
/// [`super::legend::show_above`]).
pub fn plane_plot(id: impl egui::AsIdSalt, height: f32) -> Plot<'static> {
    Plot::new(id).data_aspect(1.0).height(height).x_axis_label("x (mm)").y_axis_label("y (mm)")
}

/// The corner method buttons; labels and tooltips are the core's.
pub fn method_buttons(ui: &mut egui::Ui, method: &mut CornerMethod) {
    ui.label("Method");
    for m in CornerMethod::ALL {
        if ui.selectable_label(*method == m, m.label()).on_hover_text(m.tooltip()).clicked() {
            *method = m;
        }
    }
}

/// The core's message when the inputs are invalid (then `kept`, what is shown meanwhile), and
/// a spinner while a plan is being made.
pub fn status(ui: &mut egui::Ui, error: Option<&str>, pending: bool, kept: Option<&str>) {
    if let Some(e) = error {
        ui.add(egui::Label::new(RichText::new(format!("invalid: {e}")).color(ERROR_COLOR)).wrap());
        if let Some(text) = kept {
            ui.label(text);
        }
    }
    if pending {
        ui.horizontal(|ui| {
            ui.spinner();
            ui.label("planning…");
        });
    }
}
