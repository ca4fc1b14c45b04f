//! The slot job's tabs: parameters, metrics, Compare, undo and files, Sweep, Export NC and the
//! teaching animation.

use super::*;

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

/// egui frame time (UI + tessellation, no rasteriser) while a value changes every frame as it
/// does while a slider is dragged, at 60 frames per second with the planning thread running:
/// the step s on the Plots tab and on the Forces tab (every plan includes the force series and
/// the imprints; the force and imprint plots drawn every frame), and the step-over a_e on the
/// Pocket tab (adaptive clearing of the default 60 × 40 pocket planned and measured on its own
/// thread, the last pocket drawn every frame).
/// Run: `cargo test --release -p trochoplan frame_time -- --ignored --nocapture`.
#[test]
#[ignore = "measurement, prints frame-time statistics"]
fn frame_time_while_dragging_a_slider() {
    for tab in [Tab::Plots, Tab::Forces, Tab::Pocket] {
        let ctx = egui::Context::default();
        let repaint = ctx.clone();
        let dialogs = Box::new(FakeDialogs { open: None, save: None });
        let mut app =
            App::with_planner(Job::default(), None, dialogs, Planner::threaded(move || repaint.request_repaint()));
        let repaint = ctx.clone();
        app.pocket = crate::app::panels::pocket::PocketView::threaded(move || repaint.request_repaint());
        app.view.tab = tab;
        let mut ms = Vec::new();
        for i in 0..300 {
            let drag = f64::from(i % 150) / 150.0;
            if tab == Tab::Pocket {
                app.state.pocket.step_over_mm = 1.2 + 0.6 * drag;
            } else {
                app.state.job.step = 1.0 - 0.5 * drag;
            }
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
        let replans = if tab == Tab::Pocket { app.pocket.replans as u64 } else { app.planner.replans };
        println!(
            "{tab:?} tab, frame (UI + tessellation) over {} frames: median {:.2} ms, p90 {:.2} ms, p99 {:.2} ms, max {:.2} ms; {replans} replans",
            warm.len(),
            q(0.5),
            q(0.9),
            q(0.99),
            q(1.0),
        );
        // a slot plan takes a few ms, a measured pocket tens of ms: both replan while dragging
        let least = if tab == Tab::Pocket { 10 } else { 100 };
        assert!(replans > least, "{tab:?}: replanned while dragging: {replans}");
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
    // the panel laid out again (the preview back) before the click finds the box where it is
    h.run();
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
