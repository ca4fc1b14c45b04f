//! End-to-end tests of the headless CLI contract (`analyze`, `sweep`): names, output shape,
//! errors and files. They run the real binary.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::process::Command;

fn run(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_trochoplan")).args(args).output().expect("binary runs");
    (out.status.success(), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

fn json(args: &[&str]) -> serde_json::Value {
    let (ok, out, err) = run(args);
    assert!(ok, "{args:?} failed: {err}");
    serde_json::from_str(&out).expect("one JSON object")
}

const CONTRACT: [&str; 10] = [
    "cycle_length_mm",
    "t_cycle_s",
    "mrr_mm3_per_min",
    "f_z_mm",
    "h_max_mm",
    "t_hmax_s",
    "t_cooling_s",
    "engagement_max_deg",
    "waviness_left_mm",
    "waviness_right_mm",
];

#[test]
fn analyze_prints_the_contract_fields_for_the_papers_default_job() {
    let v = json(&["analyze"]);
    for k in CONTRACT {
        assert!(v[k].as_f64().is_some_and(f64::is_finite), "missing {k}: {v}");
    }
    // Defaults are the paper's Table 1: f_z = 600 / (2000 · 4) = 0.075 mm; circular path.
    assert_eq!(v["f_z_mm"].as_f64(), Some(0.075));
    assert_eq!(v["path"], "circular");
    // Table 2, r_e = 1: h_max 0.059 mm (2 %).
    assert!((v["h_max_mm"].as_f64().expect("h") - 0.059).abs() <= 0.02 * 0.059);
    assert!(v["engagement_limited_step_mm"].as_f64().is_some_and(|s| s > 0.0 && s < 1.0));
}

#[test]
fn every_job_flag_is_accepted_and_flags_override_the_job_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let job = dir.path().join("job.toml");
    std::fs::write(&job, "path = \"elliptical\"\naspect-ratio = 0.6\nstep = 0.5\n").expect("write");
    let v = json(&[
        "analyze",
        "--job",
        job.to_str().expect("utf8"),
        "--step",
        "0.8",
        "--slot-width",
        "20",
        "--slot-length",
        "30",
        "--depth",
        "5",
        "--tool-diameter",
        "10",
        "--teeth",
        "3",
        "--feed",
        "500",
        "--rpm",
        "2500",
        "--linear-distance",
        "0",
    ]);
    assert_eq!(v["path"], "elliptical");
    assert_eq!(v["aspect_ratio"].as_f64(), Some(0.6));
    assert_eq!(v["step_mm"].as_f64(), Some(0.8));
    let fz = 500.0 / (2500.0 * 3.0);
    assert!((v["f_z_mm"].as_f64().expect("fz") - fz).abs() < 1e-15);
    let lin = json(&["analyze", "--path", "linear-elliptical", "--aspect-ratio", "0.8", "--linear-distance", "1"]);
    assert_eq!(lin["linear_distance_mm"].as_f64(), Some(1.0));
}

#[test]
fn sweep_reproduces_table2_in_one_command() {
    let (ok, out, err) = run(&["sweep", "--param", "aspect-ratio", "--from", "0.5", "--to", "1.2", "--steps", "8"]);
    assert!(ok, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 9, "{out}");
    let header: Vec<&str> = lines[0].split(',').collect();
    for k in CONTRACT {
        assert!(header.contains(&k), "header lacks {k}");
    }
    let col = |name: &str| header.iter().position(|h| *h == name).expect("column");
    // Table 2 h_max column (Wagih et al. 2023), within 2 %.
    let paper = [0.068, 0.062, 0.059, 0.057, 0.058, 0.059, 0.059, 0.060];
    for (line, h) in lines[1..].iter().zip(paper) {
        let cells: Vec<&str> = line.split(',').collect();
        let ours: f64 = cells[col("h_max_mm")].parse().expect("number");
        assert!((ours - h).abs() <= 0.02 * h, "{line}");
        assert_eq!(cells[0], "elliptical");
    }
    assert_eq!(lines[3].split(',').nth(1), Some("0.7"), "values read as typed");
}

#[test]
fn sweep_of_step_and_linear_distance_work() {
    let (ok, out, _) = run(&["sweep", "--param", "step", "--from", "0.5", "--to", "1.5", "--steps", "3"]);
    assert!(ok && out.lines().count() == 4, "{out}");
    let (ok, out, _) = run(&[
        "sweep",
        "--param",
        "linear-distance",
        "--from",
        "0",
        "--to",
        "1.2",
        "--steps",
        "4",
        "--aspect-ratio",
        "0.8",
    ]);
    assert!(ok && out.lines().count() == 5, "{out}");
    assert!(out.lines().nth(1).is_some_and(|l| l.starts_with("linear-elliptical,0,")), "{out}");
}

#[test]
fn bad_input_names_the_parameter_and_exits_non_zero() {
    for (args, name) in [
        (vec!["analyze", "--step", "-1"], "step"),
        (vec!["analyze", "--tool-diameter", "25"], "tool-diameter"),
        (vec!["analyze", "--slot-width", "nan"], "slot-width"),
        (vec!["analyze", "--teeth", "0"], "teeth"),
        (vec!["analyze", "--path", "elliptical", "--aspect-ratio", "0"], "aspect-ratio"),
        (vec!["analyze", "--slot-length", "0.5"], "slot-length"),
        (vec!["sweep", "--param", "step", "--from", "0.5", "--to", "20", "--steps", "3"], "step"),
        (vec!["analyze", "--path", "spiral"], "path"),
    ] {
        let (ok, out, err) = run(&args);
        assert!(!ok, "{args:?} must fail");
        assert!(out.is_empty(), "{args:?} printed {out}");
        assert!(err.contains(name), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}

/// An error message names the flag as typed, the value short, and the allowed range.
fn fails_with(args: &[&str], message: &str) {
    let (ok, out, err) = run(args);
    assert!(!ok && out.is_empty(), "{args:?} must fail: {out}");
    assert_eq!(err, format!("trochoplan: {message}\n"), "{args:?}");
}

#[test]
fn negative_counts_get_the_core_message_not_clap_unexpected_argument() {
    fails_with(&["analyze", "--teeth", "-1"], "invalid teeth = -1: must be a whole number from 1 to 64");
    fails_with(
        &["sweep", "--param", "step", "--from", "0.5", "--to", "1", "--steps", "-1"],
        "invalid steps = -1: must be a whole number from 1 to 200",
    );
}

#[test]
fn a_tiny_slot_width_blames_the_slot_width() {
    fails_with(
        &["analyze", "--slot-width", "1e-10"],
        "invalid slot-width = 1e-10: must be a finite number from 0.01 to 100000 mm",
    );
}

#[test]
fn numbers_in_messages_are_short() {
    fails_with(
        &["analyze", "--slot-width", "1e308"],
        "invalid slot-width = 1e308: must be a finite number from 0.01 to 100000 mm",
    );
    fails_with(
        &["analyze", "--engagement-limit", "1000.0000000000001"],
        "invalid engagement-limit = 1000: must be between 0° and 180° (exclusive)",
    );
}

#[test]
fn corner_messages_name_the_flag_the_user_typed() {
    let dir = tempfile::tempdir().expect("tempdir");
    let nc = dir.path().join("c.ngc");
    let nc = nc.to_str().expect("utf8");
    fails_with(
        &["corner", "--nc-tolerance", "0", "--export", nc],
        "invalid nc-tolerance = 0: must be from 0.0001 to 1 mm",
    );
    fails_with(
        &["corner", "--tool-diameter", "1e-9"],
        "invalid tool-diameter = 1e-9: must be a finite number from 0.01 to 1000 mm",
    );
}

#[test]
fn engagement_names_the_tool_diameter_as_typed() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (path, stock) = (dir.path().join("p.csv"), dir.path().join("s.txt"));
    std::fs::write(&path, "x,y\n-20,0\n20,0\n").expect("write");
    std::fs::write(&stock, "-50,2.5\n50,2.5\n50,40\n-50,40\n").expect("write");
    let (p, s) = (path.to_str().expect("utf8"), stock.to_str().expect("utf8"));
    fails_with(
        &["engagement", "--path-csv", p, "--stock-polygon", s, "--tool-diameter", "-10"],
        "invalid tool-diameter = -10: must be a finite number > 0 mm",
    );
}

#[test]
fn a_polygon_parse_error_names_the_polygon_file_not_a_job_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let poly = dir.path().join("rect.txt");
    std::fs::write(&poly, "0,0\n60,0\nx,40\n0,40\n").expect("write");
    let p = poly.to_str().expect("utf8");
    fails_with(&["pocket", "--polygon", p], &format!("{p} line 3: expected two numbers x,y, got \"x,40\""));
}

#[test]
fn corrupt_job_file_is_a_clear_error() {
    let dir = tempfile::tempdir().expect("tempdir");
    let job = dir.path().join("bad.toml");
    std::fs::write(&job, "slot-width = [1, 2\n").expect("write");
    let (ok, _, err) = run(&["analyze", "--job", job.to_str().expect("utf8")]);
    assert!(!ok && err.contains("bad.toml"), "{err}");
    let (ok, _, err) = run(&["analyze", "--job", "/nonexistent/job.toml"]);
    assert!(!ok && err.contains("/nonexistent/job.toml"), "{err}");
}

#[test]
fn job_files_must_be_regular_files_and_devices_stay_devices() {
    // `--job /dev/zero` must not be read without bound nor a FIFO hang the command; `-o /dev/null`
    // must not replace /dev/null by a regular file (as root).
    let (ok, _, err) = run(&["analyze", "--job", "/dev/zero"]);
    assert!(!ok && err.contains("/dev/zero") && err.contains("regular file"), "{err}");
    let dir = tempfile::tempdir().expect("tempdir");
    let fifo = dir.path().join("job.fifo");
    assert!(Command::new("mkfifo").arg(&fifo).status().expect("mkfifo").success());
    let (ok, _, err) = run(&["analyze", "--job", fifo.to_str().expect("utf8")]);
    assert!(!ok && err.contains("regular file"), "{err}");
    let (ok, _, err) = run(&["export", "--dialect", "linuxcnc", "-o", "/dev/null"]);
    assert!(ok, "{err}");
    assert!(!std::fs::metadata("/dev/null").expect("meta").is_file(), "/dev/null is still a device");
    // the longest legal file name (255 bytes) is written
    let long = dir.path().join(format!("{}.ngc", "p".repeat(251)));
    let (ok, _, err) = run(&["export", "--dialect", "linuxcnc", "-o", long.to_str().expect("utf8")]);
    assert!(ok && long.is_file(), "{err}");
}

#[test]
fn series_csv_is_written_whole_or_not_at_all() {
    let dir = tempfile::tempdir().expect("tempdir");
    let csv = dir.path().join("series.csv");
    let v = json(&["analyze", "--series", csv.to_str().expect("utf8")]);
    let text = std::fs::read_to_string(&csv).expect("written");
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("time_s,h_mm,engagement_deg,cutting,s_mm,x_mm,y_mm"));
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|c| c.parse().expect("number")).collect()).collect();
    // One steady-state cycle of teeth spaced f_z: floor(cycle length / f_z) + 1 rows.
    let expected = (v["cycle_length_mm"].as_f64().expect("len") / 0.075).floor() as usize + 1;
    assert_eq!(rows.len(), expected);
    let h_max = rows.iter().map(|r| r[1]).fold(0.0, f64::max);
    assert!((h_max - v["h_max_mm"].as_f64().expect("h")).abs() < 1e-6);
    // Unwritable path: error, exit non-zero, nothing left behind.
    let (ok, _, err) = run(&["analyze", "--series", "/proc/not-writable/series.csv"]);
    assert!(!ok && err.contains("series.csv"), "{err}");
}

#[test]
fn pocket_medial_axis_prints_circles_axis_and_engagement_by_move() {
    // 60 × 40 rectangle, D 10: perforative trochoids along the medial axis; the JSON carries
    // the circles, the axis, the per-move maxima and the whole path.
    let dir = tempfile::tempdir().unwrap();
    let poly = dir.path().join("rect.txt");
    std::fs::write(&poly, "0,0\n60,0\n60,40\n0,40\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_trochoplan"))
        .args(["pocket", "--method", "medial-axis", "--step-over", "1.5", "--polygon", poly.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["method"], "medial-axis");
    assert!(v["circle_count"].as_u64().unwrap() > 20);
    assert_eq!(v["circles"].as_array().unwrap().len() as u64, v["circle_count"].as_u64().unwrap());
    // The 60 × 40 rectangle's axis: four corner branches and the spine.
    assert_eq!(v["axis"].as_array().unwrap().len(), 5);
    let target = v["target_deg"].as_f64().unwrap();
    assert!(v["body_max_engagement_deg"].as_f64().unwrap() <= target + 1.0, "{}", v["body_max_engagement_deg"]);
    // the peak over everything at depth includes the corner-point arcs (no straight
    // tips into the corner point), within the target + 1° too
    let peak = v["max_engagement_deg"].as_f64().unwrap();
    assert!(peak >= v["body_max_engagement_deg"].as_f64().unwrap() && peak <= target + 1.0, "{peak}");
    assert_eq!(v["helices"].as_array().unwrap().len(), 1, "a helix, no plunge");
    assert_eq!(v["corner_points"].as_array().unwrap().len(), 4);
    let kinds: Vec<&str> = v["by_kind"].as_array().unwrap().iter().map(|m| m["kind"].as_str().unwrap()).collect();
    assert!(!kinds.contains(&"tip"), "{kinds:?}");
    for k in ["entry", "spiral", "circle", "link", "corner-point", "return"] {
        assert!(kinds.contains(&k), "{k} missing: {kinds:?}");
    }
    assert_eq!(v["segments"].as_array().unwrap().len(), v["kinds"].as_array().unwrap().len());
}

/// The force, PI and imprint keys; PI is null without `--ra-um` and
/// PI-without-Ra divided by Ra with it (eq. 7); the force-series CSV has one row per spindle
/// step ≤ 1° over the cycle (t_cycle·n/60·360 steps).
#[test]
fn analyze_reports_forces_pi_and_imprints() {
    let v = json(&["analyze"]);
    for k in [
        "force_resultant_max_n",
        "force_resultant_mean_n",
        "t_force_max_share",
        "torque_max_nm",
        "power_max_w",
        "performance_index_without_ra",
        "imprint_density_mean_per_mm",
    ] {
        assert!(v[k].as_f64().is_some_and(|x| x.is_finite() && x > 0.0), "{k}: {v}");
    }
    assert!(v["performance_index"].is_null(), "{v}");
    assert_eq!(v["material"], "p20");
    let dir = tempfile::tempdir().expect("tempdir");
    let csv = dir.path().join("forces.csv");
    let w = json(&["analyze", "--ra-um", "0.5", "--force-series", csv.to_str().expect("utf8")]);
    let pi = w["performance_index"].as_f64().expect("PI with Ra");
    assert!((pi - 2.0 * w["performance_index_without_ra"].as_f64().expect("PI")).abs() < 1e-9 * pi);
    let text = std::fs::read_to_string(&csv).expect("written");
    let rows = text.lines().count() - 1;
    let steps = (w["t_cycle_s"].as_f64().expect("t") * 2000.0 / 60.0 * 360.0).ceil() as usize;
    assert_eq!(rows, steps, "one row per 1° spindle step");
    assert!(text.starts_with("time_s,fx_n,fy_n,fz_n,f_r_n,torque_nm,cutting\n"));
    // Material and helix flags change the forces; a softer material lowers the peak.
    let al = json(&["analyze", "--material", "al-6061-t6"]);
    assert!(al["force_resultant_max_n"].as_f64() < v["force_resultant_max_n"].as_f64());
    let (ok, _, err) = run(&["analyze", "--material", "unobtainium"]);
    assert!(!ok && err.contains("material") && err.contains("p20"), "{err}");
    let (ok, _, err) = run(&["analyze", "--helix-angle", "75"]);
    assert!(!ok && err.contains("helix-angle") && err.contains("60"), "{err}");
    let (ok, _, err) = run(&["analyze", "--ra-um", "-1"]);
    assert!(!ok && err.contains("ra-um"), "{err}");
}

/// `calibrate` inverts the edge-force model's full-slot means (docs/process-model.md): slot tests
/// made from the p20 set by the closed form
/// (F̄x = −N·a_p·Krc·f_z/4 − N·a_p·Kre/π etc., computed here) give the set back; fewer than two
/// feeds is refused naming the file's flag.
#[test]
fn calibrate_recovers_the_coefficients_of_slot_tests() {
    let (n, ap) = (4.0, 6.0);
    let pi = std::f64::consts::PI;
    let mut text = String::from("f_z,fx,fy,fz\n");
    for fz in [0.05, 0.1, 0.15] {
        let fx = -n * ap * 960.0 * fz / 4.0 - n * ap * 35.0 / pi;
        let fy = n * ap * 2400.0 * fz / 4.0 + n * ap * 35.0 / pi;
        let fzz = n * ap * 360.0 * fz / pi + n * ap * 5.0 / 2.0;
        text.push_str(&format!("{fz},{fx},{fy},{fzz}\n"));
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let f = dir.path().join("slot.csv");
    std::fs::write(&f, &text).expect("write");
    let v = json(&["calibrate", "--slot-forces", f.to_str().expect("utf8")]);
    for (k, want) in [("ktc", 2400.0), ("krc", 960.0), ("kac", 360.0), ("kte", 35.0), ("kre", 35.0), ("kae", 5.0)] {
        let got = v[k].as_f64().expect(k);
        assert!((got - want).abs() < 1e-6 * want, "{k}: {got} vs {want}");
    }
    assert!(v["rms_residual_n"]["fy"].as_f64().is_some_and(|r| r < 1e-6));
    std::fs::write(&f, "f_z,fx,fy,fz\n0.1,-800,1500,280\n0.1,-810,1490,281\n").expect("write");
    let (ok, _, err) = run(&["calibrate", "--slot-forces", f.to_str().expect("utf8")]);
    assert!(!ok && err.contains("slot-forces") && err.contains("different feeds"), "{err}");
}

/// `--machine` and the real-time keys; `optimize` prints a job that `analyze --job`
/// reproduces and writes its front; contradictory limits name the tightest one.
#[test]
fn machine_and_optimize() {
    // 3000 mm/min on the hobby router (400 mm/s²): the loops run slower than programmed.
    let v = json(&["analyze", "--machine", "hobby-router", "--feed", "3000", "--rpm", "10000"]);
    assert_eq!(v["machine"], "hobby-router");
    let (t, t_real) = (v["t_cycle_s"].as_f64().expect("t"), v["t_cycle_real_s"].as_f64().expect("t real"));
    assert!(t_real > 1.1 * t, "{t} {t_real}");
    for k in ["machining_time_real_s", "mrr_real_mm3_per_min", "feed_held_share"] {
        assert!(v[k].as_f64().is_some_and(f64::is_finite), "{k}: {v}");
    }
    let (ok, _, err) = run(&["analyze", "--machine", "lathe"]);
    assert!(!ok && err.contains("machine") && err.contains("vmc"), "{err}");

    let dir = tempfile::tempdir().expect("tempdir");
    let front = dir.path().join("front.csv");
    let front_arg = front.to_str().expect("utf-8");
    let (ok, toml, err) = run(&[
        "optimize",
        "--max-hmax",
        "0.075",
        "--max-engagement",
        "57.5",
        "--machine",
        "vmc",
        "--slot-length",
        "60",
        "--front",
        front_arg,
    ]);
    assert!(ok, "{err}");
    let job_file = dir.path().join("best.toml");
    std::fs::write(&job_file, &toml).expect("write");
    let v = json(&["analyze", "--job", job_file.to_str().expect("utf-8")]);
    // The printed figures are the job's own (comment line "real MRR … mm³/min").
    let mrr = v["mrr_real_mm3_per_min"].as_f64().expect("mrr");
    assert!(toml.contains(&format!("real MRR {mrr:.0} mm³/min")), "{toml}\n{mrr}");
    // And its time with the variable feed is analyze's (the optimiser vs FreeCAD table of
    // docs/process-model.md).
    let vf = json(&["analyze", "--job", job_file.to_str().expect("utf-8"), "--variable-feed"]);
    let t_vf = vf["machining_time_real_variable_feed_s"].as_f64().expect("t vf");
    assert!(toml.contains(&format!("with --variable-feed: real machining time {t_vf:.1} s")), "{toml}\n{t_vf}");
    assert!(v["h_max_mm"].as_f64().expect("h") <= 0.075 && v["engagement_max_deg"].as_f64().expect("a") <= 57.5);
    assert_eq!(v["machine"], "vmc");
    let csv = std::fs::read_to_string(&front).expect("front written");
    assert!(csv.starts_with("path,aspect_ratio,") && csv.lines().count() >= 3, "{csv}");

    let (ok, _, err) = run(&["optimize", "--max-hmax", "0.075", "--max-engagement", "0.01"]);
    assert!(!ok && err.contains("max-engagement") && err.contains("tightest"), "{err}");
    let (ok, _, err) = run(&["optimize", "--max-hmax", "-1", "--max-engagement", "50"]);
    assert!(!ok && err.contains("max-hmax"), "{err}");
    let (ok, _, err) = run(&["optimize", "--max-hmax", "0.075", "--max-engagement", "50", "--max-force", "-3"]);
    assert!(!ok && err.contains("max-force"), "{err}");
    assert!(csv.lines().next().is_some_and(|h| h.ends_with("force_resultant_max_n,front")), "{csv}");
    assert!(csv.lines().skip(1).any(|l| l.ends_with(",force")) && csv.lines().any(|l| l.ends_with(",waviness")));

    // Pockets: the real time at depth on a machine is at least the programmed one.
    let poly = dir.path().join("rect.csv");
    std::fs::write(&poly, "0,0\n60,0\n60,40\n0,40\n").expect("write");
    let p = poly.to_str().expect("utf-8");
    let ideal = json(&["pocket", "--polygon", p, "--feed", "3000", "--method", "plain"]);
    let slow = json(&["pocket", "--polygon", p, "--feed", "3000", "--method", "plain", "--machine", "hobby-router"]);
    let fast = json(&["pocket", "--polygon", p, "--feed", "3000", "--method", "plain", "--machine", "hsc"]);
    let at_feed = ideal["path_length_mm"].as_f64().expect("length") / 50.0;
    let (t_slow, t_fast) = (slow["time_real_s"].as_f64().expect("t"), fast["time_real_s"].as_f64().expect("t"));
    assert!(t_slow > t_fast && t_fast > at_feed, "{t_slow} {t_fast} {at_feed}");
    assert!(slow["feed_held_share"].as_f64().expect("share") < fast["feed_held_share"].as_f64().expect("share"));
}

/// `-` and `/dev/stdout` are the standard output for every output flag; the report then goes
/// to stderr, so each stream holds one whole thing. No file named "-" is made.
#[test]
fn dash_and_dev_stdout_write_to_the_standard_output() {
    let dir = tempfile::tempdir().expect("tempdir");
    let in_dir = |args: &[&str]| {
        let out =
            Command::new(env!("CARGO_BIN_EXE_trochoplan")).args(args).current_dir(dir.path()).output().expect("run");
        (
            out.status.success(),
            String::from_utf8_lossy(&out.stdout).into_owned(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    for target in ["-", "/dev/stdout"] {
        let (ok, out, err) = in_dir(&["export", "--dialect", "grbl", "-o", target]);
        assert!(ok, "{err}");
        assert!(out.starts_with("(TrochoPlan") && out.trim_end().ends_with("M30"), "the program on stdout");
        assert!(err.contains("grbl program") && err.contains(&format!("{} bytes", out.len())), "{err}");
        let (ok, out, err) = in_dir(&["analyze", "--series", target]);
        assert!(ok, "{err}");
        assert!(out.starts_with("time_s,h_mm,"), "the series on stdout: {}", &out[..40.min(out.len())]);
        let v: serde_json::Value = serde_json::from_str(&err).expect("the JSON report on stderr");
        assert!(v["h_max_mm"].is_number());
    }
    let (ok, out, err) = in_dir(&["optimize", "--max-hmax", "0.075", "--max-engagement", "57.5", "--front", "-"]);
    assert!(ok && out.starts_with("path,aspect_ratio,") && err.contains("slot-width"), "{err}");
    assert_eq!(std::fs::read_dir(dir.path()).expect("dir").count(), 0, "no file named - and no temporary file");
}

/// An output that is one of the inputs, or two outputs that are one file, are refused before
/// any work, naming both flags; the input is left as it was.
#[test]
fn outputs_that_are_inputs_or_each_other_are_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let p = |name: &str| dir.path().join(name).to_str().expect("utf8").to_owned();
    let polygon = p("in.txt");
    std::fs::write(&polygon, "0,0\n50,0\n50,30\n0,30\n").expect("write");
    let job = p("job.toml");
    std::fs::write(&job, "feed = 600\n").expect("write");
    let same_polygon = format!("{}/./in.txt", dir.path().display());
    let (series, series2) = (p("s.csv"), format!("{}/./s.csv", dir.path().display()));
    let cases: [(Vec<&str>, [&str; 2]); 6] = [
        (vec!["pocket", "--polygon", &polygon, "--export", &same_polygon], ["--polygon", "--export"]),
        (vec!["export", "--dialect", "grbl", "--job", &job, "-o", &job], ["--job", "--output"]),
        (vec!["analyze", "--job", &job, "--series", &job], ["--job", "--series"]),
        (vec!["analyze", "--materials", &job, "--force-series", &job], ["--materials", "--force-series"]),
        (vec!["analyze", "--series", &series, "--force-series", &series2], ["--series", "--force-series"]),
        (vec!["analyze", "--series", "-", "--force-series", "/dev/stdout"], ["--series", "--force-series"]),
    ];
    for (args, flags) in cases {
        let (ok, out, err) = run(&args);
        assert!(!ok && out.is_empty(), "{args:?} must fail");
        assert!(flags.iter().all(|f| err.contains(f)), "{args:?}: {err}");
    }
    assert_eq!(std::fs::read_to_string(&polygon).expect("read"), "0,0\n50,0\n50,30\n0,30\n");
    assert_eq!(std::fs::read_to_string(&job).expect("read"), "feed = 600\n");
    assert!(!dir.path().join("s.csv").exists());
}

/// A replaced output keeps its mode; a read-only one is refused by name and left whole; a
/// temporary file of a process no longer alive (a SIGKILL during a large export) is removed by
/// the next write into its folder.
#[test]
fn replaced_outputs_keep_their_mode_and_stale_temporaries_are_cleaned() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("slot.ngc");
    let f = file.to_str().expect("utf8");
    std::fs::write(&file, "old\n").expect("write");
    std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o640)).expect("chmod");
    let mut child = Command::new("true").spawn().expect("spawn");
    let dead = child.id();
    child.wait().expect("wait"); // its PID now names no process
    let stale = dir.path().join(format!(".slot.ngc.trochoplan-tmp-{dead}-0"));
    std::fs::write(&stale, "half a program").expect("write");
    let (ok, _, err) = run(&["export", "--dialect", "linuxcnc", "-o", f]);
    assert!(ok, "{err}");
    let meta = std::fs::metadata(&file).expect("meta");
    assert_eq!(meta.permissions().mode() & 0o7777, 0o640);
    assert!(std::fs::read_to_string(&file).expect("read").contains("M30"));
    assert!(!stale.exists(), "stale temporary file removed");
    std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o444)).expect("chmod");
    let before = std::fs::read_to_string(&file).expect("read");
    let (ok, _, err) = run(&["export", "--dialect", "grbl", "-o", f]);
    assert!(!ok && err.contains("slot.ngc") && err.contains("read-only (mode 0444)"), "{err}");
    assert_eq!(std::fs::read_to_string(&file).expect("read"), before);
    assert_eq!(std::fs::read_dir(dir.path()).expect("dir").count(), 1, "only the program");
}

/// SIGTERM, SIGINT and SIGHUP end the process through its clean-up (exit status 128 + the
/// signal's number, 143 for SIGTERM, as a shell reports it), not by the default action that
/// would leave a temporary file. `optimize` runs for seconds: the signal comes mid-work.
#[test]
fn termination_signals_go_through_the_clean_up() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (sig, code) in [("TERM", 143), ("INT", 130), ("HUP", 129)] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_trochoplan"))
            .args(["optimize", "--max-hmax", "0.075", "--max-engagement", "57.5", "--front", "front.csv"])
            .current_dir(dir.path())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .expect("spawn");
        std::thread::sleep(std::time::Duration::from_millis(500));
        let killed = Command::new("kill").args([&format!("-{sig}"), &child.id().to_string()]).status().expect("kill");
        assert!(killed.success());
        let status = child.wait().expect("wait");
        assert_eq!(status.code(), Some(code), "SIG{sig}: {status:?}");
    }
    assert_eq!(std::fs::read_dir(dir.path()).expect("dir").count(), 0, "nothing left behind");
}

/// `--open-edges -1` is not taken for an unknown flag: the index is named with its range.
#[test]
fn a_negative_open_edge_names_open_edges_and_its_range() {
    let dir = tempfile::tempdir().expect("tempdir");
    let polygon = dir.path().join("p.txt");
    std::fs::write(&polygon, "0,0\n50,0\n50,30\n0,30\n").expect("write");
    let p = polygon.to_str().expect("utf8");
    for v in ["-1", "1,-2"] {
        let (ok, _, err) = run(&["pocket", "--polygon", p, "--open-edges", v]);
        assert!(!ok && !err.contains("unexpected argument"), "{err}");
        assert!(err.contains("invalid open-edges = -") && err.contains("an edge of the polygon, 0 to"), "{err}");
    }
    // past the last edge: the core's own check, with the polygon's range (4 edges: 0 to 3)
    let (ok, _, err) = run(&["pocket", "--polygon", p, "--open-edges", "9"]);
    assert!(!ok && err.contains("invalid open-edges = 9: must be an edge of the polygon, 0 to 3"), "{err}");
}

/// Inputs that drive work have limits checked before the work, named with the limit.
#[test]
fn work_is_bounded_before_it_starts() {
    let dir = tempfile::tempdir().expect("tempdir");
    // 201 sweep values, one over the limit of 200
    fails_with(
        &["sweep", "--param", "step", "--from", "0.5", "--to", "1", "--steps", "201"],
        "invalid steps = 201: must be a whole number from 1 to 200",
    );
    // a_p ≤ 5·D: 5 · 10 mm (the default tool) = 50 mm
    fails_with(
        &["optimize", "--depth", "1e4", "--max-hmax", "0.1", "--max-engagement", "60"],
        "invalid depth = 10000: must be from 0.01 to 5·D = 50 mm (the deepest cut of a tool 10 mm across)",
    );
    // a library over 1 MiB (1 048 576 bytes): 10 000 entries of 13 + 16 + 12 + 13 + 12 + 12 + 11
    // + 11 + 10 = 110 bytes (one per line) are 1 100 000 bytes
    let lib = dir.path().join("lib.toml");
    let entry = |i: usize| {
        format!(
            "[[material]]\nname = \"m{i:05}\"\nlabel = \"x\"\nktc = 2400.0\nkrc = 960.0\nkac = 360.0\nkte = 35.0\nkre = 35.0\nkae = 5.0\n"
        )
    };
    assert_eq!(entry(0).len(), 110);
    std::fs::write(&lib, (0..10_000).map(entry).collect::<String>()).expect("write");
    let (ok, _, err) = run(&["analyze", "--materials", lib.to_str().expect("utf8")]);
    assert!(!ok && err.contains("invalid materials") && err.contains("at most 1048576 bytes"), "{err}");
    // 1001 slot tests, one over the limit of 1000
    let csv = dir.path().join("slot.csv");
    let rows: String = (0..1001).map(|i| format!("{},100,200,30\n", 0.01 + 1e-5 * f64::from(i))).collect();
    std::fs::write(&csv, format!("f_z,fx,fy,fz\n{rows}")).expect("write");
    let (ok, _, err) = run(&["calibrate", "--slot-forces", csv.to_str().expect("utf8")]);
    assert!(!ok && err.contains("invalid slot-forces") && err.contains("at most 1000 tests"), "{err}");
}

/// A reader that stops early (`trochoplan … | head -c 1`) closes the pipe: the report is cut
/// short, but the process neither panics nor reports an error.
#[test]
fn a_reader_closing_the_pipe_early_is_not_a_panic() {
    use std::io::Read;
    use std::process::Stdio;
    // a pocket report (about 90 kB) is larger than a pipe's buffer (64 kB on Linux), so the
    // writer meets the closed pipe rather than finishing into the buffer
    let dir = tempfile::tempdir().expect("tempdir");
    let polygon = dir.path().join("rect.txt");
    std::fs::write(&polygon, "0,0\n60,0\n60,40\n0,40\n").expect("write");
    let mut child = Command::new(env!("CARGO_BIN_EXE_trochoplan"))
        .args(["pocket", "--polygon", polygon.to_str().expect("utf-8"), "--step-over", "1.527"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("binary runs");
    let mut first = [0u8; 1];
    child.stdout.take().expect("stdout").read_exact(&mut first).ok();
    // the read end is dropped here: every later write of the report meets a closed pipe
    let mut stderr = String::new();
    child.stderr.take().expect("stderr").read_to_string(&mut stderr).expect("stderr");
    let status = child.wait().expect("wait");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(status.success(), "exit {status:?}: {stderr}");
}

/// A sweep's work is estimated before any value is planned. With 64 teeth at 20 000 rpm the
/// default slot holds 31.424 mm / (600/(20000·64) mm) = 67 038 tooth positions a cycle at
/// step 1 (the most of the values 0.5–1), so a plan is at both caps of the estimate (core
/// `sweep::plan_cost_ms`): 4096 positions × 0.0124 ms + 400 000 force pairs × 19/400 000 ms =
/// 69.79 ms, plus 10 ms × log2(67 038/4096) = 40.33 ms, × 1.15 = 126.6 ms; 5000 ms of budget /
/// 126.6 ms = 39.5, so 39 values are planned and 40 refused at once.
#[test]
fn a_sweep_of_costly_plans_is_refused_before_the_work_naming_steps_and_the_limit() {
    let args = |steps: &'static str| {
        ["sweep", "--teeth", "64", "--rpm", "20000", "--param", "step", "--from", "0.5", "--to", "1", "--steps", steps]
    };
    let started = std::time::Instant::now();
    let (ok, out, err) = run(&args("40"));
    assert!(!ok && out.is_empty(), "{out}");
    assert!(
        err.starts_with("trochoplan: invalid steps = 40: must be at most 39 for this job")
            && err.contains("126.6 ms")
            && err.contains("at most 5000 ms of estimated work"),
        "{err}"
    );
    // refused before any plan: far below one plan's time
    assert!(started.elapsed().as_secs_f64() < 1.0);
    let (ok, out, err) = run(&args("39"));
    assert!(ok, "{err}");
    assert_eq!(out.lines().count(), 1 + 39);
}

/// The chords of `export --linear-segments` are counted from the curvature before fitting.
/// The largest slot of the allowed ranges (B 100 000, D 50 000, r_e 3: a = 12 500, b = 37 500)
/// at step 1000 has 202 cycles (as `analyze` reports); its cycle needs about 43 770 chords at
/// 1e-4 mm (the writer fits 43 769, from its own refusal message without this check), so
/// 202 × 43 770 = 8.8 million blocks, over the 4 000 000 a program may have by more than the
/// estimate's 25 % margin: refused at once, naming the tolerance, and no file written.
#[test]
fn a_chord_program_over_the_block_limit_is_refused_before_fitting_naming_the_tolerance() {
    let dir = tempfile::tempdir().expect("tempdir");
    let nc = dir.path().join("big.ngc");
    let nc_path = nc.to_str().expect("utf8");
    let job = [
        "--slot-width",
        "100000",
        "--tool-diameter",
        "50000",
        "--slot-length",
        "100000",
        "--path",
        "elliptical",
        "--aspect-ratio",
        "3",
        "--step",
        "1000",
        "--linear-segments",
        "--tolerance",
        "1e-4",
        "-o",
        nc_path,
    ];
    let started = std::time::Instant::now();
    let (ok, out, err) = run(&[&["export", "--dialect", "linuxcnc"][..], &job].concat());
    assert!(!ok && out.is_empty(), "{out}");
    assert!(err.starts_with("trochoplan: invalid tolerance = 0.0001: must be at least about"), "{err}");
    assert!(err.contains("202 cycles") && err.contains("more than the 4000000 a program may have"), "{err}");
    assert!(started.elapsed().as_secs_f64() < 1.0, "fitted before refusing");
    assert!(!nc.exists());
    // the loop form, which the message offers, writes one cycle
    let (ok, _, err) = run(&[&["export", "--dialect", "linuxcnc", "--compact"][..], &job].concat());
    assert!(ok, "{err}");
}
