//! `trochoplan export` as a user meets it: files, errors and exit codes.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;

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

const DIALECTS: [(&str, &str); 4] = [("linuxcnc", "ngc"), ("fanuc", "nc"), ("grbl", "gcode"), ("sinumerik", "mpf")];

/// The feeds a program sets, read back by rs274 (it starts at F0 before the program sets one:
/// that is not a feed of the program).
fn feeds_set(canon: &str) -> Vec<f64> {
    canon
        .lines()
        .filter_map(|l| l.split("SET_FEED_RATE(").nth(1))
        .filter_map(|r| r.trim_end_matches(')').trim().parse::<f64>().ok())
        .filter(|&f| f > 0.0)
        .collect()
}

/// `export --variable-feed --target-hmax 1e-6` wrote `F0.0` in every dialect (rs274: "Cannot do
/// g1 with zero feed rate"). The smallest target is the one whose lowest need, F·target/h_max
/// at the thickest chip, is the smallest feed (1 mm/min without a machine): target ≥
/// 1·h_max/F, with h_max from `analyze` and F = 600 mm/min (the default job). Below it every
/// dialect refuses by name; just above it the programs pass rs274 and set no feed under 1.
#[test]
fn variable_feed_targets_below_the_smallest_feed_are_refused_and_the_smallest_passes_rs274() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = trochoplan(&["analyze"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let (h_max, feed) = (v["h_max_mm"].as_f64().expect("h_max"), 600.0);
    let least = 1.0 * h_max / feed;
    for (dialect, ext) in DIALECTS {
        let file = dir.path().join(format!("low.{ext}"));
        for target in ["1e-6", &format!("{}", least * 0.99)] {
            let out = trochoplan(&[
                "export",
                "--dialect",
                dialect,
                "--variable-feed",
                "--target-hmax",
                target,
                "-o",
                file.to_str().expect("utf-8"),
            ]);
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(!out.status.success(), "{dialect} {target}: must fail");
            assert!(err.contains("invalid target-hmax") && err.contains("min-feed 1 mm/min"), "{err}");
            assert!(!file.exists(), "{dialect}: no program written");
        }
        let target = format!("{}", least * 1.001);
        let out = trochoplan(&[
            "export",
            "--dialect",
            dialect,
            "--variable-feed",
            "--target-hmax",
            &target,
            "-o",
            file.to_str().expect("utf-8"),
        ]);
        assert!(out.status.success(), "{dialect}: {}", String::from_utf8_lossy(&out.stderr));
        let text = std::fs::read_to_string(&file).expect("program");
        // every F word of the program is at least F1.0 (the smallest feed, to the 0.1 written)
        let words: Vec<f64> = text
            .split(|c: char| c.is_whitespace())
            .filter_map(|w| w.strip_prefix('F'))
            .filter_map(|w| w.parse::<f64>().ok())
            .collect();
        assert!(!words.is_empty() && words.iter().all(|&f| f >= 1.0), "{dialect}: {words:?}");
        if dialect != "sinumerik" {
            // rs274 reads the other three (the Sinumerik program is back-plotted in the core)
            let canon = nc_common::interpret(&file).unwrap_or_else(|e| panic!("{dialect}: {e}"));
            let set = feeds_set(&canon);
            assert!(!set.is_empty() && set.iter().all(|&f| f >= 1.0), "{dialect}: {set:?}");
        }
    }
}

/// A `[machine]` table whose feeds are below its smallest feed, or a feed option below it, is
/// refused by name before any program is written.
#[test]
fn feeds_below_the_machines_smallest_feed_name_the_option() {
    let dir = tempfile::tempdir().expect("tempdir");
    let job = dir.path().join("tiny.toml");
    let machine = "name = \"tiny\"\nmax-feed-y = 5000\nacceleration-x = 3000\nacceleration-y = 3000\n\
                   jerk-x = 50000\njerk-y = 50000\npath-tolerance = 0.01\n";
    let file = dir.path().join("x.nc");
    let f = file.to_str().expect("utf-8");
    let j = job.to_str().expect("utf-8");
    let cases: [(String, Vec<&str>, &str); 6] = [
        (
            format!("[machine]\n{machine}max-feed-x = 1e-9\n"),
            vec![],
            "invalid max-feed-x = 1e-9: must be from the machine's min-feed 1 to 1000000 mm/min",
        ),
        (format!("[machine]\n{machine}max-feed-x = 5000\nmin-feed = 0\n"), vec![], "invalid min-feed = 0"),
        (
            format!("[machine]\n{machine}max-feed-x = 5000\nmin-feed = 10\n"),
            vec!["--feed", "8"],
            "invalid feed = 8: must be from the machine's min-feed 10",
        ),
        (
            String::new(),
            vec!["--rpm", "1", "--teeth", "1", "--feed", "0.5"],
            "invalid feed = 0.5: must be from the machine's min-feed 1",
        ),
        (
            String::new(),
            vec!["--return-feed", "0.5"],
            "invalid return-feed = 0.5: must be from the machine's min-feed 1",
        ),
        (
            String::new(),
            vec!["--variable-feed", "--max-feed", "0.5"],
            "invalid max-feed = 0.5: must be from the machine's min-feed 1",
        ),
    ];
    for (toml, flags, message) in cases {
        std::fs::write(&job, &toml).expect("write");
        let mut args = vec!["export", "--dialect", "grbl", "--job", j, "-o", f];
        args.extend(flags);
        let out = trochoplan(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(message), "{args:?}: {err}");
        assert!(!file.exists());
    }
}

/// An expanded program of more than 4 000 000 blocks is refused before writing, naming the step;
/// the loop form writes it. 100 000 mm at s = 0.1 mm is 1 000 000 cycles, of more than four
/// blocks each for the circular path (an arc per half turn and the step line at least).
#[test]
fn programs_too_long_to_write_name_the_step() {
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("long.ngc");
    let f = file.to_str().expect("utf-8");
    let job = ["--slot-length", "1e5", "--step", "0.1"];
    let out = trochoplan(&[&["export", "--dialect", "linuxcnc", "-o", f][..], &job].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("invalid step = 0.1") && err.contains("--compact"), "{err}");
    assert!(!file.exists());
    let out = trochoplan(&[&["export", "--dialect", "linuxcnc", "--compact", "-o", f][..], &job].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

/// The program's frame from a job file's `[program]` table, a flag overriding it, and bad
/// values named by their flag with the range.
#[test]
fn the_frame_comes_from_the_job_file_and_the_flags_override_it() {
    let dir = tempfile::tempdir().expect("tempdir");
    let job = dir.path().join("job.toml");
    std::fs::write(&job, "feed = 718.9\n[program]\ntool-number = 7\nwork-offset = \"G56\"\nclearance = 20\nretract = 2\ncoolant = \"mist\"\n")
        .expect("job file");
    let (j, file) = (job.to_str().expect("utf-8"), dir.path().join("slot.nc"));
    let f = file.to_str().expect("utf-8");
    let run = |extra: &[&str]| {
        let args: Vec<&str> =
            ["export", "--job", j, "--dialect", "fanuc", "-o", f].iter().chain(extra).copied().collect();
        let out = trochoplan(&args);
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        std::fs::read_to_string(&file).expect("program")
    };
    let text = run(&[]);
    for word in ["\nG56\n", "\nT7 M6\nG43 H7\n", "\nS2000 M3\nM7\n", "\nG0 Z20.000\n", "F718.9", "\nM9\n"] {
        assert!(text.contains(word), "{word:?} in {text}");
    }
    let text = run(&["--tool-number", "3", "--program-number", "42", "--spindle-direction", "ccw"]);
    assert!(text.contains("\nT3 M6\nG43 H3\n") && text.starts_with("%\nO42\n"), "{text}");
    // M4 with the conventional job: the header says the program cuts climb
    assert!(text.contains("(climb milling with M4: loops clockwise)"), "{text}");

    for (flags, flag, range) in [
        (&["--tool-number", "0"][..], "tool-number", "from 1 to 9999"),
        (&["--tool-number", "-2"][..], "tool-number", "from 1 to 9999"),
        (&["--retract", "25"][..], "retract", "≤ 20 mm"),
        (&["--clearance", "0"][..], "clearance", "> 0 and ≤ 1000 mm"),
        (&["--program-name", "9X"][..], "program-name", "a letter"),
    ] {
        let args: Vec<&str> =
            ["export", "--job", j, "--dialect", "fanuc", "-o", f].iter().chain(flags).copied().collect();
        let out = trochoplan(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(flag) && err.contains(range), "{flags:?}: {err}");
    }
    // the frame flags of corner and pocket need --export
    let out = trochoplan(&["corner", "--units", "inch"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("--units") && err.contains("--export"), "{err}");
}
