//! Headless GUI tests (egui_kittest, no display): drive the real window contents through the
//! accessibility tree and check the plan and the shown values.

use super::panels::label;
use super::*;
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use panels::compare;
use std::path::Path;
use trochoplan_core::{Error, Param};

/// Dialogs answering from fixed paths: tests never open a real dialog.
struct FakeDialogs {
    open: Option<PathBuf>,
    save: Option<PathBuf>,
}

impl FileDialogs for FakeDialogs {
    fn open_job(&mut self) -> Option<PathBuf> {
        self.open.clone()
    }
    fn save_job(&mut self, _current: Option<&Path>) -> Option<PathBuf> {
        self.save.clone()
    }
    fn save_nc(&mut self, _stem: &str, _extension: &str) -> Option<PathBuf> {
        self.save.clone()
    }
    fn open_outline(&mut self) -> Option<PathBuf> {
        self.open.clone()
    }
}

fn harness_with(app: App) -> Harness<'static, App> {
    let mut h =
        Harness::builder().with_size(egui::vec2(1400.0, 900.0)).build_ui_state(|ui, app: &mut App| app.show(ui), app);
    h.run();
    h
}

fn harness() -> Harness<'static, App> {
    harness_with(App::new(Job::default(), None, Box::new(FakeDialogs { open: None, save: None })))
}

/// The default job's window whose save dialog answers `file`.
fn harness_saving_to(file: &std::path::Path) -> Harness<'static, App> {
    harness_with(App::new(Job::default(), None, Box::new(FakeDialogs { open: None, save: Some(file.to_owned()) })))
}

fn metrics(h: &Harness<'_, App>) -> trochoplan_core::Metrics {
    h.state().planner.last.as_ref().expect("a plan").plan.metrics.clone()
}

fn shows(h: &Harness<'_, App>, text: &str) -> bool {
    h.query_all_by_label(text).next().is_some()
}

#[test]
fn default_job_shows_its_metrics() {
    let h = harness();
    let m = metrics(&h);
    assert!(shows(&h, &format!("{:.4} mm", m.h_max_mm)), "h_max shown");
    assert!(shows(&h, &format!("{:.0} mm³/min", m.mrr_mm3_per_min)), "MRR shown");
    assert!(h.state().planner.error.is_none());
}

#[test]
fn changing_the_step_in_the_ui_replans_and_updates_the_shown_metrics() {
    let mut h = harness();
    let before = metrics(&h);
    let replans = h.state().planner.replans;
    h.get_by_role_and_label(Role::Slider, Param::Step.label()).set_value_accesskit(0.7);
    h.run();
    let after = metrics(&h);
    assert!((h.state().state.job.step - 0.7).abs() < 1e-9, "job step {}", h.state().state.job.step);
    assert!((after.step_mm - 0.7).abs() < 1e-9, "plan step {}", after.step_mm);
    assert!(h.state().planner.replans > replans, "replanned");
    assert!(after.mrr_mm3_per_min < before.mrr_mm3_per_min, "smaller step, less MRR");
    assert!(after.h_max_mm < before.h_max_mm, "smaller step, thinner chips");
    assert!(shows(&h, &format!("{:.0} mm³/min", after.mrr_mm3_per_min)), "new MRR shown");
    assert!(shows(&h, &format!("{:.4} mm", after.h_max_mm)), "new h_max shown");
    assert!(!shows(&h, &format!("{:.0} mm³/min", before.mrr_mm3_per_min)), "old MRR gone");
}

#[test]
fn lowering_the_aspect_ratio_moves_mrr_and_waviness_as_the_paper_describes() {
    let mut h = harness();
    h.get_by_label(trochoplan_core::PathKind::Elliptical.label()).click();
    h.run();
    assert_eq!(h.state().state.job.path, trochoplan_core::PathKind::Elliptical);
    let r1 = metrics(&h);
    h.get_by_role_and_label(Role::Slider, Param::AspectRatio.label()).set_value_accesskit(0.5);
    h.run();
    let r05 = metrics(&h);
    assert!((r05.aspect_ratio - 0.5).abs() < 1e-9);
    // Table 2 / Fig. 9: MRR up ~22 %, waviness up.
    assert!(r05.mrr_mm3_per_min > 1.15 * r1.mrr_mm3_per_min, "{} vs {}", r05.mrr_mm3_per_min, r1.mrr_mm3_per_min);
    assert!(r05.waviness_left_mm > r1.waviness_left_mm);
    assert!(r05.t_cooling_s < r1.t_cooling_s);
}

#[test]
fn climb_milling_mirrors_the_loops_and_swaps_the_walls() {
    let mut h = harness();
    h.get_by_label(trochoplan_core::PathKind::Elliptical.label()).click();
    h.run();
    let conv = metrics(&h);
    h.get_by_label("climb").click();
    h.run();
    assert_eq!(h.state().state.job.direction, trochoplan_core::job::Direction::Climb);
    let climb = metrics(&h);
    // climb is the mirror image — same h_max, the walls' waviness swapped
    assert_eq!(climb.direction, trochoplan_core::job::Direction::Climb);
    assert!((climb.h_max_mm - conv.h_max_mm).abs() < 1e-12);
    assert!((climb.waviness_left_mm - conv.waviness_right_mm).abs() < 1e-12);
    assert!((climb.waviness_right_mm - conv.waviness_left_mm).abs() < 1e-12);
}

#[test]
fn an_invalid_value_is_marked_at_the_field_and_the_last_plan_is_kept() {
    let mut h = harness();
    let before = metrics(&h);
    h.get_by_role_and_label(Role::Slider, Param::ToolDiameter.label()).set_value_accesskit(25.0);
    h.run();
    let app = h.state();
    assert_eq!(app.state.job.tool_diameter, 25.0);
    let err = app.planner.error.clone().expect("invalid job");
    assert_eq!(err.parameter(), Some(Param::ToolDiameter));
    assert!(shows(&h, &err.to_string()), "the core's message is shown");
    assert!(shows(&h, "Job invalid: showing the last valid plan."));
    assert_eq!(metrics(&h), before, "last valid plan kept");
    // Still draws and recovers.
    h.get_by_role_and_label(Role::Slider, Param::ToolDiameter.label()).set_value_accesskit(11.0);
    h.run();
    assert!(h.state().planner.error.is_none());
    assert!((metrics(&h).a_mm - 4.5).abs() < 1e-12);
}

#[test]
fn compare_mode_adds_variants_and_shows_percent_changes() {
    let mut h = harness();
    h.get_by_label("Compare").click();
    h.run();
    assert_eq!(h.state().view.tab, Tab::Compare);
    h.get_by_label("Pin current job").click();
    h.run();
    assert_eq!(h.state().variants.len(), 1);
    h.get_by_label(trochoplan_core::PathKind::Elliptical.label()).click();
    h.run();
    h.get_by_role_and_label(Role::Slider, Param::AspectRatio.label()).set_value_accesskit(0.8);
    h.run();
    h.get_by_label("Pin current job").click();
    h.run();
    let app = h.state();
    assert_eq!(app.variants.len(), 2);
    assert!((app.variants[1].job.aspect_ratio - 0.8).abs() < 1e-9);
    let (m0, m1) = (&app.variants[0].planned.plan.metrics, &app.variants[1].planned.plan.metrics);
    let p = compare::percent_change(m1.mrr_mm3_per_min, m0.mrr_mm3_per_min).expect("percent");
    let cell = format!("{:.0}  ({p:+.1} %)", m1.mrr_mm3_per_min);
    assert!(shows(&h, &cell), "table shows {cell}");
    h.get_by_label("Pin the paper's set").click();
    h.run();
    assert_eq!(h.state().variants.len(), 3);
}

#[test]
fn undo_redo_and_open_save_through_the_dialog_trait() {
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("job.toml");
    let app =
        App::new(Job::default(), None, Box::new(FakeDialogs { open: Some(file.clone()), save: Some(file.clone()) }));
    let mut h = harness_with(app);
    h.get_by_role_and_label(Role::Slider, Param::Step.label()).set_value_accesskit(0.8);
    h.run();
    // Save as (fake dialog), edit, open again.
    h.state_mut().apply(Command::SaveAs, &egui::Context::default());
    let saved = std::fs::read_to_string(&file).expect("saved");
    assert!(saved.contains("step = 0.8"), "{saved}");
    h.get_by_role_and_label(Role::Slider, Param::Step.label()).set_value_accesskit(0.5);
    h.run();
    h.state_mut().apply(Command::Open, &egui::Context::default());
    h.run();
    assert!((h.state().state.job.step - 0.8).abs() < 1e-12);
    // Undo goes back to the edit before opening.
    h.state_mut().apply(Command::Undo, &egui::Context::default());
    h.run();
    assert!((h.state().state.job.step - 0.5).abs() < 1e-12, "undo: {}", h.state().state.job.step);
    h.state_mut().apply(Command::Redo, &egui::Context::default());
    h.run();
    assert!((h.state().state.job.step - 0.8).abs() < 1e-12, "redo");
}

#[test]
fn sweep_tab_runs_in_the_background_and_teaching_animates() {
    let mut h = harness();
    h.get_by_label("Sweep").click();
    h.run();
    h.state_mut().state.sweep.steps = 6;
    h.get_by_label("Run sweep").click();
    // One frame starts the run; `run()` here would fail under load while the progress bar
    // keeps asking for repaints. The loop below waits for the worker.
    h.step();
    let t0 = Instant::now();
    while h.state().sweep.as_ref().is_some_and(SweepRun::running) && t0.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(10));
        h.step();
    }
    h.run();
    let run = h.state().sweep.as_ref().expect("sweep");
    assert_eq!(run.points.len(), 6);
    assert!(run.points.iter().all(|p| p.result.is_ok()));

    h.get_by_label("Plots").click();
    h.run();
    h.get_by_label("Play").click();
    for _ in 0..5 {
        h.step();
    }
    assert!(h.state().anim.playing);
    assert!(h.state().anim.t_s.is_some());
}

/// eframe storage in memory.
#[derive(Default)]
struct MemoryStorage(std::collections::HashMap<String, String>);

impl eframe::Storage for MemoryStorage {
    fn get_string(&self, key: &str) -> Option<String> {
        self.0.get(key).cloned()
    }
    fn set_string(&mut self, key: &str, value: String) {
        self.0.insert(key.to_owned(), value);
    }
    fn remove_string(&mut self, key: &str) {
        self.0.remove(key);
    }
    fn flush(&mut self) {}
}

#[test]
fn persisted_state_round_trips() {
    let mut state = State::default().with_job(Job { step: 0.6, ..Job::default() });
    state.view.tab = Tab::Sweep;
    let mut storage = MemoryStorage::default();
    State::save(&state.inputs, &state.view, &mut storage);
    let back = State::load(&storage).expect("stored");
    assert_eq!(back, state);
    let app = App::new(Job::default(), Some(back), Box::new(NativeDialogs));
    assert!((app.planner.last.as_ref().expect("plan").plan.metrics.step_mm - 0.6).abs() < 1e-12);
    assert_eq!(app.view.tab, Tab::Sweep);
}

/// Part of the one flat record that versions before the undoable [`Inputs`] stored.
#[derive(serde::Serialize)]
struct EarlierState {
    job: Job,
    tab: Tab,
    teach: bool,
    cycles_shown: usize,
    pinned: Vec<PinnedJob>,
    file: Option<PathBuf>,
}

#[test]
fn an_earlier_saved_state_still_loads_with_its_pins() {
    let job = Job { step: 0.7, ..Job::default() };
    let bad = Job { tool_diameter: 25.0, ..Job::default() };
    let pinned = vec![PinnedJob { label: "a".into(), job: job.clone() }, PinnedJob { label: "bad".into(), job: bad }];
    let file = Some(PathBuf::from("/tmp/job.toml"));
    let earlier = EarlierState { job, tab: Tab::Compare, teach: true, cycles_shown: 4, pinned, file: file.clone() };
    let mut storage = MemoryStorage::default();
    eframe::set_value(&mut storage, state::INPUTS_KEY, &earlier);
    let app = App::new(Job::default(), State::load(&storage), Box::new(NativeDialogs));
    assert_eq!(app.view, View { tab: Tab::Compare, file });
    assert_eq!((app.state.teach, app.state.cycles_shown), (true, 4));
    assert_eq!(app.state.corner, Inputs::default().corner, "missing fields take their defaults");
    assert_eq!(app.variants.len(), 1, "the valid pin is planned, the invalid one dropped");
    assert_eq!(app.state.pinned.len(), 1);
    assert!((app.variants[0].planned.plan.metrics.step_mm - 0.7).abs() < 1e-12);
}

#[test]
fn the_menu_and_the_tab_bar_list_every_tab_once_with_one_label() {
    let mut h = harness();
    for t in &tabs::TABS {
        assert_eq!(t.tab.spec().label, t.label);
        h.get_by_label(t.label).click();
        h.run();
        assert_eq!(h.state().view.tab, t.tab, "tab bar: {}", t.label);
    }
    h.get_by_label("View").click();
    h.run();
    assert_eq!(h.query_all_by_label("Plots").count(), 2, "menu and tab bar");
    h.get_by_role_and_label(Role::RadioButton, "Sweep").click();
    h.run();
    assert_eq!(h.state().view.tab, Tab::Sweep, "View menu");
}

/// Let the undo history settle: the harness advances 0.25 s a step, the undoer records a state
/// that stayed unchanged for 1 s.
fn settle(h: &mut Harness<'_, App>) {
    for _ in 0..6 {
        h.step();
    }
}

#[test]
fn undo_and_redo_cover_every_input_but_not_the_tab() {
    let mut h = harness();
    h.get_by_label("Teach").click();
    settle(&mut h);
    h.get_by_label("Compare").click();
    h.run();
    h.get_by_label("Pin current job").click();
    settle(&mut h);
    h.get_by_label("Export NC").click();
    h.run();
    h.get_by_label("Fanuc-style ISO").click();
    h.state_mut().state.sweep.steps = 7;
    h.state_mut().state.corner_nc.depth_mm = -2.5;
    settle(&mut h);
    let edited = h.state().state.clone();
    assert!(edited.teach && edited.pinned.len() == 1 && h.state().variants.len() == 1);
    assert_ne!(edited.export, Inputs::default().export, "dialect chosen");
    let initial = Inputs::default();

    // Ctrl+Z: the export, sweep and corner settings; the Edit menu: the pin; the button: Teach.
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run();
    let s = &h.state().state;
    assert_eq!((s.sweep.steps, s.corner_nc.depth_mm), (initial.sweep.steps, initial.corner_nc.depth_mm));
    assert_eq!(s.export, initial.export, "dialect undone");
    assert_eq!(s.pinned.len(), 1);
    h.get_by_label("Edit").click();
    h.run();
    h.get_by_label("Undo  (Ctrl+Z)").click();
    h.run();
    assert!(h.state().state.pinned.is_empty() && h.state().variants.is_empty(), "pin undone");
    assert!(h.state().state.teach);
    h.get_by_label("Undo").click();
    h.run();
    assert_eq!(h.state().state, initial, "back to the start");
    assert_eq!(h.state().view.tab, Tab::Export, "the tab is no input");

    for _ in 0..3 {
        h.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::Z);
        h.run();
    }
    assert_eq!(h.state().state, edited, "redone");
    assert_eq!(h.state().variants.len(), 1, "the pin's plan is back");
}

#[test]
fn threaded_planner_delivers_the_newest_plan_and_validates_at_once() {
    let mut p = Planner::threaded(|| {});
    assert!(p.update(&Job::default(), 5));
    assert!(p.last.is_some(), "the first plan is computed at once");
    for step in [0.9, 0.8, 0.7] {
        p.update(&Job { step, ..Job::default() }, 5);
    }
    let t0 = Instant::now();
    while p.pending() && t0.elapsed().as_secs() < 30 {
        std::thread::sleep(std::time::Duration::from_millis(2));
        p.poll();
    }
    assert!(!p.pending());
    assert!((p.last.as_ref().expect("plan").plan.metrics.step_mm - 0.7).abs() < 1e-12, "newest plan wins");
    assert!(!p.update(&Job { tool_diameter: 25.0, ..Job::default() }, 5), "invalid: nothing planned");
    assert_eq!(p.error.as_ref().and_then(Error::parameter), Some(Param::ToolDiameter));
    assert!((p.last.as_ref().expect("plan").plan.metrics.step_mm - 0.7).abs() < 1e-12, "last valid plan kept");
}

/// egui frame time (UI + tessellation, no rasteriser) while the step changes every frame as it
/// does while a slider is dragged, at 60 frames per second with the planning thread running
/// (every plan includes the force series and the imprints), on the Plots tab and
/// on the Forces tab (its force and imprint plots drawn every frame).
/// Run: `cargo test --release -p trochoplan frame_time -- --ignored --nocapture`.
#[test]
#[ignore = "measurement, prints frame-time statistics"]
fn frame_time_while_dragging_a_slider() {
    for tab in [Tab::Plots, Tab::Forces] {
        let ctx = egui::Context::default();
        let repaint = ctx.clone();
        let dialogs = Box::new(FakeDialogs { open: None, save: None });
        let mut app =
            App::with_planner(Job::default(), None, dialogs, Planner::threaded(move || repaint.request_repaint()));
        app.view.tab = tab;
        let mut ms = Vec::new();
        for i in 0..300 {
            app.state.job.step = 1.0 - 0.5 * f64::from(i % 150) / 150.0;
            let input = egui::RawInput {
                screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(1400.0, 900.0))),
                time: Some(f64::from(i) / 60.0),
                ..Default::default()
            };
            let t0 = Instant::now();
            let out = ctx.run_ui(input, |ui| app.show(ui));
            let meshes = ctx.tessellate(out.shapes, out.pixels_per_point);
            ms.push(t0.elapsed().as_secs_f64() * 1e3);
            assert!(!meshes.is_empty());
            std::thread::sleep(std::time::Duration::from_millis(16));
        }
        let warm = &mut ms[30..];
        warm.sort_by(f64::total_cmp);
        let q = |p: f64| warm[((warm.len() - 1) as f64 * p) as usize];
        println!(
            "{tab:?} tab, frame (UI + tessellation) over {} frames: median {:.2} ms, p90 {:.2} ms, p99 {:.2} ms, max {:.2} ms; last plan {:.2} ms",
            warm.len(),
            q(0.5),
            q(0.9),
            q(0.99),
            q(1.0),
            app.planner.plan_ms
        );
        assert!(app.planner.replans > 100, "{tab:?}: replanned while dragging: {}", app.planner.replans);
        assert_eq!(app.view.tab, tab);
    }
}

fn export_text(h: &Harness<'_, App>) -> String {
    h.state().export.view().expect("a program").text.clone()
}

#[test]
fn export_panel_previews_each_dialect_reports_errors_and_saves_the_previewed_text() {
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("slot.ngc");
    let mut h = harness_saving_to(&file);
    h.get_by_label("File").click();
    h.run();
    h.get_by_label("Export NC…").click();
    h.run();
    assert_eq!(h.state().view.tab, Tab::Export);
    let linuxcnc = export_text(&h);
    assert!(linuxcnc.contains("G21") && linuxcnc.contains("G64 P"), "{linuxcnc}");
    assert!(shows(&h, "G17 G21 G40 G49 G80 G90 G91.1 G94"), "preview shows the set-up block");
    assert!(!h.state().export.view().expect("view").backplot.is_empty(), "back-plot drawn");
    let generated = h.state().export.generated;
    h.run();
    assert_eq!(h.state().export.generated, generated, "not regenerated per frame");

    h.get_by_label("Sinumerik 840D").click();
    h.run();
    let sinumerik = export_text(&h);
    assert_ne!(sinumerik, linuxcnc);
    assert!(sinumerik.contains("G71") && sinumerik.starts_with("; TrochoPlan slot"), "{sinumerik}");
    assert!(!sinumerik.contains("G21"));
    assert!(shows(&h, "G17 G40 G71 G90 G94"), "preview follows the dialect");

    // an invalid tolerance: the core's message in the panel, no panic, nothing to save
    h.get_by_role_and_label(Role::Slider, label::NC_TOLERANCE).set_value_accesskit(5.0);
    h.run();
    assert_eq!(h.state().state.export.tolerance_mm, 5.0);
    let opts = trochoplan_core::nc::NcOptions { tolerance_mm: 5.0, ..Default::default() };
    let msg = opts.validate().expect_err("invalid").to_string();
    assert!(shows(&h, &format!("Cannot write the program: {msg}")), "error shown: {msg}");
    assert!(h.query_by_label(label::SAVE_NC_PROGRAM).is_none(), "no save button without a program");

    h.get_by_role_and_label(Role::Slider, label::NC_TOLERANCE).set_value_accesskit(0.01);
    h.get_by_label(label::COMPACT_LOOP).click();
    h.run();
    let view = h.state().export.view().expect("program").clone();
    assert!(view.text.contains("GOTOB"), "compact Sinumerik loop");
    assert!(view.backplot_note.is_some() && !view.backplot.is_empty(), "loop back-plotted as expanded");
    h.get_by_label(label::SAVE_NC_PROGRAM).click();
    h.run();
    let saved = std::fs::read_to_string(&file).expect("saved");
    assert_eq!(saved, view.text, "the file holds the previewed text");
    let (status, is_err) = h.state().status.clone().expect("status");
    assert!(!is_err && status.starts_with("exported"), "{status}");
}

#[test]
fn teaching_highlights_the_chip_of_a_cutting_tooth_and_none_while_cooling() {
    let mut h = harness();
    // the animation starts at the h_max tooth: it cuts
    let (plan, g) = {
        let p = h.state().planner.last.as_ref().expect("plan");
        (p.plan.clone(), p.graphics.clone())
    };
    let c = h.state().anim.cursor(&plan).expect("cursor");
    assert!(c.cutting);
    let outline = &h.state().chip.outline;
    let core = plan.chip_outline(c.tooth);
    assert!(outline.len() >= 3, "chip drawn at a cutting tooth");
    assert_eq!(outline.len(), core.len() + 1, "closed outline");
    assert!(!h.state().chip.fill.is_empty(), "chip filled");
    assert!((outline[0].x - (core[0].x + g.origin[0])).abs() < 1e-12);
    // scrub into the cooling interval through the UI
    let (a, b) = g.cooling[0];
    h.get_by_role_and_label(Role::Slider, "t").set_value_accesskit(0.5 * (a + b));
    h.run();
    let c = h.state().anim.cursor(&plan).expect("cursor");
    assert!(!c.cutting, "cooling tooth at t = {}", c.t_s);
    assert!(h.state().chip.outline.is_empty(), "no chip while cooling");
    // and back to a cutting tooth
    h.get_by_label("at h_max").click();
    h.run();
    assert!(!h.state().chip.outline.is_empty());
}

fn corner_harness() -> Harness<'static, App> {
    let mut h = harness();
    h.get_by_label("Corner").click();
    h.run();
    h
}

/// Step the harness until the Corner tab's background plan has arrived (at most 120 s).
fn wait_for_corner(h: &mut Harness<'_, App>) {
    let t0 = Instant::now();
    while h.state().corner.pending() && t0.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    h.run();
}

fn corner_result(h: &Harness<'_, App>) -> std::sync::Arc<panels::corner::CornerResult> {
    h.state().corner.last.clone().expect("a corner result")
}

#[test]
fn corner_tab_opens_and_shows_the_measured_engagement() {
    let h = corner_harness();
    assert_eq!(h.state().view.tab, Tab::Corner);
    assert!(h.state().corner.error.is_none(), "{:?}", h.state().corner.error);
    let r = corner_result(&h);
    assert_eq!(r.method, "variable");
    assert!(r.circles > 0, "variable circles planned");
    assert!(r.plain_max_deg > r.max_deg, "plain {} vs variable {}", r.plain_max_deg, r.max_deg);
    assert!(shows(&h, &format!("{:.1}°", r.max_deg)), "strategy max shown");
    assert!(shows(&h, &format!("{:.1}°", r.plain_max_deg)), "plain max shown");
    assert!(r.body_max_deg <= r.target_deg + 1.0, "body {} within target {} + 1°", r.body_max_deg, r.target_deg);
    assert!(shows(&h, &format!("{:.1}° / {:.1}° ({:.1}°)", r.body_max_deg, r.tip_deg, r.tip_limit_deg)));
}

#[test]
fn corner_angle_and_method_replan_and_change_the_shown_numbers() {
    use trochoplan_core::corner::CornerMethod;
    let mut h = corner_harness();
    let before = corner_result(&h);
    let replans = h.state().corner.replans;
    h.get_by_role_and_label(Role::Slider, label::CORNER_ANGLE).set_value_accesskit(60.0);
    h.run();
    let after = corner_result(&h);
    assert!(h.state().corner.replans > replans, "replanned");
    assert_eq!(after.angle_deg, 60.0);
    assert_ne!(after.plain_max_deg, before.plain_max_deg);
    assert!(shows(&h, &format!("{:.1}°", after.plain_max_deg)));

    h.get_by_label(CornerMethod::Isometric.label()).click();
    h.run();
    let iso = corner_result(&h);
    assert_eq!(iso.method, "isometric");
    assert_eq!(h.state().state.corner.method, CornerMethod::Isometric);
    assert_ne!(iso.path_length_mm, after.path_length_mm);
    assert!(shows(&h, &format!("{:.1} mm", iso.path_length_mm)), "isometric length shown");
}

#[test]
fn invalid_corner_input_shows_the_core_error_and_keeps_the_last_result() {
    let mut h = corner_harness();
    let before = corner_result(&h);
    h.state_mut().state.corner.use_step_over = true;
    h.run();
    h.state_mut().state.corner.step_over_mm = 12.0; // ≥ D = 10
    h.run();
    let err = h.state().corner.error.clone().expect("an error for a_e ≥ D");
    assert!(err.contains("step-over"), "{err}");
    assert!(shows(&h, &format!("invalid: {err}")), "error shown at the panel");
    let kept = corner_result(&h);
    assert_eq!(kept.angle_deg, before.angle_deg, "last result kept");
    h.get_by_role_and_label(Role::Slider, label::CORNER_ANGLE).set_value_accesskit(200.0);
    h.run();
    assert!(h.state().corner.error.is_some());
}

#[test]
fn pocket_mode_shows_the_rings_and_reports_a_bad_polygon() {
    let mut h = corner_harness();
    h.get_by_label("Pocket").click();
    h.run();
    // adaptive clearing is the default; the rings are the corner method's
    assert!(h.state().state.corner.pocket_adaptive);
    h.get_by_label(label::POCKET_ADAPTIVE).click();
    h.run();
    wait_for_corner(&mut h);
    assert!(h.state().corner.error.is_none(), "{:?}", h.state().corner.error);
    let p = h.state().corner.last_pocket.clone().expect("a pocket");
    assert!(!p.rings.is_empty());
    assert!(shows(&h, &format!("{} rings", p.rings.len())));
    // a self-intersecting bow tie
    h.state_mut().state.corner.polygon_text = "0,0\n60,40\n60,0\n0,40\n".to_owned();
    h.run();
    assert!(h.state().corner.error.is_some(), "bow tie rejected");
    assert!(h.state().corner.last_pocket.is_some(), "last pocket kept");
}

#[test]
fn pocket_mode_plans_the_medial_axis_strategy_for_the_whole_pocket() {
    use trochoplan_core::corner::{CornerMethod, parse_points};
    use trochoplan_core::geom::Polygon;
    use trochoplan_core::pocket::{self, PocketPlan, PocketRequest, PocketStrategy};
    let mut h = corner_harness();
    h.get_by_label("Pocket").click();
    h.run();
    h.state_mut().state.corner.pocket_adaptive = false;
    h.state_mut().state.corner.method = CornerMethod::MedialAxis;
    h.run();
    wait_for_corner(&mut h);
    assert!(h.state().corner.error.is_none(), "{:?}", h.state().corner.error);
    let p = h.state().corner.last_pocket.clone().expect("a pocket");
    let PocketPlan::MedialAxis(plan) = &p.plan else { panic!("medial-axis plan expected, got rings") };
    // The tab shows what the core plans for the same inputs.
    let i = &h.state().state.corner;
    let polygon = Polygon::new(parse_points(&i.polygon_text, "polygon").unwrap()).unwrap();
    let req = PocketRequest {
        polygon,
        tool_diameter_mm: i.tool_diameter_mm,
        step_over_mm: i.pocket_step_over_mm,
        strategy: PocketStrategy::MedialAxis,
        ..PocketRequest::default()
    };
    let PocketPlan::MedialAxis(want) = pocket::plan(&req).unwrap() else { panic!("medial-axis plan expected") };
    assert_eq!(want.path.segments(), plan.path.segments());
    assert!(shows(&h, &p.detail), "{}", p.detail);
    assert!(p.detail.contains(&format!("{} circles along the medial axis", want.circles.len())), "{}", p.detail);
}

#[test]
fn pocket_mode_opens_an_svg_outline() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("pocket.svg");
    std::fs::write(&file, r#"<svg><polygon points="0,0 50,0 50,30 0,30"/></svg>"#).unwrap();
    let app = App::new(Job::default(), None, Box::new(FakeDialogs { open: Some(file), save: None }));
    let mut h = harness_with(app);
    h.get_by_label("Corner").click();
    h.run();
    h.get_by_label("Pocket").click();
    h.run();
    h.get_by_label(label::POCKET_OPEN_OUTLINE).click();
    h.run();
    // SVG's y points down: the outline is flipped into the planner's y-up frame
    assert_eq!(h.state().state.corner.polygon_text, "0,0\n50,0\n50,-30\n0,-30\n");
    assert!(
        h.state().status.as_ref().is_some_and(|(m, err)| !err && m.contains("4 vertices")),
        "{:?}",
        h.state().status
    );
}

#[test]
fn pocket_mode_plans_adaptive_clearing() {
    use trochoplan_core::pocket::{self, PocketPlan};
    let mut h = corner_harness();
    h.get_by_label("Pocket").click();
    h.run();
    wait_for_corner(&mut h);
    // adaptive clearing is the default
    assert!(h.state().state.corner.pocket_adaptive);
    assert!(h.state().corner.error.is_none(), "{:?}", h.state().corner.error);
    let p = h.state().corner.last_pocket.clone().expect("a pocket");
    let PocketPlan::Adaptive(plan) = &p.plan else { panic!("adaptive plan expected") };
    // the tab shows what the core plans for the tab's request
    let req = h.state().state.corner.pocket_request().unwrap();
    let PocketPlan::Adaptive(want) = pocket::plan(&req).unwrap() else { panic!("adaptive plan expected") };
    assert_eq!(want.path.segments(), plan.path.segments());
    assert!(shows(&h, &p.detail), "{}", p.detail);
    assert!(p.detail.contains(&format!("{:.0} mm at depth", want.path.measurement.length_at_depth_mm)), "{}", p.detail);
}

/// The Pocket tab's open-edges field: typed into, the tab plans the pocket
/// open on that edge (entered from outside the stock); a bad list is an error naming it.
#[test]
fn pocket_mode_takes_open_edges() {
    use trochoplan_core::pocket::{Entry, PocketPlan};
    let mut h = corner_harness();
    h.get_by_label("Pocket").click();
    h.run();
    wait_for_corner(&mut h);
    h.get_by_label(label::POCKET_OPEN_EDGES).click();
    h.run();
    h.get_by_label(label::POCKET_OPEN_EDGES).type_text("0");
    h.run();
    wait_for_corner(&mut h);
    assert_eq!(h.state().state.corner.pocket_open_edges, "0");
    assert!(h.state().corner.error.is_none(), "{:?}", h.state().corner.error);
    let p = h.state().corner.last_pocket.clone().expect("a pocket");
    let PocketPlan::Adaptive(plan) = &p.plan else { panic!("adaptive plan expected") };
    assert_eq!(plan.open_edges, vec![0]);
    assert!(matches!(plan.parts[0].entry, Entry::Outside { .. }), "{:?}", plan.parts[0].entry);
    assert!(shows(&h, &p.detail) && p.detail.starts_with("outside entry"), "{}", p.detail);
    h.state_mut().state.corner.pocket_open_edges = "0, x".to_owned();
    h.run();
    let e = h.state().corner.error.clone().expect("a bad list is an error");
    assert!(e.contains("open edges"), "{e}");
}

/// Step frames until the Corner tab's acceptance table is no longer being computed.
fn wait_for_table(h: &mut Harness<'_, App>) {
    let t0 = Instant::now();
    while h.state().corner.table.running() && t0.elapsed().as_secs() < 600 {
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    h.run();
}

#[test]
fn corner_table_lists_every_angle_for_each_strategy_as_the_core_measures_it() {
    use trochoplan_core::corner::acceptance::{ANGLES_DEG, STRATEGIES, acceptance_row};
    let mut h = corner_harness();
    h.get_by_label("Acceptance table").click();
    h.step(); // the click: the table is asked for after the panels drew
    h.step();
    assert!(h.state().corner.table.running(), "measured on the worker thread");
    assert!(h.query_by_label(label::CANCEL_TABLE).is_some(), "progress with a cancel button");
    wait_for_table(&mut h);
    let table = &h.state().corner.table;
    assert!(table.complete() && table.error.is_none(), "{:?}", table.error);
    assert_eq!(table.angles.len(), 9);
    let mut per_strategy = [0usize; 3];
    for (a, &angle) in table.angles.iter().zip(&ANGLES_DEG) {
        assert_eq!(a.angle_deg, angle);
        let rows = a.rows.as_ref().expect("rows");
        for (i, (r, m)) in rows.iter().zip(&STRATEGIES).enumerate() {
            assert_eq!((r.method, r.corner_angle_deg), (*m, angle));
            per_strategy[i] += 1;
        }
        assert!(shows(&h, &format!("{angle:.0}°")), "row of {angle}° shown");
    }
    assert_eq!(per_strategy, [9, 9, 9], "9 rows per strategy");
    let all: Vec<_> = table.angles.iter().flat_map(|a| a.rows.as_ref().expect("rows").iter()).collect();
    let shown_verdicts = h.query_all_by_label("pass").count() + h.query_all_by_label("fail").count();
    assert_eq!(shown_verdicts, 27, "a verdict per strategy and angle");
    assert_eq!(h.query_all_by_label("pass").count(), all.iter().filter(|r| r.passes()).count());

    // the 90° rows are the core's, for the tab's settings, and shown as such
    let request = h.state().state.corner.request();
    let settings = request.settings().expect("valid settings");
    let rows90 = table.angles[4].rows.as_ref().expect("rows").clone();
    for (row, &m) in rows90.iter().zip(&STRATEGIES) {
        let want = acceptance_row(90.0, m, settings, request.spacing_mm).expect("core row");
        assert_eq!(*row, want, "{}", m.name());
        for text in [
            format!("{:.2}", want.body_max_deg),
            format!("{:.2}", want.tip_deg),
            format!("{:.2}", want.tip_limit_deg),
            format!("{:.1}", want.path_length_mm),
            format!("{:.1}", want.time_s),
        ] {
            assert!(shows(&h, &text), "{} at 90°: {text} shown", m.name());
        }
    }
    assert!(shows(&h, &format!("{:.2}", rows90[0].plain_max_deg)), "plain max shown");

    // an invalid input: the core's message, the last table kept, nothing recomputed
    h.state_mut().state.corner.use_step_over = true;
    h.state_mut().state.corner.step_over_mm = 12.0; // ≥ D = 10
    h.run();
    let err = h.state().corner.table.error.clone().expect("invalid step-over");
    assert!(err.contains("step-over"), "{err}");
    assert!(shows(&h, &format!("invalid: {err}")));
    assert!(h.state().corner.table.complete() && !h.state().corner.table.running(), "last table kept");
}

#[test]
fn corner_export_previews_the_core_program_saves_it_and_reports_a_bad_depth() {
    use trochoplan_core::nc::{CutSetup, Dialect, NcOptions, corner_program, pocket_program};
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("corner.nc");
    let mut h = harness_saving_to(&file);
    h.get_by_label("Corner").click();
    h.run();
    assert!(h.query_by_label(label::SAVE_PROGRAM_AS).is_none(), "export closed by default");
    h.get_by_label(label::NC_EXPORT).click();
    h.run();
    assert!(h.state().state.corner_nc.open);
    let r = corner_result(&h);
    // the CLI's defaults give the CLI's program (`trochoplan corner --export`)
    let want = corner_program(
        &r.report.plan,
        r.report.settings(),
        r.report.angle_deg,
        CutSetup::default(),
        &NcOptions::default(),
    )
    .expect("core program");
    assert_eq!(h.state().corner_nc.view().expect("program").text, want.text);
    assert!(shows(&h, "(TrochoPlan corner)"), "preview shows the program");
    let generated = h.state().corner_nc.generated;
    h.run();
    assert_eq!(h.state().corner_nc.generated, generated, "not regenerated per frame");

    h.get_by_label("Fanuc-style ISO").click();
    h.get_by_label(label::G1_CHORDS_ONLY).click();
    h.run();
    let fanuc = h.state().corner_nc.view().expect("program").text.clone();
    let opts = NcOptions { dialect: Dialect::Fanuc, linear_segments: true, ..NcOptions::default() };
    let want = corner_program(&r.report.plan, r.report.settings(), r.report.angle_deg, CutSetup::default(), &opts)
        .expect("core program");
    assert_eq!(fanuc, want.text);
    assert!(fanuc.starts_with("%\nO1000\n") && !fanuc.contains("\nG3"), "Fanuc, chords only");

    // a bad depth: the core's message in the tab, no save button, no panic
    h.get_by_role_and_label(Role::SpinButton, label::DEPTH_BELOW_Z0).set_value_accesskit(-1.0);
    h.run();
    assert_eq!(h.state().state.corner_nc.depth_mm, -1.0);
    let bad = CutSetup { depth_mm: -1.0, ..CutSetup::default() };
    let msg = corner_program(&r.report.plan, r.report.settings(), r.report.angle_deg, bad, &opts)
        .expect_err("depth")
        .to_string();
    assert!(msg.contains("depth"), "{msg}");
    assert!(shows(&h, &format!("Cannot write the program: {msg}")), "error shown: {msg}");
    assert!(h.query_by_label(label::SAVE_PROGRAM_AS).is_none(), "nothing to save");

    h.get_by_role_and_label(Role::SpinButton, label::DEPTH_BELOW_Z0).set_value_accesskit(3.0);
    h.run();
    let preview = h.state().corner_nc.view().expect("program").text.clone();
    assert!(preview.contains("\nG1 Z-3.000 F600.0\n"), "depth 3 mm: {preview}");
    h.get_by_label(label::SAVE_PROGRAM_AS).click();
    h.run();
    assert_eq!(std::fs::read_to_string(&file).expect("saved"), preview, "the file holds the previewed text");
    let (status, is_err) = h.state().status.clone().expect("status");
    assert!(!is_err && status.starts_with("exported"), "{status}");

    // pocket mode exports the whole pocket (adaptive by default)
    h.get_by_label("Pocket").click();
    h.run();
    wait_for_corner(&mut h);
    let p = h.state().corner.last_pocket.clone().expect("a pocket");
    let cut = CutSetup { depth_mm: 3.0, ..CutSetup::default() };
    assert!(matches!(p.plan, trochoplan_core::pocket::PocketPlan::Adaptive(_)), "adaptive pocket expected");
    let want = pocket_program(&p.plan, cut, &opts).expect("core pocket program");
    let preview = h.state().corner_nc.view().expect("program").text.clone();
    assert_eq!(preview, want.text);
    h.get_by_label(label::SAVE_PROGRAM_AS).click();
    h.run();
    assert_eq!(std::fs::read_to_string(&file).expect("saved"), preview);
}

/// F_R,max and PI without Ra are among the derived values; the Forces tab draws;
/// the helix slider and the material picker replan with new forces (a lower helix angle puts
/// fewer edges in the cut at once: a higher peak; titanium's set has lower cutting but higher
/// axial coefficients than P20's).
#[test]
fn forces_tab_and_the_material_inputs_replan_the_forces() {
    let mut h = harness();
    let m = metrics(&h);
    assert!(shows(&h, &format!("{:.1} N", m.force_resultant_max_n)), "F_R,max shown");
    assert!(shows(&h, &format!("{:.3}", m.performance_index_without_ra)), "PI without Ra shown");
    h.get_by_label("Forces").click();
    h.run();
    assert_eq!(h.state().view.tab, Tab::Forces);
    h.get_by_role_and_label(Role::Slider, Param::HelixAngle.label()).set_value_accesskit(10.0);
    h.run();
    let low_helix = metrics(&h);
    assert!((h.state().state.job.helix_angle - 10.0).abs() < 1e-9);
    assert!(
        low_helix.force_resultant_max_n > m.force_resultant_max_n,
        "{} vs {}",
        low_helix.force_resultant_max_n,
        m.force_resultant_max_n
    );
    let lib = trochoplan_core::material::Library::builtin();
    h.get_by_role_and_label(Role::ComboBox, Param::Material.label()).click();
    h.run_steps(15);
    h.get_by_label(lib.get("ti-6al-4v").expect("ti").label.as_str()).click();
    h.run_steps(15);
    assert_eq!(h.state().state.job.material, "ti-6al-4v");
    assert_ne!(metrics(&h).force_resultant_max_n, low_helix.force_resultant_max_n);
}

#[test]
fn machine_tab_shows_the_feed_and_the_optimiser_runs_in_the_background_and_loads_a_job() {
    use trochoplan_core::machine::MachineChoice;
    let mut h = harness();
    // The job's machine (the picker sits below the fold of the parameter panel at this
    // size); the feed plot reports its real cycle time.
    h.state_mut().state.job = Job {
        feed: 3000.0,
        rpm: 10000.0,
        machine: Some(MachineChoice::Preset("hobby-router".into())),
        ..Job::default()
    };
    h.run();
    h.get_by_label("Machine & optimise").click();
    h.run();
    let m = metrics(&h);
    assert!(m.t_cycle_real_s > m.t_cycle_s);
    let line = format!("real cycle {:.3} s vs programmed {:.3} s", m.t_cycle_real_s, m.t_cycle_s);
    assert!(h.query_all_by_label_contains(&line).next().is_some(), "{line}");
    // The optimiser on the paper's slot (back to its feed on the vmc).
    h.state_mut().state.job = Job { machine: Some(MachineChoice::Preset("vmc".into())), ..Job::default() };
    h.run();
    h.get_by_label("Optimise").click();
    h.step();
    let t0 = Instant::now();
    while h.state().optimise.as_ref().is_some_and(|r| r.running()) && t0.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    h.run();
    let best = h.state().optimise.as_ref().and_then(|r| r.best_job()).expect("a best job");
    h.get_by_label("Load best").click();
    h.run();
    assert_eq!(h.state().state.job, best);
    assert!(metrics(&h).h_max_mm <= 0.075 + 1e-9);
    // Cancel stops a run.
    h.get_by_label("Optimise").click();
    h.step();
    h.step();
    h.get_by_label("Cancel").click();
    h.step();
    assert!(h.state().optimise.as_ref().is_some_and(|r| !r.running() && r.cancelled));
}

/// The Optimise panel's minimum cooling share (`optimize --min-cooling`): the
/// checkbox turns the limit on, and the best job it loads keeps a tooth out of the cut at
/// least that share of the cycle. 0.49 binds: the optimum without it reads 0.47 and the best
/// reachable is 0.504 (`trochoplan optimize … --min-cooling 0.6` names it).
#[test]
fn optimise_panel_limits_the_cooling_share() {
    use trochoplan_core::machine::MachineChoice;
    let mut h = harness();
    h.state_mut().state.job = Job { machine: Some(MachineChoice::Preset("vmc".into())), ..Job::default() };
    h.run();
    h.get_by_label("Machine & optimise").click();
    h.run();
    assert!(!h.state().state.optimise.limit_cooling);
    h.get_by_label("cooling share >=").click();
    h.run();
    assert!(h.state().state.optimise.limit_cooling);
    h.state_mut().state.optimise.min_cooling_share = 0.49;
    h.run();
    h.get_by_label("Optimise").click();
    h.step();
    let t0 = Instant::now();
    while h.state().optimise.as_ref().is_some_and(|r| r.running()) && t0.elapsed().as_secs() < 300 {
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    h.run();
    let best = h.state().optimise.as_ref().and_then(|r| r.best_job()).expect("a best job");
    h.get_by_label("Load best").click();
    // The loaded job is planned on the planner's worker; the longer result line re-lays the grid.
    let t0 = Instant::now();
    while h.state().planner.last.as_ref().is_none_or(|l| l.plan.job.feed != best.feed || l.plan.job.step != best.step)
        && t0.elapsed().as_secs() < 60
    {
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    assert_eq!(h.state().state.job, best);
    let m = metrics(&h);
    assert!(m.t_cooling_s / m.t_cycle_s >= 0.49 - 1e-9, "{} / {}", m.t_cooling_s, m.t_cycle_s);
    assert!(m.h_max_mm <= 0.075 + 1e-9);
}
