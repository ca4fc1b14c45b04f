//! `trochoplan export` as a user meets it: files, errors and exit codes.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::process::{Command, Output};

fn trochoplan(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_trochoplan")).args(args).output().expect("run trochoplan")
}

#[test]
fn export_writes_a_program_and_reports_its_size() {
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("slot.ngc");
    let f = file.to_str().expect("utf-8 path");
    let out = trochoplan(&["export", "--dialect", "linuxcnc", "-o", f]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&file).expect("program written");
    assert!(text.contains("G21") && text.contains("M30"));
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(summary.contains(&format!("{} bytes", text.len())), "{summary}");
    assert_eq!(std::fs::read_dir(dir.path()).expect("dir").count(), 1, "no temporary file left");
}

#[test]
fn unwritable_path_fails_clearly_and_leaves_the_old_file_whole() {
    let out = trochoplan(&["export", "--dialect", "grbl", "-o", "/nonexistent-dir/slot.gcode"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("cannot write /nonexistent-dir/slot.gcode"), "{err}");

    // a failing export (bad option) never touches an existing program
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("old.nc");
    std::fs::write(&file, "old program\n").expect("write");
    let f = file.to_str().expect("utf-8 path");
    let out = trochoplan(&["export", "--dialect", "fanuc", "--tolerance", "0", "-o", f]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("tolerance") && err.contains("0.0001"), "names the option and its range: {err}");
    assert_eq!(std::fs::read_to_string(&file).expect("read"), "old program\n");
}

#[test]
fn bad_job_and_impossible_options_name_the_parameter() {
    let dir = tempfile::tempdir().expect("tempdir");
    let f = dir.path().join("x.nc");
    let f = f.to_str().expect("utf-8 path");
    let out = trochoplan(&["export", "--dialect", "fanuc", "--compact", "-o", f]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("compact"));
    let out = trochoplan(&["export", "--dialect", "linuxcnc", "--step", "-1", "-o", f]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("step"));
    assert!(!std::path::Path::new(f).exists());
}
