//! The Corner tab: one corner, its acceptance table and its NC export.

use super::*;

fn corner_harness() -> Harness<'static, App> {
    let mut h = harness();
    h.get_by_label("Corner").click();
    h.run();
    h
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
    assert_eq!(r.summary.method, "variable");
    assert!(!r.summary.circles.is_empty(), "variable circles planned");
    assert!(
        r.summary.plain_max_engagement_deg > r.summary.max_engagement_deg,
        "plain {} vs variable {}",
        r.summary.plain_max_engagement_deg,
        r.summary.max_engagement_deg
    );
    assert!(shows(&h, &format!("{:.1}°", r.summary.max_engagement_deg)), "strategy max shown");
    assert!(shows(&h, &format!("{:.1}°", r.summary.plain_max_engagement_deg)), "plain max shown");
    assert!(
        r.body_max_deg <= r.summary.target_deg + 1.0,
        "body {} within target {} + 1°",
        r.body_max_deg,
        r.summary.target_deg
    );
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
    assert_eq!(after.summary.corner_angle_deg, 60.0);
    assert_ne!(after.summary.plain_max_engagement_deg, before.summary.plain_max_engagement_deg);
    assert!(shows(&h, &format!("{:.1}°", after.summary.plain_max_engagement_deg)));

    h.get_by_label(CornerMethod::Isometric.label()).click();
    h.run();
    let iso = corner_result(&h);
    assert_eq!(iso.summary.method, "isometric");
    assert_eq!(h.state().state.corner.method, CornerMethod::Isometric);
    assert_ne!(iso.summary.path_length_mm, after.summary.path_length_mm);
    assert!(shows(&h, &format!("{:.1} mm", iso.summary.path_length_mm)), "isometric length shown");
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
    assert_eq!(kept.summary.corner_angle_deg, before.summary.corner_angle_deg, "last result kept");
    h.get_by_role_and_label(Role::Slider, label::CORNER_ANGLE).set_value_accesskit(200.0);
    h.run();
    assert!(h.state().corner.error.is_some());
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
    use trochoplan_core::nc::{CutSetup, Dialect, NcOptions, corner_program};
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
}
