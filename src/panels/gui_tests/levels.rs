//! A slot in levels and a closed slot in the window: the parameter fields, the levels' summary
//! in the derived values and the Export NC tab's program, the CLI's for the same job.

use super::*;
use egui_kittest::kittest::NodeT;

/// Wait for the planner's answer (the window plans on a worker; the tests' planner inline).
fn planned(h: &mut Harness<'_, App>) {
    let t0 = std::time::Instant::now();
    while h.state().planner.pending() && t0.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    h.run();
}

#[test]
fn a_closed_keyway_exported_from_the_window_is_the_clis_export_program() {
    let dir = tempfile::tempdir().expect("tempdir");
    let gui_file = dir.path().join("gui.ngc");
    let mut h = harness_saving_to(&gui_file);
    // the keyway of docs/slot-paths.md: 60 × 10 mm, 12 mm deep, D 8, levels of at most 4 mm
    {
        let job = &mut h.state_mut().state.job;
        job.slot_width = 10.0;
        job.slot_length = 60.0;
        job.depth = 12.0;
        job.tool_diameter = 8.0;
    }
    h.run();
    // the levels and the slot's ends through their fields
    h.get_by_role_and_label(Role::CheckBox, Param::MaxStepDown.label()).click();
    h.run();
    h.get_by_role_and_label(Role::Slider, Param::MaxStepDown.label()).set_value_accesskit(4.0);
    h.run();
    h.get_by_role_and_label(Role::CheckBox, Param::Closed.label()).click();
    h.run();
    planned(&mut h);
    let job = h.state().state.job.clone();
    assert_eq!((job.max_step_down, job.closed), (Some(4.0), true));
    let lp =
        h.state().planner.last.as_ref().and_then(|p| p.levels.as_ref()?.as_ref().ok()).expect("levels planned").clone();
    // 12 mm at most 4 mm a level: ⌈12/4⌉ = 3 levels of 4 mm
    assert_eq!(lp.levels.count(), 3);
    assert!((lp.levels.axial_depth_mm - 4.0).abs() < 1e-12);
    assert!(shows(&h, &format!("3 × {:.3} mm", 4.0)), "levels' summary shown");
    assert!(shows(&h, "closed (helix entry)"));
    // tool centre D/2 = 4 mm from both end walls: Y4 to Y56
    assert!(shows(&h, &format!("{:.3} to {:.3} mm", 4.0, 56.0)), "tool centre's reach shown");

    h.get_by_label(Tab::Export.spec().label).click();
    h.run();
    h.get_by_label(label::SAVE_NC_PROGRAM).click();
    h.run();
    let gui = std::fs::read_to_string(&gui_file).expect("the window wrote the program");

    let cli_file = dir.path().join("cli.ngc");
    let cli = cli_file.to_str().expect("path");
    let args = [
        "export",
        "--slot-width",
        "10",
        "--slot-length",
        "60",
        "--depth",
        "12",
        "--tool-diameter",
        "8",
        "--max-step-down",
        "4",
        "--closed",
        "--dialect",
        "linuxcnc",
        "-o",
        cli,
    ];
    let out = command_line(&args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(report.contains("3 levels, closed slot"), "{report}");
    let want = std::fs::read_to_string(&cli_file).expect("the CLI wrote the program");
    assert_eq!(gui, want, "the window's program is the CLI's");
    // a levels program: a helix (G2/G3 with a Z word) at each of the three floors
    for z in ["Z-4", "Z-8", "Z-12"] {
        assert!(gui.contains(z), "floor {z} in the program");
    }
    // the loop form writes one level: not offered for levels
    assert!(h.get_by_role_and_label(Role::CheckBox, label::COMPACT_LOOP).accesskit_node().is_disabled());
}
