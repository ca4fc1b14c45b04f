//! Parameter panel: the job's inputs with units, sliders with number boxes, tooltips giving the
//! meaning, the effect and the paper's recommended range, and the core's validation message at
//! the offending field.

use super::label;
use eframe::egui::{self, Color32, RichText, Slider, SliderClamping};
use trochoplan_core::{Job, JobError, PathKind};

/// Colour of validation messages.
pub const ERROR_COLOR: Color32 = Color32::from_rgb(210, 40, 40);

struct Field<'a> {
    label: &'static str,
    /// Core parameter name (kebab-case) whose errors belong here.
    name: &'static str,
    unit: &'static str,
    tooltip: String,
    range: std::ops::RangeInclusive<f64>,
    log: bool,
    decimals: usize,
    enabled: bool,
    error: Option<&'a JobError>,
}

fn field(ui: &mut egui::Ui, f: Field, value: &mut f64) {
    let lab = ui.label(f.label).on_hover_text(&f.tooltip);
    let mut slider = Slider::new(value, f.range)
        .clamping(SliderClamping::Never)
        .logarithmic(f.log)
        .max_decimals(f.decimals)
        .suffix(format!(" {}", f.unit));
    if f.log {
        slider = slider.smallest_positive(1e-3);
    }
    ui.add_enabled(f.enabled, slider).labelled_by(lab.id).on_hover_text(&f.tooltip);
    ui.end_row();
    field_error(ui, f.name, f.error);
}

/// The core's message under the field it names.
fn field_error(ui: &mut egui::Ui, name: &str, error: Option<&JobError>) {
    if let Some(e) = error.filter(|e| e.parameter() == Some(name)) {
        ui.label(RichText::new("invalid").color(ERROR_COLOR));
        ui.add(egui::Label::new(RichText::new(e.to_string()).color(ERROR_COLOR)).wrap());
        ui.end_row();
    }
}

/// Draw the parameter panel; edits `job` in place.
pub fn show(ui: &mut egui::Ui, job: &mut Job, error: Option<&JobError>) {
    if let Some(e) = error.filter(|e| e.parameter().is_none()) {
        ui.colored_label(ERROR_COLOR, e.to_string());
    }
    let b = job.slot_width;
    ui.spacing_mut().slider_width = (ui.available_width() - 215.0).clamp(80.0, 220.0);

    ui.heading("Slot");
    egui::Grid::new("slot_grid").num_columns(2).spacing([8.0, 4.0]).show(ui, |ui| {
        let f = |label, name, unit, tooltip: &str, range, log| Field {
            label,
            name,
            unit,
            tooltip: tooltip.to_owned(),
            range,
            log,
            decimals: 3,
            enabled: true,
            error,
        };
        field(
            ui,
            f(
                label::SLOT_WIDTH,
                "slot-width",
                "mm",
                "Slot width B (mm). With the tool diameter it sets the \
                trochoidal radius a = (B − D)/2. Paper Table 1: 20 mm.",
                2.0..=100.0,
                true,
            ),
            &mut job.slot_width,
        );
        field(
            ui,
            f(
                label::SLOT_LENGTH,
                "slot-length",
                "mm",
                "Slot length L (mm) along +y from the stock face. \
                Sets the number of cycles and the machining time; does not change the per-cycle \
                analysis. Paper: 20 mm.",
                1.0..=2000.0,
                true,
            ),
            &mut job.slot_length,
        );
        field(
            ui,
            f(
                label::DEPTH,
                "depth",
                "mm",
                "Axial depth of cut a_p = slot depth in one pass (mm). \
                MRR = B·s·a_p / t_cycle grows linearly with it. Paper section 4: 6 mm.",
                0.1..=50.0,
                true,
            ),
            &mut job.depth,
        );
    });

    ui.add_space(6.0);
    ui.heading("Tool and cutting data");
    egui::Grid::new("tool_grid").num_columns(2).spacing([8.0, 4.0]).show(ui, |ui| {
        field(
            ui,
            Field {
                label: label::TOOL_DIAMETER,
                name: "tool-diameter",
                unit: "mm",
                tooltip: format!(
                    "Tool diameter D (mm). Grechishnikov et al. (2017) recommend 50–60 % of the slot \
                     width, here {:.1}–{:.1} mm. Must be ≥ B/2 (else each loop leaves an island) and < B. \
                     A larger tool shrinks a = (B − D)/2: shorter path, more MRR, less engagement room. \
                     Paper: 10 mm.",
                    0.5 * b,
                    0.6 * b
                ),
                range: (0.5 * b).max(0.1)..=(0.95 * b).max(0.2),
                log: false,
                decimals: 3,
                enabled: true,
                error,
            },
            &mut job.tool_diameter,
        );
        let lab = ui.label(label::TEETH);
        let tip = "Number of teeth z. Feed per tooth f_z = f_r/(n·z): more teeth, thinner chips \
            (h scales with f_z) and a shorter cooling time per tooth. Paper: 4.";
        lab.clone().on_hover_text(tip);
        ui.add(Slider::new(&mut job.teeth, 1..=12).clamping(SliderClamping::Never))
            .labelled_by(lab.id)
            .on_hover_text(tip);
        ui.end_row();
        field_error(ui, "teeth", error);
        let f = |label, name, unit, tooltip: &str, range, decimals| Field {
            label,
            name,
            unit,
            tooltip: tooltip.to_owned(),
            range,
            log: true,
            decimals,
            enabled: true,
            error,
        };
        field(
            ui,
            f(
                label::FEED,
                "feed",
                "mm/min",
                "Tool-centre feed rate f_r (mm/min). Sets the cycle time \
                t_cycle = cycle length / f_r and the feed per tooth f_z = f_r/(n·z), to which h is \
                proportional. Paper Table 1: 600 mm/min.",
                10.0..=10000.0,
                1,
            ),
            &mut job.feed,
        );
        field(
            ui,
            f(
                label::RPM,
                "rpm",
                "rpm",
                "Spindle speed n (rpm). Higher n: smaller f_z, thinner chips, \
                same cycle time. Paper Table 1: 2000 rpm.",
                100.0..=40000.0,
                0,
            ),
            &mut job.rpm,
        );
    });

    ui.add_space(6.0);
    ui.heading("Path");
    for kind in PathKind::ALL {
        ui.radio_value(&mut job.path, kind, kind.label()).on_hover_text(kind.about());
    }
    field_error_line(ui, "path", error);
    egui::Grid::new("path_grid").num_columns(2).spacing([8.0, 4.0]).show(ui, |ui| {
        field(
            ui,
            Field {
                label: label::STEP,
                name: "step",
                unit: "mm",
                tooltip: "Trochoidal step s (mm per cycle). Larger s: more MRR, thicker chips, larger \
                    engagement and waviness. Keep the engagement ≤ 46° (Grechishnikov et al. 2017): the \
                    engagement-limited step is in the derived values. Paper Table 1: 1 mm."
                    .to_owned(),
                range: 0.05..=(0.5 * job.tool_diameter).max(0.1),
                log: false,
                decimals: 3,
                enabled: true,
                error,
            },
            &mut job.step,
        );
        field(
            ui,
            Field {
                label: label::ASPECT_RATIO,
                name: "aspect-ratio",
                unit: "",
                tooltip: "Aspect ratio r_e = b/a of the elliptical loops (eq. 2), for elliptical and \
                    linear-elliptical paths. Lower r_e: shorter path and more MRR (0.5: +21.8 % vs r_e = 1, \
                    Table 2) with h_max almost constant, but more wall waviness (0.6: +48 %, Fig. 9). \
                    The paper studies 0.5–1.2."
                    .to_owned(),
                range: 0.3..=1.5,
                log: false,
                decimals: 3,
                enabled: job.path.uses_aspect_ratio(),
                error,
            },
            &mut job.aspect_ratio,
        );
        field(
            ui,
            Field {
                label: label::LINEAR_DISTANCE,
                name: "linear-distance",
                unit: "mm",
                tooltip: "Linear distance d (mm) travelled along each wall per cycle (linear-elliptical \
                    path, paper section 3). d = 0.75·s reduced the waviness three times against d = 0; \
                    more d gave only ~60 % further (Figs. 25–28). The paper uses 0.75–1.25 mm."
                    .to_owned(),
                range: 0.0..=(0.25 * job.slot_width).max(0.1),
                log: false,
                decimals: 3,
                enabled: job.path == PathKind::LinearElliptical,
                error,
            },
            &mut job.linear_distance,
        );
    });
}

fn field_error_line(ui: &mut egui::Ui, name: &str, error: Option<&JobError>) {
    if let Some(e) = error.filter(|e| e.parameter() == Some(name)) {
        ui.colored_label(ERROR_COLOR, format!("invalid: {e}"));
    }
}
