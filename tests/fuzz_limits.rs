//! Inputs that drive work and outputs that could go wrong, fuzzed: drawings, outlines, options
//! and libraries far past every limit (their sizes drawn by a fixed-seed generator) must give a
//! result or a clear refusal naming the parameter within [`TIME_LIMIT`] and [`MEMORY_LIMIT`];
//! messages name what the user gave; outputs to the standard output, onto an input or twice
//! onto one file behave as the README says. CI runs every case, so a new unbounded input shows
//! as a failure here rather than as a hang on a user's machine.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;
mod pocket_common;

use pocket_common::Rng;
use std::f64::consts::TAU;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The longest a refusal or a bounded result may take (whole process, wall time).
const TIME_LIMIT: Duration = Duration::from_secs(5);
/// The most memory one run may use (peak resident set, kB).
const MEMORY_LIMIT_KB: u64 = 500 * 1024;

/// What one run did: exit code, standard error, peak memory (kB) and wall time.
struct Outcome {
    code: i32,
    stdout: Vec<u8>,
    stderr: String,
    peak_kb: u64,
    elapsed: Duration,
}

/// The peak resident set (VmHWM, kB) of a running process, read from /proc.
fn peak_kb(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Run the binary in `dir`, polling its peak memory; killed (and the test failed) past twice
/// the time limit, so a hang cannot stall CI.
fn run(dir: &Path, label: &str, args: &[&str]) -> Outcome {
    let (out, err) = (dir.join(format!("{label}.out")), dir.join(format!("{label}.err")));
    let start = Instant::now();
    // the shell caps the data segment (heap and anonymous mappings) at the memory limit: a run
    // that allocates past it aborts, which fails the test as a signal; the polled peak below
    // reports what a slower run used
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -d {MEMORY_LIMIT_KB} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_trochoplan"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out).expect("stdout file"))
        .stderr(std::fs::File::create(&err).expect("stderr file"))
        .spawn()
        .expect("run trochoplan");
    let mut peak = 0;
    let status = loop {
        if let Some(kb) = peak_kb(child.id()) {
            peak = peak.max(kb);
        }
        if let Some(s) = child.try_wait().expect("wait") {
            break s;
        }
        if start.elapsed() > 2 * TIME_LIMIT {
            let _ = child.kill();
            panic!("{label}: still running after {:?}: trochoplan {args:?}", 2 * TIME_LIMIT);
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let o = Outcome {
        code: status.code().unwrap_or_else(|| panic!("{label}: killed by a signal")),
        stdout: std::fs::read(out).expect("stdout"),
        stderr: std::fs::read_to_string(err).expect("stderr"),
        peak_kb: peak,
        elapsed: start.elapsed(),
    };
    assert!(!o.stderr.contains("panicked"), "{label}: panic: {}", o.stderr);
    o
}

/// The run finished within the limits, and either succeeded or was refused (exit 2) with a
/// message that names one of `names`.
fn bounded(dir: &Path, label: &str, args: &[&str], names: &[&str]) -> Outcome {
    let o = run(dir, label, args);
    eprintln!("{label}: exit {} in {:.2} s, {} kB: {}", o.code, o.elapsed.as_secs_f64(), o.peak_kb, o.stderr.trim());
    assert!(o.elapsed <= TIME_LIMIT, "{label}: {:.2} s > {TIME_LIMIT:?}", o.elapsed.as_secs_f64());
    assert!(o.peak_kb <= MEMORY_LIMIT_KB, "{label}: {} kB > {MEMORY_LIMIT_KB} kB", o.peak_kb);
    assert!(o.code == 0 || o.code == 2, "{label}: exit {}: {}", o.code, o.stderr);
    if o.code == 2 {
        assert!(names.iter().any(|n| o.stderr.contains(n)), "{label}: refusal names none of {names:?}: {}", o.stderr);
    }
    o
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).expect("write");
    p.to_str().expect("utf-8").to_string()
}

/// Points of a circle of `n` vertices about (50, 50), radius 40, as "x,y" lines.
fn circle(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|k| (50.0 + 40.0 * (TAU * k as f64 / n as f64).cos(), 50.0 + 40.0 * (TAU * k as f64 / n as f64).sin()))
        .collect()
}

/// A DXF drawing with the given ENTITIES section body (and `$INSUNITS` mm).
fn dxf(entities: &str) -> String {
    format!(
        "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n{entities}0\nENDSEC\n0\nEOF\n"
    )
}

/// A closed LWPOLYLINE through `pts`, the bulge `bulge` on its second vertex.
fn lwpolyline(pts: &[(f64, f64)], bulge: &str) -> String {
    let mut s = format!("0\nLWPOLYLINE\n8\n0\n90\n{}\n70\n1\n", pts.len());
    for (i, (x, y)) in pts.iter().enumerate() {
        s.push_str(&format!("10\n{x}\n20\n{y}\n"));
        if i == 1 {
            s.push_str(&format!("42\n{bulge}\n"));
        }
    }
    s
}

const RECT: [(f64, f64); 4] = [(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)];

#[test]
fn work_past_every_limit_is_refused_in_time_and_memory() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path();
    let mut rng = Rng::new(20);
    let rect = write(dir, "rect.txt", "0,0\n60,0\n60,40\n0,40\n");
    // drawings: huge bulges and arcs, too many vertices or entities
    for (k, bulge) in ["inf", "-inf", "NaN", &format!("{:e}", rng.log_range(1e6, 1e12))].iter().enumerate() {
        let f = write(dir, &format!("bulge{k}.dxf"), &dxf(&lwpolyline(&RECT, bulge)));
        bounded(dir, &format!("bulge {bulge}"), &["pocket", "--polygon", &f], &["bulge", "vertices"]);
    }
    let r = format!("{:e}", rng.log_range(1e9, 1e14));
    let svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M 0 0 L 60 0 A {r} {r} 0 1 1 60 40 L 0 40 Z\"/></svg>"
    );
    bounded(dir, "svg arc", &["pocket", "--polygon", &write(dir, "arc.svg", &svg)], &["vertices"]);
    let n = 20_001 + rng.below(200_000);
    let pts = circle(n);
    let points: Vec<String> = pts.iter().map(|(x, y)| format!("{x:.6},{y:.6}")).collect();
    let svg = format!("<svg xmlns=\"http://www.w3.org/2000/svg\"><polygon points=\"{}\"/></svg>", points.join(" "));
    bounded(dir, "svg vertices", &["pocket", "--polygon", &write(dir, "many.svg", &svg)], &["vertices"]);
    let dxf_many = dxf(&lwpolyline(&pts, "0"));
    bounded(dir, "dxf vertices", &["pocket", "--polygon", &write(dir, "many.dxf", &dxf_many)], &["vertices"]);
    bounded(
        dir,
        "text vertices",
        &["pocket", "--polygon", &write(dir, "many.txt", &points.join("\n"))],
        &["vertices", "points"],
    );
    let lines: String = (0..n.min(40_000))
        .map(|k| {
            let (a, b) = (pts[k], pts[(k + 1) % n]);
            format!("0\nLINE\n8\n0\n10\n{}\n20\n{}\n11\n{}\n21\n{}\n", a.0, a.1, b.0, b.1)
        })
        .collect();
    bounded(
        dir,
        "dxf lines",
        &["pocket", "--polygon", &write(dir, "lines.dxf", &dxf(&lines))],
        &["vertices", "chain", "loop"],
    );
    // pocket planners: many vertices, a tiny helix, a tiny step-over
    let n = 1001 + rng.below(5000);
    let ring: Vec<String> = circle(n).iter().map(|(x, y)| format!("{x:.6},{y:.6}")).collect();
    let ring = write(dir, "ring.txt", &ring.join("\n"));
    for method in ["plain", "variable", "isometric", "adaptive", "medial-axis"] {
        bounded(dir, &format!("{n}-gon {method}"), &["pocket", "--polygon", &ring, "--method", method], &["polygon"]);
    }
    let helix = format!("{:e}", rng.log_range(1e-12, 1e-3));
    bounded(
        dir,
        "tiny helix",
        &["pocket", "--polygon", &rect, "--method", "medial-axis", "--helix-radius", &helix],
        &["helix-radius"],
    );
    let step = format!("{:e}", rng.log_range(1e-12, 1e-3));
    for method in ["variable", "isometric", "plain"] {
        bounded(
            dir,
            &format!("corner step {method}"),
            &["corner", "--method", method, "--step-over", &step],
            &["step-over"],
        );
        bounded(
            dir,
            &format!("pocket step {method}"),
            &["pocket", "--polygon", &rect, "--method", method, "--step-over", &step],
            &["step-over"],
        );
    }
    // slot commands: depth, sweep steps, library size
    let depth = format!("{}", rng.log_range(60.0, 1e6));
    bounded(
        dir,
        "optimize depth",
        &["optimize", "--max-hmax", "0.075", "--max-engagement", "57.5", "--depth", &depth],
        &["depth"],
    );
    let steps = format!("{}", 201 + rng.below(100_000));
    bounded(
        dir,
        "sweep steps",
        &["sweep", "--param", "aspect-ratio", "--from", "0.5", "--to", "1.2", "--steps", &steps],
        &["steps"],
    );
    let entries = 10_001 + rng.below(100_000);
    let library: String = (0..entries)
        .map(|i| {
            format!(
                "[[material]]\nname = \"m{i}\"\nlabel = \"m\"\nktc = 1.7e3\nkrc = 6e2\nkac = 3e2\nkte = 20.0\nkre = 25.0\nkae = 2.0\n"
            )
        })
        .collect();
    bounded(dir, "library", &["analyze", "--materials", &write(dir, "lib.toml", &library)], &["materials"]);
}

#[test]
fn messages_name_what_the_user_gave_and_outputs_go_where_they_are_told() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path();
    let mut rng = Rng::new(21);
    // a vast outline is refused for its size, not with an infinite step-over
    let big = format!("{:e}", rng.log_range(1e7, 1e300));
    let f = write(dir, "big.txt", &format!("0,0\n{big},0\n{big},{big}\n0,{big}\n"));
    let o = bounded(dir, "vast outline", &["pocket", "--polygon", &f], &["coordinates", "polygon"]);
    assert!(o.code == 2 && !o.stderr.contains("inf"), "{}", o.stderr);
    // a negative edge number is the core's message, not clap's "unexpected argument"
    let edge = format!("-{}", 1 + rng.below(9));
    let rect = write(dir, "rect.txt", "0,0\n60,0\n60,40\n0,40\n");
    let o = bounded(dir, "negative edge", &["pocket", "--polygon", &rect, "--open-edges", &edge], &["open-edges"]);
    assert!(o.code == 2 && !o.stderr.contains("unexpected argument"), "{}", o.stderr);
    // a bad number in a drawing is quoted
    let bad = format!("{}x{}", rng.below(60), rng.below(10));
    let svg = format!("<svg xmlns=\"http://www.w3.org/2000/svg\"><polygon points=\"0,0 60,0 60,{bad} 0,40\"/></svg>");
    let o = bounded(dir, "bad svg number", &["pocket", "--polygon", &write(dir, "bad.svg", &svg)], &["number"]);
    assert!(o.code == 2 && o.stderr.contains(&bad), "{}", o.stderr);
    // a refusal for the step-over names the spacing as the default the user did not give
    let o = bounded(dir, "small step-over", &["pocket", "--polygon", &rect, "--step-over", "0.01"], &["step-over"]);
    assert!(o.code == 2 && o.stderr.contains("default"), "{}", o.stderr);
    // `-` and /dev/stdout are the standard output; the report then goes to stderr
    for out in ["-", "/dev/stdout"] {
        let o = bounded(dir, "stdout", &["export", "--dialect", "linuxcnc", "-o", out], &[]);
        assert_eq!(o.code, 0, "{}", o.stderr);
        assert!(String::from_utf8_lossy(&o.stdout).contains("M30"), "{out}: no program on stdout");
        assert!(!dir.join("-").exists(), "a file named - was written");
    }
    // an output onto an input, or two outputs onto one file
    let o = bounded(dir, "onto input", &["pocket", "--polygon", &rect, "--export", &rect], &["--polygon"]);
    assert_eq!(o.code, 2);
    assert_eq!(std::fs::read_to_string(&rect).expect("read"), "0,0\n60,0\n60,40\n0,40\n", "the input was replaced");
    let o = bounded(dir, "same output", &["analyze", "--series", "x.csv", "--force-series", "./x.csv"], &["--series"]);
    assert!(o.code == 2 && !dir.join("x.csv").exists(), "{}", o.stderr);
    // a replaced file keeps its mode
    use std::os::unix::fs::PermissionsExt;
    let nc = dir.join("keep.ngc");
    std::fs::write(&nc, "old").expect("write");
    let mode = [0o640, 0o600, 0o664][rng.below(3)];
    std::fs::set_permissions(&nc, std::fs::Permissions::from_mode(mode)).expect("chmod");
    let o = bounded(dir, "mode", &["export", "--dialect", "linuxcnc", "-o", "keep.ngc"], &[]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert_eq!(std::fs::metadata(&nc).expect("meta").permissions().mode() & 0o777, mode);
    // no temporary file is left behind by any of the runs above
    let left: Vec<_> = std::fs::read_dir(dir)
        .expect("dir")
        .filter_map(Result::ok)
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("tmp"))
        .collect();
    assert!(left.is_empty(), "temporary files left: {left:?}");
}
