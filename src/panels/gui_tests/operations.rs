//! The Operations tab: a part job file opened through the path field (no system dialog), its
//! operations listed with the numbers the core's part planner gives, an operation opened in
//! its own tab, the part's program saved, and an operation's error as the command line gives it.

use super::*;
use crate::app::panels::operations_list::{self as list, length_text, peak_text, time_text};
use crate::app::panels::path_field::PathPurpose;
use trochoplan_core::machine::Machine;
use trochoplan_core::nc::{DEFAULT_TOLERANCE_MM, Dialect};
use trochoplan_core::part::{self, PartFile, PartReport, PlannedOperation};

/// The example part of docs/jobs.md: its first TOML block, with `part.txt` the 60 × 40
/// rectangle its report is given for.
fn example_part(dir: &Path) -> PathBuf {
    let doc = include_str!("../../../docs/jobs.md");
    let start = doc.find("```toml\n").expect("a TOML block") + "```toml\n".len();
    let end = start + doc[start..].find("```").expect("its end");
    let job = dir.join("part.toml");
    std::fs::write(&job, &doc[start..end]).unwrap();
    std::fs::write(dir.join("part.txt"), "0,0\n60,0\n60,40\n0,40\n").unwrap();
    job
}

/// The window with the part `job` opened by Ctrl+Shift+P through the path field, its
/// operations planned.
fn part_window(job: &Path) -> Harness<'static, App> {
    let mut h = harness_with(App::new(Job::default(), None, Box::new(NoPortal)));
    h.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::P);
    h.run();
    type_path(&mut h, job);
    assert!(!shows(&h, label::PATH_FIELD), "closed once opened: {:?}", h.state().status);
    assert_eq!(h.state().view.tab, Tab::Operations);
    let t0 = Instant::now();
    while h.state().operations.pending() && t0.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    h.run();
    h
}

/// The core's part planning of `job` on machine `vmc` (the tab's first machine), as
/// `trochoplan job --machine vmc` plans it: the file, the operations and the report.
fn core_part(job: &Path) -> (PartFile, Vec<PlannedOperation>, PartReport) {
    let file = part::parse(&std::fs::read_to_string(job).unwrap()).unwrap();
    let dir = job.parent().unwrap().to_path_buf();
    let outline = move |name: &str| crate::shared::outline::read_pocket(&dir.join(name), "outline file");
    let vmc = Machine::preset("vmc").unwrap();
    let ops = part::plan_part(&file, &outline, Some(&vmc)).unwrap();
    let report = part::report(&ops, Some((&vmc, file.program.retract_height_mm()))).unwrap();
    (file, ops, report)
}

#[test]
fn the_example_part_lists_its_operations_with_the_cores_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let job = example_part(dir.path());
    let mut h = part_window(&job);
    let (_, _, want) = core_part(&job);
    let view = &h.state().operations;
    assert_eq!(view.rows.len(), 3, "slot, pocket, corner");
    for (row, w) in view.rows.iter().zip(&want.operations) {
        let got = &row.result.as_ref().expect("planned").as_ref().expect("no error").report;
        assert_eq!(
            (got.operation, got.kind, got.tool, got.tool_diameter_mm),
            (w.operation, w.kind, w.tool, w.tool_diameter_mm)
        );
        // the same core calls on the same inputs: the same numbers, to the last bit
        assert_eq!(got.path_length_mm, w.path_length_mm, "operation {}", w.operation);
        assert_eq!(got.peak_engagement_deg, w.peak_engagement_deg, "operation {}", w.operation);
        assert_eq!(got.time_real_s, w.time_real_s, "operation {}", w.operation);
        for text in [length_text(w.path_length_mm), peak_text(w.peak_engagement_deg), time_text(w.time_real_s)] {
            assert!(shows(&h, &text), "operation {} shows {text}", w.operation);
        }
        assert!(shows(&h, &format!("{}. {}", w.operation, w.kind)));
        assert!(shows(&h, &format!("T{} · D {:.2} mm", w.tool, w.tool_diameter_mm)));
    }
    let t = view.totals().expect("all planned");
    assert_eq!(
        (t.path_length_mm, t.peak_engagement_deg, t.time_real_s),
        (want.path_length_mm, want.peak_engagement_deg, want.time_real_s)
    );
    assert!(shows(&h, &length_text(want.path_length_mm)) && shows(&h, &time_text(want.time_real_s)));
    assert!(shows(&h, list::WHOLE_PART));
    // an ideal machine: planned again, no times, as `trochoplan job` without `--machine`
    h.state_mut().operations.settings.machine = None;
    h.run();
    let file = part::parse(&std::fs::read_to_string(&job).unwrap()).unwrap();
    let dir2 = dir.path().to_path_buf();
    let outline = move |name: &str| crate::shared::outline::read_pocket(&dir2.join(name), "outline file");
    let ideal = part::report(&part::plan_part(&file, &outline, None).unwrap(), None).unwrap();
    for (row, w) in h.state().operations.rows.iter().zip(&ideal.operations) {
        let got = &row.result.as_ref().expect("planned").as_ref().expect("no error").report;
        assert_eq!(
            (got.path_length_mm, got.peak_engagement_deg, got.time_real_s),
            (w.path_length_mm, w.peak_engagement_deg, None)
        );
    }
    assert_eq!(h.state().operations.totals().and_then(|t| t.time_real_s), None);
    // the tab's words with a part open: no code names, no document paths (the words test's rule)
    let bad: Vec<String> = super::words::texts(&h)
        .into_iter()
        .filter(|t| !super::words::code_names(t, &|_| false).is_empty() || t.contains('`'))
        .collect();
    assert!(bad.is_empty(), "{bad:?}");
}

#[test]
fn the_pocket_operation_opens_the_pocket_tab_with_its_outline_and_tool() {
    let dir = tempfile::tempdir().unwrap();
    let job = example_part(dir.path());
    let mut h = part_window(&job);
    let (file, ops, _) = core_part(&job);
    h.get_by_label("2. pocket").click();
    h.run();
    assert_eq!(h.state().view.tab, Tab::Pocket);
    let t0 = Instant::now();
    while h.state().pocket.pending() && t0.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    h.run();
    // the outline file's rectangle in the vertex editor
    use egui_kittest::kittest::NodeT;
    let shown = h.get_by_label(label::POCKET_VERTICES).accesskit_node().value().unwrap_or_default().to_owned();
    let rect = trochoplan_core::outline::read("polygon", &shown).unwrap();
    let (boundary, islands) = rect.one_pocket().unwrap();
    let xy: Vec<(f64, f64)> = boundary.iter().map(|p| (p.x, p.y)).collect();
    assert_eq!(xy, [(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)]);
    assert!(islands.is_empty());
    // its tool (T2, D 6) and keys: step-over 1.5, depth 3
    let s = &h.state().state;
    let tool = file.tool.iter().find(|t| t.number == 2).unwrap();
    assert_eq!(
        (s.job.tool_diameter, s.job.teeth, s.job.rpm, s.job.feed),
        (tool.diameter, tool.teeth, tool.rpm, tool.feed)
    );
    assert_eq!((s.pocket.step_over_mm, s.pocket_nc.depth_mm), (1.5, 3.0));
    // the Pocket tab plans what the part planned for the operation (none of its keys is one
    // the tab lacks): the same path
    assert!(h.state().pocket.error.is_none(), "{:?}", h.state().pocket.error);
    let tab = h.state().pocket.last.clone().expect("a pocket");
    assert_eq!(tab.plan.toolpath().length_mm(), ops[1].planned.path_length_mm());
    let (msg, err) = h.state().status.clone().unwrap_or_default();
    assert!(!err && msg.contains("operation 2 (pocket, T2)"), "{msg}");
}

#[test]
fn the_part_program_saved_is_the_cores_and_an_operations_error_is_the_command_lines() {
    let dir = tempfile::tempdir().unwrap();
    let job = example_part(dir.path());
    let mut h = part_window(&job);
    let (file, ops, _) = core_part(&job);
    h.get_by_label(Dialect::Fanuc.label()).click();
    h.run();
    h.get_by_label(list::SAVE_PART_PROGRAM).click();
    h.run();
    let out = dir.path().join("part.nc");
    type_path(&mut h, &out);
    let written = std::fs::read_to_string(&out).expect("program written");
    let opts = crate::shared::nc::NcChoices::new(Dialect::Fanuc, DEFAULT_TOLERANCE_MM, false, file.program.clone());
    let want = part::part_program(&ops, &opts.options()).unwrap();
    assert_eq!(written, want.text);
    assert!(written.contains("T2 M6"), "the tool change to the pocket's tool");

    // an outline that does not exist: that operation's row has the message `trochoplan job`
    // gives, the others are planned
    let text = std::fs::read_to_string(&job).unwrap().replace("outline = \"part.txt\"", "outline = \"missing.txt\"");
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, text).unwrap();
    let h = part_window(&bad);
    let rows = &h.state().operations.rows;
    let Some(Err(e)) = &rows[1].result else { panic!("operation 2 fails: {:?}", rows[1].result.is_some()) };
    assert!(rows[0].result.as_ref().is_some_and(Result::is_ok) && rows[2].result.as_ref().is_some_and(Result::is_ok));
    assert!(shows(&h, e), "{e}");
    let cli = command_line(&["job", &bad.display().to_string()]);
    let stderr = String::from_utf8_lossy(&cli.stderr);
    assert!(!cli.status.success() && stderr.contains(e.as_str()), "{e} in {stderr}");
    assert!(e.starts_with("operation 2: outline"), "{e}");
    assert!(h.state().operations.planned().is_none(), "no part program with an error");
}

#[test]
fn the_threaded_view_plans_every_operation_with_a_progress_that_ends_full() {
    let dir = tempfile::tempdir().unwrap();
    let job = example_part(dir.path());
    let (file, ops, _) = core_part(&job);
    let mut v = panels::operations::PartView::threaded(|| {});
    v.load(&job, file);
    v.update();
    let t0 = Instant::now();
    while (v.pending() || v.rows.iter().any(|r| r.result.is_none())) && t0.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(10));
        v.update();
    }
    let p = v.progress().expect("a progress report");
    assert_eq!((p.fraction, p.text.as_deref()), (1.0, Some("3 operations planned")));
    for (row, op) in v.rows.iter().zip(&ops) {
        let got = row.result.as_ref().expect("planned").as_ref().expect("no error");
        assert_eq!(got.planned.planned.path_length_mm(), op.planned.path_length_mm());
    }
}

#[test]
fn the_slot_and_the_corner_operations_open_in_their_tabs_with_the_parts_plans() {
    let dir = tempfile::tempdir().unwrap();
    let job = example_part(dir.path());
    let mut h = part_window(&job);
    let (_, ops, _) = core_part(&job);
    // the slot: the edited job of the slot's tabs, its plan the part's first operation's
    h.get_by_label("1. slot").click();
    h.run();
    assert_eq!(h.state().view.tab, Tab::Plots);
    let t0 = Instant::now();
    while h.state().planner.pending() && t0.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    let s = &h.state().state.job;
    assert_eq!((s.slot_width, s.depth, s.tool_diameter, s.program.tool_number), (16.0, 4.0, 10.0, 1));
    assert_eq!(metrics(&h).path_length_mm, ops[0].planned.path_length_mm());
    // the corner: the Corner tab with its angle and tool, its plan the part's third operation's
    h.get_by_label(Tab::Operations.spec().label).click();
    h.run();
    h.get_by_label("3. corner").click();
    h.run();
    assert_eq!(h.state().view.tab, Tab::Corner);
    let c = &h.state().state.corner;
    assert_eq!((c.angle_deg, c.tool_diameter_mm, h.state().state.corner_nc.depth_mm), (90.0, 6.0, 2.0));
    let r = h.state().corner.last.clone().expect("a corner");
    assert_eq!(r.report.plan.toolpath.length_mm(), ops[2].planned.path_length_mm());
}

/// A part opened is a part in the recent files, opened again as one from File → Open recent;
/// the next start opens it again without leaving the tab it shows, and a part file that is
/// gone by then is forgotten with a message naming it.
#[test]
fn the_part_is_a_recent_file_and_is_opened_again_at_the_next_start() {
    let dir = tempfile::tempdir().unwrap();
    let job = example_part(dir.path());
    let mut h = part_window(&job);
    let view = h.state().view.clone();
    assert_eq!((view.recent.first(), view.part.as_ref()), (Some(&job), Some(&job)));
    assert!(matches!(h.state().recent_purpose(&job), PathPurpose::OpenPart));
    // the menu names it a part and opens it as one
    h.get_by_label("Plots").click();
    h.run();
    h.get_by_label("File").click();
    h.run();
    h.get_by_label("Open recent").click();
    h.run();
    h.get_by_label(&format!("{} (part)", job.display())).click();
    h.run();
    assert_eq!(h.state().view.tab, Tab::Operations, "{:?}", h.state().status);
    // a job saved under another name is a job, and the part stays a part
    let slot = dir.path().join("slot.toml");
    h.state_mut().save_to(&slot);
    assert!(matches!(h.state().recent_purpose(&slot), PathPurpose::OpenJob));
    assert!(matches!(h.state().recent_purpose(&job), PathPurpose::OpenPart));
    // the next start, on the Plots tab
    let stored = |view: &View| State { view: View { tab: Tab::Plots, ..view.clone() }, ..State::default() };
    let view = h.state().view.clone();
    let mut app = App::new(Job::default(), Some(stored(&view)), Box::new(NoPortal));
    app.reopen_part();
    let n = part::parse(&std::fs::read_to_string(&job).unwrap()).unwrap().operation.len();
    assert_eq!((app.view.tab, app.operations.rows.len()), (Tab::Plots, n), "{:?}", app.status);
    assert_eq!(app.operations.path.as_ref(), Some(&job));
    std::fs::remove_file(&job).unwrap();
    let mut app = App::new(Job::default(), Some(stored(&view)), Box::new(NoPortal));
    app.reopen_part();
    assert_eq!((app.view.part.as_ref(), app.operations.rows.len()), (None, 0));
    let (msg, error) = app.status.clone().expect("a message");
    assert!(error && msg.contains(&job.display().to_string()), "{msg}");
}
