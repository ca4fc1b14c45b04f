//! The Pocket tab's inputs ([`PocketInputs`]): what `trochoplan pocket` takes, with its
//! defaults, and the row of fields that edits them, each with its unit and a tooltip.
//!
//! The pocket is cut with the job's tool and cutting data (tool diameter, teeth, feed, spindle
//! speed: the parameters panel beside the Plots tab), as the CLI cuts one command with one tool;
//! they are shown here, not edited. The depth is the NC export's depth, the retract height the
//! program frame's: the real time of the program is timed at them.

use super::label;
use eframe::egui::{self, DragValue, RichText};
use serde::{Deserialize, Serialize};
use trochoplan_core::geom::Polygon;
use trochoplan_core::job::Direction;
use trochoplan_core::machine::{self, Machine};
use trochoplan_core::pocket::{self, AdaptiveOptions, PaceOptions, PocketRequest, PocketStrategy};

/// Label of the target engagement field.
pub const TARGET: &str = "Target engagement";
/// Label of the helix radius field.
pub const HELIX_RADIUS: &str = "Helix radius";
/// Label of the ramp angle field.
pub const RAMP_ANGLE: &str = "Ramp angle";
/// Label of the finish stock field.
pub const FINISH_STOCK: &str = "Finish stock";
/// Label of the peak limit field.
pub const PEAK_LIMIT: &str = "Peak limit";
/// Label of the machine choice.
pub const MACHINE: &str = "Machine";
/// Label of the step-over field.
pub const STEP_OVER: &str = "Step-over a_e";
/// Label of the depth field.
pub const DEPTH: &str = "Depth";
/// The machine choice of no machine: every programmed feed held.
pub const IDEAL_MACHINE: &str = "ideal (feeds held)";

/// Inputs of the Pocket tab, persisted with the app state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct PocketInputs {
    /// Pocket boundary, one vertex "x,y" per line; after an empty line each further loop is an
    /// island inside it.
    pub polygon_text: String,
    /// Ring step-over a_e (mm).
    pub step_over_mm: f64,
    /// How the pocket is cleared (`--method`).
    pub strategy: PocketStrategy,
    /// The pocket's open edges, "i, j, …" (`--open-edges`: edge i from vertex i to i + 1).
    pub open_edges: String,
    /// Engagement the passes are planned to (degrees, `--target-engagement`); `None`: the
    /// core's default.
    pub target_deg: Option<f64>,
    /// Helix radius of the tool centre (mm, `--helix-radius`); `None`: the core's default.
    pub helix_radius_mm: Option<f64>,
    /// Ramp angle of the helix or ramp (degrees, `--ramp-angle`).
    pub ramp_deg: f64,
    /// Radial stock of the finishing contour (mm, `--finish-stock`).
    pub finish_stock_mm: f64,
    /// Climb or conventional (`--direction`).
    pub direction: Direction,
    /// Largest accepted peak (degrees, `--peak-limit`); `None`: the target + 1°.
    pub peak_limit_deg: Option<f64>,
    /// Machine preset (`--machine`); `None`: an ideal machine.
    pub machine: Option<String>,
    /// Cutting depth below Z0 (mm): the NC export's depth (a copy taken each frame).
    #[serde(skip)]
    pub depth_mm: f64,
    /// Draw the NC program read back over the planned path.
    pub show_program: bool,
    /// The job's tool diameter D (mm), feed f_r (mm/min), spindle speed (rpm) and teeth
    /// (copies taken each frame): the pocket is planned, paced and written with them.
    #[serde(skip)]
    pub tool_diameter_mm: f64,
    #[serde(skip)]
    pub feed_mm_per_min: f64,
    #[serde(skip)]
    pub spindle_rpm: f64,
    #[serde(skip)]
    pub teeth: u32,
    /// Retract height above Z0 of the program frame (mm; a copy taken each frame).
    #[serde(skip)]
    pub safe_z_mm: f64,
}

impl Default for PocketInputs {
    /// The defaults of `trochoplan pocket`: the README's rectangle, adaptive clearing.
    fn default() -> Self {
        let pocket = PocketRequest::default();
        let a = AdaptiveOptions::default();
        PocketInputs {
            polygon_text: crate::shared::outline::points_text(pocket.polygon.vertices()),
            step_over_mm: pocket.step_over_mm,
            strategy: pocket.strategy,
            open_edges: String::new(),
            target_deg: a.target_deg,
            helix_radius_mm: a.helix_radius_mm,
            ramp_deg: a.ramp_deg,
            finish_stock_mm: a.finish_stock_mm,
            direction: a.direction,
            peak_limit_deg: pocket.peak_limit_deg,
            machine: None,
            depth_mm: trochoplan_core::nc::CutSetup::default().depth_mm,
            show_program: true,
            tool_diameter_mm: pocket.tool_diameter_mm,
            feed_mm_per_min: pocket.feed_mm_per_min,
            spindle_rpm: pocket.pace.rpm,
            teeth: pocket.pace.teeth,
            safe_z_mm: trochoplan_core::frame::ProgramFrame::default().retract_height_mm(),
        }
    }
}

impl PocketInputs {
    /// The machine of the inputs, if one is chosen.
    pub fn machine(&self) -> Result<Option<Machine>, String> {
        self.machine.as_deref().map(Machine::preset).transpose().map_err(|e| e.to_string())
    }

    /// The core's pocket request of the tab's inputs, built as `trochoplan pocket` builds it
    /// from its flags: the polygon text read and validated, every other input the CLI does not
    /// take from the tab at its default.
    pub fn request(&self) -> Result<PocketRequest, String> {
        // read as a point-list outline, as `trochoplan pocket --polygon` reads its file: loops
        // separated by an empty line, the first the boundary, the loops inside it its islands
        let pockets = trochoplan_core::outline::read("polygon", &self.polygon_text).map_err(|e| e.to_string())?;
        let (boundary, island_points) = pockets.one_pocket().map_err(|e| e.to_string())?;
        let points = boundary.to_vec();
        let polygon = Polygon::new(points.clone()).map_err(|e| format!("polygon: {e}"))?;
        let islands = island_points
            .iter()
            .enumerate()
            .map(|(k, v)| Polygon::new(v.clone()).map_err(|e| format!("island {}: {e}", k + 1)))
            .collect::<Result<Vec<_>, _>>()?;
        let open: Vec<usize> = self
            .open_edges
            .split([',', ' '])
            .filter(|w| !w.trim().is_empty())
            .map(|w| w.trim().parse::<usize>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("open edges: \"{}\" is not a list of edge numbers i, j, …", self.open_edges))?;
        let open_edges = pocket::stored_open_edges(&polygon, &points, &open).map_err(|e| e.to_string())?;
        let d = PocketRequest::default();
        let m = self.machine()?;
        let p = PaceOptions::default();
        Ok(PocketRequest {
            polygon,
            islands,
            tool_diameter_mm: self.tool_diameter_mm,
            step_over_mm: self.step_over_mm,
            feed_mm_per_min: self.feed_mm_per_min,
            strategy: self.strategy,
            spacing_mm: d.spacing_mm,
            adaptive: AdaptiveOptions {
                helix_radius_mm: self.helix_radius_mm,
                ramp_deg: self.ramp_deg,
                finish_stock_mm: self.finish_stock_mm,
                direction: self.direction,
                depth_mm: self.depth_mm,
                target_deg: self.target_deg,
                ..AdaptiveOptions::default()
            },
            open_edges,
            // as `trochoplan pocket --machine`: the machine's largest feed and block time
            pace: PaceOptions {
                teeth: self.teeth,
                rpm: self.spindle_rpm,
                max_feed_mm_per_min: m.as_ref().map(|m| m.max_speed_mm_per_s() * 60.0),
                block_time_s: m.as_ref().map_or(p.block_time_s, |m| m.block_time),
                machine: m,
                ..p
            },
            peak_limit_deg: self.peak_limit_deg,
            ..d
        })
    }
}

/// The job's tool and cutting data, read-only, with the cutting speed and the chip per tooth.
pub fn tool_row(ui: &mut egui::Ui, i: &PocketInputs) {
    let vc = std::f64::consts::PI * i.tool_diameter_mm * i.spindle_rpm / 1000.0;
    let fz = i.feed_mm_per_min / (i.spindle_rpm * f64::from(i.teeth));
    let fz = if fz.is_finite() { format!("{fz:.3} mm") } else { "— (no spindle speed or teeth)".to_owned() };
    ui.label(RichText::new("Tool (the job's)").strong()).on_hover_text(
        "The pocket is cut with the job's tool and cutting data: change them in the parameters panel \
         beside the Plots tab. One tool for the slot, the pocket and their programs.",
    );
    ui.label(format!(
        "D {:.2} mm · {} teeth · feed {:.0} mm/min · {:.0} rpm · Vc {:.0} m/min · chip per tooth {fz}",
        i.tool_diameter_mm, i.teeth, i.feed_mm_per_min, i.spindle_rpm, vc
    ))
    .on_hover_text(
        "Tool diameter, teeth, the programmed feed and the spindle speed of the job; the cutting speed \
         Vc = π·D·n and the chip per tooth f_z = feed / (n · teeth). Each move's feed is then raised \
         or lowered so that every tooth's largest chip stays at f_z.",
    );
}

/// An optional number labelled by `label`: a checkbox (ticked: the user's value, at first
/// `default`) and the value, or what is used unticked (`auto`).
fn optional(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut Option<f64>,
    default: f64,
    speed: f64,
    suffix: &str,
    auto: &str,
) -> egui::Response {
    let l = ui.label(label);
    let mut on = value.is_some();
    let tick = ui.checkbox(&mut on, "").labelled_by(l.id).on_hover_text(format!("Unticked: {auto}"));
    if tick.changed() {
        *value = if on { Some(default) } else { None };
    }
    match value {
        Some(v) => ui.add(DragValue::new(v).speed(speed).suffix(suffix.to_owned()).max_decimals(3)).labelled_by(l.id),
        None => ui.add_enabled(false, egui::Label::new(auto)),
    }
}

/// The pocket's own inputs: method, step-over, target, entry, finish stock, direction, open
/// edges, peak limit, machine, depth.
pub fn input_rows(ui: &mut egui::Ui, i: &mut PocketInputs) {
    let adaptive = matches!(i.strategy, PocketStrategy::Adaptive | PocketStrategy::Slot);
    ui.horizontal_wrapped(|ui| {
        let l = ui.label(STEP_OVER);
        ui.add(DragValue::new(&mut i.step_over_mm).speed(0.05).suffix(" mm").max_decimals(3))
            .labelled_by(l.id)
            .on_hover_text(
                "Distance between two passes side by side, more than 0 and less than the tool diameter. \
             On a straight wall it gives the engagement arccos(1 − a_e/r).",
            );
        optional(ui, TARGET, &mut i.target_deg, 50.0, 0.5, "°", "from the step-over").on_hover_text(
            "Angle of the tool's circumference in the cut that every adaptive pass is planned to \
                 (degrees, from the step-over's straight-wall angle up to 90°). Unticked: the step-over \
                 read as an area rate on a 90° corner, at most 50°. With the medial axis it replaces \
                 the corner target of Wu et al. (2016).",
        );
        optional(ui, PEAK_LIMIT, &mut i.peak_limit_deg, 60.0, 0.5, "°", "target + 1°").on_hover_text(
            "Largest measured engagement accepted anywhere on the path (degrees, above the target, \
                 at most 180; adaptive clearing). A pocket whose path reads above it is refused with \
                 the move and place named.",
        );
        ui.separator();
        let l = ui.label(label::POCKET_OPEN_EDGES);
        ui.add_enabled(
            i.strategy == PocketStrategy::Adaptive,
            egui::TextEdit::singleline(&mut i.open_edges).id_salt("pocket_open_edges").desired_width(60.0),
        )
        .labelled_by(l.id)
        .on_hover_text(
            "Edges without a wall (adaptive clearing): \"0\" or \"0, 2\"; edge i runs from vertex i to \
             vertex i + 1 (counted from 0). The tool goes down outside the stock there and clears inward.",
        );
    });
    ui.horizontal_wrapped(|ui| {
        let d = i.tool_diameter_mm;
        optional(ui, HELIX_RADIUS, &mut i.helix_radius_mm, 0.375 * d, 0.05, " mm", "0.375 × D").on_hover_text(
            "Radius of the tool centre's helix going down into the stock (mm). Unticked: 0.375 × D, \
                 down to 0.25 × D where the pocket is narrower; where not even that fits, a zig-zag ramp.",
        );
        let l = ui.label(RAMP_ANGLE);
        ui.add(DragValue::new(&mut i.ramp_deg).speed(0.1).suffix("°").max_decimals(2)).labelled_by(l.id).on_hover_text(
            "Angle of the helix or ramp going down (degrees), more than 0 and at most 15; 2–5° suits \
             most solid end mills.",
        );
        let l = ui.label(FINISH_STOCK);
        ui.add_enabled(adaptive, DragValue::new(&mut i.finish_stock_mm).speed(0.01).suffix(" mm").max_decimals(3))
            .labelled_by(l.id)
            .on_hover_text(
                "Material left on the walls for the finishing pass (mm; adaptive clearing). 0: no finishing pass.",
            );
        let l = ui.label(DEPTH);
        ui.add(DragValue::new(&mut i.depth_mm).speed(0.1).suffix(" mm").max_decimals(3))
            .labelled_by(l.id)
            .on_hover_text(
                "Depth of the pocket below the stock top Z0 (mm), the program's cutting depth: the helix \
             goes down to it and the real time counts it.",
            );
        ui.separator();
        ui.label("Direction");
        for d in Direction::ALL {
            ui.radio_value(&mut i.direction, d, d.name()).on_hover_text(direction_help(d));
        }
        ui.separator();
        machine_choice(ui, &mut i.machine);
    });
}

/// The milling direction in the shop's words.
fn direction_help(d: Direction) -> &'static str {
    match d {
        Direction::Climb => {
            "Climb milling: the tool turns with the feed (M3, loops counter-clockwise); the chip starts thick."
        }
        Direction::Conventional => {
            "Conventional milling: the tool turns against the feed (M3, loops clockwise); the chip starts thin."
        }
    }
}

/// The machine: none (every feed held) or a preset.
fn machine_choice(ui: &mut egui::Ui, choice: &mut Option<String>) {
    machine_picker(
        ui,
        [MACHINE, IDEAL_MACHINE, "pocket_machine"],
        choice,
        "The machine the program runs on: its acceleration, jerk, rapid rate and block time give \
         the real time and the feed it reaches; the largest feed a move is paced to is its \
         largest feed. Ideal: every programmed feed held, moves up to 3 × the feed.",
    );
}

/// A choice of the machine under `label`: `None` the ideal one (shown as `ideal`) or a preset
/// by name; `salt` keeps its list apart from other pickers in the window.
pub(super) fn machine_picker(
    ui: &mut egui::Ui,
    [label, ideal, salt]: [&str; 3],
    choice: &mut Option<String>,
    tooltip: &str,
) {
    let l = ui.label(label);
    let shown = choice.clone().unwrap_or_else(|| ideal.to_owned());
    egui::ComboBox::from_id_salt(salt)
        .selected_text(shown)
        .show_ui(ui, |ui| {
            ui.selectable_value(choice, None, ideal);
            for name in machine::preset_names() {
                ui.selectable_value(choice, Some(name.to_owned()), name);
            }
        })
        .response
        .labelled_by(l.id)
        .on_hover_text(tooltip);
}
