//! Files without a system file dialog: the window asks in its path field, and every save and
//! open works through it from the keyboard (a plain X11 desktop without an XDG portal).

use super::*;

fn status(h: &Harness<'_, App>) -> (String, bool) {
    h.state().status.clone().unwrap_or_default()
}

#[test]
fn without_a_portal_jobs_programs_and_outlines_are_saved_and_opened_through_the_path_field() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness_with(App::new(Job::default(), None, Box::new(NoPortal)));

    // Save job as (Ctrl+Shift+S): no dialog, the path field asks instead
    h.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::S);
    h.run();
    assert!(shows(&h, "No file dialog appeared: type the file's path and press Enter."));
    let job_file = dir.path().join("slot.toml");
    type_path(&mut h, &job_file);
    let saved = std::fs::read_to_string(&job_file).expect("job written");
    assert_eq!(Job::from_toml(&saved).unwrap(), Job::default());
    assert!(!shows(&h, label::PATH_FIELD), "closed once saved");
    assert_eq!(h.state().view.file.as_deref(), Some(job_file.as_path()));

    // a path that cannot be written: the field stays open and says why
    h.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::S);
    h.run();
    type_path(&mut h, &dir.path().join("no such dir").join("x.toml"));
    let (msg, err) = status(&h);
    assert!(err && shows(&h, &msg), "{msg}");
    assert!(shows(&h, label::PATH_FIELD), "still open after the error");
    h.key_press(egui::Key::Escape);
    h.run();
    assert!(!shows(&h, label::PATH_FIELD), "Escape cancels");

    // Open job (Ctrl+O) brings the saved job back
    h.state_mut().state.job.step = 0.5;
    h.run();
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::O);
    h.run();
    type_path(&mut h, &job_file);
    assert_eq!(h.state().state.job, Job::default(), "{:?}", status(&h));

    // the slot's NC program (Ctrl+E): the previewed text
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::E);
    h.run();
    let nc_file = dir.path().join("slot.ngc");
    type_path(&mut h, &nc_file);
    let written = std::fs::read_to_string(&nc_file).expect("program written");
    assert_eq!(Some(written.as_str()), h.state().export.view().map(|v| v.text.as_str()));
    assert!(written.contains("G54") && written.contains("M30"), "{written}");

    // an outline (Ctrl+Shift+O) into the Pocket tab's vertices
    let outline = dir.path().join("pocket.txt");
    std::fs::write(&outline, "0,0\n50,0\n50,30\n0,30\n").unwrap();
    h.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::O);
    h.run();
    type_path(&mut h, &outline);
    assert_eq!(h.state().state.pocket.polygon_text, "0,0\n50,0\n50,30\n0,30\n", "{:?}", status(&h));

    // the recent files list them, newest first
    assert_eq!(h.state().view.recent, vec![outline.clone(), job_file]);

    // the Program tab: an NC program (the slot's, written above) and its stock outline
    h.get_by_label("Program").click();
    h.run();
    h.get_by_label(label::OPEN_PROGRAM_A).click();
    h.run();
    type_path(&mut h, &nc_file);
    let loaded = h.state().program.slots[0].loaded.as_ref().map(|p| p.path.clone());
    assert_eq!(loaded.as_deref(), Some(nc_file.as_path()), "{:?}", status(&h));
    h.get_by_label(label::OPEN_STOCK).click();
    h.run();
    type_path(&mut h, &outline);
    assert!(h.state().program.stock.is_some(), "{:?}", status(&h));
}
