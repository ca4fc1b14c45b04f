//! The Program panel: the frame of every program the window writes, saved with the job; the
//! Corner and Pocket tabs' programs in that frame, at the job's feed and spindle speed.

use super::*;
use trochoplan_core::frame::{ProgramFrame, Units};
use trochoplan_core::nc::{NcOptions, program};

#[test]
fn the_program_panel_sets_the_frame_of_every_program_and_is_saved_with_the_job() {
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("job.toml");
    let mut h = harness_saving_to(&file);
    h.get_by_label(Tab::Export.spec().label).click();
    h.run();
    h.get_by_role_and_label(Role::SpinButton, label::TOOL_NUMBER).set_value_accesskit(7.0);
    h.run();
    h.get_by_label("inch (G20)").click();
    h.run();
    let frame = ProgramFrame { tool_number: 7, units: Units::Inch, ..ProgramFrame::default() };
    assert_eq!(h.state().state.job.program, frame);
    // the slot's program is the core's with that frame
    let opts = NcOptions { frame: frame.clone(), ..NcOptions::default() };
    let want = program(&trochoplan_core::plan(&Job::default()).expect("plan"), &opts).expect("program");
    let shown = h.state().export.view().expect("program").text.clone();
    assert_eq!(shown, want.text);
    assert!(shown.contains("\nG17 G20 ") && shown.contains("\nT7 M6\nG43 H7\n"), "{shown}");

    // saved with the job
    h.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::S);
    h.run();
    let saved = std::fs::read_to_string(&file).expect("saved");
    assert!(saved.contains("[program]"), "{saved}");
    assert_eq!(Job::from_toml(&saved).expect("job").program, frame);

    // the pocket's program: the same frame, the job's feed and spindle speed
    h.state_mut().state.job.feed = 718.9;
    h.state_mut().state.job.rpm = 2500.0;
    h.get_by_label("Pocket").click();
    h.run();
    let t0 = Instant::now();
    while (h.state().pocket.pending() || h.state().pocket.last.is_none()) && t0.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    h.get_by_label(label::NC_EXPORT).click();
    h.run();
    let pocket = h.state().pocket_nc.view().expect("pocket program").text.clone();
    for word in ["feed 718.9 mm/min", "2500 rpm", "\nS2500 M3\n", "\nT7 M6\n", "\nG17 G20 "] {
        assert!(pocket.contains(word), "{word} in {pocket}");
    }
    assert!(!pocket.contains("feed 600.0"), "not the pocket's old default feed");
}
