//! The tabs of the window, listed once in [`TABS`]: the View menu and the tab bar are built from
//! it, and the central panel shows the selected tab's panel.

use super::panels::compare::{self, VariantView};
use super::panels::graphics::Chip;
use super::panels::plots::{self, Cursor, Layer, PALETTE};
use super::{App, Command, Planner, Tab, Variant, panels};
use eframe::egui;
use trochoplan_core::Plan;

/// One tab: its label (menu and tab bar), tooltip and panel.
pub struct TabSpec {
    pub tab: Tab,
    pub label: &'static str,
    pub tooltip: &'static str,
    /// The slot's parameter and derived-value panels are shown beside it (the Corner and Pocket
    /// tabs have their own tool and inputs, and the acceptance table needs the whole width).
    pub slot_panels: bool,
    /// Draws the tab into the central panel.
    pub show: fn(&mut App, &mut egui::Ui, &mut Vec<Command>),
}

/// Every tab, in the order of the menu and the tab bar.
pub const TABS: [TabSpec; 10] = [
    TabSpec {
        tab: Tab::Plots,
        label: "Plots",
        tooltip: "Tool path, chip, chip thickness, engagement and wall of the edited job",
        slot_panels: true,
        show: plots_tab,
    },
    TabSpec {
        tab: Tab::Compare,
        label: "Compare",
        tooltip: "Pinned variants side by side: metrics and plots",
        slot_panels: true,
        show: compare_tab,
    },
    TabSpec {
        tab: Tab::Sweep,
        label: "Sweep",
        tooltip: "Metrics against r_e or d, planned on a background thread",
        slot_panels: true,
        show: sweep_tab,
    },
    TabSpec {
        tab: Tab::Forces,
        label: "Forces",
        tooltip: "Cutting forces over the cycle (Figs. 14–15) and edge imprints on the slot bottom (Figs. 21–22)",
        slot_panels: true,
        show: forces_tab,
    },
    TabSpec {
        tab: Tab::Export,
        label: "Export NC",
        tooltip: "Dialect, tolerance, preview, back-plot and save of the NC program",
        slot_panels: true,
        show: export_tab,
    },
    TabSpec {
        tab: Tab::Corner,
        label: "Corner",
        tooltip: "One pocket corner with corner trochoids, and the acceptance table",
        slot_panels: false,
        show: corner_tab,
    },
    TabSpec {
        tab: Tab::Pocket,
        label: "Pocket",
        tooltip: "A whole polygonal pocket: adaptive clearing, rings with corner trochoids, or the medial axis",
        slot_panels: false,
        show: pocket_tab,
    },
    TabSpec {
        tab: Tab::Optimise,
        label: "Machine & optimise",
        tooltip: "Feed over one cycle on the job's machine; the job of highest real MRR within your limits",
        slot_panels: true,
        show: optimise_tab,
    },
    TabSpec {
        tab: Tab::Program,
        label: "Program",
        tooltip: "Check any NC program: engagement, chip, force and problems along its path, two programs compared",
        slot_panels: false,
        show: program_tab,
    },
    TabSpec {
        tab: Tab::Operations,
        label: "Operations",
        tooltip: "A whole part: its operations from a part job file, each planned, opened in its own tab, and one program",
        slot_panels: false,
        show: operations_tab,
    },
];

impl Tab {
    /// This tab's entry in [`TABS`].
    pub fn spec(self) -> &'static TabSpec {
        let i = TABS.iter().position(|t| t.tab == self).unwrap_or(0);
        &TABS[i]
    }
}

fn plots_tab(app: &mut App, ui: &mut egui::Ui, _cmds: &mut Vec<Command>) {
    let s = &mut app.state;
    ui.horizontal(|ui| {
        let l = ui.label("cycles drawn");
        ui.add(egui::DragValue::new(&mut s.cycles_shown).range(2..=20))
            .labelled_by(l.id)
            .on_hover_text("Cycles of the tool-centre path drawn in the path view");
        ui.checkbox(&mut s.chip_close_up, "chip close-up")
            .on_hover_text("Chip view: the middle of the chip at 8·h (on) or the whole chip (off)");
        if !app.variants.is_empty() {
            ui.checkbox(&mut s.overlay_pins, format!("overlay {} pinned", app.variants.len()));
        }
    });
    let Some(cur) = &app.planner.last else {
        ui.label("No valid job yet: fix the marked parameter.");
        return;
    };
    panels::teach::controls(ui, &mut app.anim, &cur.plan);
    let cursor = app.anim.cursor(&cur.plan);
    let layers = layers(&app.planner, &app.variants, s.overlay_pins);
    plot_grid(ui, &layers, cursor, &app.chip, s.chip_close_up, s.teach);
}

fn compare_tab(app: &mut App, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
    let views: Vec<VariantView> = app
        .variants
        .iter()
        .enumerate()
        .map(|(i, v)| VariantView { label: &v.label, color: PALETTE[i + 1], metrics: &v.planned.plan.metrics })
        .collect();
    let can_pin = app.planner.error.is_none();
    cmds.extend(compare::show(ui, &views, can_pin));
    ui.separator();
    let cursor = app.planner.last.as_ref().and_then(|p| app.anim.cursor(&p.plan));
    let layers = layers(&app.planner, &app.variants, true);
    plot_grid(ui, &layers, cursor, &app.chip, app.state.chip_close_up, app.state.teach);
}

fn forces_tab(app: &mut App, ui: &mut egui::Ui, _cmds: &mut Vec<Command>) {
    let Some(cur) = &app.planner.last else {
        ui.label("No valid job yet: fix the marked parameter.");
        return;
    };
    panels::teach::controls(ui, &mut app.anim, &cur.plan);
    let cursor = app.anim.cursor(&cur.plan);
    let layers = layers(&app.planner, &app.variants, app.state.overlay_pins);
    let teach = app.state.teach;
    let avail = ui.available_size();
    let top = egui::vec2(avail.x, ((avail.y - 8.0) * 0.6).max(160.0));
    let bottom = egui::vec2(avail.x, (avail.y - 8.0 - top.y).max(120.0));
    sized(ui, top, |ui| plots::force_plot(ui, &layers, cursor, teach));
    sized(ui, bottom, |ui| plots::imprint_plot(ui, &layers, teach));
}

fn sweep_tab(app: &mut App, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
    cmds.extend(panels::sweep::show(ui, &mut app.state.sweep, app.sweep.as_ref(), &app.state.job));
}

fn export_tab(app: &mut App, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
    app.refresh_export();
    let job_error = app.planner.error.as_ref().map(ToString::to_string);
    let levels = app.planner.last.as_ref().is_some_and(|p| p.plan.job.in_levels());
    let (export, frame) = (&mut app.state.export, &mut app.state.job.program);
    cmds.extend(panels::export::show(ui, export, frame, &app.export, levels, job_error.as_deref()));
    // settings edited this frame: regenerate now, so the next frame shows them
    app.refresh_export();
}

fn optimise_tab(app: &mut App, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
    let plan = app.planner.last.as_ref().map(|p| &p.plan);
    cmds.extend(panels::optimise::show(ui, &mut app.state.optimise, app.optimise.as_ref(), plan));
}

fn program_tab(app: &mut App, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
    cmds.extend(panels::program_view::show(ui, &mut app.state.program, &mut app.program));
}

fn operations_tab(app: &mut App, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
    app.operations.update();
    cmds.extend(panels::operations_list::show(ui, &mut app.operations));
    // the machine chosen this frame: plan again now
    app.operations.update();
}

fn corner_tab(app: &mut App, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
    app.refresh_corner();
    let (inputs, nc) = (&mut app.state.corner, &mut app.state.corner_nc);
    cmds.extend(panels::corner::show(ui, inputs, &app.corner, nc, &app.corner_nc));
    // inputs edited this frame: ask for the new plan (and program) now
    app.refresh_corner();
}

fn pocket_tab(app: &mut App, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
    app.refresh_pocket();
    let nc = &mut panels::corner_nc::NcExport { settings: &mut app.state.pocket_nc, cache: &app.pocket_nc };
    cmds.extend(panels::pocket::show(ui, &mut app.state.pocket, &app.pocket, nc));
    // inputs edited this frame: ask for the new plan (and program) now
    app.refresh_pocket();
}

/// The plotted layers: the edited plan (unless it is pinned) and, with `with_pins`, the pinned
/// variants in their table colours. The layer of the edited plan is the primary one (cursor,
/// cooling and h_max annotations), also when it is drawn as one of the pins.
fn layers<'a>(planner: &'a Planner, variants: &'a [Variant], with_pins: bool) -> Vec<Layer<'a>> {
    let current = planner.last.as_ref();
    let is_current = |v: &Variant| current.is_some_and(|p| p.plan.job == v.planned.plan.job);
    let pins: Vec<(usize, &Variant)> = if with_pins { variants.iter().enumerate().collect() } else { Vec::new() };
    let mut out = Vec::new();
    if let Some(p) = current
        && !pins.iter().any(|(_, v)| is_current(v))
    {
        out.push(Layer { name: "current", color: PALETTE[0], g: &p.graphics, w: w_of(&p.plan), primary: true });
    }
    for (i, v) in pins {
        let primary = is_current(v);
        let layer =
            Layer { name: &v.label, color: PALETTE[i + 1], g: &v.planned.graphics, w: w_of(&v.planned.plan), primary };
        if primary { out.insert(0, layer) } else { out.push(layer) }
    }
    out
}

fn w_of(p: &Plan) -> (f64, f64) {
    (p.metrics.waviness_left_mm, p.metrics.waviness_right_mm)
}

/// `f` drawn into a box of `size` at the cursor of `ui`.
fn sized(ui: &mut egui::Ui, size: egui::Vec2, f: impl FnOnce(&mut egui::Ui)) {
    ui.allocate_ui_with_layout(size, egui::Layout::top_down(egui::Align::Min), |ui| {
        ui.set_min_size(size);
        ui.set_max_width(size.x);
        f(ui);
    });
}

/// The four plots in a 2 × 2 grid filling the rest of `ui`; the path view's cell shares its
/// width with the zoomed chip view.
fn plot_grid(
    ui: &mut egui::Ui,
    layers: &[Layer],
    cursor: Option<Cursor>,
    chip: &Chip,
    chip_close_up: bool,
    teach: bool,
) {
    let gap = 8.0;
    let avail = ui.available_size();
    let cell = egui::vec2(((avail.x - gap) / 2.0).max(150.0), ((avail.y - gap) / 2.0).max(140.0));
    // top row: the path view shares its cell with the chip view, so it gets more of the width
    let wide = egui::vec2(((avail.x - gap) * 0.6).max(300.0), cell.y);
    let narrow = egui::vec2((avail.x - gap - wide.x).max(150.0), cell.y);
    ui.horizontal(|ui| {
        sized(ui, wide, |ui| {
            let w = ui.available_width();
            let chip_w = (0.45 * w).clamp(150.0, 400.0);
            let h = ui.available_height();
            ui.horizontal_top(|ui| {
                let path_w = w - chip_w - ui.spacing().item_spacing.x;
                sized(ui, egui::vec2(path_w, h), |ui| plots::path_view(ui, layers, cursor, chip, teach));
                sized(ui, egui::vec2(chip_w, h), |ui| plots::chip_view(ui, layers, cursor, chip, chip_close_up, teach));
            });
        });
        sized(ui, narrow, |ui| plots::h_plot(ui, layers, cursor, teach));
    });
    ui.add_space(gap);
    ui.horizontal(|ui| {
        sized(ui, cell, |ui| plots::engagement_plot(ui, layers, cursor, teach));
        sized(ui, cell, |ui| plots::wall_plot(ui, layers, teach));
    });
}
