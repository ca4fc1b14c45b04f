//! Parameter panel: the job's inputs with units, sliders with number boxes, tooltips giving the
//! meaning, the effect and the paper's recommended range, and the core's validation message at
//! the offending field.

use eframe::egui::{self, Color32, RichText, Slider, SliderClamping};
use std::ops::RangeInclusive;
use trochoplan_core::job::Direction;
use trochoplan_core::{Error, Job, Param, PathKind};

/// Colour of validation messages.
pub const ERROR_COLOR: Color32 = Color32::from_rgb(210, 40, 40);

/// One numeric input: the core parameter it edits (its label, and the errors shown under it).
struct Field<'a> {
    param: Param,
    unit: &'static str,
    tooltip: String,
    range: RangeInclusive<f64>,
    log: bool,
    decimals: usize,
    enabled: bool,
    error: Option<&'a Error>,
}

impl<'a> Field<'a> {
    /// A linear slider with 3 decimals, enabled.
    fn new(param: Param, unit: &'static str, tooltip: impl Into<String>, range: RangeInclusive<f64>) -> Self {
        let tooltip = tooltip.into();
        Field { param, unit, tooltip, range, log: false, decimals: 3, enabled: true, error: None }
    }

    fn log(self) -> Self {
        Field { log: true, ..self }
    }

    fn decimals(self, decimals: usize) -> Self {
        Field { decimals, ..self }
    }

    fn enabled(self, enabled: bool) -> Self {
        Field { enabled, ..self }
    }

    fn error(self, error: Option<&'a Error>) -> Self {
        Field { error, ..self }
    }

    /// Draw the label, the slider with its number box and the field's error (one grid row each).
    fn show(self, ui: &mut egui::Ui, value: &mut f64) {
        let lab = ui.label(self.param.label()).on_hover_text(&self.tooltip);
        let mut slider = Slider::new(value, self.range)
            .clamping(SliderClamping::Never)
            .logarithmic(self.log)
            .max_decimals(self.decimals)
            .custom_parser(super::number::parse)
            .suffix(format!(" {}", self.unit));
        if self.log {
            slider = slider.smallest_positive(1e-3);
        }
        ui.add_enabled(self.enabled, slider).labelled_by(lab.id).on_hover_text(&self.tooltip);
        ui.end_row();
        field_error(ui, self.param, self.error);
    }
}

/// The core's message under the field of `param` (a grid row).
fn field_error(ui: &mut egui::Ui, param: Param, error: Option<&Error>) {
    if let Some(e) = error.filter(|e| e.parameter() == Some(param)) {
        ui.label(RichText::new("invalid").color(ERROR_COLOR));
        ui.add(egui::Label::new(RichText::new(e.to_string()).color(ERROR_COLOR)).wrap());
        ui.end_row();
    }
}

/// The core's message about `param` on a line of its own (outside a grid).
fn field_error_line(ui: &mut egui::Ui, param: Param, error: Option<&Error>) {
    if let Some(e) = error.filter(|e| e.parameter() == Some(param)) {
        ui.colored_label(ERROR_COLOR, format!("invalid: {e}"));
    }
}

/// Tooltip of the milling-direction choice.
const DIRECTION_TIP: &str = "With the spindle turning M3 (clockwise seen from above), the paper's \
    clockwise loops (eq. 1) cut in conventional (up) milling: each tooth enters the chip at zero \
    thickness and leaves it at h_max. Climb (down) milling mirrors every loop in the slot's centre \
    line: the tooth meets the thick end first, which most carbide tools prefer. Geometry (h_max, \
    engagement, path, times) is the mirror image, the two walls' waviness swap, the forces differ.";

/// Draw the parameter panel; edits `job` in place.
pub fn show(ui: &mut egui::Ui, job: &mut Job, error: Option<&Error>) {
    if let Some(e) = error.filter(|e| e.parameter().is_none()) {
        ui.colored_label(ERROR_COLOR, e.to_string());
    }
    ui.spacing_mut().slider_width = (ui.available_width() - 215.0).clamp(80.0, 220.0);
    ui.heading("Slot");
    egui::Grid::new("slot_grid").num_columns(2).spacing([8.0, 4.0]).show(ui, |ui| slot_fields(ui, job, error));
    ui.add_space(6.0);
    ui.heading("Tool and cutting data");
    egui::Grid::new("tool_grid").num_columns(2).spacing([8.0, 4.0]).show(ui, |ui| tool_fields(ui, job, error));
    ui.add_space(6.0);
    ui.heading("Path");
    for kind in PathKind::ALL {
        ui.radio_value(&mut job.path, kind, kind.label()).on_hover_text(kind.about());
    }
    field_error_line(ui, Param::Path, error);
    ui.horizontal(|ui| {
        ui.label("Milling").on_hover_text(DIRECTION_TIP);
        for d in [Direction::Conventional, Direction::Climb] {
            ui.radio_value(&mut job.direction, d, d.name()).on_hover_text(d.help());
        }
    });
    egui::Grid::new("path_grid").num_columns(2).spacing([8.0, 4.0]).show(ui, |ui| path_fields(ui, job, error));
    ui.add_space(6.0);
    ui.heading("Material and process");
    egui::Grid::new("process_grid").num_columns(2).spacing([8.0, 4.0]).show(ui, |ui| process_fields(ui, job, error));
    machine_picker(ui, job, error);
}

/// Work material (built-in library), helix angle and the measured Ra,max of eq. (7).
fn process_fields(ui: &mut egui::Ui, job: &mut Job, error: Option<&Error>) {
    let lib = trochoplan_core::material::Library::builtin();
    let lab = ui.label(Param::Material.label());
    let tip = "Work material: the six coefficients of the linear edge-force model \
        (dF = (K_c·h + K_e)·dz, Altintas & Lee 1996) from the library assets/materials/library.toml, \
        each value with its source. The paper's material is P20, unhardened.";
    lab.clone().on_hover_text(tip);
    let current = lib.get(&job.material).map_or(job.material.as_str(), |m| m.label.as_str()).to_owned();
    egui::ComboBox::from_id_salt("material")
        .selected_text(current)
        .width(ui.spacing().slider_width + 60.0)
        .show_ui(ui, |ui| {
            for m in &lib.materials {
                let k = &m.coefficients;
                let text = format!(
                    "Ktc {} Krc {} Kac {} N/mm², Kte {} Kre {} Kae {} N/mm",
                    k.ktc, k.krc, k.kac, k.kte, k.kre, k.kae
                );
                if ui
                    .selectable_label(job.material == m.name && job.coefficients.is_none(), &m.label)
                    .on_hover_text(text)
                    .clicked()
                {
                    job.material.clone_from(&m.name);
                    job.coefficients = None;
                }
            }
        })
        .response
        .labelled_by(lab.id)
        .on_hover_text(tip);
    ui.end_row();
    field_error(ui, Param::Material, error);
    Field::new(
        Param::HelixAngle,
        "°",
        "Helix angle β of the flutes (0–60°). The edge at height z lags its bottom by z·tanβ/R, \
        so several teeth share the cut and the force rises and falls more smoothly; it does not \
        change the mean force. The paper's tool: 35°.",
        0.0..=60.0,
    )
    .decimals(1)
    .error(error)
    .show(ui, &mut job.helix_angle);
    let lab = ui.label(Param::RaUm.label());
    let tip = "Largest measured roughness Ra,max (µm) of the slot (walls and bottom). Not \
        predicted: enter your measurement to get PI = MRR/(F_R,max·Ra,max·W_max), eq. (7). \
        Without it the planner ranks by MRR/(F_R,max·W_max) (\"PI without Ra\").";
    lab.clone().on_hover_text(tip);
    ui.horizontal(|ui| {
        let mut on = job.ra_um.is_some();
        if ui.checkbox(&mut on, "").on_hover_text(tip).changed() {
            job.ra_um = on.then_some(1.0);
        }
        if let Some(ra) = &mut job.ra_um {
            ui.add(
                egui::DragValue::new(ra)
                    .speed(0.01)
                    .range(0.0..=1000.0)
                    .custom_parser(super::number::parse)
                    .suffix(" µm"),
            )
            .labelled_by(lab.id)
            .on_hover_text(tip);
        } else {
            ui.label(RichText::new("not entered").weak());
        }
    });
    ui.end_row();
    field_error(ui, Param::RaUm, error);
    for p in [Param::Ktc, Param::Krc, Param::Kac, Param::Kte, Param::Kre, Param::Kae, Param::Runout] {
        field_error(ui, p, error);
    }
}

/// The machine for the real cycle time: ideal, a preset, or the job file's own.
fn machine_picker(ui: &mut egui::Ui, job: &mut Job, error: Option<&Error>) {
    use trochoplan_core::machine::{MachineChoice, preset_names};
    ui.heading("Machine");
    let shown = job.machine.as_ref().map_or("ideal (programmed feed)".to_owned(), |m| m.name().to_owned());
    egui::ComboBox::from_id_salt("machine_picker")
        .selected_text(shown)
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut job.machine, None, "ideal (programmed feed)");
            for name in preset_names() {
                let choice = Some(MachineChoice::Preset(name.to_owned()));
                ui.selectable_value(&mut job.machine, choice, name);
            }
        })
        .response
        .on_hover_text(
            "Acceleration, jerk and feed limits of the machine: the real cycle time, real MRR and \
             the feed plot (Machine & optimise tab) follow them. Presets in assets/machines/.",
        );
    for p in trochoplan_core::machine::Machine::PARAMS {
        field_error_line(ui, p, error);
    }
}

/// Slot width, length and depth.
fn slot_fields(ui: &mut egui::Ui, job: &mut Job, error: Option<&Error>) {
    Field::new(
        Param::SlotWidth,
        "mm",
        "Slot width B (mm). With the tool diameter it sets the \
        trochoidal radius a = (B − D)/2. Paper Table 1: 20 mm.",
        2.0..=100.0,
    )
    .log()
    .error(error)
    .show(ui, &mut job.slot_width);
    Field::new(
        Param::SlotLength,
        "mm",
        "Slot length L (mm) along +y from the stock face. \
        Sets the number of cycles and the machining time; does not change the per-cycle \
        analysis. Paper: 20 mm.",
        1.0..=2000.0,
    )
    .log()
    .error(error)
    .show(ui, &mut job.slot_length);
    Field::new(
        Param::Depth,
        "mm",
        "Axial depth of cut a_p = slot depth in one pass (mm). \
        MRR = B·s·a_p / t_cycle grows linearly with it. Paper section 4: 6 mm.",
        0.1..=50.0,
    )
    .log()
    .error(error)
    .show(ui, &mut job.depth);
    levels_fields(ui, job, error);
}

/// Tooltip of the deepest cut of one level.
const MAX_STEP_DOWN_TIP: &str = "Deepest cut of one level (mm). Ticked, the depth is cut in \
    n = ⌈depth / max step-down⌉ equal levels of depth / n each (12 mm at 5 mm: 3 levels of 4 mm, \
    not 5 + 5 + 2). Every level repeats the same loops at its own floor: the chips and the \
    engagement are those of one pass, the forces, torque and power those of one level's depth. \
    Unticked: one level at the full depth.";

/// Tooltip of the closed slot.
const CLOSED_TIP: &str = "A slot closed at both ends, as a keyway: the slot runs from Y0 to the \
    slot length with round ends. The tool centre stays D/2 from both end walls, so the cutting \
    edge stops at the wall. Each level is entered by a helix on the loop radius (B − D)/2 inside \
    the slot (at most 0.1·D and 5° down per turn; a centre-cutting end mill), then the loops, a \
    link back along the wall and one last loop into the end. Target: every move engages at most \
    the steady-state loop's engagement + 1° (measured, in the derived values). \
    Unticked (open slot): each level starts outside the stock before Y0, and the loops run on \
    past the slot length until the whole width is cut there (the tool centre then passes the \
    end by about a + s, in the air beyond the part).";

/// The levels (a ticked maximum step-down) and the slot's ends.
fn levels_fields(ui: &mut egui::Ui, job: &mut Job, error: Option<&Error>) {
    let lab = ui.label(Param::MaxStepDown.label()).on_hover_text(MAX_STEP_DOWN_TIP);
    ui.horizontal(|ui| {
        let mut on = job.max_step_down.is_some();
        if ui.checkbox(&mut on, "").labelled_by(lab.id).on_hover_text(MAX_STEP_DOWN_TIP).changed() {
            job.max_step_down = on.then_some((job.depth / 2.0).max(0.1));
        }
        if let Some(m) = &mut job.max_step_down {
            let depth = job.depth.max(0.2);
            ui.add(
                Slider::new(m, 0.1..=depth)
                    .clamping(SliderClamping::Never)
                    .logarithmic(true)
                    .max_decimals(3)
                    .custom_parser(super::number::parse)
                    .suffix(" mm"),
            )
            .labelled_by(lab.id)
            .on_hover_text(MAX_STEP_DOWN_TIP);
        } else {
            ui.label(RichText::new("one level at the full depth").weak());
        }
    });
    ui.end_row();
    field_error(ui, Param::MaxStepDown, error);
    let lab = ui.label(Param::Closed.label()).on_hover_text(CLOSED_TIP);
    ui.checkbox(&mut job.closed, "both ends are walls (keyway)").labelled_by(lab.id).on_hover_text(CLOSED_TIP);
    ui.end_row();
    field_error(ui, Param::Closed, error);
}

/// Tool diameter, teeth, feed and spindle speed.
fn tool_fields(ui: &mut egui::Ui, job: &mut Job, error: Option<&Error>) {
    let b = job.slot_width;
    let tip = format!(
        "Tool diameter D (mm). Grechishnikov et al. (2017) recommend 50–60 % of the slot \
         width, here {:.1}–{:.1} mm. Must be ≥ B/2 (else each loop leaves an island) and < B. \
         A larger tool shrinks a = (B − D)/2: shorter path, more MRR, less engagement room. \
         Paper: 10 mm.",
        0.5 * b,
        0.6 * b
    );
    let range = (0.5 * b).max(0.1)..=(0.95 * b).max(0.2);
    Field::new(Param::ToolDiameter, "mm", tip, range).error(error).show(ui, &mut job.tool_diameter);
    teeth_field(ui, &mut job.teeth, error);
    Field::new(
        Param::Feed,
        "mm/min",
        "Tool-centre feed rate f_r (mm/min). Sets the cycle time \
        t_cycle = cycle length / f_r and the feed per tooth f_z = f_r/(n·z), to which h is \
        proportional. Paper Table 1: 600 mm/min.",
        10.0..=10000.0,
    )
    .log()
    .decimals(1)
    .error(error)
    .show(ui, &mut job.feed);
    Field::new(
        Param::Rpm,
        "rpm",
        "Spindle speed n (rpm). Higher n: smaller f_z, thinner chips, \
        same cycle time. Paper Table 1: 2000 rpm.",
        100.0..=40000.0,
    )
    .log()
    .decimals(0)
    .error(error)
    .show(ui, &mut job.rpm);
    shop_values(ui, job);
}

/// The cutting speed and the chip load per tooth of the fields above, as the shop states them.
fn shop_values(ui: &mut egui::Ui, job: &Job) {
    let vc_tip = "Cutting speed Vc = π·D·n/1000 (m/min): the speed of the cutting edge, from the \
        tool diameter and the spindle speed; tool makers give its range for each work material.";
    let fz_tip = "Chip load per tooth f_z = f_r/(n·z) (mm): the feed each tooth advances in one \
        turn of the spindle; the chip thickness h is proportional to it.";
    let shown = |x: Option<f64>, decimals: usize, unit: &str| {
        x.map_or_else(|| "— (needs valid values)".to_owned(), |x| format!("{x:.decimals$} {unit}"))
    };
    ui.label("Cutting speed Vc").on_hover_text(vc_tip);
    ui.label(RichText::new(shown(job.cutting_speed_m_per_min(), 1, "m/min")).monospace()).on_hover_text(vc_tip);
    ui.end_row();
    ui.label("Chip load per tooth f_z").on_hover_text(fz_tip);
    ui.label(RichText::new(shown(job.chip_load_mm(), 4, "mm")).monospace()).on_hover_text(fz_tip);
    ui.end_row();
}

/// The whole-number slider of the teeth z.
fn teeth_field(ui: &mut egui::Ui, teeth: &mut u32, error: Option<&Error>) {
    let lab = ui.label(Param::Teeth.label());
    let tip = "Number of teeth z. Feed per tooth f_z = f_r/(n·z): more teeth, thinner chips \
        (h scales with f_z) and a shorter cooling time per tooth. Paper: 4.";
    lab.clone().on_hover_text(tip);
    let slider = Slider::new(teeth, 1..=12).clamping(SliderClamping::Never).custom_parser(super::number::parse);
    ui.add(slider.suffix(" teeth")).labelled_by(lab.id).on_hover_text(tip);
    ui.end_row();
    field_error(ui, Param::Teeth, error);
}

/// Step, aspect ratio and linear distance (the last two enabled for the paths that use them).
fn path_fields(ui: &mut egui::Ui, job: &mut Job, error: Option<&Error>) {
    Field::new(
        Param::Step,
        "mm",
        "Trochoidal step s (mm per cycle). Larger s: more MRR, thicker chips, larger \
        engagement and waviness. Keep the engagement ≤ 46° (Grechishnikov et al. 2017): the \
        engagement-limited step is in the derived values. Paper Table 1: 1 mm.",
        0.05..=(0.5 * job.tool_diameter).max(0.1),
    )
    .error(error)
    .show(ui, &mut job.step);
    Field::new(
        Param::AspectRatio,
        "",
        "Aspect ratio r_e = b/a of the elliptical loops (eq. 2), for elliptical and \
        linear-elliptical paths. Lower r_e: shorter path and more MRR (0.5: +21.8 % vs r_e = 1, \
        Table 2) with h_max almost constant, but more wall waviness (0.6: +48 %, Fig. 9). \
        The paper studies 0.5–1.2.",
        0.3..=1.5,
    )
    .enabled(job.path.uses_aspect_ratio())
    .error(error)
    .show(ui, &mut job.aspect_ratio);
    Field::new(
        Param::LinearDistance,
        "mm",
        "Linear distance d (mm) travelled along each wall per cycle (linear-elliptical \
        path, paper section 3). d = 0.75·s reduced the waviness three times against d = 0; \
        more d gave only ~60 % further (Figs. 25–28). The paper uses 0.75–1.25 mm.",
        0.0..=(0.25 * job.slot_width).max(0.1),
    )
    .enabled(job.path == PathKind::LinearElliptical)
    .error(error)
    .show(ui, &mut job.linear_distance);
}
