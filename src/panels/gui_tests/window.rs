//! The window: the tab list, and the state persisted between sessions (earlier records too).

use super::*;

#[test]
fn persisted_state_round_trips() {
    let mut state = State::default().with_job(Job { step: 0.6, ..Job::default() });
    state.view.tab = Tab::Sweep;
    let mut storage = MemoryStorage::default();
    State::save(&state.inputs, &state.view, &mut storage);
    let back = State::load(&storage).expect("stored");
    assert_eq!(back, state);
    let app = App::new(Job::default(), Some(back), Box::new(NativeDialogs::default()));
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
    let app = App::new(Job::default(), State::load(&storage), Box::new(NativeDialogs::default()));
    assert_eq!(app.view, View { tab: Tab::Compare, file, ..View::default() });
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

/// Part of the record that versions before the Pocket tab stored: the pocket's inputs in the
/// Corner tab's record, its mode `Pocket` when the pocket was shown.
#[derive(serde::Serialize)]
struct EarlierCorner {
    angle_deg: f64,
    method: trochoplan_core::corner::CornerMethod,
    tool_diameter_mm: f64,
    mode: EarlierMode,
    polygon_text: String,
    pocket_step_over_mm: f64,
    pocket_adaptive: bool,
    pocket_open_edges: String,
}

/// The Corner tab's pocket mode of those versions.
#[derive(serde::Serialize)]
enum EarlierMode {
    Pocket,
}

#[derive(serde::Serialize)]
struct EarlierWithPocket {
    job: Job,
    corner: EarlierCorner,
    corner_nc: panels::corner_nc::CornerNcSettings,
}

/// A state stored with the Corner tab's pocket mode loads: the pocket (outline, method,
/// step-over, adaptive, open edges, export settings) moves to the Pocket tab, which is shown;
/// the Corner tab keeps its corner. A state stored with the Pocket tab is loaded as stored.
#[test]
fn a_state_stored_with_the_corner_tabs_pocket_mode_opens_on_the_pocket_tab() {
    use trochoplan_core::corner::CornerMethod;
    let corner = EarlierCorner {
        angle_deg: 75.0,
        method: CornerMethod::MedialAxis,
        tool_diameter_mm: 8.0,
        mode: EarlierMode::Pocket,
        polygon_text: "0,0\n50,0\n50,30\n0,30\n".into(),
        pocket_step_over_mm: 2.0,
        pocket_adaptive: false,
        pocket_open_edges: "1".into(),
    };
    let corner_nc = panels::corner_nc::CornerNcSettings { depth_mm: 4.0, ..Default::default() };
    let earlier = EarlierWithPocket { job: Job::default(), corner, corner_nc: corner_nc.clone() };
    let mut storage = MemoryStorage::default();
    eframe::set_value(&mut storage, state::INPUTS_KEY, &earlier);
    assert!(storage.0.get(state::INPUTS_KEY).is_some_and(|t| t.contains("Pocket")), "stored as then");
    eframe::set_value(&mut storage, state::VIEW_KEY, &View { tab: Tab::Corner, ..View::default() });
    let loaded = State::load(&storage).expect("the earlier record loads");
    assert_eq!(loaded.view.tab, Tab::Pocket, "the pocket was shown: the Pocket tab is");
    let p = &loaded.inputs.pocket;
    assert_eq!(p.polygon_text, "0,0\n50,0\n50,30\n0,30\n");
    // the pocket is cut with the job's tool now: the earlier pocket's own diameter is not kept
    assert_eq!((p.strategy, p.step_over_mm), (trochoplan_core::pocket::PocketStrategy::MedialAxis, 2.0));
    assert_eq!(p.open_edges, "1");
    assert_eq!(loaded.inputs.pocket_nc, corner_nc, "exported with the Corner tab's settings");
    let c = &loaded.inputs.corner;
    assert_eq!((c.mode, c.angle_deg, c.tool_diameter_mm), (panels::corner::CornerMode::Corner, 75.0, 8.0));

    // stored again (now with the Pocket tab's record) it loads as it was saved
    let mut again = MemoryStorage::default();
    let mut edited = loaded.clone();
    edited.inputs.pocket.step_over_mm = 3.0;
    edited.view.tab = Tab::Corner;
    State::save(&edited.inputs, &edited.view, &mut again);
    assert_eq!(State::load(&again).expect("stored"), edited);
}

#[test]
fn ctrl_and_a_digit_show_the_tab_of_that_place_in_the_tab_bar() {
    let mut h = harness();
    // from the last tab backwards, so every press changes the tab shown
    for (i, t) in tabs::TABS.iter().enumerate().rev() {
        let key = commands::tab_shortcut(i).expect("a shortcut for every tab").logical_key;
        h.key_press_modifiers(egui::Modifiers::COMMAND, key);
        h.run();
        assert_eq!(h.state().view.tab, t.tab, "shortcut {i}: {}", t.label);
        let digit = (i + 1) % 10;
        assert!(t.hover_text(&h.ctx).ends_with(&format!("+{digit})")), "tooltip of {}", t.label);
    }
    // a text field with the keyboard does not stop them
    h.get_by_role_and_label(Role::SpinButton, Param::Step.label()).focus();
    h.run();
    assert!(h.ctx.memory(|m| m.focused().is_some()), "a field has the keyboard");
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Num2);
    h.run();
    assert_eq!(h.state().view.tab, tabs::TABS[1].tab);
    // Ctrl+T: the teaching explanations on and off
    let teach = h.state().state.teach;
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::T);
    h.run();
    assert_eq!(h.state().state.teach, !teach);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::T);
    h.run();
    assert_eq!(h.state().state.teach, teach);
}
