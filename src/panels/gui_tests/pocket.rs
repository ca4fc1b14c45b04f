//! The Pocket tab: outline editor and outline files, methods, open edges, NC export, and the
//! pocket of states stored before the tab.

use super::*;
use trochoplan_core::corner::CornerMethod;
use trochoplan_core::pocket::{PocketPlan, PocketStrategy};

/// The window on the Pocket tab, its dialogs answering `open` and `save`.
fn pocket_harness_with(open: Option<PathBuf>, save: Option<PathBuf>) -> Harness<'static, App> {
    let mut h = harness_with(App::new(Job::default(), None, Box::new(FakeDialogs { open, save })));
    h.get_by_label("Pocket").click();
    h.run();
    assert_eq!(h.state().view.tab, Tab::Pocket);
    wait_for_pocket(&mut h);
    h
}

fn pocket_harness() -> Harness<'static, App> {
    pocket_harness_with(None, None)
}

/// Step the harness until the Pocket tab's background plan has arrived (at most 120 s).
fn wait_for_pocket(h: &mut Harness<'_, App>) {
    let t0 = Instant::now();
    while h.state().pocket.pending() && t0.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    h.run();
}

fn pocket_result(h: &Harness<'_, App>) -> std::sync::Arc<panels::pocket::PocketResult> {
    h.state().pocket.last.clone().expect("a pocket")
}

#[test]
fn pocket_tab_shows_the_rings_and_reports_a_bad_polygon() {
    let mut h = pocket_harness();
    // adaptive clearing is the default; the rings are a corner method's
    assert_eq!(h.state().state.pocket.strategy, PocketStrategy::Adaptive);
    h.get_by_label(PocketStrategy::Rings(CornerMethod::Variable).label()).click();
    h.run();
    wait_for_pocket(&mut h);
    assert!(h.state().pocket.error.is_none(), "{:?}", h.state().pocket.error);
    let p = pocket_result(&h);
    let n = p.report.rings().len();
    assert!(n > 0);
    assert!(shows(&h, &if n == 1 { "1 ring".to_owned() } else { format!("{n} rings") }), "{n} rings");
    assert!(shows(&h, "offset"), "the ring table");
    // a self-intersecting bow tie
    h.state_mut().state.pocket.polygon_text = "0,0\n60,40\n60,0\n0,40\n".to_owned();
    h.run();
    assert!(h.state().pocket.error.is_some(), "bow tie rejected");
    assert!(h.state().pocket.last.is_some(), "last pocket kept");
}

#[test]
fn pocket_tab_plans_the_medial_axis_strategy_for_the_whole_pocket() {
    use trochoplan_core::engagement::parse_points;
    use trochoplan_core::geom::Polygon;
    use trochoplan_core::pocket::{self, PocketRequest};
    let mut h = pocket_harness();
    h.state_mut().state.pocket.strategy = PocketStrategy::MedialAxis;
    h.run();
    wait_for_pocket(&mut h);
    assert!(h.state().pocket.error.is_none(), "{:?}", h.state().pocket.error);
    let p = pocket_result(&h);
    let PocketPlan::MedialAxis(plan) = &p.plan else { panic!("medial-axis plan expected, got rings") };
    // The tab shows what the core plans for the same inputs.
    let i = &h.state().state.pocket;
    let polygon = Polygon::new(parse_points(&i.polygon_text, "polygon").unwrap()).unwrap();
    let req = PocketRequest {
        polygon,
        tool_diameter_mm: i.tool_diameter_mm,
        step_over_mm: i.step_over_mm,
        strategy: PocketStrategy::MedialAxis,
        ..PocketRequest::default()
    };
    let PocketPlan::MedialAxis(want) = pocket::plan(&req).unwrap() else { panic!("medial-axis plan expected") };
    assert_eq!(want.path.segments(), plan.path.segments());
    assert!(shows(&h, &p.report.detail()), "{}", p.report.detail());
    assert!(
        p.report.detail().contains(&format!("{} circles along the medial axis", want.circles.len())),
        "{}",
        p.report.detail()
    );
}

#[test]
fn pocket_tab_opens_an_svg_outline() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("pocket.svg");
    std::fs::write(&file, r#"<svg><polygon points="0,0 50,0 50,30 0,30"/></svg>"#).unwrap();
    let mut h = pocket_harness_with(Some(file), None);
    h.get_by_label(label::POCKET_OPEN_OUTLINE).click();
    h.run();
    // SVG's y points down: the outline is flipped into the planner's y-up frame
    assert_eq!(h.state().state.pocket.polygon_text, "0,0\n50,0\n50,-30\n0,-30\n");
    assert!(
        h.state().status.as_ref().is_some_and(|(m, err)| !err && m.contains("4 vertices")),
        "{:?}",
        h.state().status
    );
}

#[test]
fn pocket_tab_plans_adaptive_clearing() {
    use trochoplan_core::pocket;
    let mut h = pocket_harness();
    wait_for_pocket(&mut h);
    // adaptive clearing is the default
    assert_eq!(h.state().state.pocket.strategy, PocketStrategy::Adaptive);
    assert!(h.state().pocket.error.is_none(), "{:?}", h.state().pocket.error);
    let p = pocket_result(&h);
    let PocketPlan::Adaptive(plan) = &p.plan else { panic!("adaptive plan expected") };
    // the tab shows what the core plans for the tab's request
    let req = h.state().state.pocket.request().unwrap();
    let PocketPlan::Adaptive(want) = pocket::plan(&req).unwrap() else { panic!("adaptive plan expected") };
    assert_eq!(want.path.segments(), plan.path.segments());
    assert!(shows(&h, &p.report.detail()), "{}", p.report.detail());
    assert!(
        p.report.detail().contains(&format!("{:.0} mm at depth", want.path.measurement.length_at_depth_mm)),
        "{}",
        p.report.detail()
    );
    // one pass, so no ring table: its moves by kind, each row as the core's report of the plan
    let rows = trochoplan_core::report::pocket(&req, &PocketPlan::Adaptive(want)).unwrap().by_kind().to_vec();
    assert!(rows.len() >= 4, "helix entry, rings, corners, finish at least: {rows:?}");
    for row in &rows {
        assert!(shows(&h, panels::pocket_numbers::kind_label(row.kind)), "{:?} row", row.kind);
        assert!(shows(&h, &format!("{:.1} mm", row.length_mm)), "{:?} length", row.kind);
    }
    assert!(!shows(&h, "offset"), "no ring table for adaptive clearing");
}

/// The Pocket tab's open-edges field: typed into, the tab plans the pocket
/// open on that edge (entered from outside the stock); a bad list is an error naming it.
#[test]
fn pocket_tab_takes_open_edges() {
    use trochoplan_core::toolpath::Entry;
    let mut h = pocket_harness();
    wait_for_pocket(&mut h);
    h.get_by_label(label::POCKET_OPEN_EDGES).click();
    h.run();
    h.get_by_label(label::POCKET_OPEN_EDGES).type_text("0");
    h.run();
    wait_for_pocket(&mut h);
    assert_eq!(h.state().state.pocket.open_edges, "0");
    assert!(h.state().pocket.error.is_none(), "{:?}", h.state().pocket.error);
    let p = pocket_result(&h);
    let PocketPlan::Adaptive(plan) = &p.plan else { panic!("adaptive plan expected") };
    assert_eq!(plan.open_edges, vec![0]);
    assert!(matches!(plan.parts[0].entry, Entry::Outside { .. }), "{:?}", plan.parts[0].entry);
    assert!(shows(&h, &p.report.detail()) && p.report.detail().starts_with("outside entry"), "{}", p.report.detail());
    h.state_mut().state.pocket.open_edges = "0, x".to_owned();
    h.run();
    let e = h.state().pocket.error.clone().expect("a bad list is an error");
    assert!(e.contains("open edges"), "{e}");
}

/// The Pocket tab's NC export writes the core's program of the shown pocket (`trochoplan
/// pocket --export`'s call) with the tab's own settings, and saves the previewed text.
#[test]
fn pocket_export_previews_the_core_program_and_saves_it() {
    use trochoplan_core::nc::{CutSetup, Dialect, NcOptions, pocket_program};
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("pocket.nc");
    let mut h = pocket_harness_with(None, Some(file.clone()));
    assert!(h.query_by_label(label::SAVE_PROGRAM_AS).is_none(), "export closed by default");
    h.get_by_label(label::NC_EXPORT).click();
    h.run();
    assert!(h.state().state.pocket_nc.open && !h.state().state.corner_nc.open, "the tab's own settings");
    let p = pocket_result(&h);
    assert!(matches!(p.plan, PocketPlan::Adaptive(_)), "adaptive pocket expected");
    let want = pocket_program(&p.plan, CutSetup::default(), &NcOptions::default()).expect("core program");
    assert_eq!(h.state().pocket_nc.view().expect("program").text, want.text, "the CLI's defaults");
    let first_line = want.text.lines().find(|l| l.starts_with('(')).expect("a comment line");
    assert!(shows(&h, first_line), "preview shows the program: {first_line}");

    h.get_by_label("Fanuc-style ISO").click();
    h.get_by_label(label::G1_CHORDS_ONLY).click();
    h.get_by_role_and_label(Role::SpinButton, label::DEPTH_BELOW_Z0).set_value_accesskit(3.0);
    h.run();
    let opts = NcOptions { dialect: Dialect::Fanuc, linear_segments: true, ..NcOptions::default() };
    let cut = CutSetup { depth_mm: 3.0, ..CutSetup::default() };
    let want = pocket_program(&p.plan, cut, &opts).expect("core pocket program");
    let preview = h.state().pocket_nc.view().expect("program").text.clone();
    assert_eq!(preview, want.text);
    assert_eq!(h.state().state.corner_nc, panels::corner_nc::CornerNcSettings::default(), "Corner tab untouched");
    h.get_by_label(label::SAVE_PROGRAM_AS).click();
    h.run();
    assert_eq!(std::fs::read_to_string(&file).expect("saved"), preview);
    let (status, is_err) = h.state().status.clone().expect("status");
    assert!(!is_err && status.starts_with("exported"), "{status}");
}

/// The strategy row: adaptive clearing is chosen at first and no other strategy is shown
/// chosen; a click on another plans with it and moves the selection there.
#[test]
fn pocket_strategy_row_shows_and_sets_the_strategy() {
    use egui_kittest::kittest::NodeT;
    let mut h = pocket_harness();
    let selected = |h: &Harness<'_, App>, s: PocketStrategy| {
        h.get_by_label(s.label()).accesskit_node().toggled() == Some(egui::accesskit::Toggled::True)
    };
    let only = |h: &Harness<'_, App>, chosen: PocketStrategy| {
        PocketStrategy::ALL.iter().all(|&s| selected(h, s) == (s == chosen))
    };
    assert!(only(&h, PocketStrategy::Adaptive), "adaptive alone shown chosen");
    let iso = PocketStrategy::Rings(CornerMethod::Isometric);
    h.get_by_label(iso.label()).click();
    h.run();
    wait_for_pocket(&mut h);
    assert_eq!(h.state().state.pocket.strategy, iso);
    assert!(only(&h, iso), "isometric alone shown chosen");
    assert_eq!(pocket_result(&h).plan.strategy(), iso);
}

/// Set the spin button labelled `label` to `v`.
fn set_number(h: &mut Harness<'_, App>, label: &str, v: f64) {
    h.get_by_role_and_label(Role::SpinButton, label).set_value_accesskit(v);
    h.run();
}

/// Tick the checkbox of the optional field labelled `label`.
fn tick(h: &mut Harness<'_, App>, label: &str) {
    h.get_by_role_and_label(Role::CheckBox, label).click();
    h.run();
}

/// Every field of the Pocket tab reaches the core's request: set through the window, the plan
/// shown is the one `pocket::plan` makes of the request built here as `trochoplan pocket`
/// builds it from the same flags (`--step-over 2 --target-engagement 55 --peak-limit 70
/// --helix-radius 3 --ramp-angle 3 --finish-stock 0.3 --depth 4 --direction conventional
/// --machine vmc`, the job's tool and cutting data); the real time is the core's
/// `toolpath_time` of that plan on vmc, shown as h:min:s.
#[test]
fn pocket_fields_reach_the_request() {
    use panels::pocket_inputs as pi;
    use trochoplan_core::job::Direction;
    use trochoplan_core::machine::{CutHeights, Machine, toolpath_time};
    use trochoplan_core::pocket::{self, AdaptiveOptions, PaceOptions, PocketRequest};
    let mut h = pocket_harness();
    // a_e = 2 on D = 10: φ* = arccos(1 − 2/5) = 53.1°, so a target of 55° is allowed
    set_number(&mut h, pi::STEP_OVER, 2.0);
    tick(&mut h, pi::TARGET);
    set_number(&mut h, pi::TARGET, 55.0);
    tick(&mut h, pi::PEAK_LIMIT);
    set_number(&mut h, pi::PEAK_LIMIT, 70.0);
    tick(&mut h, pi::HELIX_RADIUS);
    set_number(&mut h, pi::HELIX_RADIUS, 3.0);
    set_number(&mut h, pi::RAMP_ANGLE, 3.0);
    set_number(&mut h, pi::FINISH_STOCK, 0.3);
    set_number(&mut h, pi::DEPTH, 4.0);
    h.get_by_label("conventional").click();
    h.run();
    h.get_by_role_and_label(Role::ComboBox, pi::MACHINE).click();
    h.run();
    h.get_by_label("vmc").click();
    h.run();
    wait_for_pocket(&mut h);
    assert!(h.state().pocket.error.is_none(), "{:?}", h.state().pocket.error);
    assert_eq!(h.state().state.pocket_nc.depth_mm, 4.0, "the program's depth is the pocket's");

    let job = Job::default();
    let vmc = Machine::preset("vmc").unwrap();
    let req = PocketRequest {
        tool_diameter_mm: job.tool_diameter,
        step_over_mm: 2.0,
        feed_mm_per_min: job.feed,
        adaptive: AdaptiveOptions {
            helix_radius_mm: Some(3.0),
            ramp_deg: 3.0,
            finish_stock_mm: 0.3,
            direction: Direction::Conventional,
            depth_mm: 4.0,
            target_deg: Some(55.0),
            ..AdaptiveOptions::default()
        },
        pace: PaceOptions {
            teeth: job.teeth,
            rpm: job.rpm,
            max_feed_mm_per_min: Some(vmc.max_speed_mm_per_s() * 60.0),
            block_time_s: vmc.block_time,
            machine: Some(vmc.clone()),
            ..PaceOptions::default()
        },
        peak_limit_deg: Some(70.0),
        ..PocketRequest::default()
    };
    assert_eq!(h.state().state.pocket.request().unwrap(), req, "the tab's request");
    let want = pocket::plan(&req).unwrap();
    let p = pocket_result(&h);
    assert_eq!(p.plan, want, "the plan shown is the core's plan of the request");
    let report = trochoplan_core::report::pocket(&req, &want).unwrap();
    assert_eq!(panels::pocket_numbers::target_deg(&report), Some(55.0));
    let heights = CutHeights { depth_mm: 4.0, safe_z_mm: job.program.retract_height_mm() };
    let t = toolpath_time(want.toolpath(), heights, job.feed, &vmc).unwrap();
    let (name, shown) = p.real_time.clone().expect("a machine");
    assert_eq!((name.as_str(), shown.unwrap().total_s), ("vmc", t.total_s));
    let line = panels::pocket_numbers::lines(&p, &h.state().state.pocket)
        .into_iter()
        .map(|(l, _)| l)
        .find(|l| l.starts_with("real time"))
        .expect("a real-time line");
    assert!(line.contains(&panels::pocket_numbers::hms(t.total_s)) && shows(&h, &line), "{line}");
}

/// The method row: whichever method is clicked is the one shown selected, alone, and the plan
/// shown is of it (the trochoidal slot on a narrow pocket, the others on the default
/// rectangle); a pocket too narrow for adaptive clearing's helix is planned as a slot and the
/// tab says so.
#[test]
fn pocket_method_row_shows_the_planned_method() {
    use egui_kittest::kittest::NodeT;
    let mut h = pocket_harness();
    let selected = |h: &Harness<'_, App>, s: PocketStrategy| {
        h.get_by_label(s.label()).accesskit_node().toggled() == Some(egui::accesskit::Toggled::True)
    };
    let narrow = "0,0\n60,0\n60,14\n0,14\n";
    for chosen in PocketStrategy::ALL {
        if chosen == PocketStrategy::Slot {
            h.state_mut().state.pocket.polygon_text = narrow.to_owned();
        } else {
            h.state_mut().state.pocket.polygon_text = panels::pocket::PocketInputs::default().polygon_text;
        }
        h.get_by_label(chosen.label()).click();
        h.run();
        wait_for_pocket(&mut h);
        assert!(h.state().pocket.error.is_none(), "{}: {:?}", chosen.label(), h.state().pocket.error);
        for s in PocketStrategy::ALL {
            assert_eq!(
                selected(&h, s),
                s == chosen,
                "{} shown {} while {} is chosen",
                s.label(),
                selected(&h, s),
                chosen.label()
            );
        }
        assert_eq!(pocket_result(&h).plan.strategy(), chosen, "the plan shown is of the chosen method");
        assert!(!h.query_all_by_label_contains("Planned as").any(|_| true), "no note for {}", chosen.label());
    }
    // 60 × 14 mm with D = 10: the default helix (0.375·D = 3.75 mm, bore 17.5 mm) does not fit
    h.get_by_label(PocketStrategy::Adaptive.label()).click();
    h.state_mut().state.pocket.polygon_text = narrow.to_owned();
    h.run();
    wait_for_pocket(&mut h);
    // the helix's bore, even at 0.25·D (2 × 2.5 + 10 = 15 mm), is wider than the 14 mm pocket
    assert_eq!(pocket_result(&h).plan.strategy(), PocketStrategy::Slot);
    assert!(selected(&h, PocketStrategy::Adaptive), "the chosen method stays selected");
    assert!(h.query_all_by_label_contains("Planned as trochoidal slot").next().is_some(), "the note says why");
}

/// The vertex editor keeps what is typed while the message line above it changes: an outline
/// typed line by line is invalid (a message), then valid (no message), and every character
/// typed is in the editor.
#[test]
fn pocket_editor_keeps_the_text_while_the_message_changes() {
    let mut h = pocket_harness();
    h.state_mut().state.pocket.polygon_text.clear();
    h.run();
    h.get_by_label(label::POCKET_VERTICES).click();
    h.run();
    let mut typed = String::new();
    let mut errors = Vec::new();
    for chunk in ["0,0\n", "50,0\n", "50,30\n", "0,30\n", "# a comment\n"] {
        h.get_by_label(label::POCKET_VERTICES).type_text(chunk);
        h.run();
        wait_for_pocket(&mut h);
        typed.push_str(chunk);
        assert_eq!(h.state().state.pocket.polygon_text, typed, "the editor kept every character");
        errors.push(h.state().pocket.error.is_some());
    }
    assert_eq!(errors, [true, true, false, false, false], "the message line changed while typing");
    let p = pocket_result(&h);
    assert_eq!(p.boundary.len(), 5, "the typed rectangle is planned: {:?}", p.boundary);
}

/// The program's back-plot: the NC program of the shown plan, read back by the core's
/// back-plot, is what the plot draws over the planned path; an inch program reads back in mm.
#[test]
fn pocket_draws_the_program_read_back() {
    use trochoplan_core::nc::{Dialect, backplot};
    let mut h = pocket_harness();
    assert!(h.state().state.pocket.show_program, "shown by default");
    let text = h.state().pocket_nc.view().expect("a program").text.clone();
    let want: Vec<[f64; 2]> = backplot(&text, Dialect::LinuxCnc, panels::pocket_plot::DRAW_CHORD_TOLERANCE_MM)
        .unwrap()
        .iter()
        .map(|p| [p.x, p.y])
        .collect();
    let shown = panels::pocket_plot::shown_backplot(&h.ctx).expect("the program drawn");
    assert_eq!(shown.as_ref().as_ref().unwrap(), &want);
    // the program ends where the plan ends (its last move in the plane)
    let p = pocket_result(&h);
    let (a, b) = (want.last().unwrap(), p.path.last().unwrap());
    assert!((a[0] - b[0]).hypot(a[1] - b[1]) < 0.01, "program ends at {a:?}, plan at {b:?}");
    // an inch program (G20) is read back in mm
    h.state_mut().state.job.program.units = trochoplan_core::frame::Units::Inch;
    h.run();
    h.run();
    let text = h.state().pocket_nc.view().expect("a program").text.clone();
    assert!(text.contains("G20"), "an inch program");
    let inch: Vec<[f64; 2]> = backplot(&text, Dialect::LinuxCnc, panels::pocket_plot::DRAW_CHORD_TOLERANCE_MM)
        .unwrap()
        .iter()
        .map(|p| [p.x, p.y])
        .collect();
    let shown = panels::pocket_plot::shown_backplot(&h.ctx).expect("the program drawn");
    assert_eq!(shown.as_ref().as_ref().unwrap(), &inch);
    let last = inch.last().unwrap();
    assert!((last[0] - b[0]).hypot(last[1] - b[1]) < 0.05, "inch program ends at {last:?} mm, plan at {b:?}");
}

/// Planning on the worker thread: while the plan is being made the tab shows a spinner and
/// "planning…" with the seconds spent, and the last plan stays on screen; when the answer
/// arrives the line goes and the new plan is shown.
#[test]
fn pocket_shows_planning_until_the_threaded_plan_arrives() {
    let mut h = pocket_harness();
    h.state_mut().pocket = panels::pocket::PocketView::threaded(|| {});
    h.step();
    wait_for_pocket(&mut h);
    let first = pocket_result(&h);
    h.state_mut().state.pocket.strategy = PocketStrategy::MedialAxis;
    h.step();
    let mut seen = h.state().pocket.pending() && h.query_all_by_label_contains("planning…").next().is_some();
    let t0 = Instant::now();
    while h.state().pocket.pending() && t0.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.step();
        if h.state().pocket.pending() {
            assert!(
                h.state().pocket.last.as_ref().is_some_and(|p| std::sync::Arc::ptr_eq(p, &first)),
                "the last plan stays"
            );
            seen |= h.query_all_by_label_contains("planning…").next().is_some();
        }
    }
    h.step();
    assert!(seen, "the planning line was shown while the plan was made");
    assert!(!h.state().pocket.pending(), "answered within 120 s");
    assert_eq!(pocket_result(&h).plan.strategy(), PocketStrategy::MedialAxis);
    assert!(h.query_all_by_label_contains("planning…").next().is_none(), "the line goes with the answer");
}

/// An outline file with an island (a square inside the boundary): the editor holds the
/// boundary and, after an empty line, the island; the plan is the core's for that boundary and
/// island (adaptive clearing round it), and the island is drawn.
#[test]
fn pocket_tab_opens_and_plans_an_outline_with_an_island() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("island.txt");
    std::fs::write(&file, "0,0\n60,0\n60,40\n0,40\n\n25,15\n35,15\n35,25\n25,25\n").unwrap();
    let mut h = pocket_harness_with(Some(file), None);
    h.get_by_label(label::POCKET_OPEN_OUTLINE).click();
    h.run();
    assert_eq!(h.state().state.pocket.polygon_text, "0,0\n60,0\n60,40\n0,40\n\n25,15\n35,15\n35,25\n25,25\n");
    assert!(h.state().status.as_ref().is_some_and(|(m, _)| m.contains("1 island")), "{:?}", h.state().status);
    wait_for_pocket(&mut h);
    assert!(h.state().pocket.error.is_none(), "{:?}", h.state().pocket.error);
    let r = pocket_result(&h);
    assert_eq!(r.islands, vec![vec![[25.0, 15.0], [35.0, 15.0], [35.0, 25.0], [25.0, 25.0], [25.0, 15.0]]]);
    let req = h.state().state.pocket.request().unwrap();
    assert_eq!(req.islands.len(), 1);
    let core = trochoplan_core::pocket::plan(&req).unwrap();
    assert_eq!(r.plan.path().segments(), core.path().segments());
}
