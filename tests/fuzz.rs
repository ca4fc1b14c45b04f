//! Fuzz of every command, kept in the repository and run by the test command: random
//! valid slot jobs, random simple polygons (exported programs read back through LinuxCNC's
//! `rs274` and checked against the plan and the walls), malformed job / polygon / CSV files and
//! hostile titles. Counted: panics, runs over 10 s, gouges, silent misparses, active comments —
//! each must be zero. Inputs come from a fixed-seed generator, so a failure names a case that can
//! be run again; the number of cases bounds the run time (about a minute on 2 cores).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;
mod pocket_common;

use nc_common::{budget, check_cut, cut, interpret, motions};
use pocket_common::{Rng, below_top_violations, check_pocket_program, pocket_export, run, star_polygon};
use std::path::Path;
use trochoplan_core::{Job, PathKind, plan};

/// A random slot job over the whole valid range of each parameter (and somewhat past it: the
/// checks then expect a named rejection).
fn random_job(rng: &mut Rng) -> Job {
    let path = PathKind::ALL[rng.below(PathKind::ALL.len())];
    let slot_width = rng.log_range(2.0, 200.0);
    let tool_diameter = slot_width * rng.range(0.45, 0.98);
    let teeth = 1 + rng.below(8) as u32;
    let rpm = rng.log_range(500.0, 40_000.0);
    let f_z = rng.log_range(0.005, 0.3);
    Job {
        path,
        slot_width,
        slot_length: rng.log_range(1.0, 3.0 * slot_width),
        depth: rng.log_range(0.1, 30.0),
        tool_diameter,
        teeth,
        feed: f_z * rpm * f64::from(teeth),
        rpm,
        step: tool_diameter * rng.log_range(0.005, 0.4),
        aspect_ratio: rng.range(0.3, 2.0),
        linear_distance: slot_width * rng.range(0.0, 0.3),
        ..Job::default()
    }
}

fn job_flags(job: &Job) -> Vec<String> {
    let mut f = vec!["--path".to_string(), job.path.name().to_string()];
    for (flag, v) in [
        ("--slot-width", job.slot_width),
        ("--slot-length", job.slot_length),
        ("--depth", job.depth),
        ("--tool-diameter", job.tool_diameter),
        ("--feed", job.feed),
        ("--rpm", job.rpm),
        ("--step", job.step),
        ("--aspect-ratio", job.aspect_ratio),
        ("--linear-distance", job.linear_distance),
    ] {
        f.push(flag.to_string());
        f.push(format!("{v}"));
    }
    f.push("--teeth".to_string());
    f.push(job.teeth.to_string());
    f
}

#[test]
fn random_slot_jobs_plan_or_are_rejected_by_name_and_their_programs_retrace_the_plan() {
    let mut rng = Rng::new(13);
    let dir = tempfile::tempdir().expect("tempdir");
    let (mut planned, mut rejected, mut exported) = (0, 0, 0);
    for k in 0..60 {
        let job = random_job(&mut rng);
        let flags = job_flags(&job);
        let label = format!("job {k} {flags:?}");
        let mut args = vec!["analyze"];
        args.extend(flags.iter().map(String::as_str));
        let r = run(&label, &args);
        match plan(&job) {
            Ok(p) => {
                assert_eq!(r.code, 0, "{label}: the core plans it, the CLI says {}", r.stderr);
                let v: serde_json::Value = serde_json::from_str(&r.stdout).expect("JSON");
                let numbers = v.as_object().expect("object").values().filter_map(serde_json::Value::as_f64);
                assert!(numbers.clone().count() > 5 && numbers.into_iter().all(f64::is_finite), "{label}: {v}");
                planned += 1;
                // every fourth planned job (bounded cost): export, read back, compare
                if planned % 4 == 1 && p.metrics.path_length_mm < 20_000.0 {
                    let file = dir.path().join(format!("job{k}.ngc"));
                    let mut args = vec!["export", "--dialect", "linuxcnc", "-o", file.to_str().expect("utf-8")];
                    args.extend(flags.iter().map(String::as_str));
                    let r = run(&label, &args);
                    assert_eq!(r.code, 0, "{label}: {}", r.stderr);
                    let m = motions(&interpret(&file).unwrap_or_else(|e| panic!("{label}: {e}")));
                    check_cut(&label, &cut(&m, p.job.depth, 1e-4), &p, 0.005, 1e-4).unwrap_or_else(|e| panic!("{e}"));
                    exported += 1;
                }
            }
            Err(e) => {
                let name = e.parameter().expect("a job error names its parameter").cli_name();
                assert_eq!(r.code, 2, "{label}: {e}");
                assert!(r.stderr.contains(name), "{label}: {} does not name {name}", r.stderr);
                rejected += 1;
            }
        }
    }
    assert!(
        planned >= 20 && rejected >= 1 && exported >= 5,
        "{planned} planned, {rejected} rejected, {exported} exported"
    );
}

#[test]
fn random_pockets_of_every_method_never_gouge() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut rng = Rng::new(5);
    let mut checked = 0;
    for seed in 0..5u64 {
        let n = 6 + rng.below(12);
        let polygon = star_polygon(100 + seed, n);
        let d = rng.range(6.0, 12.0);
        let a_e = d * rng.range(0.12, 0.3);
        let (d_s, a_e_s) = (format!("{d}"), format!("{a_e}"));
        for method in ["plain", "variable", "medial-axis"] {
            let label = format!("star {seed} ({n} vertices, D {d:.3}, a_e {a_e:.3}) {method}");
            let args = ["--method", method, "--tool-diameter", &d_s, "--step-over", &a_e_s, "--dialect", "fanuc"];
            let Some(e) = pocket_export(dir.path(), &format!("star{seed}_{method}.nc"), &polygon, &args) else {
                continue; // rejected by name (e.g. the tool does not fit): checked inside
            };
            check_pocket_program(&label, &e, &polygon, 0.5 * d, 0.005, 3);
            // every move below the stock top, links included, exactly against the walls
            let all = motions(&interpret(&e.file).unwrap_or_else(|err| panic!("{label}: {err}")));
            let bad = below_top_violations(&all, &polygon, &[], 0.5 * d, budget(0.005, 1e-3));
            assert!(bad.is_empty(), "{label}: {}", bad.join("\n"));
            checked += 1;
        }
    }
    // a rejection is allowed, but the test must still check programs
    assert!(checked >= 10, "only {checked} of 15 pockets were planned and checked");
}

/// A valid 60 × 40 rectangle file and mutations of one of its lines. Each mutated file must
/// either give the same polygon (a BOM, a header) or an error that names the line — never a
/// polygon with a vertex fewer or a number read from half a field.
#[test]
fn malformed_polygon_and_path_files_are_errors_naming_the_line() {
    let dir = tempfile::tempdir().expect("tempdir");
    let lines = ["0,0", "60,0", "60,40", "0,40"];
    let reference = pocket_length(dir.path(), "ref", &lines.join("\n"), "polygon").expect("the rectangle plans");
    /// A named mutation of one polygon line.
    type Mutation = (&'static str, fn(&str) -> String);
    let bad: [Mutation; 7] = [
        ("trailing comment", |l| format!("{l} # note")),
        ("letter O for zero", |l| l.replace('0', "O")),
        ("third column", |l| format!("{l},5")),
        ("semicolon", |l| l.replacen(',', ";", 1)),
        ("one number", |l| l.split(',').next().unwrap_or("").to_string()),
        ("NaN", |l| format!("NaN,{}", l.split(',').nth(1).unwrap_or(""))),
        ("trailing garbage", |l| format!("{l}x")),
    ];
    for (k, line) in lines.iter().enumerate() {
        for (what, mutate) in bad {
            let mut m: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
            m[k] = mutate(line);
            let text = m.join("\n");
            let label = format!("{what} on line {}: {text:?}", k + 1);
            // either read as the same rectangle (a comment the format allows) or an error
            // naming the line: never another polygon
            match pocket_length(dir.path(), &format!("m{k}"), &text, "polygon") {
                Err(msg) => assert!(msg.contains(&format!("line {}", k + 1)), "{label}: {msg}"),
                Ok(len) => assert_eq!(len, reference, "{label}: silently planned another pocket"),
            }
        }
    }
    // benign: a UTF-8 BOM, a header line, CRLF line ends
    for (what, text) in [
        ("BOM", format!("\u{feff}{}", lines.join("\n"))),
        ("header", format!("x,y\n{}", lines.join("\n"))),
        ("CRLF", lines.join("\r\n")),
    ] {
        let len = pocket_length(dir.path(), "benign", &text, "polygon").unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!(len, reference, "{what}: a different pocket");
    }
    // the engagement command's path CSV: `0,5;25` is not (0, 5), a third column is not ignored
    let stock = dir.path().join("stock.txt");
    std::fs::write(&stock, lines.join("\n")).expect("write");
    for (what, text) in
        [("semicolon", "0,5;25\n30,5\n"), ("third column", "0,5,1\n30,5\n"), ("comment", "0,5 # a\n30,5\n")]
    {
        let csv = dir.path().join("path.csv");
        std::fs::write(&csv, text).expect("write");
        let r = run(
            what,
            &[
                "engagement",
                "--path-csv",
                csv.to_str().expect("utf-8"),
                "--stock-polygon",
                stock.to_str().expect("utf-8"),
            ],
        );
        assert!(r.code == 2 && r.stderr.contains("line 1"), "{what}: exit {} {}", r.code, r.stderr);
    }
}

/// Path length of the plain pocket planned from `text`, or the error message.
fn pocket_length(dir: &Path, name: &str, text: &str, what: &str) -> Result<f64, String> {
    let file = dir.join(format!("{name}.{what}"));
    std::fs::write(&file, text).expect("write");
    let r = run(name, &["pocket", "--polygon", file.to_str().expect("utf-8"), "--method", "plain"]);
    if r.code != 0 {
        return Err(r.stderr);
    }
    let v: serde_json::Value = serde_json::from_str(&r.stdout).expect("JSON");
    Ok(v["path_length_mm"].as_f64().expect("path length"))
}

#[test]
fn malformed_job_files_are_clear_errors() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut rng = Rng::new(77);
    let valid = Job::default().to_toml();
    for k in 0..40 {
        let mut bytes = valid.clone().into_bytes();
        // flip, delete or insert a few bytes: a corrupt or truncated job file
        for _ in 0..1 + rng.below(4) {
            let at = rng.below(bytes.len());
            match rng.below(3) {
                0 => bytes[at] = b"=[]\"#x-.,\n0"[rng.below(11)],
                1 => {
                    bytes.truncate(at);
                    if bytes.is_empty() {
                        bytes.push(b'=');
                    }
                }
                _ => bytes.insert(at, b"=[]\"#x-.,\n0"[rng.below(11)]),
            }
        }
        let file = dir.path().join(format!("job{k}.toml"));
        std::fs::write(&file, &bytes).expect("write");
        let label = format!("job file {k}: {:?}", String::from_utf8_lossy(&bytes));
        let r = run(&label, &["analyze", "--job", file.to_str().expect("utf-8")]);
        match Job::from_toml(&String::from_utf8_lossy(&bytes)).map(|j| plan(&j)) {
            Ok(Ok(_)) => assert_eq!(r.code, 0, "{label}: {}", r.stderr),
            _ => assert!(r.code == 2 && !r.stderr.trim().is_empty(), "{label}: exit {} {}", r.code, r.stderr),
        }
    }
}

#[test]
fn hostile_titles_never_form_active_comments() {
    // Random titles built from LinuxCNC's active-comment words, delimiters, control and
    // non-ASCII characters, in random case with leading spaces; rs274 must run every program
    // without a message (any stderr line fails `interpret`) and cut the planned slot.
    const PIECES: [&str; 18] = [
        "MSG,",
        "debug,",
        "Print,",
        "LOG,",
        "logopen,",
        "LOGAPPEND,",
        "logclose",
        "ABORT,",
        "probeopen ",
        "PROBECLOSE",
        "py,",
        "(",
        ")",
        ";",
        "%",
        "\n",
        "\t",
        "é",
    ];
    let dir = tempfile::tempdir().expect("tempdir");
    let mut rng = Rng::new(4);
    let p = plan(&Job::default()).expect("valid");
    for k in 0..25 {
        let mut title = " ".repeat(rng.below(3));
        for _ in 0..1 + rng.below(4) {
            title.push_str(PIECES[rng.below(PIECES.len())]);
            title.push_str(["x", "stop", "/tmp/t", "", " "][rng.below(5)]);
        }
        for (dialect, ext) in [("linuxcnc", "ngc"), ("grbl", "gcode")] {
            let file = dir.path().join(format!("t{k}.{ext}"));
            let label = format!("title {title:?} {dialect}");
            let r =
                run(&label, &["export", "--dialect", dialect, "--title", &title, "-o", file.to_str().expect("utf-8")]);
            assert_eq!(r.code, 0, "{label}: {}", r.stderr);
            let m = motions(&interpret(&file).unwrap_or_else(|e| panic!("{label}: {e}")));
            check_cut(&label, &cut(&m, p.job.depth, 1e-4), &p, 0.005, if dialect == "grbl" { 1e-3 } else { 1e-4 })
                .unwrap_or_else(|e| panic!("{e}"));
        }
    }
}
