//! `trochoplan verify` on the project's own programs agrees with their plans, and reads
//! FreeCAD's programs (docs/verify.md, "Acceptance").
//!
//! - **Slot**: `export --machine hobby-router` (the paper's Table 1 job, 32 cycles) verified over
//!   a stock box from the slot's face y = 0 to its length, against `analyze --machine
//!   hobby-router`: peak engagement within 0.5°, h_max within 1 % (verify's exact chip at the
//!   reached feed against the analysis's tooth-by-tooth chip), the time of the feed moves in
//!   the plane within 1 % of `machining_time_real_s` (the cycles' real time), the peak force,
//!   torque and power within 2 %.
//! - **Pocket**: `pocket --machine hobby-router --export` of the 60 × 40 rectangle (adaptive
//!   clearing, the pace that follows the chip) verified over its outline: peak engagement
//!   within 0.5° of the plan's `max_engagement_deg` over every move but the flat turn at depth
//!   after the helix (the plan measures that turn with the helix's bore cut; the program's
//!   helix is written in half turns, whose last one leaves a wedge 0.81 mm high that the turn
//!   cuts, which verify measures), h_max (the exact chip at the reached feed) within 1 % of the
//!   plan's `h_max_mm`, real time within 1 % of `time_real_s`.
//! - **Corner**: `corner --machine hobby-router --export` (90°, the variable method) verified
//!   over the corner's stock (the wedge of its walls less what the previous ring, one
//!   step-over further in, enclosed): peak engagement within 0.5° of `max_engagement_deg`,
//!   real time within 1 % of `time_real_s`.
//! - **FreeCAD**: the six programs of `tests/data/freecad/` with their outlines as stock and
//!   part run without error; their peaks, times and gouges are printed (the table of
//!   docs/verify.md): `cargo test --release --test verify_acceptance -- --nocapture`.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use serde_json::Value;
use std::path::Path;
use std::process::Command;

fn run(dir: &Path, args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_trochoplan")).args(args).current_dir(dir).output().expect("binary runs");
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).expect("utf-8")
}

fn json(text: &str) -> Value {
    serde_json::from_str(text).expect("json")
}

fn f(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} in {v}"))
}

/// The rows of a per-move CSV as (line, kind, z0, z1, time_s, engagement_deg).
fn csv_rows(path: &Path) -> Vec<(usize, String, f64, f64, f64, f64)> {
    let text = std::fs::read_to_string(path).expect("csv");
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().expect("header").split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).expect(name);
    let (l, k, z0, z1, t, e) = (col("line"), col("kind"), col("z0"), col("z1"), col("time_s"), col("engagement_deg"));
    lines
        .map(|row| {
            let c: Vec<&str> = row.split(',').collect();
            let n = |i: usize| c[i].parse::<f64>().expect("number");
            (c[l].parse().expect("line"), c[k].to_owned(), n(z0), n(z1), n(t), n(e))
        })
        .collect()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The slot program verified against `analyze` for the same job (`extra`: job flags).
/// Returns verify's problem kinds.
fn slot_case(d: &Path, extra: &[&'static str]) -> Vec<String> {
    let with = |args: &[&'static str]| [args, extra].concat();
    run(d, &with(&["export", "--machine", "hobby-router", "--dialect", "linuxcnc", "--output", "slot.ngc"]));
    let a = json(&run(d, &with(&["analyze", "--machine", "hobby-router"])));
    // the paper's Table 1 slot: B 20, L 20 from the face y = 0; the stock beyond the walls
    let v = json(&run(d, &["verify", "slot.ngc", "--stock-box=-30,0,30,20", "--machine", "hobby-router"]));
    let rows = [
        ("engagement (deg)", f(&v, "max_engagement_deg"), f(&a, "engagement_max_deg")),
        ("h_max (mm)", f(&v, "h_max_mm"), f(&a, "h_max_mm")),
        ("h_max at the programmed feed (mm)", f(&v, "h_max_programmed_mm"), f(&a, "h_max_programmed_mm")),
        ("time at feed (s)", f(&v, "time_at_feed_s"), f(&a, "machining_time_real_s")),
        ("F_R,max (N)", f(&v, "force_resultant_max_n"), f(&a, "force_resultant_max_n")),
        ("torque (N·m)", f(&v, "torque_max_nm"), f(&a, "torque_max_nm")),
        ("power (W)", f(&v, "power_max_w"), f(&a, "power_max_w")),
    ];
    for (name, ours, plan) in rows {
        println!("slot {extra:?} {name}: verify {ours:.6} plan {plan:.6} ({:+.3} %)", 100.0 * (ours - plan) / plan);
    }
    assert!((rows[0].1 - rows[0].2).abs() <= 0.5, "{rows:?}");
    for r in &rows[1..4] {
        assert!(rel(r.1, r.2) <= 0.01, "{r:?}");
    }
    for r in &rows[4..] {
        assert!(rel(r.1, r.2) <= 0.02, "{r:?}");
    }
    v["problems"].as_array().expect("problems").iter().filter_map(|p| p["kind"].as_str().map(str::to_owned)).collect()
}

#[test]
fn slot_agrees_with_analyze() {
    let dir = tempfile::tempdir().expect("tempdir");
    let kinds = slot_case(dir.path(), &[]);
    // no geometric problem; the job's 726 W and 3.47 N·m at 2000 rpm are above the hobby
    // router's 710 W and 0.68 N·m (its preset): power and torque problems, as they should be
    assert!(kinds.iter().any(|k| k == "power") && kinds.iter().any(|k| k == "torque"), "{kinds:?}");
    assert!(kinds.iter().all(|k| matches!(k.as_str(), "power" | "torque")), "{kinds:?}");
}

/// At 6000 mm/min and 20 000 rpm the hobby router (5000 mm/min at most, less on its arcs) never
/// reaches the programmed feed: the chip, forces, torque and power at the feed it reaches
/// agree between `analyze` (the tooth series scaled by the planned feed profile) and `verify`
/// (the program read back, its own feed planning and chip), and the programmed-feed chip
/// beside them agrees too.
#[test]
fn slot_at_a_feed_the_machine_cannot_reach_agrees_with_analyze() {
    let dir = tempfile::tempdir().expect("tempdir");
    slot_case(dir.path(), &["--feed", "6000", "--rpm", "20000"]);
}

#[test]
fn pocket_agrees_with_its_plan() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    std::fs::write(d.join("rect.txt"), "0,0\n60,0\n60,40\n0,40\n").expect("write");
    let p = json(&run(d, &["pocket", "--polygon", "rect.txt", "--machine", "hobby-router", "--export", "p.ngc"]));
    let v = json(&run(
        d,
        &[
            "verify",
            "p.ngc",
            "--stock",
            "rect.txt",
            "--part",
            "rect.txt",
            "--machine",
            "hobby-router",
            "--moves",
            "m.csv",
        ],
    ));
    let rows = csv_rows(&d.join("m.csv"));
    // the moves in the plane at depth; the first is the flat turn after the helix
    let flat: Vec<&(usize, String, f64, f64, f64, f64)> =
        rows.iter().filter(|r| r.1 == "feed" && r.2 == -6.0 && r.3 == -6.0).collect();
    let peak = flat[1..].iter().map(|r| r.5).fold(0.0, f64::max);
    let turn = flat[0].5;
    let (plan_peak, plan_h) = (f(&p, "max_engagement_deg"), f(&p["pace"], "h_max_peak_mm"));
    println!("pocket engagement: verify {peak:.4} plan {plan_peak:.4}; flat turn after the helix {turn:.2}");
    println!("pocket h_max programmed: verify {:.6} plan {plan_h:.6}", f(&v, "h_max_programmed_mm"));
    println!("pocket h_max reached: {:.6}, circular {:.6}", f(&v, "h_max_mm"), f(&v, "h_max_circular_mm"));
    println!("pocket time: verify {:.4} plan {:.4}", f(&v, "time_real_s"), f(&p, "time_real_s"));
    println!("pocket problems: {}", v["problems"].as_array().map_or(0, Vec::len));
    assert!((peak - plan_peak).abs() <= 0.5, "{peak} {plan_peak}");
    // h_max at the feed the machine reaches: the plan's exact chip at the peaks of its moves
    // (`pocket::chip`, on its own tool path and the program's moves timed) against verify's
    // (the program read back): within 1 %.
    println!("pocket h_max plan: reached {:.6} programmed {:.6}", f(&p, "h_max_mm"), f(&p, "h_max_programmed_mm"));
    assert!(rel(f(&v, "h_max_mm"), f(&p, "h_max_mm")) <= 0.01);
    // At the programmed feeds the pace holds f_z·κ (the circular-path chip, an upper bound of
    // the exact chip) at the target, so hundreds of moves cut nearly the same peak chip and
    // each side measures exactly only its 48 largest circular ones: the exact peaks agree
    // within 2 %, and neither is above the pace's bound by more than 1 % (positions between
    // the pace's measured ones).
    let h = f(&v, "h_max_programmed_mm");
    assert!(rel(h, f(&p, "h_max_programmed_mm")) <= 0.02, "{h}");
    assert!(h <= plan_h * 1.01 && f(&p, "h_max_programmed_mm") <= plan_h * 1.01, "{h} {plan_h}");
    assert!(rel(f(&v, "time_real_s"), f(&p, "time_real_s")) <= 0.01);
    assert!(v["problems"].as_array().is_some_and(|p| p.iter().all(|p| p["kind"] != "gouge")), "{}", v["problems"]);
}

#[test]
fn corner_agrees_with_its_plan() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let c = json(&run(d, &["corner", "--machine", "hobby-router", "--export", "c.ngc"]));
    // The corner's frame: apex X0 Y0, bisector +X, walls y = ±x, 100 mm long. Its moves run a
    // tool radius (5) from the walls; the previous ring ran one step-over a_e further in, and
    // everything inside it was cleared before: the stock is the wedge less the region the ring
    // encloses with its tool, the walls offset by a_e inward with the corner rounded by the
    // tool about the ring's corner C = (w·√2, 0), w = 5 + a_e (an arc of radius 5 from the
    // tangent point on one offset wall to that on the other, through C − (5, 0)).
    let ae = f(&c, "step_over_mm");
    let (r, s2) = (5.0, std::f64::consts::SQRT_2);
    let (w, far) = (r + ae, 100.0 / s2);
    let mut stock = vec![(0.0, 0.0), (far, -far), (far, -far + ae * s2)];
    for k in 0..=90 {
        let a = (225.0 - f64::from(k)).to_radians();
        stock.push((w * s2 + r * a.cos(), r * a.sin()));
    }
    stock.extend([(far, far - ae * s2), (far, far)]);
    let text: String = stock.iter().map(|(x, y)| format!("{x},{y}\n")).collect();
    std::fs::write(d.join("stock.txt"), text).expect("write");
    run(d, &["verify", "c.ngc", "--stock", "stock.txt", "--machine", "hobby-router", "--moves", "m.csv"]);
    let rows = csv_rows(&d.join("m.csv"));
    let corner: Vec<_> = rows.iter().collect();
    let peak = corner.iter().filter(|r| r.1 == "feed").map(|r| r.5).fold(0.0, f64::max);
    // the corner program's own rapids to its start are not part of its time (the position
    // before a program is unknown): from its first feed move on
    let first = corner.iter().position(|r| r.1 == "feed").expect("feed");
    let time: f64 = corner[first..].iter().map(|r| r.4).sum();
    println!("corner engagement: verify {peak:.4} plan {:.4}", f(&c, "max_engagement_deg"));
    println!("corner time: verify {time:.4} plan {:.4}", f(&c, "time_real_s"));
    assert!((peak - f(&c, "max_engagement_deg")).abs() <= 0.5);
    assert!(rel(time, f(&c, "time_real_s")) <= 0.01);
}

#[test]
fn freecad_programs_verify() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/freecad");
    println!(
        "| pocket | peak ° | p95 ° | h_max mm | F_R,max N | power W | time s | at feed mm | rapids mm | gouges (deepest mm) | problems |"
    );
    for name in ["rect", "L", "dumbbell", "u-channel", "pentagon-notch", "narrow"] {
        let (ngc, txt) = (data.join(format!("{name}.ngc")), data.join(format!("{name}.txt")));
        let (ngc, txt) = (ngc.to_str().expect("utf-8"), txt.to_str().expect("utf-8"));
        let v = json(&run(&data, &["verify", ngc, "--stock", txt, "--part", txt, "--machine", "vmc"]));
        let problems = v["problems"].as_array().expect("problems");
        let gouges: Vec<f64> =
            problems.iter().filter(|p| p["kind"] == "gouge").map(|p| p["value"].as_f64().expect("value")).collect();
        let kinds: Vec<String> = problems.iter().map(|p| format!("{} line {}", p["kind"], p["line"])).collect();
        println!(
            "| {name} | {:.1} | {:.1} | {:.4} | {:.0} | {:.0} | {:.1} | {:.0} | {:.0} | {} ({:.3}) | {} |",
            f(&v, "max_engagement_deg"),
            f(&v, "p95_engagement_deg"),
            f(&v, "h_max_mm"),
            f(&v, "force_resultant_max_n"),
            f(&v, "power_max_w"),
            f(&v, "time_real_s"),
            f(&v, "length_at_feed_mm"),
            f(&v, "rapid_length_mm"),
            gouges.len(),
            gouges.iter().copied().fold(0.0, f64::max),
            kinds.join("; ")
        );
        assert!(f(&v, "time_real_s") > 0.0 && f(&v, "max_engagement_deg") > 0.0);
    }
}

/// `analyze` warns above the machine's spindle limits: the hobby router at 6000 mm/min and
/// 20 000 rpm (the paper's job otherwise) peaks at about 7.3 kW and 3.5 N·m against its preset's
/// 710 W and 0.68 N·m; the VMC's 10 kW and 60 N·m hold the paper's job, so no warning.
#[test]
fn analyze_warns_above_the_spindle_limits() {
    let dir = tempfile::tempdir().expect("tempdir");
    let a = json(&run(dir.path(), &["analyze", "--machine", "hobby-router", "--feed", "6000", "--rpm", "20000"]));
    let w = a["warnings"].as_array().expect("warnings");
    assert!(f(&a, "power_max_w") > 710.0 && f(&a, "torque_max_nm") > 0.68);
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(w[0].as_str().is_some_and(|s| s.contains("710 W")), "{w:?}");
    let a = json(&run(dir.path(), &["analyze", "--machine", "vmc"]));
    assert!(a.get("warnings").is_none(), "{a}");
}

/// `optimize` checks its best job against the machine's spindle limits as `analyze` does (the
/// limits are not among the optimiser's): on the hobby router the best job within h_max 0.1 mm
/// and 60° is the same job `analyze` then reports, and each warning line agrees with that
/// analysis (power and torque above 710 W and 0.68 N·m); on the VMC (10 kW, 60 N·m) none.
#[test]
fn optimize_warns_above_the_spindle_limits() {
    let dir = tempfile::tempdir().expect("tempdir");
    let args = ["optimize", "--machine", "hobby-router", "--max-hmax", "0.1", "--max-engagement", "60"];
    let text = run(dir.path(), &args);
    let warnings: Vec<&str> = text.lines().filter(|l| l.starts_with("# warning: ")).collect();
    // the best job, analysed on its own
    let job = dir.path().join("best.toml");
    let toml: String = text.lines().filter(|l| !l.starts_with('#')).map(|l| format!("{l}\n")).collect();
    std::fs::write(&job, toml).expect("write job");
    let a = json(&run(dir.path(), &["analyze", "--job", job.to_str().expect("utf-8")]));
    let expected: Vec<String> = a["warnings"]
        .as_array()
        .expect("warnings")
        .iter()
        .map(|w| format!("# warning: {}", w.as_str().expect("text")))
        .collect();
    assert!(f(&a, "power_max_w") > 710.0 && f(&a, "torque_max_nm") > 0.68, "{a}");
    assert_eq!(warnings, expected.iter().map(String::as_str).collect::<Vec<_>>(), "{text}");
    let vmc = run(dir.path(), &["optimize", "--machine", "vmc", "--max-hmax", "0.1", "--max-engagement", "60"]);
    assert!(!vmc.contains("# warning"), "{vmc}");
}

/// `optimize --hold-spindle-limits` holds the machine's spindle power and torque: the best job,
/// analysed on its own, is within the hobby router's 710 W and 0.68 N·m at the programmed feed
/// (which bounds them at any feed the machine reaches), with no warning, and its real MRR is
/// at most that of the search without them; without a machine with limits the flag is refused
/// by name.
#[test]
fn optimize_holds_the_spindle_limits() {
    let dir = tempfile::tempdir().expect("tempdir");
    let base = ["optimize", "--machine", "hobby-router", "--max-hmax", "0.1", "--max-engagement", "60"];
    let free = run(dir.path(), &base);
    let held = run(dir.path(), &[&base[..], &["--hold-spindle-limits"]].concat());
    assert!(!held.contains("# warning"), "{held}");
    let mrr = |text: &str| -> f64 {
        let line = text.lines().find(|l| l.starts_with("# real MRR ")).expect("MRR line");
        line["# real MRR ".len()..].split(' ').next().expect("number").parse().expect("number")
    };
    assert!(mrr(&held) <= mrr(&free), "{held}\n{free}");
    let job = dir.path().join("held.toml");
    let toml: String = held.lines().filter(|l| !l.starts_with('#')).map(|l| format!("{l}\n")).collect();
    std::fs::write(&job, toml).expect("write job");
    let a = json(&run(dir.path(), &["analyze", "--job", job.to_str().expect("utf-8")]));
    println!("held: power {} W torque {} N·m", f(&a, "power_max_programmed_w"), f(&a, "torque_max_programmed_nm"));
    assert!(f(&a, "power_max_programmed_w") <= 710.0 * (1.0 + 1e-9), "{a}");
    assert!(f(&a, "torque_max_programmed_nm") <= 0.68 * (1.0 + 1e-9), "{a}");
    assert!(f(&a, "h_max_programmed_mm") <= 0.1 && f(&a, "engagement_max_deg") <= 60.0, "{a}");
    assert!(a.get("warnings").is_none(), "{a}");
    let out = Command::new(env!("CARGO_BIN_EXE_trochoplan"))
        .args(["optimize", "--max-hmax", "0.1", "--max-engagement", "60", "--hold-spindle-limits"])
        .output()
        .expect("runs");
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--hold-spindle-limits"));
}
